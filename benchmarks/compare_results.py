"""Compare two ``shtaerman verify`` result folders number by number (timings excluded).

Run: python benchmarks/compare_results.py OLD_DIR NEW_DIR [--rtol 1e-9]. Every numeric leaf of
results.json and every numeric cell of the studies' CSV files is compared; a pair differs when
|a - b| > rtol max(|a|, |b|) (so a zero must stay exactly zero). Keys that vary from run to run
are skipped: timings, seconds, cpu_seconds, generated, environment, and the CPU time a text quotes
("31 s of CPU time"). Prints each difference
(path, old, new, relative change) and a summary line; exit code 1 when anything differs, or a
key, a file or a row is on one side only.
"""

from __future__ import annotations

import argparse
import csv
import json
import math
import re
import sys
from collections.abc import Iterator
from pathlib import Path

SKIPPED = {"timings", "seconds", "cpu_seconds", "generated", "environment"}
"""Keys whose values vary from run to run."""
CPU_IN_TEXT = re.compile(r"[0-9.]+ s of CPU")
"""A CPU time quoted in a finding."""


def leaves(value: object, path: str = "") -> Iterator[tuple[str, object]]:
    """(path, value) of every leaf of a JSON document, skipping :data:`SKIPPED` keys."""
    if isinstance(value, dict):
        for key, item in value.items():
            if key not in SKIPPED:
                yield from leaves(item, f"{path}/{key}")
    elif isinstance(value, list):
        for index, item in enumerate(value):
            yield from leaves(item, f"{path}[{index}]")
    elif isinstance(value, str):
        yield path, CPU_IN_TEXT.sub("(time) s of CPU", value)
    else:
        yield path, value


def csv_leaves(folder: Path) -> Iterator[tuple[str, object]]:
    """(file:row:column, cell) of every CSV file under ``folder``."""
    for path in sorted(folder.rglob("*.csv")):
        with path.open(newline="", encoding="utf-8") as stream:
            for number, row in enumerate(csv.reader(stream)):
                for column, cell in enumerate(row):
                    yield f"{path.relative_to(folder)}:{number}:{column}", _number(cell)


def _number(cell: str) -> object:
    try:
        return float(cell)
    except ValueError:
        return cell


def relative_change(old: float, new: float) -> float:
    """|new - old| / max(|old|, |new|) (0 for equal values, NaN for equal NaNs)."""
    if old == new or (math.isnan(old) and math.isnan(new)):
        return 0.0
    return abs(new - old) / max(abs(old), abs(new))


def differences(old: dict, new: dict, rtol: float) -> tuple[list[str], int]:
    """Lines naming each leaf that moved, and the count of numeric leaves compared."""
    lines, compared = [], 0
    for key in sorted(old.keys() | new.keys()):
        if key not in old or key not in new:
            lines.append(f"{key}: only in {'new' if key in new else 'old'}")
            continue
        a, b = old[key], new[key]
        numeric = all(isinstance(v, int | float) and not isinstance(v, bool) for v in (a, b))
        if not numeric:
            if a != b:
                lines.append(f"{key}: {a!r} -> {b!r}")
            continue
        compared += 1
        change = relative_change(float(a), float(b))
        if not change <= rtol:
            lines.append(f"{key}: {a!r} -> {b!r} (relative {change:.2e})")
    return lines, compared


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("old", type=Path)
    parser.add_argument("new", type=Path)
    parser.add_argument("--rtol", type=float, default=1e-9)
    args = parser.parse_args()
    total, compared = [], 0
    for name, read in (
        ("results.json", lambda f: dict(leaves(json.loads((f / "results.json").read_text())))),
        ("CSV files", lambda f: dict(csv_leaves(f))),
    ):
        lines, count = differences(read(args.old), read(args.new), args.rtol)
        print(f"{name}: {count} numbers compared, {len(lines)} differ (rtol {args.rtol:g})")
        total += lines
        compared += count
    print("\n".join(total[:200]))
    if len(total) > 200:
        print(f"... and {len(total) - 200} more")
    return 1 if total else 0


if __name__ == "__main__":
    sys.exit(main())
