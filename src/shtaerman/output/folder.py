"""``shtaerman verify``: run studies and write a complete result folder, or nothing.

The folder is assembled aside and moved into place only when every file is written, so a
failed or interrupted run never leaves something that looks complete.
"""

from __future__ import annotations

import json
import sys
import time
from collections.abc import Callable, Mapping
from pathlib import Path
from typing import Any, TextIO

from ..plots.formats import check_figure_format
from ..plots.gallery import (
    paper_figures,
    study_convergence_figures,
    study_field_figures,
    study_figures,
)
from ..study.kinds import kind_function
from ..study.run import StudyOutcome, run_study
from .export import write_indentation
from .files import json_safe, staged_folder, write_csv
from .report import results_document, study_document, write_reports

__all__ = [
    "ProgressBar",
    "finish_verification",
    "run_verification",
    "study_entry",
    "write_contact_study",
]


class ProgressBar:
    """One line per stage on stderr: ``[###---] 2/6 paper: FEM contact curve (3.1 s)``."""

    def __init__(self, total: int, stream: TextIO | None = None, width: int = 20) -> None:
        self.total, self.done, self.width = total, 0, width
        self.stream = sys.stderr if stream is None else stream
        self.start = time.perf_counter()

    def __call__(self, line: str) -> None:
        filled = round(self.width * self.done / max(self.total, 1))
        bar = "#" * filled + "-" * (self.width - filled)
        elapsed = time.perf_counter() - self.start
        print(
            f"[{bar}] {self.done}/{self.total} {line} ({elapsed:.1f} s)",
            file=self.stream,
            flush=True,
        )

    def advance(self) -> None:
        """Mark one study done."""
        self.done += 1


def write_contact_study(
    outcome: StudyOutcome, folder: Path, root: Path, figure_format: str = "png"
) -> tuple[dict[str, str], dict[str, str]]:
    """A contact study's files (VTU, CSV curves and histories) and figures, paths from root
    (``figure_format`` "svg" or "pdf": each chart also in that format beside its PNG)."""
    files = _study_files(outcome, folder, root)
    return files, _study_figures(outcome, folder, root, figure_format)


def _study_files(outcome: StudyOutcome, folder: Path, root: Path) -> dict[str, str]:
    folder.mkdir()
    written = write_indentation(outcome.contact, folder)
    for variant, history in outcome.histories.items():
        path = folder / f"history_{variant}.csv"
        write_csv(path, history.columns())
        written.append(path)
    return {path.stem: str(path.relative_to(root)) for path in written}


def _study_figures(
    outcome: StudyOutcome, folder: Path, root: Path, figure_format: str
) -> dict[str, str]:
    made = {
        **study_field_figures(outcome, folder),
        **study_figures(outcome, folder, figure_format),
        **study_convergence_figures(outcome, folder, figure_format),
    }
    return {title: str(path.relative_to(root)) for title, path in made.items()}


def study_entry(outcome: Any, stage: Path, figure_format: str = "png") -> dict[str, object]:
    """Write one study's files and figures into ``stage/<name>``; its results.json entry."""
    study = outcome.study
    start = time.perf_counter()
    write = kind_function(getattr(study, "kind", "contact"), "write")
    files, pictures = write(outcome, stage / study.name, stage, figure_format)
    return json_safe(study_document(outcome, files, time.perf_counter() - start, pictures))


def finish_verification(
    stage: Path, entries: Mapping[str, dict], *, quick: bool, figure_format: str = "png"
) -> dict[str, object]:
    """The figures of no study (the Ateb functions for each indenter exponent of the
    studies), results.json and both reports, from the studies' entries."""
    exponents = [entry["inputs"]["exponent"] for entry in entries.values() if "inputs" in entry]
    made = paper_figures(stage, exponents, figure_format)
    shared = {title: str(path.relative_to(stage)) for title, path in made.items()}
    results = results_document(entries, quick=quick, figures=shared)
    (stage / "results.json").write_text(json.dumps(results, indent=2), encoding="utf-8")
    write_reports(results, stage)
    return results


def run_verification(
    studies: list[Any],
    out: Path,
    *,
    quick: bool = False,
    progress: Callable[[str], None] | None = None,
    force: bool = False,
    figure_format: str = "png",
) -> dict[str, object]:
    """Run the studies one after another in this process and write ``out`` (results.json,
    report.md, report.html, per-study VTU fields, CSV curves and histories, PNG figures, and
    with ``figure_format`` "svg" or "pdf" each chart also in that format beside its PNG).
    Returns the results document. (``shtaerman verify`` runs them as dask tasks instead:
    :mod:`shtaerman.sweep.verify`.)

    ``out`` may exist only as an empty folder, or with ``force`` as any folder (replaced)."""
    check_figure_format(figure_format)
    bar = progress or ProgressBar(len(studies))
    advance = getattr(bar, "advance", lambda: None)
    with staged_folder(out, force=force) as stage:
        entries = {}
        for study in studies:
            outcome = run_study(study, quick=quick, progress=bar)
            bar(f"{study.name}: files and figures")
            entries[study.name] = study_entry(outcome, stage, figure_format)
            advance()
            bar(f"{study.name}: {'PASS' if outcome.passed else 'FAIL'}")
        return finish_verification(stage, entries, quick=quick, figure_format=figure_format)
