"""``shtaerman sweep FILE.toml|NAME [--workers N] [--scheduler ADDRESS] [--out DIR] [--resume]
[--force]``: the subcommand, kept apart so that it plugs into any argparse tree.

Exit codes: 0 every case succeeded or was refused (beyond a validity limit of the model: its
row says why, the summary line counts it), 1 a case failed or could not run (or the sweep was
interrupted: 128 + the signal number), 2 bad input, or every case refused (one line on stderr,
nothing computed).
"""

from __future__ import annotations

import argparse
import shlex
import signal
import sys
from pathlib import Path
from typing import Any

from ..cli.common import add_inputs, path_text
from ..plots.formats import add_figure_format
from ..problem import worded
from ..validation import InputError

__all__ = ["add_parser", "register", "run"]


def add_parser(subparsers: argparse._SubParsersAction) -> argparse.ArgumentParser:
    """Add the ``sweep`` subcommand (``set_defaults(handler=run)``) and return its parser."""
    p = subparsers.add_parser(
        "sweep",
        help="run a grid of cases (a TOML sweep file) on dask.distributed",
        description="Run every case of a sweep file in parallel; each finished case is saved "
        "at once, so an interrupted sweep can be completed with --resume.",
    )
    p.add_argument(
        "sweep",
        type=path_text,
        metavar="FILE.toml|NAME",
        help="a sweep file, or the name of a shipped sweep (e.g. nu-grid, impact-velocity)",
    )
    add_inputs(p, ("workers",), None, derived={"workers": "the cores"})  # as verify's
    p.add_argument(
        "--scheduler",
        metavar="ADDRESS",
        help="use an existing dask cluster, e.g. tcp://host:8786 (its workers need shtaerman)",
    )
    p.add_argument(
        "--out", type=path_text, metavar="DIR", help="result folder (default: sweep-<name>)"
    )
    p.add_argument(
        "--resume",
        action="store_true",
        help="complete the sweep in DIR: compute only the cases without a saved result",
    )
    p.add_argument(
        "--force",
        action="store_true",
        help="replace a sweep folder this tool wrote (never files you added) once this run "
        "completes; interrupted, the old folder stays whole and this run's saved cases are kept "
        "beside it in DIR.incomplete-PID (the 'resume with' line completes them there and "
        "moves them to DIR)",
    )
    add_figure_format(p)
    p.set_defaults(handler=run)
    return p


def register(commands: argparse._SubParsersAction) -> None:
    """Add the ``sweep`` subcommand (the ``shtaerman.cli`` package's convention)."""
    add_parser(commands)


def run(args: argparse.Namespace) -> int:
    """Run the sweep named by ``args``; returns the exit code (raises InputError on bad input)."""
    from .engine import SweepInterrupted, run_sweep
    from .spec import find_sweep, load_sweep

    workers = args.workers
    if workers is not None and args.scheduler:
        raise InputError("--workers: sizes the local cluster; drop it with --scheduler", "workers")
    spec = load_sweep(find_sweep(args.sweep))
    out = Path(args.out) if args.out else Path(f"sweep-{spec.name}")
    try:
        outcome = run_sweep(
            spec,
            out,
            workers=workers,
            scheduler=args.scheduler,
            resume=args.resume,
            force=args.force,
            figure_format=args.figure_format,
        )
    except KeyboardInterrupt:  # before the sweep's own handler is in place
        print(f"shtaerman: sweep {spec.name!r} interrupted (SIGINT)", file=sys.stderr)
        return 128 + signal.SIGINT
    except SweepInterrupted as stop:
        print(_interrupted_text(args, spec.name, out, stop), file=sys.stderr)
        return 128 + stop.signum
    except OSError as error:  # a full disk, a lost mount: what is saved stays saved
        print(_failed_text(args, out, error), file=sys.stderr)
        return 1
    except InputError as error:  # the API's keywords out, resume, scheduler are options here
        keys = ("out", "resume", "scheduler")
        key = next((k for k in keys if str(error).startswith(f"{k}: ")), None)
        spoken = ("--" if key else "") + worded(str(error), "cli")  # resume=True: --resume
        if spoken == str(error):
            raise
        raise InputError(spoken, key or error.parameter) from None
    _report(args, spec, out.with_name(outcome.out.name), outcome)  # moved: a --force completed
    return outcome.exit_code


def _resume_command(args: argparse.Namespace, out: Path) -> str:
    """The command that completes the sweep in ``out`` as ``args`` asked it: on the same
    workers or cluster, with the same figure format (without it the completed sweep's figures
    would be PNG only)."""
    command = ["shtaerman", "sweep", str(args.sweep), "--out", str(out), "--resume"]
    if args.workers is not None:
        command += ["--workers", str(args.workers)]
    if args.scheduler:
        command += ["--scheduler", args.scheduler]
    if args.figure_format != "png":
        command += ["--figure-format", args.figure_format]
    return shlex.join(command)


def _interrupted_text(args: argparse.Namespace, name: str, out: Path, stop: Any) -> str:
    """One line: what an interrupted sweep kept, and how to complete it."""
    from .engine import is_sweep_folder

    refused = f" ({stop.refused} more refused, outside the model's validity)" * bool(stop.refused)
    if stop.restored:
        kept = f"--force kept the previous sweep in {out}, unchanged"
        if stop.kept_in is None:
            return f"shtaerman: sweep {name!r} interrupted ({stop}); {kept}"
        return (
            f"shtaerman: sweep {name!r} interrupted ({stop}); {kept}; {stop.saved} of "
            f"{_cases(stop.total)} of this run saved in {stop.kept_in}{refused}; resume with: "
            f"{_resume_command(args, stop.kept_in)}"
        )
    if not stop.saved and not is_sweep_folder(out):
        return f"shtaerman: sweep {name!r} interrupted ({stop}) before any case was saved"
    if stop.total and stop.saved == stop.total:  # stopped while writing the summary
        return (
            f"shtaerman: sweep {name!r} interrupted ({stop}): all {_cases(stop.total)} saved in "
            f"{out}{refused}, its summary and figures not all written; write them with: "
            f"{_resume_command(args, out)}"
        )
    return (
        f"shtaerman: sweep {name!r} interrupted ({stop}): {stop.saved} of {_cases(stop.total)} "
        f"saved in {out}{refused}; resume with: {_resume_command(args, out)}"
    )


def _cases(count: int) -> str:
    """``count`` cases in words: "1 case", "2 cases"."""
    return f"{count} case{'s' * (count != 1)}"


def _failed_text(args: argparse.Namespace, out: Path, error: OSError) -> str:
    """One line for a failed write: the error, and how to complete what is saved."""
    from .engine import is_sweep_folder

    what = error.strerror or str(error)
    where = f" ({error.filename})" if error.filename else ""
    kept = getattr(error, "kept_in", None)  # --force: the old folder is back, whole
    if kept is not None:
        return (
            f"shtaerman: error: {what}{where}; {out} unchanged (--force keeps it whole), this "
            f"run's finished cases saved in {kept}: complete them with: "
            f"{_resume_command(args, kept)}"
        )
    if not is_sweep_folder(out):
        return f"shtaerman: error: {what}{where}; nothing was saved"
    return (
        f"shtaerman: error: {what}{where}; the finished cases are saved in {out}: complete the "
        f"sweep with: {_resume_command(args, out)}"
    )


def _report(args: argparse.Namespace, spec: Any, out: Path, outcome: Any) -> None:
    """The summary line, the warnings, and where the results are (or how to complete them)."""
    if outcome.computed:
        plural = "s" if outcome.workers != 1 else ""
        done = f"{outcome.computed} computed on {outcome.workers} worker{plural}"
    else:
        done = f"none of {outcome.lost} could run" if outcome.lost else "nothing to compute"
    if outcome.reused:
        done += f", {outcome.reused} from an earlier run"
    refused = f", {outcome.refused} refused (outside the model's validity)" * bool(outcome.refused)
    print(
        f"sweep {spec.name} ({spec.kind}): {_cases(outcome.total)}, {outcome.succeeded} ok, "
        f"{outcome.failed} failed{refused} ({done}) in {outcome.seconds:.1f} s"
    )
    if outcome.warned:
        print(
            f"shtaerman: warning: {outcome.warned} case(s) issued warnings (summary.warnings in "
            f"{out / 'results.json'})",
            file=sys.stderr,
        )
    if outcome.lost:
        print(
            f"shtaerman: {_cases(outcome.lost)} could not run ({outcome.lost_reason}); complete "
            f"them with: {_resume_command(args, out)}",
            file=sys.stderr,
        )
    else:  # figures over 1 or 2 axes only, and not when they failed (a warning says why)
        figures = f"  {out / 'figures'}" if outcome.figures else ""
        print(f"results: {out / 'cases.csv'}  {out / 'results.json'}{figures}")
