"""``shtaerman verify``: run studies and write a complete result folder.

The folder is assembled aside and moved into place only when every file is written, so a
failed run never leaves something that looks complete. Each study is recorded in
:data:`PROGRESS_FILE` as it finishes; an interrupted run (Ctrl-C, SIGTERM) with finished
studies moves them into place with that file and without results.json or reports, and
``resume=True`` completes such a folder, computing only the studies it lacks.
"""

from __future__ import annotations

import contextlib
import dataclasses
import hashlib
import json
import os
import shutil
import sys
import time
from collections.abc import Callable, Iterable, Mapping
from dataclasses import dataclass
from functools import partial
from pathlib import Path
from typing import TYPE_CHECKING, Any, NoReturn, TextIO

from ..plots.formats import check_figure_format
from ..problem import worded
from ..signals import deferred
from ..study.kinds import kind_function
from ..study.run import run_study
from ..theory.indenter import PowerLawIndenter
from ..validation import InputError, NumericalFailureError
from .export import write_histories, write_indentation
from .files import FOLDER_MARKER, KeepStaged, json_safe, staged_folder
from .report import results_document, study_document, write_reports

if TYPE_CHECKING:
    from ..study.contact.runner import StudyOutcome

__all__ = [
    "PROGRESS_FILE",
    "Executor",
    "ProgressBar",
    "Resuming",
    "VerifyInterrupted",
    "compute_study",
    "finish_verification",
    "in_process",
    "keep_finished",
    "kept_entries",
    "run_verification",
    "save_progress",
    "shared_figures",
    "study_entry",
    "write_contact_study",
]


PROGRESS_FILE = "incomplete.json"
"""Marker of a result folder whose run was interrupted: the finished studies' entries."""
PROGRESS_FORMAT = "shtaerman-verify-progress-1"


class VerifyInterrupted(BaseException):
    """A verify run stopped by ``cause`` (Ctrl-C, SIGTERM, an error) after ``kept`` of
    ``total`` studies finished; those are in the result folder, which ``resume=True``
    completes, or with ``force`` in ``kept_in`` beside the old folder, left whole."""

    def __init__(self, cause: BaseException, kept: int, total: int) -> None:
        super().__init__(type(cause).__name__)
        self.cause, self.kept, self.total = cause, kept, total
        self.kept_in: Path | None = None


def study_fingerprint(study: Any) -> str:
    """A digest of every input of ``study`` but the path of its file, and of this shtaerman's
    version (hex, 16 characters): a study is kept for a resume only if both are the same."""
    from ..version import __version__

    if dataclasses.is_dataclass(study) and hasattr(study, "source"):
        study = dataclasses.replace(study, source=Path(""))
    return hashlib.sha256(f"{__version__}\n{study!r}".encode()).hexdigest()[:16]


def save_progress(
    stage: Path,
    studies: list[Any],
    entries: Mapping[str, dict],
    quick: bool,
    inputs: Mapping[str, Any] | None = None,
) -> None:
    """Write :data:`PROGRESS_FILE` in ``stage``: the finished studies' entries, and the
    ``inputs`` a resume must give again (JSON values; atomic)."""
    fingerprints = {study.name: study_fingerprint(study) for study in studies}
    document = {
        "format": PROGRESS_FORMAT,
        "quick": quick,
        "requested": sorted(fingerprints),
        "studies": {
            name: {"fingerprint": fingerprints[name], "entry": entry}
            for name, entry in entries.items()
        },
        **({} if inputs is None else {"inputs": json_safe(dict(inputs))}),
    }
    temporary = stage / f".{PROGRESS_FILE}.tmp"
    temporary.write_text(json.dumps(document), encoding="utf-8")
    os.replace(temporary, stage / PROGRESS_FILE)


@dataclass(frozen=True)
class Resuming:
    """How a command words its refusals of a resume: its option, what it makes (``run``) of
    what (``items``), and how to resume it the same way (``same``)."""

    option: str = "resume"
    run: str = "run"
    items: str = "studies"
    same: str = "resume it with the same studies (the command it printed)"


def kept_entries(
    stage: Path,
    studies: list[Any],
    *,
    quick: bool,
    inputs: Mapping[str, Any] | None = None,
    words: Resuming = Resuming(),
) -> dict[str, dict]:
    """The entries of the finished studies a resumed folder holds (``stage`` starts with its
    content) whose inputs are the same as now; everything else in ``stage`` is removed.

    Raises
    ------
    InputError
        When the folder was run with another ``quick``, other ``inputs`` (as
        :func:`save_progress` saved them) or other studies than ``studies`` (one it finished
        would be lost, one it did not finish silently dropped), or its progress file is
        unreadable; worded by ``words``.
    """
    marker = stage / PROGRESS_FILE
    if not marker.is_file():
        return {}
    option, run = words.option, words.run
    try:
        document = json.loads(marker.read_text(encoding="utf-8"))
        stored = document["studies"] if document["format"] == PROGRESS_FORMAT else None
        if not isinstance(stored, dict) or not isinstance(document["quick"], bool):
            raise ValueError("not a progress file")
    except (OSError, ValueError, KeyError, TypeError):
        raise InputError(
            f"{option}: {PROGRESS_FILE} is not one this tool wrote; use force=True to start again",
            option,
        ) from None
    if document["quick"] != quick:
        mode = "with --quick" if document["quick"] else "without --quick"
        raise InputError(
            f"{option}: the interrupted {run} was {mode}; resume it the same way", option
        )
    _check_inputs(document.get("inputs"), inputs, words)
    wanted = {study.name: study_fingerprint(study) for study in studies}
    dropped = sorted(name for name in stored if name not in wanted)
    if dropped:
        raise InputError(
            f"{option}: the interrupted {run} also finished {', '.join(map(repr, dropped))}, "
            f"which this command does not name; {words.same}",
            option,
        )
    requested = document.get("requested")  # absent from the files of earlier versions
    if isinstance(requested, list) and sorted(map(str, requested)) != sorted(wanted):
        raise InputError(
            f"{option}: the interrupted {run} was of the {words.items} "
            f"{', '.join(map(str, requested))}; {words.same}, or start again with force=True",
            option,
        )
    kept = {
        name: item["entry"]
        for name, item in stored.items()
        if isinstance(item, dict)
        and isinstance(item.get("entry"), dict)
        and wanted.get(name) == item.get("fingerprint")
    }
    for path in stage.iterdir():
        if path.name == FOLDER_MARKER:
            continue
        if path.name not in kept or path.name == PROGRESS_FILE:  # unfinished, changed, marker
            _remove_entry(path)
    return kept


def _check_inputs(stored: Any, inputs: Mapping[str, Any] | None, words: Resuming) -> None:
    """Refuse a resume whose ``inputs`` differ from those ``stored`` with the kept runs (none
    stored: an earlier version's file, not checked), naming each that differs as ``name=...``
    (:func:`shtaerman.problem.worded` spells it per route)."""
    if inputs is None or not isinstance(stored, dict):
        return
    now = json.loads(json.dumps(json_safe(dict(inputs))))
    differ = [name for name in sorted({*stored, *now}) if stored.get(name) != now.get(name)]
    if differ:
        changes = ", ".join(f"{n}=... ({stored.get(n)} there, {now.get(n)} now)" for n in differ)
        raise InputError(
            f"{words.option}: the interrupted {words.run}'s kept runs were made with another "
            f"{changes}; {words.same}, or start again with force=True",
            words.option,
        )


def _remove_entry(path: Path) -> None:
    if path.is_dir() and not path.is_symlink():
        shutil.rmtree(path)
    else:
        path.unlink()


def keep_finished(
    stage: Path,
    studies: list[Any],
    entries: Mapping[str, dict],
    error: BaseException,
    *,
    quick: bool,
    inputs: Mapping[str, Any] | None = None,
) -> NoReturn:
    """Re-raise ``error``; after some studies finished, as :class:`KeepStaged` that moves them
    (with :data:`PROGRESS_FILE`, ``inputs`` as :func:`save_progress`) into place, for an
    interruption and an error alike."""
    if not entries:
        raise error
    for path in stage.iterdir():
        if path.name not in entries and path.name not in (PROGRESS_FILE, FOLDER_MARKER):
            _remove_entry(path)
    with contextlib.suppress(OSError):  # a full disk: the file of the last study stands
        save_progress(stage, studies, entries, quick, inputs)
    raise KeepStaged(VerifyInterrupted(error, len(entries), len(studies))) from None


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
    # imported here, not at the top: the process that runs the studies on dask workers
    # draws no study's figures, and matplotlib, pyvista and VTK cost it ~1 s before the
    # workers start (benchmarks/verify_cost.py); signals held: VTK's import, interrupted,
    # segfaulted at times
    with deferred():
        from ..plots.gallery import study_figures

    folder.mkdir()
    written = write_indentation(outcome.contact, folder)
    written += write_histories(outcome.histories, folder)
    made = study_figures(outcome, folder, figure_format)
    return (
        {path.stem: str(path.relative_to(root)) for path in written},
        {title: str(path.relative_to(root)) for title, path in made.items()},
    )


def study_entry(outcome: Any, stage: Path, figure_format: str = "png") -> dict[str, object]:
    """Write one study's files and figures into ``stage/<name>``; its results.json entry."""
    study = outcome.study
    start = time.perf_counter()
    write = kind_function(getattr(study, "kind", "contact"), "write")
    files, pictures = write(outcome, stage / study.name, stage, figure_format)
    return json_safe(study_document(outcome, files, time.perf_counter() - start, pictures))


def finish_verification(
    stage: Path,
    entries: Mapping[str, dict],
    *,
    quick: bool,
    figure_format: str = "png",
    drawn: SharedFigures | None = None,
) -> dict[str, object]:
    """The figures of no study (:func:`shared_figures`: unless ``drawn`` holds those of the
    studies' exponents), results.json and both reports, from the studies' entries."""
    inputs = [entry["inputs"] for entry in entries.values() if "inputs" in entry]
    exponents = [given["exponent"] for given in inputs if given["exponent"] is not None]
    if drawn is None or drawn[0] != tuple(sorted(set(exponents))):
        drawn = shared_figures(str(stage), exponents, figure_format)
    results = results_document(entries, quick=quick, figures=drawn[1])
    (stage / "results.json").write_text(json.dumps(results, indent=2), encoding="utf-8")
    write_reports(results, stage)
    return results


SharedFigures = tuple[tuple[float, ...], dict[str, str]]
"""The figures of no study: the exponents they are drawn for (sorted, once each), and caption
-> path relative to the result folder."""


def shared_figures(stage: str, exponents: Iterable[float], figure_format: str) -> SharedFigures:
    """The figures of no study (the Ateb functions for each power-law exponent; a sphere or a
    tabulated profile has none), drawn into ``stage``: a task of its own, which a worker done
    with its studies draws while another finishes (:func:`run_verification`)."""
    # not from plots.gallery: this process (on dask, the one that runs no study) draws no
    # field, and gallery would import pyvista and VTK (benchmarks/verify_cost.py)
    from ..plots.ateb import paper_figures

    made = paper_figures(stage, exponents, figure_format)
    relative = {title: str(path.relative_to(stage)) for title, path in made.items()}
    return tuple(sorted(set(exponents))), relative


def study_exponents(studies: list[Any]) -> list[float]:
    """The power-law exponents of ``studies``' strikers (a profile of another kind has none)."""
    return [
        study.indenter.exponent
        for study in studies
        if isinstance(getattr(study, "indenter", None), PowerLawIndenter)
    ]


Finished = Callable[[Any, dict], None]
"""Told each study with its results.json entry as soon as its files are written."""
Executor = Callable[
    [list[Any], Path, bool, str, Callable[[str], None], Finished, Callable[[], SharedFigures]],
    SharedFigures,
]
"""Runs ``(todo, stage, quick, figure_format, progress, finished, shared)``: computes each
study of ``todo``, writes its files into ``stage`` (:func:`compute_study`) and calls
``finished``; runs ``shared`` (a picklable task, :func:`shared_figures`) and returns what it
drew."""


def compute_study(
    study: Any,
    stage: Path,
    quick: bool,
    figure_format: str = "png",
    progress: Callable[[str], None] | None = None,
) -> dict[str, object]:
    """Run one study and write its files and figures into ``stage``; its results.json entry.

    Raises
    ------
    InputError, NumericalFailureError
        An input the FEM refuses, a computation that failed (what to change in the study
        file's words: :func:`shtaerman.problem.worded`); a failure's message starts with the
        study file and the study's name.
    """
    try:
        outcome = run_study(study, quick=quick, progress=progress)
    except (InputError, NumericalFailureError) as error:
        said = worded(str(error), "file")
        if isinstance(error, NumericalFailureError):
            raise NumericalFailureError(f"{study.source}: study {study.name!r}: {said}") from None
        if said == str(error):
            raise
        raise type(error)(said, error.parameter) from None
    if progress is not None:
        progress(f"{study.name}: files and figures")
    return study_entry(outcome, stage, figure_format)


def in_process(
    todo: list[Any],
    stage: Path,
    quick: bool,
    figure_format: str,
    progress: Callable[[str], None],
    finished: Finished,
    shared: Callable[[], SharedFigures],
) -> SharedFigures:
    """The :data:`Executor` that runs the studies one after another in this process, on one
    BLAS thread as a dask task runs them (:func:`shtaerman.sweep.verify.verify_task`), so that
    ``--workers 1`` prints the default run's numbers."""
    from threadpoolctl import threadpool_limits

    with threadpool_limits(limits=1, user_api="blas"):
        for study in todo:
            finished(study, compute_study(study, stage, quick, figure_format, progress))
    return shared()


def run_verification(
    studies: list[Any],
    out: Path,
    *,
    quick: bool = False,
    progress: Callable[[str], None] | None = None,
    force: bool = False,
    figure_format: str = "png",
    resume: bool = False,
    executor: Executor = in_process,
) -> dict[str, object]:
    """Run the studies and write ``out`` (results.json, report.md, report.html, per-study VTU
    fields, CSV curves and histories, PNG figures, and with ``figure_format`` "svg" or "pdf"
    each chart also in that format beside its PNG). Returns the results document.

    ``executor`` computes the studies (default: one after another in this process;
    :mod:`shtaerman.sweep.verify` runs them as dask tasks). ``out`` may exist only as an empty
    folder, or with ``force`` as a result folder of this tool (replaced), or with ``resume``
    as a folder a stopped run left (its finished studies are kept). Each finished study is
    recorded in :data:`PROGRESS_FILE` at once: a run stopped by a signal or an error keeps
    them in ``out`` (with ``force``: beside it, ``out`` left whole; the exception's
    ``kept_in`` says where), and after a SIGKILL the next run writing ``out`` moves them there.

    Raises
    ------
    VerifyInterrupted
        Ctrl-C, SIGTERM or an error after some studies finished: they are in ``out``, or in
        its ``kept_in`` (``force``).
    """
    check_figure_format(figure_format)
    bar = progress or ProgressBar(len(studies))
    advance = getattr(bar, "advance", lambda: None)
    marker = PROGRESS_FILE if resume else None
    with staged_folder(out, force=force, resume_marker=marker, keep_marker=PROGRESS_FILE) as stage:
        entries = kept_entries(stage, studies, quick=quick)
        for _ in entries:
            advance()

        def finished(study: Any, entry: dict) -> None:
            save_progress(stage, studies, {**entries, study.name: entry}, quick)
            entries[study.name] = entry
            advance()
            bar(f"{study.name}: {'PASS' if entry['passed'] else 'FAIL'}")

        try:
            todo = [study for study in studies if study.name not in entries]
            drawn, exponents = None, study_exponents(studies)
            if todo:
                shared = partial(shared_figures, str(stage), exponents, figure_format)
                drawn = executor(todo, stage, quick, figure_format, bar, finished, shared)
            in_file_order = {study.name: entries[study.name] for study in studies}
            results = finish_verification(
                stage, in_file_order, quick=quick, figure_format=figure_format, drawn=drawn
            )
        except BaseException as error:
            keep_finished(stage, studies, entries, error, quick=quick)
        # absent when a resume found every study finished (it wrote no progress of its own)
        (stage / PROGRESS_FILE).unlink(missing_ok=True)
        return results
