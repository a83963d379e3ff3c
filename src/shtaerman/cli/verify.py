"""``shtaerman verify``: run cross-check studies and write a result folder with a report."""

from __future__ import annotations

import argparse
import math
import os
import shlex
import sys
import time
from pathlib import Path
from typing import Any

from ..validation import InputError
from .common import add_figure_format, add_inputs, in_option_words, keywords, path_text, warn


def register(commands: argparse._SubParsersAction) -> None:
    """Add the ``verify`` subcommand."""
    p = commands.add_parser(
        "verify",
        help="run cross-check studies: FEM -> impact -> report",
        description=(
            "Run cross-check studies (TOML files, or the names of shipped studies) and write "
            "results.json, report.md, report.html, VTU fields, CSV curves and figures into a "
            "new folder. Exit code 1 when a check fails."
        ),
    )
    p.add_argument(
        "studies",
        nargs="*",
        type=path_text,
        metavar="STUDY",
        help="study files (.toml) or shipped study names (default: the shipped studies but "
        "the extended ones)",
    )
    p.add_argument(
        "--extended",
        action="store_true",
        help="also the extended shipped studies (rubber models and other minutes-long ones)",
    )
    force = (
        "once the run completes; interrupted, the old folder stays whole and the finished "
        "studies are kept beside it, in OUT.incomplete-PID (the 'complete them with' line)"
    )
    derived = {"out": "a new shtaerman-results-* folder"}
    add_inputs(p, ("out", "force"), None, derived=derived, notes={"force": force})
    p.add_argument("--quick", action="store_true", help="coarse meshes (seconds; for CI)")
    add_figure_format(p)
    p.add_argument(
        "--resume",
        action="store_true",
        help="complete the folder an interrupted run left in --out: compute only the studies "
        "it lacks",
    )
    cores = "the number of cores; 1 runs the studies one after another in this process"
    add_inputs(p, ("workers",), None, derived={"workers": cores})
    p.set_defaults(handler=run)


DEFAULT_OUT_PREFIX = "shtaerman-results-"


def default_out() -> Path:
    """A new folder name, unique per run: time stamp and process id."""
    stamp = time.strftime("%Y%m%d-%H%M%S")
    return Path(f"{DEFAULT_OUT_PREFIX}{stamp}-{os.getpid()}")


def run(args: argparse.Namespace) -> int:
    """Run the studies; print a verdict per study and every failing check."""
    from ..signals import deferred

    with deferred():  # VTK's modules: an interrupt in their import was a segfault at times
        from ..output.files import adopt_killed_runs, check_output_folder
        from ..output.folder import PROGRESS_FILE, ProgressBar, VerifyInterrupted, run_verification
        from ..study.schema import find_study, load_study, shipped_studies
        from ..sweep.engine import default_workers

    if args.resume and args.force:
        raise InputError("--resume and --force exclude each other: --resume keeps the folder")
    if args.resume and args.out is None:
        raise InputError("--resume: name the folder to complete with --out DIR", "resume")
    if args.extended and args.studies:
        raise InputError(
            "--extended: applies to the shipped studies only (run without study names); a "
            "named study runs whether it is extended or not"
        )
    paths = [find_study(name) for name in args.studies] or shipped_studies(extended=args.extended)
    studies = [study for path in paths for study in load_study(path)]
    _check_unique_names(studies)
    if args.quick:
        _say_full_quick(paths)
    marker = PROGRESS_FILE if args.resume else None
    if args.out is None:
        adopt_killed_runs(Path.cwd(), DEFAULT_OUT_PREFIX)
    with in_option_words():  # "--out: ...", not the API's keyword
        out = check_output_folder(
            Path(args.out) if args.out is not None else default_out(),
            force=args.force,
            resume_marker=marker,
            keep_marker=PROGRESS_FILE,
        )
    workers = args.workers or default_workers()
    options = keywords(args, ("quick", "force", "resume", "figure_format"))
    try:
        with in_option_words():  # a resume's refusals: "--resume: ...", not the API's keyword
            if workers > 1 and len(studies) > 1:
                from ..sweep.verify import run_verification_on_dask

                bar = ProgressBar(len(studies))
                results = run_verification_on_dask(
                    studies, out, workers=args.workers, progress=bar, **options
                )
            else:
                results = run_verification(studies, out, **options)
    except VerifyInterrupted as stop:
        print(_interrupted_text(args, stop, out), file=sys.stderr)
        return stopped_code(stop.cause)
    print(verify_text(results, out))
    return 0 if results["passed"] else 1


def _say_full_quick(paths: list[Path]) -> None:
    """Say that --quick runs a dynamic or effects study without [quick] on its full mesh."""
    import tomllib

    for path in paths:
        data = tomllib.loads(path.read_text())
        if data.get("kind") in ("dynamic", "effects") and "quick" not in data:
            warn(
                f"{path} has no [quick] table: --quick runs it on its full [numerics] mesh and "
                "time steps (without the estimate); a [quick] table sets coarse ones"
            )


def _check_unique_names(studies: list) -> None:
    """Raise InputError when two studies share a name (their result folder)."""
    names = [study.name for study in studies]
    duplicates = sorted({name for name in names if names.count(name) > 1})
    if not duplicates:
        return
    sources = {str(getattr(s, "source", "")) for s in studies if s.name == duplicates[0]}
    if len(sources) == 1:  # one file's [sweep] values that round to the same name
        raise InputError(
            f"studies: the [sweep] of {sources.pop()} gives two studies the name "
            f"{duplicates[0]!r}: its values must differ within 6 significant digits"
        )
    raise InputError(f"studies: two studies are named {duplicates[0]!r}; rename one")


def stopped_code(cause: BaseException) -> int:
    """The exit code of a run stopped by ``cause``: 130 Ctrl-C, 2 a refused input, 1 another
    error, 143 SIGTERM."""
    if isinstance(cause, KeyboardInterrupt):
        return 130
    if isinstance(cause, Exception):
        return 2 if isinstance(cause, InputError) else 1
    return 143


def _interrupted_text(args: argparse.Namespace, stop: Any, out: Path) -> str:
    """What a stopped run kept, and the command that completes it (a --force run's: beside
    the old folder, which stays whole)."""
    kept = "" if stop.kept_in is None else f" ({str(out)!r} unchanged: --force keeps it whole)"
    out = out if stop.kept_in is None else stop.kept_in
    command = ["shtaerman", "verify", *args.studies, "--out", str(out)]
    if args.quick:
        command.append("--quick")
    if args.workers is not None:
        command += ["--workers", str(args.workers)]
    command.append("--resume")
    if isinstance(stop.cause, Exception):
        reason = f"error: {_one_line(stop.cause)};"
    else:
        reason = "interrupted:" if isinstance(stop.cause, KeyboardInterrupt) else "terminated:"
    if stop.kept == stop.total:  # stopped while writing results.json, the reports
        return (
            f"shtaerman: {reason} all {stop.total} studies finished and kept in {str(out)!r}, "
            f"the summary and reports not written{kept}; write them with: {shlex.join(command)}"
        )
    return (
        f"shtaerman: {reason} {stop.kept} of {stop.total} studies finished and kept in "
        f"{str(out)!r}{kept}; complete them with: {shlex.join(command)}"
    )


def _one_line(error: Exception) -> str:
    """An error in one line: its message, or for an OSError its reason and file."""
    if isinstance(error, OSError) and error.strerror:
        where = f" ({error.filename})" if error.filename else ""
        return f"{error.strerror}{where}"
    return " ".join(str(error).split()) or type(error).__name__


def _size(value: float | None, undefined: float = math.inf) -> float:
    """|value| of a check in results.json, ``undefined`` where it holds null (a NaN, the
    worst)."""
    return undefined if value is None else abs(value)


def verify_text(results: dict, out: Path) -> str:
    """Verdict per study, the worst check, and each failing check with value and tolerance."""
    lines = [f"{'study':<24} verdict  {'worst check (value / tolerance)':<48}"]
    for name, study in results["studies"].items():
        checks = study["checks"]
        verdict = "PASS" if study["passed"] else "FAIL"
        if not checks:  # an effect table has no tolerances
            lines.append(f"{name:<24} {verdict:<8} (no checks: a table of effects)")
            continue
        worst = max(checks, key=lambda c: _size(c["value"]) / c["tolerance"])
        lines.append(
            f"{name:<24} {verdict:<8} {worst['name']}: {_size(worst['value'], math.nan):.1e} / "
            f"{worst['tolerance']:.0e}"
        )
        lines += [
            f"{'':<24}   failed {c['name']}: {_size(c['value'], math.nan):.2e} > tolerance "
            f"{c['tolerance']:.1e}"
            for c in checks
            if not c["passed"]
        ]
    lines.append(f"results: {out / 'results.json'}  report: {out / 'report.html'}")
    return "\n".join(lines)
