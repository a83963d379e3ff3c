"""``shtaerman verify``: run cross-check studies and write a result folder with a report."""

from __future__ import annotations

import argparse
import os
import time
from pathlib import Path

from ..validation import InputError
from .common import add_figure_format, add_inputs


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
        metavar="STUDY",
        help="study files (.toml) or shipped study names (default: every shipped study)",
    )
    add_inputs(p, ("out", "force"), None, derived={"out": "a new shtaerman-results-* folder"})
    p.add_argument("--quick", action="store_true", help="coarse meshes (seconds; for CI)")
    add_figure_format(p)
    cores = "the number of cores; 1 runs the studies one after another in this process"
    add_inputs(p, ("workers",), None, derived={"workers": cores})
    p.set_defaults(handler=run)


def default_out() -> Path:
    """A new folder name, unique per run: time stamp and process id."""
    stamp = time.strftime("%Y%m%d-%H%M%S")
    return Path(f"shtaerman-results-{stamp}-{os.getpid()}")


def run(args: argparse.Namespace) -> int:
    """Run the studies; print a verdict per study and every failing check."""
    from ..output.files import check_output_folder
    from ..output.folder import ProgressBar, run_verification
    from ..study.schema import find_study, load_study, shipped_studies

    paths = [find_study(name) for name in args.studies] or shipped_studies()
    studies = [study for path in paths for study in load_study(path)]
    names = [study.name for study in studies]
    duplicates = sorted({name for name in names if names.count(name) > 1})
    if duplicates:
        raise InputError(f"studies: two studies are named {duplicates[0]!r}; rename one")
    out = check_output_folder(
        Path(args.out) if args.out is not None else default_out(), force=args.force
    )
    workers = args.workers or os.cpu_count() or 1
    if workers > 1 and len(studies) > 1:
        from ..sweep.verify import run_verification_on_dask

        bar = ProgressBar(len(studies))
        results = run_verification_on_dask(
            studies,
            out,
            quick=args.quick,
            workers=min(workers, len(studies)),
            force=args.force,
            progress=bar,
            figure_format=args.figure_format,
        )
    else:
        results = run_verification(
            studies, out, quick=args.quick, force=args.force, figure_format=args.figure_format
        )
    print(verify_text(results, out))
    return 0 if results["passed"] else 1


def verify_text(results: dict, out: Path) -> str:
    """Verdict per study, the worst check, and each failing check with value and tolerance."""
    lines = [f"{'study':<24} verdict  {'worst check (value / tolerance)':<48}"]
    for name, study in results["studies"].items():
        checks = study["checks"]
        worst = max(checks, key=lambda c: abs(c["value"]) / c["tolerance"])
        verdict = "PASS" if study["passed"] else "FAIL"
        lines.append(
            f"{name:<24} {verdict:<8} {worst['name']}: {abs(worst['value']):.1e} / "
            f"{worst['tolerance']:.0e}"
        )
        lines += [
            f"{'':<24}   failed {c['name']}: {abs(c['value']):.2e} > tolerance {c['tolerance']:.1e}"
            for c in checks
            if not c["passed"]
        ]
    lines.append(f"results: {out / 'results.json'}  report: {out / 'report.html'}")
    return "\n".join(lines)
