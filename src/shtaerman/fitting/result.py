"""The result of a fit: the fitted values with their 95 % intervals, as ``fit --json``."""

from __future__ import annotations

from dataclasses import dataclass, field, fields
from typing import Any

import numpy as np

from ..theory.materials import Material
from ..validation import NumericalFailureError
from ..vocabulary import MODULUS
from .corrections import check_striker_reach
from .corrections import youngs_modulus as _young
from .engine import Solution
from .models import Known

__all__ = ["UNITS", "FitResult", "fitted_entries", "shown_names"]

UNITS = {
    "E2": "Pa",
    "nu2": "1",
    "mass": "kg",
    "velocity": "m/s",
    "time_offset": "s",
    "baseline": "N",
}
"""The unit of each fitted name (the Prony weights g_i: 1; the times tau_i: s)."""
NU2_RANGE = (0.0, 0.5)
"""The Poisson's ratios a fit considers (nu2 enters only as nu2^2: its sign is not seen)."""
ROUND_OFF = 1e-9
"""Relative slack of a fitted E* past the end of its reach: exact data fitted back land a few
ulps beyond a bound they were made at (nu2 = 0.5); any real excess is far larger."""


@dataclass(frozen=True)
class FitResult:
    """A fit of a forward model to a measurement; the attributes are the JSON keys."""

    kind: str
    """indentation, force-history, rebound or resilience."""
    fitted: dict[str, dict[str, Any]]
    """Name -> value, low, high (the 95 % interval), identifiable, unit (and reason, why
    the Mooney ratio of an indentation is not identifiable, or why nu2 is at its bound)."""
    correlation: dict[str, Any]
    """names (the fitted parameters, by the unknowns' names: E2 or nu2 for the combined
    modulus they are fitted as) and matrix (null where a variance is unbounded)."""
    residual: dict[str, Any]
    """rms and max of model - data, their unit, and the number of values."""
    noise: dict[str, Any]
    """value (the standard deviation used for the intervals), unit, estimated (from the
    residual) or given."""
    forward_model: str
    """The exact model the data were compared with."""
    corrections: list[dict[str, Any]]
    """The FE correction that entered (a pad, waves, finite strain; empty without them): its
    name, the FE / exact ratios of the peak force (force_scale) and contact time
    (time_scale), the largest shape difference (shape_max, of the peak), the FE run's
    relative error estimates (fe_error) and the point of its last FE run (at)."""
    data: dict[str, Any]
    """source, rows (fitted: after resample), rows_read (in the file) and the columns'
    units."""
    known: dict[str, Any]
    """The known values of the problem (SI units)."""
    evaluations: int
    """Forward-model evaluations used: the search's, its Jacobians' and the intervals'
    (the forward model's own error refits are not counted)."""
    fe_runs: int = 0
    """FE impacts run for the corrections (each with its two coarser ladder levels)."""
    forward_error: dict[str, dict[str, float]] = field(default_factory=dict)
    """Fitted name -> source -> the shift that the forward model's own error makes, added
    in quadrature to the interval's half-widths: fe_P_max, fe_t_contact (the FE run's error
    estimates), steps (the viscoelastic impact's time steps); natural units (E_star, the
    combined modulus, in Pa)."""
    curves: dict[str, np.ndarray] = field(repr=False, compare=False, default_factory=dict)
    """The columns of fit.csv: the abscissa, data, model and residual (SI units)."""

    def to_dict(self) -> dict[str, Any]:
        """The JSON of ``shtaerman fit --json``."""
        return {f.name: getattr(self, f.name) for f in fields(self) if f.name != "curves"}


def _entry(value: float, low: float, high: float, ident: bool, unit: str) -> dict[str, Any]:
    return {"value": float(value), "low": float(low), "high": float(high),
            "identifiable": bool(ident), "unit": unit}  # fmt: skip


def _poisson(known: Known, modulus: float) -> float:
    """nu2 giving the combined modulus ``modulus`` with the known E2 (NaN if none does)."""
    square = 1.0 - known.E2 * (1.0 / modulus - known.striker.compliance)
    return float(np.sqrt(square)) if square >= 0 else float("nan")


def _nu2_reach(known: Known) -> tuple[float, float]:
    """The combined moduli E* in Pa that nu2 in [0, 0.5] gives with the known E2 and striker:
    from its value at nu2 = 0 to that at nu2 = 0.5 (any E2 gives less than the striker's own
    1/Q1: :func:`.corrections.check_striker_reach`)."""
    q1 = known.striker.compliance
    least, most = (1.0 / (q1 + (1.0 - nu * nu) / known.E2) for nu in NU2_RANGE)
    return least, most


def _unreachable(known: Known, modulus: float, reach: tuple[float, float]) -> str:
    """The message of a fitted E* (Pa) past the ``reach`` of nu2 with the known E2: what the
    data need of it."""
    above = modulus > reach[1]
    return (
        f"nu2: no nu2 in [0, 0.5] gives the data's E* = {modulus:.6g} Pa with E2={known.E2:g} "
        f"(E* {'at most' if above else 'at least'} {reach[int(above)]:.6g} Pa, at nu2 = "
        f"{NU2_RANGE[int(above)]:g}): give unknowns='E2' or {'raise' if above else 'lower'} E2=..."
    )


def _within_reach(known: Known, sol: Solution, j: int, unknowns: list[str]) -> float:
    """The fitted E* in Pa (parameter ``j``); with nu2 the one unknown, on the end of its
    reach (:func:`_nu2_reach`) where it lies past it by no more than its 95 % interval or
    round-off: there the fitted nu2 is at its bound. Past that, NumericalFailureError naming
    the fixed option: no value of the unknowns in their range reproduces the data."""
    value, low, high = (float(v[j]) for v in (sol.values, sol.low, sol.high))
    check_striker_reach(known, value)  # E2 never clips: its bound is E2 = inf
    if "E2" in unknowns:
        return value
    reach = _nu2_reach(known)
    if reach[0] <= value <= reach[1]:
        return value
    slack = ROUND_OFF * value
    near = reach[1] if value > reach[1] else reach[0]
    if low - slack <= near <= high + slack:
        return near
    raise NumericalFailureError(_unreachable(known, value, reach))


def _check_young(modulus: float, young: float) -> float:
    """The fitted E2 ``young`` (Pa, from the data's E* ``modulus``), or NumericalFailureError
    when it lies outside the range E2 takes on every route (:data:`MODULUS`): no E2 the suite
    takes reproduces the data under the fixed options."""
    if not MODULUS.contains(young):
        raise NumericalFailureError(
            f"E2: the data's E* = {modulus:.4g} Pa needs E2 = {young:.4g} Pa, outside "
            f"{MODULUS.text()} Pa, E2's range: check the striker's profile and the data's units"
        )
    return young


def _moduli(known: Known, sol: Solution, j: int, unknowns: list[str]) -> dict[str, dict]:
    """E2 and/or nu2 from the fitted combined modulus E* (parameter ``j``)."""
    value, low, high, ident = sol.values[j], sol.low[j], sol.high[j], sol.identifiable[j]
    fitted = _within_reach(known, sol, j, unknowns)
    out = {}
    if "E2" in unknowns:
        young = _check_young(value, _young(known, value, known.nu2))
    if "E2" in unknowns and "nu2" in unknowns:  # only E* is seen: E2 over every nu2
        out["E2"] = _entry(young, _young(known, low, NU2_RANGE[1]),
                           _young(known, high, NU2_RANGE[0]), ident, "Pa")  # fmt: skip
        out["nu2"] = _entry(known.nu2, *NU2_RANGE, False, "1")
    elif "E2" in unknowns:
        nu2 = known.nu2
        out["E2"] = _entry(young, _young(known, low, nu2), _young(known, high, nu2), ident, "Pa")
    else:
        ends = [_poisson(known, low), _poisson(known, high)]
        ends = [NU2_RANGE[0] if np.isnan(e) else min(e, NU2_RANGE[1]) for e in ends]
        spans = ends[0] <= NU2_RANGE[0] and ends[1] >= NU2_RANGE[1]
        at = NU2_RANGE[int(fitted < value)] if fitted != value else None
        nu2 = _poisson(known, value) if at is None else at
        ends = [min(ends[0], nu2), max(ends[1], nu2)]  # at a bound, past an end by round-off
        out["nu2"] = _entry(nu2, *ends, ident and not spans, "1")
        if at is not None:
            out["nu2"]["reason"] = (
                f"at its bound {at:g}: the data's E* lies {abs(value / fitted - 1):.2g} (relative) "
                f"past what nu2 = {at:g} gives with E2 = {known.E2:g}, within its 95 % interval "
                "or round-off"
            )
    return out


def shown_names(names: list[str], unknowns: list[str]) -> list[str]:
    """The fitted parameters ``names`` by the unknowns' names: the combined modulus E_star is
    E2 (or nu2 when only nu2 is fitted)."""
    modulus = "E2" if "E2" in unknowns else "nu2"
    return [modulus if name == "E_star" else name for name in names]


def fitted_entries(known: Known, names: list[str], sol: Solution, unknowns: list[str]) -> dict:
    """Name -> value, low, high, identifiable and unit of every unknown."""
    out: dict[str, dict] = {}
    for j, name in enumerate(names):
        if name == "E_star":
            out.update(_moduli(known, sol, j, unknowns))
        else:
            unit = UNITS.get(name, "s" if name.startswith("tau") else "1")
            out[name] = _entry(sol.values[j], sol.low[j], sol.high[j], sol.identifiable[j], unit)
    return out


def known_values(known: Known) -> dict[str, Any]:
    """The problem's known values as JSON."""
    striker: Material = known.striker
    prony = known.prony
    return {
        "shape_coefficient": getattr(known.indenter, "shape_coefficient", None),
        "exponent": getattr(known.indenter, "exponent", None),
        "profile": {"kind": known.indenter.kind, "parameters": known.indenter.parameters},
        "E1": striker.youngs_modulus,
        "nu1": striker.poisson_ratio,
        "E2": known.E2,
        "nu2": known.nu2,
        "mass": known.mass,
        "velocity": known.velocity,
        "prony": None if prony is None else
        [{"g": g, "tau": tau} for g, tau in zip(prony.weights, prony.times, strict=True)],
        "time_offset": known.time_offset or 0.0,
        "baseline": known.baseline,
        "steps": known.steps,
    }  # fmt: skip
