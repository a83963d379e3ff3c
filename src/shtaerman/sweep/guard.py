"""A script that starts a sweep without an ``if __name__ == "__main__":`` guard.

On Linux the local cluster forks its workers (:mod:`shtaerman.sweep.engine`), which never
run the main script again: no guard is needed there. Elsewhere dask starts each worker with
multiprocessing's spawn (or forkserver), which runs the main script again in the new process
before it becomes a worker, and an unguarded script would call the sweep again. The copy in
the worker stops at once, silently, and leaves a mark in the cluster's scratch folder
(:data:`SCRATCH_ENV` names it); the sweep that started the cluster finds the mark when the
cluster fails and raises one :class:`InputError` that names the guard.
"""

from __future__ import annotations

import contextlib
import multiprocessing
import os
from pathlib import Path

from ..validation import InputError

__all__ = ["SCRATCH_ENV", "check_not_bootstrapping", "raise_if_unguarded"]

SCRATCH_ENV = "SHTAERMAN_SWEEP_SCRATCH"
"""Environment variable of the worker processes: the local cluster's scratch folder."""
MARK = "unguarded-main"
UNGUARDED = (
    "sweep: the main script starts a sweep as it is imported, and dask's worker processes "
    "import it again; start it under 'if __name__ == \"__main__\":' (a notebook needs no guard)"
)


def check_not_bootstrapping() -> None:
    """Stop the process quietly when it is a new worker that runs the main script again.

    multiprocessing marks the process as ``_inheriting`` while it runs the parent's main
    script (spawn, forkserver). The mark for :func:`raise_if_unguarded` is left in the
    scratch folder of the cluster; outside one (a user's own process pool) the reason is
    printed instead, as the only line.
    """
    if not getattr(multiprocessing.current_process(), "_inheriting", False):
        return
    scratch = os.environ.get(SCRATCH_ENV)
    if scratch is None:
        raise SystemExit(f"shtaerman: error: {UNGUARDED}")
    with contextlib.suppress(OSError):
        (Path(scratch) / MARK).touch()
    raise SystemExit(1)


def raise_if_unguarded(scratch: str) -> None:
    """Raise InputError naming the guard when a worker of the cluster with this ``scratch``
    folder stopped in the main script (:func:`check_not_bootstrapping`); without the
    exception being handled (dask's "Nanny failed to start", which says less)."""
    if (Path(scratch) / MARK).exists():
        raise InputError(UNGUARDED) from None
