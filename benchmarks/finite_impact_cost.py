"""Where the finite-strain impact's march spends its CPU (speed63): counts and a time split.

Runs the researcher's relaxing pad (z = 8 r^1.3, 0.12 kg at 0.027 m/s on a 12 mm neo-Hookean
pad, E2 3 MPa, nu2 0.49, Prony 0.3:1e-3, mesh 0.2, 100 time steps per t_y, no estimate) in
three forms: with inertia (density2 1000) and a Coulomb indenter (friction 0.5), its massless
twin (density2 0) and the frictionless one with inertia, as the CLI runs them::

    shtaerman dynamic --exponent 1.3 --shape-coefficient 8 --E2 3e6 --nu2 0.49 \
        --mass 0.12 --velocity 0.027 --model neo-hookean --density2 1000 \
        --thickness 0.012 --prony 0.3:1e-3 --interface bonded --friction 0.5 \
        --mesh-size 0.2 --no-estimate

For each: time steps, steps cut, striker-equation (secant) evaluations, contact solves,
Newton iterations (states admitted), factorizations (QDLDL, SuperLU) and back-solves, and the
CPU seconds (``time.process_time``) of each part, exclusive of the parts nested inside it
(the kinematics inside a residual count as kinematics). The load average is printed beside
(the machine is shared); the results (x_max, P_max, t_contact, e) are printed with 17 digits
so that two versions can be compared.

Measured: benchmarks/FEM_NOTES.md, "The finite-strain impact's march (session 63, speed63)".

Run: PYTHONPATH=src python benchmarks/finite_impact_cost.py [--cases inertial massless ...]
(before and after a change: once with each version's src on PYTHONPATH, the loads alike).
"""

from __future__ import annotations

import argparse
import contextlib
import io
import json
import os
import time
from collections import defaultdict
from collections.abc import Iterator
from unittest import mock

from shtaerman.cli import main
from shtaerman.fem import finite_viscoelastic, hyperelastic, solver, stepper
from shtaerman.fem.contact import finite, finite_stick

STRIKER = "--exponent 1.3 --shape-coefficient 8 --E2 3e6 --nu2 0.49 --mass 0.12 --velocity 0.027"
PAD = "--model neo-hookean --thickness 0.012 --prony 0.3:1e-3 --mesh-size 0.2 --no-estimate"
CASES = {
    "inertial": "--density2 1000 --interface bonded --friction 0.5",
    "massless": "--density2 0 --interface bonded --friction 0.5",
    "frictionless": "--density2 1000 --interface frictionless",
}
PARTS = (  # (owner, attribute, label): the label's CPU excludes the parts called inside it
    (stepper, "_secant", "striker secant (rest)"),
    (finite.NewtonStepper, "iterate", "Newton loop (rest)"),
    (finite.NewtonStepper, "admit", "admit (rest)"),
    (hyperelastic.HyperelasticSystem, "state", "kinematics"),
    (finite_viscoelastic.ViscoelasticBody, "state", "Prony stress"),
    (hyperelastic.HyperelasticSystem, "residual", "residual"),
    (stepper._InertialSystem, "residual", "inertia (residual)"),
    (hyperelastic.HyperelasticSystem, "tangent_data", "tangent assembly"),
    (finite, "eliminate_gaps", "eliminate gaps (rest)"),
    (finite_stick, "eliminate_gaps", "eliminate gaps (rest)"),
    (finite.NewtonStepper, "geometry", "contact geometry"),
    (finite_stick, "_shifted_load", "stuck nodes' shift"),
    (finite_stick._Kept, "constrained", "added stuck dofs (rest)"),
    (finite, "bordered_step", "bordered step (rest)"),
    (finite_stick, "_load_step", "stick and slip (rest)"),
    (solver.PatternSolver, "_ldl_solve", "factorization QDLDL"),
    (solver.PatternSolver, "_ordered_solve", "factorization SuperLU"),
    (solver.PatternSolver, "factorized", "factorization (rest)"),
    (solver._ScaledSolve, "__call__", "back-solves"),
    (finite_viscoelastic.ViscoelasticBody, "commit", "Prony history update"),
    (finite_stick.HistoryStepper, "commit", "friction history update"),
    (hyperelastic.HyperelasticSystem, "energy", "energy"),
)
COUNTED = (  # (owner, attribute, what its calls count), not timed
    (stepper, "_advanced", "time steps (a cut step's halves: two)"),
    (stepper.QuasiStaticBody, "commit", "time steps (a cut step's halves: two)"),
    (stepper, "_body_step", "striker-equation evaluations"),
    (stepper.QuasiStaticBody, "at", "striker-equation evaluations"),
    (finite_stick.HistoryStepper, "solve", "contact solves"),
    (finite.NewtonStepper, "solve", "contact solves"),
    (finite_stick, "_warm_newton", "Newtons of the stick and slip"),
)


class Split:
    """CPU seconds per label, exclusive of the labelled calls nested inside, and call counts."""

    def __init__(self) -> None:
        self.cpu: dict[str, float] = defaultdict(float)
        self.calls: dict[str, int] = defaultdict(int)
        self.stack: list[list] = []  # [label, start, nested CPU]

    def wrap(self, method, label: str):
        def timed(*args, **kwargs):
            self.stack.append([label, time.process_time(), 0.0])
            try:
                return method(*args, **kwargs)
            finally:
                name, start, nested = self.stack.pop()
                spent = time.process_time() - start
                self.cpu[name] += spent - nested
                if self.stack:
                    self.stack[-1][2] += spent
                self.calls[name] += 1

        return timed

    def count(self, method, label: str):
        def counted(*args, **kwargs):
            self.calls[label] += 1
            return method(*args, **kwargs)

        return counted


@contextlib.contextmanager
def instrumented(split: Split) -> Iterator[None]:
    with contextlib.ExitStack() as stack:
        for owner, name, label in PARTS:
            method = getattr(owner, name)
            stack.enter_context(mock.patch.object(owner, name, split.wrap(method, label)))
        for owner, name, label in COUNTED:
            method = getattr(owner, name)
            stack.enter_context(mock.patch.object(owner, name, split.count(method, label)))
        yield


def load() -> str:
    one, five, fifteen = os.getloadavg()
    return f"load average {one:.2f} {five:.2f} {fifteen:.2f} on {os.cpu_count()} cores"


def run(case: str) -> None:
    argv = ["dynamic", *STRIKER.split(), *PAD.split(), *CASES[case].split(), "--json"]
    split, out = Split(), io.StringIO()
    print(f"\n== {case}: {CASES[case]} ({load()})")
    begun = time.process_time()
    with instrumented(split), contextlib.redirect_stdout(out):
        code = main(argv)
    total = time.process_time() - begun
    print(f"exit {code}; {total:.2f} CPU s in all ({load()})")
    result = json.loads(out.getvalue())
    dynamic, mesh = result["dynamic"], result["mesh"]
    print(f"dofs {mesh['dofs']}, retried: {result.get('retried')}")
    for key in ("x_max", "P_max", "t_contact", "restitution", "energy_balance_error"):
        print(f"  {key} = {dynamic[key]!r}")
    stepping = result["timings"]["stepping"]
    print(f"  stepping (wall) {stepping:.2f} s")
    for label in dict.fromkeys(label for _, _, label in COUNTED):
        print(f"  {label}: {split.calls[label]}")
    labels = list(dict.fromkeys(label for _, _, label in PARTS))
    timed = sum(split.cpu[label] for label in labels)
    for label in sorted(labels, key=lambda label: -split.cpu[label]):
        if split.calls[label]:
            cpu, calls = split.cpu[label], split.calls[label]
            print(f"  {label:28s} {cpu:7.2f} CPU s  {calls:6d} calls  {1e3 * cpu / calls:7.2f} ms")
    print(f"  {'(outside the parts)':28s} {total - timed:7.2f} CPU s")


def cli() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--cases", nargs="+", choices=list(CASES), default=list(CASES))
    for case in parser.parse_args().cases:
        run(case)


if __name__ == "__main__":
    cli()
