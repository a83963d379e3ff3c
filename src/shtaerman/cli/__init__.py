"""The ``shtaerman`` command line: one module per subcommand, ``main(argv=None)``.

Thin: each subcommand parses, calls the library and prints. Bad input gives one line on stderr
naming the parameter and its valid range, and exit code 2; Ctrl-C and SIGTERM stop with one
line and exit codes 130 and 143, after every partly written output has been removed.
"""

from __future__ import annotations

import argparse
import os
import select
import signal
import sys
import warnings
from collections.abc import Sequence

from ..sweep import cli as sweep
from ..validation import InputError, NumericalFailureError
from ..version import __version__
from . import (
    contact,
    dynamic,
    effects,
    fit,
    impact,
    init_study,
    prony_plot,
    tables,
    validate,
    verify,
)
from .common import Parser, warn

__all__ = ["EXIT_INPUT", "Terminated", "build_parser", "main", "stopped"]

EXIT_FAILED = 1
EXIT_INPUT = 2
EXIT_INTERRUPTED = 130
EXIT_TERMINATED = 143
NOTHING_PARTIAL = "every output is complete or absent (nothing partial is kept)"
STDOUT_CLOSED = (
    "standard output is closed; redirect it to a file or to /dev/null (e.g. '> run.log')"
)
PIPE_OUTPUT = "the reader of an output pipe quit before the output was complete"
STOPPING = (signal.SIGINT, signal.SIGTERM)
"""The signals that stop a run cleanly (:func:`_stop`)."""
SUBCOMMANDS = (
    impact,
    tables,
    contact,
    dynamic,
    effects,
    fit,
    verify,
    validate,
    init_study,
    prony_plot,
    sweep,
)
DESCRIPTION = """\
Finite-element cross-check of Shtaerman's power-law contact and the quasi-static impact of a
striker z = A r^n on an elastic half-space (Ol'shanskii et al. 2019). SI units everywhere.

Run 'shtaerman COMMAND --help' for the options of a command."""


class Terminated(BaseException):
    """SIGTERM, raised like Ctrl-C so that staged outputs are cleaned up on the way out."""


def build_parser() -> argparse.ArgumentParser:
    """The ``shtaerman`` argument parser with its subcommands."""
    parser = Parser(prog="shtaerman", description=DESCRIPTION)
    parser.add_argument("--version", action="version", version=f"shtaerman {__version__}")
    commands = parser.add_subparsers(
        dest="command", title="commands", metavar="COMMAND", parser_class=Parser
    )
    for module in SUBCOMMANDS:
        module.register(commands)
    return parser


_SIGNALLED: list[int] = []
"""The SIGINTs and SIGTERMs received: a library that catches the exception raised for one
(VTK's lazy loader turns it into an ImportError; a weakref callback prints and drops it) may
hide it, and the run must stop all the same."""


def _stop(signum: int, frame: object) -> None:
    """SIGINT raises KeyboardInterrupt, SIGTERM :class:`Terminated`; both are recorded."""
    _SIGNALLED.append(signum)
    raise KeyboardInterrupt if signum == signal.SIGINT else Terminated


def stopped(signum: int) -> int:
    """The line and exit code of a run stopped by ``signum`` (130 SIGINT, 143 SIGTERM)."""
    interrupted = signum == signal.SIGINT
    print(
        f"shtaerman: {'interrupted' if interrupted else 'terminated'}; {NOTHING_PARTIAL}",
        file=sys.stderr,
    )
    return EXIT_INTERRUPTED if interrupted else EXIT_TERMINATED


def _run(argv: Sequence[str] | None) -> int:
    parser = build_parser()
    args = parser.parse_args(argv)
    if args.command is None:
        parser.print_help(sys.stderr)
        return EXIT_INPUT
    return args.handler(args)


def _stdout_gone() -> bool:
    """True when standard output is a pipe whose reader has quit (poll reports an error)."""
    try:
        poller = select.poll()
        poller.register(sys.stdout.fileno(), select.POLLOUT)
        return any(events & (select.POLLERR | select.POLLHUP) for _, events in poller.poll(0))
    except (AttributeError, OSError, ValueError):
        return False


def _report(caught: list[warnings.WarningMessage]) -> None:
    for warning in caught:
        if not issubclass(warning.category, DeprecationWarning):
            warn(str(warning.message))


def _spoken(error: Exception) -> str:
    """``error``'s message with the inputs it names as keywords (``force=True``, ``out=...``)
    spelled as options (``--force``, ``--out``): what a command did not already reword."""
    from ..problem import worded

    return worded(str(error), "cli")


def main(argv: Sequence[str] | None = None) -> int:
    """Run the CLI; returns the exit code (0 success, 1 failed check, 2 bad input, 130 Ctrl-C,
    143 SIGTERM)."""
    if sys.stdout is None:  # started with '>&-': every result would be lost without a word
        print(f"shtaerman: error: {STDOUT_CLOSED}", file=sys.stderr)
        return EXIT_INPUT
    _SIGNALLED.clear()
    ignored = {number for number in STOPPING if signal.getsignal(number) is signal.SIG_IGN}
    previous = {n: signal.signal(n, _stop) for n in STOPPING if n not in ignored}  # '&' jobs
    try:
        with warnings.catch_warnings(record=True) as caught:
            warnings.simplefilter("always")
            try:
                code = _run(argv)
            except (InputError, NumericalFailureError) as error:  # bad input; a failed computation
                code = EXIT_INPUT if isinstance(error, InputError) else EXIT_FAILED
                _report(caught)
                caught.clear()
                print(f"shtaerman: error: {_spoken(error)}", file=sys.stderr)
            _report(caught)
        if _SIGNALLED and code not in (EXIT_INTERRUPTED, EXIT_TERMINATED):
            return stopped(_SIGNALLED[0])  # a library swallowed it; the outputs are whole
    except KeyboardInterrupt:
        return stopped(signal.SIGINT)
    except Terminated:
        return stopped(signal.SIGTERM)
    except ImportError:  # VTK's lazy loader turns an exception raised inside it into this
        if not _SIGNALLED:
            raise
        return stopped(_SIGNALLED[0])
    except BrokenPipeError as error:
        if not _stdout_gone():  # an output file was a pipe (FIFO) whose reader quit early
            print(f"shtaerman: error: {error}: {PIPE_OUTPUT}", file=sys.stderr)
            return EXIT_FAILED
        # the reader closed stdout (e.g. '| head'): stop quietly, as Unix tools do
        os.dup2(os.open(os.devnull, os.O_WRONLY), sys.stdout.fileno())
        return 0
    except OSError as error:  # the machine's fault, not the input's: a full disk, a lost mount
        print(f"shtaerman: error: {error}; {NOTHING_PARTIAL}", file=sys.stderr)
        return EXIT_FAILED
    finally:
        for number, handler in previous.items():
            signal.signal(number, handler)
    return code


if __name__ == "__main__":
    sys.exit(main())
