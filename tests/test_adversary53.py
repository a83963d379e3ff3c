"""Session 53's new-user and adversary pass over main (025e43b): what it found, fixed."""

import math

import pytest

import shtaerman as sh
from shtaerman.cli import main
from shtaerman.validation import InputError

PAD_STRIKER = sh.PowerLawIndenter(shape_coefficient=8.0, exponent=1.3)  # issue 28's A = 8
RUBBER = sh.Material(youngs_modulus=3e6, poisson_ratio=0.49)


def test_an_overflowing_central_pressure_is_refused_not_printed_as_unbounded(capsys):
    """z = 1e308 r^1.3: a_c = 6.2e-174 m, whose square underflows to 0, so p_c = P_c /
    (pi a_c^2) came out inf; the impact printed 'p_c inf' with the note '(n <= 1: the pressure
    at the centre of the contact is unbounded)' for n = 1.3, and --json gave p_c null, where
    z = 1e-300 r^1.3 (p_c = 0) is refused by the floating-point range. inf is exact only for
    n <= 1 (the cone and sharper), which still gives it."""
    with pytest.raises(InputError, match=r"give p_c = inf, outside the floating-point range"):
        sh.impact(sh.PowerLawIndenter(shape_coefficient=1e308, exponent=1.3), RUBBER,
                  mass=0.12, velocity=1.5)  # fmt: skip
    cone = sh.impact(sh.PowerLawIndenter(shape_coefficient=8.0, exponent=1.0), RUBBER,
                     mass=0.12, velocity=1.5)  # fmt: skip
    assert math.isinf(cone.p_c)  # exact: the cone's central pressure is unbounded
    args = ["impact", "--exponent", "1.3", "--shape-coefficient", "1e308", "--mass", "0.12"]
    assert main(args) == 2
    out, err = capsys.readouterr()
    assert out == "" and err.count("\n") == 1 and "p_c = inf" in err, err


def test_a_viscoelastic_curve_without_a_rate_names_the_option_on_the_command_line(capsys):
    """`contact --prony 0.3:1e-3` said '--rate: ... give rate > 0 m/s': the remedy named the
    keyword, not the option; Python keeps its keyword."""
    assert main(["contact", "--prony", "0.3:1e-3", "--no-estimate"]) == 2
    out, err = capsys.readouterr()
    assert out == "" and err.count("\n") == 1, err
    assert err.rstrip().endswith("is pressed at a speed: give --rate > 0 m/s"), err
    with pytest.raises(InputError, match=r"pressed at a speed: give rate=\.\.\. > 0 m/s$"):
        sh.Problem.curve(PAD_STRIKER, RUBBER, depths=[1e-3], prony="0.3:1e-3")
