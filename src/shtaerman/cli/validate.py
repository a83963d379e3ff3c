"""``shtaerman validate``: published results recomputed by the suite (docs/validation.md)."""

from __future__ import annotations

import argparse
import json
import sys
from pathlib import Path

from ..validation_suite import run_suite, suite_text
from .common import print_json


def register(commands: argparse._SubParsersAction) -> None:
    """Add the ``validate`` subcommand."""
    p = commands.add_parser(
        "validate",
        help="published results (Dimitriadis, Garcia, Hunter) recomputed by the suite",
        description="Each row: a published value, the suite's value with its error bar, the "
        "difference and the tolerance the reference's accuracy allows. Exit code 1 when a "
        "row expected to agree does not.",
    )
    p.add_argument("--quick", action="store_true", help="coarse meshes (about 20 s, not 1 min)")
    p.add_argument("--json", action="store_true", help="print one JSON object")
    p.add_argument("--out", metavar="DIR", help="write DIR/validation.json")
    p.set_defaults(handler=run)


def run(args: argparse.Namespace) -> int:
    """Run the suite, print its table (or JSON); 1 when a row disagrees beyond tolerance."""
    rows = run_suite(quick=args.quick, progress=lambda name: print(name, file=sys.stderr))
    document = {"quick": args.quick, "rows": [row.to_dict() for row in rows]}
    if args.out is not None:
        folder = Path(args.out)
        folder.mkdir(parents=True, exist_ok=True)
        (folder / "validation.json").write_text(json.dumps(document, indent=1) + "\n")
    if args.json:
        print_json(document)
    else:
        print(suite_text(rows))
    return 1 if any(row.verdict == "DISAGREES" for row in rows) else 0
