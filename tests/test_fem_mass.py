"""The contact dofs' mass given back to their neighbours (`redistribute_normal_mass`)."""

import math

import numpy as np
import pytest
import scipy.sparse as sp

from shtaerman.fem.elasticity import redistribute_normal_mass


def test_the_mass_given_back_is_the_mass_taken_to_its_own_round_off():
    # two contact dofs (0, 1) coupled to two neighbours (2, 3) of a body whose far field (4..7)
    # is 1e10 times heavier: the mesh of a dynamic run, where the contact nodes carry ~1e-14
    # of the total. Differencing the two totals lost eps M_total / lost ~ 1e-3 of it (4.5 %
    # on the stepper history's mesh); summed from the removed entries it is exact to a few eps
    # of the removed entries (measured 0), whatever order a library sums in.
    diagonal = np.array([0.1, 0.3, 0.7, 0.9, 1e10 / 3, 1e10 / 7, 1e10 / 9, 1e10 / 11])
    mass = sp.diags(diagonal).tolil()
    for i, j, value in [(0, 2, 0.05), (1, 3, -0.02), (0, 1, 0.01), (4, 5, 1e9 / 13)]:
        mass[i, j] = mass[j, i] = value
    mass = mass.tocsr()
    contact = np.array([0, 1])
    taken = 2 * math.fsum(mass[contact].data) - math.fsum(mass[contact][:, contact].data)
    result = redistribute_normal_mass(mass, contact)
    given = result.diagonal() - mass.diagonal()
    assert np.all(result[contact].data == 0) and np.all(given[4:] == 0)
    # the two neighbours share it in proportion to their diagonals (0.7 : 0.9)
    assert given[2:4] == pytest.approx(taken * np.array([0.7, 0.9]) / 1.6, rel=1e-14, abs=0.0)
