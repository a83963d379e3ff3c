"""The verification report: results.json, and report.md and a self-contained report.html.

Reads study outcomes and figure files; computes nothing of its own. Each kind's text (tables,
findings, times) comes from its text module (:data:`TEXTS`). Both reports are jinja2
templates shipped in the package (``templates/report.md.j2``, ``templates/report.html.j2``),
rendered from one context built once from the results document by :func:`report_context`.
HTML autoescaping is on: study names and descriptions cannot inject markup; the Markdown
template escapes the characters Markdown would read as markup.
"""

from __future__ import annotations

import base64
import datetime as dt
import importlib.metadata
import os
import platform
import re
import urllib.parse
from collections.abc import Callable, Mapping
from functools import cache
from pathlib import Path
from types import ModuleType
from typing import Any

import jinja2

from ..study.run import recorded_warnings
from ..version import __version__
from . import text_contact, text_dynamic, text_effects, text_finite
from .entry import no_summary_row, stored_findings, stored_tables
from .files import json_safe
from .wording import number, seconds, times_text

__all__ = [
    "TEXTS",
    "environment",
    "render_html",
    "render_markdown",
    "report_context",
    "results_document",
    "study_document",
    "validity_table",
    "write_reports",
]

PACKAGES = (
    "numpy",
    "scipy",
    "scikit-fem",
    "gmsh",
    "meshio",
    "pyvista",
    "vtk",
    "matplotlib",
    "pymetis",
    "jinja2",
)
TEXTS: dict[str, ModuleType] = {
    "contact": text_contact,
    "dynamic": text_dynamic,
    "finite-strain": text_finite,
    "effects": text_effects,
}
"""Study kind -> its text module: ``entry``, and where the kind has its own, ``tables``,
``findings``, ``timing_text``, ``validity_rows`` and ``summary_row`` (:data:`DEFAULTS`)."""
SUMMARY_LEGEND = (
    "Contact columns: the largest relative error over the depths against Shtaerman's exact "
    "solution. Impact columns: the largest relative difference of the two FEM-fed impacts "
    "(FEM-fitted beta through the Ateb solution; tabulated FEM P(x) integrated numerically) "
    "against the exact impact. Each study's checks below give every value with its tolerance."
)
TIMING_LEGEND = (
    "Study total (s): wall time of the whole study, its computation and the writing of its "
    "files and figures."
)
CONTACT_TIMING_LEGEND = (
    "FEM curve (s): meshing, assembly, factorization and contact solves of the study's depth "
    "ladder; its study total adds the fits, the three impacts and the mesh-convergence study "
    "if any."
)
"""Legends of the summary (every kind) and of the contact cross-check (contact studies only)."""


def environment() -> dict[str, object]:
    """Versions and the machine, for the record."""
    versions = {}
    for name in PACKAGES:
        try:
            versions[name] = importlib.metadata.version(name)
        except importlib.metadata.PackageNotFoundError:
            versions[name] = None
    return {
        "shtaerman": __version__,
        "python": platform.python_version(),
        "platform": platform.platform(),
        "cpu_count": os.cpu_count(),
        "packages": versions,
    }


def study_document(
    outcome: Any,
    files: dict[str, str],
    output_seconds: float | None = None,
    figures: Mapping[str, str] | None = None,
) -> dict[str, object]:
    """One study's entry of results.json, by its kind's text module (:data:`TEXTS`).

    ``files``: stem to path and ``figures``: caption to PNG path, both relative to the result
    folder; ``output_seconds``: the time spent writing them (s), if known. ``warnings``: the
    validity warnings the study's runs issued, once each (:func:`~shtaerman.study.run.run_study`
    records them; [] within every limit).
    """
    kind = getattr(outcome.study, "kind", "contact")
    entry = TEXTS[kind].entry(outcome, files, output_seconds, figures)
    return {**entry, "warnings": recorded_warnings(outcome)}


def results_document(
    entries: Mapping[str, dict],
    *,
    quick: bool,
    figures: Mapping[str, str] | None = None,
) -> dict[str, object]:
    """The whole results.json (strict JSON: non-finite numbers are null).

    ``entries``: per study name, in order, its entry (:func:`study_document`).
    ``figures``: caption to PNG path relative to the result folder of the figures that belong
    to no study. The reports are rendered from this document alone.
    """
    return json_safe(
        {
            "studies": dict(entries),
            "figures": dict(figures or {}),
            "passed": all(entry["passed"] for entry in entries.values()),
            "quick": quick,
            "generated": dt.datetime.now(dt.UTC).isoformat(timespec="seconds"),
            "environment": environment(),
        }
    )


# --- the context both reports are rendered from ----------------------------------------------


DEFAULTS: dict[str, Callable[..., Any]] = {
    "tables": stored_tables,
    "findings": stored_findings,
    "timing_text": times_text,
    "summary_row": no_summary_row,
    "validity_rows": lambda name, study: [],
}
"""What a kind's text module that does not define one of these functions shows: the tables
and findings its entry stores, the common times, no cross-check row, no validity rows."""


def _study_text(study: Mapping[str, Any], part: str) -> Callable[..., Any]:
    """The function ``part`` of the study's kind's text module, else :data:`DEFAULTS`'."""
    return getattr(TEXTS[study.get("kind", "contact")], part, DEFAULTS[part])


def _summary_row(name: str, study: dict) -> list[str]:
    checks = study["checks"]
    worst = max(checks, key=lambda c: abs(c["value"] or 0.0) / c["tolerance"], default=None)
    timings = study.get("timings") or {}
    return [
        name,
        study.get("kind", "contact"),
        "PASS" if study["passed"] else "FAIL",
        "-"
        if worst is None
        else f"{worst['name']}: {number(abs(worst['value'] or 0.0), '.1e')}"
        f" / {number(worst['tolerance'], '.0e')}",
        seconds(timings.get("total", study.get("seconds"))),
    ]


def _checks(study: dict) -> list[dict[str, str]]:
    return [
        {
            "name": check["name"],
            "value": number(check["value"], ".2e"),
            "tolerance": number(check["tolerance"], ".1e"),
            "result": "PASS" if check["passed"] else "FAIL",
        }
        for check in study["checks"]
    ]


def validity_table(studies: dict) -> dict[str, object] | None:
    """Where the model holds to 1 % and 5 %, one row per assumption a study tests (its kind's
    ``validity_rows``); None when no study tests one."""
    rows = [
        row
        for name, study in studies.items()
        for row in _study_text(study, "validity_rows")(name, study)
    ]
    if not rows:
        return None
    return {
        "title": "Where the model holds: up to which input its difference from the FEM stays "
        "within 1 % and 5 % (limits interpolated between computed points; ± the estimated "
        "error in the value's unit; 'difference ± e': the estimated FEM error of the "
        "difference where the limit is decided, in percentage points; stated only where it "
        "is below a fifth of the level; 'over the whole range computed' where the level is "
        "never crossed: the limit lies beyond)",
        "header": ["assumption tested", "holds to 1 %", "holds to 5 %"],
        "rows": rows,
    }


def _warnings(studies: dict) -> list[dict[str, str]]:
    """The validity warnings of every study, each with its study's name (an entry of an
    older results.json has none)."""
    return [
        {"study": name, "text": text}
        for name, study in studies.items()
        for text in study.get("warnings", [])
    ]


def _failures(studies: dict) -> list[dict[str, str]]:
    """The failed checks of every study (:func:`_checks`), each with its study's name."""
    return [
        {"study": name, **check}
        for name, study in studies.items()
        for check in _checks(study)
        if check["result"] == "FAIL"
    ]


def _summaries(studies: dict) -> dict[str, dict[str, object]]:
    """The summary table of every study, and the contact cross-check of those with a row."""
    contact = [_study_text(study, "summary_row")(name, study) for name, study in studies.items()]
    return {
        "summary": {
            "legend": SUMMARY_LEGEND,
            "timing_legend": TIMING_LEGEND,
            "header": [
                "study",
                "kind",
                "verdict",
                "worst check (value / tolerance)",
                "study total (s)",
            ],
            "rows": [_summary_row(name, study) for name, study in studies.items()],
        },
        "contact_summary": {
            "timing_legend": CONTACT_TIMING_LEGEND,
            "header": [
                "study",
                "verdict",
                *text_contact.CONTACT_COLUMNS.values(),
                *text_contact.IMPACT_COLUMNS,
                "FEM curve (s)",
            ],
            "rows": [row for row in contact if row is not None],
        },
    }


def _figures(captioned: Mapping[str, str]) -> list[dict[str, str]]:
    return [{"caption": caption, "file": file} for caption, file in captioned.items()]


def _study_section(name: str, study: dict, figures: Mapping[str, str]) -> dict[str, object]:
    return {
        "name": name,
        "description": study["description"],
        "case": study.get("case", ""),
        "verdict": "PASS" if study["passed"] else "FAIL",
        "checks": _checks(study),
        "tables": _study_text(study, "tables")(study),
        "timing_text": _study_text(study, "timing_text")(study),
        "figures": _figures(figures),
        "warnings": list(study.get("warnings", [])),
    }


def report_context(
    results: dict, figures: Mapping[str, Mapping[str, str]] | None = None
) -> dict[str, object]:
    """Everything either report shows, as display strings, from the results document.

    Parameters
    ----------
    results : dict
        The results document (:func:`results_document`).
    figures : mapping, optional
        Per study name, caption to PNG path relative to the result folder; key ``""`` holds
        the figures that belong to no study. Default: the document's own ``figures``.
    """
    studies = results["studies"]
    if figures is None:
        figures = {name: study.get("figures", {}) for name, study in studies.items()}
        figures[""] = results.get("figures", {})
    return {
        "passed": results["passed"],
        "verdict": "all studies PASS" if results["passed"] else "at least one study FAILS",
        "quick": results["quick"],
        "failures": _failures(studies),
        "warnings": _warnings(studies),
        "findings": [
            sentence
            for name, study in studies.items()
            for sentence in _study_text(study, "findings")(name, study)
        ],
        "validity": validity_table(studies),
        **_summaries(studies),
        "studies": [
            _study_section(name, study, figures.get(name, {})) for name, study in studies.items()
        ],
        "shared_figures": _figures(figures.get("", {})),
        "generated": results["generated"],
        "environment": results["environment"],
    }


# --- rendering ---------------------------------------------------------------------------------

_MARKDOWN_SPECIAL = re.compile(r"([\\`*\[\]<>|])")


def _markdown_text(value: object) -> str:
    """Plain text for Markdown: markup characters backslash-escaped, one line."""
    return _MARKDOWN_SPECIAL.sub(r"\\\1", " ".join(str(value).split()))


def _url_path(value: str) -> str:
    """A relative file path as a URL path (spaces and the like percent-encoded)."""
    return urllib.parse.quote(Path(value).as_posix())


@cache
def _environment() -> jinja2.Environment:
    env = jinja2.Environment(
        loader=jinja2.PackageLoader("shtaerman.output", "templates"),
        autoescape=jinja2.select_autoescape(enabled_extensions=("html.j2",), default=False),
        undefined=jinja2.StrictUndefined,
        trim_blocks=True,
        lstrip_blocks=True,
        keep_trailing_newline=True,
    )
    env.filters["md"] = _markdown_text
    env.filters["urlpath"] = _url_path
    return env


def _data_uri(folder: Path) -> Callable[[str], str]:
    """A function from a PNG path relative to ``folder`` to its base64 data URI.

    Only PNG files inside ``folder`` are embedded: a results document naming any other file
    (``../secret``) raises ValueError instead of copying it into the page.
    """
    root = folder.resolve()

    def encode(file: str) -> str:
        path = (root / file).resolve()
        if path.suffix.lower() != ".png" or not path.is_relative_to(root):
            raise ValueError(f"figure {file!r} is not a PNG inside the result folder")
        data = base64.b64encode(path.read_bytes()).decode("ascii")
        return f"data:image/png;base64,{data}"

    return encode


def render_markdown(context: Mapping[str, object]) -> str:
    """report.md from :func:`report_context` (relative image links)."""
    return _environment().get_template("report.md.j2").render(context)


def render_html(context: Mapping[str, object], folder: Path) -> str:
    """report.html from :func:`report_context`, every image read from ``folder`` and embedded."""
    template = _environment().get_template("report.html.j2")
    return template.render({**context, "data_uri": _data_uri(folder)})


def write_reports(
    results: dict, folder: Path, figures: Mapping[str, Mapping[str, str]] | None = None
) -> tuple[Path, Path]:
    """report.md and report.html in ``folder`` from one context; returns their paths.

    ``figures`` as for :func:`report_context` (default: those of the results document).
    """
    context = report_context(results, figures)
    markdown, page = folder / "report.md", folder / "report.html"
    markdown.write_text(render_markdown(context), encoding="utf-8")
    page.write_text(render_html(context, folder), encoding="utf-8")
    return markdown, page
