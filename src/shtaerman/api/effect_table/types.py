"""The effect table's data types: a run's outcome, one entry's change with its error bar, and
what the figure reads of a table (a protocol: :class:`.table.EffectTable` satisfies it).

Here, below both :mod:`.table` and :mod:`.figure`, so that the figure names the table's types
while :meth:`.table.EffectTable.plot` imports the figure (no import cycle).
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any, Protocol

__all__ = ["Cell", "Run", "TableView"]


@dataclass(frozen=True)
class Run:
    """One variant's outcome.

    ``values`` (SI) and ``errors`` (their estimated absolute errors) are None when the variant
    was refused or failed; then ``refused`` is its one-line reason. ``errors`` is None with
    ``error_note`` saying why when the run had no error estimate. ``notes`` list the numerical
    options the variant's combination does not take (left out of its run). ``warned`` holds
    the warnings its run gave, (category as ``module.qualname``, text) each: a resumed table
    says them again for a run it keeps (not in :meth:`.table.EffectTable.to_dict`).
    """

    label: str
    role: str
    effect: str | None
    cell: str
    values: dict[str, float] | None = None
    errors: dict[str, float] | None = None
    error_note: str | None = None
    refused: str | None = None
    seconds: float = 0.0
    notes: tuple[str, ...] = ()
    warned: tuple[tuple[str, str], ...] = ()


@dataclass(frozen=True)
class Cell:
    """One entry: the change from the paper and its error bar (None: n/a)."""

    change: float | None
    error: float | None


class TableView(Protocol):
    """What the figure reads of an effect table (:class:`.table.EffectTable`)."""

    @property
    def runs(self) -> tuple[Run, ...]: ...  # every variant, in the table's order

    @property
    def problem(self) -> dict[str, Any]: ...  # the full problem's parts (its description)

    def cells(self, label: str) -> dict[str, Cell]: ...  # the run's change per quantity

    def interaction(self) -> dict[str, Cell]: ...  # full minus the sum of the single effects
