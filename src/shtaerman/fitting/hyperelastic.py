"""The indentation fit of a rubber at finite strain: E2 and the Mooney ratio from FE curves.

E2 scales out of a rubber's FE contact curve exactly: at a fixed nu2 and a fixed shape of the
strain energy (Mooney ratio r, Yeoh c2 and c3, Gent Jm) every constant of W is proportional
to E2, so P(x; E2, r) = E2 p(x; r) (measured: 4e-12 between E2 and 2 E2). One FE curve at the
data's depths then gives p for a known shape, and E2 is fitted exactly (P is linear in it).

The Mooney ratio r changes p: it is fitted on p tabulated at a few r (:data:`RATIO_NODES`,
quadratic interpolation through the three nodes nearest r), with one FE curve added at each
fitted r until r settles (the fitted r is then a node: the model there is the FE curve
itself). A fit so costs a handful of FE runs.

The FE curves' own force error estimate e enters the intervals: E2's by e (P = E2 p), r's
by e / c of r's range, c the largest change of the curve's shape (E2 refitted: a change of r
mostly rescales the curve like E2) that r makes over its range. r is not identifiable when
its interval so widened spans that whole range. E2 moves with r, so E2's interval spans its
fits with r held at each end of r's interval (the whole range when r is not identifiable).
"""

from __future__ import annotations

import dataclasses
from collections.abc import Sequence
from dataclasses import dataclass, field

import numpy as np

from ..problem import Loading, Problem
from ..theory.materials import Material
from ..validation import InputError
from .data import Measurement
from .engine import Progress, Solution, solve
from .iteration import widened
from .models import Model, Parameter

__all__ = ["RATIO_NODES", "FECurves", "finite_indentation_fit"]

RATIO_NODES = (0.0, 0.45, 0.9)
"""The Mooney ratios of the first FE curves; r is sought within their span."""
E_REF = 1e6
"""E2 in Pa of the FE curves (scaled out)."""
SETTLE = 0.1
"""The outer iteration stops when the fitted r lies within this of its half-interval (or
1e-6) of an FE node."""
MAX_RUNS = 10
"""Most FE curves of one fit."""


@dataclass
class FECurves:
    """FE curves P/E2 in N/Pa at the data's depths, by Mooney ratio, and their errors."""

    problem: Problem
    depths: np.ndarray
    refine: float
    progress: Progress | None = None
    table: dict[float, np.ndarray] = field(default_factory=dict)
    errors: list[float] = field(default_factory=list)
    """Each FE curve's estimated relative force error."""

    def add(self, ratio: float) -> None:
        """Run the FE curve at Mooney ratio ``ratio`` (None: the problem's own shape)."""
        from ..api.fem_contact import contact

        body = self.problem.body
        shape = {"mooney_ratio": ratio} if body.model == "mooney-rivlin" else {}
        material = Material(E_REF, body.material.poisson_ratio)
        case = dataclasses.replace(
            self.problem,
            striker=dataclasses.replace(self.problem.striker, mass=None, velocity=None),
            body=dataclasses.replace(body, material=material, prony=None, **shape),
            loading=Loading("curve", tuple(float(x) for x in self.depths)),
        )
        if self.progress is not None:
            self.progress(f"fit: FE contact curve {len(self.table) + 1} ({body.model}"
                          + (f", mooney_ratio {ratio:.6g})" if shape else ")"))  # fmt: skip
        run = contact(case, refine=self.refine, estimate=True)
        self.table[ratio] = np.asarray(run.force, dtype=float) / E_REF
        error = (run.error_estimate or {}).get("force")
        self.errors.append(float(error) if error is not None else 0.0)

    def shape(self, ratio: float) -> np.ndarray:
        """p(x; r) in N/Pa: the quadratic through the (up to) three nodes nearest ``ratio``."""
        nodes = sorted(self.table, key=lambda r: abs(r - ratio))[:3]
        out = np.zeros_like(self.depths)
        for i, a in enumerate(nodes):
            weight = np.prod([(ratio - b) / (a - b) for j, b in enumerate(nodes) if j != i])
            out += weight * self.table[a]
        return out

    @property
    def error(self) -> float:
        """The largest estimated relative force error of the FE curves."""
        return max(self.errors, default=0.0)


def _model(curves: FECurves, measured: Measurement, names: Sequence[str],
           ratio: float | None) -> Model:  # fmt: skip
    """E2 (log) and, when fitted, the Mooney ratio within :data:`RATIO_NODES`."""
    force = measured.columns["force"]
    if ratio is None:  # the problem's own shape: one FE curve, E2 linear
        ratio = next(iter(curves.table))
    start = float(np.sum(force * curves.shape(ratio)) / np.sum(curves.shape(ratio) ** 2))
    params = [Parameter("E2", start, start / 1e4, start * 1e4, True)]
    if "mooney_ratio" in names:
        params.append(Parameter("mooney_ratio", ratio, RATIO_NODES[0], RATIO_NODES[-1]))

    def predict(values: dict[str, float]) -> np.ndarray:
        return values["E2"] * curves.shape(values.get("mooney_ratio", ratio))

    return Model(tuple(params), force, predict, False, "N",
                 f"FE contact curves at finite strain ({curves.problem.body.model}); E2 "
                 "scaled out exactly")  # fmt: skip


def _check(problem: Problem, names: Sequence[str]) -> None:
    """Refuse unknowns the finite-strain indentation fit does not take."""
    if problem.body.prony is not None:
        raise InputError("prony: an indentation curve at finite strain is fitted elastic; "
                         "leave prony unset", "prony")  # fmt: skip
    allowed = ("E2", "mooney_ratio") if problem.body.model == "mooney-rivlin" else ("E2",)
    for name in names:
        if name not in allowed:
            raise InputError(
                f"fit: an indentation at finite strain ({problem.body.model}) cannot fit "
                f"{name!r}; choose from {', '.join(allowed)}",
                "fit",
            )


def finite_indentation_fit(problem: Problem, measured: Measurement, names: Sequence[str],
                           noise: float | None, refine: float,
                           progress: Progress | None = None,
                           ) -> tuple[Model, Solution, FECurves, str | None, dict]:  # fmt: skip
    """Fit E2 (and the Mooney ratio) of a rubber's indentation curve: the model, its
    solution (E2 over every r when r is not identifiable; the intervals widened by the FE
    error), the FE curves run, why r is not identifiable (None if it is, or not fitted) and
    the shifts the FE error made (``fe_force``, natural units).

    The outer iteration stops at once when r cannot be identifiable (its interval with the
    FE error spans its range): 3 FE curves then."""
    _check(problem, names)
    depths = measured.columns["depth"]
    if np.any(np.diff(depths) <= 0):
        raise InputError(f"{measured.source}: column 'depth' must increase for an FE curve "
                         "(fit the loading part only)", "data")  # fmt: skip
    curves = FECurves(problem, depths, refine, progress)
    if "mooney_ratio" not in names:
        curves.add(problem.body.mooney_ratio or 0.0)
        model = _model(curves, measured, names, None)
        sol = solve(model, noise)
        return model, widened(sol, _shifts(sol, curves)), curves, None, _shifts(sol, curves)
    for ratio in RATIO_NODES:
        curves.add(ratio)
    start = problem.body.mooney_ratio or 0.0
    while True:
        model = _model(curves, measured, names, start)
        sol = solve(model, noise)
        change, floor = _shape_change(model, sol, curves)
        shifts = _shifts(sol, curves, change)
        wide = widened(sol, shifts)
        low, high = (
            np.maximum(wide.low, [0.0, RATIO_NODES[0]]),
            np.minimum(wide.high, [np.inf, RATIO_NODES[-1]]),
        )
        wide = dataclasses.replace(wide, low=low, high=high)
        seen = wide.identifiable[1] and (wide.low[1] > RATIO_NODES[0]
                                         or wide.high[1] < RATIO_NODES[-1])  # fmt: skip
        ratio, half = float(sol.values[1]), float(wide.high[1] - wide.low[1]) / 2
        near = min(abs(ratio - r) for r in curves.table)
        if not seen or near <= max(SETTLE * half, 1e-6) or len(curves.table) >= MAX_RUNS:
            break
        curves.add(ratio)  # an FE curve at the fitted r: the model there is the FE itself
        start = ratio
    reason = None
    if seen:
        ends = (float(wide.low[1]), float(wide.high[1]))
    else:
        ends = (RATIO_NODES[0], RATIO_NODES[-1])
        reason = (f"over mooney_ratio {ends[0]:g}-{ends[1]:g} the curve's shape (E2 refitted) "
                  f"changes by at most {change:.2g} of the largest force, against noise and FE "
                  f"error {floor:.2g}: indent deeper, refine the FE curves, or give "
                  "mooney_ratio")  # fmt: skip
    final = widened(
        _e2_over(model, noise, sol, ends, seen), {"fe_force": shifts["fe_force"] * [1, 0]}
    )
    return model, final, curves, reason, shifts


def _e2_over(model: Model, noise: float | None, sol: Solution, ends: tuple[float, float],
             seen: bool) -> Solution:  # fmt: skip
    """``sol`` with the Mooney ratio's interval ``ends`` (identifiable if ``seen``) and E2's
    interval spanning E2's fits with r held at each end: E2 moves with r (a change of r
    mostly rescales the curve), so E2 is no better known than r."""
    fits = [solve(model, noise, hold={"mooney_ratio": r}) for r in ends]
    low = np.array([min(sol.low[0], *(f.low[0] for f in fits)), ends[0]])
    high = np.array([max(sol.high[0], *(f.high[0] for f in fits)), ends[1]])
    return dataclasses.replace(sol, low=low, high=high, identifiable=np.array([True, seen]))


def _shifts(sol: Solution, curves: FECurves, change: float | None = None) -> dict:
    """The shifts of E2 (and r) by the FE curves' force error e: e E2 (P = E2 p); for r,
    e / ``change`` of its range (linearised: the shape moves by ``change`` over the range)."""
    shift = np.zeros_like(sol.values)
    shift[0] = curves.error * sol.values[0]
    if change is not None:
        shift[1] = (RATIO_NODES[-1] - RATIO_NODES[0]) * curves.error / max(change, 1e-300)
    return {"fe_force": shift}


def _shape_change(model: Model, sol: Solution, curves: FECurves) -> tuple[float, float]:
    """(the largest change of the curve's shape over r in :data:`RATIO_NODES`, E2 refitted
    to each end; the noise and the FE error estimate combined), both relative to the
    largest force. Linearised, an error e of the shape moves r by e / change of its span."""
    force = model.observed
    top = float(np.max(np.abs(force)))
    ends = []
    for ratio in RATIO_NODES[:: len(RATIO_NODES) - 1]:
        shape = curves.shape(ratio)
        ends.append(shape * np.sum(force * shape) / np.sum(shape * shape))
    change = float(np.max(np.abs(ends[1] - ends[0]))) / top
    return change, float(np.hypot(sol.noise / top, curves.error))
