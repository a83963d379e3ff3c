"""``shtaerman verify`` on the sweep engine: every study one dask task, the cores all busy.

Each task runs its study and writes the study's files and figures into the staging folder
(the workers of the local cluster share this machine's disk) and returns its results.json
entry; this process collects the entries as they finish, then writes results.json and the
reports. The folder is staged and moved into place only when complete, as in the sequential
:func:`shtaerman.output.folder.run_verification`, which runs the same steps in this process.
"""

from __future__ import annotations

from collections.abc import Callable
from pathlib import Path
from typing import Any

from ..output.files import staged_folder
from ..output.folder import (
    PROGRESS_FILE,
    finish_verification,
    keep_finished,
    kept_entries,
    save_progress,
    study_entry,
)
from ..plots.formats import check_figure_format
from ..study.run import run_study
from ..validation import InputError
from .engine import dask_client

__all__ = ["run_verification_on_dask", "submission_order", "verify_task"]


def submission_order(studies: list[Any]) -> list[Any]:
    """The long studies first (finite strain, then dynamic, then contact), so the workers
    finish together instead of one waiting on a late long study."""
    rank = {"finite-strain": 0, "dynamic": 1}
    return sorted(studies, key=lambda study: rank.get(getattr(study, "kind", ""), 2))


INPUT_ERROR = "input_error"
"""Key of a task's result that carries a refused input instead of an entry: returned, not
raised, so that the worker does not log the refusal as a failed computation with its
traceback."""


def verify_task(
    study: Any, stage: str, quick: bool, figure_format: str = "png"
) -> dict[str, object]:
    """One study, run and written (a dask task): its results.json entry, or
    {:data:`INPUT_ERROR`: message} for an input the FEM refused."""
    from threadpoolctl import threadpool_limits

    with threadpool_limits(limits=1, user_api="blas"):
        try:
            return study_entry(run_study(study, quick=quick), Path(stage), figure_format)
        except InputError as error:
            return {INPUT_ERROR: str(error)}


def run_verification_on_dask(
    studies: list[Any],
    out: Path,
    *,
    quick: bool = False,
    workers: int | None = None,
    force: bool = False,
    resume: bool = False,
    progress: Callable[[str], None] | None = None,
    figure_format: str = "png",
) -> dict[str, object]:
    """Run the studies as dask tasks on a local cluster and write ``out``; the results document.

    Parameters
    ----------
    studies : list
        Loaded studies of any kind.
    out : Path
        The result folder (new, or replaced with ``force``, or completed with ``resume``).
    quick : bool
        Coarse settings (CI).
    workers : int, optional
        Worker processes (default: the cores).
    resume : bool
        Keep the finished studies of a folder an interrupted run left; compute the others.
    progress : callable, optional
        Receives one line per finished study.
    figure_format : {"png", "svg", "pdf"}
        "svg" or "pdf" also writes each chart in that format beside its PNG.

    Raises
    ------
    VerifyInterrupted
        Ctrl-C or SIGTERM after some studies finished: they are in ``out``.
    """
    check_figure_format(figure_format)
    report = progress or (lambda _line: None)
    marker = PROGRESS_FILE if resume else None
    with staged_folder(out, force=force, resume_marker=marker) as stage:
        entries = kept_entries(stage, studies, quick=quick)
        todo = [study for study in studies if study.name not in entries]
        try:
            for _ in entries:
                getattr(report, "advance", lambda: None)()
            if todo:
                task = (str(stage), quick, figure_format)
                _run_on_dask(todo, studies, task, entries, workers, report)
        except BaseException as error:
            keep_finished(stage, studies, entries, error, quick=quick)
        (stage / PROGRESS_FILE).unlink(missing_ok=True)
        in_file_order = {study.name: entries[study.name] for study in studies}
        return finish_verification(stage, in_file_order, quick=quick, figure_format=figure_format)


def _run_on_dask(
    todo: list[Any],
    studies: list[Any],
    task: tuple[str, bool, str],
    entries: dict[str, dict],
    workers: int | None,
    report: Callable[[str], None],
) -> None:
    """Compute ``todo`` on a local cluster (``task``: the stage folder, quick and the figure
    format of :func:`verify_task`); each entry is added to ``entries`` and saved in the
    progress file as it arrives."""
    stage, quick = Path(task[0]), task[1]
    from distributed import as_completed

    advance = getattr(report, "advance", lambda: None)
    with dask_client(None if workers is None else min(workers, len(todo))) as client:
        report(f"{len(todo)} studies on {len(client.scheduler_info()['workers'])} workers")
        futures = {
            client.submit(verify_task, study, *task, pure=False): study.name
            for study in submission_order(todo)
        }
        for future in as_completed(futures):
            entry = future.result()
            if INPUT_ERROR in entry:
                client.cancel(list(futures))  # the other studies' results are moot
                raise InputError(entry[INPUT_ERROR])
            name = futures[future]
            entries[name] = entry
            save_progress(stage, studies, entries, quick)
            advance()
            verdict = "PASS" if entry["passed"] else "FAIL"
            report(f"{name}: {verdict} (computed in {entry['seconds']:.1f} s)")
