"""The FEM layer on a rigid base against its analytic limits (shtaerman.theory.layer).

Run ``python benchmarks/layer_limits.py`` (a few minutes on 2 idle cores) or with ``--quick``
(fewer thicknesses). Prints tables; nothing is asserted. A rigid z = A r^n (A = 5, n = 3/2 unless
``--exponent``) is pressed to one depth, whose half-space contact radius is a = 10 mm, into a
layer of thickness H (default mesh, the force of
:func:`shtaerman.fem.contact.linear.aligned_force`):

(a) nu = 0.3, bonded: P_FE / P_oedometric (thin limit) and P_FE / P_Shtaerman (thick limit);
(b) nu = 0.5, bonded: P_FE / P_thin-film (thin limit) and P_FE / P_Shtaerman;
(c) nu = 0.3 and 0.5, lubricated: P_FE / P_sliding (the foundation k = E*/H) and
    P_FE / P_Shtaerman;
(d) the truncation of the lateral extent: the force change when LAYER_EXTENT doubles.

The approach rates are least-squares fits of |ratio - 1| = C (H/a)^p over the three thinnest
(thin limit) or thickest (thick limit) layers of a table.
"""

from __future__ import annotations

import argparse

import numpy as np

import shtaerman.fem.mesh as fem_mesh
from shtaerman.fem.mesh import Geometry
from shtaerman.study.contact.indentation import run_indentation
from shtaerman.theory.indenter import PowerLawIndenter
from shtaerman.theory.layer import half_space_limit, thin_layer_limit
from shtaerman.theory.materials import Material

RADIUS = 0.01
"""Half-space contact radius a (m) at the depth used."""
THIN = (0.05, 0.1, 0.2, 0.5)
THICK = (1.0, 1.5, 3.0, 7.5, 15.0, 30.0, 60.0)


def layer_force(
    indenter: PowerLawIndenter, body: Material, depth: float, thickness: float, base: str
) -> tuple[float, float]:
    """FEM force (N) and contact radius (m) at ``depth`` on the layer, default mesh."""
    result = run_indentation(indenter, body, np.array([depth]), geometry=Geometry(thickness, base))
    step = result.steps[-1]
    return step.force, step.contact_radius


def rate(ratios: list[float], h_over_a: list[float]) -> tuple[float, float]:
    """C, p of |ratio - 1| = C (H/a)^p (least squares in logs)."""
    slope, intercept = np.polyfit(np.log(h_over_a), np.log(np.abs(np.array(ratios) - 1.0)), 1)
    return float(np.exp(intercept)), float(slope)


def table(indenter: PowerLawIndenter, nu: float, base: str, ratios: tuple[float, ...]) -> None:
    """Print H/a, P/P_half-space, FE radius/a and P/P_thin-limit for each H/a in ``ratios``."""
    body = Material(7.5e6, nu)
    half = half_space_limit(indenter, body)
    depth = float(half.depth(RADIUS))
    thin_name = ("thin-film" if nu == 0.5 else "oedometric") if base == "bonded" else "sliding"
    print(f"\nnu = {nu}, {base} base, n = {indenter.exponent:g}, depth {depth:.4e} m, a = {RADIUS}")
    print(f"  H/a      P/P_hs    a_FE/a   P/P_{thin_name}")
    rows = []
    for h_over_a in ratios:
        force, radius = layer_force(indenter, body, depth, h_over_a * RADIUS, base)
        limit = thin_layer_limit(indenter, body, h_over_a * RADIUS, base)
        thin = force / float(limit.force(depth))
        rows.append((h_over_a, force / float(half.force(depth)), radius / RADIUS, thin))
        print(f"  {h_over_a:<7g}  {rows[-1][1]:.5f}  {rows[-1][2]:.5f}  {thin:.5f}", flush=True)
    thick = [row for row in rows if row[0] >= 7.5]
    if len(thick) >= 3:
        c, p = rate([row[1] for row in thick[-3:]], [row[0] for row in thick[-3:]])
        print(f"  thick limit: P/P_hs - 1 = {c:.3g} (H/a)^{p:.3f}")
    if len(rows) >= 3 and rows[2][0] < 1:
        c, p = rate([row[3] for row in rows[:3]], [row[0] for row in rows[:3]])
        print(f"  thin limit: |P/P_{thin_name} - 1| = {c:.3g} (H/a)^{p:.3f}")


def truncation(indenter: PowerLawIndenter) -> None:
    """Force change when the lateral extent doubles, per base, nu and H/a."""
    print(f"\ntruncation: force(LAYER_EXTENT = {fem_mesh.LAYER_EXTENT:g}) / force(x 2) - 1")
    default = fem_mesh.LAYER_EXTENT
    for nu, base, h_over_a in (
        (0.3, "lubricated", 0.05),
        (0.5, "bonded", 0.05),
        (0.3, "bonded", 1.5),
        (0.5, "lubricated", 15.0),
    ):
        body = Material(7.5e6, nu)
        depth = float(half_space_limit(indenter, body).depth(RADIUS))
        forces = []
        for extent in (default, 2 * default):
            fem_mesh.LAYER_EXTENT = extent
            forces.append(layer_force(indenter, body, depth, h_over_a * RADIUS, base)[0])
        fem_mesh.LAYER_EXTENT = default
        print(f"  nu {nu}, {base}, H/a {h_over_a:g}: {forces[0] / forces[1] - 1:+.2e}")


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--quick", action="store_true")
    parser.add_argument("--exponent", type=float, default=1.5)
    args = parser.parse_args()
    indenter = PowerLawIndenter(5.0, args.exponent)
    thin = THIN[:3] if args.quick else THIN
    thick = (1.5, 15.0) if args.quick else THICK
    table(indenter, 0.3, "bonded", (*thin, *thick))
    table(indenter, 0.5, "bonded", (*thin, *thick))
    table(indenter, 0.3, "lubricated", (*thin, *thick))
    table(indenter, 0.5, "lubricated", (*thin, *thick))
    if not args.quick:
        truncation(indenter)


if __name__ == "__main__":
    main()
