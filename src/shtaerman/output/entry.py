"""The results.json entry of a study of any kind: its own keys plus the common ones."""

from __future__ import annotations

from collections.abc import Mapping
from typing import Any

__all__ = ["kind_entry"]


def kind_entry(
    outcome: Any,
    document: Mapping[str, object],
    files: dict[str, str],
    output_seconds: float | None,
    figures: Mapping[str, str] | None,
) -> dict[str, object]:
    """``document`` (the kind's keys) between ``kind``, ``description``, ``source`` and the
    common keys: ``checks``, ``passed``, ``seconds``, ``timings`` (computation, output, total
    in s), ``files`` and ``figures`` (paths relative to the result folder)."""
    study = outcome.study
    return {
        "kind": study.kind,
        "description": study.description,
        "source": str(study.source),
        **document,
        "checks": [check.to_dict() for check in outcome.checks],
        "passed": outcome.passed,
        "seconds": outcome.seconds,
        "timings": {
            "computation": outcome.seconds,
            "output": output_seconds,
            "total": outcome.seconds + (output_seconds or 0.0),
        },
        "files": files,
        "figures": dict(figures or {}),
    }
