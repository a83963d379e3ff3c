"""Power-law fits of a force-depth curve."""

import math

import numpy as np
import pytest

from shtaerman.fem.fit import exponent_sensitivity, fit_power_law


def test_exact_power_law_is_recovered():
    depths = np.geomspace(1e-3, 1e-2, 5)
    fit = fit_power_law(depths, 3.0e6 * depths ** (5 / 3), 5 / 3)
    # a least-squares line through exact logs: round-off only
    assert fit.exponent == pytest.approx(5 / 3, rel=1e-12)
    assert fit.beta == pytest.approx(3.0e6, rel=1e-10)
    assert fit.beta_fixed_exponent == pytest.approx(3.0e6, rel=1e-12)
    assert fit.log_residual < 1e-12


def test_one_depth_measures_no_exponent():
    # a single point fixes beta for the theory's exponent, and nothing else: no fake exponent
    fit = fit_power_law([2e-3], [50.0], 5 / 3)
    assert fit.beta_fixed_exponent == pytest.approx(50.0 / 2e-3 ** (5 / 3), rel=1e-14)
    assert math.isnan(fit.exponent) and math.isnan(fit.beta) and math.isnan(fit.log_residual)


DEPTHS = 1.6e-3 * 1.265 ** np.arange(8)  # the paper's default eight depths' ratio
EXACT = 2.8e6 * DEPTHS ** (5 / 3)


def _moved(errors):
    """How far relative force errors move the free fit's exponent and the fixed one's beta."""
    exact, perturbed = (fit_power_law(DEPTHS, EXACT * (1 + e), 5 / 3) for e in (0.0, errors))
    return (
        perturbed.exponent - exact.exponent,
        perturbed.beta_fixed_exponent / exact.beta_fixed_exponent - 1,
    )


def test_the_exponent_moves_by_at_most_the_sensitivity_times_the_force_error():
    eps = 1e-5
    bound = exponent_sensitivity(DEPTHS) * eps
    # the slope's weights (L_i - mean L) / sum (L_j - mean L)^2 over L = ln x, spacing ln 1.265:
    # sum |w_i| = 16 / (42 ln 1.265), 1.6182
    assert exponent_sensitivity(DEPTHS) == pytest.approx(16 / (42 * math.log(1.265)), rel=1e-12)
    rng = np.random.default_rng(5)
    for errors in rng.uniform(-eps, eps, (200, DEPTHS.size)):
        exponent, beta = _moved(errors)
        # ln(1 + e) = e (1 + O(eps)): the bound holds to a relative 1e-5 (and round-off of the
        # fit, 1e-15 of q, far below the 1.6e-5 bound)
        assert abs(exponent) <= bound * (1 + 2 * eps)
        assert abs(beta) <= eps * (1 + 2 * eps)
    # the signs of the weights reach it: errors -eps at the shallow half, +eps at the deep half
    exponent, beta = _moved(np.where(np.arange(DEPTHS.size) < 4, -eps, eps))
    assert exponent == pytest.approx(bound, rel=2 * eps)
    # a common error leaves the exponent alone (sum w_i = 0; round-off 1e-15) and moves beta
    exponent, beta = _moved(np.full(DEPTHS.size, eps))
    assert abs(exponent) < 1e-12 and beta == pytest.approx(eps, rel=1e-9)
