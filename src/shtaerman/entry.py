"""The console script's entry: the command line, stopped cleanly even while it is imported.

Importing the command line (numpy, scipy, scikit-fem, dask) takes about a second, before
:func:`shtaerman.cli.main` installs its handlers: a SIGINT or SIGTERM in that second used to
end in a traceback or a silent kill. Here the two signals are only recorded while the import
runs (nothing has been written yet), and a recorded one stops the run at once afterwards, with
the command line's line and exit code (130, 143). A signal the parent set to ignore (a ``&``
job) stays ignored. This module imports nothing heavy itself.
"""

from __future__ import annotations

import signal
import sys

__all__ = ["main"]

_STOPPING = (signal.SIGINT, signal.SIGTERM)


def main() -> int:
    """Import the command line with SIGINT and SIGTERM held, then run it (its exit code)."""
    held: list[int] = []
    ignored = {number for number in _STOPPING if signal.getsignal(number) is signal.SIG_IGN}
    previous = {
        number: signal.signal(number, lambda signum, frame: held.append(signum))
        for number in _STOPPING
        if number not in ignored
    }
    try:
        from .cli import main as run
        from .cli import stopped
    finally:
        for number, handler in previous.items():
            signal.signal(number, handler)
    if held:
        return stopped(held[0])
    return run()


if __name__ == "__main__":  # pragma: no cover
    sys.exit(main())
