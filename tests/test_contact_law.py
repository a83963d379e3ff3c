"""The tabulated FEM contact law: log-log interpolation, exact for a power law."""

from __future__ import annotations

import numpy as np
import pytest

from shtaerman.study.contact.contact_law import FemContactLaw


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
