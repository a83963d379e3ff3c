"""The effect table of a sphere or a tabulated profile (issue 29): every variant runs on the
profile, viscoelasticity too (Lee-Radok and Ting hold for any profile; the linear FE impact is
sized on the profile's own viscoelastic impact).

Coarse runs as in tests/test_effects.py (mesh size 0.2, 50 steps, no ladder: about a second
each): a 10 mm sphere with waves and a Prony series runs its FE variants.
"""

import json

import pytest

import shtaerman as sh
from shtaerman.cli import main
from shtaerman.problem import parts

BALL = sh.SphereIndenter(0.01)
BODY = sh.Material(3e6, 0.49, 1000.0)
CASE = dict(mass=0.12, velocity=1.5)
COARSE = dict(mesh_size=0.2, time_steps=50, estimate=False)
ARGV = ("effects", "--sphere-radius", "0.01", "--E2", "3e6", "--nu2", "0.49")
ARGV += ("--mass", "0.12", "--velocity", "1.5", "--density2", "1000", "--prony", "0.3:1e-3")
ARGV += ("--mesh-size", "0.2", "--time-steps", "50", "--no-estimate")


@pytest.fixture(scope="module")
def sphere_table():
    """The table of the sphere with waves and hysteresis (its FE runs, a few seconds)."""
    return sh.effects(parts(BALL, BODY, **CASE, prony="0.3:1e-3"), **COARSE)


def test_every_variant_runs_on_the_sphere(sphere_table):
    table = sphere_table
    assert all(run.refused is None for run in table.runs), [r.refused for r in table.runs]
    ball = sh.impact(BALL, BODY, **CASE)
    # the reference is Sneddon's sphere (the same quadrature), not a power law's
    assert table.reference["P_c"] == ball.P_c
    problem = sh.Problem.impact(BALL, BODY, **CASE)
    alone = sh.dynamic(problem, **COARSE)
    # the same deterministic FE run: equal to the last bit
    assert table.run("waves alone").values["P_max"] == alone.P_max
    assert table.run("without viscoelasticity").values["P_max"] == alone.P_max
    # hysteresis loses energy: the full sphere rebounds lower than the elastic one
    full, elastic = table.run("full").values, table.run("without viscoelasticity").values
    assert full["restitution"] < elastic["restitution"]
    described = table.to_dict()["problem"]["indenter"]
    assert described == {
        "A": None,
        "n": None,
        "profile": {"kind": "sphere", "parameters": {"radius": 0.01}},
    }


def test_the_command_line_runs_the_sphere_with_its_prony(capsys, monkeypatch, sphere_table):
    """The command line asks for the fixture's table (the same problem, the same settings) and
    prints it: the table's FE runs are the fixture's, not run a second time (18 CPU s), and
    test_every_variant_runs_on_the_sphere checks them."""
    import shtaerman.cli.effects as command

    asked = []

    def table(problem, *, progress=None, **options):
        asked.append((problem, options))
        return sphere_table

    monkeypatch.setattr(command, "effects", table)
    assert main([*ARGV, "--json"]) == 0
    [(problem, options)] = asked
    assert problem == parts(BALL, BODY, **CASE, prony="0.3:1e-3")
    assert options == {"refine": 1.0, **COARSE}
    document = json.loads(capsys.readouterr()[0])
    assert "dropped" not in document
    assert document["problem"]["indenter"]["profile"]["kind"] == "sphere"
    full = next(run for run in document["runs"] if run["label"] == "full")
    assert full["values"]["restitution"] < 1.0


@pytest.mark.parametrize(
    ("extra", "says"),
    [
        (("--exponent", "1.3"), "--sphere-radius: give one striker profile"),
        (("--profile", "no.csv"), "--sphere-radius: give one striker profile"),
        (("--sphere-radius", "-1"), "--sphere-radius must"),
    ],
)
def test_a_bad_striker_profile_exits_2_with_one_line(capsys, extra, says):
    argv = [arg for arg in ARGV if arg not in ("--sphere-radius", "0.01")]
    first = ["--sphere-radius", "0.01"] if extra[0] != "--sphere-radius" else []
    assert main([*argv, *first, *extra]) == 2
    _, err = capsys.readouterr()
    lines = err.strip().splitlines()
    assert len(lines) == 1 and says in lines[0], lines
