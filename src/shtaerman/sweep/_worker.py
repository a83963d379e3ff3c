"""Dask worker preload of the local cluster: the worker processes ignore SIGINT, die on SIGTERM
and keep freed memory for their next arrays.

Ctrl-C in a terminal reaches every process of the foreground group, the dask workers too; each
would print a KeyboardInterrupt traceback. The sweep's own process handles SIGINT (saves, shuts
the cluster down, says how to resume), so the workers leave it to it. A forked worker inherits
the sweep's own SIGTERM handler, which only sets a flag there: SIGTERM gets its default back,
so that the nanny (or the user) can still end the worker.
"""

from __future__ import annotations

import signal
import threading

from ..allocator import keep_freed_memory

SET_UP: list[str] = []
"""What :func:`dask_setup` did in this process, for a diagnosis (a CI pass once found a forked
worker with the sweep's handlers still in place)."""


def dask_setup(worker: object) -> None:
    """Called by dask in each worker process as it starts."""
    thread = threading.current_thread()
    if thread is threading.main_thread():
        signal.signal(signal.SIGINT, signal.SIG_IGN)
        signal.signal(signal.SIGTERM, signal.SIG_DFL)
        SET_UP.append("signals")
    else:
        SET_UP.append(f"signals left: {thread.name} is not the main thread")
    keep_freed_memory()
    SET_UP.append("memory")
