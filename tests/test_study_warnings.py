"""A study run beyond a validity limit (:mod:`shtaerman.guards`) says so in its files: the
study driver records each ValidityWarning its runs issue, once, in the study's results.json
entry (``warnings``) and in both reports, on every route (sh.run_study, verify in this
process, verify as dask tasks). Before, the warning reached stderr only, and a study outside
a model's limits looked clean in its result folder."""

from __future__ import annotations

import dataclasses
import json
import warnings
from types import SimpleNamespace

import pytest

import shtaerman as sh
import shtaerman.study.run as study_run
from shtaerman.cli import main
from shtaerman.guards import FailedCheckWarning, ValidityWarning
from shtaerman.study.checks import Outcome
from shtaerman.validation import InputError

DEEP = "is 1.26 contact radii (x/a, with Shtaerman's a), far outside small strain"
"""The guard's sentence for the paper's striker pressed to 0.025 m: x/a 1.26 > 1.2
(tests/test_route_identities.py checks the ratio itself)."""


def _study(tmp_path, name: str, depths: str) -> str:
    """The contact study template at ``depths`` on the coarse quick mesh (about 1.5 s CPU),
    tolerances widened so that the coarse mesh passes (the checks are not what is tested)."""
    path = tmp_path / f"{name}.toml"
    assert main(["init-study", str(path), "--kind", "contact"]) == 0
    text = path.read_text().replace('depths = "impact"', f"depths = {depths}")
    text = text.replace("[half_space]", "[quick]\nmesh_size = 0.2\n[half_space]", 1)
    text = text.replace("force = 1e-3", "force = 1e-2")
    text = text.replace("contact_radius = 1e-2", "contact_radius = 5e-2")
    path.write_text(text.replace("[indenter]", f'name = "{name}"\n[indenter]', 1))
    return str(path)


def _reports(out) -> tuple[dict, str, str]:
    results = json.loads((out / "results.json").read_text())
    return results, (out / "report.md").read_text(), (out / "report.html").read_text()


def test_a_study_beyond_a_limit_records_its_warning_in_results_json_and_both_reports(tmp_path):
    path = _study(tmp_path, "deep", "[0.01, 0.025]")
    out = tmp_path / "out"
    with pytest.warns(ValidityWarning) as said:
        ran = sh.run_study(path, out, quick=True)
    [warning] = [w for w in said if issubclass(w.category, ValidityWarning)]  # said once
    assert str(warning.message).startswith(f"{path}: study 'deep': depth: ")  # whose it is
    results, markdown, html = _reports(out)
    [text] = results["studies"]["deep"]["warnings"]
    assert DEEP in text and ran.studies["deep"]["warnings"] == [text]
    assert results["passed"]  # a warning is not a failed check: the numbers are kept
    top, section = markdown.index("## Warnings: runs outside"), markdown.index("### Warnings")
    assert top < markdown.index("## Summary") < markdown.index("## deep: PASS") < section
    assert markdown.count(DEEP) == 2  # the list at the top and the study's own section
    assert html.count("far outside small strain") == 2 and 'id="warnings"' in html


def test_a_study_within_the_limits_records_an_empty_list(tmp_path):
    path = _study(tmp_path, "shallow", "[0.005, 0.01]")  # x/a 0.93 at the deepest
    out = tmp_path / "out"
    with warnings.catch_warnings():
        warnings.simplefilter("error", ValidityWarning)  # none may be issued
        sh.run_study(path, out, quick=True)
    results, markdown, html = _reports(out)
    assert results["studies"]["shallow"]["warnings"] == []
    assert "Warnings" not in markdown and "Warnings" not in html


def test_verify_on_dask_workers_carries_the_warnings_to_its_files_and_stderr(tmp_path, capfd):
    """The studies run in worker processes (verify takes dask for more than one study): the
    warning travels in the entry and is said once, by the verify process."""
    deep = _study(tmp_path, "deep", "[0.01, 0.025]")
    shallow = _study(tmp_path, "shallow", "[0.005, 0.01]")
    out = tmp_path / "out"
    assert main(["verify", "--quick", "--workers", "2", "--out", str(out), deep, shallow]) == 0
    err = capfd.readouterr().err
    assert "2 studies on " in err  # they did run as dask tasks
    assert err.count(DEEP) == 1 and f"{deep}: study 'deep': depth: " in err, err
    results, markdown, _ = _reports(out)
    [text] = results["studies"]["deep"]["warnings"]
    assert DEEP in text and markdown.count(DEEP) == 2
    assert results["studies"]["shallow"]["warnings"] == []


@dataclasses.dataclass(frozen=True)
class _Done(Outcome):
    """A kind's outcome: frozen, with its own fields."""

    study: object
    checks: tuple = ()


def test_the_warnings_are_a_field_of_the_frozen_outcome(monkeypatch):
    """Before, the driver set an attribute on the frozen outcome (object.__setattr__): a copy
    (dataclasses.replace) lost it and an outcome compared equal with and without warnings."""

    def run(study, quick, progress):
        warnings.warn("depth: b", ValidityWarning, stacklevel=1)
        return _Done(study)

    study = _fake_kind(monkeypatch, run)
    with pytest.warns(ValidityWarning):
        outcome = study_run.run_study(study)
    assert outcome.warnings == ("depth: b",)
    assert dataclasses.replace(outcome, checks=()).warnings == ("depth: b",)  # a copy keeps them
    assert outcome != _Done(study)  # the same numbers without the warnings: another outcome
    assert "warnings" in {item.name for item in dataclasses.fields(outcome)}


def _fake_kind(monkeypatch, run) -> SimpleNamespace:
    monkeypatch.setattr(study_run, "kind_function", lambda kind, role: run)
    return SimpleNamespace(kind="contact", name="s", source="s.toml")


def test_the_driver_keeps_each_validity_warning_once_in_order_and_passes_others_on(
    monkeypatch,
):
    def run(study, quick, progress):
        for text in ("depth: b", "thickness: a", "depth: b"):  # a limit passed twice
            warnings.warn(text, ValidityWarning, stacklevel=1)
        warnings.warn("energy: c", FailedCheckWarning, stacklevel=1)
        warnings.warn("not a limit", UserWarning, stacklevel=1)
        return _Done(study)

    study = _fake_kind(monkeypatch, run)
    with warnings.catch_warnings(record=True) as said:
        warnings.simplefilter("always")
        outcome = study_run.run_study(study)
    assert study_run.recorded_warnings(outcome) == ["depth: b", "thickness: a", "energy: c"]
    assert [str(w.message) for w in said] == [
        "s.toml: study 's': depth: b",
        "s.toml: study 's': thickness: a",
        "s.toml: study 's': energy: c",
        "not a limit",
    ]
    assert said[2].category is FailedCheckWarning and said[3].category is UserWarning


def test_the_warnings_before_a_refusal_are_still_said(monkeypatch):
    def run(study, quick, progress):
        warnings.warn("depth: b", ValidityWarning, stacklevel=1)
        raise InputError("depths: too small", "depths")

    study = _fake_kind(monkeypatch, run)
    with pytest.warns(ValidityWarning, match="study 's': depth: b"):
        with pytest.raises(
            InputError, match=r"^s\.toml: study 's': key 'contact.depths': too small$"
        ):
            study_run.run_study(study)
