"""Dask worker preload of the local cluster: the worker processes ignore SIGINT, die on SIGTERM,
log only what is critical and keep freed memory for their next arrays.

Ctrl-C in a terminal reaches every process of the foreground group, the dask workers too; each
would print a KeyboardInterrupt traceback. The sweep's own process handles SIGINT (saves, shuts
the cluster down, says how to resume), so the workers leave it to it. A forked worker inherits
the sweep's own SIGTERM handler, which only sets a flag there: SIGTERM gets its default back,
so that the nanny (or the user) can still end the worker.
"""

from __future__ import annotations

import logging
import signal

from ..allocator import keep_freed_memory

WORKER_LOGGERS = ("distributed", "tornado", "asyncio")
"""Loggers a worker keeps to CRITICAL: a task's exception reaches the sweep with its future,
and a worker still busy when the cluster shuts down would print a "heartbeat" traceback
(``DASK_LOGGING__DISTRIBUTED`` reaches only a spawned worker, which imports dask afresh)."""

SET_UP: list[str] = []
"""What :func:`dask_setup` did in this process, for a diagnosis."""


def dask_setup(worker: object) -> None:
    """Called by dask in each worker process as it starts.

    Python's own check decides whether this is the main thread (``signal.signal`` raises
    ValueError elsewhere), not the threading module's: in a worker forked from the nanny's
    watch thread, ``threading.main_thread()`` can still be the parent's main thread.
    """
    try:
        signal.signal(signal.SIGINT, signal.SIG_IGN)
        signal.signal(signal.SIGTERM, signal.SIG_DFL)
        SET_UP.append("signals")
    except ValueError as error:  # not the interpreter's main thread
        SET_UP.append(f"signals left: {error}")
    for name in WORKER_LOGGERS:
        logging.getLogger(name).setLevel(logging.CRITICAL)
    SET_UP.append("logs")
    keep_freed_memory()
    SET_UP.append("memory")
