"""The tabulated FEM contact law: log-log interpolation, exact for a power law."""

from __future__ import annotations

import numpy as np
import pytest

from shtaerman.study.contact.contact_law import FemContactLaw
from shtaerman.theory.contact import PowerLawContact
from shtaerman.theory.indenter import PowerLawIndenter


@pytest.fixture
def law():
    depths = np.geomspace(1e-5, 1e-2, 9)  # m
    forces = 3.0e7 * depths**1.6 * (1.0 + 0.1 * np.sin(np.arange(9)))  # N, kinked table
    return FemContactLaw(depths, forces, np.sqrt(depths), forces, 3.0e7, 1.6)


def test_power_law_segments_and_end_slopes(law):
    d, p = law.depths, law.forces
    # between nodes k and k+1 the law is p_k (x / d_k)^s, s the segment's log-log slope;
    # beyond the ends the nearest segment's slope (exact up to exp/log round-off: 1e-14)
    slopes = np.diff(np.log(p)) / np.diff(np.log(d))
    for x, k in ((np.sqrt(d[2] * d[3]), 2), (0.5 * d[0], 0), (2.0 * d[-1], slopes.size - 1)):
        assert law.force(x) == pytest.approx(p[k] * (x / d[k]) ** slopes[k], rel=1e-13)
    assert np.allclose(law.force(d), p, rtol=1e-14, atol=0)
    assert law.force(0.0) == 0.0 and law.force(-1e-3) == 0.0


def test_one_depth_and_an_array_agree_to_the_bit(law):
    # the ODE calls the law with one depth at a time (a faster path): the same numbers
    x = np.concatenate([[0.0, -1.0], np.geomspace(1e-6, 5e-2, 50)])
    together = law.force(x)
    assert np.array_equal([float(law.force(np.asarray(v))) for v in x], together)
    assert np.array_equal(law.contact_radius(x[5]), law.contact_radius(x)[5])
    assert np.shape(law.central_pressure(x[5])) == ()


def test_central_to_mean_ratio_is_hertz_on_hertz_tables():
    """The ratio solve_impact reads (ContactLaw) is the FEM table's p(0) pi a^2 / P at its
    deepest step: on Hertz's exact table it is Hertz's 3/2, to round-off (1e-14)."""
    hertz = PowerLawContact(PowerLawIndenter.sphere(0.01), 1.0e7)
    depths = np.geomspace(1e-6, 1e-4, 5)  # m
    forces, radii = hertz.force(depths), hertz.contact_radius(depths)
    law = FemContactLaw(depths, forces, radii, hertz.central_pressure(depths), hertz.beta, 1.5)
    assert law.central_to_mean_ratio == pytest.approx(1.5, rel=1e-14)
    kinked = FemContactLaw(depths, forces, radii, 2.0 * forces / (np.pi * radii**2), 1.0, 1.5)
    assert kinked.central_to_mean_ratio == pytest.approx(2.0, rel=1e-14)  # not a constant
