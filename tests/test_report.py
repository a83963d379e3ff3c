"""The reports: a checks table per study, failures first, labelled times, escaped names.

Rendered from the session's quick verify run (tests/conftest.py); variations (a failing check,
hostile study names) are re-rendered from its results document, which holds everything the
reports show.
"""

import copy
import json
from html.parser import HTMLParser

import pytest

from shtaerman.output.report import render_html, render_markdown, report_context, write_reports
from shtaerman.output.report import validity_table as report_validity
from shtaerman.study.limits import LEVELS, thresholds

HOSTILE = 'x" onmouseover="alert(1)<script>alert(2)</script>'


class Elements(HTMLParser):
    """Every start tag with its attributes, and the text, of an HTML page."""

    def __init__(self) -> None:
        super().__init__()
        self.tags: list[tuple[str, dict[str, str | None]]] = []
        self.text: list[str] = []

    def handle_starttag(self, tag, attrs):
        self.tags.append((tag, dict(attrs)))

    def handle_data(self, data):
        self.text.append(data)


def parse(page: str) -> Elements:
    parser = Elements()
    parser.feed(page)
    return parser


@pytest.fixture(scope="module")
def results(quick_verify):
    return quick_verify[2]


def failing(results: dict, name: str = "paper") -> dict:
    """A copy of ``results`` whose study ``name`` fails its contact force check."""
    failed = copy.deepcopy(results)
    study = failed["studies"][name]
    check = next(c for c in study["checks"] if c["name"] == "contact force")
    check["tolerance"], check["passed"] = 1e-9, False
    study["passed"] = failed["passed"] = False
    return failed


def test_results_record_figures_and_labelled_times(results):
    for study in results["studies"].values():
        times = study["timings"]
        assert set(times) == {"fem_curve", "convergence", "computation", "output", "total"}
        # the FEM curve is part of the computation, the computation part of the total
        assert 0 < times["fem_curve"] < times["computation"] < times["total"]
        assert times["computation"] == study["seconds"]
        assert len(study["figures"]) >= 9
    assert results["studies"]["paper"]["timings"]["convergence"] > 0
    # the Ateb functions for each exponent: the paper (n = 3/2) and hertz (n = 2)
    assert list(results["figures"].values()) == ["ateb.png", "ateb_n2.png"]


def test_markdown_has_a_checks_table_per_study(quick_verify):
    _, out, results = quick_verify
    text = (out / "report.md").read_text()
    assert text.count("| check | value (relative) | tolerance | result |") == len(
        results["studies"]
    )
    for study in results["studies"].values():
        for check in study["checks"]:
            assert (
                f"| {check['name']} | {check['value']:.2e} | {check['tolerance']:.1e} | PASS |"
                in (text.replace("\\", ""))
            )
    assert "FEM curve (s)" in text and "study total (s)" in text and "time (s)" not in text
    assert "FAILED" not in text


def test_html_has_a_checks_table_per_study(quick_verify):
    _, out, results = quick_verify
    page = parse((out / "report.html").read_text())
    tables = [attrs.get("class") for tag, attrs in page.tags if tag == "table"]
    assert tables.count("checks") == len(results["studies"])
    assert "FEM curve (s)" in page.text and "study total (s)" in page.text
    assert not any(attrs.get("class") == "failures" for _, attrs in page.tags)


def test_failures_come_first_with_value_and_tolerance(results, quick_verify):
    context = report_context(failing(results))
    markdown = render_markdown(context)
    value = results["studies"]["paper"]["checks"][0]["value"]
    line = f"- **paper**: contact force = {value:.2e} is outside the tolerance ±1.0e-09"
    assert line in markdown
    assert markdown.index("## FAILED checks") < markdown.index("## Summary")
    assert "| contact force | " in markdown and "| 1.0e-09 | FAIL |" in markdown
    page = render_html(context, quick_verify[1])
    first = page.index('<section class="failures"')
    assert first < page.index("<h2>Summary</h2>")
    assert f"contact force = {value:.2e} is outside the tolerance ±1.0e-09" in page
    assert '<tr class="failed"><td>contact force</td>' in page


@pytest.mark.parametrize("name", [HOSTILE, "a<b", 'quote"d', "pipe|name"])
def test_study_names_cannot_inject(results, quick_verify, name):
    hostile = failing(results, "hertz")
    hostile["studies"] = {name: hostile["studies"].pop("hertz"), **hostile["studies"]}
    hostile["studies"][name]["description"] = name
    page = parse(render_html(report_context(hostile), quick_verify[1]))
    # nothing but the report's own markup: no script, no event handler, no stray attribute
    assert [tag for tag, _ in page.tags if tag == "script"] == []
    assert {key for _, attrs in page.tags for key in attrs} <= {
        "lang",
        "charset",
        "name",
        "content",
        "class",
        "id",
        "alt",
        "src",
    }
    # the name is shown as text, whole: heading, summary row, failures, description
    assert "".join(page.text).count(name) >= 4
    markdown = render_markdown(report_context(hostile))
    summary = next(
        line for line in markdown.splitlines() if line.startswith("| ") and "FAIL" in line
    )
    assert summary.count(" | ") == 4  # five cells: a "|" in the name does not add one
    assert "<script>" not in markdown


def test_reports_render_from_the_results_document_alone(quick_verify, tmp_path):
    _, out, results = quick_verify
    for png in out.rglob("*.png"):
        target = tmp_path / png.relative_to(out)
        target.parent.mkdir(parents=True, exist_ok=True)
        target.write_bytes(png.read_bytes())
    reloaded = json.loads(json.dumps(results))
    markdown, page = write_reports(reloaded, tmp_path)
    assert markdown.read_text() == (out / "report.md").read_text()
    assert page.read_text() == (out / "report.html").read_text()


@pytest.mark.parametrize("file", ["../outside.png", "../../etc/passwd", "results.json"])
def test_only_pngs_inside_the_folder_are_embedded(results, quick_verify, file):
    other = copy.deepcopy(results)
    other["figures"] = {"a figure": file}
    with pytest.raises(ValueError, match="not a PNG inside the result folder"):
        render_html(report_context(other), quick_verify[1])


EVERY = (
    "over the whole range computed (to v0 = {} m/s, the fastest; the limit lies beyond; "
    "difference ± {} %)"
)
"""A dynamic limit never crossed: the fastest v0 computed, a lower bound."""


def test_validity_table_from_the_dynamic_and_finite_strain_results():
    # the report's opening table is built from the studies' structured limits, not from prose
    studies = {
        "dynamic": {
            "kind": "dynamic",
            "inputs": {"velocities": [0.5, 1.0, 2.0, 3.0, 4.0, 5.0]},
            "limits": {
                "all": {
                    "1%": {"velocity": None, "bound": "none", "error": 3e-4, "resolved": True},
                    "5%": {
                        "velocity": 3.1238,
                        "bound": "interpolated",
                        "error": 3e-4,
                        "resolved": True,
                    },
                },
                "x": {
                    "1%": {
                        "velocity": 0.7149,
                        "bound": "interpolated",
                        "error": 6e-5,
                        "resolved": True,
                    },
                    "5%": {"velocity": 5.0, "bound": "all", "error": 1e-4, "resolved": True},
                },
                "t": {
                    "1%": {
                        "velocity": 2.94,
                        "bound": "interpolated",
                        "error": 7e-4,
                        "resolved": True,
                    },
                    "5%": {"velocity": 5.0, "bound": "all", "error": 7e-4, "resolved": True},
                },
            },
        },
        "rubber": {
            "kind": "finite-strain",
            "inputs": {"nu2": 0.5},
            "validity": [
                {"level": 0.01, "status": "interpolated", "depth_to_radius": 0.1648}
                | {"depth": 5.54e-5, "velocity": 0.00363},
                {"level": 0.05, "status": "interpolated", "depth_to_radius": 0.8969}
                | {"depth": 8.89e-3, "velocity": 3.125},
            ],
        },
        "paper": {"kind": "contact"},
    }
    rows = report_validity(studies)["rows"]
    assert [row[1:] for row in rows] == [
        [
            "not even at v0 = 0.5 m/s (the slowest computed; difference ± 0.03 %)",
            "up to v0 = 3.12 m/s (difference ± 0.03 %)",
        ],
        ["up to v0 = 0.715 m/s (difference ± 0.006 %)", EVERY.format(5, 0.01)],
        ["up to v0 = 2.94 m/s (difference ± 0.07 %)", EVERY.format(5, 0.07)],  # the t_c row
        [
            "up to x/a = 0.165, depth 0.0554 mm, reached at v0 = 0.00363 m/s (no error estimate)",
            "up to x/a = 0.897, depth 8.89 mm, reached at v0 = 3.12 m/s (no error estimate)",
        ],
    ]
    assert "t_c" in rows[2][0] and "nu2 = 0.5" in rows[3][0]
    assert report_validity({"paper": {"kind": "contact"}}) is None


def test_validity_table_states_a_dynamic_limit_only_where_resolved():
    # the study's thresholds decide "resolved" (error < level / 5); a fabricated estimate of
    # 0.3 % against the 1 % level (> 0.2 %) and a study without estimates are not stated
    limits = {
        "1%": thresholds([0.5, 1.0], [0.005, 0.02], 0.01, errors=[3e-3, 1e-4]),
        "5%": thresholds([0.5, 1.0], [0.005, 0.02], 0.05, errors=[3e-3, 1e-4]),
    }
    assert limits["1%"]["resolved"] is False and limits["5%"]["resolved"] is True
    unestimated = {f"{level:.0%}": thresholds([0.5, 1.0], [0.005, 0.02], level) for level in LEVELS}
    inputs = {"velocities": [0.5, 1.0]}
    studies = {
        "dynamic": {"kind": "dynamic", "inputs": inputs, "limits": {"all": limits}},
        "quick": {"kind": "dynamic", "inputs": inputs, "limits": {"all": unestimated}},
    }
    table = report_validity(studies)
    assert [row[1:] for row in table["rows"]] == [
        ["not resolved (difference ± 0.3 %, not below a fifth of 1 %)", EVERY.format(1, 0.01)],
        ["not resolved (no error estimate)", "not resolved (no error estimate)"],
    ]
    assert (
        "the estimated FEM error of the difference where the limit is decided, in percentage "
        "points; stated only where it is below a fifth of the level" in table["title"]
    )


def crossing(level, departure_error):
    """A finite-strain validity entry with estimates (the default run's 1 % one, nu2 = 0.5)."""
    return {
        "level": level,
        "status": "interpolated",
        "depth_to_radius": 0.1636,
        "depth": 1.23e-3,
        "velocity": 0.00363,
        "errors": {"depth_to_radius": 0.038, "depth": 0.11, "velocity": 0.15},
        "departure_error": departure_error,
    }


@pytest.mark.parametrize(
    ("level", "departure_error", "resolved"),
    [(0.01, 4.1e-4, True), (0.01, 1.99e-3, True), (0.01, 2.01e-3, False), (0.05, 0.012, False)],
)
def test_finite_depth_limits_stated_only_where_the_error_is_below_a_fifth(
    level, departure_error, resolved
):
    study = {"kind": "finite-strain", "validity": [crossing(level, departure_error)]}
    table = report_validity({"rubber": study})
    cell = table["rows"][0][1 if level == 0.01 else 2]
    if resolved:
        # ± in the value's unit, as the dynamic limits' "up to v0 = 3.12 ± 0.1 m/s"
        assert cell == (
            "up to x/a = 0.164 ± 0.006, depth 1.23 ± 0.1 mm, reached at v0 = 0.00363 ± 0.0005 "
            f"m/s (difference ± {100 * departure_error:.1g} %)"
        )
    else:
        fifth = f"not below a fifth of {100 * level:g} %"
        assert cell == f"not resolved (difference ± {100 * departure_error:.2g} %, {fifth})"
    assert "fifth of the level" in table["title"] and "10-100" not in table["title"]
