"""``shtaerman effects`` / :func:`shtaerman.effects`: the effect table of an impact.

Coarse runs (mesh size 0.2, 50 steps, no ladder: about half a second each) of the researcher's
pad (issue 28: z = 8 r^1.3, 0.12 kg at 1.5 m/s, E2 3 MPa, nu2 0.49, 1000 kg/m^3, 12 mm, Prony
0.3:1e-3) with the effects that run today; finite strain takes over a minute per run even on a
coarse mesh and is left to the benchmark.
"""

import csv
import io
import json
import math

import numpy as np
import pytest
from matplotlib.colors import to_rgb
from served_runs import served_impacts

import shtaerman as sh
from shtaerman.api.effect_table.table import QUANTITIES, Cell, dominance
from shtaerman.cli import main
from shtaerman.problem import parts

INDENTER = sh.PowerLawIndenter(8.0, 1.3)
BODY = sh.Material(3e6, 0.49, 1000.0)
CASE = dict(mass=0.12, velocity=1.5)
COARSE = dict(mesh_size=0.2, time_steps=50, estimate=False)
ARGV = ("--exponent", "1.3", "--shape-coefficient", "8", "--E2", "3e6", "--nu2", "0.49")
ARGV += ("--mass", "0.12", "--velocity", "1.5", "--density2", "1000")
ARGV += ("--mesh-size", "0.2", "--time-steps", "50", "--no-estimate")


@pytest.fixture(scope="module", autouse=True)
def served():
    """The module's FE runs by their inputs (tests/served_runs.py): the tables of the command
    line and of the API here share most of their runs (the same variants of one case)."""
    with pytest.MonkeyPatch.context() as patch:
        served_impacts(patch)
        yield


@pytest.fixture(scope="module")
def pad_table():
    """The pad, the waves and the Prony series: eight runs."""
    problem = sh.Problem.impact(INDENTER, BODY, **CASE, thickness=0.012, prony="0.3:1e-3")
    return sh.effects(problem, **COARSE)


RUBBER = dict(thickness=0.012, model="neo-hookean", interface="bonded", friction=0.5)
"""The researcher's full case (issue 28) at 1.5 m/s: its rubber reaches x/a = 2.3, beyond the
finite-strain reach 1.2, which ``shtaerman dynamic`` refuses before any work."""


def test_interaction_closes_the_sum_on_the_real_table(pad_table):
    assert pad_table.effects == ("pad", "waves", "viscoelasticity")
    assert pad_table.absent == ("finite strain", "friction")
    interaction = pad_table.interaction()
    for key in QUANTITIES:
        singles = [pad_table.cells(f"{name} alone")[key].change for name in pad_table.effects]
        full = pad_table.cells("full")[key].change
        # exact by construction: only the round-off of four additions
        assert full == pytest.approx(math.fsum(singles) + interaction[key].change, abs=1e-14)
    # the pad and the Prony series interact: the pad's stiffening is felt by a softer,
    # relaxing body (the coarse run's interaction in t_contact is -2.1 %, its terms +-11 %)
    assert abs(interaction["t_contact"].change) > 0.01


def test_every_effect_off_is_the_papers_impact(pad_table):
    quasi = sh.impact(INDENTER, BODY, **CASE)
    none = pad_table.run("none")
    assert none.cell == "linear, elastic, half-space, frictionless, massless"  # words, not False
    # the coarse FE (size 0.2, 50 steps) is within 0.06 % of the exact Ateb impact; 0.5 %
    # leaves room for the mesh while failing any missed effect (the smallest here is 1.5 %)
    assert none.values["P_max"] == pytest.approx(quasi.P_c, rel=5e-3)
    assert none.values["x_max"] == pytest.approx(quasi.x_c, rel=5e-3)
    assert none.values["t_contact"] == pytest.approx(quasi.t_y, rel=5e-3)
    assert none.values["restitution"] == pytest.approx(1.0, abs=1e-3)  # massless: no loss
    assert pad_table.reference["P_c"] == quasi.P_c  # the reference is sh.impact itself


def test_without_the_error_estimate_every_bar_is_na_and_says_why(pad_table):
    for run in pad_table.runs:
        assert run.errors is None
        assert "estimate was switched off" in run.error_note
    assert pad_table.dominant()["P_max"]["resolved"] is None
    # the Prony series dominates (P_max -15.7 % against the pad's +14.0 %)
    assert pad_table.dominant()["P_max"]["effect"] == "viscoelasticity"


@pytest.mark.parametrize(
    ("full", "says"),
    [
        (RUBBER, "mass, velocity: 0.12 kg at 1.5 m/s drive the striker"),  # x/a beyond 1.2
        ({**RUBBER, "base": "lubricated"}, "base: a layer at finite strain is bonded only"),
    ],
)
def test_a_refused_full_problem_refuses_the_table_before_any_run(full, says):
    """Old code: the linear variants ran (six runs, 17 s on the coarse mesh) before the full
    model was refused, and the table came back with the full row refused."""
    said = []
    with pytest.raises(sh.InputError, match=says):
        sh.effects(parts(INDENTER, BODY, **CASE, **full), **COARSE, progress=said.append)
    assert said == []  # not one run started


def test_the_command_line_refuses_a_refused_full_problem_in_one_line(capsys):
    argv = ["effects", *ARGV, "--thickness", "0.012", "--model", "neo-hookean"]
    argv += ["--interface", "bonded", "--friction", "0.5"]
    assert main(argv) == 2
    printed, err = capsys.readouterr()
    assert printed == "" and len(err.strip().splitlines()) == 1
    assert "--mass, --velocity" in err and "effects: run" not in err


def test_each_distinct_refusal_is_said_once():
    """Old code: the same long refusal was printed in every row it applied to."""
    from shtaerman.api.effect_table.report import table_markdown, table_text
    from shtaerman.api.effect_table.table import EffectTable, Run

    why = "refused: mass, velocity: a reason long enough to fill a line " + "x" * 80
    other = "failed: Newton did not converge"
    values = dict.fromkeys(QUANTITIES, 1.0)
    runs = (
        Run("none", "none", None, "-", values=values),
        Run("finite strain alone", "alone", "finite strain", "-", refused=why),
        Run("full", "full", None, "-", values=values),
        Run("without pad", "without", "pad", "-", refused=why),
        Run("without waves", "without", "waves", "-", refused=other),
    )
    reference = {"P_c": 1.0, "x_c": 1.0, "t_c": 0.5, "t_y": 1.0}
    table = EffectTable(reference, runs, ())
    for text in (table_text(table), table_markdown(table)):
        assert text.count(why) == 1 and text.count(other) == 1
        assert "refused: as finite strain alone" in text


def test_dominance_is_resolved_only_beyond_the_error_bars():
    # 5 +- 1 against 3 +- 0.5: 4 > 3.5, resolved; against 3 +- 1.5: 4 < 4.5, not
    assert dominance({"a": Cell(-5.0, 1.0), "b": Cell(3.0, 0.5)})["resolved"] is True
    assert dominance({"a": Cell(-5.0, 1.0), "b": Cell(3.0, 1.5)})["resolved"] is False
    assert dominance({"a": Cell(5.0, None), "b": Cell(3.0, 0.5)})["resolved"] is None
    assert dominance({"a": Cell(0.5, 1.0)}) == {
        "effect": "a",
        "resolved": False,
        "why": "the only effect that ran",
    }
    assert dominance({"a": Cell(None, None)})["effect"] is None


def test_cli_writes_the_table_as_json_csv_and_markdown(tmp_path, capsys):
    """The waves and friction on the half-space: six rows, four runs (7.5 CPU s; with the pad,
    eight runs and 12.3 CPU s; the pad's table is pad_table's)."""
    out = tmp_path / "table"
    argv = ("effects", *ARGV, "--interface", "bonded", "--friction", "0.5", "--json")
    assert main([*argv, "--out", str(out)]) == 0
    printed, err = capsys.readouterr()
    document = json.loads(printed)
    assert json.loads((out / "effects.json").read_text()) == document
    assert "effects: run 1/6: none: done in" in err  # a progress line per run
    # two effects: "without waves" is "friction alone" and the other way round, run once each
    assert err.count(": the same problem as ") == 2, err
    rows = {
        row["variant"]: row
        for row in csv.DictReader(io.StringIO((out / "effects.csv").read_text()))
    }
    waves = next(run for run in document["runs"] if run["label"] == "waves alone")
    assert float(rows["waves alone"]["P_max"]) == waves["values"]["P_max"]
    full = next(run for run in document["runs"] if run["label"] == "full")
    assert float(rows["full"]["x_max_change"]) == full["changes"]["x_max"]["change"]
    markdown = (out / "effects.md").read_text()
    assert "| waves alone | -1.57 ± n/a |" in markdown  # the coarse run's P_max change
    assert (out / "effects.png").read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"  # and the figure


@pytest.mark.parametrize(
    ("extra", "option"),
    [
        (("--mesh-size", "0.5"), "--mesh-size"),
        (("--interface", "bonded", "--friction", "-1"), "--friction"),
        (("--force",), "--force"),
        (("--model", "rubber"), "--model"),
    ],
)
def test_bad_input_exits_2_with_one_line(capsys, extra, option):
    assert main(["effects", *ARGV, *extra]) == 2
    _, err = capsys.readouterr()
    lines = err.strip().splitlines()
    assert len(lines) == 1 and option in lines[0]


def test_a_failed_out_keeps_the_printed_table(tmp_path, capsys, monkeypatch):
    """A full disk under --out lost the computed table (adversary): it is printed first, and
    the finished runs stay in --out for --resume (adv53: they were removed with the folder)."""
    import errno

    import shtaerman.cli.effects as cli_effects

    def full(table, stage):
        raise OSError(errno.ENOSPC, "No space left on device")

    monkeypatch.setattr(cli_effects, "write_table", full)
    argv = ["effects", *ARGV, "--json", "--out", str(tmp_path / "table")]
    assert main(argv) == 1
    printed, err = capsys.readouterr()
    assert json.loads(printed)["runs"]  # the whole table, on stdout
    assert "No space left on device" in err and err.count(f"--out {tmp_path / 'table'}") == 1
    kept = sorted(p.name for p in (tmp_path / "table").iterdir())
    assert kept == [".shtaerman-folder.json", "incomplete.json"]  # no part of a table file


def test_a_run_keeps_an_option_its_combinations_limit_allows(monkeypatch):
    """The runs' options are tested by shtaerman.problem.check_options, allows included: the
    table once dropped every option a limit names, whatever its value."""
    import shtaerman.api.effect_table.run as run
    import shtaerman.problem as problem

    limit = problem.OptionLimit(
        lambda cell: cell.loading == "inertia",
        ("time_steps",),
        "at most 100 steps here, got {value}",
        lambda value, given: value <= 100,
    )
    for module in (problem, run):  # wherever the table is read from
        monkeypatch.setattr(module, "OPTION_SUPPORT", (limit,), raising=False)
    impact = sh.Problem.impact(INDENTER, BODY, **CASE)
    assert run._options(impact, {"time_steps": 80, "mesh_size": 0.2}) == (
        {"time_steps": 80, "mesh_size": 0.2},
        (),
    )
    assert run._options(impact, {"time_steps": 200, "mesh_size": 0.2}) == (
        {"mesh_size": 0.2},
        ("time_steps not applied: at most 100 steps here, got 200",),
    )


def test_a_run_drops_each_refused_option_once_and_checks_what_is_left(monkeypatch):
    """Two options refused one after the other, then none left: every given option checked,
    each refused one dropped with its note in order, and the empty set checked last (the
    behaviour of the while True loop that the bounded one replaced)."""
    import shtaerman.api.effect_table.run as run
    import shtaerman.problem as problem

    seen = []
    limit = problem.OptionLimit(
        lambda cell: seen.append(None) is None,  # counts the checks of each option
        ("time_steps", "mesh_size"),
        "not here, got {value}",
        lambda value, given: False,
    )
    for module in (problem, run):
        monkeypatch.setattr(module, "OPTION_SUPPORT", (limit,), raising=False)
    impact = sh.Problem.impact(INDENTER, BODY, **CASE)
    assert run._options(impact, {"time_steps": 200, "mesh_size": 0.2}) == (
        {},
        ("time_steps not applied: not here, got 200", "mesh_size not applied: not here, got 0.2"),
    )
    assert len(seen) == 3  # {both}, {mesh_size}, {} : one check per dropped option, one last
    seen.clear()
    assert run._options(impact, {}) == ({}, ())
    assert len(seen) == 1


def test_the_study_reports_headline_table_carries_every_error_bar():
    """Old code: the effects study's table printed the changes without their bars (issue 28
    point 6: each entry carries its error bar), and e - 1 as per cent."""
    from shtaerman.api.effect_table.table import EffectTable, Run
    from shtaerman.output.text_effects import study_tables

    errors = dict.fromkeys(QUANTITIES, 1e-3)
    runs = [
        Run(label, role, None, "-", values=dict.fromkeys(QUANTITIES, 1.1), errors=errors)
        for label, role in (("none", "none"), ("pad alone", "alone"), ("full", "full"))
    ]
    runs[1] = Run(**{**vars(runs[1]), "effect": "pad"})
    reference = {"P_c": 1.0, "x_c": 1.0, "t_c": 0.5, "t_y": 1.0}
    document = {"effects": EffectTable(reference, tuple(runs), ()).to_dict()}
    [table] = study_tables(document)
    for row in table["rows"]:
        assert all(" ± " in cell for cell in row[1:]), row
    full = next(row for row in table["rows"] if row[0] == "full")
    # +10 % ± 0.1 points of P_c; e - 1 = +0.1 ± 0.001 as is, not in per cent
    assert full[1:] == ["+10.00 ± 0.10"] * 3 + ["+0.1000 ± 0.0010"]
    assert table["rows"][-1][0] == "interaction"


def test_the_study_names_every_part_of_its_case():
    """Old code: the effects study's case read "layer bonded; neo-hookean; coulomb", without
    the Prony series or the friction coefficient (issue 28 point 8)."""
    from shtaerman.output.text_effects import case_of

    problem = dict(model="neo-hookean", prony=[(0.3, 1e-3)], geometry="layer bonded")
    problem.update(thickness=0.012, interface="coulomb", friction=0.5)
    assert case_of(problem) == (
        "12 mm pad on a bonded rigid base; neo-Hookean rubber, Prony series g:tau = 0.3:0.001 "
        "s; bonded indenter with Coulomb friction mu = 0.5"
    )
    paper = dict(model="linear", prony=None, geometry="half-space", thickness=None)
    paper.update(interface="frictionless", friction=None)
    assert case_of(paper) == "half-space; linear elastic; frictionless indenter"


def test_the_figure_draws_each_run_and_names_a_run_that_did_not_run(pad_table, tmp_path):
    """effects.png: one bar per run and panel in the role's colour, whiskers where a bar is
    known; a refused run reads "not run" (checked in the SVG twin, whose text is text)."""
    from dataclasses import replace

    from matplotlib.image import imread

    from shtaerman.api.effect_table.figure import COLOURS
    from shtaerman.api.effect_table.table import EffectTable

    runs = tuple(
        replace(run, values=None, errors=None, refused="friction: refused here")
        if run.label == "without pad"
        else run
        for run in pad_table.runs
    )
    table = EffectTable(pad_table.reference, runs, pad_table.absent, pad_table.problem)
    path = table.plot(tmp_path / "effects.png", "svg")
    image = (imread(path)[..., :3] * 255).round()
    for role in ("alone", "full", "without", "interaction"):
        rgb = np.array(to_rgb(COLOURS[role])) * 255
        assert np.all(np.abs(image - rgb) <= 2, axis=-1).sum() > 500, role  # a bar's pixels
    svg = (tmp_path / "effects.svg").read_text()
    assert svg.count("not run") == 4  # the refused run, in each of the four panels
    assert "pad alone" in svg and "interaction" in svg


def test_a_vector_figure_without_out_is_refused(capsys):
    assert main(["effects", *ARGV, "--figure-format", "svg"]) == 2
    _, err = capsys.readouterr()
    assert err.count("\n") == 1 and "--figure-format" in err and "--out" in err


def test_the_figure_names_its_case_its_quantities_and_what_each_colour_is(pad_table, monkeypatch):
    """effects.png says what it shows: a title naming the striker's mass and velocity and
    every part of the case, a panel title per quantity as a change from the paper's value, and
    a legend naming each role drawn in that role's colour and the whiskers (session 53's
    figure had neither title nor legend)."""
    from figure_helpers import capture
    from matplotlib.colors import to_rgba

    from shtaerman.api.effect_table import figure as module

    drawn = capture(monkeypatch, module, lambda: pad_table.plot("effects.png"))
    title = drawn.get_suptitle()
    assert "0.12 kg at 1.5 m/s" in title and "12 mm pad on a bonded rigid base" in title
    assert "Prony series g:tau = 0.3:0.001 s" in title and "frictionless indenter" in title
    assert [panel.get_title() for panel in drawn.axes] == list(module.TITLES.values())
    assert module.TITLES["P_max"] == "P_max / P_c \N{MINUS SIGN} 1 (%)"
    [legend] = drawn.legends
    roles = ("none", "alone", "full", "without", "interaction")
    texts = [text.get_text() for text in legend.get_texts()]
    assert texts == [*(module.LEGEND[role] for role in roles), "estimated error"]
    patches = legend.get_patches()
    assert [p.get_facecolor() for p in patches] == [to_rgba(module.COLOURS[r]) for r in roles]
    assert "whiskers: each run's estimated absolute error" in module.EFFECTS_CAPTION


PAD_ARGV = (*ARGV, "--density2", "0", "--thickness", "0.012")
"""The pad alone (a massless body, the last --density2 counts): two runs, 'full' and 'without
pad' the same problems as 'pad alone' and 'none'."""


def _interrupted(monkeypatch, at: int) -> None:
    """Make the table's run number ``at`` (1-based) a Ctrl-C."""
    import shtaerman.api.effect_table.run as table_run

    real, calls = table_run._run, []

    def run(*args, **kwargs):
        calls.append(None)
        if len(calls) == at:
            raise KeyboardInterrupt
        return real(*args, **kwargs)

    monkeypatch.setattr(table_run, "_run", run)


def _warning_lines(err: str) -> list[str]:
    return [line for line in err.splitlines() if line.startswith("shtaerman: warning:")]


def test_a_resumed_table_says_the_kept_runs_warnings_with_their_runs(tmp_path, capsys, monkeypatch):
    """Adversary 53: incomplete.json kept no run's warnings, so a --resume said the x/a
    warning of every run 'for the runs: quasi-static (paper), pad alone, full' only, the
    kept run 'none' (and 'without pad', its same problem) left out. A resumed table says its
    warnings as the table run in one go says them."""
    assert main(["effects", *PAD_ARGV]) == 0
    whole = _warning_lines(capsys.readouterr().err)
    assert len(whole) == 1 and "(runs:" not in whole[0]  # every run passes x/a 2.27
    out = str(tmp_path / "table")
    with monkeypatch.context() as patched:
        _interrupted(patched, at=2)  # 'none' finished, 'pad alone' stopped
        assert main(["effects", *PAD_ARGV, "--out", out]) == 130
    capsys.readouterr()
    saved = json.loads((tmp_path / "table" / "incomplete.json").read_text())
    entry = saved["studies"]["none"]["entry"]
    assert [name for name, _ in entry["warned"]] == ["shtaerman.guards.ValidityWarning"]
    assert main(["effects", *PAD_ARGV, "--out", out, "--resume"]) == 0
    err = capsys.readouterr().err
    assert "run 1/4: none: kept from an earlier run" in err
    assert _warning_lines(err) == whole
