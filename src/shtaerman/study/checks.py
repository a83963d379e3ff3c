"""A pass/fail check: a relative difference against its tolerance (every study kind)."""

from __future__ import annotations

from collections.abc import Iterable
from dataclasses import dataclass

__all__ = ["Check", "failures"]


@dataclass(frozen=True)
class Check:
    """One pass/fail comparison: a relative difference against its tolerance."""

    name: str
    value: float
    tolerance: float

    @property
    def passed(self) -> bool:
        """Whether |value| <= tolerance."""
        return abs(self.value) <= self.tolerance

    def to_dict(self) -> dict[str, object]:
        """Plain data for JSON."""
        return {
            "name": self.name,
            "value": self.value,
            "tolerance": self.tolerance,
            "passed": self.passed,
        }


def failures(checks: Iterable[Check]) -> tuple[str, ...]:
    """One line per check that fails: its name, its value and its tolerance."""
    return tuple(
        f"{check.name}: {check.value:.2e} beyond its tolerance {check.tolerance:g}"
        for check in checks
        if not check.passed
    )
