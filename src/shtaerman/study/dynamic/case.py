"""One dynamic case: the elastodynamic FE impact against the quasi-static (Ateb) impact (a
sphere's or a tabulated profile's: Sneddon's law, :mod:`shtaerman.theory.profile_impact`).

:func:`run_case` (also what ``shtaerman dynamic`` runs) computes the exact quasi-static impact,
the first-order radiation estimate (:mod:`shtaerman.theory.radiation`) and the dynamic FE impact
(:mod:`shtaerman.fem.dynamic_contact`) for the same striker and half-space; :func:`compare` states
how far the quasi-static x_c, P_c and t_c are from the dynamic x_max, P_max and t_contact / 2
(quasi-static / dynamic - 1).
"""

from __future__ import annotations

import math
import warnings
from collections.abc import Callable, Sequence
from dataclasses import dataclass, replace
from functools import partial
from typing import TYPE_CHECKING, Any

from ...fem.dynamic_contact import DynamicSettings
from ...fem.finite_dynamic import FiniteImpactSettings
from ...fem.impact import check_impact_reach, run_impact
from ...fem.impact_run import ImpactRun
from ...fem.mesh import HALF_SPACE, Geometry
from ...guards import check_within_layer, warn_outside_validity
from ...theory.impact import ImpactResult, impact_in_floats
from ...theory.materials import RIGID, Material, effective_modulus
from ...theory.profile_impact import ProfileImpactResult
from ...theory.radiation import RadiationEstimate, impact_radiation
from ...theory.sneddon import Indenter, contact_law
from ...theory.viscoelastic import (
    PronySeries,
    elastic_impact,
    rigid_impact,
    viscoelastic_impact,
)
from ...validation import NumericalFailureError
from ..richardson import Estimate
from .accuracy import ImpactLadder, check_ladder, run_ladder

if TYPE_CHECKING:
    from ...fem.rubber import RubberModel
    from ...problem import Problem

__all__ = [
    "COMPARED",
    "DynamicCase",
    "compare",
    "finite_settings",
    "problem_case",
    "run_case",
    "viscoelastic_compare",
    "viscoelastic_reference",
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


REFERENCE_STEPS = 2000
"""Time steps per glassy t_c of the viscoelastic quasi-static reference (its error, second
order in the step, is estimated against half as many: about 1e-7 relative)."""
VISCOELASTIC_COMPARED = ("x_max", "P_max", "t_contact", "restitution")
"""The viscoelastic reference's quantities compared with the dynamic FE impact's."""


def viscoelastic_reference(problem: Problem, t_c: float | None = None) -> dict[str, Any] | None:
    """The quasi-static impact of ``problem``'s striker on its viscoelastic half-space
    (Lee-Radok while loading, Ting while unloading:
    :func:`shtaerman.theory.viscoelastic.viscoelastic_impact`), what its massless FE impact
    converges to; None without a Prony series.

    Its keys (SI): x_max, P_max, t_x_max, t_contact, v_out, restitution, energy_lost_fraction
    (1 - e^2); ``steps`` per glassy t_c and ``step_error``, the largest relative change of the
    compared values from ``steps / 2`` over 3 (Richardson, second order); ``exact`` whether it
    is the exact solution of the body's equations (an incompressible body at small strain;
    nu2 < 0.5 with an elastic bulk, or a rubber at finite strain, have it as the small-strain
    incompressible reference); ``small_strain`` True for a rubber at finite strain. The
    interface (bonded, Coulomb) and a layer's base are not in it: it is the frictionless
    half-space's, as ``quasi_static``. ``t_c`` (s) is the case's elastic impact's, when solved
    (the glassy one: the two runs share it, not solve it)."""
    prony = problem.body.prony
    if prony is None:
        return None
    striker, material = problem.striker, problem.body.material
    assert striker.mass is not None
    law = contact_law(striker.indenter, effective_modulus(RIGID, material))
    if t_c is None:
        t_c = elastic_impact(striker.mass, striker.velocity, law).t_c
    run = partial(viscoelastic_impact, striker.mass, striker.velocity, law, prony, t_c=t_c)
    fine, coarse = run(steps=REFERENCE_STEPS), run(steps=REFERENCE_STEPS // 2)
    change = max(abs(getattr(coarse, k) / getattr(fine, k) - 1) for k in VISCOELASTIC_COMPARED)
    keys = ("x_max", "P_max", "t_x_max", "t_contact", "v_out", "restitution")
    reference: dict[str, Any] = {key: getattr(fine, key) for key in keys}
    reference["energy_lost_fraction"] = 1.0 - fine.restitution**2
    incompressible = material.poisson_ratio == 0.5
    reference.update(steps=REFERENCE_STEPS, step_error=change / 3.0)
    reference.update(exact=incompressible and not problem.body.finite)
    reference.update(small_strain=problem.body.finite)
    return reference


def viscoelastic_compare(reference: dict[str, Any], result: ImpactRun) -> dict[str, float]:
    """The viscoelastic quasi-static reference (:func:`viscoelastic_reference`) / the dynamic
    FE impact - 1 for :data:`VISCOELASTIC_COMPARED` (its keys), dimensionless."""
    return {key: reference[key] / getattr(result, key) - 1.0 for key in VISCOELASTIC_COMPARED}


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
        failed on its retries too."""
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


def run_case(
    indenter: Indenter,
    half_space: Material,
    density: float,
    mass: float,
    velocity: float,
    settings: DynamicSettings | FiniteImpactSettings | None = None,
    *,
    snapshots: Callable[[ImpactResult], Sequence[float]] | None = None,
    ladder: bool = False,
    refine: float = 1.0,
    prony: PronySeries | None = None,
    friction: float | None = None,
    rubber: RubberModel | None = None,
    quasi: ImpactResult | ProfileImpactResult | None = None,
    geometry: Geometry = HALF_SPACE,
    energy_series: bool = True,
) -> DynamicCase:
    """Quasi-static impact, first-order radiation estimate and dynamic FE impact (SI units),
    every body (the arguments of :func:`~shtaerman.fem.impact.run_impact`).

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
    settings : DynamicSettings or FiniteImpactSettings, optional
        Numerical controls of the finest level (resolved); by their kind the body, linear or
        a rubber at finite strain (default ``DynamicSettings()``).
    snapshots : callable, optional
        Given the quasi-static impact, the times in s at which the finest level keeps the
        fields.
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
    rubber : RubberModel, optional
        The rubber of a finite-strain body (with FiniteImpactSettings).
    quasi : ImpactResult or ProfileImpactResult, optional
        The quasi-static impact when already solved (a study's loader solved it).
    geometry : Geometry
        The body's shape (default the half-space); the quasi-static impact and the radiation
        estimate stay the half-space's.
    energy_series : bool
        The energies inside R_a at every step (:func:`~shtaerman.fem.impact.run_impact`).

    Returns
    -------
    DynamicCase
        Its ``result`` the finest level that passed (:func:`.accuracy.run_ladder`: a level
        that fails numerically is retried with more time steps), its ``ladder`` the whole
        ladder (None without ``ladder``).
    """
    with warnings.catch_warnings(record=True) as said:  # said once the FE run took the inputs:
        warnings.simplefilter("always")  # a refusal is the one line
        impact, finite = (mass, velocity), isinstance(settings, FiniteImpactSettings)
        solved = quasi  # the study's loader solved it, checked as here
        exact = rigid_impact(indenter, half_space, *impact) if solved is None else lambda: solved
        physics = (geometry, prony, exact)
        check_impact_reach(indenter, half_space, density, impact, finite, friction, *physics)
        law = contact_law(indenter, effective_modulus(RIGID, half_space))
        quasi = impact_in_floats(mass, velocity, exact)  # the floating-point range first
        estimate = impact_radiation(mass, velocity, law, density, half_space, quasi)
        sizing = quasi if isinstance(quasi, ProfileImpactResult) else None  # for every run
    times = tuple(snapshots(quasi)) if snapshots is not None else ()
    settings = DynamicSettings() if settings is None else settings
    inputs = (indenter, half_space, density, mass, velocity)

    def run(level: Any, **kept: tuple[float, ...]) -> ImpactRun:
        physics = {"geometry": geometry, "exact": sizing, "energy_series": energy_series}
        return run_impact(*inputs, level, rubber, prony, friction, **physics, **kept)

    def say() -> None:
        for said_once in said:
            message, category = said_once.message, said_once.category
            warnings.warn_explicit(message, category, said_once.filename, said_once.lineno)

    finest = partial(run, snapshot_times=times) if times else run  # the fields it keeps
    try:
        levels = run_ladder(run, settings, refine=refine, estimate=ladder, first=finest)
    except NumericalFailureError:  # it ran: the warnings beside the failure's one line
        say()
        raise
    say()
    if isinstance(settings, DynamicSettings):  # the rubber's run checks itself
        g_inf = 1.0 if prony is None else prony.g_inf
        layer = (levels.finest.x_max, geometry.thickness)
        check_within_layer(indenter, layer, impact, quasi.x_c, g_inf)
        warn_outside_validity(indenter, levels.finest.x_max, None, finite=False)
    return DynamicCase(velocity, quasi, estimate, levels.finest, levels if ladder else None)


def finite_settings(
    problem: Problem,
    time_steps: int | None = None,
    mesh_size: float | None = None,
    refine: float = 1.0,
    estimate: bool = True,
) -> FiniteImpactSettings:
    """The finest level's settings of the impact of ``problem`` on a rubber at finite strain,
    as ``shtaerman dynamic --model`` runs it, every level of its ladder (refine / 2 with
    ``estimate``) checked before any run (InputError naming the option): ``time_steps`` per
    quasi-static impact duration (default 50; 100 with inertia), ``mesh_size`` the smallest
    element / refined radius (default the finite-strain contact's)."""
    from ...fem.finite_dynamic import impact_mesh
    from ...vocabulary import entry

    rho = problem.body.material.density
    assert rho is not None
    if mesh_size is not None:
        mesh_size = entry("mesh_size").check(mesh_size, "dynamic")
    if time_steps is not None:  # the command line's range: one guard on every route
        time_steps = entry("time_steps").check(time_steps, "dynamic")
    mesh = impact_mesh(problem.interface.coefficient)
    if mesh_size is not None:
        mesh = replace(mesh, size=mesh_size)
    settings = FiniteImpactSettings(steps=time_steps, mesh=mesh).resolved(rho)
    check_ladder(settings, refine, estimate)
    return settings.refined(refine)


def problem_case(problem: Problem, settings: Any, **options: Any) -> DynamicCase:
    """:func:`run_case` of ``problem`` (an impact) with ``settings`` (of the finest level)
    and the keywords ``options`` (``snapshots``, ``ladder``, ``refine``)."""
    striker, body = problem.striker, problem.body
    material = body.material
    assert material.density is not None and striker.mass is not None
    inputs = (striker.indenter, material, material.density, striker.mass, striker.velocity)
    physics = dict(prony=body.prony, friction=problem.interface.coefficient)
    physics["geometry"] = problem.geometry
    rubber = body.rubber() if body.finite else None
    return run_case(*inputs, settings, **options, **physics, rubber=rubber)
