"""Dask worker preload of the local cluster: the worker processes ignore SIGINT.

Ctrl-C in a terminal reaches every process of the foreground group, the spawned dask workers
too; each would print a KeyboardInterrupt traceback. The sweep's own process handles SIGINT
(saves, shuts the cluster down, says how to resume), so the workers leave it to it.
"""

from __future__ import annotations

import signal
import threading


def dask_setup(worker: object) -> None:
    """Called by dask in each worker process as it starts."""
    if threading.current_thread() is threading.main_thread():
        signal.signal(signal.SIGINT, signal.SIG_IGN)
