"""Python's SIGINT/SIGTERM handlers kept working across calls into C extensions.

A C extension can break a Python signal handler in two ways, each with its own remedy. gmsh
runs Python code inside its calls (ctypes converts numpy arguments), so a handler raising
there surfaces as a foreign exception: :func:`deferred` holds the handlers until the block
ends. METIS (under pymetis) installs a C handler of its own for SIGTERM for the length of a
call, so Python's handler never sees the signal (holding it does nothing there):
:func:`call_trapping` hands a signal caught that way back to Python.
"""

from __future__ import annotations

import contextlib
import signal
import threading
from collections.abc import Callable, Iterator
from typing import TypeVar

__all__ = ["call_trapping", "deferred"]

T = TypeVar("T")


@contextlib.contextmanager
def deferred() -> Iterator[None]:
    """Hold SIGINT/SIGTERM's Python handlers until the block ends, then run the first one.

    A C extension that runs Python code while it works turns an exception raised there into
    one of its own. gmsh's Python API passes numpy vectors to ctypes, whose conversion runs
    Python code; a handler raising there (``KeyboardInterrupt``, the CLI's ``Terminated``)
    reached the caller as ``ctypes.ArgumentError``, a traceback instead of a clean stop. gmsh
    does not return to Python while it meshes, so the delay is the read-back of the mesh. Main
    thread only (where Python runs its handlers); handlers not installed from Python are left
    as they are. This does not help against an extension that traps the signal in C itself
    (METIS): use :func:`call_trapping` there.
    """
    if threading.current_thread() is not threading.main_thread():
        yield
        return
    caught: list[int] = []
    numbers = [n for n in (signal.SIGINT, signal.SIGTERM) if signal.getsignal(n) is not None]
    previous = {n: signal.signal(n, lambda signum, _: caught.append(signum)) for n in numbers}
    try:
        yield
    finally:
        for number, handler in previous.items():
            signal.signal(number, handler)
        if caught:
            signal.raise_signal(caught[0])


def call_trapping(function: Callable[[], T], number: int = signal.SIGTERM) -> T:
    """Call ``function``, whose C code traps signal ``number`` itself; pass a caught one on.

    METIS (GKlib, under pymetis) sets a C handler of its own for SIGTERM with ``signal()`` at
    the start of each call and puts the previous one back at the end. A SIGTERM in between
    jumps out of the ordering (pymetis raises ``RuntimeError: Caught an unknown exception!``),
    Python's handler never runs, and the signal is left blocked in the thread. Even a call
    that is not interrupted leaves Python's handler with ``SA_RESTART`` (a blocking read would
    not return to Python on SIGTERM).

    Here Python's handler is installed again after every call. A failure with ``number``
    newly blocked is the signal caught in there: it is unblocked and raised again, so that
    the process's own disposition acts (the CLI's handler raises, the default one ends the
    process); if the process lives on (a handler that only records it, or ``SIG_IGN``), the
    call is made again. Not recoverable: a signal that lands while METIS is inside
    ``malloc``; the jump leaves the heap locked or damaged, and the process hangs or aborts.

    Parameters
    ----------
    function : callable
        The call, without arguments.
    number : int
        The signal the C code traps.

    Returns
    -------
    object
        What ``function`` returns.
    """
    if not hasattr(signal, "pthread_sigmask"):  # Windows: no signal masks
        return function()
    while True:
        before = signal.pthread_sigmask(signal.SIG_BLOCK, [])
        try:
            return function()
        except Exception:
            if not _newly_blocked(number, before):
                raise
        finally:
            _reinstall(number)
        _raise_again(number)


def _newly_blocked(number: int, before: set[signal.Signals]) -> bool:
    """Whether ``number`` is blocked in this thread now but was not in ``before``."""
    return number in signal.pthread_sigmask(signal.SIG_BLOCK, []) and number not in before


def _reinstall(number: int) -> None:
    """Install Python's own handler for ``number`` again (main thread; flags as Python sets)."""
    if threading.current_thread() is not threading.main_thread():
        return
    handler = signal.getsignal(number)
    if handler is not None:
        signal.signal(number, handler)


def _raise_again(number: int) -> None:
    """Unblock ``number`` in this thread and raise it, for the process's own disposition."""
    signal.pthread_sigmask(signal.SIG_UNBLOCK, [number])
    signal.raise_signal(number)
