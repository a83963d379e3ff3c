"""The verification report: results.json, and report.md and a self-contained report.html.

Reads study outcomes and figure files; computes nothing of its own. Both reports are jinja2
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
from typing import Any

import jinja2

from .. import __version__
from ..study.finite_accuracy import resolved
from ..study.run import IMPACT_KEYS, StudyOutcome
from .files import json_safe

__all__ = [
    "environment",
    "render_html",
    "render_markdown",
    "report_context",
    "results_document",
    "write_html",
    "write_markdown",
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
UNITS = {"beta": "N/m^q", "x_c": "m", "P_c": "N", "a_c": "m", "p_c": "Pa", "t_c": "s", "t_y": "s"}
VARIANTS = {
    "analytic": "exact (analytic beta, Ateb)",
    "fem_fitted": "FEM-fitted beta, Ateb",
    "fem_tabulated": "FEM P(x) tabulated, ODE",
}
CONTACT_COLUMNS = {
    "force": "force",
    "beta": "beta",
    "exponent": "exponent",
    "contact_radius": "radius",
    "central_pressure": "p(0)",
}
IMPACT_COLUMNS = ("x_c", "P_c", "t_c")
SUMMARY_LEGEND = (
    "Contact columns: the largest relative error over the depths against Shtaerman's exact "
    "solution. Impact columns: the largest relative difference of the two FEM-fed impacts "
    "(FEM-fitted beta through the Ateb solution; tabulated FEM P(x) integrated numerically) "
    "against the exact impact. Each study's checks below give every value with its tolerance."
)
TIMING_LEGEND = (
    "FEM curve (s): meshing, assembly, factorization and contact solves of the study's depth "
    "ladder. Study total (s): wall time of the whole study: the FEM curve, fits, the three "
    "impacts, the mesh-convergence study if any, and writing its files and figures."
)


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


def _timings(outcome: StudyOutcome, output: float | None) -> dict[str, float | None]:
    """Wall times of one study in s (``output``: writing its files and figures, if known)."""
    fem = float(outcome.contact.timings.get("total", float("nan")))
    levels = outcome.convergence.levels if outcome.convergence is not None else []
    convergence = sum(float(level.get("timings", {}).get("total", 0.0)) for level in levels)
    return {
        "fem_curve": fem,
        "convergence": convergence,
        "computation": outcome.seconds,
        "output": output,
        "total": outcome.seconds + (output or 0.0),
    }


def study_document(
    outcome: StudyOutcome,
    files: dict[str, str],
    output_seconds: float | None = None,
    figures: Mapping[str, str] | None = None,
) -> dict[str, object]:
    """One study's entry of results.json.

    ``figures``: caption to PNG path (relative to the result folder) of the study's figures.

    ``seconds`` is the computation (:func:`shtaerman.study.run.run_study`); ``timings`` splits
    the study's wall time: ``fem_curve`` (the FEM contact curve), ``convergence`` (its
    meshes), ``computation`` (= ``seconds``), ``output`` (files and figures) and ``total``.
    """
    study = outcome.study
    if getattr(study, "kind", "contact") != "contact":
        return _kind_document(outcome, files, output_seconds, figures)
    return {
        "kind": "contact",
        "description": study.description,
        "source": str(study.source),
        "inputs": {
            "shape_coefficient": study.indenter.shape_coefficient,
            "exponent": study.indenter.exponent,
            "E1": study.striker.youngs_modulus,
            "nu1": study.striker.poisson_ratio,
            "E2": study.half_space.youngs_modulus,
            "nu2": study.half_space.poisson_ratio,
            "mass": study.mass,
            "velocity": study.velocity,
        },
        "contact": outcome.contact.to_dict(),
        "impact": outcome.impacts,
        "differences": outcome.differences(),
        "checks": [check.to_dict() for check in outcome.checks],
        "passed": outcome.passed,
        "seconds": outcome.seconds,
        "timings": _timings(outcome, output_seconds),
        "files": files,
        "figures": dict(figures or {}),
        **({"convergence": outcome.convergence.to_dict()} if outcome.convergence else {}),
        **({"accuracy": outcome.accuracy.to_dict()} if outcome.accuracy else {}),
    }


def _kind_document(
    outcome: Any,
    files: dict[str, str],
    output_seconds: float | None,
    figures: Mapping[str, str] | None,
) -> dict[str, object]:
    """The results.json entry of a study of another kind: its own document plus the common
    keys (checks, verdict, times, files, figures)."""
    study = outcome.study
    return {
        "kind": study.kind,
        "description": study.description,
        "source": str(study.source),
        **outcome.document(),
        "checks": [check.to_dict() for check in outcome.checks],
        "passed": outcome.passed,
        "seconds": outcome.seconds,
        "timings": {
            "computation": outcome.seconds,
            "output": output_seconds,
            "total": outcome.seconds + (output_seconds or 0.0),
        },
        "files": files,
        "figures": dict(figures or {}),
    }


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


def _number(value: float | None, spec: str) -> str:
    return "-" if value is None else format(value, spec)


def _seconds(value: float | None) -> str:
    return "-" if value is None else f"{value:.1f}"


def _is_contact(study: dict) -> bool:
    return study.get("kind", "contact") == "contact"


def _contact_row(name: str, study: dict) -> list[str]:
    errors = study["contact"]["errors"]
    differences = [study["differences"][v] for v in ("fem_fitted", "fem_tabulated")]
    worst = {
        key: max((abs(d[key]) for d in differences if d.get(key) is not None), default=float("nan"))
        for key in IMPACT_COLUMNS
    }
    timings = study.get("timings") or {}
    return [
        name,
        "PASS" if study["passed"] else "FAIL",
        *(_number(errors.get(key), ".1e") for key in CONTACT_COLUMNS),
        *(_number(worst[key], ".1e") for key in IMPACT_COLUMNS),
        _seconds(timings.get("fem_curve", study["contact"]["timings"].get("total"))),
    ]


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
        else f"{worst['name']}: {_number(abs(worst['value'] or 0.0), '.1e')}"
        f" / {_number(worst['tolerance'], '.0e')}",
        _seconds(timings.get("total", study.get("seconds"))),
    ]


def _checks(study: dict) -> list[dict[str, str]]:
    return [
        {
            "name": check["name"],
            "value": _number(check["value"], ".2e"),
            "tolerance": _number(check["tolerance"], ".1e"),
            "result": "PASS" if check["passed"] else "FAIL",
        }
        for check in study["checks"]
    ]


def _impact_table(study: dict) -> dict[str, object]:
    rows = [
        [label] + [_number(study["impact"][variant][key], ".6g") for key in IMPACT_KEYS]
        for variant, label in VARIANTS.items()
        if variant in study["impact"]
    ]
    header = ["impact", *(f"{k} ({UNITS[k]})" for k in IMPACT_KEYS)]
    return {"title": "The impact three ways", "header": header, "rows": rows}


ESTIMATED = {
    "force": "force (worst depth)",
    "beta": "beta",
    "exponent": "exponent",
    "contact_radius": "contact radius (worst depth)",
    "central_pressure": "p(0) (worst depth)",
}


def _estimate_table(study: dict) -> dict[str, object] | None:
    """FEM value +- its Richardson estimate, the true error and their ratio (effectivity)."""
    accuracy = study.get("accuracy")
    if not accuracy:
        return None
    ladder = ", ".join(str(level["dofs"]) for level in accuracy["mesh_ladder"])
    rows = []
    for key, label in ESTIMATED.items():
        if key not in accuracy["error_estimate"]:
            continue
        details = accuracy["estimate_details"][key]
        rows.append(
            [
                label,
                f"{_number(details['value'], '.6g')} ± "
                f"{_number(accuracy['error_estimate'][key], '.1e')}",
                _number(accuracy["true_error"].get(key), ".1e"),
                _number(accuracy["effectivity"].get(key), ".2f"),
                details["method"] + (f" ({details['reason']})" if details["reason"] else ""),
            ]
        )
    return {
        "title": f"Error estimates (3-mesh ladder, {ladder} dofs): value ± estimated relative "
        "error, the true error against the exact solution, and their ratio",
        "header": ["quantity", "FEM value ± estimate", "true error", "effectivity", "method"],
        "rows": rows,
    }


def _tables(study: dict) -> list[dict[str, object]]:
    if not _is_contact(study):
        return list(study.get("tables", []))
    return [table for table in (_impact_table(study), _estimate_table(study)) if table]


def _contact_finding(name: str, study: dict) -> str:
    errors = study["contact"]["errors"]
    text = (
        f"{name}: the FEM reproduces Shtaerman's contact law to {_number(errors['force'], '.1e')}"
        f" (force), {_number(errors['beta'], '.1e')} (beta) and p(0) to "
        f"{_number(errors['central_pressure'], '.1e')}"
    )
    accuracy = study.get("accuracy")
    if accuracy:
        text += (
            f"; its own error estimate says {_number(accuracy['error_estimate']['force'], '.1e')}"
            f" (force), {_number(accuracy['error_estimate']['beta'], '.1e')} (beta)"
        )
    return text + "."


def _velocity(limit: dict | None) -> str:
    """A velocity limit of the dynamic study: "3.12 m/s", "all computed (5 m/s)", "none", or
    "not resolved (...)" where its estimated error is not below a fifth of the level."""
    if limit and not limit.get("resolved"):
        if limit.get("error") is None:
            return "not resolved (no error estimate)"
        return f"not resolved (estimate {100 * limit['error']:.2g} %)"
    if not limit or limit.get("velocity") is None:
        return "no: already off at the slowest v0 computed"
    if limit.get("bound") == "all":
        return f"every v0 computed (to {limit['velocity']:.3g} m/s)"
    spread = limit.get("velocity_error")
    plus_minus = "" if spread is None else f" ± {spread:.1g}"
    return f"v0 = {limit['velocity']:.3g}{plus_minus} m/s"


def _depth(entry: dict | None) -> str:
    """A depth limit of a finite-strain study: x/a and the impact velocity reaching it, ± their
    estimated relative errors; "not resolved" where the departure's estimated error there is
    not below a fifth of the level (:func:`shtaerman.study.finite_accuracy.resolved`)."""
    if not entry or entry.get("depth_to_radius") is None:
        return "-"
    where, velocity = f"x/a = {entry['depth_to_radius']:.2f}", f"v0 = {entry['velocity']:.2g} m/s"
    if "departure_error" not in entry:
        return f"{where} ({velocity}; not estimated)"
    error = entry["departure_error"]
    if error is None or not resolved(entry["level"], error):
        return f"not resolved (estimated error of the departure {_number(error, '.1e')})"
    errors = entry.get("errors") or {}
    return (
        f"{where} ± {_number(errors.get('depth_to_radius'), '.1e')} ({velocity} ± "
        f"{_number(errors.get('velocity'), '.1e')})"
    )


def validity_table(studies: dict) -> dict[str, object] | None:
    """Where the paper's model holds to 1 % and 5 %, from the dynamic and finite-strain
    studies' structured results (``limits``, ``validity``), one row per assumption tested."""
    rows = []
    for name, study in studies.items():
        if study.get("kind") == "dynamic" and "limits" in study:
            limits = study["limits"]
            for key, label in (
                ("all", "x_c, P_c and t_c"),
                ("P", "P_c"),
                ("x", "x_c"),
                ("t", "t_c"),
            ):
                if key in limits:
                    rows.append(
                        [
                            f"no elastic waves ({name}): quasi-static {label} against the "
                            "dynamic FE impact",
                            _velocity(limits[key].get("1%")),
                            _velocity(limits[key].get("5%")),
                        ]
                    )
        if study.get("kind") == "finite-strain" and "validity" in study:
            levels = {round(entry["level"], 4): entry for entry in study["validity"]}
            nu = study.get("inputs", {}).get("nu2")
            rows.append(
                [
                    f"linear elasticity ({name}): beta x^q against neo-Hookean rubber"
                    + (f", nu2 = {nu:g}" if nu is not None else ""),
                    _depth(levels.get(0.01)),
                    _depth(levels.get(0.05)),
                ]
            )
    if not rows:
        return None
    return {
        "title": "Where the paper's model holds (limits interpolated between computed points; "
        "shown only where the estimated FEM error is below a fifth of the effect; ± estimated "
        "relative error)",
        "header": ["assumption tested", "holds to 1 % up to", "holds to 5 % up to"],
        "rows": rows,
    }


def _findings(studies: dict) -> list[str]:
    found = []
    for name, study in studies.items():
        if _is_contact(study):
            found.append(_contact_finding(name, study))
        else:
            found += [f"{name}: {sentence}" for sentence in study.get("findings", [])]
    return found


def _timing_text(study: dict) -> str:
    timings = study.get("timings") or {}
    if not _is_contact(study):
        parts = [f"computation {_seconds(timings.get('computation', study['seconds']))} s"]
        if timings.get("output") is not None:
            parts.append(f"files and figures {_seconds(timings['output'])} s")
        parts.append(f"study total {_seconds(timings.get('total', study['seconds']))} s")
        return "; ".join(parts)
    contact = study["contact"]["timings"]
    parts = [
        f"FEM curve {_seconds(timings.get('fem_curve', contact.get('total')))} s (mesh "
        f"{_seconds(contact.get('mesh'))}, assembly {_seconds(contact.get('assembly'))}, "
        f"factorization {_seconds(contact.get('factorization'))}, contact "
        f"{_seconds(contact.get('contact'))})"
    ]
    if timings.get("convergence"):
        parts.append(f"mesh-convergence study {_seconds(timings['convergence'])} s")
    parts.append(f"computation in all {_seconds(timings.get('computation', study['seconds']))} s")
    if timings.get("output") is not None:
        parts.append(f"files and figures {_seconds(timings['output'])} s")
    parts.append(f"study total {_seconds(timings.get('total', study['seconds']))} s")
    return "; ".join(parts)


def _figures(captioned: Mapping[str, str]) -> list[dict[str, str]]:
    return [{"caption": caption, "file": file} for caption, file in captioned.items()]


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
    failures = [
        {
            "study": name,
            "check": check["name"],
            "value": _number(check["value"], ".2e"),
            "tolerance": _number(check["tolerance"], ".1e"),
        }
        for name, study in studies.items()
        for check in study["checks"]
        if not check["passed"]
    ]
    contact = {name: study for name, study in studies.items() if _is_contact(study)}
    return {
        "passed": results["passed"],
        "verdict": "all studies PASS" if results["passed"] else "at least one study FAILS",
        "quick": results["quick"],
        "failures": failures,
        "findings": _findings(studies),
        "validity": validity_table(studies),
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
            "header": [
                "study",
                "verdict",
                *CONTACT_COLUMNS.values(),
                *IMPACT_COLUMNS,
                "FEM curve (s)",
            ],
            "rows": [_contact_row(name, study) for name, study in contact.items()],
        },
        "studies": [
            {
                "name": name,
                "description": study["description"],
                "verdict": "PASS" if study["passed"] else "FAIL",
                "checks": _checks(study),
                "tables": _tables(study),
                "timing_text": _timing_text(study),
                "figures": _figures(figures.get(name, {})),
            }
            for name, study in studies.items()
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


def write_markdown(results: dict, figures: dict[str, dict[str, str]], path: Path) -> None:
    """report.md beside the figures (relative image links)."""
    path.write_text(render_markdown(report_context(results, figures)), encoding="utf-8")


def write_html(results: dict, figures: dict[str, dict[str, str]], folder: Path) -> Path:
    """report.html with every image embedded: it opens from disk anywhere."""
    path = folder / "report.html"
    path.write_text(render_html(report_context(results, figures), folder), encoding="utf-8")
    return path
