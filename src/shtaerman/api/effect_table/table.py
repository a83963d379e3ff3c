"""The effect table: each variant's P_max, x_max, t_contact and e against the paper's
quasi-static impact, with error bars, the interaction and the dominant effect.

A change is measured from the paper's exact quasi-static value (``reference``): P_max / P_c - 1,
x_max / x_c - 1 and t_contact / t_y - 1 (fractions), and e - 1 for the restitution (the paper's
e is 1). The interaction is the full model's change minus the sum of the single effects'
changes, so ``full = sum(alone) + interaction`` holds exactly, by construction. An error bar is
the run's estimated absolute error (the ladder's, :attr:`shtaerman.DynamicResult.estimate_details`)
over the reference; the interaction's is the sum of its terms' error bars (an upper bound: it
must not understate). Where a run has no error estimate, its bar is None ("n/a") and
:attr:`Run.error_note` says why.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from ...output.files import json_safe
from .types import Cell, Run  # in .types, which the figure imports too (no cycle)

__all__ = [
    "QUANTITIES",
    "Cell",
    "EffectTable",
    "Run",
    "change",
    "dominance",
    "interaction",
    "refusal_words",
]

QUANTITIES = {"P_max": "P_c", "x_max": "x_c", "t_contact": "t_y", "restitution": None}
"""Each impact quantity -> the paper's quasi-static value it is measured against (None: the
restitution, 1 in the paper, whose change is the difference e - 1)."""
UNITS = {"P_max": "N", "x_max": "m", "t_contact": "s", "restitution": ""}


def refusal_words(refused: str | None, label: str, first: dict[str, str]) -> str | None:
    """The refusal of the run ``label`` as a table says it: in full at the first run that
    gave it (recorded in ``first``), else "refused: as <that run>" (a long reason once, not
    once per variant); None: it ran."""
    if refused is None:
        return None
    origin = first.setdefault(refused, label)
    return refused if origin == label else f"{refused.split(':', 1)[0]}: as {origin}"


def change(value: float, key: str, reference: dict[str, float]) -> float:
    """The change of ``value`` (quantity ``key``, SI) from the paper's: a fraction, or e - 1."""
    ref = QUANTITIES[key]
    return value - 1.0 if ref is None else value / reference[ref] - 1.0


def _change_error(error: float, key: str, reference: dict[str, float]) -> float:
    ref = QUANTITIES[key]
    return error if ref is None else error / reference[ref]


def cells(run: Run, reference: dict[str, float]) -> dict[str, Cell]:
    """A run's changes and their error bars, per quantity (None for a refused run)."""
    out = {}
    for key in QUANTITIES:
        if run.values is None:
            out[key] = Cell(None, None)
            continue
        error = None if run.errors is None else _change_error(run.errors[key], key, reference)
        out[key] = Cell(change(run.values[key], key, reference), error)
    return out


def interaction(full: Cell, singles: list[Cell]) -> Cell:
    """The full change minus the sum of the single changes; its bar is the sum of the bars
    (None when any term has none)."""
    if full.change is None or any(single.change is None for single in singles):
        return Cell(None, None)
    value = full.change - math.fsum(single.change for single in singles)  # type: ignore[misc]
    bars = [full.error, *(single.error for single in singles)]
    return Cell(value, None if None in bars else math.fsum(bars))  # type: ignore[arg-type]


def dominance(singles: dict[str, Cell]) -> dict[str, Any]:
    """The effect whose single change is largest in magnitude, and whether that ranking is
    resolved: its change exceeds its bar, and the margin over the runner-up exceeds both bars
    (None: unknown, a bar is n/a)."""
    ranked = sorted(
        ((name, c) for name, c in singles.items() if c.change is not None),
        key=lambda item: -abs(item[1].change),  # type: ignore[arg-type]
    )
    if not ranked:
        return {"effect": None, "resolved": None, "why": "no single effect ran"}
    (name, top), rest = ranked[0], ranked[1:2]
    bars = [top.error, *(c.error for _, c in rest)]
    if None in bars:
        return {"effect": name, "resolved": None, "why": "an error bar is n/a"}
    margin = abs(top.change) - top.error  # type: ignore[arg-type,operator]
    if rest:
        runner = rest[0][1]
        resolved = margin > abs(runner.change) + runner.error  # type: ignore[arg-type,operator]
        why = f"against {rest[0][0]}"
    else:
        resolved, why = margin > 0, "the only effect that ran"
    return {"effect": name, "resolved": bool(resolved and margin > 0), "why": why}


@dataclass(frozen=True)
class EffectTable:
    """The effect table of one problem (:func:`shtaerman.effects`).

    ``reference`` holds the paper's quasi-static x_c, P_c, t_c, t_y (SI); ``runs`` every
    variant (``none``: all effects off, by FE; ``<effect> alone``; ``full``; ``without
    <effect>``); ``absent`` the effects the problem does not have; ``problem`` a description of
    the full problem's parts.
    """

    reference: dict[str, float]
    runs: tuple[Run, ...]
    absent: tuple[str, ...]
    problem: dict[str, Any] = field(default_factory=dict)

    def run(self, label: str) -> Run:
        """The run labelled ``label``."""
        return next(run for run in self.runs if run.label == label)

    @property
    def effects(self) -> tuple[str, ...]:
        """The effects the problem has, in the table's order."""
        return tuple(run.effect for run in self.runs if run.role == "alone")  # type: ignore[misc]

    def cells(self, label: str) -> dict[str, Cell]:
        """The changes and error bars of the run ``label``."""
        return cells(self.run(label), self.reference)

    def interaction(self) -> dict[str, Cell]:
        """Per quantity: the full change minus the sum of the single changes."""
        singles = [self.cells(f"{name} alone") for name in self.effects]
        full = self.cells("full")
        return {key: interaction(full[key], [s[key] for s in singles]) for key in QUANTITIES}

    def dominant(self) -> dict[str, dict[str, Any]]:
        """Per quantity: the dominant single effect and whether it is resolved."""
        singles = {name: self.cells(f"{name} alone") for name in self.effects}
        return {key: dominance({n: c[key] for n, c in singles.items()}) for key in QUANTITIES}

    def plot(self, path: Path | str, figure_format: str = "png") -> Path:
        """Draw the table into the PNG ``path`` (or .svg/.pdf; ``figure_format`` "svg" or
        "pdf" adds that format beside the PNG), one panel per quantity, each variant's change
        with its error bar (:func:`.figure.plot_effect_table`); the path."""
        from .figure import plot_effect_table

        return plot_effect_table(self, path, figure_format)

    def to_dict(self) -> dict[str, Any]:
        """The JSON of ``shtaerman effects --json`` (SI; changes as fractions, e as e - 1;
        null: n/a)."""
        rows = []
        for run in self.runs:
            row = {k: v for k, v in vars(run).items() if k not in ("notes", "warned")}
            row["notes"] = list(run.notes)
            row["changes"] = {k: vars(c) for k, c in cells(run, self.reference).items()}
            rows.append(row)
        return json_safe(
            {
                "problem": self.problem,
                "reference": dict(self.reference),
                "effects": list(self.effects),
                "absent": list(self.absent),
                "runs": rows,
                "interaction": {k: vars(c) for k, c in self.interaction().items()},
                "dominant": self.dominant(),
            }
        )
