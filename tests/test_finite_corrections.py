"""A finite-strain study's ``[corrections]``: the linear dynamic, the massless finite-strain and
the nonlinear dynamic impacts at each velocity, their shifts against the paper's quasi-static
impact, their sum, and the table and finding in the report.

One quick study (the default [quick] contact ladder and mesh; the finite-strain impacts on the
coarse graded mesh of tests/test_finite_dynamic_inertia.py, patched in as their default) serves
the module: one velocity, about 20 s of CPU time.
"""

from __future__ import annotations

import json
import math

import pytest
from study_texts import FINITE_STUDY

from shtaerman.cli import main
from shtaerman.fem.mesh import MeshSettings
from shtaerman.output.report import (
    render_markdown,
    report_context,
    results_document,
    study_document,
)
from shtaerman.output.text_corrections import QUICK_WORDS
from shtaerman.study.finite.corrections import COLUMNS, QUANTITIES
from shtaerman.study.run import run_study
from shtaerman.study.schema import StudyError, load_study, shipped_studies

MINIMAL = 'name = "tiny"\n' + FINITE_STUDY
CORRECTIONS = "[corrections]\nvelocities = [1.0]\ndensity2 = 1100.0\n"
COARSE = MeshSettings(size=0.25, domain=1e3, growth=0.5, axis_size=1e-3, axis_growth=0.25)
"""The coarse graded mesh of the inertia tests, for every finite-strain impact here."""


@pytest.fixture(scope="module")
def outcome(tmp_path_factory):
    import shtaerman.fem.finite_dynamic as finite_dynamic

    path = tmp_path_factory.mktemp("corrections") / "tiny.toml"
    path.write_text(MINIMAL + CORRECTIONS)
    study = load_study(path)[0]
    with pytest.MonkeyPatch.context() as patch:
        patch.setattr(finite_dynamic, "IMPACT_MESH", COARSE)
        lines: list[str] = []
        result = run_study(study, quick=True, progress=lines.append)
    return result, lines


@pytest.mark.parametrize(
    ("table", "key"),
    [
        ("velocities = [0.0]\n", "corrections.velocities"),
        ("velocities = [-1.0, 3.0]\n", "corrections.velocities"),
        ("velocities = []\n", "corrections.velocities"),
        ('velocities = "fast"\n', "corrections.velocities"),
        ("velocities = [true]\n", "corrections.velocities"),
        ("velocities = [1.0, 1.0]\n", "corrections.velocities"),  # twice the cost, no answer
        ('velocities = [1.0]\ndensity2 = "heavy"\n', "corrections.density2"),
        ("velocities = [1.0]\ndensity2 = 0.0\n", "corrections.density2"),
        ("velocities = [1.0]\ndensity2 = -5.0\n", "corrections.density2"),
        ("velocities = [1.0]\ndensity2 = 2e6\n", "corrections.density2"),
        ("density2 = 1100.0\n", "corrections.velocities"),
        ("velocities = [1.0]\ncolour = 1\n", "corrections.colour"),
    ],
)
def test_bad_corrections_table_is_one_line_exit_2(tmp_path, capsys, table, key):
    path = tmp_path / "bad.toml"
    path.write_text(MINIMAL + "[corrections]\n" + table)
    with pytest.raises(StudyError, match=f"'{key}'"):
        load_study(path)
    assert main(["verify", "--quick", "--out", str(tmp_path / "run"), str(path)]) == 2
    err = capsys.readouterr().err
    assert f"bad.toml: key '{key}'" in err and err.count("\n") == 1
    if key == "corrections.density2":  # the range of a body with inertia: 0 is not in it
        assert "expected a density in [1e-06, 1e+06] (kg/m^3" in err and " or 0" not in err
    assert not (tmp_path / "run").exists()


def test_table_is_loaded_and_absent_means_none(tmp_path):
    path = tmp_path / "ok.toml"
    path.write_text(MINIMAL + "[corrections]\nvelocities = [1.0, 3.0]\n")
    corrections = load_study(path)[0].corrections
    assert corrections.velocities == (1.0, 3.0) and corrections.density == 1100.0
    shipped = next(p for p in shipped_studies() if p.stem == "finite_strain")
    assert all(study.corrections is None for study in load_study(shipped))


def test_extended_study_is_the_papers_case():
    from shtaerman.study.schema import studies_folder

    study = load_study(studies_folder() / "extended" / "corrections.toml")[0]
    assert study.corrections.velocities == (0.5, 1.0, 3.0, 5.0)
    assert study.corrections.density == 1100.0
    assert study.rubber.name == "neo-hookean" and study.half_space.poisson_ratio == 0.5
    assert (study.mass, study.indenter.shape_coefficient, study.indenter.exponent) == (
        0.7,
        5.0,
        1.5,
    )


def test_corrections_add_up_by_their_definitions(outcome):
    result, lines = outcome
    data = result.corrections
    assert data["quick"] and data["density2"] == 1100.0 and len(data["rows"]) == 1
    row = data["rows"][0]
    ref, shifts, e = row["reference"], row["shifts"], row["restitution"]
    assert list(shifts) == list(COLUMNS)
    for key, against in QUANTITIES.items():
        for column in ("linear_dynamic", "finite_strain", "nonlinear"):
            # each shift is the reported impact's number against the paper's quasi-static one
            assert shifts[column][key] == row["impacts"][column][key] / ref[against] - 1
        # the sum as independent corrections, exactly
        total = shifts["linear_dynamic"][key] + shifts["finite_strain"][key]
        assert shifts["sum"][key] == total
        # nonlinear - sum in percentage points, the difference of the reported shifts
        assert row["departure"][key] == pytest.approx(
            100 * (shifts["nonlinear"][key] - shifts["sum"][key]), rel=1e-12, abs=1e-12
        )
    assert e["sum"] == e["linear_dynamic"] + e["finite_strain"] - 1
    assert row["departure"]["restitution"] == e["nonlinear"] - e["sum"]
    # the massless body radiates nothing: e = 1 up to the time integration (issue's 5e-4)
    assert e["finite_strain"] == pytest.approx(1.0, abs=5e-4)
    # both wave columns lose energy to the waves, and the finite-strain impact goes deeper
    assert 0.9 < e["linear_dynamic"] < 0.99 and 0.9 < e["nonlinear"] < 0.99
    assert shifts["finite_strain"]["x_max"] > 0 > shifts["linear_dynamic"]["x_max"]
    # the paper's quasi-static reference at 1 m/s, not the study's 3 m/s
    assert ref["x_c"] == pytest.approx(3.7364833635e-3, rel=1e-9)
    # one progress line per impact run
    assert sum("corrections at v0 = 1 m/s" in line for line in lines) == 3


def test_table_and_finding_reach_results_json_and_the_report(outcome):
    result, _ = outcome
    entry = json.loads(json.dumps(study_document(result, {}, None, None)))
    assert entry["corrections"]["rows"][0]["velocity"] == 1.0
    table = entry["tables"][-1]
    assert table["title"].startswith("Do the corrections add?")
    assert [row[1] for row in table["rows"]] == [
        "x_max / x_c - 1",
        "P_max / P_c - 1",
        "t_contact / t_y - 1",
        "e",
    ]
    row = entry["corrections"]["rows"][0]
    assert table["rows"][1][-1] == f"{row['departure']['P_max']:+.2f} pp"
    finding = entry["findings"][-1]
    assert "Do the corrections add?" in finding and " pp at 1 m/s" in finding
    assert finding.endswith(QUICK_WORDS)  # a quick run's departures are not the answer
    assert ("less" in finding) == (
        abs(row["shifts"]["nonlinear"]["P_max"]) < abs(row["shifts"]["sum"]["P_max"])
    )
    page = render_markdown(report_context(results_document({"tiny": entry}, quick=True)))
    line = next(line for line in page.splitlines() if "| P_max / P_c - 1 |" in line)
    assert line.startswith("| 1 m/s |") and line.count(" %") == 4
    assert "Do the corrections add?" in page
    assert all(math.isfinite(v) for v in row["departure"].values())
