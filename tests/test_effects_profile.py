"""The effect table of a sphere or a tabulated profile (issue 29): the variants a profile
supports run; viscoelasticity, which a profile refuses in every run that has it
(:data:`shtaerman.problem.PROFILE_SUPPORT`), is dropped in one line before any run.

Coarse runs as in tests/test_effects.py (mesh size 0.2, 50 steps, no ladder: about a second
each): a 10 mm sphere with waves and a Prony series runs two FE variants (none, waves alone).
"""

import json
import warnings

import pytest

import shtaerman as sh
from shtaerman.api.effect_table.report import table_text
from shtaerman.cli import main
from shtaerman.problem import parts

BALL = sh.SphereIndenter(0.01)
BODY = sh.Material(3e6, 0.49, 1000.0)
CASE = dict(mass=0.12, velocity=1.5)
COARSE = dict(mesh_size=0.2, time_steps=50, estimate=False)
ARGV = ("effects", "--sphere-radius", "0.01", "--E2", "3e6", "--nu2", "0.49")
ARGV += ("--mass", "0.12", "--velocity", "1.5", "--density2", "1000", "--prony", "0.3:1e-3")
ARGV += ("--mesh-size", "0.2", "--time-steps", "50", "--no-estimate")
# a sphere's refusal names its radius (commit 8b402f4), a table's names profile
DROPPED = "effects: viscoelasticity dropped (every run with it is refused): sphere_radius: a visco"


@pytest.fixture(scope="module")
def sphere_table():
    """The table and its progress lines and warnings (two FE runs, about 2.5 s)."""
    lines: list[str] = []
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        table = sh.effects(
            parts(BALL, BODY, **CASE, prony="0.3:1e-3"), **COARSE, progress=lines.append
        )
    return table, lines, [str(warning.message) for warning in caught]


def test_a_sphere_drops_viscoelasticity_before_any_run(sphere_table):
    table, lines, said = sphere_table
    # the one line comes first, before the first run's progress line, and once as a warning
    assert lines[0].startswith(DROPPED) and lines[1].startswith("effects: run 1/")
    assert [text for text in said if text.startswith(DROPPED)] == [lines[0]]
    assert list(table.dropped) == ["viscoelasticity"]
    for label in ("viscoelasticity alone", "full", "without waves"):  # each has the prony
        assert table.run(label).refused.startswith("refused: sphere_radius: a viscoelastic body")
    assert "  dropped: viscoelasticity: sphere_radius: a viscoelastic body" in table_text(table)
    assert table.to_dict()["dropped"] == table.dropped


def test_the_variants_a_sphere_supports_run_on_the_sphere(sphere_table):
    table = sphere_table[0]
    ball = sh.impact(BALL, BODY, **CASE)
    # the reference is Sneddon's sphere (the same quadrature), not a power law's
    assert table.reference["P_c"] == ball.P_c
    problem = sh.Problem.impact(BALL, BODY, **CASE)
    alone = sh.dynamic(problem, **COARSE)
    # the same deterministic FE run: equal to the last bit
    assert table.run("waves alone").values["P_max"] == alone.P_max
    assert table.run("without viscoelasticity").values["P_max"] == alone.P_max
    assert table.run("none").values is not None
    described = table.to_dict()["problem"]["indenter"]
    assert described == {
        "A": None,
        "n": None,
        "profile": {"kind": "sphere", "parameters": {"radius": 0.01}},
    }


def test_the_command_line_says_the_drop_first(capsys):
    assert main([*ARGV, "--json"]) == 0
    printed, err = capsys.readouterr()
    assert err.splitlines()[0].startswith(DROPPED)  # before "effects: run 1/6: none ..."
    document = json.loads(printed)
    assert list(document["dropped"]) == ["viscoelasticity"]
    assert document["problem"]["indenter"]["profile"]["kind"] == "sphere"


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
