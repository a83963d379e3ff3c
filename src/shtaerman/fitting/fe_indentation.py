"""The indentation fit by FE contact curves (a rubber at finite strain, a pad): E2 and one
shape constant.

E2 scales out of the FE curve exactly, P(x; E2, s) = E2 p(x; s); the shape constant s
(:func:`shape_axes`) is fitted on p interpolated between FE curves (:meth:`FECurves.shape`),
and the FE curves' error widens both intervals (docs/fit.md, "A rubber at finite strain or a
pad: an indentation curve by FE curves").
"""

from __future__ import annotations

import dataclasses
import math
from collections.abc import Callable, Sequence
from dataclasses import dataclass, field
from typing import Any

import numpy as np
from scipy.interpolate import CubicSpline

from ..problem import Body, Loading, Problem
from ..theory.materials import RIGID, Material
from ..validation import InputError, NumericalFailureError
from .corrections import check_rigid_striker, fe_parts
from .data import Measurement
from .engine import Progress, Solution, solve
from .iteration import widened
from .models import Model, Parameter

__all__ = [
    "POISSON_AXIS",
    "SHAPE_AXES",
    "FECurves",
    "ShapeAxis",
    "finite_indentation_fit",
    "shape_axes",
    "shape_axis",
]

E_REF = 1e6
"""E2 in Pa of the FE curves (scaled out)."""
SETTLE = 0.1
"""The outer iteration stops when the fitted s lies within this of its half-interval (or
1e-6 of its range) of an FE node."""
MAX_RUNS = 10
"""Most FE curves of one fit."""


@dataclass(frozen=True)
class ShapeAxis:
    """One shape constant of a rubber model that an indentation fit can seek.

    ``low``/``high`` bound it (natural units); the FE curves are interpolated in
    ``coordinate(s)`` (s itself, or 1/Jm where the energy depends on 1/Jm); ``fields(s,
    body)`` gives the :class:`~shtaerman.problem.Body` fields of a curve at s."""

    name: str
    low: float
    high: float
    fields: Callable[[float, Body], dict]
    coordinate: Callable[[float], float] = float
    log: bool = False

    @property
    def nodes(self) -> tuple[float, float, float]:
        """The three values of the first FE curves: the ends and the middle (in the
        interpolation coordinate)."""
        ends = self.coordinate(self.low), self.coordinate(self.high)
        middle = (ends[0] + ends[1]) / 2
        return self.low, self.from_coordinate(middle), self.high

    def from_coordinate(self, value: float) -> float:
        """The constant whose coordinate is ``value``."""
        return 1.0 / value if self.coordinate is _inverse else value

    def start(self, body: Body) -> float:
        """The body's own value of the constant, within the bounds."""
        value = {"mooney_ratio": body.mooney_ratio, "gent_limit": body.gent_limit,
                 "nu2": body.material.poisson_ratio}.get(self.name)  # fmt: skip
        if self.name == "yeoh_c2":
            value = body.rubber().yeoh[0]
        return float(min(max(value if value is not None else self.low, self.low), self.high))


def _inverse(value: float) -> float:
    return 1.0 / value


def _yeoh_axis(body: Body) -> ShapeAxis:
    """Yeoh's c2 = C20/C10 with c3 held: from the least c3 allows (c2^2 < 3 c3) to 1."""
    c3 = body.rubber().yeoh[1]
    low = -0.99 * math.sqrt(3.0 * c3) if c3 > 0.0 else 0.0
    return ShapeAxis("yeoh_c2", low, 1.0, lambda s, b: {"yeoh": (s, b.rubber().yeoh[1])})


SHAPE_AXES: dict[str, Callable[[Body], ShapeAxis]] = {
    "mooney-rivlin": lambda body: ShapeAxis(
        "mooney_ratio", 0.0, 0.9, lambda s, b: {"mooney_ratio": s}
    ),
    "yeoh": _yeoh_axis,
    "gent": lambda body: ShapeAxis(
        "gent_limit", 10.0, 1000.0, lambda s, b: {"gent_limit": s}, _inverse, log=True
    ),
}
"""Model -> the shape constant its indentation fit seeks (the Mooney ratio over [0, 0.9];
Yeoh's c2 over [-0.99 sqrt(3 c3), 1] with c3 held; Gent's Jm over [10, 1000], interpolated
in 1/Jm)."""


POISSON_AXIS = ShapeAxis("nu2", 0.0, 0.5, lambda s, b: {"material": Material(E_REF, s)})
"""nu2 over [0, 0.5] on a bonded pad: its curve's shape depends on nu2 (a thin one stiffens
steeply as nu2 -> 0.5), where a half-space's and a lubricated pad's depend on E* alone."""


def shape_axis(body: Body) -> ShapeAxis | None:
    """The shape constant of ``body``'s model, or None (neo-Hookean: no shape constant)."""
    make = SHAPE_AXES.get(body.model)
    return None if make is None else make(body)


def shape_axes(problem: Problem) -> dict[str, ShapeAxis]:
    """Name -> the shape constants an indentation fit of ``problem`` can seek (one at a
    time): its rubber model's, and nu2 on a bonded pad."""
    axes = [shape_axis(problem.body)]
    if problem.geometry.thickness is not None and problem.geometry.base == "bonded":
        axes.append(POISSON_AXIS)
    return {axis.name: axis for axis in axes if axis is not None}


@dataclass
class FECurves:
    """FE curves P/E2 in N/Pa at the data's depths, by value of the shape constant, and their
    errors."""

    problem: Problem
    depths: np.ndarray
    refine: float
    progress: Progress | None = None
    axis: ShapeAxis | None = None
    table: dict[float, np.ndarray] = field(default_factory=dict)
    errors: list[float] = field(default_factory=list)
    """Each FE curve's estimated relative force error."""
    _spline: tuple[int, CubicSpline] | None = field(default=None, repr=False)
    """The spline of :meth:`shape` and the number of curves it was built on."""

    def add(self, value: float | None) -> None:
        """Run the FE curve at shape constant ``value`` (None: the problem's own shape)."""
        from ..api.fem_contact import contact

        body = self.problem.body
        fields = {"material": Material(E_REF, body.material.poisson_ratio), "prony": None}
        fields |= {} if value is None else self.axis.fields(value, body)
        case = dataclasses.replace(
            self.problem,
            striker=dataclasses.replace(  # the FE striker is rigid (so are its numbers)
                self.problem.striker, mass=None, velocity=None, material=RIGID
            ),
            body=dataclasses.replace(body, **fields),
            loading=Loading("curve", tuple(float(x) for x in self.depths)),
        )
        if self.progress is not None:
            where = "" if value is None else f", {self.axis.name} {value:.6g}"
            self.progress(f"fit: FE contact curve {len(self.table) + 1} ({fe_parts(case)}{where})")
        run = self._run(contact, case, value)
        self.table[0.0 if value is None else value] = np.asarray(run.force, float) / E_REF
        error = (run.error_estimate or {}).get("force")
        self.errors.append(float(error) if error is not None else 0.0)

    def _run(self, contact: Callable, case: Problem, value: float | None) -> Any:
        """The FE curve of ``case``; one that fails at a shape constant the fit chose (not
        the user's input) is a numerical failure naming it and what to change."""
        from ..fem.hyperelastic import NewtonError

        try:
            return contact(case, refine=self.refine, estimate=True)
        except NewtonError as error:
            if value is None:
                raise
            axis = self.axis
            raise NumericalFailureError(
                f"fit: the FE contact curve at {axis.name} = {value:.6g}, where the fit sought "
                f"it (over [{axis.low:.6g}, {axis.high:.6g}]), failed: {error}; give "
                f"{axis.name} and fit E2 alone, or fit shallower depths"
            ) from None

    def shape(self, value: float) -> np.ndarray:
        """p(x; s) in N/Pa: the not-a-knot cubic spline (in the axis' coordinate) through
        every FE curve's value at each depth; through three, their quadratic."""
        if self.axis is None:
            return next(iter(self.table.values()))
        if self._spline is None or self._spline[0] != len(self.table):  # built once per curve
            nodes = sorted(self.table, key=self.axis.coordinate)
            u = np.array([self.axis.coordinate(r) for r in nodes])
            curves = np.array([self.table[r] for r in nodes])
            spline = CubicSpline(u, curves, axis=0, bc_type="not-a-knot")
            self._spline = (len(self.table), spline)
        return self._spline[1](self.axis.coordinate(value))

    @property
    def error(self) -> float:
        """The largest estimated relative force error of the FE curves."""
        return max(self.errors, default=0.0)


def _model(curves: FECurves, measured: Measurement, value: float | None) -> Model:
    """E2 (log) and, when fitted (``value`` its start), the shape constant within its
    bounds."""
    force = measured.columns["force"]
    axis = curves.axis
    p0 = curves.shape(value if value is not None else 0.0)
    start = float(np.sum(force * p0) / np.sum(p0**2))
    params = [Parameter("E2", start, start / 1e4, start * 1e4, True)]
    if value is not None:
        params.append(Parameter(axis.name, value, axis.low, axis.high, axis.log))

    def predict(values: dict[str, float]) -> np.ndarray:
        return values["E2"] * curves.shape(values.get(axis.name, 0.0) if axis else 0.0)

    return Model(tuple(params), force, predict, False, "N",
                 f"FE contact curves: {fe_parts(curves.problem)}; E2 scaled out "
                 "exactly")  # fmt: skip


def _check(problem: Problem, names: Sequence[str]) -> ShapeAxis | None:
    """The shape constant sought (None: E2 alone); refuses unknowns the FE-curve
    indentation fit does not take."""
    if problem.body.prony is not None:
        raise InputError("prony: an indentation curve by FE curves is fitted elastic; "
                         "leave prony unset", "prony")  # fmt: skip
    axes = shape_axes(problem)
    allowed = ("E2", *axes)
    if "nu2" in names and "nu2" not in axes and problem.geometry.thickness is not None:
        raise InputError("unknowns: nu2 is not identifiable from a lubricated pad's curve: like a "
                         "half-space's it depends on E2 / (1 - nu2^2) alone; give nu2 and fit "
                         "E2", "unknowns")  # fmt: skip
    for name in names:
        if name not in allowed:
            raise InputError(
                f"unknowns: an indentation with {fe_parts(problem)} cannot fit "
                f"{name!r}; choose from {', '.join(allowed)}",
                "unknowns",
            )
    sought = [axes[name] for name in names if name in axes]
    if len(sought) > 1:
        got = ", ".join(axis.name for axis in sought)
        raise InputError(f"unknowns: one shape constant per fit, got {got}; give the others",
                         "unknowns")  # fmt: skip
    return sought[0] if sought else None


def _check_striker(curves: FECurves, measured: Measurement) -> None:
    """:func:`.corrections.check_rigid_striker` at the E2 the first FE curve gives."""
    shape = next(iter(curves.table.values()))
    force = measured.columns["force"]
    young = float(np.sum(force * shape) / np.sum(shape**2))
    problem = curves.problem
    check_rigid_striker(problem.striker.material, problem.body.material.poisson_ratio, young,
                        curves.error, "contact curves")  # fmt: skip


def finite_indentation_fit(problem: Problem, measured: Measurement, names: Sequence[str],
                           noise: float | None, refine: float,
                           progress: Progress | None = None,
                           ) -> tuple[Model, Solution, FECurves, str | None, dict]:  # fmt: skip
    """Fit E2 (and one shape constant, :func:`shape_axes`) of an indentation curve by FE:
    the model, its solution (E2 over the constant's whole range when that is not
    identifiable; the intervals widened by the FE error), the FE curves run, why the constant
    is not identifiable (None if it is, or not fitted) and the shifts the FE error made
    (``fe_force``, natural units).

    The outer iteration stops at once when the constant cannot be identifiable (its
    interval with the FE error spans its range): 3 FE curves then."""
    axis = _check(problem, names)
    depths = measured.columns["depth"]
    if np.any(np.diff(depths) <= 0):
        raise InputError(f"{measured.source}: column 'depth' must increase for an FE curve "
                         "(fit the loading part only)", "data")  # fmt: skip
    curves = FECurves(problem, depths, refine, progress, axis)
    if axis is None:
        curves.add(None)
        _check_striker(curves, measured)
        model = _model(curves, measured, None)
        sol = solve(model, noise)
        shifts = _shifts(sol, curves)
        return model, widened(sol, shifts), curves, None, shifts
    for value in axis.nodes:
        curves.add(value)
    _check_striker(curves, measured)
    model, sol, wide, shifts, floor, change = _settled(curves, measured, noise, axis)
    seen = _seen(wide, axis)
    reason = None
    ends = (float(wide.low[1]), float(wide.high[1])) if seen else (axis.low, axis.high)
    if not seen:
        reason = (f"over {axis.name} {ends[0]:g}-{ends[1]:g} the curve's shape (E2 refitted) "
                  f"changes by at most {change:.2g} of the largest force, against noise and FE "
                  f"error {floor:.2g}: indent deeper, refine the FE curves, or give "
                  f"{axis.name}")  # fmt: skip
    final = widened(
        _e2_over(model, noise, sol, ends, seen, axis.name),
        {"fe_force": shifts["fe_force"] * [1, 0]},
    )
    return model, final, curves, reason, shifts


def _seen(wide: Solution, axis: ShapeAxis) -> bool:
    """Whether the widened interval of the shape constant is narrower than its range."""
    return bool(wide.identifiable[1] and (wide.low[1] > axis.low or wide.high[1] < axis.high))


def _settled(curves: FECurves, measured: Measurement, noise: float | None, axis: ShapeAxis,
             ) -> tuple[Model, Solution, Solution, dict, float, float]:  # fmt: skip
    """Fit, and add an FE curve at the fitted constant until it lies near a node (or cannot
    be identifiable, or :data:`MAX_RUNS`): the model, the solution, the widened one (clipped
    to the bounds), the FE shifts, the noise-and-FE floor and the shape change."""
    start = axis.start(curves.problem.body)
    while True:
        model, sol = _best_fit(curves, measured, noise, start)
        change = _shape_change(model, curves)
        shifts = _shifts(sol, curves, change)
        wide = widened(sol, shifts)
        low = np.maximum(wide.low, [0.0, axis.low])
        high = np.minimum(wide.high, [np.inf, axis.high])
        wide = dataclasses.replace(wide, low=low, high=high)
        floor = float(np.hypot(sol.noise / np.max(np.abs(model.observed)), curves.error))
        value, half = float(sol.values[1]), float(wide.high[1] - wide.low[1]) / 2
        near = min(abs(value - r) for r in curves.table)
        settled = near <= max(SETTLE * half, 1e-6 * (axis.high - axis.low))
        if not _seen(wide, axis) or settled or len(curves.table) >= MAX_RUNS:
            return model, sol, wide, shifts, floor, change
        curves.add(value)  # an FE curve at the fitted s: the model there is the FE itself
        start = value


def _best_fit(curves: FECurves, measured: Measurement, noise: float | None,
              start: float) -> tuple[Model, Solution]:  # fmt: skip
    """The least-squares fit from ``start`` and from every FE curve's value of the shape
    constant, the one of the smallest residual: the interpolated model can have a local
    minimum at a node."""
    fits = []
    for value in dict.fromkeys((start, *curves.table)):
        model = _model(curves, measured, value)
        fits.append((model, solve(model, noise)))
    return min(fits, key=lambda fit: float(np.sum(fit[1].residual ** 2)))


def _e2_over(model: Model, noise: float | None, sol: Solution, ends: tuple[float, float],
             seen: bool, name: str) -> Solution:  # fmt: skip
    """``sol`` with the shape constant's interval ``ends`` (identifiable if ``seen``) and
    E2's interval spanning E2's fits with the constant held at each end: E2 moves with it (a
    change of shape mostly rescales the curve), so E2 is no better known than the shape."""
    fits = [solve(model, noise, hold={name: r}) for r in ends]
    low = np.array([min(sol.low[0], *(f.low[0] for f in fits)), ends[0]])
    high = np.array([max(sol.high[0], *(f.high[0] for f in fits)), ends[1]])
    return dataclasses.replace(sol, low=low, high=high, identifiable=np.array([True, seen]))


def _shifts(sol: Solution, curves: FECurves, change: float | None = None) -> dict:
    """The shifts of E2 (and s) by the FE curves' force error e: e E2 (P = E2 p); for s,
    e / ``change`` of its range (linearised: the shape moves by ``change`` over the range)."""
    shift = np.zeros_like(sol.values)
    shift[0] = curves.error * sol.values[0]
    if change is not None:
        shift[1] = (curves.axis.high - curves.axis.low) * curves.error / max(change, 1e-300)
    return {"fe_force": shift}


def _shape_change(model: Model, curves: FECurves) -> float:
    """The largest change of the curve's shape over the constant's range, E2 refitted to
    each end, relative to the largest force. Linearised, an error e of the shape moves s by
    e / change of its range."""
    force = model.observed
    top = float(np.max(np.abs(force)))
    ends = []
    for value in (curves.axis.low, curves.axis.high):
        shape = curves.shape(value)
        ends.append(shape * np.sum(force * shape) / np.sum(shape * shape))
    return float(np.max(np.abs(ends[1] - ends[0]))) / top
