"""Wall time of the main job, `shtaerman verify` on every shipped study (default meshes).

Run: python benchmarks/bench_verify.py [--quick]. Prints seconds per study and in total;
asserts nothing about time. The issue's budget: under 60 s on a 2-core machine. Measured on
this project's machines: 22.8 s before the paper study had its 5-mesh convergence study, 28.4 s
for the same code on a slower day, 31.6-33.6 s with it (the convergence study alone: 3.2 s).
"""

import argparse
import os
import tempfile
import time
from pathlib import Path

from shtaerman.output.folder import run_verification
from shtaerman.study.schema import load_study, shipped_studies


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--quick", action="store_true", help="coarse meshes, as in CI")
    args = parser.parse_args()
    studies = [study for path in shipped_studies() for study in load_study(path)]
    with tempfile.TemporaryDirectory() as folder:
        start = time.perf_counter()
        results = run_verification(
            studies, Path(folder) / "run", quick=args.quick, progress=lambda _line: None
        )
        total = time.perf_counter() - start
    print(f"machine: {os.cpu_count()} cores; {'quick' if args.quick else 'default'} meshes")
    print(f"{'study':<16} {'dofs':>7} {'FEM s':>7} {'study s':>8}  verdict")
    for name, study in results["studies"].items():
        contact = study["contact"]
        print(
            f"{name:<16} {contact['mesh']['dofs']:>7} {contact['timings']['total']:>7.2f} "
            f"{study['seconds']:>8.2f}  {'PASS' if study['passed'] else 'FAIL'}"
        )
    print(
        f"total (with figures, report, files): {total:.1f} s; budget 60 s -> {total / 60:.2f} of it"
    )


if __name__ == "__main__":
    main()
