"""Throughput of the Ateb functions: evaluations per second on 10^6 points, ms per call.

Run as ``python benchmarks/bench_ateb.py``.  Prints timings only (best of a few repeats);
asserts nothing about wall-clock time.
"""

from __future__ import annotations

import time
from collections.abc import Callable
from functools import partial

import numpy as np

from shtaerman.theory.ateb import ateb_cosine, ateb_sine, quarter_period

POINTS = 1_000_000
REPEATS = 5
SCALAR_REPEATS = 2000
CASES = [("paper, q = 5/3", 5 / 3, 1.0), ("Hertz, q = 3/2", 1.5, 1.0), ("sin/cos", 1.0, 1.0)]


def best_time(call: Callable[[], object], repeats: int = REPEATS) -> float:
    """Shortest wall-clock time of ``repeats`` calls, in seconds."""
    times = []
    for _ in range(repeats):
        start = time.perf_counter()
        call()
        times.append(time.perf_counter() - start)
    return min(times)


def row(label: str, name: str, vector: float, scalar: float | None = None) -> str:
    """One line of the table: evaluations/s and ms per 10^6-point call, us per scalar call."""
    line = f"{label:<16} {name:<12} {POINTS / vector:>18.3e} {1e3 * vector:>14.1f}"
    return line if scalar is None else f"{line} {1e6 * scalar:>17.1f}"


def main() -> None:
    """Print the throughput table."""
    rng = np.random.default_rng(0)
    header = f"{'case':<16} {'function':<12} {'evals/s (1e6 pts)':>18} {'ms/call (1e6)':>14}"
    print(f"{header} {'us/call (scalar)':>17}")
    for label, m, n in CASES:
        phi = rng.uniform(-4, 4, POINTS) * quarter_period(m, n)
        for name, call in (
            ("ateb_sine", partial(ateb_sine, m, n)),
            ("ateb_cosine", partial(ateb_cosine, n, m)),
        ):
            vector = best_time(partial(call, phi))
            scalar = best_time(partial(call, 0.3), SCALAR_REPEATS)
            print(row(label, name, vector, scalar))
    print(row("numpy", "np.sin", best_time(partial(np.sin, phi))))


if __name__ == "__main__":
    main()
