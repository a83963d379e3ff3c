"""The outer iteration of a fit with FE corrections, and the forward model's own error.

Exact fit, one FE impact at the fitted point (:mod:`.corrections`), corrected fit, until every
identifiable value moves by less than :data:`TOLERANCE` of its interval; the FE run's and the
time steps' errors join each interval in quadrature (docs/fit.md, "The forward model's own
error").
"""

from __future__ import annotations

import dataclasses
from collections.abc import Mapping, Sequence

import numpy as np

from ..problem import Problem
from ..validation import NumericalFailureError
from .corrections import Correction, RowCorrection, fe_correction, fe_rows
from .data import Measurement
from .engine import CONFIDENCE, Solution, solve
from .models import Known, Model, all_values, build_model, prony_at

__all__ = ["MAX_ROUNDS", "TOLERANCE", "corrected_fit", "forward_error"]

MAX_ROUNDS = 8
"""Most rounds of FE runs of one fit (one FE run a round for a force history, one per drop
velocity for rebound data)."""
MIN_STEPS = 20
"""The fewest time steps the viscoelastic impact takes."""
TOLERANCE = 0.1
"""The outer iteration stops when no fitted value moves by more than this of its interval."""


def _fitted(model: Model, sol: Solution) -> dict[str, float]:
    """Fitted name -> natural value."""
    return {p.name: float(v) for p, v in zip(model.parameters, sol.values, strict=True)}


def _moved(old: Solution, new: Solution) -> bool:
    """Whether an identifiable value moved by more than TOLERANCE of its interval."""
    width = new.high - new.low
    step = np.abs(new.values - old.values)
    return bool(np.any(new.identifiable & (step > TOLERANCE * width)))


def corrected_fit(
    problem: Problem,
    known: Known,
    measured: Measurement,
    names: Sequence[str],
    noise: float | None,
    refine: float,
) -> tuple[Known, Model, Solution, list[Correction | RowCorrection]]:
    """Fit, FE run(s), fit again, until the values settle: the known parts with the last
    correction, the model, its solution and every correction measured (one per round)."""
    model = build_model(known, measured, names)
    sol = solve(model, noise)
    corrections: list[Correction | RowCorrection] = []
    while len(corrections) < MAX_ROUNDS:
        values = all_values(known, _fitted(model, sol))
        prony = prony_at(known, values)
        if measured.kind == "force-history":
            correction = fe_correction(problem, known, values, prony, refine)
        else:
            velocities = measured.columns["velocity"]
            correction = fe_rows(problem, known, values, prony, refine, velocities)
        corrections.append(correction)
        known = dataclasses.replace(known, correction=correction)
        new_model = build_model(known, measured, names, _fitted(model, sol))
        new = solve(new_model, noise)
        moved = _moved(sol, new)
        model, sol = new_model, new
        if not moved:
            return known, model, sol, corrections
    raise NumericalFailureError(
        f"the FE corrections did not settle in {MAX_ROUNDS} rounds of FE runs (the fitted values "
        "still moved by more than a tenth of their intervals): give starting values nearer "
        "the data (E2, ...) or a finer FE run (refine)"
    )


def _refit(known: Known, measured: Measurement, names: Sequence[str], noise: float | None,
           sol: Solution, starts: Mapping[str, float]) -> np.ndarray:  # fmt: skip
    """The fitted values of the model of ``known``, started from ``starts``, with the
    parameters ``sol`` found not identifiable held there (none moves when all are held)."""
    if not np.any(sol.identifiable):
        return sol.values
    hold = {n: v for (n, v), ok in zip(starts.items(), sol.identifiable, strict=True) if not ok}
    return solve(build_model(known, measured, names, starts), noise, hold).values


def forward_error(
    known: Known,
    measured: Measurement,
    names: Sequence[str],
    noise: float | None,
    model: Model,
    sol: Solution,
) -> dict[str, np.ndarray]:
    """Source -> the shift of each fitted value (natural units) that the forward model's own
    error makes: ``fe_P_max`` and ``fe_t_contact`` (the FE error estimates), ``steps`` (the
    viscoelastic impact's time steps)."""
    starts = _fitted(model, sol)
    shifts = {}
    correction = known.correction
    if correction is not None:  # one shift per FE error estimate
        for key, error in correction.errors.items():
            if error > 0:
                again = dataclasses.replace(known, correction=correction.moved(key))
                shifts[f"fe_{key}"] = (
                    _refit(again, measured, names, noise, sol, starts) - sol.values
                )
    if known.prony is not None:
        other = known.steps // 2 if known.steps >= 2 * MIN_STEPS else 2 * known.steps
        again = dataclasses.replace(known, steps=other)
        shift = _refit(again, measured, names, noise, sol, starts) - sol.values
        shifts["steps"] = shift / abs((known.steps / other) ** 2 - 1.0)
    return shifts


def widened(sol: Solution, shifts: Mapping[str, np.ndarray]) -> Solution:
    """``sol`` with the shifts, each taken as one standard deviation of the forward model's
    error (times the normal quantile of the interval's confidence), added in quadrature to
    each identifiable half-interval."""
    from scipy.stats import norm  # here, not at load (see engine._noise)

    if not shifts:
        return sol
    quantile = norm.ppf(0.5 + CONFIDENCE / 2)
    error = quantile * np.sqrt(sum(np.asarray(s) ** 2 for s in shifts.values()))
    error = np.where(sol.identifiable, np.nan_to_num(error), 0.0)
    low = sol.values - np.hypot(sol.values - sol.low, error)
    high = sol.values + np.hypot(sol.high - sol.values, error)
    ident = sol.identifiable
    return dataclasses.replace(sol, low=np.where(ident, low, sol.low),
                               high=np.where(ident, high, sol.high))  # fmt: skip
