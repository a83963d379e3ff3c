"""Where a model holds, in words: a limit never crossed is the end of the range computed (a
lower bound), said plainly and apart from a crossing found inside the range; a finding says
which way the departure moves."""

from types import SimpleNamespace

import pytest
from study_texts import DYNAMIC_STUDY

from shtaerman.output import text_dynamic, text_finite
from shtaerman.output.report import (
    report_context,
    results_document,
    study_document,
    validity_table,
)
from shtaerman.study.limits import thresholds
from shtaerman.study.run import run_study
from shtaerman.study.schema import load_study


def finite_entry(status, ratio=0.547, level=0.01):
    return {
        "level": level,
        "status": status,
        "depth_to_radius": ratio,
        "depth": 3.1e-3,
        "velocity": 1.8,
        "errors": {"depth_to_radius": 0.01, "depth": 0.02, "velocity": 0.03},
        "departure_error": 1e-4,
    }


def dynamic_study(limits, velocities):
    """A dynamic study's results.json entry as the report reads it."""
    return {"kind": "dynamic", "inputs": {"velocities": velocities}, "limits": limits}


def finite_row(entry):
    study = {"kind": "finite-strain", "validity": [entry]}
    return validity_table({"rubber": study})["rows"][0]


def test_a_finite_limit_never_crossed_is_the_deepest_depth_not_a_crossing():
    cell = finite_row(finite_entry("beyond"))[1]
    assert cell.startswith("over the whole range computed (to the deepest depth, x/a = 0.547")
    assert "the limit lies deeper" in cell and "up to x/a" not in cell


def test_a_finite_crossing_inside_the_range_reads_up_to():
    cell = finite_row(finite_entry("interpolated", 0.164))[1]
    assert cell.startswith("up to x/a = 0.164 ± 0.002") and "whole range" not in cell


def test_a_finite_limit_crossed_before_the_first_depth_is_a_no():
    cell = finite_row(finite_entry("below", 0.01))[1]
    assert cell == (
        "not even at the first depth computed (x/a = 0.01 ± 0.0001, depth 3.1 ± 0.06 mm, "
        "reached at v0 = 1.8 ± 0.05 m/s; difference ± 0.01 %)"
    )


def outcome(last_force_ratio, entries):
    rows = [{"force_ratio_fem": 1.0}, {"force_ratio_fem": last_force_ratio}]
    return SimpleNamespace(rows=lambda: rows, limits=lambda: entries)


def test_the_finite_validity_finding_says_which_way_the_force_moves():
    entries = [finite_entry("interpolated", 0.164), finite_entry("beyond", 0.9, 0.05)]
    softer = text_finite._validity_finding(outcome(0.95, entries))
    assert softer.startswith("Real rubber's force falls below the linear beta x^q as the depth")
    assert "to 5 % over the whole range computed (to the deepest depth, x/a = 0.9 ±" in softer
    assert "rises above" in text_finite._validity_finding(outcome(1.08, entries))


def test_the_studys_own_validity_table_gives_plus_minus_in_the_values_unit():
    study = SimpleNamespace(limits=lambda: [finite_entry("interpolated", 0.164)])
    [row] = text_finite._validity_table(study)["rows"]
    assert row == [  # relative errors 1, 2, 3 %; the departure's 1e-4 in percentage points
        "1 %",
        "up to x/a = 0.164 ± 0.002, depth 3.1 ± 0.06 mm, reached at v0 = 1.8 ± 0.05 m/s "
        "(difference ± 0.01 %)",
    ]
    study = SimpleNamespace(limits=lambda: [finite_entry("beyond")])
    assert text_finite._validity_table(study)["rows"][0][1].startswith(
        "over the whole range computed (to the deepest depth,"
    )


def test_a_dynamic_limit_never_crossed_is_the_fastest_velocity():
    limit = thresholds([1.0, 3.0, 5.0], [0.001, 0.002, 0.004], 0.01, errors=[1e-4] * 3)
    assert limit["bound"] == "all"
    words = text_dynamic.velocity_limit(limit, "1%", 1.0)
    assert words.startswith("over the whole range computed (to v0 = 5 m/s, the fastest;")
    assert "up to" not in words
    cell = validity_table({"d": dynamic_study({"x": {"1%": limit}}, [1.0, 3.0, 5.0])})["rows"][0]
    assert cell[1] == words


def case(velocity, x, P, t, lost):
    differences = {"x": x, "P": P, "t": t, "loss_vs_estimate": 0.5}
    result = SimpleNamespace(energy_radiated_fraction=lost)
    return SimpleNamespace(velocity=velocity, differences=lambda: differences, result=result)


def test_dynamic_findings_say_which_way_and_how_it_moves_with_velocity():
    assert text_dynamic._off(0.03, "x", " ± 0.1") == "overestimates x_c by 3.00 ± 0.1 %"
    assert text_dynamic._off(-0.0095, "t", "") == "underestimates t_c by 0.95 %"
    cases = [case(1.0, 0.0132, 0.0216, -0.0042, 0.0656), case(3.0, 0.03, 0.0468, -0.0095, 0.1414)]
    studied = SimpleNamespace(cases=cases)
    assert text_dynamic._trend(studied) == (
        " The largest of the three differences grows with v0: 2.16 % at 1 m/s, 4.68 % at 3 m/s."
    )
    assert text_dynamic._loss_trend(studied) == (
        "; the fraction grows with v0, from 6.56 % at 1 m/s to 14.14 % at 3 m/s"
    )
    single = SimpleNamespace(cases=cases[:1])
    assert text_dynamic._trend(single) == "" and text_dynamic._loss_trend(single) == ""


def test_a_dynamic_limit_inside_the_range_has_the_tables_precision():
    limit = thresholds([0.5, 1.0], [0.0077, 0.013], 0.01, errors=[7e-5, 7e-5])
    # ± in m/s, and the difference's own estimated error named as such
    words = text_dynamic.velocity_limit(limit, "1%", 0.5)
    assert words == "up to v0 = 0.717 ± 0.007 m/s (difference ± 0.007 %)"
    row = validity_table({"d": dynamic_study({"x": {"1%": limit}}, [0.5, 1.0])})["rows"][0]
    assert row[1] == words


def estimate(error, absolute, method="richardson"):
    return SimpleNamespace(error=error, absolute_error=absolute, method=method)


def test_the_dynamic_estimate_finding_names_the_difference_errors_in_percentage_points():
    estimates = {key: estimate(1e-4, 1e-4) for key in text_dynamic.RELATIVE_ESTIMATES}
    estimates |= {f"difference_{k}": estimate(0.1, 0.004 if k == "t" else 1e-4) for k in "xPt"}
    quasi = SimpleNamespace(x_c=1.03, P_c=1.05, t_c=0.5 * 0.99)
    result = SimpleNamespace(x_max=1.0, P_max=1.0, t_contact=1.0)
    case = SimpleNamespace(velocity=3.0, estimates=lambda: estimates, quasi=quasi, result=result)
    ladder = SimpleNamespace(
        settings=[SimpleNamespace(steps=s) for s in (100, 141, 200)],
        results=[SimpleNamespace(mesh={"dofs": d}) for d in (6284, 7795, 11654)],
    )
    studied = SimpleNamespace(
        estimated=True, cases=[case], example=SimpleNamespace(ladder=ladder, velocity=3.0)
    )
    sentence = text_dynamic._estimate_finding(studied)
    assert "of the differences quasi-static / dynamic - 1, at most 0.4 percentage points" in (
        sentence
    )
    assert "(absolute)" not in sentence and "closest: t_c at 3 m/s" in sentence


# --- one wording per limit: the study's table, its findings and the report's table ----------

COARSE_LADDER = "[numerics]\nmesh_size = 0.1\ntime_steps = 100\n"
"""The coarsest dynamic study with its error-estimate ladder (the ladder doubles the mesh size
and halves the time steps): about 5 s of CPU time for the two velocities."""
REPORT_LABELS = {
    "x_c": "x_c",
    "P_c": "P_c",
    "t_c": "t_c",
    "all three": "x_c, P_c and t_c",
}
"""The dynamic study's quantity (its limits table) -> its name in the report's table."""


@pytest.fixture(scope="module")
def dynamic_report(tmp_path_factory):
    """The report context of the paper's striker at 1 and 3 m/s with its ladder: its limits
    resolved (x_c and t_c crossed inside the range, P_c off already at 1 m/s, ...)."""
    path = tmp_path_factory.mktemp("limits") / "waves.toml"
    path.write_text(DYNAMIC_STUDY + COARSE_LADDER)
    (study,) = load_study(path)
    outcome = run_study(study)
    assert outcome.estimated
    document = results_document({"waves": study_document(outcome, {})}, quick=False)
    return report_context(document, {})


def test_a_velocity_limit_reads_the_same_in_table_findings_and_report(dynamic_report):
    """Old code: "up to 0.715 ± 0.007 m/s (difference ± 0.007 %)" in the study's table,
    "up to 0.715 m/s" in its findings and "v0 = 0.715 ± 0.007 m/s" in the report's."""
    (section,) = dynamic_report["studies"]
    table = next(t for t in section["tables"] if t["header"][0] == "quantity")
    report = dynamic_report["validity"]["rows"]
    findings = " ".join(dynamic_report["findings"])
    for quantity, *cells in table["rows"]:
        label = f"quasi-static {REPORT_LABELS[quantity]} against"
        (row,) = [row for row in report if label in row[0]]
        assert row[1:] == cells
        for cell in cells:
            assert f"{quantity} {cell}" in findings, (quantity, cell)
    assert any(cell.startswith("up to v0 = ") for _, *cells in table["rows"] for cell in cells)


@pytest.mark.parametrize(
    "entry",
    [
        finite_entry("interpolated", 0.164),
        finite_entry("beyond", 0.9, 0.05),
        finite_entry("below", 0.01),
        {**finite_entry("interpolated"), "departure_error": 3e-3},  # not resolved at 1 %
        {k: v for k, v in finite_entry("interpolated").items() if "error" not in k},  # quick
    ],
)
def test_a_depth_limit_reads_the_same_in_table_findings_and_report(entry):
    """Old code: "to 1 % up to x/a = 0.164 ± 0.002 (depth 3.1 ± 0.06 mm, reached by an
    impact at 1.8 ± 0.05 m/s)" in the findings, "x/a = 0.164 ± 0.002 (v0 = 1.8 ± 0.05 m/s)"
    in the report's table and the values in columns of their own in the study's table."""
    level = f"{100 * entry['level']:g} %"
    cell = finite_row(entry)[1 if entry["level"] == 0.01 else 2]
    assert [level, cell] in text_finite._validity_table(outcome(0.95, [entry]))["rows"]
    assert f"holds to {level} {cell} (P against" in text_finite._validity_finding(
        outcome(0.95, [entry])
    )
    assert cell.startswith(("up to x/a", "over the whole", "not even at the", "not resolved"))
