"""The results.json entry of a study of any kind: its own keys plus the common ones."""

from __future__ import annotations

from collections.abc import Callable, Mapping
from typing import Any

from .case import prefixed

__all__ = ["kind_entry", "no_summary_row", "stored_findings", "stored_tables", "text_entry"]


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


def text_entry(
    outcome: Any,
    text: tuple[Callable[[Any], list], Callable[[Any], list]],
    files: dict[str, str],
    output_seconds: float | None,
    figures: Mapping[str, str] | None,
    *,
    case: str,
) -> dict[str, object]:
    """The entry of a kind whose text is made with the outcome: its ``case`` in words
    (:func:`.case.case_words`), its numbers, the display ``tables`` and ``findings``
    (``text``: the kind's two functions of the outcome) and the common keys
    (:func:`kind_entry`)."""
    study_tables, study_findings = text
    document = {
        "case": case,
        **outcome.document(),
        "tables": study_tables(outcome),
        "findings": study_findings(outcome),
    }
    return kind_entry(outcome, document, files, output_seconds, figures)


def stored_tables(study: Mapping[str, Any]) -> list[dict[str, object]]:
    """The display tables stored in a results.json entry."""
    return list(study.get("tables", []))


def stored_findings(name: str, study: Mapping[str, Any]) -> list[str]:
    """The findings stored in a results.json entry, each prefixed with the study's name and
    its case (:func:`.case.prefixed`)."""
    return [prefixed(name, study, sentence) for sentence in study.get("findings", [])]


def no_summary_row(name: str, study: Mapping[str, Any]) -> None:
    """No row in the contact cross-check summary."""
    return None
