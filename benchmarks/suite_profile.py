"""Where the test suite's CPU goes, by category: a sampling pytest plugin.

Run from the repository root (any pytest options; under xdist every worker samples itself):

    PYTHONPATH=$PWD/src:$PWD/benchmarks python -m pytest -p suite_profile -p no:cacheprovider \
        [-n 2] [tests ...]
    python benchmarks/suite_profile.py [DIR]      # the table of the last run (default DIR below)

Every 5 ms of this process's CPU (``ITIMER_PROF``: user + sys of all its threads) a signal
samples the main thread's stack; the CPU since the last sample (``time.process_time``, so a
long C call is counted in full when Python next runs) goes to the first category of
:data:`CATEGORIES` whose rule matches a frame on the stack, and to the test that is running
(its setup, call and teardown; a session fixture counts to the first test that asks for it).
The CPU of child processes (``RUSAGE_CHILDREN``: the CLI start-up tests' interpreters, a
sweep's workers) counts per test as "child processes". Each process writes
``DIR/<worker>.json`` at its end; the script prints the sum by category and the costliest
tests. A fork does not inherit the interval timer. Asserts nothing about time.
"""

import json
import os
import resource
import signal
import sys
import time
from collections import defaultdict
from pathlib import Path

OUT = Path(os.environ.get("SUITE_PROFILE_DIR", "/tmp/suite-profile"))
INTERVAL = 0.005
CATEGORIES = (
    ("imports", lambda f, n: f.startswith("<frozen importlib")),
    ("matplotlib constrained layout", lambda f, n: "_constrained_layout" in f),
    ("matplotlib draw + savefig", lambda f, n: "matplotlib" in f and n in ("savefig", "draw")),
    ("matplotlib figure building", lambda f, n: "matplotlib" in f),
    ("pyvista/VTK", lambda f, n: "pyvista" in f or "vtkmodules" in f),
    ("gmsh meshing", lambda f, n: "gmsh" in f),
    ("FE solves (shtaerman.fem)", lambda f, n: "shtaerman/fem/" in f),
    ("theory (shtaerman.theory)", lambda f, n: "shtaerman/theory/" in f),
    ("fitting (shtaerman.fitting)", lambda f, n: "shtaerman/fitting/" in f),
    ("other shtaerman", lambda f, n: "shtaerman/" in f and "/tests/" not in f),
    ("tests' own code", lambda f, n: "/tests/" in f),
)


def category(frame) -> str:
    """The first category whose rule matches a frame from the innermost outward."""
    stack = []
    while frame is not None:
        stack.append((frame.f_code.co_filename, frame.f_code.co_name))
        frame = frame.f_back
    for name, rule in CATEGORIES:
        if any(rule(f, n) for f, n in stack):
            return name
    return "other (pytest, stdlib, numpy outside the above)"


class Sampler:
    """The CPU per test and category of this process (see the module docstring)."""

    def __init__(self) -> None:
        self.test = "(collection and session start)"
        self.cpu: dict[str, dict[str, float]] = defaultdict(lambda: defaultdict(float))
        self.last = time.process_time()
        self.children = self._children()

    @staticmethod
    def _children() -> float:
        usage = resource.getrusage(resource.RUSAGE_CHILDREN)
        return usage.ru_utime + usage.ru_stime

    def sample(self, signum, frame) -> None:
        now = time.process_time()
        self.cpu[self.test][category(frame)] += now - self.last
        self.last = now

    def switch(self, test: str) -> None:
        now, children = time.process_time(), self._children()
        self.cpu[self.test]["(unsampled tail)"] += now - self.last
        self.cpu[self.test]["child processes"] += children - self.children
        self.last, self.children, self.test = now, children, test

    def dump(self) -> None:
        self.switch("(session end)")
        OUT.mkdir(parents=True, exist_ok=True)
        worker = os.environ.get("PYTEST_XDIST_WORKER", "main")
        (OUT / f"{worker}.json").write_text(json.dumps(self.cpu, indent=0))


SAMPLER: Sampler | None = None


def pytest_configure(config) -> None:
    global SAMPLER
    if os.environ.get("PYTEST_XDIST_WORKER") or not getattr(config.option, "numprocesses", None):
        SAMPLER = Sampler()
        signal.signal(signal.SIGPROF, SAMPLER.sample)
        signal.setitimer(signal.ITIMER_PROF, INTERVAL, INTERVAL)


def pytest_runtest_logstart(nodeid, location) -> None:
    if SAMPLER is not None:
        SAMPLER.switch(nodeid)


def pytest_unconfigure(config) -> None:
    if SAMPLER is not None:
        signal.setitimer(signal.ITIMER_PROF, 0, 0)
        SAMPLER.dump()


def table(folder: Path, top: int = 40) -> None:
    """Print the CPU by category and the ``top`` costliest tests of the run in ``folder``."""
    by_category: dict[str, float] = defaultdict(float)
    by_test: dict[str, dict[str, float]] = defaultdict(lambda: defaultdict(float))
    for path in sorted(folder.glob("*.json")):
        for test, cpu in json.loads(path.read_text()).items():
            for name, seconds in cpu.items():
                by_category[name] += seconds
                by_test[test][name] += seconds
    total = sum(by_category.values())
    print(f"{'category':50s} {'CPU s':>8s} {'share':>6s}")
    for name, seconds in sorted(by_category.items(), key=lambda item: -item[1]):
        print(f"{name:50s} {seconds:8.1f} {100 * seconds / total:5.1f}%")
    print(f"{'total':50s} {total:8.1f}\n")
    drawing = ("matplotlib", "pyvista")
    ranked = sorted(by_test.items(), key=lambda item: -sum(item[1].values()))
    for test, cpu in ranked[:top]:
        draw = sum(s for n, s in cpu.items() if n.startswith(drawing))
        print(f"{sum(cpu.values()):7.1f} s (drawing {draw:6.1f}) {test}")


if __name__ == "__main__":
    table(Path(sys.argv[1]) if len(sys.argv) > 1 else OUT)
