"""``shtaerman verify``: run studies and write a complete result folder, or nothing.

The folder is assembled aside and moved into place only when every file is written, so a
failed or interrupted run never leaves something that looks complete.
"""

from __future__ import annotations

import json
import sys
import time
from collections.abc import Callable
from pathlib import Path
from typing import TextIO

from ..plots.gallery import (
    paper_figures,
    study_convergence_figures,
    study_field_figures,
    study_figures,
)
from ..study.kinds import kind_function
from ..study.run import StudyOutcome, run_study
from ..study.schema import Study
from .export import write_indentation
from .files import staged_folder, write_csv
from .report import results_document, write_reports

__all__ = ["ProgressBar", "run_verification", "write_contact_study"]


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
    outcome: StudyOutcome, folder: Path, root: Path
) -> tuple[dict[str, str], dict[str, str]]:
    """A contact study's files (VTU, CSV curves and histories) and figures, paths from root."""
    return _study_files(outcome, folder, root), _study_figures(outcome, folder, root)


def _study_files(outcome: StudyOutcome, folder: Path, root: Path) -> dict[str, str]:
    folder.mkdir()
    written = write_indentation(outcome.contact, folder)
    for variant, history in outcome.histories.items():
        path = folder / f"history_{variant}.csv"
        write_csv(path, history.columns())
        written.append(path)
    return {path.stem: str(path.relative_to(root)) for path in written}


def _study_figures(outcome: StudyOutcome, folder: Path, root: Path) -> dict[str, str]:
    made = {
        **study_field_figures(outcome, folder),
        **study_figures(outcome, folder),
        **study_convergence_figures(outcome, folder),
    }
    return {title: str(path.relative_to(root)) for title, path in made.items()}


def run_verification(
    studies: list[Study],
    out: Path,
    *,
    quick: bool = False,
    progress: Callable[[str], None] | None = None,
    force: bool = False,
) -> dict[str, object]:
    """Run the studies and write ``out`` (results.json, report.md, report.html, per-study
    VTU fields, CSV curves and histories, PNG figures). Returns the results document.

    ``out`` may exist only as an empty folder, or with ``force`` as any folder (replaced)."""
    bar = progress or ProgressBar(len(studies))
    advance = getattr(bar, "advance", lambda: None)
    with staged_folder(out, force=force) as stage:
        outcomes, files, pictures, writing = [], {}, {}, {}
        for study in studies:
            outcome = run_study(study, quick=quick, progress=bar)
            bar(f"{study.name}: files and figures")
            start = time.perf_counter()
            write = kind_function(getattr(study, "kind", "contact"), "write")
            files[study.name], pictures[study.name] = write(outcome, stage / study.name, stage)
            writing[study.name] = time.perf_counter() - start
            outcomes.append(outcome)
            advance()
            bar(f"{study.name}: {'PASS' if outcome.passed else 'FAIL'}")
        pictures[""] = {
            title: str(path.relative_to(stage)) for title, path in paper_figures(stage).items()
        }
        results = results_document(
            outcomes, files, quick=quick, output_seconds=writing, figures=pictures
        )
        (stage / "results.json").write_text(json.dumps(results, indent=2), encoding="utf-8")
        write_reports(results, stage)
    return results
