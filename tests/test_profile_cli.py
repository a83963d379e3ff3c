"""A striker beyond the power law on the command line and in sh (issue 29 item 1):
``impact``/``contact`` take ``--sphere-radius R`` or ``--profile FILE.csv`` in place of
``--shape-coefficient``/``--exponent``; the JSON names the profile."""

import contextlib
import io
import json
import re

import numpy as np
import pytest
from cli_helpers import error_line

import shtaerman as sh
from shtaerman.cli import main

RUBBER = ("--E2", "7.5e6", "--nu2", "0.5")


def cli_json(*argv):
    """The parsed --json of one in-process CLI run (exit code 0 required)."""
    stream = io.StringIO()
    with contextlib.redirect_stdout(stream):
        code = main([*argv, "--json"])
    assert code == 0
    return json.loads(stream.getvalue())


@pytest.fixture
def paraboloid_csv(tmp_path):
    """z = r^2/(2 R), R = 10 mm, sampled every 0.25 mm to r = 50 mm."""
    r = np.linspace(0.0, 0.05, 201)
    path = tmp_path / "tip.csv"
    np.savetxt(path, np.c_[r, r**2 / 0.02], delimiter=",", header="r,z", comments="")
    return path


def test_impact_on_a_sphere_is_sh_impact_and_names_its_profile():
    document = cli_json("impact", "--sphere-radius", "0.01", *RUBBER)
    steel = sh.Material(2e11, 0.25)  # the CLI's default striker
    ball = sh.impact(
        sh.SphereIndenter(0.01), sh.Material(7.5e6, 0.5), mass=0.7, velocity=3.0, striker=steel
    )
    assert document["profile"] == {"kind": "sphere", "parameters": {"radius": 0.01}}
    assert document["beta"] is None  # no power law: no beta
    for key in ("x_c", "P_c", "a_c", "p_c", "t_c"):
        assert document[key] == getattr(ball, key)  # one computation, printed exactly


def test_impact_on_a_tabulated_paraboloid_is_the_power_law_n_2(paraboloid_csv):
    table = cli_json("impact", "--profile", str(paraboloid_csv), *RUBBER)
    hertz = cli_json("impact", "--shape-coefficient", "50", "--exponent", "2", *RUBBER)
    assert table["profile"]["kind"] == "tabulated"
    assert table["profile"]["parameters"]["points"] == 201
    # the quadrature against the Ateb closed form: x_c, P_c, a_c round-off; t_c 1e-11
    for key in ("x_c", "P_c", "a_c", "p_c", "t_c", "t_y"):
        assert table[key] == pytest.approx(hertz[key], rel=1e-10), key


@pytest.mark.parametrize(
    ("argv", "start"),
    [
        (("--sphere-radius", "0.01", "--exponent", "2"), "--sphere-radius: give one striker"),
        (("--profile", "tip.csv", "--sphere-radius", "0.01"), "--sphere-radius: give one"),
        (("--sphere-radius", "0"), "--sphere-radius must lie in (0, 1e6] m"),
        (("--profile", "/no/such/tip.csv"), "--profile: cannot read '/no/such/tip.csv'"),
    ],
)
def test_profile_options_are_refused_in_one_line(capsys, argv, start):
    for command in ("impact", "contact"):
        assert error_line(capsys, command, *argv).startswith(start)


def test_a_bad_profile_file_names_its_row_on_the_command_line(capsys, tmp_path):
    path = tmp_path / "tip.csv"
    path.write_text("r,z\n0,0\n1e-3,5e-5\n2e-3,nan\n")
    line = error_line(capsys, "impact", "--profile", str(path))
    assert line == f"--profile: '{path}' line 4, column z: expected a finite number in m, got 'nan'"


def test_a_table_too_long_is_refused_without_parsing_the_rest(capsys, tmp_path):
    # every row was parsed first (an 87 MB file of 3e6 rows: 14 CPU s and 1.6 GB to refuse
    # it, 1.4 s after): the row past the most a table takes is the last one read, so a bad
    # value further down is never reached
    path = tmp_path / "tip.csv"
    rows = "".join(f"{k * 1e-5!r},{(k * 1e-5) ** 2!r}\n" for k in range(2001))
    path.write_text("r,z\n" + rows + "0.1,x\n")
    line = error_line(capsys, "impact", "--profile", str(path))
    said = f"--profile: {str(path)!r}: takes at most 2000 rows (r, z), got more than 2000"
    assert line.startswith(said), line


@pytest.mark.parametrize("model", ["linear", "neo-hookean"])
def test_contact_on_a_sphere_writes_its_outputs(tmp_path, model):
    out = tmp_path / "run"
    argv = ["contact", "--sphere-radius", "0.01", "--depths", "1e-3,2e-3", "--no-estimate"]
    assert main([*argv, *RUBBER, "--model", model, "--out", str(out)]) == 0
    document = json.loads((out / "contact.json").read_text())
    assert document["profile"] == {"kind": "sphere", "parameters": {"radius": 0.01}}
    assert document["shape_coefficient"] is None and document["beta_analytic"] > 0
    import meshio

    field = meshio.read(out / "field_max_depth.vtu")
    assert float(field.field_data["indenter_sphere_radius [m]"][0]) == 0.01


@pytest.mark.parametrize("command", ["impact", "contact", "dynamic"])
def test_the_help_names_the_profile_a_csv_file_and_its_row_limit(command, capsys):
    """--profile's metavar was X (a number's) and its help gave no row range."""
    with pytest.raises(SystemExit):
        main([command, "--help"])
    text = " ".join(capsys.readouterr().out.split())
    assert "--profile FILE.csv" in text and "3 to 2000 rows" in text


CASES = [
    # M v0^2 / 2 overflowed in Python's float power: an OverflowError traceback, exit 1
    *(
        (command, ("--sphere-radius", "0.01", "--velocity", "1e308"))
        for command in ("impact", "contact", "dynamic", "effects")
    ),
    # the power law's impact is finite here, but the FE sizes on v0^2 (a traceback, exit 1)
    *((command, ("--velocity", "1e200", "--mass", "1e-300")) for command in ("dynamic", "effects")),
]


@pytest.mark.parametrize(("command", "argv"), CASES)
def test_a_striker_beyond_the_floating_point_range_is_one_line(capsys, command, argv):
    assert main([command, *argv]) == 2
    err = capsys.readouterr().err  # the quasi-static validity warning, then the error
    last = err.strip().splitlines()[-1]
    # adv53: headed by the options that set the number (it began 'mass 0.7 kg and ...')
    assert "Traceback" not in err and re.match(r"shtaerman: error: (--mass, )?--velocity: ", last)
    assert "= inf, outside the floating-point range" in last, last
