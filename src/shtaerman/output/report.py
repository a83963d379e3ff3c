"""The verification report: results.json, report.md and a self-contained report.html.

Reads study outcomes and figure files; computes nothing of its own.
"""

from __future__ import annotations

import base64
import datetime as dt
import html
import importlib.metadata
import os
import platform
from pathlib import Path

from .. import __version__
from ..study.run import IMPACT_KEYS, StudyOutcome
from .files import json_safe

__all__ = ["environment", "results_document", "write_html", "write_markdown"]

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
)
UNITS = {"beta": "N/m^q", "x_c": "m", "P_c": "N", "a_c": "m", "p_c": "Pa", "t_c": "s", "t_y": "s"}
VARIANTS = {
    "analytic": "exact (analytic beta, Ateb)",
    "fem_fitted": "FEM-fitted beta, Ateb",
    "fem_tabulated": "FEM P(x) tabulated, ODE",
}


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


def study_document(outcome: StudyOutcome, files: dict[str, str]) -> dict[str, object]:
    """One study's entry of results.json."""
    study = outcome.study
    return {
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
        "files": files,
        **({"convergence": outcome.convergence.to_dict()} if outcome.convergence else {}),
        **({"accuracy": outcome.accuracy.to_dict()} if outcome.accuracy else {}),
    }


def results_document(
    outcomes: list[StudyOutcome],
    files: dict[str, dict[str, str]],
    *,
    quick: bool,
) -> dict[str, object]:
    """The whole results.json (strict JSON: non-finite numbers are null)."""
    return json_safe(
        {
            "studies": {o.study.name: study_document(o, files[o.study.name]) for o in outcomes},
            "passed": all(o.passed for o in outcomes),
            "quick": quick,
            "generated": dt.datetime.now(dt.UTC).isoformat(timespec="seconds"),
            "environment": environment(),
        }
    )


def _verdict_rows(results: dict) -> list[list[str]]:
    rows = []
    for name, study in results["studies"].items():
        errors = study["contact"]["errors"]
        worst = {
            key: max(abs(study["differences"][v][key]) for v in ("fem_fitted", "fem_tabulated"))
            for key in ("x_c", "P_c", "t_c")
        }
        rows.append(
            [name, "PASS" if study["passed"] else "FAIL"]
            + [
                f"{errors[k]:.1e}"
                for k in ("force", "beta", "exponent", "contact_radius", "central_pressure")
            ]
            + [f"{worst[k]:.1e}" for k in ("x_c", "P_c", "t_c")]
            + [f"{study['seconds']:.1f}"]
        )
    return rows


VERDICT_HEADER = [
    "study",
    "verdict",
    "force",
    "beta",
    "exponent",
    "radius",
    "p(0)",
    "x_c",
    "P_c",
    "t_c",
    "time (s)",
]


def _impact_rows(study: dict) -> list[list[str]]:
    rows = []
    for variant, label in VARIANTS.items():
        values = study["impact"][variant]
        rows.append(
            [label] + ["-" if values[key] is None else f"{values[key]:.6g}" for key in IMPACT_KEYS]
        )
    return rows


def _markdown_table(header: list[str], rows: list[list[str]]) -> list[str]:
    lines = ["| " + " | ".join(header) + " |", "|" + "---|" * len(header)]
    return lines + ["| " + " | ".join(row) + " |" for row in rows]


def _intro(results: dict) -> list[str]:
    verdict = "all studies PASS" if results["passed"] else "at least one study FAILS"
    mode = " (quick: coarse meshes)" if results["quick"] else ""
    return [
        "Finite-element cross-check of Shtaerman's contact law P = beta x^((n+1)/n) and of the "
        "quasi-static impact it implies (Ol'shanskii et al. 2019, doi:10.15587/1729-4061.2019."
        f"155854). Verdict: **{verdict}**{mode}. Contact columns: largest relative error over "
        "the depths against the exact solution; impact columns: largest relative difference of "
        "the two FEM-fed impacts against the exact one.",
    ]


def write_markdown(results: dict, figures: dict[str, dict[str, str]], path: Path) -> None:
    """report.md beside the figures (relative image links)."""
    lines = ["# shtaerman verification report", "", *_intro(results), ""]
    lines += _markdown_table(VERDICT_HEADER, _verdict_rows(results))
    for name, study in results["studies"].items():
        lines += ["", f"## {name}", "", study["description"], ""]
        lines += _markdown_table(
            ["impact", *(f"{k} ({UNITS[k]})" for k in IMPACT_KEYS)], _impact_rows(study)
        )
        lines += [""] + [f"![{title}]({file})" for title, file in figures.get(name, {}).items()]
    shared = figures.get("", {})
    if shared:
        lines += ["", "## The paper's Ateb functions", ""]
        lines += [f"![{title}]({file})" for title, file in shared.items()]
    env = results["environment"]
    lines += [
        "",
        f"Generated {results['generated']} by shtaerman {env['shtaerman']} on "
        f"{env['platform']} ({env['cpu_count']} cores).",
    ]
    path.write_text("\n".join(lines) + "\n", encoding="utf-8")


def _html_table(header: list[str], rows: list[list[str]]) -> str:
    head = "".join(f"<th>{html.escape(h)}</th>" for h in header)
    body = "".join(
        "<tr>" + "".join(f'<td class="{c.lower()}">{html.escape(c)}</td>' for c in row) + "</tr>"
        for row in rows
    )
    return f"<table><thead><tr>{head}</tr></thead><tbody>{body}</tbody></table>"


def _embedded(folder: Path, file: str, title: str) -> str:
    data = base64.b64encode((folder / file).read_bytes()).decode("ascii")
    caption = html.escape(title)
    return (
        f'<figure><img alt="{caption}" src="data:image/png;base64,{data}">'
        f"<figcaption>{caption}</figcaption></figure>"
    )


STYLE = """body{font-family:sans-serif;max-width:1100px;margin:2em auto;line-height:1.4}
table{border-collapse:collapse;margin:1em 0}td,th{border:1px solid #ccc;padding:3px 8px;
text-align:right}th{background:#eee}td.pass{color:#070;font-weight:bold}
td.fail{color:#b00;font-weight:bold}img{max-width:100%}figure{margin:1em 0}"""


def write_html(results: dict, figures: dict[str, dict[str, str]], folder: Path) -> Path:
    """report.html with every image embedded: it opens from disk anywhere."""
    parts = [
        f"<!DOCTYPE html><html><head><meta charset='utf-8'><title>shtaerman report</title>"
        f"<style>{STYLE}</style></head><body><h1>shtaerman verification report</h1>"
    ]
    parts += [f"<p>{html.escape(p).replace('**', '')}</p>" for p in _intro(results)]
    parts.append(_html_table(VERDICT_HEADER, _verdict_rows(results)))
    for name, study in results["studies"].items():
        parts.append(f"<h2>{html.escape(name)}</h2><p>{html.escape(study['description'])}</p>")
        header = ["impact", *(f"{k} ({UNITS[k]})" for k in IMPACT_KEYS)]
        parts.append(_html_table(header, _impact_rows(study)))
        parts += [_embedded(folder, file, title) for title, file in figures.get(name, {}).items()]
    if figures.get(""):
        parts.append("<h2>The paper's Ateb functions</h2>")
        parts += [_embedded(folder, file, title) for title, file in figures[""].items()]
    env = results["environment"]
    parts.append(
        f"<p><small>Generated {results['generated']} by shtaerman {env['shtaerman']} "
        f"on {html.escape(str(env['platform']))}.</small></p></body></html>"
    )
    path = folder / "report.html"
    path.write_text("".join(parts), encoding="utf-8")
    return path
