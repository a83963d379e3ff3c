"""Sweep speed-up: an 8-case linear FEM contact grid on 1 local dask worker, then on 2.

The grid is exponent n in {1.5, 2} x nu2 in {0, 0.25, 0.4, 0.5} on the default mesh (about 29k
dofs a case); ``--kind dynamic``: the dynamic FE impact, velocity {1, 2} m/s x nu2 {0.3, 0.4,
0.45, 0.5} at the default mesh and steps, without the ladder (``--estimate``: with it). Each
sweep runs in a fresh folder with a fresh local cluster, set up as the engine does ("now":
workers forked on Linux, dask's profiler and monitors off) and, as the reference of the same
run, as it did before ("before": workers spawned, dask's monitoring on). Printed, with the load
average beside each wall time:

1. the fixed cost of a sweep: the wall time of a 2-case analytic impact sweep (cases of a
   millisecond), i.e. starting and stopping the workers;
2. the CPU of a sweep: its cases' (summed ``cpu_seconds`` of the records) and the rest (this
   process and the workers outside the cases); the contention is the cases' CPU on 2 workers
   over 1 worker (1.00 when two cases at once do not slow each other down);
3. the wall-time speed-up of 2 workers over 1 (the issue's target: 1.8x on an idle machine),
   which on a machine shared with other work reads low.

    python benchmarks/bench_sweep.py [--repeat K] [--workers 1,2] [--kind contact|dynamic]
        [--estimate] [--setups now,before]
"""

from __future__ import annotations

import argparse
import itertools
import json
import os
import resource
import tempfile
import time
from pathlib import Path

from shtaerman.sweep import engine, parse_sweep, run_sweep

GRID = """\
name = "bench-contact"
kind = "contact"
[axes]
exponent = [1.5, 2.0]
nu2 = [0.0, 0.25, 0.4, 0.5]
"""
GRID_DYNAMIC = """\
name = "bench-dynamic"
kind = "dynamic"
[parameters]
estimate = ESTIMATE
[axes]
velocity = [1.0, 2.0]
nu2 = [0.3, 0.4, 0.45, 0.5]
"""
TRIVIAL = """\
name = "bench-trivial"
kind = "impact"
[axes]
velocity = [1.0, 2.0]
"""


def load() -> str:
    one, five, fifteen = os.getloadavg()
    return f"load {one:.2f} / {five:.2f} / {fifteen:.2f}"


def _spin(_: int = 0) -> float:
    """A fixed CPU-bound job (about 1 s on an idle core); returns its wall time."""
    start, total = time.perf_counter(), 0
    for i in range(12_000_000):
        total += i & 7
    return time.perf_counter() - start


def capacity(workers: int) -> float:
    """What the machine gives right now: the speed-up of ``workers`` copies of a CPU-bound job
    run at once over one copy (2.0 on two idle cores, less when other work holds them)."""
    from concurrent.futures import ProcessPoolExecutor

    with ProcessPoolExecutor(workers) as pool:
        list(pool.map(_spin, range(workers)))  # start the processes
        single = pool.submit(_spin).result()
        start = time.perf_counter()
        list(pool.map(_spin, range(workers)))
        together = time.perf_counter() - start
    return workers * single / together


SETUPS = {
    "now": (engine.START_METHOD, engine.QUIET_CLUSTER),
    "before": ("spawn", {}),
}
"""How the local cluster is set up: (start method, dask settings); "before" as in 5b25f53
(spawned workers, dask's profiler and monitors on). The worker preload is the same in both, so
the freed memory a worker keeps (sweep/_worker.py) is in both; its own A/B is in-process."""


def _cpu() -> float:
    """CPU seconds of this process and of its finished children (the workers, once closed)."""
    own, children = (
        resource.getrusage(who) for who in (resource.RUSAGE_SELF, resource.RUSAGE_CHILDREN)
    )
    return own.ru_utime + own.ru_stime + children.ru_utime + children.ru_stime


def sweep(spec, out: Path, workers: int, setup: str) -> tuple[float, float, float]:
    """Wall time of one sweep, its cases' CPU seconds and the CPU seconds of the rest."""
    engine.START_METHOD, engine.QUIET_CLUSTER = SETUPS[setup]
    start, cpu = time.perf_counter(), _cpu()
    outcome = run_sweep(spec, out, workers=workers, progress=False, figures=False)
    wall, total = time.perf_counter() - start, _cpu() - cpu
    assert outcome.succeeded == outcome.total, "a case failed"
    cases = sum(c["cpu_seconds"] for c in json.loads((out / "results.json").read_text())["cases"])
    return wall, cases, total - cases


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeat", type=int, default=1, help="sweeps per worker count")
    parser.add_argument("--workers", default="1,2", help="worker counts, comma-separated")
    parser.add_argument("--kind", choices=("contact", "dynamic"), default="contact")
    parser.add_argument("--estimate", action="store_true", help="dynamic: with the ladder")
    parser.add_argument("--setups", default="now,before", help="now, before or both")
    args = parser.parse_args()
    counts = [int(w) for w in args.workers.split(",")]
    setups = list(dict.fromkeys(args.setups.split(",")))
    estimate = "true" if args.estimate else "false"
    grid = GRID if args.kind == "contact" else GRID_DYNAMIC.replace("ESTIMATE", estimate)
    spec = parse_sweep(grid, f"bench-{args.kind}.toml")
    trivial = parse_sweep(TRIVIAL, "bench-trivial.toml")
    print(f"8-case linear {args.kind} sweep; {len(os.sched_getaffinity(0))} usable cores; {load()}")
    print(f"  machine now: 2 CPU-bound processes run {capacity(2):.2f}x as fast as one")
    best: dict[tuple[str, int], float] = {}
    cpu: dict[tuple[str, int], float] = {}
    with tempfile.TemporaryDirectory() as tmp:
        sweep(trivial, Path(tmp) / "warm-up", 1, setups[0])  # dask's imports in this process
        for repeat in range(args.repeat):
            for setup, workers in itertools.product(setups, counts):
                wall, _, rest = sweep(
                    trivial, Path(tmp) / f"t{setup}{workers}-{repeat}", workers, setup
                )
                print(
                    f"  {setup:6s} {workers} worker(s): fixed cost {wall:5.2f} s wall, "
                    f"{rest:5.2f} s CPU  ({load()})"
                )
            for setup, workers in itertools.product(setups, counts):
                key = (setup, workers)
                wall, cases, rest = sweep(
                    spec, Path(tmp) / f"{setup}{workers}-{repeat}", workers, setup
                )
                best[key] = min(wall, best.get(key, float("inf")))
                cpu[key] = min(cases, cpu.get(key, float("inf")))
                print(
                    f"  {setup:6s} {workers} worker(s): wall {wall:6.2f} s, CPU of the cases "
                    f"{cases:6.2f} s, of the rest {rest:5.2f} s  ({load()})"
                )
    for setup in setups:
        for workers in counts[1:]:
            one, many = (setup, counts[0]), (setup, workers)
            print(
                f"{setup}: {workers} workers vs {counts[0]}: wall {best[one] / best[many]:.2f}x "
                f"(issue: 1.8x idle); cases' CPU {cpu[many] / cpu[one]:.2f}x (contention); best "
                f"of {args.repeat}"
            )


if __name__ == "__main__":
    main()
