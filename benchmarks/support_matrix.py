"""Every cell of the support matrix (shtaerman.problem.support_table) run on a coarse mesh: the
runnable ones through sh.contact / sh.dynamic, timed, with their force; the refused ones as
refused. The rubber cells take Newton iterations, minutes in all: this is why the test suite
walks only the linear cells (tests/test_support_matrix.py).

Run: python benchmarks/support_matrix.py [--rubber-only]. Prints one row per cell and the load.
"""

import argparse
import os
import sys
import time
import warnings
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "tests"))

from test_support_matrix import problem_of, solve

import shtaerman as sh
from shtaerman.problem import support_table


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--rubber-only", action="store_true")
    parser.add_argument("--impacts", action="store_true", help="with --rubber-only: no curves")
    args = parser.parse_args()
    print(f"load at start {os.getloadavg()[0]:.2f} on {os.cpu_count()} cores")
    for cell, verdict in support_table():
        if args.rubber_only and (
            cell.model != "rubber" or (args.impacts and cell.loading == "curve")
        ):
            continue
        name = " ".join(str(part) for part in cell)
        if verdict != "runs":
            print(f"{name:62s} refused   {verdict.split(':')[0]}")
            continue
        start = time.perf_counter()
        try:
            with warnings.catch_warnings():
                warnings.simplefilter("ignore")
                force = solve(problem_of(cell))
            outcome = f"force {force:.5g} N"
        except (sh.InputError, RuntimeError, ValueError) as error:
            outcome = f"FAILED {type(error).__name__}: {str(error)[:90]}"
        print(f"{name:62s} {time.perf_counter() - start:7.1f} s  {outcome}", flush=True)
    print(f"load at end {os.getloadavg()[0]:.2f}")


if __name__ == "__main__":
    main()
