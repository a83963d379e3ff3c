"""Wall time of the main job, `shtaerman verify` on every shipped study, in this process and as
dask tasks on 2 workers (the CLI's default on 2 cores).

Run: python benchmarks/bench_verify.py [--quick]. Prints seconds per study, the totals and the
speed-up; asserts nothing about time. The budget: under 60 s on a 2-core machine. History:
22.8 s before the paper study had its 5-mesh convergence study, 31.6-33.6 s with it (one
process, contact studies only, no error-estimate ladder).
"""

import argparse
import os
import tempfile
import time
from pathlib import Path

from shtaerman.output.folder import run_verification
from shtaerman.study.schema import load_study, shipped_studies
from shtaerman.sweep.verify import run_verification_on_dask


def timed(run, studies, quick: bool) -> tuple[float, dict]:
    with tempfile.TemporaryDirectory() as folder:
        start = time.perf_counter()
        results = run(studies, Path(folder) / "run", quick=quick)
        return time.perf_counter() - start, results


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--quick", action="store_true", help="coarse meshes, as in CI")
    args = parser.parse_args()
    studies = [study for path in shipped_studies() for study in load_study(path)]
    serial, results = timed(
        lambda s, o, quick: run_verification(s, o, quick=quick, progress=lambda _l: None),
        studies,
        args.quick,
    )
    parallel, _ = timed(
        lambda s, o, quick: run_verification_on_dask(s, o, quick=quick, workers=2),
        studies,
        args.quick,
    )
    print(
        f"machine: {os.cpu_count()} cores, load {os.getloadavg()[0]:.1f}; "
        f"{'quick' if args.quick else 'default'} settings"
    )
    print(f"{'study':<24} {'kind':<14} {'computed s':>10} {'total s':>8}  verdict")
    for name, study in results["studies"].items():
        timings = study.get("timings") or {}
        print(
            f"{name:<24} {study.get('kind', 'contact'):<14} {study['seconds']:>10.2f} "
            f"{timings.get('total', float('nan')):>8.2f}  {'PASS' if study['passed'] else 'FAIL'}"
        )
    print(
        f"one process: {serial:.1f} s; 2 dask workers: {parallel:.1f} s "
        f"(speed-up {serial / parallel:.2f}x); budget 60 s -> {parallel / 60:.2f} of it"
    )


if __name__ == "__main__":
    main()
