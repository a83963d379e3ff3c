"""Running a finite-strain study: how far real (neo-Hookean) rubber departs from Shtaerman.

The striker is rigid. On each level of the error-estimate ladder (:func:`ladder_meshes`) the
study runs the finite-strain curve, the linear FEM on the same mesh and depths (P_finite /
P_linear-FEM isolates the finite-strain effect) and three impacts M x'' = -P(x) (Shtaerman's
exact, the tabulated linear-FEM and finite-strain curves); the finest level that passed
answers. Its checks need no reference: the small-strain limit, conservation, Newton's final
correction, complementarity. The steps in full: benchmarks/FEM_NOTES.md, "Study error
estimates".
"""

from __future__ import annotations

import math
import time
import warnings
from dataclasses import asdict, dataclass, replace
from typing import Any

import msgspec
import numpy as np
from numpy.typing import ArrayLike
from scipy.integrate import IntegrationWarning, simpson
from scipy.optimize import brentq

from ...fem.contact.constraints import MIN_CONTACT_NODES
from ...fem.contact.finite import check_finite_depths, indentation_mesh
from ...fem.mesh import HALF_SPACE, Geometry, MeshSettings
from ...fem.rubber import GentLockError
from ...guards import LadderWarnings
from ...theory.impact import ImpactHistory, ImpactResult
from ...theory.indenter import PowerLawIndenter
from ...theory.materials import RIGID, effective_modulus
from ...theory.profile_impact import ProfileImpactResult
from ...theory.sneddon import Indenter, contact_law, profile_inputs
from ...theory.viscoelastic import elastic_impact
from ...validation import caller_stacklevel
from ..checks import Check, Outcome
from ..contact.contact_law import fem_contact_law
from ..contact.indentation import IndentationResult, run_indentation
from ..contact.interface import no_slip_departures, shtaerman_applies
from ..contact.runner import HISTORY_POINTS, impact_maxima, tabulated_impact
from ..dynamic.accuracy import FAILURES, EstimateMissingWarning
from ..ladder import (
    LADDER_RATIO,
    NESTED_RATIO,
    ladder_factors,
    nested_factors,
    nested_ladder,
)
from ..run import Progress
from .accuracy import FiniteEstimates, estimate_study
from .corrections import run_corrections
from .indentation import FiniteIndentationResult, run_finite_study
from .loader import FiniteStudy, FiniteTolerances, Ladder

__all__ = [
    "FiniteStudyOutcome",
    "depth_at_ratio",
    "estimate_ladder",
    "ladder",
    "ladder_meshes",
    "no_slip_checked",
    "run_finite_strain_study",
]

LEVELS = (0.01, 0.05)
"""Departures of P from the linear force whose depths the study reports."""
VARIANTS = ("linear_exact", "linear_fem", "finite_strain")
"""Impact variants: Shtaerman's exact, the same-mesh linear FEM and the finite-strain FEM."""


def depth_at_ratio(indenter: Indenter, ratio: float) -> float:
    """Depth in m whose linear contact has x/a = ``ratio``: for z = A r^n, x = kappa A a^n,
    so a = (ratio / (kappa A))^(1/(n-1)) and x = ratio a; for another profile the root of
    x(a) / a = ratio on Sneddon's law (NaN where x/a never reaches it)."""
    if isinstance(indenter, PowerLawIndenter):
        kappa_a = indenter.kappa * indenter.shape_coefficient
        return ratio * (ratio / kappa_a) ** (1.0 / (indenter.exponent - 1.0))
    law = contact_law(indenter, 1.0)  # x/a is geometry's alone
    top = law.max_contact_radius * (1.0 - 1e-9)
    low = top * 1e-9

    def excess(a: float) -> float:
        return float(law.depth(a)) / a - ratio

    if not excess(low) < 0.0 < excess(top):
        return math.nan
    return ratio * brentq(excess, low, top, xtol=1e-15 * top, rtol=1e-13)


def ladder(
    indenter: Indenter,
    modulus: float,
    x_c: float,
    spec: Ladder,
    smallest: float = 0.0,
) -> np.ndarray:
    """Depths in m: geometric from x/a = ``small_ratio`` (linear a), or from ``smallest`` m
    if deeper (where the mesh resolves the contact), to the first of ``steps`` equal steps
    up to ``reach`` x_c. x/a on the linear solution (:func:`depth_at_ratio`)."""
    top = spec.reach * x_c
    first = top / spec.steps
    exact = contact_law(indenter, modulus)
    tiny = max(depth_at_ratio(indenter, spec.small_ratio), smallest)
    equal = top * np.arange(1, spec.steps + 1) / spec.steps
    if not tiny < first or not math.isfinite(tiny) or exact.force(tiny) <= 0:
        return equal
    return np.concatenate([np.geomspace(tiny, first, spec.small_steps + 1)[:-1], equal])


START_NODES = 6
"""Surface nodes besides the axis (three P2 elements) that the first depth's contact covers on the
coarsest mesh when the ladder's ``small_ratio`` depth covers fewer than
:data:`~shtaerman.fem.contact.constraints.MIN_CONTACT_NODES` (the linear FEM on the same mesh asks
as many loaded nodes); the first force's error is set by the nodes covered (benchmarks/FEM_NOTES.md,
"Finite strain")."""
SMALL_STRAIN_SLOPE = 0.1
"""Bound on |P / P_linear - 1| / (x/a) at small x/a: the finite-strain departure is first order
in x/a (benchmarks/FEM_NOTES.md, "Finite strain"). A ladder started deeper than ``small_ratio``
(n near 1, where x/a grows slowly with the contact radius) adds this slope times the x/a it moved
to the small-strain tolerances."""


@dataclass(frozen=True)
class LadderStart:
    """Where a study's depth ladder starts when the mesh moved it beyond ``small_ratio``."""

    requested_ratio: float
    """The ladder's ``small_ratio`` (x/a)."""
    ratio: float
    """x/a of the first depth (linear a)."""
    depth: float
    """The first depth, m."""
    nodes: int = START_NODES
    """Surface nodes besides the axis its contact covers on the coarsest mesh."""

    def allowance(self) -> float:
        """What the first-order departure adds to the small-strain tolerances there."""
        return SMALL_STRAIN_SLOPE * (self.ratio - self.requested_ratio)

    def words(self) -> str:
        """One sentence for the findings and the progress."""
        return (
            f"The depth ladder starts at x/a = {self.ratio:.3g} (depth {self.depth:.3g} m), not "
            f"at small_ratio = {self.requested_ratio:g}, whose contact covers fewer than "
            f"{MIN_CONTACT_NODES} surface nodes of the coarsest mesh: the first contact covers "
            f"{self.nodes}; the small-strain checks allow the first-order departure there "
            f"({SMALL_STRAIN_SLOPE:g} x/a beyond small_ratio)."
        )

    def to_dict(self) -> dict[str, float]:
        """JSON-ready."""
        return {**asdict(self), "allowance": self.allowance()}


def surface_radii(
    indenter: Indenter, top: float, mesh: MeshSettings, geometry: Geometry = HALF_SPACE
) -> np.ndarray:
    """Radii in m of the surface nodes besides the axis (vertices and mid-sides), increasing,
    of ``mesh`` on ``geometry`` meshed for the deepest depth ``top`` (m) as
    :func:`shtaerman.fem.contact.finite.run_finite_indentation` meshes it."""
    mesh, refined = indentation_mesh(indenter, top, mesh, geometry)
    built = mesh.build(refined, geometry)
    ends = built.p[0, built.facets[:, built.boundaries["surface"]]]
    radii = np.unique(np.concatenate([ends.ravel(), 0.5 * (ends[0] + ends[1])]))
    return radii[radii > 0]


@dataclass(frozen=True)
class FiniteStudyOutcome(Outcome):
    """Everything a finite-strain study produced (SI units)."""

    study: FiniteStudy
    quick: bool
    finite: FiniteIndentationResult
    linear_fem: IndentationResult
    impacts: dict[str, dict[str, float]]
    """Maxima per variant (:data:`VARIANTS`): x_c, P_c, a_c, p_c, t_c, t_y."""
    histories: dict[str, ImpactHistory]
    checks: list[Check]
    seconds: float
    cpu_seconds: float
    estimates: FiniteEstimates | None = None
    """The mesh ladder's estimates of this (its finest) level; None in quick mode."""
    corrections: dict[str, Any] | None = None
    """The ``[corrections]`` impacts (:func:`.corrections.run_corrections`); None without."""
    start: LadderStart | None = None
    """Where the depth ladder started when the mesh moved it (None: at ``small_ratio``)."""
    estimate_missing: str = ""
    """Why ``estimates`` is None after a mesh ladder ("" when it is not): a level failed."""
    mesh_ladder: tuple[dict[str, object], ...] = ()
    """With ``estimate_missing``: per level its ``refine``, ``dofs`` and ``seconds`` (None
    where it failed, its ``failure`` named)."""

    @property
    def mesh(self) -> MeshSettings:
        """The mesh settings the study ran with."""
        return self.study.quick_mesh if self.quick else self.study.mesh

    def rows(self) -> list[dict[str, float]]:
        """Per depth: x/a (linear a), P, the ratios to Shtaerman and to the same-mesh linear
        FEM, a / a_linear, p(0) / p_avg, stored energy, Newton iterations."""
        return [
            {
                "depth": step.depth,
                "depth_to_radius": step.depth / step.contact_radius_linear,
                "force": step.force,
                "force_linear": step.force_linear,
                "force_linear_fem": linear.force,
                "force_ratio": step.force / step.force_linear,
                "force_ratio_fem": step.force / linear.force,
                "contact_radius": step.contact_radius,
                "radius_ratio": step.contact_radius / step.contact_radius_linear,
                "central_pressure": step.central_pressure,
                "central_to_mean": step.central_pressure / step.mean_pressure,
                "central_pressure_ratio": step.central_pressure / step.central_pressure_linear,
                "strain_energy": step.strain_energy,
                "newton_iterations": step.total_iterations,
            }
            for step, linear in zip(self.finite.steps, self.linear_fem.steps, strict=True)
        ]

    def validity(self, departure_shift: ArrayLike = 0.0) -> list[dict[str, float | str]]:
        """Depths up to which P stays within 1 % and 5 % of the linear force.

        The departure is P_finite / P_linear-FEM - 1 on the same mesh (discretization cancels);
        the crossing is interpolated linearly in x/a between the bracketing depths, its depth
        follows from x/a on the linear solution, its stored energy by log-log interpolation;
        the velocity is the impact velocity
        whose finite-strain maximum approach reaches that depth, v = sqrt(2 W / M).

        Parameters
        ----------
        departure_shift : float or array_like
            Added to |P/P_linear-FEM - 1| at every depth (dimensionless; the error estimator
            moves the departures by their estimated errors).
        """
        rows = self.rows()
        ratio = np.array([row["depth_to_radius"] for row in rows])
        departure = np.array([abs(row["force_ratio_fem"] - 1.0) for row in rows])
        departure = departure + np.asarray(departure_shift, dtype=float)
        depth = np.array([row["depth"] for row in rows])
        energy = np.array([row["strain_energy"] for row in rows])
        out: list[dict[str, float | str]] = []
        for level in LEVELS:
            beyond = np.flatnonzero(departure > level)
            k = int(beyond[0]) if beyond.size else -1  # -1: within the level at every depth
            if k <= 0:
                status, at, d, w = "below" if k == 0 else "beyond", ratio[k], depth[k], energy[k]
            else:
                t = (level - departure[k - 1]) / (departure[k] - departure[k - 1])
                at = ratio[k - 1] + t * (ratio[k] - ratio[k - 1])
                d = depth_at_ratio(self.study.indenter, at)
                slope = math.log(energy[k] / energy[k - 1]) / math.log(depth[k] / depth[k - 1])
                status, w = "interpolated", energy[k - 1] * (d / depth[k - 1]) ** slope
            velocity = math.sqrt(2.0 * w / self.study.mass)
            row = {"level": level, "status": status, "depth_to_radius": at, "depth": d}
            out.append({**row, "velocity": velocity})
        return out

    def ratios(self) -> dict[str, float]:
        """Finite-strain impact maxima / the paper's linear exact ones."""
        exact, finite = self.impacts["linear_exact"], self.impacts["finite_strain"]
        return {key: finite[key] / exact[key] for key in ("x_c", "P_c", "a_c", "p_c", "t_c", "t_y")}

    def at_maximum(self) -> dict[str, float]:
        """At the finite-strain x_c: P / (beta x^q), p(0) / p_avg, a / a_linear and p(0) /
        Shtaerman's p(0) at the same depth (log-log interpolated between the computed depths)."""
        rows, x_c = self.rows(), self.impacts["finite_strain"]["x_c"]
        depth = np.log([row["depth"] for row in rows])

        def at(key: str) -> float:
            return float(np.interp(math.log(x_c), depth, [row[key] for row in rows]))

        keys = ("force_ratio", "force_ratio_fem", "central_to_mean", "radius_ratio")
        keys += ("central_pressure_ratio", "depth_to_radius")
        beyond = x_c / rows[-1]["depth"] - 1.0
        return {**{key: at(key) for key in keys}, "beyond_last_depth": beyond}

    def limits(self) -> list[dict[str, object]]:
        """:meth:`validity`, with (after a mesh ladder) each crossing's estimated relative
        ``errors`` of x/a, depth and velocity and its ``departure_error`` (the estimated
        error of |P/P_linear-FEM - 1| at the depths deciding it, a fraction of the force)."""
        entries = self.validity()
        if self.estimates is None:
            return entries
        crossings = self.estimates.crossings
        return [entry | crossing for entry, crossing in zip(entries, crossings, strict=True)]

    def document(self) -> dict[str, object]:
        """The study's numbers for results.json (JSON-ready; :mod:`shtaerman.output.text_finite`
        adds the display ``tables`` and ``findings``), after a mesh ladder its estimates under
        ``accuracy``
        (:meth:`.finite_accuracy.FiniteEstimates.to_dict`), after ``[corrections]`` its
        impacts under ``corrections``."""
        mesh, surface = self.mesh, self.study.interface
        accuracy = {} if self.estimates is None else {"accuracy": self.estimates.to_dict()}
        if self.estimate_missing:  # the contact ladder's keys (AccuracyResult.to_dict)
            missing = dict.fromkeys(("error_estimate", "extrapolated", "estimate_details"))
            ladder = [dict(level) for level in self.mesh_ladder]
            missing |= {"estimate_missing": self.estimate_missing, "mesh_ladder": ladder}
            accuracy = {"accuracy": missing}
        corrections = {} if self.corrections is None else {"corrections": self.corrections}
        start = {} if self.start is None else {"ladder_start": self.start.to_dict()}
        return {
            **self.finite.to_dict_model(),
            "quick": self.quick,
            "inputs": {
                **profile_inputs(self.study.indenter),
                "E2": self.study.half_space.youngs_modulus,
                "nu2": self.study.half_space.poisson_ratio,
                "mass": self.study.mass,
                "velocity": self.study.velocity,
                "striker": "rigid",
            },
            "interface": {"kind": surface.kind, "friction": surface.friction},
            "mesh": {**self.finite.curve.mesh_stats, "settings": mesh.__dict__},
            "contact": self.finite.to_dict(),
            "steps": self.rows(),
            "impact": self.impacts,
            "impact_ratios": self.ratios(),
            "at_maximum": self.at_maximum(),
            "validity": self.limits(),
            **start,
            **accuracy,
            **corrections,
            "cpu_seconds": self.cpu_seconds,
        }


def _checks(
    study: FiniteStudy,
    finite: FiniteIndentationResult,
    linear: IndentationResult,
    depths: np.ndarray,
    quick: bool,
    start: LadderStart | None = None,
) -> list[Check]:
    tol = study.tolerances
    if quick:
        tol = msgspec.structs.replace(tol, small_strain=study.quick_small_strain)
    if start is not None:  # the first-order departure at the deeper start
        extra = start.allowance()
        small, fem = tol.small_strain + extra, tol.small_strain_fem + extra
        tol = msgspec.structs.replace(tol, small_strain=small, small_strain_fem=fem)
    first, first_fem = finite.steps[0], linear.steps[0]
    x = np.concatenate([[0.0], depths])
    p = np.concatenate([[0.0], [s.force for s in finite.steps]])
    energy = finite.steps[-1].strain_energy
    ratio = first.depth / first.contact_radius_linear
    return [
        *_linear_reference(study, first, linear, tol, ratio),
        Check(
            f"small-strain limit, P/P_linear-FEM - 1 at x/a = {ratio:.3g} (same mesh)",
            first.force / first_fem.force - 1.0,
            tol.small_strain_fem,
        ),
        Check(
            f"conservation, Simpson Int P dx / stored energy - 1 ({len(depths)} depths)",
            float(simpson(p, x=x) / energy - 1.0),
            tol.conservation,
        ),
        Check(
            "Newton, largest final correction max|du|/depth",
            float(max(s.corrections[-1] for s in finite.steps)),
            tol.newton,
        ),
        Check(
            "complementarity, largest |gap| on contact or penetration off it / depth",
            max(_complementarity(finite, s) for s in finite.steps),
            tol.complementarity,
        ),
    ]


def no_slip_checked(study: FiniteStudy) -> bool:
    """Whether a study whose reference Shtaerman's is not checks the no-slip identity of its
    same-mesh linear FEM: no slip, z = A r^n, on the half-space (Coulomb's annulus slips, and
    a pad stiffens the deep contact: :mod:`shtaerman.study.contact.interface`)."""
    no_slip, half_space = study.interface.friction is None, study.geometry.thickness is None
    return no_slip and half_space and study.indenter.kind == "power-law"


def _linear_reference(
    study: FiniteStudy,
    first: Any,
    linear: IndentationResult,
    tol: FiniteTolerances,
    ratio: float,
) -> list[Check]:
    """The small-strain limit's exact reference: Shtaerman's where it is the interface's
    (:func:`~shtaerman.study.contact.interface.shtaerman_applies`); for a bonded power law on
    nu2 < 0.5 on the half-space (:func:`no_slip_checked`), the no-slip identity of the
    same-mesh linear FEM (the reference of P/P_linear-FEM) at the deepest depth, where its
    contact covers most nodes; else none (no exact law: P/P_linear-FEM alone)."""
    if shtaerman_applies(study.interface, study.half_space.poisson_ratio):
        name = f"small-strain limit, P/P_Shtaerman - 1 at x/a = {ratio:.3g}"
        return [Check(name, first.force / first.force_linear - 1.0, tol.small_strain)]
    if not no_slip_checked(study):
        return []
    name = "linear no-slip identity P(n+1)/(2E* a d n) / chi - 1 at the deepest depth (same mesh)"
    return [Check(name, float(no_slip_departures(linear)[-1]), tol.identity)]


def _complementarity(finite: FiniteIndentationResult, step: Any) -> float:
    """Largest |g| where lambda > 0, or -g where lambda = 0, over depth (g recomputed)."""
    gap = finite.indenter.profile(step.current_radius) - step.depth - step.surface_u_z
    on = step.multipliers > 0
    worst_on = float(np.max(np.abs(gap[on]), initial=0.0))
    worst_off = float(np.max(-gap[~on], initial=0.0))
    negative = float(np.max(-step.multipliers, initial=0.0))
    return max(worst_on, worst_off, negative) / step.depth


def _run_level(
    study: FiniteStudy,
    depths: np.ndarray,
    mesh: MeshSettings,
    exact: ImpactResult | ProfileImpactResult,
    quick: bool,
    first: LadderStart | None = None,
) -> FiniteStudyOutcome:
    """The curve, the same-mesh linear FEM and three impacts on one mesh (no estimates);
    ``first``: where the ladder started when the mesh moved it."""
    start, cpu = time.perf_counter(), time.process_time()
    modulus = effective_modulus(RIGID, study.half_space)
    parts, friction = (study.indenter, study.half_space, depths, mesh), study.interface.coefficient
    finite = run_finite_study(*parts, study.rubber, friction, study.geometry)
    # nodal-sum forces, the finite-strain solver's own discretization: the ratio cancels it
    linear = run_indentation(*parts, aligned=False, friction=friction, geometry=study.geometry)
    impacts = {"linear_exact": {k: v for k, v in impact_maxima(exact).items() if k != "beta"}}
    histories = {"linear_exact": exact.history(HISTORY_POINTS)}
    for variant, result in (("linear_fem", linear), ("finite_strain", finite)):
        with warnings.catch_warnings():
            # quad's energy bracket (only the ODE's length scale) meets the log-log kinks
            warnings.simplefilter("ignore", IntegrationWarning)
            law = fem_contact_law(result, modulus)
            maxima, history = tabulated_impact(study, law, exact.x_c)
        maxima.pop("beta")
        impacts[variant], histories[variant] = maxima, history
    return FiniteStudyOutcome(
        study=study,
        quick=quick,
        finite=finite,
        linear_fem=linear,
        impacts=impacts,
        histories=histories,
        checks=_checks(study, finite, linear, depths, quick, first),
        seconds=time.perf_counter() - start,
        cpu_seconds=time.process_time() - cpu,
    )


def ladder_meshes(
    mesh: MeshSettings, nested: bool = False
) -> tuple[list[float], list[MeshSettings]]:
    """The error-estimate ladder around the study's ``mesh``: refinement factors (relative to
    ``mesh``) and settings, coarse to fine, every level checked before any meshing.

    ``nested``: :func:`shtaerman.study.ladder.nested_ladder`, factors 1/2, 1, 2,
    ratio :data:`~shtaerman.study.ladder.NESTED_RATIO`. Otherwise three independent gmsh
    meshes refined by 1/2, 1/sqrt(2), 1 (ratio :data:`~shtaerman.study.ladder.LADDER_RATIO`).
    """
    if nested:
        return nested_factors(1.0), list(nested_ladder(mesh))
    factors = ladder_factors(1.0)
    return factors, [mesh.refined(factor) for factor in factors]


LADDER_RATIOS = {True: NESTED_RATIO, False: LADDER_RATIO}
"""Element-size ratio of :func:`ladder_meshes`' levels, by ``nested``."""


def estimate_ladder(
    outcomes: list[FiniteStudyOutcome], factors: list[float], nested: bool
) -> FiniteEstimates:
    """The estimates of :func:`ladder_meshes`' levels: on a nested ladder the ratios of two
    separately computed quantities are propagated from their factors' estimates and the
    contact edge's numbers use its first order (:func:`.accuracy.estimate_study`); on
    independent gmsh levels Richardson alone."""
    rules = {"propagate": nested, "edge_order": nested, "envelopes": nested}
    return estimate_study(outcomes, factors, LADDER_RATIOS[nested], **rules)


def _depths(
    study: FiniteStudy, modulus: float, x_c: float, spec: Ladder, coarsest: MeshSettings
) -> tuple[np.ndarray, LadderStart | None]:
    """The study's depth ladder, and where it started when the ``coarsest`` mesh moved it
    (else None): a ``small_ratio`` depth whose contact covers fewer than MIN_CONTACT_NODES
    surface nodes moves to the smallest depth covering :data:`START_NODES`."""
    radii = surface_radii(study.indenter, spec.reach * x_c, coarsest, study.geometry)
    law = contact_law(study.indenter, modulus)
    requested = depth_at_ratio(study.indenter, spec.small_ratio)
    covered = np.count_nonzero(radii < law.contact_radius(requested))
    if covered >= MIN_CONTACT_NODES or radii.size < START_NODES:
        return ladder(study.indenter, modulus, x_c, spec), None
    smallest = float(law.depth(radii[START_NODES - 1] * (1.0 + 1e-9)))  # strictly inside
    depths = ladder(study.indenter, modulus, x_c, spec, smallest)
    ratio = float(depths[0] / law.contact_radius(depths[0]))
    return depths, LadderStart(spec.small_ratio, ratio, float(depths[0]))


def run_finite_strain_study(
    study: FiniteStudy,
    quick: bool = False,
    progress: Progress | None = None,
    *,
    estimate: bool = True,
) -> FiniteStudyOutcome:
    """Run one finite-strain study: the curve, the same-mesh linear FEM and three impacts, on
    the study's ladder around its mesh (:func:`ladder_meshes`) for the error estimates.

    Parameters
    ----------
    study : FiniteStudy
    quick : bool
        The coarse ``[quick]`` ladder and mesh (``verify --quick``), one mesh, no estimates.
    progress : callable, optional
        Receives a short line per stage.
    estimate : bool
        False: the study's mesh only, no estimates (sweeps).

    Returns
    -------
    FiniteStudyOutcome
        The finest level's (the study's mesh; twice as fine on a nested ladder), with
        ``estimates`` unless ``quick`` or not ``estimate``; without estimates the study's
        mesh alone; ``corrections`` after a ``[corrections]`` table (coarse if ``quick``). Its
        ``seconds`` and ``cpu_seconds`` count every level.
    """
    report = progress or (lambda _line: None)
    start, cpu = time.perf_counter(), time.process_time()
    modulus = effective_modulus(RIGID, study.half_space)
    exact = elastic_impact(study.mass, study.velocity, contact_law(study.indenter, modulus))
    spec = study.quick_ladder if quick else study.ladder
    mesh = study.quick_mesh if quick else study.mesh
    nested = study.mesh_ladder == "nested"
    if estimate and not quick:
        factors, meshes = ladder_meshes(mesh, nested)
    else:
        factors, meshes = [1.0], [mesh]
    first = None
    if study.depths is not None:
        depths = np.asarray(study.depths, dtype=float)
    else:
        depths, first = _depths(study, modulus, exact.x_c, spec, meshes[0])
        model = "neo-hookean" if study.rubber is None else study.rubber.name
        check_finite_depths(study.indenter, depths, model, (study.mass, study.velocity))
        if first is not None:
            report(f"{study.name}: {first.words()}")
    levels = _run_levels(
        study, depths, list(zip(factors, meshes, strict=True)), report, exact, quick, first
    )
    outcomes = [outcome for _, outcome in levels if not isinstance(outcome, str)]
    missing = {} if len(outcomes) == len(levels) else _missing(study, levels)
    estimates = None
    if len(outcomes) > 1 and not missing:
        estimates = estimate_ladder(outcomes, factors, nested)
    return replace(
        outcomes[-1],
        estimates=estimates,
        corrections=run_corrections(study, quick, report),
        start=first,
        seconds=time.perf_counter() - start,
        cpu_seconds=time.process_time() - cpu,
        **missing,
    )


Level = tuple[float, "FiniteStudyOutcome | str"]
"""A ladder level's refinement factor and its outcome, or what failed."""


def _run_levels(
    study: FiniteStudy,
    depths: np.ndarray,
    meshes: list[tuple[float, MeshSettings]],
    report: Progress,
    *level: Any,
) -> list[Level]:
    """:func:`_run_level` on each (factor, mesh) of ``meshes``, coarse to fine (``level``:
    the exact impact, ``quick`` and the ladder's start); a level that fails numerically
    (:data:`FAILURES`) is kept as what failed, unless it is the finest and none passed (then
    raised, as a Gent rubber's lock at once: its limit, which no mesh cures)."""
    levels: list[Level] = []
    with LadderWarnings() as said:
        for factor, mesh in meshes:
            report(
                f"{study.name}: mesh x{factor:.3g}: finite-strain curve ({depths.size} "
                "depths), linear FEM on the same mesh, impacts"
            )
            try:
                with said.level():
                    levels.append((factor, _run_level(study, depths, mesh, *level)))
            except GentLockError:
                raise
            except FAILURES as error:
                if factor == meshes[-1][0] and all(isinstance(o, str) for _, o in levels):
                    raise
                levels.append((factor, str(error)))
                report(f"{study.name}: mesh x{factor:.3g}: failed ({error})")
    return levels


def _missing(study: FiniteStudy, levels: list[Level]) -> dict[str, Any]:
    """``estimate_missing`` and ``mesh_ladder`` of a ladder whose ``levels`` lost one or
    more, said once as an :class:`EstimateMissingWarning`."""
    failed = "; ".join(f"refine {f:.3g}: {o}" for f, o in levels if isinstance(o, str))
    missing = f"a ladder level failed, {failed}"
    rows: list[dict[str, object]] = []
    for factor, outcome in levels:
        if isinstance(outcome, str):
            rows.append({"refine": factor, "dofs": None, "seconds": None, "failure": outcome})
        else:
            dofs = int(outcome.finite.curve.mesh_stats["dofs"])
            rows.append({"refine": factor, "dofs": dofs, "seconds": outcome.seconds})
    finest = next(f for f, o in reversed(levels) if not isinstance(o, str))
    warnings.warn(
        f"study {study.name!r}: no error estimate: {missing}; the finest level that passed "
        f"(mesh x{finest:.3g}) is reported. Another mesh (refine, mesh_size) may pass",
        EstimateMissingWarning,
        stacklevel=caller_stacklevel(),
    )
    return {"estimate_missing": missing, "mesh_ladder": tuple(rows)}
