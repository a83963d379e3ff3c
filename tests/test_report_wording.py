"""The reports' wording: the paper named only for its own case, no "± 0", one ± convention in
the validity table, and the Ateb figure of each study's exponent."""

import json

import numpy as np
import pytest
from PIL import Image

from shtaerman.output import text_contact, text_finite
from shtaerman.output.folder import finish_verification
from shtaerman.output.report import (
    render_html,
    render_markdown,
    report_context,
    results_document,
    validity_table,
)
from shtaerman.output.wording import plus_minus
from shtaerman.paper.case import is_paper_case, paper_case

PAPER = {
    "shape_coefficient": 5.0,
    "exponent": 1.5,
    "E2": 7.5e6,
    "nu2": 0.5,
    "mass": 0.7,
    "velocity": 3.0,
}
USER = {
    "shape_coefficient": 12.0,
    "exponent": 1.8,
    "E2": 4e6,
    "nu2": 0.49,
    "mass": 0.25,
    "velocity": 2.0,
}


def test_the_paper_case_is_its_worked_example():
    assert paper_case() == PAPER
    assert is_paper_case(PAPER) and is_paper_case(PAPER | {"E1": 2e11, "density2": 1100.0})
    assert not is_paper_case(USER)
    for key, value in USER.items():
        assert not is_paper_case(PAPER | {key: value}), key
    assert not is_paper_case({k: v for k, v in PAPER.items() if k != "mass"})


@pytest.mark.parametrize("error", [0.0, -0.0, None, float("nan")])
def test_an_estimate_of_zero_or_none_prints_no_plus_minus(error):
    assert plus_minus(error) == ""
    assert plus_minus(3.8e-2) == " ± 3.8e-02" and plus_minus(0.2, ".1g", 100) == " ± 2e+01"


def beyond(errors):
    """A finite-strain 1 % entry that holds at every computed depth: the crossing is the last
    depth on every level, so its Richardson estimate is exactly 0."""
    return {
        "level": 0.01,
        "status": "beyond",
        "depth_to_radius": 0.52,
        "depth": 4.1e-3,
        "velocity": 2.75,
        "errors": errors,
        "departure_error": 1e-4,
    }


def test_finite_limits_print_no_zero_estimate():
    entry = beyond({"depth_to_radius": 0.0, "depth": 0.0, "velocity": 0.0})
    row = validity_table({"rubber": {"kind": "finite-strain", "validity": [entry]}})["rows"][0]
    assert row[1] == (  # the departure's own estimate, 1e-4, is not 0: it is given
        "over the whole range computed (to the deepest depth, x/a = 0.52, depth 4.1 mm, reached "
        "at v0 = 2.75 m/s; the limit lies deeper; difference ± 0.01 %)"
    )
    assert row[1] == text_finite.depth_limit(entry) and "± 0 " not in row[1]
    assert "0.0e+00" not in json.dumps(row)


def test_validity_table_uses_one_plus_minus_convention():
    dynamic = {
        "kind": "dynamic",
        "inputs": {"velocities": [1.0, 3.0, 5.0]},
        "limits": {
            "all": {
                "1%": {
                    "velocity": 3.1238,
                    "bound": "interpolated",
                    "error": 3e-4,
                    "resolved": True,
                    "velocity_error": 0.1,
                },
            }
        },
    }
    finite = {"kind": "finite-strain", "validity": [beyond({"depth_to_radius": 0.038})]}
    table = validity_table({"dynamic": dynamic, "rubber": finite})
    assert table["rows"][0][1] == "up to v0 = 3.12 ± 0.1 m/s (difference ± 0.03 %)"
    assert "x/a = 0.52 ± 0.02, depth 4.1 mm" in table["rows"][1][1]  # 0.038 x 0.52, in x/a
    assert "in the value's unit" in table["title"] and "relative" not in table["title"]


def entry(exponent: float) -> dict:
    """A results.json entry of a dynamic study on an indenter of this exponent."""
    return {
        "kind": "dynamic",
        "description": "",
        "inputs": {"exponent": exponent},
        "checks": [],
        "passed": True,
        "seconds": 1.0,
        "tables": [],
        "findings": [],
        "figures": {},
    }


def test_the_ateb_figure_follows_the_studies_exponents(tmp_path):
    results = finish_verification(tmp_path, {"mine": entry(1.8)}, quick=True)
    [(caption, file)] = results["figures"].items()
    assert file == "ateb_n1.8.png" and "n = 1.8" in caption and "paper" not in caption
    image = np.asarray(Image.open(tmp_path / file))
    assert image.shape[:2] == (600, 1480) and image.std() > 10  # a picture, not a blank
    page = (tmp_path / "report.md").read_text(encoding="utf-8")
    assert "ateb_n1.8.png" in page and "ateb.png" not in page and "Tables 1-2" not in page


def test_the_papers_ateb_figure_only_beside_a_paper_exponent(tmp_path):
    results = finish_verification(tmp_path, {"a": entry(1.5), "b": entry(1.5)}, quick=True)
    assert list(results["figures"].values()) == ["ateb.png"]
    assert "Tables 1-2" in next(iter(results["figures"]))


def test_a_report_without_contact_studies_has_no_contact_footnotes(tmp_path):
    results = results_document({"mine": entry(1.8)}, quick=True)
    context = report_context(results)
    for page in (render_markdown(context), render_html(context, tmp_path)):
        assert "Study total (s): wall time of the whole study" in page
        assert "FEM curve" not in page and "mesh-convergence" not in page
        assert "the three impacts" not in page


def test_the_contact_finding_names_each_error_the_same_way():
    study = {
        "contact": {"errors": {"force": 2.1e-4, "beta": 1.3e-4, "central_pressure": 1.8e-4}},
        "accuracy": {"error_estimate": {"force": 2.3e-4, "beta": 1.5e-4}},
    }
    [sentence] = text_contact.findings("paper", study)
    assert sentence == (
        "paper: the FEM reproduces Shtaerman's contact law within a relative 2.1e-04 in the "
        "force, 1.3e-04 in beta and 1.8e-04 in p(0) (the largest errors over the depths, on the "
        "study's mesh); its own error estimate, which needs no exact solution, says 2.3e-04 "
        "(force) and 1.5e-04 (beta)."
    )
