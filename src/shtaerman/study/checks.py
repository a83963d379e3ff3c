"""A pass/fail check: a relative difference against its tolerance (every study kind)."""

from __future__ import annotations

from collections.abc import Iterable
from dataclasses import asdict, dataclass, field

__all__ = ["Check", "Outcome", "failures"]


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
        return {**asdict(self), "passed": self.passed}


def failures(checks: Iterable[Check]) -> tuple[str, ...]:
    """One line per check that fails: its name, its value and its tolerance."""
    return tuple(
        f"{check.name}: {check.value:.2e} beyond its tolerance {check.tolerance:g}"
        for check in checks
        if not check.passed
    )


@dataclass(frozen=True)
class Outcome:
    """What every study kind's run returns (:mod:`shtaerman.study.kinds`): a subclass adds
    ``study``, ``checks`` and its numbers; ``warnings`` are the validity warnings its runs
    issued, once each in the order issued, set by :func:`shtaerman.study.run.run_study`."""

    warnings: tuple[str, ...] = field(default=(), kw_only=True)

    @property
    def passed(self) -> bool:
        """Whether every check passed."""
        return all(check.passed for check in self.checks)  # type: ignore[attr-defined]
