"""Benchmark of the error estimates: effectivity on unseen cases, and ``--accuracy`` targets.

(a) For linear cases the exact solution gives the true error: for each case and ladder
    (finest refine 1, 1.41, 2) print the estimated and true relative errors of force (worst
    depth) and beta and their ratio, the effectivity index (the issue asks [1/3, 3]).
(b) ``run_to_accuracy`` for 1e-4 and 1e-5 on unseen cases: the ladder used, the time and the
    true error reached (the issue asks <= 2 TOL within 60 s on 2 cores).

Run: python benchmarks/bench_accuracy.py [--quick]
"""

from __future__ import annotations

import argparse
import time

from shtaerman.study.accuracy import run_ladder, run_to_accuracy
from shtaerman.theory.indenter import PowerLawIndenter
from shtaerman.theory.materials import Material
from shtaerman.validation import InputError

CASES = {
    "paper n=1.5 nu=0.5": (PowerLawIndenter(5.0, 1.5), Material(7.5e6, 0.5)),
    "n=1.2 nu=0.3 A=2": (PowerLawIndenter(2.0, 1.2), Material(1e7, 0.3)),
    "n=2 nu=0 A=20": (PowerLawIndenter(20.0, 2.0), Material(5e6, 0.0)),
    "n=1.8 nu=0.45 A=0.7": (PowerLawIndenter(0.7, 1.8), Material(2e7, 0.45)),
}


def effectivity_table(refines: list[float]) -> None:
    print("(a) estimated / true relative error (effectivity), finest level of a 3-mesh ladder")
    print(
        f"{'case':<22} {'refine':>6} {'dofs':>7} | {'force est':>9} {'true':>8} {'eff':>5} |"
        f" {'beta est':>9} {'true':>8} {'eff':>5} | method force/beta"
    )
    for name, (indenter, half_space) in CASES.items():
        for refine in refines:
            result = run_ladder(indenter, half_space, refine=refine)
            est, true, eff = result.error_estimate(), result.finest.errors(), result.effectivity()
            methods = "/".join(result.estimates[k].method for k in ("force", "beta"))
            print(
                f"{name:<22} {refine:6.3g} {result.levels[-1].dofs:7d} | "
                f"{est['force']:9.2e} {true['force']:8.2e} {eff['force']:5.2f} | "
                f"{est['beta']:9.2e} {true['beta']:8.2e} {eff['beta']:5.2f} | {methods}"
            )


def accuracy_table(tolerances: list[float]) -> None:
    print("\n(b) run_to_accuracy: ladder, time, true errors reached")
    for name, (indenter, half_space) in list(CASES.items())[1:]:
        for tolerance in tolerances:
            start = time.perf_counter()
            try:
                result = run_to_accuracy(indenter, half_space, tolerance, max_time=120.0)
            except InputError as refusal:
                print(
                    f"{name:<22} tol {tolerance:.0e}: refused after "
                    f"{time.perf_counter() - start:.1f} s: {refusal}"
                )
                continue
            seconds = time.perf_counter() - start
            true = result.finest.errors()
            ladder = ", ".join(f"{lv.dofs}" for lv in result.levels)
            print(
                f"{name:<22} tol {tolerance:.0e}: {seconds:5.1f} s, dofs [{ladder}], true force "
                f"{true['force']:.2e} beta {true['beta']:.2e} (<= 2 tol: "
                f"{'yes' if max(true['force'], true['beta']) <= 2 * tolerance else 'NO'})"
            )


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--quick", action="store_true", help="one ladder per case, 1e-4 only")
    args = parser.parse_args()
    effectivity_table([1.0] if args.quick else [1.0, 1.414, 2.0])
    accuracy_table([1e-4] if args.quick else [1e-4, 1e-5])


if __name__ == "__main__":
    main()
