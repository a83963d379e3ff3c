"""Freed memory kept for the next arrays: glibc's allocator thresholds raised, in our processes.

By default glibc maps each block above its threshold (128 kB, raised to the largest block freed,
at most 32 MB) afresh and returns it to the system when it is freed, so every solve faults its
matrices and factors in again, page by page. Called by the command line's process and by each
sweep worker as it starts; a library import changes nothing in the user's process.
"""

from __future__ import annotations

import ctypes
import os

HEAP_KEPT = 1 << 30
"""Bytes: arrays up to this size come from the heap, and up to this much freed memory stays
there (glibc's M_MMAP_THRESHOLD and M_TRIM_THRESHOLD; larger arrays are mapped and unmapped)."""
_M_TRIM_THRESHOLD, _M_MMAP_THRESHOLD = -1, -3  # glibc's mallopt parameters (malloc.h)


def keep_freed_memory() -> bool:
    """Let glibc's allocator reuse freed memory for the next arrays; False without glibc or
    where glibc refuses a threshold. At most :data:`HEAP_KEPT` of free memory stays on top of
    the process's heap (the page faults it saves: the commits that introduced it)."""
    try:
        if not (os.confstr("CS_GNU_LIBC_VERSION") or "").startswith("glibc"):
            return False
    except (AttributeError, ValueError):  # no confstr (Windows), or not this name (macOS)
        return False
    mallopt = ctypes.CDLL(None).mallopt
    return bool(mallopt(_M_MMAP_THRESHOLD, HEAP_KEPT)) and bool(
        mallopt(_M_TRIM_THRESHOLD, HEAP_KEPT)
    )
