"""Least squares on a forward model, with intervals from the Jacobian at the optimum.

:func:`scipy.optimize.least_squares` within the parameters' bounds, the covariance
s^2 (J^T J)^-1 at the optimum, and a parameter the data cannot determine reported with its
bounds as its interval, never with a small error bar: docs/fit.md, "How the fit decides".
"""

from __future__ import annotations

import itertools
from collections.abc import Callable
from dataclasses import dataclass

import numpy as np
from scipy.optimize import least_squares

from ..validation import InputError, NumericalFailureError
from .models import Model, Parameter

__all__ = ["CONFIDENCE", "RANK_TOLERANCE", "Progress", "Solution", "solve"]

Progress = Callable[[str], None]
"""Told a line of the fit's progress."""

CONFIDENCE = 0.95
RANK_TOLERANCE = 1e-9
"""A singular value of J below this fraction of the largest spans a null direction."""
MAX_EVALUATIONS = 60
"""Most evaluations of the forward model per fitted parameter (and one) in a search."""
PROGRESS_VALUES = 100_000
"""A model of at least this many values reports its progress (a long record)."""
PROGRESS_EVERY = 10
"""Evaluations of the forward model between two progress lines."""
NULL_COMPONENT = 1e-6
"""A parameter whose component along a null direction exceeds this is not identifiable."""


@dataclass(frozen=True)
class Solution:
    """The optimum, its intervals and the residual (natural units)."""

    values: np.ndarray
    low: np.ndarray
    high: np.ndarray
    identifiable: np.ndarray
    correlation: np.ndarray
    model: np.ndarray
    residual: np.ndarray
    """model - data, in the data's units."""
    noise: float
    """s, in the residual's units (relative for relative residuals)."""
    noise_estimated: bool
    evaluations: int


def _jacobian(function, x: np.ndarray, low: np.ndarray, high: np.ndarray) -> np.ndarray:
    """Central differences (one-sided at a bound), step 1e-6 of the parameter's range or of
    its log."""
    columns = []
    for j in range(x.size):
        step = 1e-6 * min(high[j] - low[j], 1.0)
        up, down = x.copy(), x.copy()
        up[j] = min(x[j] + step, high[j])
        down[j] = max(x[j] - step, low[j])
        columns.append((function(up) - function(down)) / (up[j] - down[j]))
    return np.column_stack(columns)


def _covariance(jac: np.ndarray, noise: float, traded: np.ndarray) -> np.ndarray:
    """s^2 (J^T J)^-1 by the SVD; infinite variance along the null directions and for the
    ``traded`` parameters (on a model's exact null direction, :func:`_traded`)."""
    _, sing, vt = np.linalg.svd(jac, full_matrices=False)
    kept = sing > RANK_TOLERANCE * sing[0] if sing.size and sing[0] > 0 else sing > np.inf
    cov = (vt[kept].T / sing[kept] ** 2) @ vt[kept] * noise**2
    null = traded.copy()
    if np.any(~kept):
        null |= np.max(np.abs(vt[~kept]), axis=0) > NULL_COMPONENT
    cov[null, :] = np.nan
    cov[:, null] = np.nan
    cov[null, null] = np.inf
    return cov


def _noise(
    residual: np.ndarray, count: int, noise: float | None, distinct: int
) -> tuple[float, float, bool]:
    """(s, quantile of the 95 % interval, whether s was estimated); ``distinct``: how many
    data values differ in value or in sensitivity (a row repeated verbatim tells the noise
    nothing: its residual is the first copy's)."""
    from scipy.stats import norm  # here, not at load: 0.6 s the command line's parser skips
    from scipy.stats import t as student

    if noise is not None:
        return float(noise), float(norm.ppf(0.5 + CONFIDENCE / 2)), False
    dof = residual.size - count
    if min(dof, distinct - count) < 1:
        repeated = f", {distinct} distinct," if distinct < residual.size else ""
        raise InputError(
            f"noise: {residual.size} data value(s){repeated} for {count} unknown(s) leave no "
            "residual to estimate the noise from; give noise (the measurement's standard "
            "deviation)",
            "noise",
        )
    s = float(np.sqrt(np.sum(residual**2) / dof))
    return s, float(student.ppf(0.5 + CONFIDENCE / 2, dof)), True


def _optimum(model: Model, noise: float | None, fixed: dict[str, float],
             progress: Progress | None = None) -> dict:  # fmt: skip
    """Least squares over the parameters not in ``fixed`` (natural values), and their
    intervals and identifiability at the optimum (fitting space); ``progress`` is told of
    every :data:`PROGRESS_EVERY` th evaluation of a model of at least :data:`PROGRESS_VALUES`
    values."""
    params = [p for p in model.parameters if p.name not in fixed]
    low = np.array([p.to_space(p.low) for p in params], dtype=float)
    high = np.array([p.to_space(p.high) for p in params], dtype=float)
    start = np.clip([p.to_space(p.start) for p in params], low, high)
    scale = np.abs(model.observed) if model.relative else np.ones_like(model.observed)

    def natural(x: np.ndarray) -> dict[str, float]:
        values = {p.name: float(p.from_space(v)) for p, v in zip(params, x, strict=True)}
        return {**fixed, **values}

    count = itertools.count(1)
    tell = progress if progress is not None and model.observed.size >= PROGRESS_VALUES else None

    def residual(x: np.ndarray) -> np.ndarray:
        r = (model.predict(natural(x)) - model.observed) / scale
        if (n := next(count)) % PROGRESS_EVERY == 0 and tell is not None:
            rms = float(np.sqrt(np.mean(r * r)))
            tell(f"fit: {n} evaluations of the forward model on {r.size} values, residual "
                 f"rms {rms:.4g} {model.unit}")  # fmt: skip
        return r

    found = least_squares(
        residual, start, bounds=(low, high), method="trf", x_scale="jac",
        xtol=1e-15, ftol=1e-15, gtol=1e-15, max_nfev=MAX_EVALUATIONS * (start.size + 1),
    )  # fmt: skip
    outside = _outside(params, natural(found.x))
    if found.status < 0 or (found.status == 0 and not np.any(outside)):  # 0: evaluations
        raise NumericalFailureError(f"the fit did not converge: {found.message}")
    jac = _jacobian(residual, found.x, low, high)
    left = residual(found.x)
    distinct = len(np.unique(np.column_stack([jac, left]), axis=0))
    s, quantile, estimated = _noise(left, start.size, noise, distinct)
    cov = _covariance(jac, s, _traded(model, params))
    half = quantile * np.sqrt(np.diag(cov))
    lo, hi = found.x - half, found.x + half
    reach = np.linalg.norm(jac, axis=0) * (high - low)
    seen = reach >= s if s > 0 else np.ones(start.size, dtype=bool)
    return {
        "params": params, "x": found.x, "low": np.clip(lo, low, high),
        "high": np.clip(hi, low, high), "bounds": (low, high), "cov": cov, "noise": s,
        "estimated": estimated, "values": natural(found.x),
        "identifiable": np.isfinite(half) & ~((lo <= low) & (hi >= high)) & seen & ~outside,
        "outside": outside, "evaluations": next(count) - 1,
    }  # fmt: skip


def _traded(model: Model, params: list[Parameter]) -> np.ndarray:
    """Which of the fitted ``params`` move along an exact null direction of ``model``
    (:attr:`Model.trades`) together with another fitted one: the data cannot tell them apart
    however exact they are (a Jacobian's rank test may see their singular value at 1e-8, above
    round-off, and give noise-free data a tight, wrong interval)."""
    names = [p.name for p in params]
    traded = np.zeros(len(names), dtype=bool)
    for direction in model.trades:
        moved = [j for j, name in enumerate(names) if name in direction]
        if len(moved) >= 2:
            traded[moved] = True
    return traded


def _outside(params: list[Parameter], values: dict[str, float]) -> np.ndarray:
    """Which parameters lie outside their window, or are tied to one that does."""
    windows = {p.name: p.window for p in params if p.window is not None}
    out = {name for name, (low, high) in windows.items() if not low <= values[name] <= high}
    out |= {name for p in params if p.name in out for name in p.tied}
    return np.array([p.name in out for p in params], dtype=bool)


def solve(model: Model, noise: float | None = None, hold: dict[str, float] | None = None,
          progress: Progress | None = None) -> Solution:  # fmt: skip
    """Fit ``model`` to its data; ``noise`` in the residual's unit, None: from the residual;
    ``hold``: parameters held (not identifiable) from the start, name -> natural value;
    ``progress``: told a line every few evaluations of a long record's model.

    A search that runs out of evaluations while a parameter lies outside its window (a
    relaxation time crawling along the unseen g_i / tau_i of a term slower than the record)
    has found that parameter not identifiable, not failed.

    The parameters found not identifiable are then held at their starting values (those
    outside their window at the values found: a relaxation time beyond the record stays
    there) and the others fitted again: their intervals are those of the data's information
    alone, not of a search that wandered along an unseen direction (a weight of a relaxation
    time outside the measured times, free to reach the bound sum g_i < 1 and so to take
    another weight with it). When none is identifiable, each is so held and reported there,
    with the model at those values, not where the search stopped.
    """
    fixed: dict[str, float] = dict(hold or {})
    found = _optimum(model, noise, fixed, progress)
    evaluations = found["evaluations"]
    while np.any(~found["identifiable"]):
        rows = zip(found["params"], found["identifiable"], found["outside"], strict=True)
        held = {p.name: found["values"][p.name] if out else p.start
                for p, ok, out in rows if not ok}  # fmt: skip
        fixed.update(held)
        if len(held) == len(found["params"]):  # none left to fit: the model at the held values
            found = _held_everywhere(model, noise, found, held)
            break
        found = _optimum(model, noise, fixed, progress)
        evaluations += found["evaluations"]
    return _solution(model, found, fixed, evaluations)


def _held_everywhere(model: Model, noise: float | None, found: dict, held: dict) -> dict:
    """``found`` with every parameter at its ``held`` value and, unless ``noise`` is given,
    the noise estimated from the residual there (the residual reported), not from the
    search's: nothing is fitted, so all the residual's degrees of freedom are left."""
    values = {**found["values"], **held}
    scale = np.abs(model.observed) if model.relative else 1.0
    left = (model.predict(values) - model.observed) / scale
    s, _, estimated = _noise(left, 0, noise, left.size)
    return {**found, "values": values, "noise": s, "estimated": estimated}


def _solution(model: Model, found: dict, fixed: dict[str, float], evaluations: int) -> Solution:
    """The :class:`Solution` of every parameter: the fitted ones from ``found``, the fixed
    (not identifiable) ones at their starts with their bounds as interval."""
    names = [p.name for p in model.parameters]
    index = {p.name: j for j, p in enumerate(found["params"])}
    ok = found["identifiable"]
    cov = np.full((len(names), len(names)), np.nan)
    for a, name in enumerate(names):
        for b, other in enumerate(names):
            if name in index and other in index and ok[index[name]] and ok[index[other]]:
                cov[a, b] = found["cov"][index[name], index[other]]
    sd = np.sqrt(np.diag(cov))
    with np.errstate(invalid="ignore", divide="ignore"):
        corr = cov / np.outer(sd, sd)
    low, high, ident = [], [], []
    for p in model.parameters:
        j = index.get(p.name)
        seen = j is not None and bool(ok[j])
        ident.append(seen)
        low.append(p.from_space(found["low"][j]) if seen else p.low)
        high.append(p.from_space(found["high"][j]) if seen else p.high)
    fitted = model.predict(found["values"])
    return Solution(
        values=np.array([found["values"].get(n, np.nan) for n in names]),
        low=np.array(low),
        high=np.array(high),
        identifiable=np.array(ident),
        correlation=corr,
        model=fitted,
        residual=fitted - model.observed,
        noise=found["noise"],
        noise_estimated=found["estimated"],
        evaluations=evaluations,
    )
