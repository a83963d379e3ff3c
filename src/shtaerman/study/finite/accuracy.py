"""Error bars for the finite-strain study: its numbers on three meshes, Richardson estimates.

Every number the study (:mod:`.runner`) reports on its finest mesh gets an estimate
(:mod:`shtaerman.study.richardson`) from the three levels: per depth (:data:`STEP_KEYS`), at
the finite-strain x_c (:data:`AT_X_C`), the impact maxima (:data:`IMPACT_KEYS`) and the 1 % /
5 % crossings. The rules of a nested ladder and the crossings': benchmarks/FEM_NOTES.md,
"Study error estimates".
"""

from __future__ import annotations

import itertools
import math
from collections.abc import Sequence
from dataclasses import dataclass
from typing import Any, Protocol

import numpy as np
from numpy.typing import ArrayLike

from ..ladder import LADDER_RATIO
from ..richardson import ESTIMATED, Estimate, envelope, propagated, richardson

__all__ = [
    "CROSSING_KEYS",
    "STEP_KEYS",
    "FiniteEstimates",
    "LevelOutcome",
    "estimate_study",
    "reported_values",
]

STEP_KEYS = ("force_ratio", "force_ratio_fem", "radius_ratio", "central_to_mean", "strain_energy")
"""Per-depth values of :meth:`.finite.FiniteStudyOutcome.rows` that get an estimate."""
AT_X_C = ("force_ratio", "force_ratio_fem", "radius_ratio", "central_to_mean")
"""Values at the finite-strain x_c (:meth:`.finite.FiniteStudyOutcome.at_maximum`) that get
an estimate."""
IMPACT_KEYS = ("x_c", "P_c", "a_c", "p_c", "t_c", "t_y")
"""Finite-strain impact maxima that get an estimate, also as ratios to the same-mesh linear
FEM impact's."""
EDGE_KEYS = ("radius_ratio", "central_to_mean")
"""Per-depth values set by the contact edge (a, and p(0)/p_avg through p_avg = P/(pi a^2))."""
EDGE_ORDER = 1.0
"""Order in h used for :data:`EDGE_KEYS` and the impact's a_c (see :func:`edge_richardson`)."""
EDGE_BAND = (0.5, 4.5)
"""Observed orders with which :func:`edge_richardson` accepts :data:`EDGE_ORDER`."""
CROSSING_KEYS = ("depth_to_radius", "depth", "velocity")
"""What a 1 % / 5 % crossing reports (x/a, depth in m, impact velocity in m/s)."""


class LevelOutcome(Protocol):
    """What the estimator reads of one ladder level's study outcome
    (:class:`.finite.FiniteStudyOutcome` without estimates)."""

    impacts: dict[str, dict[str, float]]
    finite: Any
    seconds: float
    cpu_seconds: float

    def rows(self) -> list[dict[str, float]]: ...

    def at_maximum(self) -> dict[str, float]: ...

    def validity(self, departure_shift: ArrayLike = 0.0) -> list[dict[str, Any]]: ...


@dataclass(frozen=True)
class FiniteEstimates:
    """The ladder of a finite-strain study and the estimates of its finest level.

    Attributes
    ----------
    refines : tuple of float
        Levels' refinement factors relative to the study's mesh (which holds its own
        ``[mesh] refine``), coarse to fine.
    dofs, seconds, cpu_seconds : tuple
        Per level: unknowns, wall and CPU time in s (curve, linear FEM and impacts).
    scalars : dict of str to Estimate
        ``x_c`` ... ``t_y`` (finite-strain impact), ``x_c_vs_fem`` ... (ratios to the
        linear-FEM impact), ``<step key>_at_x_c``, and ``force_ratio_worst`` (the depth with
        the largest estimate of P/(beta x^q)).
    steps : tuple of dict of str to Estimate
        Per depth, for :data:`STEP_KEYS`.
    crossings : tuple of dict
        Per departure level (:data:`.finite.LEVELS`): ``errors`` (relative, for
        :data:`CROSSING_KEYS`) and ``departure_error`` (absolute, a fraction of the force).
    ratio : float
        Element-size ratio of consecutive levels: sqrt(2) on independent gmsh meshes, 2 on a
        nested ladder.
    """

    refines: tuple[float, ...]
    dofs: tuple[int, ...]
    seconds: tuple[float, ...]
    cpu_seconds: tuple[float, ...]
    scalars: dict[str, Estimate]
    steps: tuple[dict[str, Estimate], ...]
    crossings: tuple[dict[str, object], ...]
    ratio: float = LADDER_RATIO

    def worst_step(self, key: str = "force_ratio") -> int:
        """Index of the depth with the largest estimated error of ``key``."""
        return _worst(self.steps, key)

    def fallbacks(self) -> tuple[int, int]:
        """How many of the estimated numbers (scalars and per-depth values) fell back to a
        two-level difference, and of how many."""
        every = [*self.scalars.values(), *(e for step in self.steps for e in step.values())]
        return sum(e.method not in ESTIMATED for e in every), len(every)

    def to_dict(self) -> dict[str, object]:
        """The JSON keys ``error_estimate``, ``extrapolated``, ``mesh_ladder``, ``fallbacks``
        (count and total, :meth:`fallbacks`) and details."""
        fallen, total = self.fallbacks()
        return {
            "fallbacks": {"count": fallen, "of": total},
            "error_estimate": {k: e.error for k, e in self.scalars.items()},
            "extrapolated": {k: e.extrapolated for k, e in self.scalars.items()},
            "estimate_details": {k: e.to_dict() for k, e in self.scalars.items()},
            "step_error_estimate": [{k: e.error for k, e in step.items()} for step in self.steps],
            "worst_step": self.worst_step(),
            "mesh_ladder": [
                {"refine": r, "dofs": d, "seconds": s, "cpu_seconds": c}
                for r, d, s, c in zip(
                    self.refines, self.dofs, self.seconds, self.cpu_seconds, strict=True
                )
            ],
        }


def _worst(steps: Sequence[dict[str, Estimate]], key: str) -> int:
    return int(np.argmax([step[key].error for step in steps]))


def reported_values(outcome: LevelOutcome) -> dict[str, float]:
    """The scalars an outcome reports that get an estimate, by the keys of
    :attr:`FiniteEstimates.scalars` (``force_ratio_worst`` aside)."""
    finite, fem = outcome.impacts["finite_strain"], outcome.impacts["linear_fem"]
    at = outcome.at_maximum()
    return {
        **{key: finite[key] for key in IMPACT_KEYS},
        **{f"{key}_vs_fem": finite[key] / fem[key] for key in IMPACT_KEYS},
        **{f"{key}_at_x_c": at[key] for key in AT_X_C},
    }


def _departure_error(entry: dict, ratio: np.ndarray, error: np.ndarray) -> float:
    """Largest estimated error of the departure at the depths deciding ``entry``."""
    if entry["status"] == "below":
        return float(error[0])
    if entry["status"] == "beyond":
        return float(error.max())
    k = int(np.clip(np.searchsorted(ratio, entry["depth_to_radius"]), 1, ratio.size - 1))
    return float(max(error[k - 1], error[k]))


def _crossing(index: int, levels: list[list[dict]], moved: list[list[dict]], ratio: float) -> dict:
    """Relative errors of crossing ``index``: Richardson over the trailing levels with the
    finest's status, or the move of the finest's crossing, whichever is larger."""
    finest = levels[-1][index]
    trailing = itertools.takewhile(lambda v: v[index]["status"] == finest["status"], levels[::-1])
    same = [v[index] for v in trailing][::-1]
    errors = {}
    for key in CROSSING_KEYS:
        shift = max(abs(m[index][key] / finest[key] - 1.0) for m in moved)
        ladder = richardson([v[key] for v in same], ratio).error if len(same) > 1 else 0.0
        errors[key] = max(shift, ladder)
    return errors


def _crossings(
    outcomes: Sequence[LevelOutcome], steps: tuple[dict[str, Estimate], ...], spacing: float
) -> tuple[dict[str, object], ...]:
    """``errors`` and ``departure_error`` of each 1 % / 5 % crossing of the finest outcome."""
    finest = outcomes[-1]
    rows = finest.rows()
    error = np.array(  # absolute error of the departure |P/P_linFEM - 1| per depth
        [
            abs(row["force_ratio_fem"]) * step["force_ratio_fem"].error
            for row, step in zip(rows, steps, strict=True)
        ]
    )
    ratio = np.array([row["depth_to_radius"] for row in rows])
    levels = [outcome.validity() for outcome in outcomes]
    moved = [finest.validity(error), finest.validity(-error)]
    return tuple(
        {
            "errors": _crossing(i, levels, moved, spacing),
            "departure_error": _departure_error(entry, ratio, error),
        }
        for i, entry in enumerate(levels[-1])
    )


def edge_richardson(values: Sequence[float], ratio: float) -> Estimate:
    """Richardson with the contact edge's order :data:`EDGE_ORDER`, where the differences
    shrink monotonically at an observed order in :data:`EDGE_BAND` (else the two-level
    fall-back). With the observed order above 1 the first-order correction |d2| / (s - 1)
    is the larger, conservative one."""
    return richardson(values, ratio, order=EDGE_ORDER, sane=EDGE_BAND)


def _edge_estimates(
    values: list[dict[str, float]],
    rows: list[list[dict[str, float]]],
    scalars: dict[str, Estimate],
    steps: tuple[dict[str, Estimate], ...],
    ratio: float,
) -> None:
    """Replace, in place, the estimates of the edge-driven numbers by :func:`edge_richardson`:
    :data:`EDGE_KEYS` per depth and at x_c, and the impact's a_c."""
    for k, step in enumerate(steps):
        for key in EDGE_KEYS:
            step[key] = edge_richardson([r[k][key] for r in rows], ratio)
    for key in [*(f"{k}_at_x_c" for k in EDGE_KEYS), "a_c"]:
        scalars[key] = edge_richardson([v[key] for v in values], ratio)


def _envelope_estimates(
    rows: list[list[dict[str, float]]],
    steps: tuple[dict[str, Estimate], ...],
    ratio: float,
    edge_order: bool,
) -> None:
    """Replace, in place, every per-depth estimate by the larger of its own and its
    neighbourhood's (:func:`~shtaerman.study.richardson.envelope`, the depth and one on each
    side, orders in :data:`EDGE_BAND`; the edge's numbers at :data:`EDGE_ORDER` with
    ``edge_order``)."""
    for key in STEP_KEYS:
        curves = [[row[key] for row in level] for level in rows]
        order = EDGE_ORDER if edge_order and key in EDGE_KEYS else None
        for k, step in enumerate(steps):
            step[key] = envelope(step[key], curves, k, ratio, order=order, sane=EDGE_BAND)


def _ratio_steps(rows: list[list[dict[str, float]]], ratio: float) -> list[Estimate]:
    """P/P_linear-FEM per depth, propagated from the two forces' own estimates."""
    return [
        propagated(
            rows[-1][k]["force_ratio_fem"],
            [
                (richardson([r[k]["force"] for r in rows], ratio), 1.0),
                (richardson([r[k]["force_linear_fem"] for r in rows], ratio), -1.0),
            ],
        )
        for k in range(len(rows[-1]))
    ]


def _at_x_c(
    rows: list[dict[str, float]], steps: Sequence[Estimate], x_c: float, x_c_estimate: Estimate
) -> Estimate:
    """A per-depth quantity at x_c, log-log interpolated between the depths bracketing x_c
    (weights 1 - t and t), propagated from the two depths' estimates and from x_c's, whose
    error moves the value by its log-log slope there."""
    depth = np.log([row["depth"] for row in rows])
    values = np.array([step.value for step in steps])
    if depth.size == 1:
        return propagated(float(values[0]), [(steps[0], 1.0)])
    k = int(np.clip(np.searchsorted(depth, math.log(x_c)), 1, depth.size - 1))
    t = float(np.clip((math.log(x_c) - depth[k - 1]) / (depth[k] - depth[k - 1]), 0.0, 1.0))
    slope = math.log(values[k] / values[k - 1]) / (depth[k] - depth[k - 1])
    value = float(np.interp(math.log(x_c), depth, values))
    return propagated(value, [(steps[k - 1], 1.0 - t), (steps[k], t), (x_c_estimate, slope)])


def _propagate_ratios(
    outcomes: Sequence[LevelOutcome],
    scalars: dict[str, Estimate],
    steps: tuple[dict[str, Estimate], ...],
    ratio: float,
    edge_order: bool,
) -> None:
    """Replace, in place, the estimates of the ratios of two separately computed quantities
    by propagation from the factors' own estimates: P/P_linear-FEM per depth and at x_c,
    and the finite-strain impact maxima / the linear-FEM impact's (the linear-FEM a_c by
    :func:`edge_richardson` with ``edge_order``); where a factor fell back, the ratio keeps
    its own estimate."""
    rows = [outcome.rows() for outcome in outcomes]
    for step, bound in zip(steps, _ratio_steps(rows, ratio), strict=True):
        step["force_ratio_fem"] = _preferred(step["force_ratio_fem"], bound)
    fem = [outcome.impacts["linear_fem"] for outcome in outcomes]
    for key in IMPACT_KEYS:
        rule = edge_richardson if edge_order and key == "a_c" else richardson
        factor = rule([f[key] for f in fem], ratio)
        direct = scalars[f"{key}_vs_fem"]
        bound = propagated(direct.value, [(scalars[key], 1.0), (factor, -1.0)])
        scalars[f"{key}_vs_fem"] = _preferred(direct, bound)
    x_c = outcomes[-1].impacts["finite_strain"]["x_c"]
    ratios = [step["force_ratio_fem"] for step in steps]
    bound = _at_x_c(rows[-1], ratios, x_c, scalars["x_c"])
    scalars["force_ratio_fem_at_x_c"] = _preferred(scalars["force_ratio_fem_at_x_c"], bound)


def _preferred(direct: Estimate, bound: Estimate) -> Estimate:
    """The propagated bound where every factor was estimated, else the ratio's own estimate
    (a bound summing the factors' fall-backs ignores that same-mesh errors cancel)."""
    return bound if bound.method == "propagated" else direct


def estimate_study(
    outcomes: Sequence[LevelOutcome],
    refines: Sequence[float],
    ratio: float = LADDER_RATIO,
    *,
    propagate: bool = False,
    edge_order: bool = False,
    envelopes: bool = False,
) -> FiniteEstimates:
    """Estimates of the last (finest) of three study outcomes on one mesh ladder.

    Parameters
    ----------
    outcomes : sequence of LevelOutcome
        The study on the ladder's meshes, coarse to fine (same depths), without estimates.
    refines : sequence of float
        Their refinement factors (consecutive ratio ``ratio``).
    ratio : float
        Element-size ratio of consecutive levels (> 1): 2 on the nested ladder,
        sqrt(2) on independent gmsh levels.
    propagate : bool
        Estimate the ratios of two separately computed quantities (P/P_linear-FEM per depth
        and at x_c, the impact maxima against the linear-FEM impact's) by propagating their
        factors' own estimates (:func:`~shtaerman.study.richardson.propagated`), not by
        Richardson on the ratio, whose factors' errors cancel and change sign.
    edge_order : bool
        Estimate the contact radius' numbers (:data:`EDGE_KEYS` per depth and at x_c, the
        impact's a_c) with the edge's first order (:func:`edge_richardson`); ``propagate``
        then carries a_c's estimate into a_c against the linear FEM's.
    envelopes : bool
        Give every per-depth number the larger of its own estimate and its neighbourhood's
        (:func:`_envelope_estimates`): the contact edge's error oscillates from depth to
        depth and level to level, and a depth's own differences may cross zero by chance.

    Returns
    -------
    FiniteEstimates
    """
    values = [reported_values(outcome) for outcome in outcomes]
    scalars = {key: richardson([v[key] for v in values], ratio) for key in values[-1]}
    rows = [outcome.rows() for outcome in outcomes]
    steps = tuple(
        {key: richardson([r[k][key] for r in rows], ratio) for key in STEP_KEYS}
        for k in range(len(rows[-1]))
    )
    if edge_order:
        _edge_estimates(values, rows, scalars, steps, ratio)
    if envelopes:
        _envelope_estimates(rows, steps, ratio, edge_order)
    if propagate:
        _propagate_ratios(outcomes, scalars, steps, ratio, edge_order)
    scalars["force_ratio_worst"] = steps[_worst(steps, "force_ratio")]["force_ratio"]
    return FiniteEstimates(
        refines=tuple(refines),
        dofs=tuple(int(o.finite.curve.mesh_stats["dofs"]) for o in outcomes),
        seconds=tuple(o.seconds for o in outcomes),
        cpu_seconds=tuple(o.cpu_seconds for o in outcomes),
        scalars=scalars,
        steps=steps,
        crossings=_crossings(outcomes, steps, ratio),
        ratio=ratio,
    )
