"""The effect table as text (``shtaerman effects``), markdown and CSV (``--out``)."""

from __future__ import annotations

import csv
import io
import json
import re
from itertools import chain
from pathlib import Path

from ...output.text_effects import cell_text
from ...problem import worded
from .table import QUANTITIES, UNITS, Cell, EffectTable, refusal_words

__all__ = ["FILES", "said", "table_csv", "table_markdown", "table_text", "write_table"]

FILES = ("effects.json", "effects.csv", "effects.md")
"""What ``--out`` writes."""
HEADERS = {"P_max": "P_max (%)", "x_max": "x_max (%)", "t_contact": "t_contact (%)"}
HEADERS["restitution"] = "e - 1"


_REASON = re.compile(r"(?:refused|failed): ")


def said(text: str, route: str) -> str:
    """A run's reason or note (``layer_rate not applied: ...``), or a progress line ending
    with a reason (``... full: refused: friction: ...``), written in Python's words, in those
    of ``route`` (:func:`shtaerman.problem.worded`: ``--layer-rate``, ``--friction``)."""
    found = _REASON.search(text)
    start = found.end() if found else 0
    reason = text[start:]
    failed = found is not None and found[0] == "failed: "  # a failure's head names no input
    head = None if failed else re.match(r"\w*", reason)[0]  # a refusal's: its keyword
    return text[:start] + worded(reason, route, parameter=head)


def _text(cell: Cell, key: str) -> str:
    """:func:`shtaerman.output.text_effects.cell_text` of one cell."""
    return cell_text(cell.change, cell.error, key)


def _rows(table: EffectTable, route: str = "python") -> list[tuple[str, list[str]]]:
    """(label, cells) per row of the table, the paper's values first, the interaction last;
    a refused run's single cell is its reason (in the words of ``route``)."""
    ref = table.reference
    paper = [f"{ref[QUANTITIES[k]]:.5g} {UNITS[k]}" if QUANTITIES[k] else "1" for k in QUANTITIES]
    rows, first = [("quasi-static (paper)", paper)], {}
    for run in table.runs:
        if run.refused is not None:
            reason = refusal_words(run.refused, run.label, first)
            rows.append((run.label, [said(reason, route)]))  # type: ignore[arg-type]
            continue
        cells = table.cells(run.label)
        rows.append((run.label, [_text(cells[key], key) for key in QUANTITIES]))
    interaction = table.interaction()
    missing = [run.label for run in table.runs if run.role in ("alone", "full") and run.refused]
    if missing:
        rows.append(("interaction", [f"n/a: {', '.join(missing)} did not run"]))
    else:
        rows.append(("interaction", [_text(interaction[key], key) for key in QUANTITIES]))
    return rows


def _dominant_lines(table: EffectTable) -> list[str]:
    lines = []
    for key, found in table.dominant().items():
        if found["effect"] is None:
            lines.append(f"  {key}: none ({found['why']})")
            continue
        state = {True: "resolved", False: "not resolved", None: "unknown"}[found["resolved"]]
        lines.append(f"  {key}: {found['effect']} ({state}: {found['why']})")
    return lines


def _notes(table: EffectTable, route: str = "python") -> list[str]:
    """Why a bar is n/a, and which options a run did not take (in the words of ``route``):
    each note once, after the runs it applies to."""
    runs = table.runs
    notes = [
        (run.label, ("error bar n/a: ", run.error_note))
        for run in runs
        if run.values is not None and run.error_note
    ]
    notes += [(run.label, ("", note)) for run in runs for note in run.notes]
    labels: dict[tuple[str, str], list[str]] = {}
    for label, note in notes:
        labels.setdefault(note, []).append(label)
    return [
        f"  {', '.join(names)}: {head}{said(note, route)}" for (head, note), names in labels.items()
    ]


def table_text(table: EffectTable, route: str = "python") -> str:
    """The table as printed: changes from the paper's quasi-static values with error bars;
    its reasons and notes in the words of ``route`` (``"cli"``: ``shtaerman effects``)."""
    rows = _rows(table, route)
    width = max(len(label) for label, _ in rows) + 2
    heads = [HEADERS[k] for k in QUANTITIES]
    columns = [
        max(len(h), *(len(c[i]) for _, c in rows if len(c) > 1)) for i, h in enumerate(heads)
    ]

    def line(label: str, cells: list[str]) -> str:
        padded = (c.ljust(w) for c, w in zip(cells, columns, strict=False))
        return (label.ljust(width) + "  ".join(padded)).rstrip()

    out = [
        "Effect table: changes from the paper's quasi-static impact (P_max, x_max, t_contact in "
        "per cent of P_c, x_c, t_y; e as e - 1), with their estimated errors",
        line("", heads),
        *(line(label, cells) for label, cells in rows),
        "  ±: the run's estimated absolute error (its ladder, as 'shtaerman dynamic' gives it) "
        "over the paper's value: 'dynamic' prints the same error over its own value",
        "  interaction = full - sum of the single effects (its bar: the sum of their bars)",
        "  not in the problem: " + (", ".join(table.absent) or "none"),
        "dominant single effect (largest |change|; resolved: beyond the error bars):",
        *_dominant_lines(table),
    ]
    notes = _notes(table, route)
    return "\n".join(out + (["notes:", *notes] if notes else []))


def table_markdown(table: EffectTable) -> str:
    """The table in markdown (a refused run's reason fills its row)."""
    heads = [HEADERS[k] for k in QUANTITIES]
    out = ["| variant | " + " | ".join(heads) + " |", "|---" * (len(heads) + 1) + "|"]
    for label, cells in _rows(table):
        cells = cells if len(cells) > 1 else [cells[0], "", "", ""]
        out.append(f"| {label} | " + " | ".join(c.replace("|", "/") for c in cells) + " |")
    out += ["", "Dominant single effect:", "", *(f"-{line[1:]}" for line in _dominant_lines(table))]
    notes = _notes(table)
    return "\n".join(out + (["", "Notes:", "", *(f"-{n[1:]}" for n in notes)] if notes else []))


def _blank(value: float | None) -> str:
    return "" if value is None else repr(value)


def table_csv(table: EffectTable) -> str:
    """One row per run: values (SI), their errors, changes and their bars; empty: n/a."""
    keys, head = list(QUANTITIES), ["variant", "role", "effect", "refused"]
    head += [f"{key}{end}" for key in keys for end in ("", "_error", "_change", "_change_error")]
    rows, interaction = [head], table.interaction()
    for run in table.runs:
        cells, values, errors = table.cells(run.label), run.values or {}, run.errors or {}
        numbers = [(values.get(k), errors.get(k), cells[k].change, cells[k].error) for k in keys]
        rows.append([run.label, run.role, run.effect or "", run.refused or "", *chain(*numbers)])
    numbers = [(None, None, interaction[k].change, interaction[k].error) for k in keys]
    rows.append(["interaction", "interaction", "", "", *chain(*numbers)])
    buffer = io.StringIO()
    csv.writer(buffer, lineterminator="\n").writerows(
        [row[:4] + [_blank(value) for value in row[4:]] for row in rows[1:]]
    )
    return ",".join(head) + "\n" + buffer.getvalue()


def write_table(table: EffectTable, folder: Path) -> None:
    """effects.json, effects.csv and effects.md in ``folder`` (data: reasons and notes in
    Python's words, as :meth:`EffectTable.to_dict`)."""
    (folder / "effects.json").write_text(json.dumps(table.to_dict(), indent=2) + "\n")
    (folder / "effects.csv").write_text(table_csv(table))
    (folder / "effects.md").write_text(table_markdown(table) + "\n")
