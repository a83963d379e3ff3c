"""Impact of a rigid power-law striker on a rubber half-space at finite strain, in time.

The massless body (density 0): the striker (mass M, depth X, X(0) = 0, X'(0) = v0) obeys
M X'' = -P(X), where P(X) is the force of the static finite-strain contact at depth X
(:mod:`.finite_contact`: Newton with frictionless contact against the indenter in the current
configuration, mixed u-p, any rubber model of :mod:`.rubber`), solved at every step.

Time stepping: the energy-conserving midpoint discrete gradient on the striker,

    X_{n+1} - X_n = dt (V_n + V_{n+1}) / 2,
    M (V_{n+1} - V_n) = -dt (Pi(X_{n+1}) - Pi(X_n)) / (X_{n+1} - X_n),

with Pi(X) the stored energy of the static contact at depth X (Pi = 0 without contact). It
conserves M V^2 / 2 + Pi(X) exactly at every step, so the restitution is 1 up to the Newton
tolerances, and it is second order. Each step solves the scalar equation in X_{n+1} by a
secant iteration, every evaluation being a static contact solve warm-started from the last
converged state. After the striker leaves (X_{n+1} <= 0) its speed is final.

Results: the same summary keys as the linear dynamic impact (:mod:`.dynamic_contact`); the
body carries no kinetic energy and radiates nothing, so the energy fractions are those of the
striker and of the stored energy.
"""

from __future__ import annotations

import math
import time
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from ..theory.contact import PowerLawContact
from ..theory.impact import duration_integral
from ..theory.indenter import PowerLawIndenter
from ..theory.materials import Material
from ..validation import InputError, NumericalFailureError, validate_poisson, validate_positive
from .finite_contact import (
    FINITE_MESH,
    MAX_ITERATIONS,
    NEWTON_TOLERANCE,
    NewtonStepper,
    geometric_radius,
)
from .hyperelastic import NeoHookean, NewtonError, assemble_hyperelastic
from .mesh import MeshSettings
from .rubber import RubberModel

__all__ = [
    "FiniteImpactResult",
    "FiniteImpactSettings",
    "run_finite_impact",
]

MIN_STEPS = 20
MAX_STEPS = 100_000
SECANT_TOLERANCE = 1e-10
"""The step's scalar equation is solved to |residual| <= this * M v0 / dt."""
MAX_SECANT = 30
MAX_HALVINGS = 6
IMPACT_MARGIN = 1.3
"""Refined radius / geometric contact radius at the small-strain x_c (the finite-strain contact
is wider by a few per cent)."""


@dataclass(frozen=True)
class FiniteImpactSettings:
    """Numerical controls of the finite-strain impact.

    Attributes
    ----------
    steps : int
        Time steps per quasi-static (small-strain) impact duration t_y, >= 20.
    mesh : MeshSettings
        Mesh of the half-space; its ``margin`` is replaced by ``margin`` below.
    margin : float
        Refined (candidate) radius / geometric contact radius (x_c / A)^(1/n) at the
        small-strain x_c, > 1.
    """

    steps: int = 50
    mesh: MeshSettings = FINITE_MESH
    margin: float = IMPACT_MARGIN

    def __post_init__(self) -> None:
        if not isinstance(self.steps, (int, np.integer)) or not (
            MIN_STEPS <= self.steps <= MAX_STEPS
        ):
            raise InputError(
                f"steps (time steps per impact duration) must be an integer in "
                f"[{MIN_STEPS}, {MAX_STEPS}], got {self.steps!r}",
                "steps",
            )
        if not (isinstance(self.margin, (int, float)) and math.isfinite(self.margin)) or (
            self.margin <= 1.0
        ):
            raise InputError(f"margin must be > 1, got {self.margin!r}", "margin")


@dataclass(frozen=True, eq=False)
class FiniteImpactResult:
    """The finite-strain impact: histories, maxima, energies and cost (SI units).

    Attributes
    ----------
    t, x, v, force : numpy.ndarray
        Time (s), striker depth X (m), velocity X' (m/s, downward) and contact force P (N)
        at every step.
    energies : dict of str to numpy.ndarray
        Per step, J: ``striker_kinetic``, ``body_kinetic`` (0: massless body), ``strain``
        (stored), ``absorbed`` (0), ``numerical`` (E0 minus the rest).
    x_max, P_max : float
        Largest depth (m) and force (N), from the parabola through the three samples
        around the largest sample.
    t_x_max, t_contact : float
        Time of x_max and separation time (X back to 0, linear between steps), s.
    v_out, restitution : float
        Rebound speed (m/s, upward) and e = v_out / v0.
    energy_radiated_fraction : float
        1 - e^2.
    energy_balance_error : float
        max over t of |numerical| / E0.
    timings : dict of str to float
        Seconds: ``mesh``, ``assembly``, ``stepping``, ``total``.
    mesh, parameters : dict
        Mesh counts and geometry; inputs and derived scales.
    newton_iterations : int
        Newton iterations over the run.
    """

    t: np.ndarray = field(repr=False)
    x: np.ndarray = field(repr=False)
    v: np.ndarray = field(repr=False)
    force: np.ndarray = field(repr=False)
    energies: dict[str, np.ndarray] = field(repr=False)
    x_max: float
    P_max: float
    t_x_max: float
    t_contact: float
    v_out: float
    restitution: float
    energy_radiated_fraction: float
    energy_balance_error: float
    timings: dict[str, float]
    mesh: dict[str, float]
    parameters: dict[str, float]
    newton_iterations: int

    reflected_energy_fraction: float = math.nan

    def summary(self) -> dict[str, float]:
        """The scalar results, keys of the linear dynamic impact's summary."""
        keys = (
            "x_max",
            "P_max",
            "t_x_max",
            "t_contact",
            "v_out",
            "restitution",
            "energy_radiated_fraction",
            "energy_balance_error",
            "reflected_energy_fraction",
        )
        return {key: float(getattr(self, key)) for key in keys}

    def history_columns(self) -> dict[str, np.ndarray]:
        """t (s), x (m), v (m/s), P (N), one row per step."""
        return {"t": self.t, "x": self.x, "v": self.v, "P": self.force}

    def to_dict(self) -> dict[str, object]:
        """JSON-ready: scalars, histories, energies, mesh, timings, parameters (SI)."""

        def clean(value: float) -> float | None:
            return float(value) if math.isfinite(value) else None

        return {
            **{key: clean(value) for key, value in self.summary().items()},
            "history": {key: column.tolist() for key, column in self.history_columns().items()},
            "energies": {key: column.tolist() for key, column in self.energies.items()},
            "mesh": dict(self.mesh),
            "timings": dict(self.timings),
            "parameters": {key: clean(value) for key, value in self.parameters.items()},
        }


@dataclass
class _State:
    """A converged static contact at depth X (m): solution, multipliers, force, energy."""

    depth: float
    x: np.ndarray
    lam: np.ndarray
    force: float
    energy: float


class _QuasiStaticBody:
    """The massless body: the static contact state at any depth, warm-started."""

    def __init__(self, stepper: NewtonStepper) -> None:
        self.stepper = stepper
        n = stepper.system.n_dofs
        self.zero = _State(0.0, np.zeros(n), np.zeros(stepper.nodes.radius.size), 0.0, 0.0)
        self.history = [self.zero]
        self.iterations = 0

    def at(self, depth: float) -> _State:
        """The static state at ``depth`` (m); 0 without contact (depth <= 0)."""
        if depth <= 0.0:  # no contact: the free striker at this depth
            return _State(depth, self.zero.x, self.zero.lam, 0.0, 0.0)
        return self._solve(depth, MAX_HALVINGS)

    def accept(self, state: _State) -> None:
        """Keep ``state`` as the newest converged one (the predictor's base)."""
        self.history = [*self.history[-1:], state]

    def _guess(self, depth: float) -> tuple[np.ndarray, np.ndarray]:
        s1 = self.history[-1]
        if len(self.history) < 2 or self.history[-2].depth == s1.depth:
            return s1.x, s1.lam
        s0 = self.history[-2]
        w = (depth - s1.depth) / (s1.depth - s0.depth)
        return s1.x + w * (s1.x - s0.x), np.maximum(s1.lam + w * (s1.lam - s0.lam), 0.0)

    def _solve(self, depth: float, halvings: int) -> _State:
        guess_x, guess_lam = self._guess(depth)
        try:
            x, lam, iterations, _ = self.stepper.solve(depth, guess_x, guess_lam)
        except NewtonError:
            if halvings == 0:
                raise
            middle = 0.5 * (depth + self.history[-1].depth)
            if middle <= 0.0:
                raise
            self.accept(self._solve(middle, halvings - 1))
            return self._solve(depth, halvings - 1)
        self.iterations += iterations
        energy = self.stepper.system.energy(x)
        return _State(depth, x, lam, float(lam.sum()), energy)


def _discrete_gradient(a: _State, b: _State) -> float:
    """(Pi_b - Pi_a) / (X_b - X_a) in N; the mean force when the depths nearly coincide."""
    step = b.depth - a.depth
    if abs(step) <= 1e-7 * max(abs(a.depth), abs(b.depth), 1e-300):
        return 0.5 * (a.force + b.force)
    return (b.energy - a.energy) / step


def _step(body: _QuasiStaticBody, state: _State, v: float, mass: float, dt: float, k: float):
    """One discrete-gradient step: the new state and velocity; ``k`` (N/m) the contact
    stiffness guess of the secant's first slope."""

    def residual(trial: _State) -> float:
        return 2.0 * mass * ((trial.depth - state.depth) / dt - v) / dt + _discrete_gradient(
            state, trial
        )

    scale = mass * max(abs(v), 1e-300) / dt
    # the linearized step: 2 M / dt^2 (D - dt v) + P_n + k D / 2 = 0 for D = X_{n+1} - X_n
    d0 = state.depth + (2.0 * mass * v / dt - state.force) / (2.0 * mass / dt**2 + 0.5 * k)
    s0 = body.at(d0)
    r0 = residual(s0)
    slope = 2.0 * mass / dt**2 + 0.5 * k
    for _ in range(MAX_SECANT):
        if abs(r0) <= SECANT_TOLERANCE * scale:
            return s0, 2.0 * (s0.depth - state.depth) / dt - v
        d1 = d0 - r0 / slope
        s1 = body.at(d1)
        r1 = residual(s1)
        if d1 != d0:  # the step's own slope is at least 2 M / dt^2: keep half of it
            slope = max((r1 - r0) / (d1 - d0), mass / dt**2)
        d0, s0, r0 = d1, s1, r1
    raise NumericalFailureError(
        f"the striker's step equation did not converge at depth {state.depth:g} m; "
        f"raise the time steps"
    )


def _march(body: _QuasiStaticBody, mass: float, velocity: float, dt: float, duration: float):
    """Step from first touch until the striker leaves (or ``duration`` s): arrays t, X, V, P, Pi."""
    state, v = body.zero, velocity
    t, xs, vs, forces, energies = [0.0], [0.0], [v], [0.0], [0.0]
    k = 0.0
    while t[-1] < duration:
        new, v_new = _step(body, state, v, mass, dt, k)
        if new.depth > 0 and state.depth > 0 and new.depth != state.depth:
            k = max((new.force - state.force) / (new.depth - state.depth), 0.0)
        if new.depth > 0:
            body.accept(new)
        state, v = new, v_new
        t.append(t[-1] + dt)
        xs.append(state.depth)
        vs.append(v)
        forces.append(state.force)
        energies.append(state.energy)
        if state.depth <= 0.0:
            break
    return tuple(np.array(column) for column in (t, xs, vs, forces, energies))


def _parabola_peak(t: np.ndarray, y: np.ndarray) -> tuple[float, float]:
    """Peak value and time of the parabola through the largest sample and its neighbours."""
    k = int(np.argmax(y))
    if k == 0 or k == y.size - 1:
        return float(y[k]), float(t[k])
    y0, y1, y2 = y[k - 1], y[k], y[k + 1]
    curvature = y0 - 2.0 * y1 + y2
    if curvature >= 0:
        return float(y1), float(t[k])
    shift = 0.5 * (y0 - y2) / curvature
    return float(y1 - 0.25 * (y0 - y2) * shift), float(t[k] + shift * (t[k + 1] - t[k]))


def _turning_point(
    x: np.ndarray, v: np.ndarray, force: np.ndarray, mass: float
) -> tuple[float, float]:
    """x_max (m) and P_max (N) from the step's energy identity M V^2 / 2 + Pi(X) = E0.

    From the sample k of largest X: x_max = X_k + M V_k^2 / (2 P_k) to first order in the
    (small) kinetic energy left there, corrected by the quadratic through the samples
    (X, P) around k; P_max is that quadratic at x_max.
    """
    k = int(np.argmax(x))
    if k == 0 or k == x.size - 1 or force[k] <= 0:
        return float(x[k]), float(force[k])
    around = slice(k - 1, k + 2)
    curve = np.polyfit(x[around] - x[k], force[around], 2)
    energy = 0.5 * mass * v[k] ** 2  # Pi(x_max) - Pi(X_k) = int_Xk^x_max P dX
    step = energy / force[k]
    for _ in range(20):  # Newton on int_0^s P(X_k + y) dy = energy
        c2, c1, c0 = curve
        work = c2 * step**3 / 3 + c1 * step**2 / 2 + c0 * step
        step -= (work - energy) / np.polyval(curve, step)
    return float(x[k] + step), float(np.polyval(curve, step))


def check_density(density: object) -> float:
    """Return the half-space density (kg/m^3) the finite-strain impact supports: 0 only.

    Raises
    ------
    shtaerman.validation.InputError
        For any other value (the finite-strain body with inertia is not implemented).
    """
    if isinstance(density, bool) or not isinstance(density, (int, float)) or density != 0:
        raise InputError(
            f"density2 must be 0 (massless body: the finite-strain quasi-static impact) with a "
            f"rubber model; the finite-strain body with inertia is not implemented, got "
            f"{density!r}",
            "density2",
        )
    return 0.0


def run_finite_impact(
    indenter: PowerLawIndenter,
    half_space: Material,
    density: float,
    mass: float,
    velocity: float,
    settings: FiniteImpactSettings | None = None,
    rubber: RubberModel | None = None,
) -> FiniteImpactResult:
    """Strike a rubber half-space (finite strain, massless) with a rigid power-law striker.

    Parameters: ``indenter`` z = A r^n with n > 1; ``half_space`` the small-strain E2 (Pa)
    and nu2 in [0, 0.5]; ``density`` in kg/m^3, 0 only (massless body); striker ``mass`` (kg)
    and impact ``velocity`` (m/s), > 0; ``settings`` (default :class:`FiniteImpactSettings`);
    ``rubber`` (default neo-Hookean).

    Raises
    ------
    shtaerman.validation.InputError
        Inputs out of range; the contact outgrowing the refined zone.
    NewtonError
        A static contact solve failed after halving its depth increment.
    """
    mass, velocity, law = _checked(indenter, half_space, density, mass, velocity)
    settings = FiniteImpactSettings() if settings is None else settings
    q = law.force_exponent
    x_c = ((q + 1.0) * mass * velocity**2 / (2.0 * law.beta)) ** (1.0 / (q + 1.0))
    t_y = 2.0 * duration_integral(q) * x_c / velocity
    refined = settings.margin * geometric_radius(indenter, x_c)
    clock = [time.perf_counter()]
    mesh = settings.mesh.build(refined)
    clock.append(time.perf_counter())
    stepper = _assembled(mesh, indenter, half_space, rubber, refined)
    system = stepper.system
    clock.append(time.perf_counter())
    body = _QuasiStaticBody(stepper)
    columns = _march(body, mass, velocity, t_y / settings.steps, 3.0 * t_y)
    clock.append(time.perf_counter())
    timings = {
        name: clock[k + 1] - clock[k] for k, name in enumerate(("mesh", "assembly", "stepping"))
    }
    timings["total"] = clock[-1] - clock[0]
    context = {
        "timings": timings,
        "mesh": {
            "nodes": int(mesh.p.shape[1]),
            "elements": int(mesh.t.shape[1]),
            "dofs": int(system.n_dofs),
            "contact_candidates": int(stepper.nodes.radius.size),
            "refined_radius": refined,
        },
        "parameters": _parameters(indenter, half_space, mass, velocity, t_y / settings.steps),
        "newton_iterations": body.iterations,
    }
    context["parameters"].update(quasi_static_x_c=x_c, quasi_static_t_y=t_y, beta=law.beta)
    return _result(columns, mass, context)


def _checked(
    indenter: PowerLawIndenter, half_space: Material, density: object, mass: float, velocity: float
) -> tuple[float, float, PowerLawContact]:
    """Mass (kg), velocity (m/s) and Shtaerman's law, every input checked."""
    check_density(density)
    mass = validate_positive("mass", mass, "kg")
    velocity = validate_positive("velocity", velocity, "m/s")
    validate_poisson("nu2", half_space.poisson_ratio, low=0.0)
    if indenter.exponent <= 1.0:
        raise InputError(f"exponent must be > 1 with a rubber model, got {indenter.exponent!r}")
    modulus = half_space.youngs_modulus / (1.0 - half_space.poisson_ratio**2)
    return mass, velocity, PowerLawContact(indenter, modulus)


def _assembled(
    mesh: Any,
    indenter: PowerLawIndenter,
    half_space: Material,
    rubber: RubberModel | None,
    refined: float,
) -> NewtonStepper:
    """The rubber on ``mesh`` assembled, and its contact Newton (candidates up to ``refined``)."""
    constants = (half_space.youngs_modulus, half_space.poisson_ratio)
    material = NeoHookean(*constants) if rubber is None else rubber.material(*constants)
    system = assemble_hyperelastic(mesh, material)
    return NewtonStepper(system, indenter, refined, NEWTON_TOLERANCE, MAX_ITERATIONS)


def _parameters(
    indenter: PowerLawIndenter, half_space: Material, mass: float, velocity: float, dt: float
) -> dict[str, float]:
    """Inputs and the time step, SI units."""
    return {
        "mass": mass,
        "velocity": velocity,
        "density2": 0.0,
        "shape_coefficient": indenter.shape_coefficient,
        "exponent": indenter.exponent,
        "E2": half_space.youngs_modulus,
        "nu2": half_space.poisson_ratio,
        "time_step": dt,
    }


def _result(
    columns: tuple[np.ndarray, ...], mass: float, context: dict[str, Any]
) -> FiniteImpactResult:
    """Maxima, separation and energies of a run: ``columns`` t, X, V, P, Pi; ``context`` its
    timings, mesh, parameters and Newton iterations."""
    t, x, v, force, strain = columns
    v0 = v[0]
    energy0 = 0.5 * mass * v0 * v0
    kinetic = 0.5 * mass * v * v
    zeros = np.zeros_like(t)
    numerical = energy0 - kinetic - strain
    _, t_x_max = _parabola_peak(t, x)
    x_max, p_max = _turning_point(x, v, force, mass)
    t_contact = v_out = restitution = radiated = math.nan
    if x[-1] <= 0.0 and x.size > 2:  # X back to 0 between the last two steps
        t_contact = float(t[-2] + (t[-1] - t[-2]) * x[-2] / (x[-2] - x[-1]))
        v_out = -float(v[-1])
        restitution = v_out / v0
        radiated = 1.0 - restitution**2
    energies = {"striker_kinetic": kinetic, "body_kinetic": zeros, "strain": strain}
    energies.update(absorbed=zeros, numerical=numerical)
    return FiniteImpactResult(
        t=t,
        x=x,
        v=v,
        force=force,
        energies=energies,
        x_max=x_max,
        P_max=p_max,
        t_x_max=t_x_max,
        t_contact=t_contact,
        v_out=v_out,
        restitution=restitution,
        energy_radiated_fraction=radiated,
        energy_balance_error=float(np.max(np.abs(numerical)) / energy0),
        **context,
    )
