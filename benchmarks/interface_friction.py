"""Bonded (no-slip) / frictionless indenter: force ratio and p(0)/p_avg at default settings.

For z = 5 r^n on E2 = 7.5 MPa (the paper's rubber) at its default depths (up to the x_c of
0.7 kg at 3 m/s), per nu2: P_bonded / P_frictionless at the deepest depth (nodal sums on both
sides, the same mesh), the bonded p(0)/p_avg, their change under one refinement (refine
sqrt 2) and under a finer load step (step ratio 1.01 against the default 1.02), the
incremental flat-punch identity P (n+1) / (2 E* a d n) against Mossakovskii's chi(nu), and the
cost (factorization + contact, s) of both interfaces. Prints a Markdown table.

    PYTHONPATH=src python benchmarks/interface_friction.py [n ...]
    PYTHONPATH=src python benchmarks/interface_friction.py friction   # Coulomb: P(mu) / P_f
"""

from __future__ import annotations

import math
import sys

from shtaerman.fem.contact.linear import solve_contact
from shtaerman.fem.contact.stick import solve_bonded_contact
from shtaerman.fem.elasticity import assemble
from shtaerman.fem.mesh import MeshSettings
from shtaerman.study.contact.indentation import default_depths
from shtaerman.theory.indenter import PowerLawIndenter
from shtaerman.theory.materials import Material

E2 = 7.5e6
POISSON = (0.0, 0.3, 0.45, 0.5)


def chi(nu: float) -> float:
    """Mossakovskii's bonded / frictionless flat-punch force."""
    return 1.0 if nu == 0.5 else (1 - nu) * math.log(3 - 4 * nu) / (1 - 2 * nu)


def one(indenter: PowerLawIndenter, nu: float, refine: float, ratio: float) -> dict:
    body = Material(E2, nu)
    depths = default_depths(indenter, body)
    mesh = MeshSettings().refined(refine)
    refined = mesh.margin * (depths[-1] / indenter.shape_coefficient) ** (1 / indenter.exponent)
    system = assemble(mesh.build(refined), E2, nu)
    free = solve_contact(system, indenter.profile, depths, refined, aligned=False)
    stuck = solve_bonded_contact(system, indenter.profile, depths, refined, step_ratio=ratio)
    f, b = free.steps[-1], stuck.steps[-1]
    n, e_star = indenter.exponent, E2 / (1 - nu**2)

    def identity(s):
        return s.force * (n + 1) / (2 * e_star * s.contact_radius * s.depth * n)

    return {
        "ratio": b.force / f.force,
        "radius": b.contact_radius / f.contact_radius,
        "p0b": b.central_pressure / b.mean_pressure,
        "p0f": f.central_pressure / f.mean_pressure,
        "chi": identity(b) / identity(f),
        "cost_f": sum(free.timings.values()),
        "cost_b": sum(stuck.timings.values()),
        "dofs": system.n_dofs,
    }


def main(exponents: list[float]) -> None:
    print(
        "| n | nu2 | P_b/P_f | mesh err | step err | a_b/a_f | p0/pavg b (f) | p0 mesh err "
        "| chi FE / Mossakovskii | cost b / f (s) |"
    )
    print("|---|---|---|---|---|---|---|---|---|---|")
    for n in exponents:
        indenter = PowerLawIndenter(5.0, n)
        for nu in POISSON:
            base = one(indenter, nu, 1.0, 1.02)
            fine = one(indenter, nu, math.sqrt(2.0), 1.02)
            step = one(indenter, nu, 1.0, 1.01)
            print(
                f"| {n:g} | {nu:g} | {base['ratio']:.5f} | {fine['ratio'] - base['ratio']:+.1e} "
                f"| {step['ratio'] - base['ratio']:+.1e} | {base['radius']:.4f} "
                f"| {base['p0b']:.4f} ({base['p0f']:.4f}) | {fine['p0b'] - base['p0b']:+.1e} "
                f"| {base['chi']:.4f} / {chi(nu):.4f} "
                f"| {base['cost_b']:.1f} / {base['cost_f']:.1f} ({base['dofs']} dofs) |",
                flush=True,
            )


def friction_table(exponent: float = 1.5, coefficients=(0.1, 0.2, 0.3, 0.5, 1.0)) -> None:
    """P(mu) / P_frictionless at the deepest default depth, default mesh, nu2 0 and 0.3."""
    indenter = PowerLawIndenter(5.0, exponent)
    print(f"\n| nu2 | {' | '.join(f'mu {mu:g}' for mu in coefficients)} | no slip |")
    print("|---|" + "---|" * (len(coefficients) + 1))
    for nu in (0.0, 0.3):
        body = Material(E2, nu)
        depths = default_depths(indenter, body)
        mesh = MeshSettings()
        a_g = (depths[-1] / indenter.shape_coefficient) ** (1 / indenter.exponent)
        refined = mesh.margin * a_g
        system = assemble(mesh.build(refined), E2, nu)
        free = solve_contact(system, indenter.profile, depths, refined, aligned=False)
        cells = []
        for mu in (*coefficients, math.inf):
            curve = solve_bonded_contact(system, indenter.profile, depths, refined, friction=mu)
            cells.append(f"{curve.steps[-1].force / free.steps[-1].force:.5f}")
        print(f"| {nu:g} | {' | '.join(cells)} |", flush=True)


if __name__ == "__main__":
    if sys.argv[1:2] == ["friction"]:
        friction_table()
    else:
        main([float(x) for x in sys.argv[1:]] or [1.5, 2.0])
