"""The CPU cost of the shipped finite-strain studies' Newton (issue 32): factorizations,
back-solves, Newton iterations and CPU seconds, against one factorization of the finest level.

Runs :func:`shtaerman.study.finite.runner.run_finite_strain_study` on both members of
fem/finite_strain.toml (nu2 = 0.5 and 0.3; the three levels of the nested mesh ladder, the
linear FEM and the impacts: the work ``verify finite_strain --workers 1`` does for them) and
counts, per study, the factorizations of the finite-strain Newton
(:meth:`shtaerman.fem.solver.PatternSolver.factorized`), the solves with a kept factorization
(a modified Newton step's, and a bordered step's one per changed candidate) and the Newton
iterations. It then times one factorization of the first reduced tangent the finest level
factorized (its first depth's) in the same process and prints the study's CPU seconds as a
multiple of it. CPU times come from ``time.process_time``; the load average is printed
beside them (the machine is shared).

Measured (session 56, load average 3-9 on 2 cores): main c2e2086 125 and 125 factorizations
(finest level 44 and 42), 111 and 107 finest factorizations' worth of CPU (one: ~0.2 CPU s);
with the bordered first step of a depth and no redo of a failed solve that reused nothing,
102 and 99 (finest 37 and 34), 98 and 93 worth. Of a study's CPU, SuperLU's factorizations
are ~45 %; the rest is the tangent and state assembly, the back-solves, the linear FEM and
the impacts. The hyperelastic state, residual and tangent_data calls (outermost, CPU s):
main b6f132c 5.2 and 4.9 (nu2 0.5: state 2.0, residual 0.7, tangent 2.4); with a state and
residual as one sparse product and D built in contiguous runs (branch asm56) 3.9 and 3.8
(1.4, 0.55, 1.8), load average 2.5-4.5.

Run: PYTHONPATH=src python benchmarks/finite_newton_cost.py [--members 0 1]
"""

from __future__ import annotations

import argparse
import os
import time
from unittest import mock

import numpy as np

from shtaerman.fem.contact.finite import NewtonStepper
from shtaerman.fem.hyperelastic import HyperelasticSystem
from shtaerman.fem.solver import PatternSolver
from shtaerman.study.finite.runner import run_finite_strain_study
from shtaerman.study.schema import load_study, shipped_studies


def load() -> str:
    one, five, fifteen = os.getloadavg()
    return f"load average {one:.2f} {five:.2f} {fifteen:.2f} on {os.cpu_count()} cores"


class Counter:
    """Wraps PatternSolver.factorized and NewtonStepper.iterate: counts and CPU seconds."""

    def __init__(self) -> None:
        self.factorizations = 0
        self.reused = 0
        self.factor_cpu = 0.0
        self.iterations = 0
        self.finest: tuple[PatternSolver, np.ndarray] | None = None
        self.sizes: dict[int, int] = {}
        self.assembly_cpu: dict[str, float] = {}
        self.assembling = False

    def assembly(self, method, system: HyperelasticSystem, *args, **kwargs):
        """Time an outermost state, residual or tangent_data call (not the nested state)."""
        if self.assembling:
            return method(system, *args, **kwargs)
        self.assembling, start = True, time.process_time()
        try:
            return method(system, *args, **kwargs)
        finally:
            name = method.__name__
            self.assembly_cpu[name] = self.assembly_cpu.get(name, 0.0) + (
                time.process_time() - start
            )
            self.assembling = False

    def factorized(self, solver: PatternSolver, data: np.ndarray, rhs: np.ndarray):
        start = time.process_time()
        solution, again = ORIGINAL_FACTORIZED(solver, data, rhs)
        self.factor_cpu += time.process_time() - start
        self.factorizations += 1
        size = solver.pattern.size
        self.sizes[size] = self.sizes.get(size, 0) + 1
        if self.finest is None or size > self.finest[0].pattern.size:
            self.finest = (solver, data.copy())

        def counted(b: np.ndarray) -> np.ndarray:
            self.reused += 1
            return again(b)

        return solution, counted

    def iterate(self, stepper: NewtonStepper, *args, **kwargs):
        result = ORIGINAL_ITERATE(stepper, *args, **kwargs)
        self.iterations += result[2]
        return result


ORIGINAL_FACTORIZED = PatternSolver.factorized
ORIGINAL_ITERATE = NewtonStepper.iterate


def timing(counter: Counter, name: str) -> mock._patch:
    """A patch of HyperelasticSystem.``name`` that adds its CPU to ``counter.assembly_cpu``
    (an outermost call's: a residual's or a tangent's own state call is theirs)."""
    method = getattr(HyperelasticSystem, name)
    return mock.patch.object(
        HyperelasticSystem, name, lambda s, *a, **k: counter.assembly(method, s, *a, **k)
    )


def one_factorization(counter: Counter, repeat: int = 3) -> float:
    """Least CPU seconds of ``repeat`` factorizations of the finest level's first tangent."""
    solver, data = counter.finest
    rhs = np.ones(solver.pattern.size)
    best = np.inf
    for _ in range(repeat):
        start = time.process_time()
        ORIGINAL_FACTORIZED(solver, data, rhs)
        best = min(best, time.process_time() - start)
    return best


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--members", type=int, nargs="+", default=[0, 1])
    args = parser.parse_args()
    studies = load_study(next(p for p in shipped_studies() if p.stem == "finite_strain"))
    rows = []
    for member in args.members:
        study = studies[member]
        counter = Counter()
        patches = (
            mock.patch.object(
                PatternSolver, "factorized", lambda s, d, r, c=counter: c.factorized(s, d, r)
            ),
            mock.patch.object(
                NewtonStepper, "iterate", lambda s, *a, c=counter, **k: c.iterate(s, *a, **k)
            ),
        )
        timed = [timing(counter, name) for name in ("state", "residual", "tangent_data")]
        start = time.process_time()
        with patches[0], patches[1], timed[0], timed[1], timed[2]:
            outcome = run_finite_strain_study(study)
        cpu = time.process_time() - start
        unit = one_factorization(counter)
        rows.append((study.name, counter, cpu, unit, outcome))
        print(
            f"{study.name}: CPU {cpu:.1f} s ({load()}); factorizations {counter.factorizations} "
            f"(by size {dict(sorted(counter.sizes.items()))}, {counter.factor_cpu:.1f} CPU s), "
            f"kept-factorization solves {counter.reused}, Newton iterations "
            f"{counter.iterations}; hyperelastic CPU s "
            f"{ {k: round(v, 2) for k, v in counter.assembly_cpu.items()} }; one finest "
            f"factorization {unit:.3f} CPU s: "
            "the study costs "
            f"{cpu / unit:.0f} of them",
            flush=True,
        )


if __name__ == "__main__":
    main()
