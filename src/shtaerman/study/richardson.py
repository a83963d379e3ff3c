"""Error estimates from a mesh ladder: Richardson extrapolation with the observed order.

A quantity computed on meshes whose size field is divided by a constant ratio s > 1 from one
level to the next converges as Q(h) = Q* + C h^p + o(h^p). From three levels Q1 (coarsest),
Q2, Q3 (finest), with d1 = Q1 - Q2 and d2 = Q2 - Q3:

    p  = ln(d1 / d2) / ln(s)                  (the observed order)
    Q* = Q3 - d2 / (s^p - 1)                  (the extrapolated value)
    e  = |d2 / (s^p - 1)| / |Q*|              (the estimated relative error of Q3)

The estimate is trusted only when the differences shrink monotonically and p lies in a sane
range (:data:`ORDER_RANGE`); otherwise (noise, a quantity at its floor, two levels only) the
two-level difference |d2| / |Q3| is reported instead, and the estimate says so.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass

from ..validation import InputError

__all__ = ["ORDER_RANGE", "Estimate", "richardson"]

ORDER_RANGE = (1.5, 4.5)
"""Observed orders accepted for extrapolation. P2 contact converges at orders 2-3 here
(bench_contact.py (b): force 2.55, beta 2.8-3.15, p(0) 2.9); an order outside this range
means the coarse level is not yet asymptotic (observed 0.5-0.9 on the default ladder, whose
coarsest level has growth 0.5), and extrapolating with it overestimates the error 4-10x."""


@dataclass(frozen=True)
class Estimate:
    """The finest level's value with its estimated error.

    Attributes
    ----------
    value : float
        The finest level's value (the quantity's unit).
    extrapolated : float
        Richardson's extrapolated value (``value`` for the two-level fallback).
    error : float
        Estimated relative error of ``value``, dimensionless (>= 0).
    order : float
        Observed order p (nan for the fallback).
    method : str
        ``"richardson"`` or ``"two-level"`` (the fallback; see ``reason``).
    reason : str
        Why the fallback was used ("" for Richardson).
    """

    value: float
    extrapolated: float
    error: float
    order: float
    method: str
    reason: str = ""

    @property
    def absolute_error(self) -> float:
        """Estimated absolute error of ``value`` (its unit): the Richardson correction, or the
        two-level difference; for quantities near zero (a small relative difference)."""
        return self.error * abs(self.extrapolated)

    def to_dict(self) -> dict[str, object]:
        """Plain data for JSON."""
        return {
            "value": self.value,
            "extrapolated": self.extrapolated,
            "error": self.error,
            "absolute_error": self.absolute_error,
            "order": self.order,
            "method": self.method,
            "reason": self.reason,
        }


def _two_level(coarse: float, fine: float, reason: str) -> Estimate:
    error = abs(coarse - fine) / abs(fine) if fine != 0 else math.inf
    return Estimate(fine, fine, error, math.nan, "two-level", reason)


def richardson(values: Sequence[float], ratio: float) -> Estimate:
    """Estimate the error of the finest of two or three values on a geometric mesh ladder.

    Parameters
    ----------
    values : sequence of float
        The quantity on the last levels, coarsest first (only the last three are used).
    ratio : float
        Ratio s > 1 of the element sizes of consecutive levels (h_k / h_(k+1)).

    Returns
    -------
    Estimate

    Raises
    ------
    shtaerman.validation.InputError
        For fewer than two values, a non-finite value, or ratio <= 1.
    """
    values = [float(v) for v in values][-3:]
    if len(values) < 2 or not all(math.isfinite(v) for v in values):
        raise InputError(f"values must hold at least two finite numbers, got {values!r}")
    if not ratio > 1.0:
        raise InputError(f"ratio must be > 1, got {ratio!r}")
    if len(values) == 2:
        return _two_level(*values, "two levels only")
    coarse, middle, fine = values
    d1, d2 = coarse - middle, middle - fine
    if d2 == 0.0:
        return Estimate(fine, fine, 0.0, math.nan, "two-level", "the last two levels agree")
    if d1 * d2 <= 0 or abs(d2) >= abs(d1):
        return _two_level(middle, fine, "the differences do not shrink monotonically")
    order = math.log(d1 / d2) / math.log(ratio)
    if not ORDER_RANGE[0] <= order <= ORDER_RANGE[1]:
        return _two_level(middle, fine, f"observed order {order:.2f} outside {ORDER_RANGE}")
    correction = d2 / (ratio**order - 1.0)
    extrapolated = fine - correction
    return Estimate(fine, extrapolated, abs(correction / extrapolated), order, "richardson")
