"""The effect table as a figure: each effect's change of P_max, x_max, t_contact and e.

One panel per quantity (:data:`.table.QUANTITIES`), one horizontal
bar per variant, measured from the paper's quasi-static impact as the table measures it: P_max,
x_max and t_contact in per cent of P_c, x_c and t_y, the restitution as e - 1 in per cent.
Each effect alone is blue, the full problem black, the full problem without one effect orange
and the interaction (full - sum of the single effects) grey; the whiskers are the table's error
bars (none where a run has no estimate). A variant that was refused or failed has no bar: its
row reads "not run" (its reason is the table's). The title names the case (the striker's
mass and velocity and :func:`shtaerman.output.text_effects.case_of`), the legend the colours.
"""

from __future__ import annotations

from pathlib import Path
from typing import Any

import numpy as np
from matplotlib.lines import Line2D
from matplotlib.patches import Patch

from ...output.text_effects import case_of
from ...plots.labels import MINUS
from ...plots.style import APPROXIMATION_COLOUR, EXACT_COLOUR, FEM_COLOUR, chart, save, styled
from .types import Cell, TableView

__all__ = ["EFFECTS_CAPTION", "plot_effect_table"]

WHISKERS = (
    "whiskers: each run's estimated absolute error (its mesh ladder's, as 'shtaerman dynamic' "
    "gives it) over the paper's value; the interaction's is the sum of its terms' (an upper "
    "bound); none where a run has no estimate"
)
EFFECTS_CAPTION = (
    "Effect table: the change of P_max, x_max and t_contact (per cent of the paper's P_c, x_c, "
    f"t_y) and of e (e {MINUS} 1, per cent) from the paper's quasi-static impact, for each "
    "effect alone (blue), the full problem (black), the full problem without each effect "
    f"(orange) and their interaction (grey: full minus the sum of the single effects); {WHISKERS}"
)
COLOURS = {"none": "0.6", "alone": FEM_COLOUR, "full": EXACT_COLOUR}
COLOURS |= {"without": APPROXIMATION_COLOUR, "interaction": "0.45"}
LEGEND = {"none": "every effect off", "alone": "one effect alone", "full": "full problem"}
LEGEND |= {
    "without": "full without one effect",
    "interaction": f"interaction (full {MINUS} Σ alone)",
}
TITLES = {"P_max": "P_max / P_c", "x_max": "x_max / x_c", "t_contact": "t_contact / t_y"}
TITLES = {key: f"{words} {MINUS} 1 (%)" for key, words in TITLES.items()}
TITLES["restitution"] = f"e {MINUS} 1 (%)"


def _rows(table: TableView) -> list[tuple[str, str, dict[str, Cell] | None]]:
    """(label, role, its cell per quantity; None: not run) of ``table``, from the top of the
    figure down."""
    rows = []
    for run in table.runs:
        cells = None if run.values is None else table.cells(run.label)
        rows.append((run.label, run.role, cells))
    ran = all(run.values is not None for run in table.runs if run.role in ("alone", "full"))
    rows.append(("interaction", "interaction", table.interaction() if ran else None))
    return rows


def _title(problem: dict[str, Any]) -> str:
    """What the figure shows and of which case (the table's ``problem``; none: unnamed)."""
    head = "Change of the impact from the paper's quasi-static one, by effect"
    if not problem:
        return head
    lines = [head, f"{problem['mass']:g} kg at {problem['velocity']:g} m/s"]
    for part in case_of(problem).split("; "):  # a line per 100 characters, broken at a "; "
        lines[-1:] = (
            [f"{lines[-1]}; {part}"] if len(lines[-1]) + len(part) < 98 else [lines[-1], part]
        )
    return "\n".join(lines)


@styled
def plot_effect_table(table: TableView, path: Path | str, figure_format: str = "png") -> Path:
    """Draw ``table`` (:func:`shtaerman.effects`) into ``path`` (:data:`EFFECTS_CAPTION`)."""
    rows = _rows(table)
    keys = list(TITLES)
    figure, axes = chart(1.7 + 0.24 * len(rows), 1, len(keys), width=9.0, sharey=True)
    place = np.arange(len(rows))[::-1]
    for panel, key in zip(axes, keys, strict=True):
        for y, (_, role, cells) in zip(place, rows, strict=True):
            cell = None if cells is None else cells[key]
            if cell is None or cell.change is None:
                panel.text(0.0, y, " not run", va="center", fontsize=7, color="0.4")
                continue
            error = None if cell.error is None else 100.0 * cell.error
            panel.barh(y, 100.0 * cell.change, height=0.7, xerr=error, color=COLOURS[role],
                       error_kw={"elinewidth": 0.8, "capsize": 2})  # fmt: skip
        panel.axvline(0.0, color="0.2", linewidth=0.6)
        panel.set_title(TITLES[key], fontsize=9)
        panel.grid(axis="y", visible=False)
    axes[0].set_yticks(place, [label for label, _, _ in rows])
    roles = dict.fromkeys(role for _, role, _ in rows)  # the roles drawn, in the rows' order
    handles = [Patch(color=COLOURS[role], label=LEGEND[role]) for role in roles]
    whisker = dict(color="0.2", linewidth=0.8, marker="|", markersize=6)
    handles.append(Line2D([], [], label="estimated error", **whisker))  # type: ignore[arg-type]
    figure.legend(handles=handles, loc="outside lower center", ncols=3, fontsize=8,
                  numpoints=2)  # fmt: skip
    figure.suptitle(_title(table.problem), fontsize=10)
    return save(figure, path, figure_format)
