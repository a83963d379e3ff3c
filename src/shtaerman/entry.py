"""The console script's entry: the command line, stopped cleanly even while it is imported.

Importing the command line (numpy, scipy, scikit-fem, dask) takes about a second, before
:func:`shtaerman.cli.main` installs its handlers: a SIGINT or SIGTERM in that second used to
end in a traceback or a silent kill. Here the two signals are only recorded while the import
runs (nothing has been written yet), and a recorded one stops the run at once afterwards, with
the command line's line and exit code (130, 143). A signal the parent set to ignore (a ``&``
job) stays ignored. Once the exit code is decided, both signals are ignored for the rest of
the process: Python puts the default disposition back as it finalizes, and the teardown of the
plotting stack lasts seconds, so a second Ctrl-C there killed the process (-2) after its line.
This module imports nothing heavy itself.
"""

from __future__ import annotations

import signal
import sys

from .allocator import keep_freed_memory

__all__ = ["main"]

_STOPPING = (signal.SIGINT, signal.SIGTERM)


def main() -> int:
    """Import the command line with SIGINT and SIGTERM held, then run it (its exit code).

    The holding handler stays until the exit code is decided: the command line puts its own
    in place while it runs and this one back when it returns, so a signal in the instant after
    the last output (where the default handler used to raise a traceback or kill silently)
    ends the process the same way, with the line and 130/143: every output is complete. Then
    both signals are ignored (a second Ctrl-C while the process exits changes nothing)."""
    try:
        return _held_run()
    finally:
        for number in _STOPPING:
            signal.signal(number, signal.SIG_IGN)


def _held_run() -> int:
    held: list[int] = []
    for number in _STOPPING:
        if signal.getsignal(number) is not signal.SIG_IGN:  # a '&' job keeps ignoring them
            signal.signal(number, lambda signum, frame: held.append(signum))
    keep_freed_memory()
    from .cli import Terminated, stopped
    from .cli import main as run

    if held:
        return stopped(held[0])
    try:
        code = run()
    except KeyboardInterrupt:  # in the instant the command line hands the signals back
        return stopped(signal.SIGINT)
    except Terminated:
        return stopped(signal.SIGTERM)
    return stopped(held[0]) if held and code not in (130, 143) else code


if __name__ == "__main__":  # pragma: no cover
    sys.exit(main())
