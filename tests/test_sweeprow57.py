"""A sweep records a case refused by a validity limit of the model as a row (issue 28, item 4).

A limit (the depth's reach, the striker's speed against the body's waves, a sphere's equator,
a layer's thickness against the contact) raises :class:`~shtaerman.validation.LimitError`, an
InputError: a single run refuses it as before (exit 2, same words), a sweep records its case
"refused" and runs the others. A bad value, or every case refused, still refuses the sweep.

The paper's striker on the dynamic kind's defaults (E2 7.5 MPa, density2 1100: c_s 47.7 m/s)
passes the wave-speed limit at 21.8 m/s (``shtaerman dynamic --velocity 50`` names it); the
case within runs on the coarse settings of tests/test_sweep_profile.py (time_steps 60,
mesh_size 0.05: 1-3 s).
"""

from __future__ import annotations

import contextlib
import csv
import io
import json
import math
import os
import shutil
from dataclasses import replace

import pytest

import shtaerman as sh
from shtaerman.cli import main
from shtaerman.sweep import figures as sweep_figures
from shtaerman.sweep.engine import run_sweep
from shtaerman.sweep.spec import SweepError, load_sweep, parse_sweep
from shtaerman.validation import InputError, LimitError

SWEEP = """name = "fast"
kind = "dynamic"
[parameters]
time_steps = 60
mesh_size = 0.05
{parameters}
[axes]
{axes}
"""
FAST = "velocity = [3.0, 50.0]"
PASSES = "velocity 21.8 m/s would pass"
"""The wave-speed refusal at 50 m/s names the velocity that passes."""


def _file(tmp_path, axes=FAST, parameters=""):
    path = tmp_path / "fast.toml"
    path.write_text(SWEEP.format(parameters=parameters, axes=axes))
    return path


def test_a_limit_is_an_input_error_with_the_cli_words_and_exit_code(capsys):
    striker, body = sh.PowerLawIndenter(5.0, 1.5), sh.Material(7.5e6, 0.5, 1100.0)
    with pytest.raises(LimitError, match=PASSES):
        sh.dynamic(striker, body, mass=0.7, velocity=50.0, estimate=False)
    assert issubclass(LimitError, InputError)
    assert main(["dynamic", "--velocity", "50", "--no-estimate"]) == 2
    said = capsys.readouterr().err
    assert said.startswith("shtaerman: error: --velocity, --density2: 0.7 kg at 50 m/s"), said
    assert PASSES in said and "Traceback" not in said
    with pytest.raises(InputError) as bad:  # a value out of its range is no limit
        sh.dynamic(striker, sh.Material(-1.0, 0.5, 1100.0), mass=0.7, velocity=3.0)
    assert not isinstance(bad.value, LimitError)


@pytest.fixture(scope="module")
def swept(tmp_path_factory):
    """``sweep fast.toml --out DIR --workers 1`` of FAST (one case ok, one refused), run once
    for the two tests below: (the file, DIR, what it printed). Its figures took most of the
    5 CPU s of a run."""
    folder = tmp_path_factory.mktemp("swept")
    path, out, printed = _file(folder), folder / "out", io.StringIO()
    with contextlib.redirect_stdout(printed):
        assert main(["sweep", str(path), "--out", str(out), "--workers", "1"]) == 0
    return path, out, printed.getvalue()


def test_the_refused_case_is_a_row_and_the_others_run(swept):
    path, out, printed = swept
    spec = load_sweep(path)
    assert list(spec.refused) == [1] and spec.refused[1].startswith("velocity, density2: ")
    assert PASSES in spec.refused[1]  # the file's keys, as the load refused the sweep
    line = printed.splitlines()[0]
    assert "2 cases, 1 ok, 0 failed, 1 refused (outside the model's validity) (1 computed" in line
    rows = list(csv.DictReader((out / "cases.csv").open()))
    assert [row["status"] for row in rows] == ["ok", "refused"]
    assert rows[1]["error"] == spec.refused[1]
    assert rows[1]["restitution"] == "" and rows[1]["x_max [m]"] == ""  # no outputs
    assert 0.5 < float(rows[0]["restitution"]) < 1.0  # the case within ran (e = 0.93)
    results = json.loads((out / "results.json").read_text())
    assert results["summary"]["refused"] == 1 and results["summary"]["refused_cases"] == [1]
    assert results["summary"]["failed_cases"] == []
    record = json.loads((out / "cases" / "1.json").read_text())
    assert record["status"] == "refused" and record["outputs"] == {}
    assert (out / "figures" / "restitution.png").is_file()


def test_resume_keeps_the_refused_rows_and_runs_nothing_again(swept, tmp_path, capsys):
    # a copy of the swept folder (its records name no absolute path) and of its file
    path, out = _file(tmp_path), shutil.copytree(swept[1], tmp_path / "out")
    saved = {p.name: p.read_bytes() for p in (out / "cases").glob("*.json")}
    drawn = sorted((out / "figures").iterdir())
    for figure in drawn:  # a time no drawing now can give: a figure drawn again shows
        os.utime(figure, ns=(10**18, 10**18))
    capsys.readouterr()
    assert main(["sweep", str(path), "--out", str(out), "--resume"]) == 0
    assert "nothing to compute, 1 from an earlier run" in capsys.readouterr().out
    assert {p.name: p.read_bytes() for p in (out / "cases").glob("*.json")} == saved
    # the figures of the same results (but for the timings and the file's new path) are kept:
    # drawing them again cost ~5 CPU s of the resume's 5
    assert [figure.stat().st_mtime_ns for figure in drawn] == [10**18] * len(drawn) != []
    path.write_text(SWEEP.format(parameters="", axes="velocity = [3.0, 50.0, 60.0]"))
    assert main(["sweep", str(path), "--out", str(out), "--resume"]) == 0
    line = capsys.readouterr().out
    assert "3 cases, 1 ok, 0 failed, 2 refused" in line and "nothing to compute" in line
    rows = list(csv.DictReader((out / "cases.csv").open()))
    assert [row["status"] for row in rows] == ["ok", "refused", "refused"]
    assert sorted(p.name for p in (out / "cases").iterdir()) == ["0.json", "1.json", "2.json"]


def test_a_saved_refused_case_within_the_limits_at_load_runs_on_resume(tmp_path):
    """Refusal is the load's verdict, made again at each load: a record saved "refused" (by a
    release whose limit was narrower, here a spec told so) is not kept when the case is
    within the limits now."""
    spec = parse_sweep(SWEEP.format(parameters="", axes="velocity = [3.0]"))
    narrower = replace(spec, refused={0: "velocity: beyond an older limit"})
    out = tmp_path / "out"
    first = run_sweep(narrower, out, workers=1, progress=False, figures=False)
    assert (first.refused, first.computed, first.exit_code) == (1, 0, 2)  # all refused: 2
    assert json.loads((out / "cases" / "0.json").read_text())["status"] == "refused"
    again = run_sweep(spec, out, workers=1, resume=True, progress=False, figures=False)
    assert (again.succeeded, again.refused, again.computed) == (1, 0, 1)
    assert json.loads((out / "cases" / "0.json").read_text())["status"] == "ok"
    assert sorted(p.name for p in (out / "cases").iterdir()) == ["0.json"]  # none kept unused


def test_a_finite_strain_case_beyond_the_reach_is_a_refused_row():
    """z = 8 r^1.3 at 0.1 m/s: the ladder to 1.1 x_c reaches x/a 1.5, beyond the 1.2 of the
    finite-strain contact; at 0.01 m/s within (tests/test_sweep_finite_impact.py refuses the
    case alone)."""
    striker = "shape_coefficient = 8.0\nexponent = 1.3\nE2 = 3e6\nnu2 = 0.49\nmass = 0.12"
    text = f'name = "r"\nkind = "finite-strain"\n[parameters]\n{striker}\n[axes]\n'
    spec = parse_sweep(text + "velocity = [0.01, 0.1]\n")
    assert list(spec.refused) == [1]
    said = "shape_coefficient, mass, velocity: the striker z = 8 r^1.3 at 0.12 kg and 0.1 m/s"
    assert spec.refused[1].startswith(said)


def test_every_case_refused_refuses_the_sweep(tmp_path, capsys):
    path = _file(tmp_path, axes="velocity = [50.0, 60.0]")
    assert main(["sweep", str(path), "--out", str(tmp_path / "out")]) == 2
    said = capsys.readouterr().err.strip()
    assert said.startswith(f"shtaerman: error: {path}: case 0 (velocity = 50.0): velocity, ")
    assert said.endswith("(all 2 cases are outside the model's validity)") and "\n" not in said
    assert not (tmp_path / "out").exists()


@pytest.mark.parametrize(
    ("axes", "parameters", "says"),
    [
        # a value out of its range, beside a refused case
        ("velocity = [3.0, 50.0]\nE2 = [7.5e6, -1.0]", "", "axes.E2[1] must lie in"),
        # a combination the check function refuses (no limit), after a refused case
        (
            "velocity = [50.0, 3.0]\nlayer_rate = [5.0, 0.0]",
            "thickness = 0.02",
            "case 1 (velocity = 50.0, layer_rate = 0.0): layer_rate: ",
        ),
    ],
)
@pytest.mark.filterwarnings("ignore:velocity 50 m/s exceeds 5 m/s")  # a layer's x_c, at load
def test_a_bad_value_still_refuses_the_whole_sweep(tmp_path, capsys, axes, parameters, says):
    path = _file(tmp_path, axes=axes, parameters=parameters)
    with pytest.raises(SweepError, match=r"^" + str(path)) as refused:
        load_sweep(path)
    assert says in str(refused.value)
    assert not isinstance(refused.value, LimitError)
    assert main(["sweep", str(path), "--out", str(tmp_path / "out")]) == 2


def _captured(monkeypatch) -> list:
    """The figures :mod:`shtaerman.sweep.figures` saves, kept instead of written."""
    kept: list = []
    monkeypatch.setattr(sweep_figures, "save", lambda figure, path, *_: kept.append(figure))
    return kept


def _results(statuses: list[str], axes: dict) -> dict:
    """A dynamic sweep's results.json content with cases of ``statuses`` (e = 0.9 where ok)."""
    cases = [
        {"index": i, "status": s, "outputs": {"restitution": 0.9} if s == "ok" else {}}
        for i, s in enumerate(statuses)
    ]
    return {
        "spec": {"name": "fast", "kind": "dynamic", "axes": axes},
        "kind": {"outputs": {"restitution": ""}, "parameter_units": {"velocity": "m/s"}},
        "cases": cases,
    }


def test_the_figures_mark_the_refused_cases(monkeypatch, tmp_path):
    kept = _captured(monkeypatch)
    statuses = ["ok", "failed", "refused", "ok"]
    results = _results(statuses, {"velocity": [1.0, 2.0], "nu2": [0.4, 0.5]})
    sweep_figures._heat_map(results, "restitution", "", tmp_path, "png")
    texts = [text.get_text() for text in kept[0].axes[0].texts]
    assert texts == ["0.9", "failed", "refused", "0.9"]  # rows: velocity; columns: nu2
    results = _results(statuses, {"velocity": [1.0, 2.0, 3.0, 4.0]})
    sweep_figures._curve(results, "restitution", "", tmp_path, "png")
    ax = kept[1].axes[0]
    [label] = [text.get_text() for text in ax.get_legend().get_texts()]
    assert label == "refused: outside the model's validity"
    lines = [line for line in ax.lines if line.get_linestyle() in ("--", ":")]
    marked = {line.get_linestyle(): line.get_xdata()[0] for line in lines}
    assert marked == {":": 2.0, "--": 3.0}  # failed dotted, refused dashed
    assert math.isfinite(float(texts[0]))
