"""``shtaerman.impact``: the exact quasi-static impact of a striker of any profile."""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np
from numpy.typing import ArrayLike

from ..guards import warn_outside_validity
from ..output.files import json_safe
from ..problem import check_bodies, in_python_words
from ..theory import impact as theory
from ..theory.contact import PowerLawContact
from ..theory.indenter import PowerLawIndenter
from ..theory.materials import RIGID, Material, effective_modulus
from ..theory.profile_impact import ProfileImpactResult, solve_profile_impact
from ..theory.sneddon import Indenter, SneddonContact

__all__ = ["ImpactResult", "check_bodies", "impact"]


SOLVED = (
    *("beta", "x_c", "P_c", "a_c", "p_c", "t_c", "t_y", "impulse", "impulse_simpson"),
    *("force_exponent", "mass", "velocity"),
)
"""The attributes an :class:`ImpactResult` reads from its closed-form solution (as floats)."""


@dataclass(frozen=True)
class ImpactResult:
    """The quasi-static impact: the keys of ``shtaerman impact --json`` (SI units), read from
    its closed-form solution (:data:`SOLVED`).

    Attributes
    ----------
    beta : float
        Force-law coefficient of P = beta x^q, N m^-q.
    x_c, P_c, a_c, p_c : float
        Maximum approach (m), force (N), contact radius (m), central pressure (Pa; inf for
        n <= 1).
    t_c, t_y : float
        Compression time and impact duration, s.
    impulse, impulse_simpson : float
        2 M v0 and the paper's Simpson estimate of it (its eq. 16), N s.
    force_exponent : float
        q = (n + 1) / n (a sphere's or a tabulated profile's: its smooth tip's 3/2, and
        ``beta`` NaN, null in the JSON: their force law is no power law).
    mass, velocity : float
        Striker mass M in kg and approach velocity v0 in m/s.
    modulus : float
        Combined modulus E* of striker and body, Pa.
    solution : shtaerman.theory.impact.ImpactResult or ProfileImpactResult
        The solution behind these numbers (its contact law included): the Ateb closed form
        of the power law, or the quadrature of any other profile
        (:mod:`shtaerman.theory.profile_impact`).
    ode_check : dict or None
        The numerical ODE's x_c, t_c, t_y, rebound_velocity and max_history_difference (the
        largest |x_ode - x| / x_c), when asked for with ``check=True``.
    """

    solution: theory.ImpactResult | ProfileImpactResult = field(repr=False)
    ode_check: dict[str, float] | None = None

    def __getattr__(self, name: str) -> float:
        if name in SOLVED:
            return float(getattr(self.solution, name))
        raise AttributeError(f"{type(self).__name__!r} object has no attribute {name!r}")

    @property
    def modulus(self) -> float:
        """Combined modulus E* of striker and body, Pa."""
        return float(self.solution.law.modulus)

    def __repr__(self) -> str:
        return f"ImpactResult({', '.join(f'{k}={v!r}' for k, v in self.to_dict().items())})"

    def history(self, points: int = 201, times: ArrayLike | None = None) -> theory.ImpactHistory:
        """The exact t, x, v, P, a, p0 over [0, t_y] (``points`` instants, or ``times`` in s).

        Raises
        ------
        shtaerman.validation.InputError
            If ``points`` < 2 or a time lies outside [0, t_y].
        """
        return self.solution.history(points, times)

    def to_dict(self) -> dict[str, object]:
        """The JSON object of ``shtaerman impact --json`` (SI units): non-finite numbers
        are None (the CLI's null)."""
        document: dict[str, object] = self.solution.maxima()
        document["force_exponent"] = self.force_exponent
        indenter = self.solution.law.indenter
        document["profile"] = {"kind": indenter.kind, "parameters": indenter.parameters}
        document["modulus"] = self.modulus
        if self.ode_check is not None:
            document["ode_check"] = dict(self.ode_check)
        return json_safe(document)


@in_python_words
def impact(
    indenter: Indenter,
    body: Material,
    *,
    mass: float,
    velocity: float,
    striker: Material | None = None,
    check: bool = False,
) -> ImpactResult:
    """The exact quasi-static impact of a striker on an elastic half-space.

    Parameters
    ----------
    indenter : PowerLawIndenter, SphereIndenter or TabulatedIndenter
        The striker's profile: z = A r^n (A in m^(1-n), the Ateb closed form), the exact
        sphere or a tabulated z(r) (Sneddon's contact law, the impact by quadrature).
    body : Material
        The half-space (its density is not used).
    mass, velocity : float
        Striker mass M in kg and approach velocity v0 in m/s (> 0; above 5 m/s a
        :class:`~shtaerman.theory.impact.QuasiStaticValidityWarning`).
    striker : Material, optional
        The striker's material; default rigid.
    check : bool
        Also integrate the ODE numerically and report the agreement (``ode_check``).

    Returns
    -------
    ImpactResult

    Raises
    ------
    shtaerman.validation.InputError
        If an input lies outside its range.

    Warns
    -----
    shtaerman.guards.ValidityWarning
        If x_c lies beyond a validity limit of linear elasticity
        (:func:`shtaerman.guards.outside_validity`, as every route warns).
    """
    striker = RIGID if striker is None else striker
    check_bodies(indenter, body, striker)
    modulus = effective_modulus(striker, body)
    if isinstance(indenter, PowerLawIndenter):
        result = theory.solve_impact(mass, velocity, PowerLawContact(indenter, modulus))
    else:
        result = solve_profile_impact(mass, velocity, SneddonContact(indenter, modulus))
    warn_outside_validity(indenter, result.x_c, None, finite=False)
    return ImpactResult(result, _ode_check(result) if check else None)


def _ode_check(result: theory.ImpactResult | ProfileImpactResult) -> dict[str, float]:
    """The numerical ODE's maxima and its largest history difference from the exact one."""
    from ..theory.impact_ode import integrate_impact  # scipy.integrate: only for check=True

    numerical = integrate_impact(result.mass, result.velocity, result.law.force, result.x_c)
    exact = result.history(2001)
    x, _ = numerical.sample(exact.t[:-1])
    return {
        "x_c": numerical.x_c,
        "t_c": numerical.t_c,
        "t_y": numerical.t_y,
        "rebound_velocity": numerical.rebound_velocity,
        "max_history_difference": float(np.max(np.abs(x - exact.x[:-1])) / result.x_c),
    }
