"""Backward error of the mixed u-p factorization against E / L (Pa/m), before and after the
unit-free test vector of :func:`shtaerman.fem.solver.backward_error`.

Run ``python benchmarks/bench_units.py`` (about a minute on 2 idle cores). The paper's striker
shape (n = 1.5, A = 5) on the quick study mesh at nu = 0.5, E/L from 1e-9 to 1e12 Pa/m by the
modulus E at L ~ 7 mm and by the contact size L (depths 1e-9 .. 1e3 m) at E = 7.5 MPa. Per
case: the componentwise backward error of a test solve with x = z (SI units: the old check,
which refused E/L below ~1e-5 Pa/m as "singular") and with x = D z (D the symmetric scaling:
the new check), and the relative change of the FE force, contact radius and central pressure
against E = 7.5 MPa, depth 1 mm (the same relative mesh: 0 up to round-off). Prints a table;
nothing is asserted.
"""

from __future__ import annotations

import numpy as np

from shtaerman.fem.contact.linear import factorize_stiffness
from shtaerman.fem.elasticity import assemble
from shtaerman.fem.mesh import HALF_SPACE
from shtaerman.fem.solver import backward_error
from shtaerman.study.contact.indentation import refined_radius, run_indentation
from shtaerman.study.contact.loader import QUICK_MESH
from shtaerman.theory.indenter import PowerLawIndenter
from shtaerman.theory.materials import Material

INDENTER = PowerLawIndenter(5.0, 1.5)
KEYS = ("force", "contact_radius", "central_pressure")


def case(modulus: float, depth: float) -> tuple[float, float, float, dict[str, float]]:
    """E/L, the backward errors with x = z and x = D z, and the FE's relative errors."""
    depths = np.array([depth, 2.0 * depth])
    radius = refined_radius(INDENTER, depths, QUICK_MESH, HALF_SPACE)
    system = assemble(QUICK_MESH.build(radius, HALF_SPACE), modulus, 0.5)
    free = system.free_dofs()
    factorization = factorize_stiffness(system, free, radius)
    matrix = system.reduced_matrix(free)
    old = backward_error(matrix, factorization)
    new = backward_error(matrix, factorization, getattr(factorization, "scale", None))
    if hasattr(factorization, "order"):  # an OrderedLU keeps d in elimination order
        scale = np.empty_like(factorization.scale)
        scale[factorization.order] = factorization.scale
        new = backward_error(matrix, factorization, scale)
    errors = run_indentation(INDENTER, Material(modulus, 0.5), depths, QUICK_MESH).errors()
    return modulus / radius, old, new, {key: errors[key] for key in KEYS}


def main() -> None:
    reference = case(7.5e6, 1e-3)[3]
    print(f"{'E Pa':>9} {'depth m':>9} {'E/L Pa/m':>9} {'x = z':>9} {'x = D z':>9}  FE change")
    cases = [(10.0**k, 1e-3) for k in range(-11, 11, 2)]
    cases += [(7.5e6, 10.0**k) for k in range(-9, 4, 2)]
    for modulus, depth in cases:
        ratio, old, new, errors = case(modulus, depth)
        change = max(abs(errors[k] - reference[k]) for k in KEYS)  # relative errors
        print(f"{modulus:9.2g} {depth:9.2g} {ratio:9.2g} {old:9.2g} {new:9.2g}  {change:.2g}")


if __name__ == "__main__":
    main()
