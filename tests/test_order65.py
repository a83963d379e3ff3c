"""An error bar's metadata says what was done: ``order`` is the order of the correction that
gave the error (the observed one where :func:`at_most_order` took it, below the known order),
``observed_order`` the ladder's own order wherever it was computed, in range or not, and
``reason`` why it did or did not correct. Before, the JSON said order 2.0 beside an error at the
observed 1.5, and observed_order null beside a reason quoting its value."""

import math

import pytest

from shtaerman.study.dynamic.accuracy import DYNAMIC_SANE, over_levels
from shtaerman.study.ladder import LADDER_RATIO
from shtaerman.study.richardson import at_most_order, curve_richardson, richardson


def _ladder(order: float) -> list[float]:
    """Q = 1 + 0.01 h^order at h = 1, 1/s, 1/s^2 (s = sqrt 2): observed order exactly ``order``."""
    return [1.0 + 0.01 * LADDER_RATIO ** (-k * order) for k in range(3)]


def test_an_impact_error_at_the_observed_order_says_that_order():
    details = over_levels(_ladder(1.5), float).to_dict()
    observed = richardson(_ladder(1.5), LADDER_RATIO, sane=DYNAMIC_SANE)  # its own estimate
    assert details["order"] == pytest.approx(1.5, rel=1e-9) == details["observed_order"]
    assert details["error"] == observed.error  # the error this order gives (test_order64)
    said = (
        "the observed order 1.50 corrects the error, below the known 2 that the extrapolation keeps"
    )
    assert details["reason"] == said


def test_a_curve_error_at_the_observed_order_says_that_order():
    # two points converging as C_j h^2 with C = (1, -4): the curve's observed order 2 < known 3
    curves = [[2.0 + h**2, 5.0 - 4.0 * h**2] for h in (1.0, 1 / LADDER_RATIO, 0.5)]
    estimate = at_most_order(curve_richardson, curves, LADDER_RATIO, 3.0)
    assert estimate.order == pytest.approx(2.0, rel=1e-12) == estimate.observed_order
    assert estimate.error == curve_richardson(curves, LADDER_RATIO).error


def test_a_known_order_not_above_the_observed_one_corrects_and_says_why():
    estimate = over_levels(_ladder(3.0), float)
    assert estimate.order == 2.0 and estimate.observed_order == pytest.approx(3.0, rel=1e-9)
    assert estimate.reason == "the known order 2 corrects; the observed 3.00 is not below it"
    # asked for directly (no at_most_order), a known order above the observed one corrects
    below = richardson(_ladder(1.5), LADDER_RATIO, order=2.0, sane=DYNAMIC_SANE)
    assert below.order == 2.0 and below.observed_order == pytest.approx(1.5, rel=1e-9)
    assert below.reason == "the known order 2 corrects, as asked; the observed 1.50 is below it"


@pytest.mark.parametrize(
    ("values", "fallback", "method"),
    [([1.0, 1.5, 1.8], "last", "two-level"), ([1.0, 1.5, 1.8], "largest", "scatter")],
)
def test_an_observed_order_out_of_range_is_reported_beside_its_reason(values, fallback, method):
    # d1 = -0.5, d2 = -0.3: p = log2(0.5 / 0.3) = 0.737, below (1.5, 4.5): not used
    estimate = richardson(values, 2.0, fallback=fallback).to_dict()
    assert estimate["observed_order"] == pytest.approx(math.log2(5.0 / 3.0), rel=1e-12)
    assert estimate["method"] == method and math.isnan(estimate["order"])
    assert estimate["reason"] == "observed order 0.74 outside (1.5, 4.5)"


def test_differences_that_grow_report_their_order_and_the_reason():
    # d1 = -0.1, d2 = -0.2, one sign, growing: p = log2(0.5) = -1, not used
    estimate = richardson([1.0, 1.1, 1.3], 2.0)
    assert estimate.observed_order == pytest.approx(-1.0, rel=1e-12)
    assert estimate.method == "two-level" and "do not shrink monotonically" in estimate.reason
    # of opposite signs there is no order: nan, as before
    assert math.isnan(richardson([1.0, 1.1, 1.05], 2.0).observed_order)
