"""The impact ladder's Richardson estimate took the stepping's order 2 even where its levels
converge more slowly, and so understated: at an observed order 1.5 it gave 0.68 of the true
error, at 1.21 (a z = 2 r^1.2 striker's restitution, session 62) about 0.5, the edge of
issue 28's [0.5, 5]. Like the contact curve's (study.contact.accuracy, "Accuracy 1e-6" in
benchmarks/FEM_NOTES.md), the error is now the correction at the lower of the two orders."""

import math

import pytest

from shtaerman.study.dynamic.accuracy import over_levels
from shtaerman.study.ladder import LADDER_RATIO
from shtaerman.study.richardson import richardson


def _ladder(order: float) -> list[float]:
    """Q = 1 + 0.01 h^order at h = 1, 1/s, 1/s^2 (s = sqrt 2): exact 1, the finest's error
    0.01 s^(-2 order)."""
    return [1.0 + 0.01 * LADDER_RATIO ** (-k * order) for k in range(3)]


def test_a_ladder_slower_than_the_known_order_is_told_its_own_error():
    estimate = over_levels(_ladder(1.5), float)
    true = 0.01 * 2.0**-1.5  # relative to the exact 1: Richardson at the observed 1.5 is exact
    assert estimate.method == "richardson" and estimate.observed_order == pytest.approx(1.5)
    assert estimate.error == pytest.approx(true, rel=1e-9)  # was 0.68 of it (order 2)
    # the extrapolated value stays at the known order 2: Q3 - d2 / (s^2 - 1), s^2 - 1 = 1
    _, middle, fine = _ladder(1.5)
    assert estimate.extrapolated == pytest.approx(fine - (middle - fine), rel=1e-12)


def test_a_ladder_at_or_above_the_known_order_is_unchanged():
    values = _ladder(3.0)
    plain = richardson(values, LADDER_RATIO, order=2.0, sane=(1.0, 5.0), fallback="largest")
    assert over_levels(values, float) == plain
    d2 = 0.01 * (2.0**-1.5 - 2.0**-3)  # Q2 - Q3 at order 3; the correction d2 / (s^2 - 1) = d2
    assert math.isclose(plain.error, d2 / (values[2] - d2), rel_tol=1e-9)
