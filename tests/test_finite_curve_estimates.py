"""Each depth's error bar of the finite-strain contact curve (``shtaerman.contact``,
study/contact/accuracy.py ``step_estimates``, study/finite/indentation.py ``CURVE_ORDERS``).

The mesh is sized by the deepest depth asked (its refined zone is margin times the deepest
depth's contact radius), so the same depth on two curves of different deepest depths lies on
meshes of different element size; the load path does not matter (the same mesh gives the same
values to 9 digits on three depth ladders: benchmarks/FEM_NOTES.md, "Finite-strain curve per
depth"). About 4 s of CPU time (default mesh, ladders of 4.5k-14k dofs).
"""

from __future__ import annotations

import warnings

import pytest

import shtaerman as sh
from shtaerman.theory.indenter import PowerLawIndenter
from shtaerman.theory.materials import Material

INDENTER = PowerLawIndenter(5.0, 1.5)  # the CLI's defaults: z = 5 r^1.5, E2 7.5 MPa, nu2 0.5
BODY = Material(7.5e6, 0.5)
SHARED = [0.5e-3, 1e-3]  # m


@pytest.fixture(scope="module")
def curves():
    """The curve to 1 mm and the curve to 3 mm (mesh 1.8x coarser at the shared depths)."""
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")  # the validity notes of the deep curve
        return [
            sh.contact(INDENTER, BODY, model="neo-hookean", depths=depths)
            for depths in (SHARED, [*SHARED, 3e-3])
        ]


@pytest.mark.parametrize("key", ["force", "contact_radius", "central_pressure"])
def test_each_depths_error_bars_cover_the_move_with_the_deepest_depth(curves, key):
    """Where both estimates bound their true errors, |Q_1 - Q_3| <= |Q_1 - Q*| + |Q_3 - Q*|
    (the triangle inequality), relative to Q_3 within a factor 1 + 1e-2 (far below the 20 %
    margin left here). On main the contact radius at 0.5 mm moved 4.8e-3 against the curves'
    estimates 4.4e-4 + 3.6e-3: taken at the linear contact's order 2.5, while the finite-strain
    contact edge converges at first order (its curve estimates are now 1.45e-3 + 1.1e-2)."""
    shallow, deep = curves
    for k in range(len(SHARED)):
        moved = abs(getattr(shallow, key)[k] / getattr(deep, key)[k] - 1.0)
        curve = shallow.error_estimate[key] + deep.error_estimate[key]  # the worst depth's
        assert moved <= curve, (key, SHARED[k], moved, curve)
        bars = shallow.step_error_estimate[k][key] + deep.step_error_estimate[k][key]
        assert moved <= bars, (key, SHARED[k], moved, bars)
    assert len(deep.to_dict()["step_error_estimate"]) == 3  # one per depth in the JSON
