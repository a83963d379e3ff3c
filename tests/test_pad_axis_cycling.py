"""The thin incompressible pad pressed past x/H = 0.53 (issue 28 item 3: a combination that
failed numerically now runs).

The 4 mm neo-Hookean pad under z = 5 r^1.5 failed at 2.13 mm ("Newton did not converge", at
every step size down to 1e-12 m): the axis node's ring carries ~1e-18 of the force on the axis
grading, its multiplier became round-off and flipped the node in and out of the active set on
every iteration, the corrections at 7e-13 of the depth. The free surface was nowhere near an
instability (smallest in-plane stretch 0.87 beside the contact, Biot's 0.544).
"""

from __future__ import annotations

from types import SimpleNamespace

import numpy as np
import pytest

import shtaerman as sh
from shtaerman.fem.contact.finite import NEWTON_TOLERANCE, NewtonStepper
from shtaerman.theory.indenter import PowerLawIndenter
from shtaerman.theory.materials import Material

DEPTHS = [4e-4, 8e-4, 1.2e-3, 1.6e-3, 2.0e-3, 2.4e-3]  # m: x/H up to 0.6 on the 4 mm pad


def test_the_thin_incompressible_pad_runs_past_x_over_h_053():
    curve = sh.contact(
        PowerLawIndenter(5.0, 1.5),
        Material(7.5e6, 0.5),
        model="neo-hookean",
        depths=DEPTHS,
        thickness=4e-3,
        mesh_size=0.2,
        estimate=False,
    )
    depth = np.array([step["depth"] for step in curve.steps])
    force = np.array([step["force"] for step in curve.steps])
    # before: NewtonError at 2.13 mm; a thin incompressible pad stiffens with depth
    assert np.array_equal(depth, DEPTHS) and np.all(np.diff(force) > 0)
    assert np.all(np.diff(force / np.asarray(DEPTHS)) > 0)


def _stepper() -> SimpleNamespace:
    return SimpleNamespace(tolerance=NEWTON_TOLERANCE)


def test_a_candidate_flipping_on_round_off_leaves_the_set_settled():
    """The cycle measured on the pad: lambda_0 = 1.3e-15 N of P = 484 N, its gap ~1e-19 m."""
    lam = np.array([1.3e-15, 200.0, 284.0, 0.0])
    gap = np.array([-1e-19, 0.0, 0.0, 1e-5])
    active, previous = np.array([True, True, True, False]), np.array([False, True, True, False])
    assert NewtonStepper.settled(_stepper(), active, previous, lam, gap, 2.1e-3)


@pytest.mark.parametrize(
    ("lam_0", "gap_0"),
    [
        (1e-5, 0.0),  # 2e-8 of P: above the tolerance's 1e-8 of it, a force that counts
        (0.0, -1e-10),  # 5e-8 of the depth: a penetration that counts
    ],
)
def test_a_candidate_that_carries_force_or_gap_does_not(lam_0, gap_0):
    lam = np.array([lam_0, 200.0, 284.0, 0.0])
    gap = np.array([gap_0, 0.0, 0.0, 1e-5])
    active, previous = np.array([True, True, True, False]), np.array([False, True, True, False])
    assert not NewtonStepper.settled(_stepper(), active, previous, lam, gap, 2.1e-3)
