"""Independent numerical integration of M x'' = -P(x) for any force law P(x).

The built-in cross-check of the exact Ateb solution (:mod:`shtaerman.theory.impact`), and the
way to run the impact on a tabulated force law with no power-law assumption (the FEM curve).
The equation is scaled by the energy depth L (Int_0^L P dx = M v0^2 / 2) and L / v0, and
integrated with scipy's DOP853 at tight tolerances; events mark maximum compression (x' = 0)
and separation (x = 0).
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike
from scipy.integrate import OdeSolution, quad, solve_ivp
from scipy.optimize import brentq

from ..validation import validate_positive

__all__ = ["NumericalImpact", "energy_depth", "integrate_impact"]

ForceLaw = Callable[[np.ndarray], np.ndarray]
MAX_BRACKET_DOUBLINGS = 200
"""The bracket of :func:`energy_depth` grows from the guess by at most 2^200 (1.6e60)."""


def energy_depth(mass: float, velocity: float, force: ForceLaw, depth_guess: float) -> float:
    """Depth x_c in m where the stored energy Int_0^x P equals M v0^2 / 2, to about 1e-9.

    Only the scale of the integration: the maximum approach itself comes from the ODE's event.
    Computed in units of depth_guess and P(depth_guess), so that energies below the smallest
    float (a striker at 1e-248 m/s) stay representable.

    Parameters
    ----------
    mass, velocity : float
        M in kg, v0 in m/s.
    force : callable
        P(x) in N for depths x in m; increasing, P(0) = 0.
    depth_guess : float
        A depth in m of the right order; the bracket is widened from it.
    """
    reference, scaled = _scaled_law(force, depth_guess)
    kinetic = 0.5 * (mass * velocity / reference) * (velocity / depth_guess)

    def surplus(s: float) -> float:
        return quad(lambda u: float(scaled(u)), 0.0, s, epsabs=0, epsrel=1e-9)[0] - kinetic

    upper = 1.0
    for _ in range(MAX_BRACKET_DOUBLINGS):
        if surplus(upper) >= 0:
            break
        upper *= 2.0
    else:
        raise RuntimeError(
            f"no depth up to {upper * depth_guess:g} m stores the kinetic energy "
            f"{0.5 * mass * velocity**2:g} J (is P(x) increasing from P(0) = 0, and depth_guess "
            f"of the right order?)"
        )
    return depth_guess * brentq(surplus, 0.0, upper, xtol=1e-12 * upper, rtol=1e-10)


def _scaled_law(force: ForceLaw, depth: float) -> tuple[float, ForceLaw]:
    """P(depth) in N and the force law in its units, s -> P(depth s) / P(depth)."""
    reference = float(force(np.asarray(depth)))
    if not 0.0 < reference < np.inf:
        raise RuntimeError(f"no depth stores the impact's energy: P({depth:g} m) = {reference:g} N")
    return reference, lambda s: force(depth * np.asarray(s)) / reference


@dataclass(frozen=True)
class NumericalImpact:
    """Result of the numerical integration (SI units)."""

    x_c: float
    """Maximum approach in m."""
    P_c: float
    """Maximum force in N."""
    t_c: float
    """Time of maximum approach in s."""
    t_y: float
    """Time of separation in s."""
    rebound_velocity: float
    """Approach velocity at separation in m/s (-v0 for an elastic impact)."""
    _solution: OdeSolution
    _length: float
    _velocity: float

    def sample(self, times: ArrayLike) -> tuple[np.ndarray, np.ndarray]:
        """Approach x in m and velocity x' in m/s at times t in s (dense output, 7th order)."""
        tau = np.asarray(times, dtype=float) * self._velocity / self._length
        scaled = self._solution(tau)
        return self._length * scaled[0], self._velocity * scaled[1]


def integrate_impact(
    mass: float,
    velocity: float,
    force: ForceLaw,
    depth_guess: float,
    *,
    rtol: float = 1e-12,
) -> NumericalImpact:
    """Integrate M x'' = -P(x), x(0) = 0, x'(0) = v0 until separation.

    Parameters
    ----------
    mass : float
        M in kg.
    velocity : float
        v0 in m/s.
    force : callable
        P(x) in N for an array of depths x in m (x >= 0).
    depth_guess : float
        A depth in m of the order of the maximum approach, to start the energy bracket.
    rtol : float
        Relative tolerance of DOP853 (the absolute one is rtol * 1e-3 in scaled units).

    Returns
    -------
    NumericalImpact
    """
    mass = validate_positive("mass", mass, "kg")
    velocity = validate_positive("velocity", velocity, "m/s")
    length = energy_depth(mass, velocity, force, depth_guess)
    reference, scaled = _scaled_law(force, length)
    stiffness = (length / velocity) * (reference / (mass * velocity))  # L P(L) / (M v0^2)

    def rhs(_tau: float, y: np.ndarray) -> list[float]:
        return [y[1], -stiffness * float(scaled(max(y[0], 0.0)))]

    def turning(_tau: float, y: np.ndarray) -> float:
        return y[1]

    def separation(_tau: float, y: np.ndarray) -> float:
        return y[0]

    turning.direction = -1
    separation.direction = -1
    separation.terminal = True
    solution = solve_ivp(
        rhs,
        (0.0, 20.0),
        [0.0, 1.0],
        method="DOP853",
        rtol=rtol,
        atol=rtol * 1e-3,
        events=(turning, separation),
        dense_output=True,
    )
    (tau_c, *_), (tau_y, *_) = solution.t_events
    (y_c, *_), (y_y, *_) = solution.y_events
    scale = length / velocity
    return NumericalImpact(
        x_c=length * y_c[0],
        P_c=float(force(np.asarray(length * y_c[0]))),
        t_c=tau_c * scale,
        t_y=tau_y * scale,
        rebound_velocity=velocity * y_y[1],
        _solution=solution.sol,
        _length=length,
        _velocity=velocity,
    )
