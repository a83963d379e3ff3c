"""Session 60's changes tried as an adversary (adv60): what a refusal names runs."""

from __future__ import annotations

import re

import pytest

from shtaerman.cli import main
from shtaerman.fem.finite_dynamic import prepare_finite_impact
from shtaerman.fem.mesh import Geometry
from shtaerman.theory.indenter import PowerLawIndenter
from shtaerman.theory.materials import Material
from shtaerman.validation import LimitError

PAD = ["--model", "neo-hookean", "--velocity", "1e-16", "--thickness", "0.012"]
"""The paper's striker, 0.7 kg, below the finite-strain floor on a 12 mm pad."""


@pytest.mark.parametrize("density", ["0", "1100"])
def test_the_finite_strain_floor_on_a_pad_names_a_velocity_its_layer_takes(capsys, density):
    # it named 4.95e-12 m/s, the half-space's, which the pad then refused: "thickness: must
    # lie in [3.46e-10, 3.45e-05] m at these depths" (exit 2 again, naming no velocity)
    assert main(["dynamic", *PAD, "--density2", density, "--no-estimate"]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "Traceback" not in err, err
    assert "below the 0.001 the finite-strain model is run at" in err
    named = float(re.search(r"raise --velocity to at least about (\S+) m/s", err)[1])
    striker, rubber, pad = PowerLawIndenter(5.0, 1.5), Material(7.5e6, 0.5), Geometry(0.012)
    # sized, meshed and assembled at the named velocity: every check before the time steps
    prepare_finite_impact(striker, rubber, float(density), 0.7, named, geometry=pad)
    # 1 % slower is refused by the pad's thickness range: the named velocity is its edge,
    # not one far inside it (the floor's own, 4.95e-12 m/s, is 1e5 times slower)
    with pytest.raises(LimitError, match="thickness: must lie in"):
        prepare_finite_impact(striker, rubber, float(density), 0.7, 0.99 * named, geometry=pad)


def test_a_depth_just_beyond_the_reach_is_not_printed_as_the_reach():
    # dynamic --model neo-hookean --mass 8.16, the mass the reach's refusal of 1e308 kg names,
    # runs and warned "0.0214499 m is 1.2 contact radii (x/a ...), unverified: the
    # finite-strain contact was validated up to x/a 1.2"
    from shtaerman.guards import MAX_DEPTH_RATIO, depth_ratio, outside_validity

    striker = PowerLawIndenter(5.0, 1.5)
    depth = 0.0214499
    assert MAX_DEPTH_RATIO < depth_ratio(striker, depth) < 1.205  # printed as 1.2 by .3g
    (said,) = outside_validity(striker, depth, None, finite=True)
    shown = float(re.search(r"m is (\S+) contact radii", said)[1])
    assert shown > MAX_DEPTH_RATIO, said


def test_the_reach_floors_velocity_remedy_has_a_float_square(capsys):
    # 1e300 kg at 1e-300 m/s on z = 50 r^3 named "raise --velocity to at least about
    # 3.18e-159 m/s", whose v0^2 = 1e-317 the run refused in turn ("give it a value of a
    # physical size"): the floor's remedy is now at least the velocity whose square is 4 times
    # the smallest normal float, 2.99e-154 m/s, which runs (any faster one is as deep or more)
    import sys

    blunt = ["--mass", "1e300", "--exponent", "3", "--shape-coefficient", "50"]
    assert main(["dynamic", *blunt, "--velocity", "1e-300"]) == 2
    err = capsys.readouterr().err
    named = float(re.search(r"raise --velocity to at least about (\S+) m/s", err)[1])
    assert named**2 >= sys.float_info.min, err
    coarse = ["--mesh-size", "0.2", "--time-steps", "50", "--no-estimate"]
    assert main(["dynamic", *blunt, "--velocity", repr(named), *coarse]) == 0
    capsys.readouterr()
