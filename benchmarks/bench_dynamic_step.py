"""Where a time step of the dynamic impact spends its CPU, and what the per-step solve costs.

The 3 m/s impact of fem/dynamic.toml at the study's finest settings (200 steps per t_y, size
1/40: 11,654 dofs, 400 steps, one BLAS thread as ``march`` runs). Every figure is CPU seconds
(``time.process_time``) and its ratio to one SuperLU factorization of a fixed 2-D Laplacian
timed in the same run (``verify_cost.reference``), with the one-minute load beside it: the
machine is shared, compare ratios, not wall time. Sections:

(a) one ``march``: ms per step of the predictor's back-substitution, the rest of the
    predictor (x_hat, M_h y, the alpha_f load), the contact (its LCP apart), the rest of
    ``advance`` (K x, velocities, accelerations) and ``_observe`` (M_h v, contact radius,
    central pressure);
(b) the effective matrix's factor: fill (nonzeros of L + U) and one solve per fill-reducing
    order (METIS nested dissection of the node graph as shipped, weighted by dofs per node, of
    the dof graph; SuperLU's MMD_AT_PLUS_A and COLAMD; MMD of the node graph; reverse
    Cuthill-McKee); the shipped solve with and without its permutation and scaling copies,
    transposed, and one product with L and U (the streaming floor of a solve of that fill);
(c) the per-step sparse products: M_h y and M_h v apart and as one complex product (M_h
    stored complex once per run), K x.

``--compare SRC`` instead runs (a) in fresh processes alternately on SRC (e.g. an old
checkout's ``src``) and on this tree's ``src``, ``--rounds`` times, and prints ms per step, the
reference, the load and the ratio new / old of the per-step cost in references.

Run: python benchmarks/bench_dynamic_step.py [--compare SRC [--rounds K]]. Asserts nothing.

Measured 2026-12-01 (session 59), reference ~0.26-0.29 s: (a) at load 9, a step 4.2 ms =
0.015 ref: solve 2.3, K x and the updates 0.66, observe 0.46, contact 0.31 + LCP 0.29,
predictor rest 0.22 ms. (b) fill 1.18-1.26M for every order but COLAMD (1.81M) and RCM
(2.21M); the solve alone 1.4-1.6 ms, transposed 12 % less; one product with L and U 0.96 ms.
(c) one complex product 0.20 ms against 0.16 ms for M_h y and M_h v. --compare against the
code before the transposed solve (main d043a2c), 5 rounds at load 1.6-1.8: new / old 0.885
per-step solve, 0.929 per step. Details in FEM_NOTES.md, "Time stepping cost".
"""

from __future__ import annotations

import argparse
import json
import os
import subprocess
import sys
import time
from dataclasses import replace
from pathlib import Path

import numpy as np
import pymetis
import scipy.sparse as sp
import scipy.sparse.linalg as spla
from scipy.sparse.csgraph import reverse_cuthill_mckee
from threadpoolctl import threadpool_limits
from verify_cost import load, reference

from shtaerman.fem import solver, stepper
from shtaerman.fem.dynamic_contact import DynamicSettings, prepare_dynamic_impact
from shtaerman.theory.indenter import PowerLawIndenter
from shtaerman.theory.materials import Material

SRC = Path(__file__).resolve().parents[1] / "src"
PARTS = {  # name -> (module, function) timed inside march
    "solve": None,
    "predictor": (stepper, "_predictor"),
    "contact": (stepper, "_contact"),
    "lcp": (stepper, "complementarity"),
    "advance": (stepper, "advance"),
    "observe": (stepper, "_observe"),
}


def setup() -> tuple[stepper.ImpactProblem, dict[str, object]]:
    """The 3 m/s case of fem/dynamic.toml at its finest ladder level, and its march options."""
    run = prepare_dynamic_impact(
        PowerLawIndenter(5.0, 1.5),
        Material(7.5e6, 0.5),
        1100.0,
        0.7,
        3.0,
        DynamicSettings(steps=200, size=1.0 / 40.0),
    )
    options = {"duration": run.duration, "tail_time": run.tail_time, "force_exponent": 5 / 3}
    return run.problem, {**options, "energy_series": False}


class _Timed:
    """A factorization whose solves add their CPU seconds to ``spent['solve']``."""

    def __init__(self, inner: solver.Factorization, spent: dict[str, float]) -> None:
        self.inner, self.spent = inner, spent
        self.backend, self.shape = inner.backend, inner.shape

    def solve(self, rhs: np.ndarray) -> np.ndarray:
        start = time.process_time()
        out = self.inner.solve(rhs)
        self.spent["solve"] += time.process_time() - start
        return out


def _timing(module: object, name: str, spent: dict[str, float], key: str) -> object:
    """Wrap ``module.name`` so that its calls add their CPU seconds to ``spent[key]``."""
    function = getattr(module, name)

    def timed(*args: object, **kwargs: object) -> object:
        start = time.process_time()
        out = function(*args, **kwargs)
        spent[key] += time.process_time() - start
        return out

    setattr(module, name, timed)
    return function


def march_parts() -> dict[str, float]:
    """(a): ms per step of each part of one march, the whole step and the reference."""
    problem, options = setup()
    spent = dict.fromkeys(PARTS, 0.0)
    timed = replace(problem, factorization=_Timed(problem.factorization, spent))
    saved = {k: _timing(*v, spent, k) for k, v in PARTS.items() if v is not None}
    ref = reference()
    start = time.process_time()
    history = stepper.march(timed, **options)
    total = time.process_time() - start
    for key, function in saved.items():
        setattr(PARTS[key][0], PARTS[key][1], function)
    steps = history.t.size - 1
    per = {k: 1e3 * v / steps for k, v in spent.items()}
    return {
        "step": 1e3 * total / steps,
        "solve": per["solve"],
        "predictor rest": per["predictor"] - per["solve"],
        "lcp": per["lcp"],
        "contact rest": per["contact"] - per["lcp"],
        "advance rest": per["advance"] - per["predictor"] - per["contact"],
        "observe": per["observe"],
        "reference": 1e3 * min(ref, reference()),
        "load": load(),
    }


def cpu_ms(function: object, repeat: int = 300) -> float:
    """Least of three means of ``repeat`` calls, CPU ms."""
    function()
    best = float("inf")
    for _ in range(3):
        start = time.process_time()
        for _ in range(repeat):
            function()
        best = min(best, (time.process_time() - start) / repeat)
    return 1e3 * best


def _expand(group_order: np.ndarray, groups: np.ndarray) -> np.ndarray:
    """The unknowns in the order of their groups (a node order), each group's together."""
    rank = np.empty(groups.max() + 1, dtype=np.int64)
    rank[np.asarray(group_order)] = np.arange(rank.size)
    return np.argsort(rank[groups], kind="stable")


def orders(scaled: sp.csc_matrix, groups: np.ndarray) -> dict[str, np.ndarray | str]:
    """Fill-reducing orders of (b): a permutation, or a SuperLU permc_spec."""
    n, count = scaled.shape[0], int(groups.max()) + 1
    incidence = sp.csr_matrix((np.ones(n), (np.arange(n), groups)), shape=(n, count))
    nodes = (incidence.T @ (abs(scaled) > 0).astype(float) @ incidence).tocsr()
    nodes.setdiag(0)
    nodes.eliminate_zeros()
    dofs = (abs(scaled) > 0).astype(float).tocsr()
    dofs.setdiag(0)
    dofs.eliminate_zeros()
    node_graph = pymetis.CSRAdjacency(nodes.indptr, nodes.indices)
    weighted = pymetis.nested_dissection(node_graph, vweights=np.bincount(groups))[0]
    mmd = spla.splu(
        (nodes + sp.eye(count)).tocsc(),
        permc_spec="MMD_AT_PLUS_A",
        diag_pivot_thresh=0.0,
        options={"SymmetricMode": True},
    )
    return {
        "METIS ND node graph (shipped)": solver.nested_dissection(scaled, groups),
        "METIS ND nodes weighted by dofs": _expand(weighted, groups),
        "METIS ND dof graph": np.asarray(
            pymetis.nested_dissection(pymetis.CSRAdjacency(dofs.indptr, dofs.indices))[0]
        ),
        "SuperLU MMD_AT_PLUS_A": "MMD_AT_PLUS_A",
        "SuperLU COLAMD": "COLAMD",
        "MMD of the node graph": _expand(np.argsort(mmd.perm_c), groups),
        "reverse Cuthill-McKee nodes": _expand(reverse_cuthill_mckee(nodes, True), groups),
    }


def factor_table(problem: stepper.ImpactProblem) -> None:
    """(b): fill and solve per order, and the shipped solve's overheads and floor."""
    shipped = problem.factorization
    scale, order = shipped.scale, shipped._inner.order
    free = problem.free
    scaled = _scaled_effective(problem)
    rhs = np.random.default_rng(0).standard_normal(free.size)
    ref = reference()
    print(f"\n(b) factor of the scaled effective matrix, {free.size} unknowns, load {load():.1f}")
    print(f"    reference factorization {1e3 * ref:.1f} ms CPU")
    for name, how in orders(scaled, problem.system.dof_nodes()[free]).items():
        if isinstance(how, str):
            options = {"SymmetricMode": True, "Equil": False}
            lu = spla.splu(scaled, permc_spec=how, diag_pivot_thresh=0.0, options=options)
            b = rhs
        else:
            lu = solver._superlu_in_order(scaled[how][:, how].tocsc())
            b = rhs[how]
        ms = cpu_ms(lambda lu=lu, b=b: lu.solve(b))
        fill = lu.L.nnz + lu.U.nnz
        print(f"    {name:34s} fill {fill:9,d}  solve {ms:.3f} ms = {ms / 1e3 / ref:.4f} ref")
    lu, b = shipped._inner.lu, (scale * rhs)[order]
    upper, lower = lu.U.tocsr(), lu.L.tocsr()
    rows = {
        "shipped solve (scaling, permutation)": lambda: shipped.solve(rhs),
        "its SuperLU solve alone": lambda: lu.solve(b),
        "its SuperLU solve, transposed": lambda: lu.solve(b, trans="T"),
        "one product with L and one with U": lambda: (lower @ b, upper @ b),
    }
    for name, function in rows.items():
        ms = cpu_ms(function)
        print(f"    {name:34s} {ms:.3f} ms = {ms / 1e3 / ref:.4f} ref")


def _scaled_effective(problem: stepper.ImpactProblem) -> sp.csc_matrix:
    """D K_eff D on the free dofs, as the shipped factorization factorized it (rebuilt from
    the problem's matrices)."""
    s = problem.scheme
    effective = (
        (1.0 - s.alpha_f) * problem.system.matrix
        + ((1.0 - s.alpha_f) * s.gamma / (s.beta * s.dt)) * problem.damping
        + ((1.0 - s.alpha_m) / (s.beta * s.dt**2)) * problem.body_mass
    )
    reduced = effective.tocsr()[problem.free][:, problem.free]
    d = sp.diags(problem.factorization.scale)
    return (d @ reduced @ d).tocsc()


def product_table(problem: stepper.ImpactProblem) -> None:
    """(c): the per-step sparse products apart and combined."""
    mass, stiffness = problem.body_mass, problem.system.matrix
    complex_mass = mass.astype(np.complex128)
    y, v = np.random.default_rng(1).standard_normal((2, mass.shape[0]))
    both = complex_mass @ (y + 1j * v)
    exact = np.array_equal(both.real, mass @ y) and np.array_equal(both.imag, mass @ v)
    ref = reference()
    print(f"\n(c) per-step sparse products, load {load():.1f}, reference {1e3 * ref:.1f} ms")
    rows = {
        f"M_h y and M_h v ({mass.nnz:,d} entries)": lambda: (mass @ y, mass @ v),
        f"one complex product (bitwise equal: {exact})": lambda: complex_mass @ (y + 1j * v),
        f"K x ({stiffness.nnz:,d} entries)": lambda: stiffness @ y,
    }
    for name, function in rows.items():
        ms = cpu_ms(function, 2000)
        print(f"    {name:44s} {ms:.4f} ms = {ms / 1e3 / ref:.5f} ref")


def compare(old: str, rounds: int) -> None:
    """(a) in fresh processes, alternately on ``old`` and on this tree's src."""
    per = {"old": [], "new": [], "old solve": [], "new solve": []}
    for k in range(rounds):
        for label, src in (("old", old), ("new", str(SRC))):
            env = {**os.environ, "PYTHONPATH": f"{src}{os.pathsep}{Path(__file__).parent}"}
            out = subprocess.run(
                [sys.executable, __file__, "--parts-json"], env=env, capture_output=True, text=True
            )
            row = json.loads(out.stdout.splitlines()[-1])
            per[label].append(row["step"] / row["reference"])
            per[f"{label} solve"].append(row["solve"] / row["reference"])
            print(
                f"round {k} {label}: {row['step']:.3f} ms/step (solve {row['solve']:.3f}), "
                f"reference "
                f"{row['reference']:.1f} ms, load {row['load']:.1f}, "
                f"{row['step'] / row['reference']:.5f} ref/step"
            )
    for part in ("", " solve"):
        ratio = np.median(per[f"new{part}"]) / np.median(per[f"old{part}"])
        print(f"median new / old per step{part} in references: {ratio:.3f}")


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--compare", metavar="SRC", help="an old tree's src to alternate with")
    parser.add_argument("--rounds", type=int, default=3)
    parser.add_argument("--parts-json", action="store_true", help=argparse.SUPPRESS)
    args = parser.parse_args()
    with threadpool_limits(limits=1, user_api="blas"):
        if args.parts_json:
            print(json.dumps(march_parts()))
        elif args.compare:
            compare(args.compare, args.rounds)
        else:
            parts = march_parts()
            ref = parts["reference"]
            print(f"(a) one march, ms per step (load {parts['load']:.1f}, reference {ref:.1f} ms)")
            for key, value in parts.items():
                if key not in ("reference", "load"):
                    print(f"    {key:16s} {value:7.3f} ms = {value / ref:.5f} ref")
            problem, _ = setup()
            factor_table(problem)
            product_table(problem)


if __name__ == "__main__":
    main()
