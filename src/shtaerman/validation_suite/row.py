"""One row of the validation suite: a published value against the suite's own, with the
tolerance the reference's accuracy allows."""

from __future__ import annotations

from dataclasses import asdict, dataclass
from typing import Any

__all__ = ["Row"]


@dataclass(frozen=True)
class Row:
    """A published value and the suite's value of the same quantity.

    Attributes
    ----------
    case : str
        Short name of the case (the table the row belongs to).
    source : str
        Authors, year, journal, equation or table.
    inputs : str
        The inputs, in words (dimensionless where the source is).
    quantity : str
        What is compared (dimensionless unless named).
    published : float
        The published value.
    value : float
        The suite's value, computed as a user would (``command``).
    error_bar : float
        The suite's own error bar on ``value`` (mesh estimate or fit), same unit.
    tolerance : float
        Largest accepted ``|value - published|``, same unit.
    why : str
        Why the tolerance is that wide: the reference's own accuracy.
    command : str
        The command a reader runs to get ``value``.
    verdict : str
        "agrees" when within tolerance; otherwise "refuted" with the argument in the docs
        (:attr:`expect_agreement` False) or "DISAGREES".
    """

    case: str
    source: str
    inputs: str
    quantity: str
    published: float
    value: float
    error_bar: float
    tolerance: float
    why: str
    command: str
    expect_agreement: bool = True

    @property
    def difference(self) -> float:
        """``value - published`` (same unit)."""
        return self.value - self.published

    @property
    def agrees(self) -> bool:
        """True when ``|difference| <= tolerance``."""
        return abs(self.difference) <= self.tolerance

    @property
    def verdict(self) -> str:
        """ "agrees", "refuted" (a published value the docs show is wrong) or "DISAGREES"."""
        if self.agrees:
            return "agrees"
        return "DISAGREES" if self.expect_agreement else "refuted"

    def to_dict(self) -> dict[str, Any]:
        """The row's JSON object: its fields, the difference and the verdict."""
        document = asdict(self)
        document.update(difference=self.difference, verdict=self.verdict)
        return document
