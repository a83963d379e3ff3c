"""Error estimates from a mesh ladder: Richardson extrapolation with the observed order.

From three levels Q1 (coarsest), Q2, Q3 whose sizes shrink by s > 1 per level, with
d1 = Q1 - Q2 and d2 = Q2 - Q3: p = ln(d1 / d2) / ln(s), Q* = Q3 - d2 / (s^p - 1), relative
error |d2 / (s^p - 1)| / |Q*|. The fall-backs, the known order, curves, propagation and
envelopes: benchmarks/FEM_NOTES.md, "Study error estimates".
"""

from __future__ import annotations

import math
from collections.abc import Callable, Sequence
from dataclasses import dataclass, replace

import numpy as np
from numpy.typing import ArrayLike

from ..validation import InputError

__all__ = [
    "ESTIMATED",
    "FALLBACKS",
    "ORDER_RANGE",
    "Estimate",
    "curve_richardson",
    "envelope",
    "propagated",
    "richardson",
    "worst_point",
]

ORDER_RANGE = (1.5, 4.5)
"""Observed orders accepted for extrapolation; outside this range the coarse level is taken as
not yet asymptotic (P2 contact's orders: ``benchmarks/bench_contact.py`` (b))."""

FALLBACKS = ("last", "largest")
"""What :func:`richardson` reports without a clean order: the last difference |d2|, or the
largest of |d1| and |d2| (for a quantity whose levels scatter)."""

ESTIMATED = ("richardson", "propagated", "envelope")
"""Methods of an :class:`Estimate` that are estimates; the others are fall-backs."""


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
        The order of the correction that gives ``error``: the observed p, or the known order
        when one was given (:func:`at_most_order`: the lower of the two); nan where no
        correction gives the error (a fallback, ``"propagated"``).
    method : str
        ``"richardson"``, ``"propagated"`` (a bound from separately estimated factors,
        :func:`propagated`), ``"envelope"`` (a neighbourhood's largest error,
        :func:`envelope`), or the fallback (see ``reason``): ``"two-level"`` (the last
        difference) or ``"scatter"`` (the largest of the two differences).
    reason : str
        Why the fallback was used, or why the observed order did or did not correct where a
        known order was given ("" where the observed order corrects without one).
    observed_order : float
        The ladder's own order p = ln(d1 / d2) / ln(s) wherever d1 and d2 have one sign, in
        range or not (nan otherwise).
    """

    value: float
    extrapolated: float
    error: float
    order: float
    method: str
    reason: str = ""
    observed_order: float = math.nan

    @property
    def absolute_error(self) -> float:
        """Estimated absolute error of ``value`` (its unit): the Richardson correction, or the
        two-level difference; for quantities near zero (a small relative difference)."""
        return self.error * abs(self.extrapolated)

    def to_dict(self) -> dict[str, object]:
        """Plain data for JSON."""
        keys = ("value", "extrapolated", "error", "absolute_error", "order", "method", "reason")
        return {key: getattr(self, key) for key in (*keys, "observed_order")}


def _two_level(coarse: float, fine: float, reason: str, observed: float = math.nan) -> Estimate:
    error = abs(coarse - fine) / abs(fine) if fine != 0 else math.inf
    return Estimate(fine, fine, error, math.nan, "two-level", reason, observed)


def _checked(values: Sequence, ratio: float) -> list:
    values = list(values)[-3:]
    finite = all(bool(np.all(np.isfinite(v))) for v in values)
    if len(values) < 2 or not finite:
        raise InputError(f"values must hold at least two finite numbers, got {values!r}")
    if not ratio > 1.0:
        raise InputError(f"ratio must be > 1, got {ratio!r}")
    return values


def _observed_order(
    d1: float, d2: float, ratio: float, sane: tuple[float, float]
) -> tuple[float, str]:
    """The order of two differences (nan unless they have one sign) and why it may not
    correct ("" where it may)."""
    if d1 * d2 <= 0:
        return math.nan, "the differences do not shrink monotonically"
    observed = math.log(d1 / d2) / math.log(ratio)
    if abs(d2) >= abs(d1):
        return observed, "the differences do not shrink monotonically"
    if not sane[0] <= observed <= sane[1]:
        return observed, f"observed order {observed:.2f} outside {sane}"
    return observed, ""


def _known(order: float, observed: float) -> str:
    """Why the known ``order`` corrects rather than the ``observed`` one."""
    asked = "" if observed >= order else ", as asked"
    below = "is not below it" if observed >= order else "is below it"
    return f"the known order {order:g} corrects{asked}; the observed {observed:.2f} {below}"


def richardson(
    values: Sequence[float],
    ratio: float,
    *,
    order: float | None = None,
    sane: tuple[float, float] = ORDER_RANGE,
    fallback: str = "last",
) -> Estimate:
    """Estimate the error of the finest of two or three values on a geometric mesh ladder.

    Parameters
    ----------
    values : sequence of float
        The quantity on the last levels, coarsest first (only the last three are used).
    ratio : float
        Ratio s > 1 of the element sizes of consecutive levels (h_k / h_(k+1)).
    order : float, optional
        The known asymptotic order q used for the correction; default the observed one.
    sane : (float, float)
        Observed orders accepted as asymptotic (default :data:`ORDER_RANGE`).
    fallback : str
        Without a clean order (three values): ``"last"`` reports |d2| / |Q3| (method
        ``"two-level"``), ``"largest"`` max(|d1|, |d2|) / |Q3| (method ``"scatter"``).

    Returns
    -------
    Estimate

    Raises
    ------
    shtaerman.validation.InputError
        For fewer than two values, a non-finite value, ratio <= 1, or an unknown fallback.
    """
    if fallback not in FALLBACKS:
        raise InputError(f"Unknown fallback {fallback!r}. Pick one of {FALLBACKS}")
    values = [float(v) for v in _checked(values, ratio)]
    if len(values) == 2:
        return _two_level(*values, "two levels only")
    coarse, middle, fine = values
    d1, d2 = coarse - middle, middle - fine
    observed, why = (
        _observed_order(d1, d2, ratio, sane)
        if d2 != 0.0
        else (math.nan, "the last two levels agree")
    )
    if why and fallback == "largest":
        error = max(abs(d1), abs(d2)) / abs(fine) if fine != 0 else math.inf
        return Estimate(fine, fine, error, math.nan, "scatter", why, observed)
    if d2 == 0.0:
        return Estimate(fine, fine, 0.0, math.nan, "two-level", "the last two levels agree")
    if why:
        return _two_level(middle, fine, why, observed)
    used, reason = (observed, "") if order is None else (order, _known(order, observed))
    correction = d2 / (ratio**used - 1.0)
    extrapolated = fine - correction
    error = abs(correction / extrapolated)
    return Estimate(fine, extrapolated, error, used, "richardson", reason, observed)


def worst_point(curves: Sequence[ArrayLike]) -> int:
    """The point of a curve whose estimate :func:`curve_richardson` reports: the index where
    the last two levels (``curves[-2]``, ``curves[-1]``) differ most relative to the finest."""
    coarse, fine = (np.asarray(c, dtype=float) for c in curves[-2:])
    return int(np.argmax(np.abs(coarse - fine) / np.abs(fine)))


def curve_richardson(
    curves: Sequence[ArrayLike],
    ratio: float,
    *,
    order: float | None = None,
    sane: tuple[float, float] = ORDER_RANGE,
) -> Estimate:
    """Estimate the largest relative error over a curve's points on a geometric mesh ladder.

    With D_k the largest |Q_k - Q_(k+1)| / |Q_finest| over the points, the observed order is
    ln(D_1 / D_2) / ln(s) and the estimate D_2 / (s^q - 1); the value and extrapolated value
    are those of the point where D_2 is reached.

    Parameters
    ----------
    curves : sequence of array_like
        The quantity at the same points on the last levels, coarsest first (last three used).
    ratio, order, sane
        As for :func:`richardson`.

    Returns
    -------
    Estimate
    """
    curves = [np.asarray(c, dtype=float) for c in _checked(curves, ratio)]
    fine = curves[-1]
    scale = np.abs(fine)
    last = np.abs(curves[-2] - fine) / scale
    worst = worst_point(curves)
    if len(curves) == 2:
        return _two_level(float(curves[-2][worst]), float(fine[worst]), "two levels only")
    d1 = float(np.max(np.abs(curves[0] - curves[1]) / scale))
    d2 = float(last[worst])
    if d2 == 0.0:
        value = float(fine[worst])
        return Estimate(value, value, 0.0, math.nan, "two-level", "the last two levels agree")
    observed, why = _observed_order(d1, d2, ratio, sane)
    if why:
        return _two_level(float(curves[-2][worst]), float(fine[worst]), why, observed)
    used, reason = (observed, "") if order is None else (order, _known(order, observed))
    error = d2 / (ratio**used - 1.0)
    correction = (fine[worst] - curves[-2][worst]) / (ratio**used - 1.0)
    value = float(fine[worst])
    return Estimate(value, float(value + correction), error, used, "richardson", reason, observed)


def propagated(value: float, factors: Sequence[tuple[Estimate, float]]) -> Estimate:
    """The error of Q = prod F_i^k_i from its separately estimated factors.

    First-order propagation with the signs of the factors' errors unknown:
    |dQ / Q| <= sum |k_i| |dF_i / F_i|. A bound: where the factors' errors cancel (two
    quantities on the same mesh), Q is closer than it says.

    Parameters
    ----------
    value : float
        Q on the finest level (the quantity's unit).
    factors : sequence of (Estimate, float)
        Each factor's estimate (relative error) and its exponent k_i.

    Returns
    -------
    Estimate
        Method ``"propagated"`` when every factor's method is in :data:`ESTIMATED`;
        otherwise ``"two-level"``, its reason naming the factors' fall-backs. Nothing is
        extrapolated (``extrapolated`` is ``value``).
    """
    if not factors:
        raise InputError("factors must hold at least one (Estimate, exponent) pair, got none")
    error = sum(abs(k) * e.error for e, k in factors)
    prefix = "a factor fell back: "
    fallen = [e.reason.removeprefix(prefix) for e, _ in factors if e.method not in ESTIMATED]
    if fallen:
        reason = prefix + "; ".join(dict.fromkeys(fallen))
        return Estimate(value, value, error, math.nan, "two-level", reason)
    return Estimate(value, value, error, math.nan, "propagated")


def envelope(
    own: Estimate,
    curves: Sequence[ArrayLike],
    index: int,
    ratio: float,
    *,
    order: float | None = None,
    sane: tuple[float, float] = ORDER_RANGE,
) -> Estimate:
    """The larger of a point's own estimate and its neighbourhood's :func:`curve_richardson`.

    Parameters
    ----------
    own : Estimate
        The point's own estimate (any rule); kept where it is the larger estimate.
    curves : sequence of array_like
        The quantity at every point on the last levels, coarsest first (last three used).
    index : int
        The point.
    ratio, order, sane
        As for :func:`curve_richardson` over points ``index - 1`` to ``index + 1``.

    Returns
    -------
    Estimate
        ``own`` where it is an estimate (:data:`ESTIMATED`) at least as large as the
        neighbourhood's, or where neither is one; else method ``"envelope"`` with the
        neighbourhood's error and order, and the point's own value (not extrapolated).
    """
    near = [np.asarray(c, dtype=float)[max(0, index - 1) : index + 2] for c in curves]
    widest = curve_richardson(near, ratio, order=order, sane=sane)
    if widest.method not in ESTIMATED:
        return own
    if own.method in ESTIMATED and own.error >= widest.error:
        return own
    return Estimate(
        own.value,
        own.value,
        widest.error,
        widest.order,
        "envelope",
        widest.reason,
        widest.observed_order,
    )


def at_most_order(
    estimate: Callable[..., Estimate],
    values: Sequence,
    ratio: float,
    order: float | None,
    **options,
) -> Estimate:
    """``estimate`` (:func:`richardson` or :func:`curve_richardson`, with ``options``) of
    ``values`` at the known ``order``; where the ladder's observed order is lower, the error is
    the correction at the observed order (the larger; ``order`` says it), the extrapolated value
    stays at the known order: one the ladder has not reached yet would understate the error."""
    known = estimate(values, ratio, order=order, **options)
    if known.method == "richardson" and known.observed_order < known.order:
        observed = estimate(values, ratio, **options)
        reason = (
            f"the observed order {observed.order:.2f} corrects the error, below the known "
            f"{known.order:g} that the extrapolation keeps"
        )
        return replace(known, error=observed.error, order=observed.order, reason=reason)
    return known
