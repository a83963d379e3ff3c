"""Every cell of the support matrix (shtaerman.problem.support_table) run on a coarse mesh: the
runnable ones through sh.contact / sh.dynamic, timed, with their force; the refused ones as
refused. A runnable rubber cell runs with each of the four rubber models (their shapes:
tests/test_support_matrix.py RUBBER_MODELS). The rubber cells take Newton iterations: the test
suite runs one model per cell and only the cheapest cells (tests/test_support_matrix.py SLOW
names the others); their costs are what this prints.

Run: python benchmarks/support_matrix.py [--rubber-only] [--impacts] [--model NAME] [--cell
WORDS]. Prints one row per cell and model: the CPU seconds of its run, its sparse LU
factorizations, the solves that reused one (a modified Newton's steps), the evaluations of the
striker's step equation (the secant's, each a contact Newton of the body), and the load.
"""

import argparse
import contextlib
import os
import sys
import time
import warnings
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "tests"))

from test_support_matrix import RUBBER_MODELS, SLOW, problem_of, solve

import shtaerman as sh
import shtaerman.fem.stepper as stepper
from shtaerman.fem.solver import PatternSolver
from shtaerman.problem import support_table


@contextlib.contextmanager
def counted():
    """Counts of the run inside: factorizations, solves with a reused one, step evaluations."""
    counts = {"factorizations": 0, "reused": 0, "evaluations": 0}
    factorized = PatternSolver.factorized
    at, body_step = stepper.QuasiStaticBody.at, stepper._body_step

    def counting_factorized(self, data, rhs):
        counts["factorizations"] += 1
        solution, again = factorized(self, data, rhs)

        def counting_again(b):
            counts["reused"] += 1
            return again(b)

        return solution, counting_again

    def counting(function):
        def wrapped(*args, **keywords):
            counts["evaluations"] += 1
            return function(*args, **keywords)

        return wrapped

    PatternSolver.factorized = counting_factorized
    stepper.QuasiStaticBody.at, stepper._body_step = counting(at), counting(body_step)
    try:
        yield counts
    finally:
        PatternSolver.factorized = factorized
        stepper.QuasiStaticBody.at, stepper._body_step = at, body_step


def run(cell, model: str) -> str:
    """The cell's force, or its failure, in a few words, after its CPU time (s)."""
    start = time.process_time()
    try:
        with warnings.catch_warnings(record=True) as caught, counted() as counts:
            warnings.simplefilter("always")
            force = solve(problem_of(cell, model))
        outcome = f"force {force:.5g} N"
        retried = [str(w.message) for w in caught if "retried" in str(w.message)]
        outcome += f"  ({retried[0][:90]})" if retried else ""
    except (sh.InputError, RuntimeError, ValueError) as error:
        outcome = f"FAILED {type(error).__name__}: {str(error)[:90]}"
    cpu = time.process_time() - start
    tally = "{factorizations:5d} LU {reused:5d} reused {evaluations:4d} evaluations"
    tally = tally.format(**counts)
    return f"{cpu:7.1f} s  {tally}  {outcome}"


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--rubber-only", action="store_true")
    parser.add_argument("--impacts", action="store_true", help="no curves")
    parser.add_argument("--model", choices=list(RUBBER_MODELS), help="this rubber model only")
    parser.add_argument("--cell", help="the cells whose name (as printed) contains these words")
    args = parser.parse_args()
    models = [args.model] if args.model else list(RUBBER_MODELS)
    print(f"load at start {os.getloadavg()[0]:.2f} on {os.cpu_count()} cores")
    for cell, verdict in support_table():
        if (args.rubber_only and cell.model != "rubber") or (
            args.impacts and cell.loading == "curve"
        ):
            continue
        name = " ".join(str(part) for part in cell)
        if args.cell and args.cell not in name:
            continue
        if verdict != "runs":
            print(f"{name:62s} refused   {verdict.split(':')[0]}")
            continue
        for model in models if cell.model == "rubber" else ["linear"]:
            mark = " (slow: benchmark only)" if cell in SLOW else ""
            print(f"{name:62s} {model:13s} {run(cell, model)}{mark}", flush=True)
    print(f"load at end {os.getloadavg()[0]:.2f}")


if __name__ == "__main__":
    main()
