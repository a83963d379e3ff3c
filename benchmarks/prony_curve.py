"""The contact curve of the paper's viscoelastic rubber pressed at a constant rate.

The paper's indenter (A = 5 m^-1/2, n = 3/2, rigid) pressed into the half-space E2 = 7.5 MPa
(instantaneous), nu2 = 0.5, one Prony term g = 0.5 at tau = 2 ms, at 1 m/s and 0.01 m/s, to the
eight default depths (up to the x_c of 0.7 kg at 3 m/s). For each rate: the FEM curve on the
default mesh ladder (its error estimate and the true error against Lee and Radok's closed
form), the relaxation 1 - R_q at the deepest depth, and the elastic curve's true error on the
same mesh (nodal sums) beside it; then the time-step changes at 100, 200 (default) and 400
steps.

Run: python benchmarks/prony_curve.py [--refine R]
"""

from __future__ import annotations

import argparse
import time

import numpy as np

import shtaerman as sh
from shtaerman.fem.contact.rate import press_at_rate
from shtaerman.fem.elasticity import assemble
from shtaerman.fem.mesh import MeshSettings
from shtaerman.study.contact.indentation import refined_radius
from shtaerman.theory.contact import PowerLawContact
from shtaerman.theory.viscoelastic import PronySeries

PAPER = sh.PowerLawIndenter(shape_coefficient=5.0, exponent=1.5)
BODY = sh.Material(7.5e6, 0.5)
SERIES = "0.5:2e-3"


def _worst(forces: np.ndarray, exact: np.ndarray) -> float:
    return float(np.max(np.abs(forces / exact - 1.0)))


def _march(depths: np.ndarray, rate: float, refine: float, steps: int) -> np.ndarray:
    """The FEM forces (N, nodal sums) of the curve at ``steps`` time steps."""
    mesh = MeshSettings().refined(refine)
    radius = refined_radius(PAPER, depths, mesh)
    system = assemble(mesh.build(radius), BODY.youngs_modulus, BODY.poisson_ratio)
    series = PronySeries.parse(SERIES)
    curve = press_at_rate(system, PAPER.profile, depths, radius, series, rate, steps=steps,
                          aligned=False)  # fmt: skip
    return np.array([step.force for step in curve.steps])


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__)
    parser.add_argument("--refine", type=float, default=1.0)
    refine = parser.parse_args().refine
    elastic = sh.contact(PAPER, BODY, refine=refine, estimate=False)
    depths = elastic.depth
    nodal = np.array([step["force_nodal_sum"] for step in elastic.steps])
    glassy = PowerLawContact(PAPER, 7.5e6 / 0.75).force(depths)
    print(f"elastic, refine {refine:g}: worst force error {_worst(nodal, glassy):.2e} (nodal sums)")
    for rate in (1.0, 0.01):
        start = time.perf_counter()
        result = sh.contact(PAPER, BODY, prony=SERIES, rate=rate, refine=refine)
        seconds = time.perf_counter() - start
        exact = np.array([step["force_analytic"] for step in result.steps])
        print(
            f"rate {rate:g} m/s: P_FEM/P_LR - 1 = "
            + " ".join(f"{v:+.1e}" for v in result.force / exact - 1.0)
            + f"; relaxation 1 - R_q at the deepest {1.0 - exact[-1] / glassy[-1]:.3f}, at the "
            f"first {1.0 - exact[0] / glassy[0]:.3f}; estimate {result.error_estimate['force']:.1e}"
            f" (true {result.true_error['force']:.1e}); beta {result.true_error['beta']:.1e}; "
            f"{seconds:.1f} s ({result.mesh['dofs']} dofs on the finest level)"
        )
        curves = {steps: _march(depths, rate, refine, steps) for steps in (100, 200, 400)}
        print(
            "  time steps 100 -> 200 -> 400: force changes "
            f"{_worst(curves[100], curves[200]):.1e}, {_worst(curves[200], curves[400]):.1e}"
        )


if __name__ == "__main__":
    main()
