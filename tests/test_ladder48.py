"""A failed ladder level never aborts the levels that passed, on every route (issue 28, item 5).

Each test forces one level of one ladder to fail as the FEM fails numerically (an unsettled
load step, a Newton that does not converge), runs the route, and compares with the same run
without the failure: the finest level that passed must give the very numbers that level
gives in the full ladder (same mesh, same solver: equal to the last bit), and the reason must
be in the output.
"""

import csv
import io
import json

import numpy as np
import pytest
import study_texts
from ladder_helpers import failing_level
from served_runs import served_impacts
from study_texts import PAPER_CASE

from shtaerman.cli import main
from shtaerman.fem.mesh import MeshSettings
from shtaerman.study.contact import accuracy
from shtaerman.study.contact.accuracy import (
    AccuracyNotReachedWarning,
    estimate_errors,
    run_to_accuracy,
)
from shtaerman.study.dynamic.accuracy import EstimateMissingWarning
from shtaerman.theory.indenter import PowerLawIndenter
from shtaerman.theory.materials import Material

COARSE = {"mesh_size": 0.025, "growth": 0.5, "axis_size": 1e-3, "axis_growth": 0.3}
"""The paper's example on a coarse ladder: 1832, 2517, 3543 dofs (about 0.5 s in all)."""
STUDY = 'name = "pad"\n' + PAPER_CASE + "[numerics]\n"
STUDY += "".join(f"{key} = {value}\n" for key, value in COARSE.items())
WHY = "depth 0.005 m: the contact's stick and slip did not settle"
"""The forced failure's words (:func:`shtaerman.fem.contact.constraints.unsettled`)."""


NO_BUDGET = 86400.0
"""s: the time budget of --accuracy is not what these tests test, and its estimate of the
time to go follows the machine's load (two of them failed under load at the default 60 s)."""


def forces(curve) -> list[float]:
    return [step.force for step in curve.steps]


# --- the contact study ---------------------------------------------------------------------------


def test_a_contact_study_whose_finest_level_fails_reports_the_one_below(tmp_path, monkeypatch):
    from shtaerman.study.contact.runner import run_contact_study
    from shtaerman.study.schema import load_study

    path = tmp_path / "pad.toml"
    path.write_text(STUDY, encoding="utf-8")
    [study] = load_study(path)
    full = run_contact_study(study)
    failing_level(monkeypatch, 3)
    with pytest.warns(EstimateMissingWarning, match="the finest level that passed"):
        cut = run_contact_study(study)
    # the middle level of the full ladder, to the last bit: the same mesh and solve
    assert forces(cut.contact) == forces(full.accuracy.levels[1].result)
    assert cut.accuracy.estimates == {} and WHY in cut.accuracy.missing
    # the study carried on: its impacts on the level that passed, its checks, its report
    assert cut.impacts["fem_tabulated"]["x_c"] > 0 and cut.checks

    out = tmp_path / "out"
    failing_level(monkeypatch, 3)
    code = main(["verify", str(path), "--out", str(out)])  # the whole run, files and reports
    assert code in (0, 1)  # 1: the coarse mesh fails the paper's tolerances, as without it
    entry = json.loads((out / "results.json").read_text())["studies"]["pad"]
    assert WHY in entry["accuracy"]["estimate_missing"]
    assert entry["accuracy"]["error_estimate"] is None
    assert [level["dofs"] for level in entry["accuracy"]["mesh_ladder"]][-1] is None
    assert entry["contact"]["mesh"]["dofs"] == full.accuracy.levels[1].dofs
    for report in ("report.md", "report.html"):
        text = (out / report).read_text()
        assert "no error estimate: a ladder level failed, refine 1: depth 0.005 m" in text


# --- --accuracy ---------------------------------------------------------------------------------

INDENTER, RUBBER = PowerLawIndenter(5.0, 1.5), Material(7.5e6, 0.5)
ACCURACY_MESH = MeshSettings(size=0.025, growth=0.5, axis_size=1e-3, axis_growth=0.3)


def test_a_failure_beyond_the_first_three_levels_ends_the_refinement_unreached(monkeypatch):
    # 5e-4 needs five levels on this mesh (refine 0.5 .. 2: 1832 .. 10791 dofs)
    full = run_to_accuracy(INDENTER, RUBBER, 5e-4, mesh=ACCURACY_MESH, max_time=NO_BUDGET)
    assert len(full.levels) == 5 and not full.unreached
    failing_level(monkeypatch, 5)
    with pytest.warns(AccuracyNotReachedWarning, match="accuracy 0.0005 not reached"):
        cut = run_to_accuracy(INDENTER, RUBBER, 5e-4, mesh=ACCURACY_MESH, max_time=NO_BUDGET)
    assert [level.refine for level in cut.levels] == [level.refine for level in full.levels[:4]]
    assert forces(cut.finest) == forces(full.levels[3].result)
    # the estimate of the last three levels that passed, as the full run had it at level 4
    expected = estimate_errors(full.levels[1:4])
    assert cut.error_estimate() == {key: e.error for key, e in expected.items()}
    assert max(cut.error_estimate()[key] for key in ("force", "beta")) > 5e-4  # refine on
    assert "refine 2 failed" in cut.unreached and WHY in cut.unreached
    document = cut.to_dict()
    assert document["accuracy_unreached"] == cut.unreached
    assert document["error_estimate"]["force"] == expected["force"].error
    assert "accuracy_unreached" not in full.to_dict()  # additive: only where it says why


def test_a_failure_within_the_first_three_levels_leaves_the_estimate_missing(monkeypatch):
    full = run_to_accuracy(INDENTER, RUBBER, 5e-4, mesh=ACCURACY_MESH, max_time=NO_BUDGET)
    failing_level(monkeypatch, 2)
    with pytest.warns(EstimateMissingWarning, match="refine 0.707"):
        cut = run_to_accuracy(INDENTER, RUBBER, 5e-4, mesh=ACCURACY_MESH, max_time=NO_BUDGET)
    assert [level.dofs for level in cut.levels] == [full.levels[0].dofs, full.levels[2].dofs]
    assert forces(cut.finest) == forces(full.levels[2].result)
    assert cut.tolerance == 5e-4 and cut.estimates == {} and WHY in cut.missing


ACCURACY_CLI = ["contact", "--accuracy", "5e-4", "--mesh-size", "0.025", "--growth", "0.5"]
ACCURACY_CLI += ["--max-time", str(NO_BUDGET)]
"""Meets 5e-4 at its fourth level (6572, 11660, 21608, 40711 dofs; force and beta 2.9e-4)."""


def test_the_command_line_says_the_accuracy_was_not_reached_and_why(monkeypatch, capsys):
    failing_level(monkeypatch, 4)
    assert main(ACCURACY_CLI) == 0
    out, err = capsys.readouterr()
    assert "accuracy 0.0005 not reached: the level of refine 1.41 failed" in out, out
    assert "(--refine)" in out and "accuracy target" not in out, out  # in its words; not "met"
    assert "21608 dofs" in out and "ladder 6572, 11660, 21608 dofs" in out, out
    assert "not reached" in err  # the warning
    failing_level(monkeypatch, 4)
    assert main([*ACCURACY_CLI, "--json"]) == 0
    document = json.loads(capsys.readouterr().out)
    assert "refine 1.41 failed" in document["accuracy_unreached"]
    assert document["accuracy_target"] == 5e-4
    assert max(document["error_estimate"][key] for key in ("force", "beta")) > 5e-4


# --- sweeps -------------------------------------------------------------------------------------

LAYER_SWEEP = """
name = "pads"
kind = "layer"
[parameters]
nu2 = 0.5
mesh_size = 0.025
growth = 0.35
axis_size = 1e-3
axis_growth = 0.3
refine = {refine!r}
[axes]
thickness_ratio = [2.0]
"""
"""A layer on a coarse ladder whose middle level (refine 1/sqrt 2) is itself a ladder's finest
(growth 0.35: its coarsest level, refine 1/(2 sqrt 2), keeps every growth below 1)."""
MIDDLE = 1.0 / 2.0**0.5
"""The middle level's refinement as the ladder computes it (1 / LADDER_RATIO)."""


def test_a_layer_case_whose_ladder_loses_a_level_is_an_ok_row_without_estimate(monkeypatch):
    from shtaerman.sweep.engine import cases_csv, execute_case
    from shtaerman.sweep.spec import parse_sweep

    assert MIDDLE == 1.0 / accuracy.LADDER_RATIO  # the same float: the same mesh
    spec = parse_sweep(LAYER_SWEEP.format(refine=1.0))
    [case] = spec.cases()
    [middle] = parse_sweep(LAYER_SWEEP.format(refine=MIDDLE)).cases()
    below = execute_case(spec.kind_spec.case, 0, middle.params)  # in-process, no failure
    # its outputs kept; on this coarse mesh it fails its estimate's check alone (3e-3 > 1e-3)
    assert below["error"].startswith("check failed: layer force ratio error estimate: ")
    assert ";" not in below["error"] and below["estimate_missing"] is None
    failing_level(monkeypatch, 3)
    cut = execute_case(spec.kind_spec.case, 0, case.params)
    assert cut["status"] == "ok", cut["error"]  # not a failed case
    assert WHY in cut["estimate_missing"] and "refine 1:" in cut["estimate_missing"]
    assert any("no error estimate" in text for text in cut["warnings"])
    # the finest level that passed is the middle one: every number of that ladder's finest
    # to the last bit, but the estimate (NaN), its check (left out: passed) and the wall time
    assert cut["outputs"]["checks_passed"] == 1.0
    same = set(below["outputs"]) - {"error_force_ratio", "checks_passed", "seconds"}
    assert {k: cut["outputs"][k] for k in same} == {k: below["outputs"][k] for k in same}
    assert np.isnan(cut["outputs"]["error_force_ratio"])
    rows = list(csv.DictReader(io.StringIO(cases_csv(spec, [case], {0: cut}))))
    assert rows[0]["status"] == "ok" and rows[0]["error"] == ""
    assert WHY in rows[0]["estimate_missing"] and rows[0]["error_force_ratio"] == "nan"


# --- the finite-strain study --------------------------------------------------------------------

FINITE_STUDY = (
    'name = "fs"\n'
    + study_texts.FINITE_STUDY
    + """[contact]
reach = 1.1
depth_steps = 6
small_steps = 2
small_ratio = 0.02
[numerics]
mesh_size = 0.05
growth = 0.45
axis_size = 1e-4
axis_growth = 0.35
"""
)
"""The paper's rubber at finite strain on three coarse independent meshes (about 1.4k, 1.9k
and 2.4k dofs, 8 depths)."""


def test_a_finite_strain_study_whose_finest_level_fails_reports_the_one_below(
    tmp_path, monkeypatch
):
    from shtaerman.fem.hyperelastic import NewtonError
    from shtaerman.output.text_finite import study_findings
    from shtaerman.study.finite import runner
    from shtaerman.study.schema import load_study

    path = tmp_path / "fs.toml"
    path.write_text(FINITE_STUDY, encoding="utf-8")
    [study] = load_study(path)
    real, levels = runner._run_level, []

    def recorded(*args, **kwargs):
        levels.append(real(*args, **kwargs))
        return levels[-1]

    monkeypatch.setattr(runner, "_run_level", recorded)
    full = runner.run_finite_strain_study(study)
    assert full.estimates is not None and not full.estimate_missing and len(levels) == 3
    calls = []

    def failing(*args, **kwargs):
        calls.append(1)
        if len(calls) == 3:  # the finest level, as its Newton fails
            raise NewtonError("depth 9 mm: Newton did not converge in 25 iterations")
        return real(*args, **kwargs)

    monkeypatch.setattr(runner, "_run_level", failing)
    with pytest.warns(EstimateMissingWarning, match="the finest level that passed"):
        cut = runner.run_finite_strain_study(study)
    middle = levels[1]  # the full ladder's middle level: the same mesh, to the last bit
    assert [s.force for s in cut.finite.steps] == [s.force for s in middle.finite.steps]
    assert cut.impacts == middle.impacts and cut.checks == middle.checks
    assert cut.estimates is None and "refine 1: depth 9 mm: Newton" in cut.estimate_missing
    document = json.loads(json.dumps(cut.document()))
    assert document["accuracy"]["estimate_missing"] == cut.estimate_missing
    assert document["accuracy"]["error_estimate"] is None
    dofs = [level["dofs"] for level in document["accuracy"]["mesh_ladder"]]
    assert dofs == [*(lv.finite.curve.mesh_stats["dofs"] for lv in levels[:2]), None]
    said = [text for text in study_findings(cut) if "No error estimate" in text]
    assert len(said) == 1 and "Newton did not converge" in said[0], said
    assert "Quick mode" not in " ".join(study_findings(cut))  # not a quick run's words


# --- the dynamic study --------------------------------------------------------------------------


def test_a_dynamic_study_whose_finest_level_fails_twice_reports_the_one_below(
    tmp_path, monkeypatch
):
    from shtaerman.output.text_dynamic import study_findings, study_tables
    from shtaerman.study.dynamic import case as dynamic_case
    from shtaerman.study.run import run_study
    from shtaerman.study.schema import load_study
    from shtaerman.validation import NumericalFailureError

    path = tmp_path / "coarse.toml"
    path.write_text(study_texts.DYNAMIC_STUDY + "[numerics]\ntime_steps = 100\nmesh_size = 0.05\n")
    [study] = load_study(path)  # levels: size 0.1, 0.0707, 0.05; 50, 71, 100 steps
    real = served_impacts(monkeypatch)  # the cut run's passing levels are the full run's
    full = run_study(study)

    def failing(*args, **kwargs):  # the finest level at 3 m/s, and its retries (200, 400 steps)
        if args[4] == 3.0 and args[5].size == 0.05:
            raise NumericalFailureError("the step equation did not converge at t = 1 ms")
        return real(*args, **kwargs)

    monkeypatch.setattr(dynamic_case, "run_impact", failing)
    with pytest.warns(EstimateMissingWarning, match="failed on its retries too"):
        cut = run_study(study)
    slow, fast = cut.cases
    assert slow.estimated and not fast.estimated  # the other case keeps its estimate
    assert slow.result.summary() == full.cases[0].result.summary()
    # the finest level that passed at 3 m/s: the full ladder's middle level, to the last bit
    assert fast.result.summary() == full.cases[1].ladder.results[1].summary()
    assert "the retry with 200 steps failed too" in fast.ladder.missing
    assert "the retry with 400 steps failed too" in fast.ladder.missing
    document = json.loads(json.dumps(fast.document(), default=str))
    assert "step equation did not converge" in document["estimate_missing"]
    assert [level["dofs"] is None for level in document["mesh_ladder"]] == [False, False, True]
    finding = " ".join(study_findings(cut))
    assert (
        "No error estimates: at v0 = 3 m/s a ladder level failed on its retries too" in finding
    ), finding
    assert "quick run" not in finding
    captions = json.dumps(study_tables(cut))
    assert "at v0 = 3 m/s" in captions and "quick run" not in captions


DYNAMIC_SWEEP = """
name = "tiny"
kind = "dynamic"
[parameters]
time_steps = 100
mesh_size = 0.05
estimate = true
[axes]
velocity = [3.0]
density2 = [1100.0]
"""


def test_a_dynamic_case_whose_ladder_loses_a_level_is_an_ok_row_without_estimate(monkeypatch):
    from shtaerman.study.dynamic import case as dynamic_case
    from shtaerman.sweep.engine import cases_csv, execute_case
    from shtaerman.sweep.kinds import DYNAMIC_ERRORS
    from shtaerman.sweep.spec import parse_sweep
    from shtaerman.validation import NumericalFailureError

    spec = parse_sweep(DYNAMIC_SWEEP)
    [case] = spec.cases()
    real = served_impacts(monkeypatch)  # the cut run's passing levels are the full run's
    full = execute_case(spec.kind_spec.case, 0, case.params)

    def failing(*args, **kwargs):  # the coarsest level (size 0.1), and its retries
        if args[5].size > 0.09:  # 0.05 / (1 / sqrt 2)^2, to round-off
            raise NumericalFailureError("the step equation did not converge at t = 1 ms")
        return real(*args, **kwargs)

    monkeypatch.setattr(dynamic_case, "run_impact", failing)
    cut = execute_case(spec.kind_spec.case, 0, case.params)
    assert cut["status"] == full["status"] == "ok", cut["error"]
    assert "step equation did not converge" in cut["estimate_missing"]
    # the finest level passed: every number as without the failure but the estimates (NaN)
    same = set(full["outputs"]) - set(DYNAMIC_ERRORS) - {"seconds"}
    assert {k: cut["outputs"][k] for k in same} == {k: full["outputs"][k] for k in same}
    assert all(np.isnan(cut["outputs"][name]) for name in DYNAMIC_ERRORS)
    rows = list(csv.DictReader(io.StringIO(cases_csv(spec, [case], {0: cut}))))
    assert "step equation did not converge" in rows[0]["estimate_missing"]
    assert rows[0]["error_x_max"] == "nan" and rows[0]["status"] == "ok"


EFFECTS_SWEEP = """
name = "effects"
kind = "effects"
[parameters]
mesh_size = 0.1
time_steps = 100
density2 = 0.0
thickness = 0.02
estimate = true
[axes]
velocity = [3.0]
"""
"""One effect (a massless pad) on the coarsest ladder the impact allows: the half-space run,
and the pad's (alone = full)."""


def test_an_effects_case_whose_pad_runs_lose_a_level_says_which_and_why(monkeypatch):
    from shtaerman.study.dynamic import case as dynamic_case
    from shtaerman.sweep.engine import execute_case
    from shtaerman.sweep.kinds import EFFECT_QUANTITIES
    from shtaerman.sweep.spec import parse_sweep
    from shtaerman.validation import NumericalFailureError

    spec = parse_sweep(EFFECTS_SWEEP)
    [case] = spec.cases()
    real = served_impacts(monkeypatch)  # the cut run's passing levels are the full run's
    full = execute_case(spec.kind_spec.case, 0, case.params)
    assert full["status"] == "ok" and full["estimate_missing"] is None, full["error"]

    def failing(*args, **kwargs):  # the pad's coarsest level (size 0.2), and its retries
        if args[5].size > 0.19 and kwargs["geometry"].thickness is not None:
            raise NumericalFailureError("the step equation did not converge at t = 1 ms")
        return real(*args, **kwargs)

    monkeypatch.setattr(dynamic_case, "run_impact", failing)
    cut = execute_case(spec.kind_spec.case, 0, case.params)
    assert cut["status"] == "ok", cut["error"]
    missing = cut["estimate_missing"]
    assert missing.startswith(
        "pad alone: no error estimate: a ladder level failed on its retries too"
    )
    assert "; full: no error estimate" in missing and "none:" not in missing  # the pad's only
    assert "step equation did not converge" in missing
    for key in EFFECT_QUANTITIES:  # the finest levels passed: the same changes, no bars
        assert cut["outputs"][f"change_{key}"] == full["outputs"][f"change_{key}"]
        assert cut["outputs"][f"dominant_{key}"] == full["outputs"][f"dominant_{key}"]
        assert np.isnan(cut["outputs"][f"resolved_{key}"])
