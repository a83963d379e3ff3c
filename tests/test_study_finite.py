"""The finite-strain study kind: loading (errors name file and key), one quick run, its checks,
its document, and the files and figures it writes (pictures checked as pictures); its error
estimates from a mesh ladder, in its tables and in the report.

One quick run of the shipped paper case (nu2 = 0.5) serves most of the module (about 5 s of
CPU time: 8 depths on the coarse [quick] mesh); one full run on a ladder whose finest mesh is
that quick mesh (2k/2.4k/3.7k dofs, about 11 s) serves the estimate tests.
"""

import json
import math
import re
from dataclasses import replace

import meshio
import numpy as np
import pytest
from PIL import Image
from study_texts import FINITE_STUDY

from shtaerman.output import text_finite
from shtaerman.output.report import (
    render_markdown,
    report_context,
    results_document,
    study_document,
)
from shtaerman.study.finite.accuracy import CROSSING_KEYS, reported_values
from shtaerman.study.finite.loader import FiniteStudy
from shtaerman.study.finite.runner import depth_at_ratio, ladder
from shtaerman.study.richardson import ORDER_RANGE
from shtaerman.study.run import run_study
from shtaerman.study.schema import StudyError, load_study, shipped_studies
from shtaerman.theory.indenter import PowerLawIndenter

SHIPPED = next(p for p in shipped_studies() if p.stem == "finite_strain")
MINIMAL = FINITE_STUDY


@pytest.fixture(scope="module")
def outcome():
    study = load_study(SHIPPED)[0]
    return run_study(study, quick=True)


@pytest.fixture(scope="module")
def laddered():
    """The shipped paper case, not quick, on the independent ladder (a study file's default)
    whose finest mesh is the quick one."""
    study = load_study(SHIPPED)[0]
    coarse = replace(study, mesh=study.quick_mesh, ladder=study.quick_ladder)
    return run_study(replace(coarse, mesh_ladder="independent"))


@pytest.fixture(scope="module")
def written(outcome, tmp_path_factory):
    from shtaerman.study.kinds import kind_function

    root = tmp_path_factory.mktemp("finite")
    write = kind_function("finite-strain", "write")
    files, figures = write(outcome, root / outcome.study.name, root)
    return root, files, figures


def test_shipped_file_is_the_paper_case_at_two_poisson_ratios():
    studies = load_study(SHIPPED)
    assert [s.name for s in studies] == ["finite-strain-nu0.5", "finite-strain-nu0.3"]
    assert all(isinstance(s, FiniteStudy) and s.kind == "finite-strain" for s in studies)
    assert [s.half_space.poisson_ratio for s in studies] == [0.5, 0.3]
    assert (studies[0].mass, studies[0].velocity, studies[0].ladder.reach) == (0.7, 3.0, 1.1)


def test_minimal_file_takes_the_defaults(tmp_path):
    path = tmp_path / "mine.toml"
    path.write_text(MINIMAL)
    [study] = load_study(path)
    assert study.name == "mine" and study.ladder.steps == 12 and study.quick_ladder.steps == 6


@pytest.mark.parametrize(
    ("change", "key"),
    [
        ("[contact]\nsteps_ = 3\n", "contact.steps_"),
        ("[contact]\ndepth_steps = 3\n", "contact.depth_steps"),
        ('[contact]\nreach = "far"\n', "contact.reach"),
        ("[contact]\nreach = 0.5\n", "contact.reach"),
        ("[quick]\nmesh_size = -1\n", "quick.mesh_size"),
        ("[tolerances]\nconservation = 2\n", "tolerances.conservation"),
        ("[sweep]\nmass = [1.0]\nvelocity = [2.0]\n", "sweep"),
        ("colour = 1\n", "colour"),
    ],
)
def test_load_errors_name_file_and_key(tmp_path, change, key):
    path = tmp_path / "bad.toml"
    text = MINIMAL.replace('kind = "finite-strain"\n', 'kind = "finite-strain"\n' + change)
    if change.startswith("["):
        text = MINIMAL + change
    path.write_text(text)
    with pytest.raises(StudyError) as error:
        load_study(path)
    assert str(path) in str(error.value) and f"'{key}'" in str(error.value)


@pytest.mark.parametrize(
    ("old", "new", "words"),
    [
        ("nu2 = 0.5", "nu2 = -0.2", "nu2"),
        ("exponent = 1.5", "exponent = 1.0", "exponent"),
        ("E2 = 7.5e6", 'E2 = "inf"', "half_space.E2"),
    ],
)
def test_inputs_the_fem_cannot_run_are_refused_at_load(tmp_path, old, new, words):
    path = tmp_path / "bad.toml"
    path.write_text(MINIMAL.replace(old, new))
    with pytest.raises(StudyError, match=words) as error:
        load_study(path)
    assert str(path) in str(error.value)


def test_ladder_starts_at_the_small_strain_depth():
    indenter = PowerLawIndenter(5.0, 1.5)
    depth = depth_at_ratio(indenter, 0.01)
    a = (depth / (indenter.kappa * indenter.shape_coefficient)) ** (1 / 1.5)
    assert depth / a == pytest.approx(0.01, rel=1e-12)  # x = kappa A a^n inverted exactly
    study = load_study(SHIPPED)[0]
    depths = ladder(indenter, 7.5e6 / 0.75, 8.5e-3, study.ladder)
    assert depths[0] == pytest.approx(depth) and depths[-1] == pytest.approx(1.1 * 8.5e-3)
    assert depths.size == 17 and np.all(np.diff(depths) > 0)


def test_quick_study_checks_pass(outcome):
    names = [check.name for check in outcome.checks]
    assert len(names) == 5 and outcome.passed, [c for c in outcome.checks if not c.passed]
    assert any(n.startswith("conservation") for n in names)


def test_findings_name_the_paper_only_for_its_case(outcome):
    assert "moves the paper's impact (0.7 kg at 3 m/s)" in text_finite.study_findings(outcome)[0]
    mine = replace(outcome, study=replace(outcome.study, mass=0.25, velocity=2.0))
    found = " ".join(text_finite.study_findings(mine))
    assert "moves this case's impact (0.25 kg at 2 m/s)" in found and "paper" not in found


def test_rubber_moves_the_impact_the_measured_way(outcome):
    # quick mesh; the default gives x_c +1.69 %, P_c -2.21 %, t_c +1.84 % (README)
    ratios = outcome.ratios()
    assert 1.01 < ratios["x_c"] < 1.025 and 0.97 < ratios["P_c"] < 0.99
    assert 1.01 < ratios["t_c"] < 1.025
    # the same-mesh linear FEM impact is within 0.1 % of the exact one (discretization only)
    fem, exact = outcome.impacts["linear_fem"], outcome.impacts["linear_exact"]
    assert all(abs(fem[k] / exact[k] - 1) < 1e-3 for k in ("x_c", "P_c", "t_c"))


def test_document_is_json_with_tables_and_findings(outcome):
    document = json.loads(json.dumps(study_document(outcome, {}, None, None)))
    assert document["model"] == "neo-hookean" and document["quick"] is True
    for table in document["tables"]:
        assert set(table) == {"title", "header", "rows"}
        assert all(len(row) == len(table["header"]) for row in table["rows"])
        assert all(isinstance(cell, str) for row in table["rows"] for cell in row)
    assert len(document["findings"]) == 4 and "x_c" in document["findings"][0]
    levels = {entry["level"]: entry for entry in document["validity"]}
    assert levels[0.01]["depth_to_radius"] < levels[0.05]["depth_to_radius"]
    assert all(math.isfinite(entry["velocity"]) for entry in levels.values())


def test_write_produces_files_with_units(written, outcome):
    root, files, _ = written
    assert set(files) == {
        "finite_curve",
        "history_linear_exact",
        "history_linear_fem",
        "history_finite_strain",
        "field_at_x_c",
    }
    header = (root / files["finite_curve"]).read_text().splitlines()[0].split(",")
    assert header[:3] == ["depth [m]", "depth_to_radius [1]", "force [N]"]
    history = (root / files["history_finite_strain"]).read_text().splitlines()[0]
    assert history == "t [s],x [m],P [N],a [m],p0 [Pa]"
    mesh = meshio.read(root / files["field_at_x_c"])
    assert "von_mises [Pa]" in mesh.point_data and "displacement [m]" in mesh.point_data
    text = (root / files["field_at_x_c"]).read_text()
    assert 'Name="depth [m]"' in text and 'Name="model_neo-hookean [1]"' in text


def pixels(path):
    return np.asarray(Image.open(path).convert("RGB"), dtype=int)


def count(image, colour, tolerance=16):
    rgb = np.array([int(colour[i : i + 2], 16) for i in (1, 3, 5)])
    return int((np.abs(image - rgb).max(axis=2) <= tolerance).sum())


def test_figures_are_pictures_with_their_colours(written):
    root, _, figures = written
    by_stem = {(root / path).stem: pixels(root / path) for path in figures.values()}
    assert set(by_stem) == {"finite_ratios", "finite_section", "finite_impact"}
    for image in by_stem.values():
        assert image.std() > 12 and np.unique(image.reshape(-1, 3), axis=0).shape[0] > 300
    red, blue = "#d62728", "#1f77b4"
    assert (
        count(by_stem["finite_ratios"], red) > 500 and count(by_stem["finite_ratios"], blue) > 500
    )
    assert count(by_stem["finite_impact"], red) > 500
    section = by_stem["finite_section"]
    assert section.shape == (1000, 1600, 3)
    assert count(section, "#d9d9d9") > 20_000  # the grey indenter
    assert count(section, "#2ca02c") > 500  # the green contact zone on the deformed surface


TINY = {
    "mesh_size": 1 / 20,
    "growth": 0.5,
    "axis_size": 1e-3,
    "axis_growth": 0.4,
    "depth_steps": 4,
    "small_steps": 1,
    "small_ratio": 0.05,
}


def test_sweep_kind_runs_a_tiny_case():
    from shtaerman.sweep.kinds import FINITE_OUTPUTS, get_kind

    kind = get_kind("finite-strain")
    params = {**kind.defaults(), **TINY}
    kind.check(params)
    out = kind.case(params).outputs
    assert set(out) == set(FINITE_OUTPUTS)
    # coarse, yet the physics shows: rubber softens (nu2 = 0.5), x_c grows about 2 %
    assert 0.9 < out["force_ratio_xa75"] < 0.99 and 1.0 < out["x_c_ratio"] < 1.04
    assert math.isnan(out["force_ratio_xa10"]) or 0.98 < out["force_ratio_xa10"] <= 1.01
    assert out["checks_passed"] in (0.0, 1.0)  # the tiny mesh misses the 5e-3 limit at x/a 0.05


def test_sweep_file_of_the_kind_is_checked_up_front(tmp_path):
    from shtaerman.sweep import SweepError, load_sweep

    path = tmp_path / "s.toml"
    path.write_text('name = "f"\nkind = "finite-strain"\n[axes]\nnu2 = [0.5, -0.3]\n')
    with pytest.raises(SweepError, match="nu2"):
        load_sweep(path)
    path.write_text('name = "f"\nkind = "finite-strain"\n[axes]\nnu2 = [0.5, 0.3]\n')
    assert load_sweep(path).name == "f"


def every_estimate(outcome):
    estimates = outcome.estimates
    return [*estimates.scalars.values(), *(e for step in estimates.steps for e in step.values())]


def test_ladder_estimates_have_a_sane_order_or_say_why_not(laddered):
    estimates = laddered.estimates
    assert estimates.refines == pytest.approx([0.5, 2**-0.5, 1.0])
    assert estimates.dofs[0] < estimates.dofs[1] < estimates.dofs[2]
    assert estimates.dofs[-1] == laddered.finite.curve.mesh_stats["dofs"]
    every = every_estimate(laddered)
    richardson = [e for e in every if e.method == "richardson"]
    # observed on this coarse ladder: 7 of 57 Richardson, the rest noise (two-level)
    assert richardson and len(richardson) < len(every)
    assert all(ORDER_RANGE[0] <= e.order <= ORDER_RANGE[1] for e in richardson)
    assert all(e.method == "two-level" and e.reason for e in every if e not in richardson)
    assert all(0 <= e.error < 0.1 for e in estimates.scalars.values())


def test_estimates_are_of_the_finest_values(laddered):
    estimates, values = laddered.estimates, reported_values(laddered)
    for key, estimate in estimates.scalars.items():
        if key != "force_ratio_worst":
            assert estimate.value == values[key], key
    for step, row in zip(estimates.steps, laddered.rows(), strict=True):
        assert all(estimate.value == row[key] for key, estimate in step.items())
    worst = estimates.worst_step()
    assert estimates.scalars["force_ratio_worst"] is estimates.steps[worst]["force_ratio"]
    # Richardson's estimate is the distance to the extrapolated value; the fallback's is the
    # distance to the next coarser level (it extrapolates nothing)
    for e in every_estimate(laddered):
        if e.method == "richardson":
            expected = abs(e.value - e.extrapolated) / abs(e.extrapolated)
            assert e.error == pytest.approx(expected, rel=1e-12)
        else:
            assert e.extrapolated == e.value


def test_crossing_estimates_cover_the_move_of_the_departures(laddered):
    errors = np.array(
        [
            abs(r["force_ratio_fem"]) * s["force_ratio_fem"].error
            for r, s in zip(laddered.rows(), laddered.estimates.steps, strict=True)
        ]
    )
    moved = [laddered.validity(errors), laddered.validity(-errors)]
    for i, entry in enumerate(laddered.limits()):
        assert set(entry["errors"]) == set(CROSSING_KEYS)
        for key in CROSSING_KEYS:
            shift = max(abs(m[i][key] / entry[key] - 1.0) for m in moved)
            assert shift <= entry["errors"][key] < 1.0
        assert 0 < entry["departure_error"] <= errors.max()


def test_tables_and_findings_carry_the_estimates(laddered, outcome):
    curve, impact, validity = text_finite.study_tables(laddered)
    assert all(" ± " in cell for row in curve["rows"] for cell in row[3:8])
    finite = next(row for row in impact["rows"] if row[0] == "neo-Hookean finite strain")
    assert all(" ± " in cell for cell in finite[1:])
    assert all(" ± " in cell for row in impact["rows"][-2:] for cell in row[1:])
    assert all("difference ±" in row[-1] for row in validity["rows"])  # resolved or not
    found = text_finite.study_findings(laddered)
    assert "Richardson" in found[-1] and " ± " in found[0]
    assert "the study's mesh refined by 1/2, 1/sqrt(2) and 1" in found[-1]  # the default ladder
    # every ± of the findings in its value's unit: shifts in percentage points, ratios and
    # crossings as plain numbers (no relative '± 3.8e-02' beside an absolute value)
    assert re.search(r"x_c [+-]\d+\.\d\d ± [\d.]+ %, P_c [+-]\d+\.\d\d ± [\d.]+ %", found[0])
    assert re.search(r"P/\(beta x\^q\) = \d\.\d{4} ± 0\.\d+,", found[1])
    assert not any(re.search(r"± \d(\.\d+)?e-", sentence) for sentence in found[:3])
    # quick mode: one mesh, says so, and shows no error bars
    found, tables = text_finite.study_findings(outcome), text_finite.study_tables(outcome)
    assert outcome.estimates is None and "no error estimates" in found[-1]
    assert not any("±" in cell for t in tables for row in t["rows"] for cell in row)


def test_report_shows_the_finite_rows_with_estimates(laddered):
    entry = study_document(laddered, {}, None, None)
    page = render_markdown(report_context(results_document({"rubber": entry}, quick=False)))
    validity = next(line for line in page.splitlines() if "neo-Hookean rubber" in line)
    assert validity.count("±") + validity.count("not resolved") >= 2
    finite = next(line for line in page.splitlines() if "neo-Hookean finite strain" in line)
    assert finite.count("±") == 6
    assert json.loads(json.dumps(entry))["accuracy"]["mesh_ladder"][2]["refine"] == 1.0


def test_central_pressure_finding_says_p0_is_below_shtaermans(outcome):
    """p(0)/p_avg rises above 2.5 while p(0) itself falls below Shtaerman's: the contact radius
    grows (the finding must not read as a higher central pressure)."""
    at = outcome.at_maximum()
    assert at["central_pressure_ratio"] < 1 < at["central_to_mean"] / 2.5
    assert at["radius_ratio"] > 1
    sentence = text_finite.study_findings(outcome)[1]
    assert "p(0) itself is" in sentence and "% below Shtaerman's at the same depth" in sentence
    assert "contact radius is" in sentence and "% larger" in sentence
