"""Finite-strain error estimates: fall-backs and effectivity, independent gmsh levels vs nested.

Run ``PYTHONPATH=src python benchmarks/finite_effectivity.py`` (a few minutes on 2 loaded cores
at the defaults; ``--refine`` and ``--depths`` trade cost for fidelity). Nothing is asserted.

The paper's finite-strain study (fem/finite_strain.toml, nu2 = 0.5, neo-Hookean) with its
``[quick]`` depth ladder, around a study mesh of ``--refine`` (default 0.6):

- OLD: three independent gmsh meshes refined by 1/2, 1/sqrt(2), 1 (ratio sqrt 2);
- NESTED: one gmsh mesh at 1/2 and its two uniform refinements (ratio 2;
  :func:`shtaerman.study.ladder.nested_ladder`);
- REFERENCE: the nested coarse mesh refined uniformly three times (sizes / 8; 4x finer than
  the nested ladder's finest, 5.7x than the old ladder's).

For each ladder: how many of the reported numbers fall back to a two-level difference, and
the effectivity = estimated error / true error of the finest level, the true error
|Q_finest / Q_reference - 1| (the reference's own error is about 1/16 of the nested finest's
at order 2: an effectivity of 1 +- 0.1 cannot be told from 1), for a few headline numbers and
summarized over every number by group and method. The nested ladder is estimated twice on the
same runs: by Richardson alone, and by the rules the study uses on it
(:func:`shtaerman.study.finite.runner.estimate_ladder`: ratios propagated from their factors,
the contact edge's numbers at first order, every per-depth number at least its neighbourhood's
envelope).
"""

from __future__ import annotations

import argparse
import os
import statistics
import time
from dataclasses import replace
from pathlib import Path

from shtaerman.fem.mesh import MeshSettings
from shtaerman.study.finite.accuracy import estimate_study, reported_values
from shtaerman.study.finite.runner import (
    LADDER_RATIOS,
    _run_level,
    estimate_ladder,
    ladder,
    ladder_meshes,
)
from shtaerman.study.schema import load_study
from shtaerman.theory.contact import PowerLawContact
from shtaerman.theory.impact import solve_impact
from shtaerman.theory.materials import RIGID, effective_modulus

HEADLINE = (
    "P_c",
    "x_c",
    "P_c_vs_fem",
    "force_ratio_at_x_c",
    "force_ratio_fem_at_x_c",
    "central_to_mean_at_x_c",
    "radius_ratio_at_x_c",
)
"""Numbers whose effectivity is printed (keys of :attr:`FiniteEstimates.scalars`)."""


def _study(refine: float):
    path = Path(__file__).resolve().parents[1] / "fem" / "finite_strain.toml"
    study = load_study(path)[0]  # nu2 = 0.5
    base = MeshSettings(**{k: v for k, v in study.mesh.__dict__.items()})
    return replace(study, mesh=base.refined(refine / 0.8), ladder=study.quick_ladder)


def _levels(study, depths, exact, meshes):
    return [_run_level(study, depths, mesh, exact, False) for mesh in meshes]


def _effectivities(estimates, finest, reference) -> dict[tuple[str, str], list[float]]:
    """Estimate / true error of every estimated number, by (group, method)."""
    truth, values = reported_values(reference), reported_values(finest)
    groups: dict[tuple[str, str], list[float]] = {}

    def add(group: str, estimate, true: float) -> None:
        eff = estimate.error / true if true > 0 else float("inf")
        groups.setdefault((group, estimate.method), []).append(eff)

    for key, e in estimates.scalars.items():
        if key != "force_ratio_worst":
            group = "vs_fem" if key.endswith("_vs_fem") else key.split("_at_")[0] + "@x_c"
            add(
                group if "_at_" in key or key.endswith("_vs_fem") else "impact",
                e,
                abs(values[key] / truth[key] - 1.0),
            )
    for step, row, ref in zip(estimates.steps, finest.rows(), reference.rows(), strict=True):
        for key, e in step.items():
            add(key, e, abs(row[key] / ref[key] - 1.0))
    return groups


def _report(name, estimates, outcomes, reference) -> None:
    fallbacks, total = estimates.fallbacks()
    dofs = [o.finite.mesh_stats["dofs"] for o in outcomes]
    cpu = sum(o.cpu_seconds for o in outcomes)
    print(f"\n{name}: dofs {dofs}, cpu {cpu:.0f} s; fall-backs {fallbacks} of {total}")
    finest, truth = reported_values(outcomes[-1]), reported_values(reference)
    print(f"  {'number':24s} {'finest':>12s} {'estimate':>10s} {'true':>10s} eff. method")
    for key in HEADLINE:
        e = estimates.scalars[key]
        true = abs(finest[key] / truth[key] - 1.0)
        eff = e.error / true if true > 0 else float("inf")
        print(f"  {key:24s} {finest[key]:12.6g} {e.error:10.2e} {true:10.2e} {eff:6.2f} {e.method}")
    print("  effectivity of every number, by group and method: count, min / median / max, >= 1")
    for (group, method), effs in sorted(_effectivities(estimates, outcomes[-1], reference).items()):
        effs = sorted(effs)
        print(
            f"    {group:18s} {method:11s} {len(effs):3d}  {effs[0]:6.2f} "
            f"{statistics.median(effs):6.2f} {effs[-1]:8.2f}  {sum(e >= 1 for e in effs)}"
        )


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--refine", type=float, default=0.6, help="study mesh (>= 0.6)")
    args = parser.parse_args()
    study = _study(args.refine)
    modulus = effective_modulus(RIGID, study.half_space)
    exact = solve_impact(study.mass, study.velocity, PowerLawContact(study.indenter, modulus))
    depths = ladder(study.indenter, modulus, exact.x_c, study.ladder)
    print(f"load: {os.getloadavg()}; {depths.size} depths, study mesh refine {args.refine}")
    start = time.process_time()
    coarse = ladder_meshes(study.mesh, True)[1][0]
    reference = _run_level(study, depths, replace(coarse, nested=3), exact, False)
    dofs = reference.finite.mesh_stats["dofs"]
    print(f"reference: {dofs} dofs, cpu {reference.cpu_seconds:.0f} s")
    for nested in (False, True):
        factors, meshes = ladder_meshes(study.mesh, nested)
        outcomes = _levels(study, depths, exact, meshes)
        ratio = LADDER_RATIOS[nested]
        plain = estimate_study(outcomes, factors, ratio)
        _report("NESTED, Richardson only" if nested else "OLD", plain, outcomes, reference)
        if nested:  # what the study reports: propagated ratios, the edge's first order
            rules = estimate_ladder(outcomes, factors, nested)
            _report("NESTED, the nested ladder's rules", rules, outcomes, reference)
    print(f"\ntotal cpu {time.process_time() - start:.0f} s; load {os.getloadavg()}")


if __name__ == "__main__":
    main()
