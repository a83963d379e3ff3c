"""The effects kind's text: the dominant effect per quantity, from a study's effect table
(its results.json entry holds the table's JSON, ``shtaerman effects --json``)."""

from __future__ import annotations

from collections.abc import Mapping
from typing import Any

from .entry import kind_entry

__all__ = ["case_of", "entry", "study_findings"]

NAMES = {"P_max": "P_max", "x_max": "x_max", "t_contact": "t_contact", "restitution": "e"}


def case_of(problem: Mapping[str, Any]) -> str:
    """The full problem of a table (its ``problem``) in words, every part set: "12 mm pad on
    a bonded rigid base; neo-Hookean rubber, Prony series g:tau = 0.3:0.001 s; bonded
    indenter with Coulomb friction mu = 0.5"."""
    from ..plots.labels import model_label
    from ..theory.viscoelastic import PronySeries
    from .case import case_words

    model, geometry = problem["model"], problem["geometry"]
    prony = problem["prony"] and PronySeries(*zip(*problem["prony"], strict=True))
    return case_words(
        material="linear elastic" if model == "linear" else f"{model_label(model)} rubber",
        prony=prony or None,
        thickness=problem["thickness"],
        base=geometry.split()[-1] if problem["thickness"] is not None else None,
        interface="frictionless" if problem["interface"] == "frictionless" else "bonded",
        friction=problem["friction"],
    )


def study_findings(document: Mapping[str, Any]) -> list[str]:
    """One sentence per quantity: its dominant effect and whether the bars resolve it."""
    table = document["effects"]
    out = []
    for key, words in NAMES.items():
        dominant = table["dominant"][key]
        if dominant["effect"] is None:
            out.append(f"{words}: no single effect ran ({dominant['why']}).")
            continue
        resolved = {True: "resolved", False: "not resolved", None: "unknown"}[dominant["resolved"]]
        out.append(
            f"{words} moves most with {dominant['effect']} alone ({resolved}: {dominant['why']})."
        )
    return out


def cell_text(change: float | None, error: float | None, key: str) -> str:
    """One entry of an effect table: ``+1.49 ± 0.05`` (per cent; e - 1 of the ``restitution``
    as is), ``± n/a`` without a bar, "" without a change."""
    if change is None:
        return ""
    scale, digits = (1.0, 4) if key == "restitution" else (100.0, 2)
    bar = "n/a" if error is None else f"{scale * error:.{digits}f}"
    return f"{scale * change:+.{digits}f} ± {bar}"


def study_tables(document: Mapping[str, Any]) -> list[dict[str, object]]:
    """The change of each run against the paper's quasi-static values, each with its error bar
    (``shtaerman effects``' cells: %, e - 1 for e; "± n/a" without a bar), and the
    interaction."""
    table = document["effects"]

    def row(label: str, changes: Mapping[str, Any]) -> list[str]:
        cells = {key: changes[key] for key in NAMES}
        return [label, *(cell_text(c["change"], c["error"], k) or "-" for k, c in cells.items())]

    rows = [row(run["label"], run["changes"]) for run in table["runs"]]
    rows.append(row("interaction", table["interaction"]))
    header = ["run", "P_max (%)", "x_max (%)", "t_contact (%)", "e - 1"]
    return [{"title": "Effect table (± the estimated error)", "header": header, "rows": rows}]


def entry(
    outcome: Any,
    files: dict[str, str],
    output_seconds: float | None,
    figures: Mapping[str, str] | None,
) -> dict[str, object]:
    """The study's results.json entry: the table, its display table and its findings."""
    document = outcome.document()
    case = case_of(document["effects"]["problem"])
    text = {"tables": study_tables(document), "findings": study_findings(document)}
    return kind_entry(outcome, {"case": case, **document, **text}, files, output_seconds, figures)
