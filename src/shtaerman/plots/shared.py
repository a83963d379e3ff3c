"""A context shared by the threads that draw at once: global state (matplotlib's rcParams,
VTK's warning switch) is set when the first enters and restored when the last leaves.

Why not one context per figure: two threads drawing at once (a user's thread pool, a threaded
dask scheduler) would each restore on leaving the state the other still draws with.
"""

from __future__ import annotations

import threading
from collections.abc import Callable, Iterator
from contextlib import AbstractContextManager, contextmanager

__all__ = ["SharedContext"]


class SharedContext:
    """``with shared():`` holds ``make()``'s context while any thread is inside."""

    def __init__(self, make: Callable[[], AbstractContextManager]) -> None:
        self._make = make
        self._lock = threading.Lock()
        self._inside = 0
        self._context: AbstractContextManager | None = None

    @contextmanager
    def __call__(self) -> Iterator[None]:
        with self._lock:
            if self._inside == 0:
                context = self._make()
                context.__enter__()
                self._context = context
            self._inside += 1
        try:
            yield
        finally:
            with self._lock:
                self._inside -= 1
                if self._inside == 0 and self._context is not None:
                    self._context.__exit__(None, None, None)
                    self._context = None
