"""Power-law fits of a force-depth curve."""

import math

import numpy as np
import pytest

from shtaerman.fem.fit import fit_power_law


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
