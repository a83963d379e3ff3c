"""The tables of docs/validation.md from a run of ``shtaerman validate``.

Run ``shtaerman validate --json --out DIR`` (default meshes, about 1 min), then
``python benchmarks/validation_tables.py DIR/validation.json``: prints each group of rows (a
case and a source) as the page shows it, a bold head then a Markdown table, in the order of
the run. Paste each over the page's block of the same head.
"""

import argparse
import json
from pathlib import Path


def _head(row: dict) -> str:
    return f"**{row['case']}** — {row['source']}. {row['quantity']}. Tolerance: {row['why']}."


def _line(row: dict) -> str:
    cells = (
        row["inputs"],
        f"{row['published']:.4f}",
        f"{row['value']:.4f} ± {row['error_bar']:.1e}",
        f"{row['difference']:+.4f}",
        f"{row['tolerance']:.4f}",
        row["verdict"],
    )
    return "| " + " | ".join(cells) + " |"


def tables(rows: list[dict]) -> str:
    """The page's blocks of ``rows`` (validation.json's), one per (case, source)."""
    blocks: list[list[str]] = []
    group = None
    for row in rows:
        if (row["case"], row["source"]) != group:
            group = (row["case"], row["source"])
            blocks.append(
                [
                    _head(row),
                    "",
                    "| inputs | published | suite ± error bar | difference | tolerance | verdict |",
                    "|---|---|---|---|---|---|",
                ]
            )
        blocks[-1].append(_line(row))
    return "\n\n".join("\n".join(block) for block in blocks)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("json", type=Path, help="validation.json of `shtaerman validate --out`")
    print(tables(json.loads(parser.parse_args().json.read_text())["rows"]))


if __name__ == "__main__":
    main()
