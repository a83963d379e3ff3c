"""The FEM layer against the independent Hankel-transform reference, on unseen cases.

Run ``python benchmarks/layer_reference.py`` (a few minutes on 2 idle cores); ``--quick`` runs
four of the cases, ``--convergence`` only the reference's own convergence table. Prints tables;
nothing is asserted.

(a) The reference (:class:`shtaerman.theory.layer_reference.LayerReference`) at quadrature
    resolution 0.5, 1 and 2: the force converges to round-off.
(b) Twelve cases (n in 1.5..2, nu in 0.3..0.45, H/a in 0.05..15, both bases) that the tests of
    ``tests/test_layer_fem.py`` do not use: the FE force at the default mesh over the
    reference's, at the depth whose half-space contact radius is a = 10 mm (E = 7.5 MPa,
    A a^n = 5 mm); at H/a = 0.05 also over the thin-layer law of :mod:`shtaerman.theory.layer`.
"""

from __future__ import annotations

import argparse

import numpy as np

from shtaerman.fem.mesh import Geometry
from shtaerman.study.contact.indentation import run_indentation
from shtaerman.theory.indenter import PowerLawIndenter
from shtaerman.theory.layer import half_space_limit, thin_layer_limit
from shtaerman.theory.layer_reference import LayerReference
from shtaerman.theory.materials import Material

RADIUS = 0.01
"""Half-space contact radius a (m) at the depth used."""
CASES = (
    # exponent n, Poisson's ratio, base, H / a
    (1.5, 0.35, "bonded", 0.05),
    (2.0, 0.40, "lubricated", 0.05),
    (1.75, 0.30, "bonded", 0.12),
    (2.0, 0.45, "bonded", 0.3),
    (1.6, 0.42, "lubricated", 0.5),
    (1.8, 0.33, "bonded", 1.0),
    (1.5, 0.45, "lubricated", 2.0),
    (2.0, 0.30, "bonded", 3.0),
    (1.7, 0.38, "lubricated", 5.0),
    (1.9, 0.44, "bonded", 8.0),
    (1.55, 0.31, "bonded", 15.0),
    (2.0, 0.36, "lubricated", 15.0),
)
QUICK = (0, 3, 6, 10)


def case(n: float, nu: float) -> tuple[PowerLawIndenter, Material, float]:
    """Indenter (A a^n = 5 mm at a = 10 mm), body (E = 7.5 MPa) and depth of half-space a."""
    indenter = PowerLawIndenter(5e-3 / RADIUS**n, n)
    body = Material(7.5e6, nu)
    return indenter, body, float(half_space_limit(indenter, body).depth(RADIUS))


def fe_force(
    indenter: PowerLawIndenter, body: Material, depth: float, thickness: float, base: str
) -> tuple[float, int]:
    """FE force (N) and dofs at ``depth`` on the default layer mesh."""
    result = run_indentation(indenter, body, np.array([depth]), geometry=Geometry(thickness, base))
    return result.steps[-1].force, int(result.mesh_stats["dofs"])


def convergence() -> None:
    """(a): the reference force at three quadrature resolutions."""
    print("(a) reference convergence: P(resolution) / P(2) - 1")
    for n, nu, base, h_over_a in (CASES[0], CASES[3], CASES[6], CASES[10]):
        indenter, body, depth = case(n, nu)
        forces = {
            res: LayerReference(indenter, body, h_over_a * RADIUS, base, res).force(depth)
            for res in (0.5, 1.0, 2.0)
        }
        changes = "  ".join(f"{forces[r] / forces[2.0] - 1:+.1e}" for r in (0.5, 1.0))
        print(f"  n {n:g}, nu {nu:g}, {base:10s} H/a {h_over_a:<5g}: {changes}")


def acceptance(indices: tuple[int, ...]) -> None:
    """(b): the FE force over the reference's on the cases ``indices``."""
    print("\n(b) FE (default mesh) / reference, at the depth of half-space radius a = 10 mm")
    print("   n     nu    base        H/a    P_ref/P_hs  a_ref/a   FE/ref-1   dofs   FE/thin-1")
    for index in indices:
        n, nu, base, h_over_a = CASES[index]
        indenter, body, depth = case(n, nu)
        thickness = h_over_a * RADIUS
        reference = LayerReference(indenter, body, thickness, base)
        p_ref, a_ref = reference.force(depth), reference.contact_radius(depth)
        force, dofs = fe_force(indenter, body, depth, thickness, base)
        p_hs = float(half_space_limit(indenter, body).force(depth))
        thin = ""
        if h_over_a <= 0.05:
            law = float(thin_layer_limit(indenter, body, thickness, base).force(depth))
            thin = f"{force / law - 1:+.2e}"
        print(
            f"  {n:<5g} {nu:<5g} {base:10s}  {h_over_a:<5g}  {p_ref / p_hs:10.5f}  "
            f"{a_ref / RADIUS:7.4f}  {force / p_ref - 1:+.2e}  {dofs:6d}   {thin}",
            flush=True,
        )


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--quick", action="store_true")
    parser.add_argument("--convergence", action="store_true")
    args = parser.parse_args()
    convergence()
    if not args.convergence:
        acceptance(QUICK if args.quick else tuple(range(len(CASES))))


if __name__ == "__main__":
    main()
