"""Number formatting shared by the kinds' text modules (``text_*``): values, ± and times."""

from __future__ import annotations

import math
from collections.abc import Iterable, Mapping
from typing import Any

from ..problem import worded

__all__ = ["finest_passed", "number", "plus_minus", "seconds", "times_text"]


def number(value: float | None, spec: str) -> str:
    """``value`` formatted by ``spec``; "-" for a missing value."""
    return "-" if value is None else format(value, spec)


def seconds(value: float | None) -> str:
    """A time in s to 0.1 s; "-" when unknown."""
    return "-" if value is None else f"{value:.1f}"


def plus_minus(error: float | None, spec: str = ".1e", scale: float = 1.0) -> str:
    """The text " ± e" (``scale`` x ``error`` by ``spec``); "" without an estimate, and ""
    for an estimate of exactly 0 (identical on every level: it states no accuracy)."""
    if error is None or not math.isfinite(error) or error == 0:
        return ""
    return f" ± {scale * error:{spec}}"


def finest_passed(missing: str, levels: Iterable[Mapping[str, Any]]) -> str:
    """Why a ladder has no error estimate (``missing``, in a study file's words) and that the
    numbers are its finest level that passed, naming each level's dofs or "failed"."""
    ladder = ", ".join(
        "failed" if level["dofs"] is None else str(level["dofs"]) for level in levels
    )
    return (
        f"{worded(missing, 'file')}; the numbers are the finest level that passed (ladder "
        f"{ladder} dofs)"
    )


def times_text(study: Mapping[str, object], computation: str = "computation") -> str:
    """ "computation ... s; files and figures ... s; study total ... s" of a results entry
    (``computation``: the words of the first part)."""
    timings = study.get("timings") or {}
    parts = [f"{computation} {seconds(timings.get('computation', study['seconds']))} s"]
    if timings.get("output") is not None:
        parts.append(f"files and figures {seconds(timings['output'])} s")
    parts.append(f"study total {seconds(timings.get('total', study['seconds']))} s")
    return "; ".join(parts)
