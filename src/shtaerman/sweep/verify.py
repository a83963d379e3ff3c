"""``shtaerman verify`` on the sweep engine: every study one dask task, the cores all busy.

Each task runs its study and writes the study's files and figures into the staging folder
(the workers of the local cluster share this machine's disk) and returns its results.json
entry; :func:`shtaerman.output.folder.run_verification` collects the entries as they finish,
with :func:`on_dask` as its executor, and writes results.json and the reports. A study's
validity warnings travel in its entry (``warnings``) and are said by this process, as a
study run here says them.
"""

from __future__ import annotations

import warnings
from collections.abc import Callable
from pathlib import Path
from typing import Any

from ..guards import ValidityWarning
from ..output.folder import Executor, Finished, SharedFigures, compute_study, run_verification
from ..study.run import say_warnings
from ..validation import InputError, NumericalFailureError
from .engine import dask_client, worker_count

__all__ = ["on_dask", "run_verification_on_dask", "submission_order", "verify_task"]


def submission_order(studies: list[Any]) -> list[Any]:
    """The long studies first (finite strain, then dynamic, then contact), so the workers
    finish together instead of one waiting on a late long study."""
    rank = {"finite-strain": 0, "dynamic": 1}
    return sorted(studies, key=lambda study: rank.get(getattr(study, "kind", ""), 2))


FAILURE = "failure"
"""Key of a task's result that carries a refused input or a failed computation instead of an
entry, as (kind, message): returned, not raised, so that the worker does not log it as a
failed task with its traceback."""
FAILURES = {"input": InputError, "numerical": NumericalFailureError}
STUDY_MEMORY = {"contact": 800e6, "dynamic": 900e6, "finite-strain": 800e6}
"""Resident memory of a local worker process running a study of each kind (its FEM runs,
files and figures), bytes; other kinds: the largest."""


def verify_task(
    study: Any, stage: str, quick: bool, figure_format: str = "png"
) -> dict[str, object]:
    """One study, run and written (a dask task): its results.json entry, or
    {:data:`FAILURE`: (kind, message)} for an input the FEM refused or a failed computation.
    The study's validity warnings are in the entry, not said here (:func:`on_dask` says them)."""
    from threadpoolctl import threadpool_limits

    with threadpool_limits(limits=1, user_api="blas"), warnings.catch_warnings():
        warnings.simplefilter("ignore", ValidityWarning)
        try:
            return compute_study(study, Path(stage), quick, figure_format)
        except InputError as error:
            return {FAILURE: ("input", str(error))}
        except NumericalFailureError as error:
            return {FAILURE: ("numerical", str(error))}


def on_dask(workers: int | None = None) -> Executor:
    """An executor for :func:`run_verification`: one dask task per study on a local cluster
    of at most ``workers`` processes (default: the cores; never more than the studies to
    compute nor than the free memory holds)."""

    def execute(
        todo: list[Any],
        stage: Path,
        quick: bool,
        figure_format: str,
        progress: Callable[[str], None],
        finished: Finished,
        shared: Callable[[], SharedFigures],
    ) -> SharedFigures:
        from distributed import as_completed

        kinds = {getattr(study, "kind", "contact") for study in todo}
        memory = max(STUDY_MEMORY.get(kind, max(STUDY_MEMORY.values())) for kind in kinds)
        count = worker_count(workers, len(todo), memory, "studies")
        with dask_client(count) as client:
            progress(f"{len(todo)} studies on {len(client.scheduler_info()['workers'])} workers")
            futures = {
                client.submit(verify_task, study, str(stage), quick, figure_format, pure=False): (
                    study
                )
                for study in submission_order(todo)
            }
            # last in the queue: the first worker done with its studies draws them
            drawing = client.submit(shared, pure=False)
            for future in as_completed(futures):
                entry = future.result()
                if FAILURE in entry:
                    client.cancel(list(futures))  # the other studies' results are moot
                    kind, message = entry[FAILURE]
                    raise FAILURES[kind](message)
                say_warnings(futures[future], entry["warnings"])
                finished(futures[future], entry)
            return drawing.result()

    return execute


def run_verification_on_dask(
    studies: list[Any],
    out: Path,
    *,
    workers: int | None = None,
    **options: Any,
) -> dict[str, object]:
    """:func:`shtaerman.output.folder.run_verification` with the studies as dask tasks on a
    local cluster of at most ``workers`` processes (default: the cores); ``options`` as
    there (quick, force, resume, progress, figure_format)."""
    return run_verification(studies, out, executor=on_dask(workers), **options)
