"""Richardson extrapolation on synthetic ladders whose exact limit is known."""

import math

import pytest

from shtaerman.study.richardson import (
    Estimate,
    curve_richardson,
    envelope,
    propagated,
    richardson,
)
from shtaerman.validation import InputError


@pytest.mark.parametrize("order", [1.6, 2.0, 2.5, 4.0])
def test_exact_for_a_pure_power(order):
    # Q(h) = 3 + 0.7 h^p on h = 1, 1/sqrt(2), 1/2: Richardson is exact for this form
    s = math.sqrt(2.0)
    values = [3.0 + 0.7 * (1.0 / s**k) ** order for k in range(3)]
    estimate = richardson(values, s)
    assert estimate.method == "richardson"
    assert estimate.order == pytest.approx(order, rel=1e-10)
    assert estimate.extrapolated == pytest.approx(3.0, rel=1e-13)
    true_error = abs(values[-1] / 3.0 - 1.0)
    assert estimate.error == pytest.approx(true_error, rel=1e-9)


def test_higher_order_term_costs_little():
    # Q = 1 + h^2 + 0.3 h^3: the estimate stays within 15 % of the true error at h = 1/8
    s = 2.0
    values = [1.0 + h**2 + 0.3 * h**3 for h in (0.5, 0.25, 0.125)]
    estimate = richardson(values, s)
    true_error = abs(values[-1] - 1.0)
    assert 0.85 < estimate.error / true_error < 1.15


@pytest.mark.parametrize(
    ("values", "reason"),
    [
        ([1.0, 1.1, 1.05], "do not shrink monotonically"),
        ([1.0, 1.001, 1.0010001], "outside"),
        ([1.0, 1.5, 1.8], "outside"),  # order 0.94: not yet asymptotic
        ([1.2, 1.1], "two levels only"),
    ],
)
def test_falls_back_and_says_why(values, reason):
    estimate = richardson(values, 2.0)
    assert estimate.method == "two-level" and reason in estimate.reason
    assert estimate.error == pytest.approx(abs(values[-2] - values[-1]) / abs(values[-1]))
    assert math.isnan(estimate.order) and estimate.extrapolated == values[-1]


@pytest.mark.parametrize(
    ("values", "reason"),
    [
        ([1.0, 1.1, 1.1], "the last two levels agree"),  # chance agreement: not zero error
        ([1.0, 1.1, 1.05], "do not shrink monotonically"),
        ([1.0, 1.001, 1.0010001], "outside"),
    ],
)
def test_scatter_fallback_reports_the_largest_difference(values, reason):
    estimate = richardson(values, 2.0, fallback="largest")
    assert estimate.method == "scatter" and reason in estimate.reason
    largest = max(abs(values[0] - values[1]), abs(values[1] - values[2])) / abs(values[2])
    assert estimate.error == pytest.approx(largest, rel=1e-15)
    assert estimate.error >= abs(values[1] - values[2]) / abs(values[2])  # never below "last"
    assert math.isnan(estimate.order) and estimate.extrapolated == values[-1]
    # a clean order is unaffected by the fallback
    clean = [3.0 + 0.7 * 4.0**-k for k in range(3)]  # order 2
    assert richardson(clean, 2.0, fallback="largest") == richardson(clean, 2.0)
    with pytest.raises(InputError, match=r"Unknown fallback 'mean'\. Pick one of"):
        richardson(values, 2.0, fallback="mean")


def test_agreeing_levels_have_zero_error():
    assert richardson([2.0, 1.0, 1.0], 2.0) == Estimate(
        1.0, 1.0, 0.0, math.nan, "two-level", "the last two levels agree"
    )


def test_bad_input():
    with pytest.raises(InputError, match="at least two finite"):
        richardson([1.0], 2.0)
    with pytest.raises(InputError, match="at least two finite"):
        richardson([1.0, math.nan, 2.0], 2.0)
    with pytest.raises(InputError, match="ratio must be > 1"):
        richardson([1.0, 2.0, 3.0], 1.0)


def test_known_order_corrects_with_it_and_keeps_the_observed_one():
    # Q = 1 + h^2 observed at order 2; with order=3 the correction is d2 / (s^3 - 1)
    s = 2.0
    values = [1.0 + h**2 for h in (0.5, 0.25, 0.125)]
    estimate = richardson(values, s, order=3.0)
    assert estimate.order == 3.0 and estimate.observed_order == pytest.approx(2.0, rel=1e-12)
    d2 = values[1] - values[2]
    assert estimate.extrapolated == pytest.approx(values[2] - d2 / 7.0, rel=1e-14)


def test_curve_estimate_is_the_worst_point():
    # two points converging as C_j h^3 with C = (1, -4): the second point is the worst; the
    # order of the largest differences is 3 and Richardson is exact there
    s = math.sqrt(2.0)
    curves = [[2.0 + h**3, 5.0 - 4.0 * h**3] for h in (1.0, 1 / s, 0.5)]
    estimate = curve_richardson(curves, s)
    assert estimate.method == "richardson"
    assert estimate.observed_order == pytest.approx(3.0, rel=1e-12)
    assert estimate.value == curves[-1][1]
    assert estimate.extrapolated == pytest.approx(5.0, rel=1e-14)
    assert estimate.error == pytest.approx(abs(curves[-1][1] - 5.0) / curves[-1][1], rel=1e-12)


def test_curve_with_sign_changing_points_still_converges():
    # per point the differences change sign (a contact edge between nodes); their largest
    # value still shrinks as h^3, so the curve estimate is Richardson, not the fallback
    s = math.sqrt(2.0)
    jitter = [(0.3, -0.2), (-0.25, 0.3), (0.3, 0.1)]
    curves = [
        [1.0 + h**3 * j[0], 2.0 + h**3 * j[1]]
        for h, j in zip((1.0, 1 / s, 0.5), jitter, strict=True)
    ]
    for point in range(2):
        column = [curve[point] for curve in curves]
        assert richardson(column, s).method == "two-level"
    estimate = curve_richardson(curves, s, order=3.0, sane=(1.0, 5.0))
    assert estimate.method == "richardson" and estimate.order == 3.0


def test_propagated_bound_adds_the_factors_relative_errors():
    a = richardson([1.0 + h**2 for h in (1.0, 0.5, 0.25)], 2.0)
    b = richardson([2.0 + 0.5 * h**3 for h in (1.0, 0.5, 0.25)], 2.0)
    ratio = propagated(a.value / b.value**2, [(a, 1.0), (b, -2.0)])
    assert ratio.method == "propagated" and not ratio.reason
    assert ratio.error == pytest.approx(a.error + 2.0 * b.error, rel=1e-15)
    assert ratio.extrapolated == ratio.value  # a bound, nothing extrapolated


def test_propagated_falls_back_with_a_factor_and_says_which():
    fine = richardson([1.0 + h**2 for h in (1.0, 0.5, 0.25)], 2.0)
    noisy = richardson([1.0, 1.1, 1.05], 2.0)  # differences change sign
    ratio = propagated(1.0, [(fine, 1.0), (noisy, -1.0)])
    assert ratio.method == "two-level" and "do not shrink monotonically" in ratio.reason
    assert ratio.error == pytest.approx(fine.error + noisy.error, rel=1e-15)
    with pytest.raises(InputError, match="factors"):
        propagated(1.0, [])


# Three points on three levels (coarse to fine, ratio 2). Point 1's differences change sign
# (+6e-3, -2e-3: its own estimate falls back); the largest differences over points 0-2 are 8e-3
# then 2e-3 (point 0), order log2(4) = 2: the envelope's estimate is 2e-3 / (2^2 - 1). Point 2's
# neighbourhood is points 1-2: 6e-3 then 2e-3, order log2(3), estimate 2e-3 / (3 - 1).
OSCILLATING = [[1.010, 1.004, 1.0], [1.002, 0.998, 1.001], [1.0, 1.0, 1.002]]


def test_envelope_gives_a_point_whose_own_differences_oscillate_its_neighbourhoods_estimate():
    own = richardson([level[1] for level in OSCILLATING], 2.0)
    assert own.method == "two-level"
    estimate = envelope(own, OSCILLATING, 1, 2.0)
    assert estimate.method == "envelope" and estimate.observed_order == pytest.approx(2.0)
    assert estimate.error == pytest.approx(2e-3 / 3.0, rel=1e-12)  # 2e-3 relative to 1.0
    assert estimate.value == estimate.extrapolated == 1.0  # the point's own value, kept
    last = envelope(richardson([level[2] for level in OSCILLATING], 2.0), OSCILLATING, 2, 2.0)
    assert last.method == "envelope" and last.error == pytest.approx(1e-3, rel=1e-12)


def test_envelope_keeps_a_larger_own_estimate_and_a_fallback_without_a_clean_envelope():
    larger = Estimate(1.0, 0.99, 0.01, 2.0, "richardson")
    assert envelope(larger, OSCILLATING, 1, 2.0) is larger
    noisy = [[1.0, 1.0, 1.0], [1.001, 0.999, 1.0], [1.0, 1.002, 1.0]]  # largest 1e-3 then 2e-3
    own = richardson([level[1] for level in noisy], 2.0)
    assert envelope(own, noisy, 1, 2.0) is own and own.method == "two-level"
