"""One dynamic case: the elastodynamic FE impact against the quasi-static (Ateb) impact (a
sphere's or a tabulated profile's: Sneddon's law, :mod:`shtaerman.theory.profile_impact`).

:func:`run_case` (also what ``shtaerman dynamic`` runs) computes the exact quasi-static impact,
the first-order radiation estimate (:mod:`shtaerman.theory.radiation`) and the dynamic FE impact
(:mod:`shtaerman.fem.dynamic_contact`) for the same striker and half-space; :func:`compare` states
how far the quasi-static x_c, P_c and t_c are from the dynamic x_max, P_max and t_contact / 2
(quasi-static / dynamic - 1).
"""

from __future__ import annotations

import dataclasses
import math
import warnings
from collections.abc import Callable, Sequence
from dataclasses import dataclass, replace
from functools import partial
from typing import TYPE_CHECKING

from ...fem.dynamic_contact import DynamicSettings
from ...fem.impact import run_impact
from ...fem.impact_run import ImpactRun
from ...guards import warn_outside_validity
from ...theory.contact import PowerLawContact
from ...theory.impact import ImpactResult
from ...theory.materials import RIGID, Material, effective_modulus
from ...theory.profile_impact import ProfileImpactResult, solve_profile_impact
from ...theory.radiation import RadiationEstimate, profile_radiation_estimate, radiation_estimate
from ...theory.sneddon import Indenter, SneddonContact, contact_law
from ...theory.viscoelastic import PronySeries, elastic_impact
from ..richardson import Estimate
from .accuracy import ImpactLadder, check_finite_ladder, run_ladder

if TYPE_CHECKING:
    from ...problem import Problem

__all__ = [
    "COMPARED",
    "DynamicCase",
    "compare",
    "exact_impact",
    "finite_case",
    "radiation",
    "run_case",
]

QUASI_STATIC_KEYS = ("beta", "x_c", "P_c", "a_c", "p_c", "t_c", "t_y")
COMPARED = {
    "x": ("x_c", "x_max", "maximum approach"),
    "P": ("P_c", "P_max", "maximum force"),
    "t": ("t_c", "t_half", "compression time (against t_contact / 2)"),
}
"""Compared quantity -> (quasi-static key, dynamic key, words)."""


def compare(quasi: ImpactResult | ProfileImpactResult, result: ImpactRun) -> dict[str, float]:
    """Quasi-static / dynamic - 1 for x, P and t (keys of :data:`COMPARED`; t_c against
    t_contact / 2, the same as t_y against t_contact), dimensionless."""
    dynamic = {"x_max": result.x_max, "P_max": result.P_max, "t_half": 0.5 * result.t_contact}
    return {key: getattr(quasi, qs) / dynamic[dyn] - 1.0 for key, (qs, dyn, _) in COMPARED.items()}


@dataclass(frozen=True)
class DynamicCase:
    """One approach velocity: the quasi-static impact, the estimate and the dynamic FE impact
    (with its error-estimate ladder, or ``None`` when it was skipped)."""

    velocity: float
    quasi: ImpactResult | ProfileImpactResult
    estimate: RadiationEstimate
    result: ImpactRun
    ladder: ImpactLadder | None = None

    def differences(self) -> dict[str, float]:
        """:func:`compare` and the measured loss against the first-order estimate."""
        out = compare(self.quasi, self.result)
        estimated = self.estimate.energy_fraction
        out["loss_vs_estimate"] = (
            self.result.energy_radiated_fraction / estimated - 1.0 if estimated > 0 else math.nan
        )
        return out

    @property
    def estimated(self) -> bool:
        """Whether the case carries error estimates: it ran its ladder, and no level of it
        failed twice."""
        return self.ladder is not None and not self.ladder.missing

    def estimates(self) -> dict[str, Estimate]:
        """Richardson estimates from the ladder ({} without one): x_max, P_max, t_contact,
        restitution, energy_radiated_fraction (a viscoelastic body: also the split of
        :data:`.accuracy.LOSS_ESTIMATED`), and ``difference_x``, ``difference_P``,
        ``difference_t`` (:func:`compare` on every level; use ``absolute_error``)."""
        if not self.estimated:
            return {}
        quasi = self.quasi
        differences = {
            f"difference_{key}": self.ladder.estimate(lambda r, key=key: compare(quasi, r)[key])
            for key in COMPARED
        }
        return {**self.ladder.estimates, **differences}

    def document(self) -> dict[str, object]:
        """The JSON of ``shtaerman dynamic --json`` (DESIGN.md interface contract), with the
        ladder's ``error_estimate``, ``extrapolated``, ``estimate_details``, ``mesh_ladder``."""
        maxima = self.quasi.maxima()
        return {
            "quasi_static": {key: maxima[key] for key in QUASI_STATIC_KEYS},
            "dynamic": self.result.summary(),
            "radiation_estimate": self.estimate.to_dict(),
            "mesh": self.result.mesh,
            "timings": self.result.timings,
            "parameters": self.result.parameters,
            **(self.ladder.to_dict(self.estimates()) if self.ladder is not None else {}),
        }


def radiation(
    mass: float,
    velocity: float,
    law: PowerLawContact | SneddonContact,
    density: float,
    half_space: Material,
) -> RadiationEstimate:
    """The first-order radiation estimate of the quasi-static impact on ``law`` (the power
    law's closed form; a sphere's or a table's Int (dP/dt)^2 dt by quadrature over its exact
    impact); a massless half-space (density 0) radiates nothing."""
    shear, nu = half_space.shear_modulus, half_space.poisson_ratio
    rho = density if density > 0 else 1.0
    if isinstance(law, SneddonContact):
        exact = solve_profile_impact(mass, velocity, law)
        estimate = profile_radiation_estimate(exact, rho, shear, nu)
    else:
        estimate = radiation_estimate(mass, velocity, law.beta, law.force_exponent, rho, shear, nu)
    if density > 0:
        return estimate
    return dataclasses.replace(
        estimate, shear_wave_speed=math.inf, radiated_energy=0.0, energy_fraction=0.0,
        restitution=1.0,
    )  # fmt: skip


def exact_impact(
    mass: float, velocity: float, law: PowerLawContact | SneddonContact
) -> ImpactResult | ProfileImpactResult:
    """The quasi-static impact of ``mass`` kg at ``velocity`` m/s on the contact ``law``
    (:func:`shtaerman.theory.sneddon.contact_law`): the power law's closed form (Ateb),
    another profile's quadrature (Sneddon), as
    :func:`shtaerman.theory.viscoelastic.elastic_impact`."""
    return elastic_impact(mass, velocity, law)


def run_case(
    indenter: Indenter,
    half_space: Material,
    density: float,
    mass: float,
    velocity: float,
    settings: DynamicSettings | None = None,
    *,
    snapshots: Callable[[ImpactResult], Sequence[float]] | None = None,
    ladder: bool = False,
    refine: float = 1.0,
    prony: PronySeries | None = None,
    friction: float | None = None,
) -> DynamicCase:
    """Quasi-static impact, first-order radiation estimate and dynamic FE impact (SI units).

    Parameters
    ----------
    indenter : PowerLawIndenter, SphereIndenter or TabulatedIndenter
        The rigid striker's profile: z = A r^n (the quasi-static impact Ateb's closed form),
        the exact sphere or a tabulated z(r) (Sneddon's law, the impact by quadrature).
    half_space : Material
        E2 in Pa, nu2 in [0, 0.5].
    density : float
        Half-space density in kg/m^3.
    mass, velocity : float
        Striker mass in kg and approach velocity in m/s.
    settings : DynamicSettings, optional
        Numerical controls of the dynamic impact.
    snapshots : callable, optional
        Given the quasi-static impact, the times in s at which to keep the fields.
    ladder : bool
        Also run the two coarser levels of the error-estimate ladder
        (``settings.refined(1/2)`` must be valid).
    refine : float
        The refinement ``settings`` stand for, as the ladder reports it.
    prony : PronySeries, optional
        Shear relaxation of the half-space (E2, nu2 its instantaneous values); None: elastic.
    friction : float, optional
        The striker's surface (:func:`~shtaerman.fem.impact.run_impact`):
        None frictionless, ``math.inf`` bonded (no slip), mu >= 0 Coulomb. The quasi-static
        impact and the radiation estimate stay the frictionless theory's.
    """
    with warnings.catch_warnings(record=True) as said:  # said once the FE run took the inputs:
        warnings.simplefilter("always")  # a refusal is the one line
        law = contact_law(indenter, effective_modulus(RIGID, half_space))
        quasi = exact_impact(mass, velocity, law)
        estimate = radiation(mass, velocity, law, density, half_space)
    times = tuple(snapshots(quasi)) if snapshots is not None else ()
    settings = DynamicSettings() if settings is None else settings
    run = partial(run_impact, indenter, half_space, density, mass, velocity)
    result = run(settings, snapshot_times=times, prony=prony, friction=friction)
    for warning in said:
        warnings.warn_explicit(warning.message, warning.category, warning.filename, warning.lineno)
    warn_outside_validity(indenter, result.x_max, settings.thickness, finite=False)
    levels = None
    if ladder:
        physics = partial(run, prony=prony, friction=friction)
        levels = run_ladder(physics, settings, refine=refine, finest=result)
    return DynamicCase(velocity, quasi, estimate, result, levels)


def finite_case(
    problem: Problem,
    *,
    time_steps: int | None = None,
    mesh_size: float | None = None,
    refine: float = 1.0,
    estimate: bool = True,
) -> DynamicCase:
    """The impact of ``problem`` on a rubber body at finite strain (``problem.body.finite``)
    beside the quasi-static impact: the finest level of its ladder
    (:func:`.accuracy.run_ladder`; with ``estimate``, the two coarser levels too), as
    ``shtaerman dynamic --model`` runs it.

    Parameters
    ----------
    problem : Problem
        An impact on a rubber body; its density 0: the massless body.
    time_steps : int, optional
        Steps per quasi-static impact duration (default 50; 100 with inertia).
    mesh_size : float, optional
        Smallest element / refined radius (default the finite-strain contact's).
    refine : float
        Refinement of the finest level.
    estimate : bool
        Also run the ladder's coarser levels for the error estimates.

    Returns
    -------
    DynamicCase
        Its ``result`` the finest level that passed, its ``ladder`` the whole ladder (without
        ``estimate``: one level); ``estimate`` is the half-space's first-order radiation
        estimate, which does not apply to a rubber (reported as such).
    """
    from ...fem.finite_contact import FINITE_MESH
    from ...fem.finite_dynamic import INERTIA_MESH, FiniteImpactSettings
    from ...vocabulary import entry

    striker, body = problem.striker, problem.body.material
    rho = body.density
    assert rho is not None and striker.mass is not None and striker.velocity is not None
    if mesh_size is not None:
        mesh_size = entry("mesh_size").check(mesh_size, "dynamic")
    if time_steps is not None:  # the command line's range: one guard on every route
        time_steps = entry("time_steps").check(time_steps, "dynamic")
    mesh = FINITE_MESH if rho == 0 else INERTIA_MESH
    mesh = mesh if mesh_size is None else replace(mesh, size=mesh_size)
    if problem.geometry.thickness is not None:
        mesh = replace(mesh, thickness=problem.geometry.thickness, base=problem.geometry.base)
    settings = FiniteImpactSettings(steps=time_steps, mesh=mesh).resolved(rho)
    check_finite_ladder(settings, refine, estimate)
    body_model = (problem.body.rubber(), problem.body.prony, problem.interface.coefficient)
    inputs = (striker.indenter, body, rho, striker.mass, striker.velocity)

    def run(level: FiniteImpactSettings) -> ImpactRun:
        return run_impact(*inputs, level, *body_model)

    ladder = run_ladder(run, settings.refined(refine), refine=refine, estimate=estimate)
    modulus = body.youngs_modulus / (1.0 - body.poisson_ratio**2)  # the run's, to the bit
    law = contact_law(striker.indenter, modulus)
    quasi = exact_impact(striker.mass, striker.velocity, law)
    estimate_ = radiation(striker.mass, striker.velocity, law, rho, body)
    return DynamicCase(
        striker.velocity, quasi, estimate_, ladder.finest, ladder if estimate else None
    )
