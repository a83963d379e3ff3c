"""The bonded contact at finite strain (fem/contact/finite_stick.py) on the paper's case, its cost.

The paper's case (A = 5, n = 1.5, E2 = 7.5 MPa, nu2 = 0.5 neo-Hookean, the eight default
depths up to the x_c of 0.7 kg at 3 m/s) with a bonded indenter on the default finite-strain
mesh (FINITE_MESH), as ``shtaerman contact --model neo-hookean --interface bonded
--no-estimate`` runs it. Printed: the CPU seconds of the solve (``verify_cost.cpu``: user +
sys, all threads; meshing and assembly excluded), their ratio to one SuperLU factorization of
a fixed 2-D Laplacian timed in the same run (``verify_cost.reference``), the load steps, the
Newton iterations, the factorizations, the forces at the eight depths, and the one-minute
load average. With ``--compare FILE`` (a ``contact --json`` report or an earlier
``--save``), the largest relative change of the forces against it. The machine is shared:
compare CPU seconds and ratios, not wall time. Asserts nothing.

Run: python benchmarks/bonded_finite.py [--friction MU] [--save FILE] [--compare FILE]
"""

from __future__ import annotations

import argparse
import json
import math
import time
from pathlib import Path

import numpy as np
from verify_cost import cpu, load, reference

import shtaerman.fem.contact.finite_stick as finite_stick
from shtaerman.fem.contact.finite import run_finite_indentation
from shtaerman.fem.mesh import FINITE_MESH
from shtaerman.fem.solver import PatternSolver
from shtaerman.study.contact.indentation import default_depths
from shtaerman.theory.indenter import PowerLawIndenter
from shtaerman.theory.materials import Material

INDENTER = PowerLawIndenter(5.0, 1.5)
HALF_SPACE = Material(7.5e6, 0.5)


def counted() -> dict[str, int]:
    """Count the load steps, their Newton iterations and the factorizations (patches the
    solver's functions for this process)."""
    counts = {"load steps": 0, "Newton iterations": 0, "factorizations": 0}
    step, factorized = finite_stick._load_step, PatternSolver.factorized  # bonded and Coulomb

    def counting(original):
        def wrapped(*args, **kwargs):
            state = original(*args, **kwargs)
            counts["load steps"] += 1
            counts["Newton iterations"] += state.iterations
            return state

        return wrapped

    def factorizing(self, *args, **kwargs):
        counts["factorizations"] += 1
        return factorized(self, *args, **kwargs)

    finite_stick._load_step = counting(step)
    PatternSolver.factorized = factorizing
    return counts


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--friction", type=float, default=math.inf, help="Coulomb (inf: none)")
    parser.add_argument("--save", type=Path, help="write the forces (N) as JSON")
    parser.add_argument("--compare", type=Path, help="a contact --json report or a --save")
    args = parser.parse_args()
    unit = reference()
    depths = default_depths(INDENTER, HALF_SPACE)
    mesh = FINITE_MESH
    counts = counted()
    before, wall, average = cpu(), time.perf_counter(), load()
    solve = finite_stick.solve_finite_bonded_contact
    if math.isfinite(args.friction):
        solve = lambda *a, **k: finite_stick.solve_finite_bonded_contact(  # noqa: E731
            *a, friction=args.friction, **k
        )
    curve = run_finite_indentation(INDENTER, HALF_SPACE, depths, mesh, solve=solve)
    spent = cpu() - before
    solving = curve.timings["contact"] / curve.timings["total"] * spent
    forces = np.array([step.force for step in curve.steps])
    print(f"reference factorization {unit:.3f} CPU s; load {average:.1f} -> {load():.1f}")
    print(f"dofs {curve.mesh_stats['dofs']}, friction {args.friction:g}")
    print(f"CPU {spent:.1f} s ({spent / unit:.0f} references; the solve ~{solving:.1f} s)")
    print(f"wall {time.perf_counter() - wall:.1f} s")
    print(", ".join(f"{name} {count}" for name, count in counts.items()))
    print("forces (N): " + " ".join(f"{force:.9g}" for force in forces))
    if args.save:
        args.save.write_text(json.dumps({"forces": forces.tolist()}))
    if args.compare:
        report = json.loads(args.compare.read_text())
        old = np.array(report.get("forces") or [s["force"] for s in report["steps"]])
        change = np.abs(forces / old - 1.0)
        print("relative change of the forces: " + " ".join(f"{c:.1e}" for c in change))
        print(f"largest {change.max():.2e}")


if __name__ == "__main__":
    main()
