"""The paper's contact curve toward 1e-6: true error, estimate and cost per mesh level.

The paper's case (A = 5, n = 1.5, E2 = 7.5 MPa, nu2 = 0.5, the default eight depths) on the
mesh family of ``contact --accuracy 1e-6`` (``ACCURACY_MESH`` graded by ``ACCURACY_GRADING``
of :mod:`shtaerman.study.contact.accuracy`, with ``--default-family`` the default mesh, at the
domain that the far-field rule of ``run_to_accuracy`` takes for 1e-6, 1e7 refined radii) at
refine sqrt(2)^k. Per level: dofs; the true relative error of the force (worst depth,
against Shtaerman), of beta and of the fitted exponent; from the level and the two before it,
their estimates (:func:`~shtaerman.study.contact.accuracy.estimate_errors`; force and beta
are what ``--accuracy`` stops on) and the effectivity estimate / true; the level's CPU
seconds (``time.process_time``, all threads) and their ratio to one SuperLU factorization of
a fixed 2-D Laplacian timed in the same run (``verify_cost.reference``); the peak RSS of the
process so far; the one-minute load average. The machine is shared, so compare CPU seconds
and ratios, not wall time. ``--accuracy`` also runs ``run_to_accuracy(1e-6)`` at the default
caps (or ``--max-dofs``) and prints what it reached, or its refusal. Asserts nothing.

Run: python benchmarks/accuracy_1e6.py [--levels K0,K1,...] [--default-family] [--accuracy]
[--max-dofs N]
"""

from __future__ import annotations

import argparse
import resource
import time
from dataclasses import replace

from verify_cost import load, reference

from shtaerman.fem.mesh import MeshSettings
from shtaerman.study.contact.accuracy import (
    AccuracyResult,
    LadderLevel,
    accuracy_mesh,
    estimate_errors,
    run_to_accuracy,
)
from shtaerman.study.contact.indentation import default_depths, run_indentation
from shtaerman.study.ladder import LADDER_RATIO
from shtaerman.theory.indenter import PowerLawIndenter
from shtaerman.theory.materials import Material
from shtaerman.validation import InputError

INDENTER, HALF_SPACE = PowerLawIndenter(5.0, 1.5), Material(7.5e6, 0.5)
DOMAIN = 1e7
"""Domain / refined radius that ``--accuracy 1e-6`` takes (the largest, MAX_DOMAIN)."""
KEYS = ("force", "beta", "exponent")


def rss_gb() -> float:
    """Peak resident set size of this process so far, GB."""
    return resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1e6


def ladder_table(levels: list[int], unit: float, graded: bool = True) -> None:
    """One line per level: dofs, true errors, estimates and effectivity, cost."""
    depths = default_depths(INDENTER, HALF_SPACE)
    mesh = replace(MeshSettings(), domain=DOMAIN, max_dofs=5e6)
    mesh = accuracy_mesh(mesh, INDENTER, depths, 1e-6) if graded else mesh
    heads = " | ".join(f"{key[:5] + ' true':>10} {'est':>8} {'eff':>5}" for key in KEYS)
    print(
        f"{'refine':>6} {'dofs':>7} | {heads} | {'CPU s':>6} {'ratio':>6} {'RSS GB':>6} {'load':>5}"
    )
    done: list[LadderLevel] = []
    for k in levels:
        refine = LADDER_RATIO**k
        start = time.process_time()
        result = run_indentation(INDENTER, HALF_SPACE, depths, mesh.refined(refine))
        seconds = time.process_time() - start
        done.append(LadderLevel(refine, result))
        true = result.errors()
        cells = []
        if len(done) >= 3:
            ladder = AccuracyResult(tuple(done[-3:]), {})
            ladder = replace(ladder, estimates=estimate_errors(ladder.levels))
            effectivity = ladder.effectivity()
            for key in KEYS:
                estimate = ladder.estimates[key].error
                cells.append(f"{true[key]:10.3e} {estimate:8.2e} {effectivity[key]:5.2f}")
        else:
            cells = [f"{true[key]:10.3e} {'-':>8} {'-':>5}" for key in KEYS]
        print(
            f"{refine:6.3g} {result.mesh_stats['dofs']:7d} | {' | '.join(cells)} | "
            f"{seconds:6.1f} {seconds / unit:6.0f} {rss_gb():6.2f} {load():5.1f}",
            flush=True,
        )


def accuracy_run(max_dofs: float | None, unit: float) -> None:
    """``run_to_accuracy(1e-6)`` on the paper's case: what it reached, or why it refused."""
    start = time.process_time()
    try:
        result = run_to_accuracy(INDENTER, HALF_SPACE, 1e-6, max_dofs=max_dofs, max_time=1e4)
    except InputError as refusal:
        seconds = time.process_time() - start
        print(f"--accuracy 1e-6: refused after {seconds:.1f} CPU s: {refusal}")
        return
    seconds = time.process_time() - start
    true, estimate = result.finest.errors(), result.error_estimate()
    print(
        f"--accuracy 1e-6: dofs {[level.dofs for level in result.levels]}, "
        + ", ".join(
            f"{key} true {true[key]:.3e} est {estimate[key]:.2e} eff "
            f"{estimate[key] / true[key]:.2f}"
            for key in KEYS
        )
        + f"; {seconds:.1f} CPU s = {seconds / unit:.0f} x ref, RSS {rss_gb():.2f} GB, "
        f"load {load():.1f}"
    )


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--levels", default="-2,-1,0,1,2", help="k of refine sqrt(2)^k")
    parser.add_argument("--default-family", action="store_true", help="the default mesh's")
    parser.add_argument("--accuracy", action="store_true", help="run --accuracy 1e-6 too")
    parser.add_argument("--max-dofs", type=float, default=None, help="its cap (default: mesh's)")
    args = parser.parse_args()
    unit = reference()
    print(
        f"reference: one SuperLU factorization, 62,500 unknowns: {unit:.3f} CPU s, load "
        f"{load():.1f}"
    )
    ladder_table([int(k) for k in args.levels.split(",")], unit, not args.default_family)
    if args.accuracy:
        accuracy_run(args.max_dofs, unit)
    print(f"reference again: {reference():.3f} CPU s, load {load():.1f}")


if __name__ == "__main__":
    main()
