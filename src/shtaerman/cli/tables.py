"""``shtaerman tables``: the paper's Tables 1-6, printed against exact."""

from __future__ import annotations

import argparse

from .common import print_json


def register(commands: argparse._SubParsersAction) -> None:
    """Add the ``tables`` subcommand."""
    p = commands.add_parser(
        "tables",
        help="the paper's Tables 1-6: printed, exact, difference",
        description="The paper's Tables 1-6 and worked example regenerated from the exact model.",
    )
    p.add_argument("--json", action="store_true", help="print one JSON object")
    p.set_defaults(handler=run)


def run(args: argparse.Namespace) -> int:
    """Print the compared tables."""
    from ..paper.comparison import compare_tables, tables_text  # here: they load scipy.special

    tables = compare_tables()
    if args.json:
        print_json({"tables": [table.to_dict() for table in tables]})
    else:
        print(tables_text(tables))
    return 0
