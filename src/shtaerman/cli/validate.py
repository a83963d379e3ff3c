"""``shtaerman validate``: published results recomputed by the suite (docs/validation.md)."""

from __future__ import annotations

import argparse
import json
import sys

from ..output.files import output_folder, staged_folder
from ..validation_suite import run_suite, suite_text
from .common import in_option_words, path_text, print_json


def register(commands: argparse._SubParsersAction) -> None:
    """Add the ``validate`` subcommand."""
    p = commands.add_parser(
        "validate",
        help="published results (Dimitriadis, Garcia, Hunter, Long) recomputed by the suite",
        description="Each row: a published value, the suite's value with its error bar, the "
        "difference and the tolerance the reference's accuracy allows. Exit code 1 when a "
        "row expected to agree does not.",
    )
    p.add_argument("--quick", action="store_true", help="coarse meshes (about 20 s, not 1 min)")
    p.add_argument("--json", action="store_true", help="print one JSON object")
    p.add_argument(
        "--out", type=path_text, metavar="DIR", help="write DIR/validation.json (a new folder)"
    )
    p.add_argument("--force", action="store_true", help="replace --out if shtaerman wrote it")
    p.set_defaults(handler=run)


def run(args: argparse.Namespace) -> int:
    """Run the suite, print its table (or JSON); 1 when a row disagrees beyond tolerance."""
    with in_option_words():
        folder = output_folder(args.out, force=args.force)  # refused before the suite runs
    rows = run_suite(quick=args.quick, progress=lambda name: print(name, file=sys.stderr))
    document = {"quick": args.quick, "rows": [row.to_dict() for row in rows]}
    if folder is not None:
        with in_option_words(), staged_folder(folder, force=args.force) as stage:
            (stage / "validation.json").write_text(json.dumps(document, indent=1) + "\n")
    if args.json:
        print_json(document)
    else:
        print(suite_text(rows))
    return 1 if any(row.verdict == "DISAGREES" for row in rows) else 0
