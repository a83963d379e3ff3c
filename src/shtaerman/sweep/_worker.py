"""Dask worker preload of the local cluster: the worker processes ignore SIGINT, die on SIGTERM
and keep freed memory for their next arrays.

Ctrl-C in a terminal reaches every process of the foreground group, the dask workers too; each
would print a KeyboardInterrupt traceback. The sweep's own process handles SIGINT (saves, shuts
the cluster down, says how to resume), so the workers leave it to it. A forked worker inherits
the sweep's own SIGTERM handler, which only sets a flag there: SIGTERM gets its default back,
so that the nanny (or the user) can still end the worker.
"""

from __future__ import annotations

import ctypes
import os
import signal
import threading

HEAP_KEPT = 1 << 30
"""Bytes: arrays up to this size come from the heap, and up to this much freed memory stays
there (glibc's M_MMAP_THRESHOLD and M_TRIM_THRESHOLD; larger arrays are mapped and unmapped)."""
_M_TRIM_THRESHOLD, _M_MMAP_THRESHOLD = -1, -3  # glibc's mallopt parameters (malloc.h)


def keep_freed_memory() -> None:
    """Let glibc's allocator reuse freed memory for the next arrays (no-op without glibc).

    By default glibc maps each block above its threshold (128 kB, raised to the largest block
    freed, at most 32 MB) afresh and returns it to the system when it is freed, so each case of
    a sweep faults its matrices and factors in again, page by page. 8 contact cases in one
    process: 220k page faults and 0.6-0.85 s of system CPU against 4.1-4.5 s of user CPU; with
    :data:`HEAP_KEPT`, 45k faults and 0.15-0.2 s (8 dynamic cases: 0.28 s against 0.10 s of
    6.5 s); 256 MB kept 0.33 s. Two workers faulting at once contend for the memory bus. At
    most :data:`HEAP_KEPT` of free memory stays on top of the heap of a worker.
    """
    try:
        if not (os.confstr("CS_GNU_LIBC_VERSION") or "").startswith("glibc"):
            return
    except (AttributeError, ValueError):  # no confstr (Windows), or not this name (macOS)
        return
    mallopt = ctypes.CDLL(None).mallopt
    mallopt(_M_MMAP_THRESHOLD, HEAP_KEPT)
    mallopt(_M_TRIM_THRESHOLD, HEAP_KEPT)


def dask_setup(worker: object) -> None:
    """Called by dask in each worker process as it starts."""
    if threading.current_thread() is threading.main_thread():
        signal.signal(signal.SIGINT, signal.SIG_IGN)
        signal.signal(signal.SIGTERM, signal.SIG_DFL)
    keep_freed_memory()
