"""Every FEM contact number with its error bar: a mesh ladder, Richardson estimates, a target.

The ladder refines the whole size field by :data:`~shtaerman.study.ladder.LADDER_RATIO` per
level; the finest level's force, contact radius and central pressure (worst depth), beta and
exponent get Richardson estimates (:mod:`shtaerman.study.richardson`), beside the true error
where the exact solution is known. A level that fails numerically (:data:`FAILURES`) leaves,
``partial``, the finest that passed without estimate (:attr:`AccuracyResult.missing`);
:func:`run_to_accuracy` refines until a tolerance (:attr:`AccuracyResult.unreached`). More:
benchmarks/FEM_NOTES.md, "Study error estimates".
"""

from __future__ import annotations

import functools
import math
import time
import warnings
from collections.abc import Callable, Mapping
from dataclasses import dataclass, replace
from typing import Any, Protocol

import numpy as np
from numpy.typing import ArrayLike

from ...fem.fit import exponent_sensitivity
from ...fem.mesh import (
    DEFAULTS,
    HALF_SPACE,
    MAX_DOMAIN,
    Geometry,
    GradedMesh,
    Grading,
    MeshSettings,
)
from ...guards import LadderWarnings
from ...theory.indenter import PowerLawIndenter
from ...theory.materials import Material
from ...theory.viscoelastic import PronySeries
from ...validation import InputError, bound_text, caller_stacklevel, validate_positive
from ..dynamic.accuracy import FAILURES, EstimateMissingWarning
from ..ladder import LADDER_RATIO, check_ladder, ladder_factors
from ..richardson import Estimate, at_most_order, curve_richardson, richardson, worst_point
from .indentation import default_depths, refined_radius, run_indentation

__all__ = [
    "AccuracyNotReachedWarning",
    "AccuracyResult",
    "LadderLevel",
    "run_ladder",
    "run_mesh_ladder",
    "run_to_accuracy",
]

STEP_QUANTITIES = ("force", "contact_radius", "central_pressure")
"""Estimated over the depths: the estimate of the worst depth
(:func:`~shtaerman.study.richardson.curve_richardson`)."""
CURVE_QUANTITIES = ("beta", "exponent")
FORCE_LIKE = ("force", "beta")
"""What ``--accuracy`` drives below its tolerance."""
ORDERS = {"force": 3.0, "beta": 3.0, "central_pressure": 3.0, "contact_radius": 2.5}
"""Orders of the extrapolation, and the largest orders of the error estimates: a ladder that
observes a lower order (in :data:`SANE_ORDERS`) reports the correction at its own order as the
error (the exponent always uses its observed order; benchmarks/FEM_NOTES.md, "Accuracy 1e-6")."""
EDGE_ORDER = 2.0
"""The slowest order of the force's error: the contact edge's, in the surface size."""
FORCE_SAFETY = 1.25
"""Factor on the force and beta estimates (Roache's factor of safety of a three-mesh study
at its observed order; benchmarks/FEM_NOTES.md, "Accuracy 1e-6")."""
SANE_ORDERS = (1.0, 5.0)
"""Observed orders (of the largest difference over the depths) taken as asymptotic."""
TIME_GROWTH = 2.4
"""Observed time ratio of consecutive ladder levels (dofs x2; factorization superlinear)."""
TRUNCATION = {"force": 1.886, "beta": 1.16}
"""Stiffening by the clamped far boundary, times R / a (R the domain radius, a the largest
contact radius; :class:`shtaerman.fem.mesh.MeshSettings`, ``benchmarks/bench_contact.py``
(c)); a bias common to every level, unseen by the ladder, so added to the estimate."""
LAYER_TRUNCATION = 1e-5
"""Bound on the relative change of force and beta by a layer's lateral edge r = L, the same
on every level (benchmarks/FEM_NOTES.md, "Layer reference"); added to the force and beta
estimates as :data:`TRUNCATION` is on the half-space."""

Progress = Callable[[str], None]


class AccuracyNotReachedWarning(UserWarning):
    """A level of :func:`run_to_accuracy` beyond its first three failed: the estimate of the
    last three that passed is reported, above the tolerance asked."""


class LadderCurve(Protocol):
    """A contact curve a ladder level holds (linear or finite strain)."""

    steps: Any
    fit: Any
    mesh_stats: dict[str, Any]
    timings: dict[str, float]

    def errors(self) -> dict[str, float]: ...


Solve = Callable[[MeshSettings], LadderCurve]
"""One contact curve on the given mesh (the depths and materials bound in)."""


@dataclass(frozen=True)
class LadderLevel:
    """One mesh of the ladder: its refinement factor and result (linear or finite strain)."""

    refine: float
    result: LadderCurve

    @property
    def dofs(self) -> int:
        """Degrees of freedom of the level."""
        return int(self.result.mesh_stats["dofs"])

    @property
    def seconds(self) -> float:
        """Wall time of the level (mesh to contact), s."""
        return float(self.result.timings["total"])


@dataclass(frozen=True)
class AccuracyResult:
    """A mesh ladder and the error estimates of its finest level.

    Attributes
    ----------
    levels : tuple of LadderLevel
        Coarse to fine; the finest is the answer.
    estimates : dict of str to Estimate
        Per quantity; for the per-depth quantities the depth with the largest estimate.
    tolerance : float or None
        The target of :func:`run_to_accuracy` (None for a plain ladder).
    exact : bool
        Whether the levels' ``errors()`` are true errors against an exact solution (the
        linear contact); False for the finite-strain contact, which has none.
    failures : tuple of (float, str)
        The levels that failed: refinement factor and what failed; then ``estimates`` is
        empty and :attr:`missing` says why.
    unreached : str
        Why ``tolerance`` was not reached ("" when it was, or none was set): a level of
        :func:`run_to_accuracy` beyond the first three failed, ``estimates`` are those of the
        last three levels that passed.
    steps : tuple of dict of str to Estimate
        Per depth, the estimates of :data:`STEP_QUANTITIES` (:func:`step_estimates`); empty
        where ``estimates`` is.
    """

    levels: tuple[LadderLevel, ...]
    estimates: dict[str, Estimate]
    tolerance: float | None = None
    exact: bool = True
    failures: tuple[tuple[float, str], ...] = ()
    unreached: str = ""
    steps: tuple[dict[str, Estimate], ...] = ()

    @property
    def missing(self) -> str:
        """Why the estimate is missing ("" when every level passed)."""
        failed = "; ".join(f"refine {refine:.3g}: {why}" for refine, why in self.failures)
        return f"a ladder level failed, {failed}" if failed else ""

    @property
    def finest(self) -> LadderCurve:
        """The finest level's result: the reported numbers."""
        return self.levels[-1].result

    def error_estimate(self) -> dict[str, float]:
        """Estimated relative error of every quantity (dimensionless)."""
        return {key: estimate.error for key, estimate in self.estimates.items()}

    def effectivity(self) -> dict[str, float]:
        """Estimated over true relative error, where the exact solution gives the truth."""
        true = self.finest.errors()
        return {
            key: estimate.error / true[key] if true[key] > 0 else math.nan
            for key, estimate in self.estimates.items()
        }

    def worst_depths(self) -> dict[str, float]:
        """The depth (m) of each per-depth quantity's estimate and extrapolated value: where the
        last two levels differ most (:func:`~shtaerman.study.richardson.worst_point`)."""
        last = [level.result.steps for level in self.levels[-2:]]
        depths = {}
        for key in STEP_QUANTITIES:
            if key in self.estimates:
                worst = worst_point([[getattr(step, key) for step in steps] for steps in last])
                depths[key] = float(self.finest.steps[worst].depth)
        return depths

    def to_dict(self) -> dict[str, object]:
        """The JSON keys ``error_estimate``, ``extrapolated``, ``extrapolated_depth`` (the depth
        of each per-depth quantity's estimate, m: :meth:`worst_depths`), ``step_error_estimate``
        (each depth's, :attr:`steps`), ``mesh_ladder`` and details (``true_error`` and
        ``effectivity`` only where the exact solution is known; ``accuracy_unreached`` only
        where :attr:`unreached` says why)."""
        if self.failures:
            return self._without_estimate()
        truth = {}
        if self.exact:
            truth = {
                "true_error": {k: self.finest.errors()[k] for k in self.estimates},
                "effectivity": self.effectivity(),
            }
        return {
            "error_estimate": self.error_estimate(),
            "extrapolated": {k: e.extrapolated for k, e in self.estimates.items()},
            "extrapolated_depth": self.worst_depths(),
            "estimate_details": {k: e.to_dict() for k, e in self.estimates.items()},
            "step_error_estimate": [{k: e.error for k, e in step.items()} for step in self.steps],
            **truth,
            "mesh_ladder": [
                {"refine": level.refine, "dofs": level.dofs, "seconds": level.seconds}
                for level in self.levels
            ],
            "accuracy_target": self.tolerance,
            **({"accuracy_unreached": self.unreached} if self.unreached else {}),
        }

    def _without_estimate(self) -> dict[str, object]:
        """:meth:`to_dict` of a ladder with a failed level: the estimate keys None,
        ``estimate_missing`` why, the failed levels' dofs and seconds None."""
        rows = [
            {"refine": level.refine, "dofs": level.dofs, "seconds": level.seconds}
            for level in self.levels
        ]
        rows += [
            {"refine": refine, "dofs": None, "seconds": None, "failure": why}
            for refine, why in self.failures
        ]
        return {
            **dict.fromkeys(("error_estimate", "extrapolated", "extrapolated_depth")),
            "estimate_details": None,
            "step_error_estimate": None,
            "estimate_missing": self.missing,
            "mesh_ladder": sorted(rows, key=lambda row: row["refine"]),
            "accuracy_target": self.tolerance,
        }


def _truncation(result: LadderCurve, key: str) -> float:
    """The far-boundary stiffening of ``key`` (relative) on this mesh."""
    if key not in TRUNCATION:
        return 0.0
    if "thickness" in result.mesh_stats:  # a layer's lateral edge
        return LAYER_TRUNCATION
    largest = result.steps[-1].contact_radius
    return TRUNCATION.get(key, 0.0) * largest / result.mesh_stats["domain_radius"]


def estimate_errors(
    levels: tuple[LadderLevel, ...], orders: Mapping[str, float] = ORDERS
) -> dict[str, Estimate]:
    """Estimates of the finest level from the last three levels (two at least).

    Richardson over the depths (:func:`~shtaerman.study.richardson.curve_richardson`) for the
    force, contact radius and central pressure, over the levels for beta and the exponent, with
    the ``orders`` (default :data:`ORDERS`; the error at the observed order where that is
    lower), where the observed order lies in :data:`SANE_ORDERS` (else the two-level
    difference); for force and beta at least :func:`_edge_floor`, times :data:`FORCE_SAFETY`,
    plus the known far-field truncation (:data:`TRUNCATION`).

    The fits take at least the bound the force's estimate eps implies (every depth's force
    within eps, relative): beta's relative error at least eps (its log is the mean of the
    depths' log P_i), the exponent's at least S eps / |q| (relative, as every estimate;
    absolute S eps), S the fit's :func:`~shtaerman.fem.fit.exponent_sensitivity`; where
    that bound is the larger, the estimate's method is ``"propagated"`` (why:
    benchmarks/FEM_NOTES.md, "Accuracy 1e-6").
    """
    results = [level.result for level in levels]
    estimates = _curve_estimates(results, orders, slice(None))
    for key in CURVE_QUANTITIES:
        fits = [result.fit for result in results]
        values = [f.beta_fixed_exponent if key == "beta" else f.exponent for f in fits]
        if all(math.isfinite(v) for v in values):
            estimates[key] = at_most_order(
                richardson, values, LADDER_RATIO, orders.get(key), sane=SANE_ORDERS
            )
            if key in FORCE_LIKE:
                estimates[key] = _force_like(estimates[key], values, results[-1], key, orders)
    bounds = {"beta": 1.0}  # per unit force error; beta's log weighs every depth by 1/N
    if "exponent" in estimates:
        depths = [step.depth for step in results[-1].steps]
        bounds["exponent"] = exponent_sensitivity(depths) / abs(estimates["exponent"].extrapolated)
    for key, bound in bounds.items():
        if key in estimates and bound * estimates["force"].error > estimates[key].error:
            own, error = estimates[key], bound * estimates["force"].error
            reason = f"the bound from the force's error exceeds the ladder's own {own.error:.1e}"
            estimates[key] = replace(
                own, error=error, order=math.nan, method="propagated", reason=reason
            )
    return estimates


def step_estimates(
    levels: tuple[LadderLevel, ...], orders: Mapping[str, float] = ORDERS
) -> tuple[dict[str, Estimate], ...]:
    """Each depth's estimates of :data:`STEP_QUANTITIES`: the rules of :func:`estimate_errors`
    over the depth and its two neighbours (the curve's estimate takes every depth; a shallow
    depth has fewer elements across its contact than the deepest, on a mesh sized by it)."""
    results = [level.result for level in levels]
    count = len(results[-1].steps)
    return tuple(
        _curve_estimates(results, orders, slice(max(0, k - 1), k + 2)) for k in range(count)
    )


def _curve_estimates(
    results: list[LadderCurve], orders: Mapping[str, float], depths: slice
) -> dict[str, Estimate]:
    """The estimates of :data:`STEP_QUANTITIES` over the ``depths`` of the curves
    (:func:`estimate_errors`' rules)."""
    estimates = {}
    for key in STEP_QUANTITIES:
        ladder = [[getattr(step, key) for step in result.steps][depths] for result in results]
        estimates[key] = at_most_order(
            curve_richardson, ladder, LADDER_RATIO, orders[key], sane=SANE_ORDERS
        )
        if key in FORCE_LIKE:
            estimates[key] = _force_like(estimates[key], ladder, results[-1], key, orders)
    return estimates


def _force_like(
    estimate: Estimate, values: list, result: LadderCurve, key: str, orders: Mapping[str, float]
) -> Estimate:
    """``estimate`` of a force-like quantity (at the known ``orders[key]``): at least
    :func:`_edge_floor`, times :data:`FORCE_SAFETY`, plus the far-field truncation of
    ``result`` (:func:`_truncation`)."""
    error = max(estimate.error, _edge_floor(values, estimate, orders.get(key)))
    return replace(estimate, error=FORCE_SAFETY * error + _truncation(result, key))


def _edge_floor(values: list, estimate: Estimate, known: float | None) -> float:
    """The least error a force-like quantity's ladder allows (relative): its first difference
    D1 (the largest over the depths) shrunk by one level at the edge's order
    :data:`EDGE_ORDER`, then corrected as ``estimate`` is (at the lower of its order and the
    observed one; a fall-back at the edge's order). The last difference D2 can be far below
    D1 / s^2 where the far field's faster term, of the other sign, still shrinks in it; where
    the edge term dominates D2 = D1 / s^2 and the floor changes nothing.

    No floor where the ladder shows no order-2 term: Richardson's observed order at least the
    ``known`` one (if given) and every depth's two differences of one sign (two terms of
    opposite sign make a depth's differences change sign). Measurements: benchmarks/FEM_NOTES.md,
    "Accuracy 1e-6"."""
    levels = [np.atleast_1d(np.asarray(v, dtype=float)) for v in values[-3:]]
    if len(levels) < 3 or _confirmed(levels, estimate, known):
        return 0.0
    first = float(np.max(np.abs(levels[0] - levels[1]) / np.abs(levels[-1])))
    order = estimate.order if math.isfinite(estimate.order) else EDGE_ORDER
    return first / LADDER_RATIO**EDGE_ORDER / (LADDER_RATIO**order - 1.0)


def _confirmed(levels: list[np.ndarray], estimate: Estimate, known: float | None) -> bool:
    """Whether the ladder ``levels`` (three, coarse to fine) converges at the ``known`` order
    (``estimate``'s own without one) or faster, monotonically at every depth
    (:func:`_edge_floor`)."""
    monotone = np.all((levels[1] - levels[0]) * (levels[2] - levels[1]) > 0.0)
    order = estimate.order if known is None else known
    fast = estimate.method == "richardson" and estimate.observed_order >= order
    return bool(monotone and fast)


def estimated(
    levels: tuple[LadderLevel, ...], orders: Mapping[str, float], **fields: Any
) -> AccuracyResult:
    """The :class:`AccuracyResult` of ``levels`` with the estimates of the last three
    (:func:`estimate_errors`, :func:`step_estimates` at ``orders``) and the other ``fields``."""
    last = levels[-3:]
    steps = step_estimates(last, orders)
    return AccuracyResult(levels, estimate_errors(last, orders), steps=steps, **fields)


def _level(solve: Solve, base: MeshSettings, refine: float, progress: Progress) -> LadderLevel:
    level = LadderLevel(refine, solve(base.refined(refine)))
    progress(f"mesh x{refine:.3g}: {level.dofs} dofs, {level.seconds:.1f} s")
    return level


def run_mesh_ladder(
    solve: Solve,
    mesh: MeshSettings,
    *,
    refine: float = 1.0,
    progress: Progress | None = None,
    exact: bool = True,
    refined: float | None = None,
    partial: bool = False,
    geometry: Geometry = HALF_SPACE,
    orders: Mapping[str, float] = ORDERS,
) -> AccuracyResult:
    """Any contact curve on three meshes, ``mesh`` refined by refine / 2, refine / sqrt(2)
    and refine, with the estimates of :func:`estimate_errors` for the finest.

    Parameters
    ----------
    solve : callable
        MeshSettings -> a result with ``steps``, ``fit``, ``mesh_stats`` and ``timings``.
    mesh : MeshSettings
        The base mesh (refine = 1).
    refine : float
        Refinement factor of the finest level.
    progress : callable, optional
        Receives one line per level.
    exact : bool
        Whether the results' ``errors()`` are true errors (see :class:`AccuracyResult`).
    refined : float, optional
        Refined-zone radius in m of the curve, for a layer's size guard before any level.
    geometry : Geometry
        The body's shape (its layer's size guard).
    partial : bool
        Keep the levels that passed when another fails numerically (:data:`FAILURES`): the
        finest that passed answers, without estimate (an :class:`EstimateMissingWarning`);
        else the first failure is raised.
    orders : mapping of str to float
        The orders of :func:`estimate_errors` (default :data:`ORDERS`, the linear contact's).

    Raises
    ------
    NewtonError, shtaerman.validation.NumericalFailureError
        A level's failure (``partial``: the finest level's, when no level passed).
    """
    refine = validate_positive("refine", refine)
    check_ladder(mesh, refine, refined, geometry)  # every level, before the first is computed
    report = progress or (lambda _line: None)
    levels, failures = [], []
    with LadderWarnings() as said:
        for factor in ladder_factors(refine):
            try:
                with said.level():
                    levels.append(_level(solve, mesh, factor, report))
            except FAILURES as error:
                if not partial or (factor == refine and not levels):
                    raise
                failures.append((factor, str(error)))
                report(f"mesh x{factor:.3g}: failed ({error})")
    if not failures:
        return estimated(tuple(levels), orders, exact=exact)
    result = AccuracyResult(tuple(levels), {}, exact=exact, failures=tuple(failures))
    warnings.warn(
        f"no error estimate: {result.missing}; the finest level that passed (refine "
        f"{levels[-1].refine:.3g}) is reported. Another mesh (refine=..., mesh_size=...) may "
        "pass",  # in Python's words: each route words it (shtaerman.problem.worded)
        EstimateMissingWarning,
        stacklevel=caller_stacklevel(),
    )
    return result


def run_ladder(
    indenter: PowerLawIndenter,
    half_space: Material,
    depths: ArrayLike | None = None,
    mesh: MeshSettings | None = None,
    *,
    refine: float = 1.0,
    backend: str = "auto",
    progress: Progress | None = None,
    prony: PronySeries | None = None,
    rate: float | None = None,
    friction: float | None = None,
    partial: bool = False,
    geometry: Geometry = HALF_SPACE,
) -> AccuracyResult:
    """The contact on three meshes, refine / 2, refine / sqrt(2), refine: the finest answers.

    Parameters
    ----------
    indenter, half_space, depths, backend, prony, rate, friction, geometry
        As for :func:`.indentation.run_indentation`.
    mesh : MeshSettings, optional
        The base mesh (refine = 1); default ``MeshSettings()``.
    refine : float
        Refinement factor of the finest level: element sizes divided by it everywhere.
    progress : callable, optional
        Receives one line per level.
    partial : bool
        As for :func:`run_mesh_ladder`.

    Returns
    -------
    AccuracyResult
    """
    mesh = MeshSettings() if mesh is None else mesh
    depths = default_depths(indenter, half_space) if depths is None else np.asarray(depths)
    physics = {"prony": prony, "rate": rate, "friction": friction, "geometry": geometry}
    physics["backend"] = backend
    solve = functools.partial(run_indentation, indenter, half_space, depths, **physics)
    refined = refined_radius(indenter, depths, mesh, geometry)
    steps = {"progress": progress, "exact": _exact(geometry, friction), "refined": refined}
    return run_mesh_ladder(solve, mesh, refine=refine, partial=partial, geometry=geometry, **steps)


def _exact(geometry: Geometry, friction: float | None) -> bool:
    """Whether the curve's ``errors()`` are true errors: on a layer or under a bonded indenter
    they are departures from Shtaerman's solution (a layer's reference is
    :mod:`shtaerman.theory.layer_reference`)."""
    return geometry.thickness is None and friction is None


def _far_field(mesh: MeshSettings, tolerance: float, geometry: Geometry) -> MeshSettings:
    """``mesh`` with the domain enlarged until the half-space's far-boundary truncation is a
    tenth of ``tolerance``; InputError if the truncation alone exceeds half of it (on the
    layer of ``geometry``: if its lateral edge's does)."""
    if geometry.thickness is not None:
        if tolerance < 2.0 * LAYER_TRUNCATION:
            raise InputError(
                f"accuracy must be >= {bound_text(2.0 * LAYER_TRUNCATION, 'low', 2)} on a layer: "
                f"its lateral edge alone may change the force by {LAYER_TRUNCATION:.2g}, which no "
                f"refinement removes; got {tolerance!r}"
            )
        return mesh
    floor = 2.0 * TRUNCATION["force"] / (MAX_DOMAIN * mesh.margin)
    if tolerance < floor:
        raise InputError(
            f"accuracy must be >= {bound_text(floor, 'low', 2)}: the clamped far boundary alone "
            f"stiffens the force by about {floor / 2:.2g} at the largest domain "
            f"({MAX_DOMAIN:g} refined radii), which no refinement removes; got {tolerance!r}"
        )
    domain = min(max(mesh.domain, 10.0 * TRUNCATION["force"] / tolerance), MAX_DOMAIN)
    return replace(mesh, domain=domain)


ACCURACY_GRADING = Grading(near_growth=0.27, near_depth=0.05, far_growth=0.3, far_start=1e3)
"""The size field of :data:`ACCURACY_MESH`: growth 0.27 for the first 0.05 refined radii
below the surface (the rows of the finest elements), 0.3 beyond 1e3 refined radii (whose share
of the force is a / 1e3); the band starts at the smallest geometric contact radius
(:func:`accuracy_mesh`)."""
ACCURACY_MESH = GradedMesh(size=0.0016, growth=0.08, axis_growth=0.18, grading=ACCURACY_GRADING)
"""The base (refine 1) of ``--accuracy`` TOL < :data:`GRADED_BELOW` on the default
half-space, graded by :data:`ACCURACY_GRADING` (why these sizes: benchmarks/FEM_NOTES.md,
"Accuracy 1e-6")."""
GRADED_BELOW = 1e-4
"""``--accuracy`` TOL below this runs on the graded family, the cheaper one there
(benchmarks/FEM_NOTES.md, "Accuracy 1e-6")."""


def accuracy_mesh(
    mesh: MeshSettings,
    indenter: PowerLawIndenter,
    depths: np.ndarray,
    tolerance: float,
    geometry: Geometry = HALF_SPACE,
) -> MeshSettings:
    """The family of ``--accuracy`` TOL: :data:`ACCURACY_MESH` where ``mesh`` is the default
    mesh (up to the domain and the dofs cap) of the half-space ``geometry`` and TOL <
    :data:`GRADED_BELOW`, its band from the smallest geometric contact radius to the refined
    radius; else ``mesh``."""
    default = replace(mesh, domain=DEFAULTS.domain, max_dofs=DEFAULTS.max_dofs) == DEFAULTS
    if not default or geometry.thickness is not None or tolerance >= GRADED_BELOW:
        return mesh
    band = float(indenter.radius_at(depths[0])) / refined_radius(indenter, depths, mesh)
    grading = replace(ACCURACY_GRADING, band_start=min(band, 1.0))
    return replace(ACCURACY_MESH, domain=mesh.domain, max_dofs=mesh.max_dofs, grading=grading)


def _force_error(result: AccuracyResult) -> float:
    return max(result.estimates[key].error for key in FORCE_LIKE if key in result.estimates)


def _check_reachable(
    result: AccuracyResult, tolerance: float, max_dofs: int, time_left: float
) -> None:
    """Refuse early when the target needs more dofs or time than allowed."""
    error = _force_error(result)
    if error <= tolerance:
        return
    orders = [result.estimates[k].order for k in FORCE_LIKE if k in result.estimates]
    order = max(min(filter(math.isfinite, orders), default=ORDERS["force"]), SANE_ORDERS[0])
    steps = math.ceil(math.log(error / tolerance) / (order * math.log(LADDER_RATIO)))
    dofs = result.levels[-1].dofs * 2**steps
    seconds = sum(result.levels[-1].seconds * TIME_GROWTH**k for k in range(1, steps + 1))
    if dofs > max_dofs:
        raise InputError(
            f"accuracy {tolerance:g} needs about {dofs:.3g} dofs (estimated error {error:.2g} "
            f"at {result.levels[-1].dofs} dofs, order {order:.2f}), above max_dofs="
            f"{max_dofs:.0f}; raise max_dofs=... or loosen accuracy=...",
            "accuracy",
        )
    if seconds > time_left:
        raise InputError(
            f"accuracy {tolerance:g} needs about {seconds:.0f} s more (estimated error "
            f"{error:.2g} at {result.levels[-1].dofs} dofs), above what max_time=... leaves; "
            "raise it or loosen accuracy=...",
            "accuracy",
        )


def run_to_accuracy(
    indenter: PowerLawIndenter,
    half_space: Material,
    tolerance: float,
    depths: ArrayLike | None = None,
    mesh: MeshSettings | None = None,
    *,
    max_time: float = 60.0,
    max_dofs: float | None = None,
    backend: str = "auto",
    progress: Progress | None = None,
    friction: float | None = None,
    geometry: Geometry = HALF_SPACE,
) -> AccuracyResult:
    """Refine until the estimated force and beta errors are at most ``tolerance``.

    The domain is enlarged (up to the mesh's limit, :data:`shtaerman.fem.mesh.MAX_DOMAIN`) so
    that the far-field truncation, which the ladder does not see, stays below a tenth of the
    tolerance; at that limit it is about 1.5e-7, so below TOL = 1.5e-6 it takes a larger share,
    and a TOL under twice it is refused (on a layer the domain stays: its lateral edge
    contributes :data:`LAYER_TRUNCATION`, and a TOL under twice that is refused). Below
    :data:`GRADED_BELOW` the default half-space mesh is replaced by the graded family
    :data:`ACCURACY_MESH` (:func:`accuracy_mesh`). After the first three
    levels the needed refinement is predicted from the observed order; a target that needs
    more than ``max_dofs`` or ``max_time`` is refused at once with an InputError.

    Parameters
    ----------
    tolerance : float
        Target relative error of force (every depth) and beta, in (0, 0.1].
    max_time : float
        Time budget in s for the whole ladder.
    max_dofs : float, optional
        Largest finest level allowed (default: the mesh's ``max_dofs``).
    indenter, half_space, depths, mesh, backend, progress, friction, geometry
        As for :func:`run_ladder`.

    Returns
    -------
    AccuracyResult
        With ``tolerance`` set; its finest level meets it, unless a level failed
        numerically: within the first three the estimate is missing (as
        :func:`run_mesh_ladder` ``partial``), beyond them :attr:`AccuracyResult.unreached`
        says why the tolerance was not reached.
    """
    tolerance = validate_positive("accuracy", tolerance)
    if tolerance > 0.1:
        raise InputError(f"accuracy must lie in (0, 0.1], got {tolerance!r}")
    max_time = validate_positive("max-time", max_time, "s")
    start = time.perf_counter()
    mesh = _far_field(MeshSettings() if mesh is None else mesh, tolerance, geometry)
    max_dofs = mesh.max_dofs if max_dofs is None else max_dofs
    depths = default_depths(indenter, half_space) if depths is None else np.asarray(depths)
    mesh = accuracy_mesh(mesh, indenter, depths, tolerance, geometry)
    physics = {"backend": backend, "friction": friction, "geometry": geometry}
    solve = functools.partial(run_indentation, indenter, half_space, depths, **physics)
    exact, refined = _exact(geometry, friction), refined_radius(indenter, depths, mesh, geometry)
    steps = {"progress": progress, "exact": exact, "refined": refined, "partial": True}
    steps["geometry"] = geometry
    result = replace(run_mesh_ladder(solve, mesh, **steps), tolerance=tolerance)
    report = progress or (lambda _line: None)
    while not result.failures and _force_error(result) > tolerance:
        _check_reachable(result, tolerance, max_dofs, max_time - (time.perf_counter() - start))
        refine = result.levels[-1].refine * LADDER_RATIO
        try:
            level = _level(solve, mesh, refine, report)
        except FAILURES as error:
            report(f"mesh x{refine:.3g}: failed ({error})")
            return _unreached(result, refine, str(error))
        levels = (*result.levels, level)
        result = estimated(levels, ORDERS, tolerance=tolerance, exact=exact)
    return result


def _unreached(result: AccuracyResult, refine: float, why: str) -> AccuracyResult:
    """``result`` (the last three levels that passed answer) with the level of ``refine``
    failed for ``why``: :attr:`AccuracyResult.unreached` says so, and a warning."""
    unreached = (
        f"accuracy {result.tolerance:g} not reached: the level of refine {refine:.3g} failed "
        f"({why}); the estimate {_force_error(result):.2g} (force and beta) is that of the last "
        f"three levels that passed (refine {result.levels[-1].refine:.3g} answers)"
    )
    warnings.warn(unreached, AccuracyNotReachedWarning, stacklevel=caller_stacklevel())
    return replace(result, unreached=unreached)
