"""The neo-Hookean contact on a bonded layer (``contact --model neo-hookean --thickness H``).

At small depth the finite-strain solid is the linear one: the force on the same layer and
mesh (:data:`shtaerman.fem.mesh.FINITE_MESH`) must agree to the FE error, and the
departure must grow in proportion to the strain. The striker is z = 5 r^1.5 pressed until the
geometric contact radius is a = 10 um (strain x/a = 1.6 %).
"""

from __future__ import annotations

import numpy as np
import pytest

import shtaerman as sh
from shtaerman.cli import main
from shtaerman.fem.mesh import FINITE_MESH
from shtaerman.theory.indenter import PowerLawIndenter
from shtaerman.theory.materials import Material
from shtaerman.validation import InputError

INDENTER = PowerLawIndenter(5.0, 1.5)
RADIUS = 1e-5
DEPTH = 5.0 * RADIUS**1.5
DEPTHS = [DEPTH / 4, DEPTH / 2, DEPTH]


def _departure(nu: float, h_over_a: float) -> np.ndarray:
    """Neo-Hookean force / linear force - 1 at DEPTHS on the bonded layer."""
    body, thickness = Material(7.5e6, nu), h_over_a * RADIUS
    common = dict(depths=DEPTHS, thickness=thickness, estimate=False)
    finite = sh.contact(INDENTER, body, model="neo-hookean", **common)
    linear = sh.contact(INDENTER, body, mesh=FINITE_MESH, **common)
    assert finite.mesh["thickness"] == thickness and finite.mesh["base"] == "bonded"
    return finite.force / linear.force - 1.0


def test_thin_compressible_layer_tends_to_the_linear_law_with_the_strain():
    # nu 0.3, H/a 0.3: observed +0.41, +0.92, +1.69 % (strain x/H up to 5 %), a line in the
    # depth through -0.1 % at zero depth: the FE error of the two formulations on one mesh
    departure = _departure(0.3, 0.3)
    slope, zero = np.polyfit(DEPTHS, departure, 1)
    assert abs(zero) < 3e-3
    assert slope > 0 and departure[-1] == pytest.approx(slope * DEPTH, rel=0.2)


def test_incompressible_layer_equals_the_linear_one_at_small_strain():
    # nu 0.5, H/a 1: observed -0.04, -0.13, -0.05 % (no trend: the FE error dominates)
    assert np.max(np.abs(_departure(0.5, 1.0))) < 3e-3


def test_a_lubricated_layer_at_finite_strain_is_refused_in_one_line(capsys):
    body = Material(7.5e6, 0.5)
    with pytest.raises(InputError, match=r"^base: a layer at finite strain is bonded only"):
        sh.contact(INDENTER, body, model="neo-hookean", thickness=1e-5, base="lubricated")
    argv = ["contact", "--model", "neo-hookean", "--thickness", "0.02", "--base", "lubricated"]
    code = main(argv)
    out, err = capsys.readouterr()
    assert code == 2 and out == "" and err.count("\n") == 1 and "bonded only" in err
