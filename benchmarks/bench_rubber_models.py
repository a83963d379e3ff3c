"""Rubber models beyond neo-Hookean: the Treloar fit, the force at x_c per model, the cost.

Run ``PYTHONPATH=src python benchmarks/bench_rubber_models.py`` (about 10 minutes on 2 loaded
cores; ``--sections a`` for the fit alone). Nothing is asserted; wall-clock times depend on the
machine and its load (printed beside them).

(a) TRELOAR FIT. Mooney-Rivlin and Yeoh constants by linear least squares (relative residuals)
    on Treloar's (1944) incompressible uniaxial and equibiaxial nominal stresses, over three
    stretch ranges; the dimensionless shapes r = C01/(C10 + C01) and c2, c3 = C20/C10, C30/C10
    that fem/extended/rubber_models.toml uses.
(b) THE FORCE AT THE PAPER'S x_c PER MODEL. A = 5 m^-1/2, n = 1.5, E2 = 7.5 MPa (every model
    with this small-strain modulus), the default depths up to the linear x_c = 8.52 mm, default
    mesh (FINITE_MESH, one mesh): P / P_Shtaerman, P / P_neo-Hookean, a / a_lin, p(0)/p_avg at
    x_c; nu2 = 0.5 for each model, nu2 = 0.3 for each volumetric energy.
(c) COST. Wall time of each run of (b) against the neo-Hookean one, and the CPU time of one
    assembly (state, residual, tangent) at the x_c state per model.
"""

from __future__ import annotations

import argparse
import os
import time

import numpy as np

from shtaerman.fem.mesh import FINITE_MESH
from shtaerman.fem.rubber import RubberModel, rubber_model
from shtaerman.study.contact.indentation import default_depths
from shtaerman.study.finite.indentation import run_finite_study
from shtaerman.theory.indenter import PowerLawIndenter
from shtaerman.theory.materials import Material

KGF_CM2 = 0.0980665
"""MPa per kgf/cm^2 (Treloar's unit)."""
UNIAXIAL = np.array(
    [
        [1.020, 0.26], [1.125, 1.37], [1.240, 2.30], [1.390, 3.23], [1.585, 4.16], [1.900, 5.10],
        [2.180, 6.00], [2.420, 6.90], [3.020, 8.80], [3.570, 10.7], [4.030, 12.5], [4.760, 16.2],
        [5.360, 19.9],
    ]
).T  # fmt: skip
"""Treloar (1944), Trans. Faraday Soc. 40, 59: stretch, nominal stress in kgf/cm^2."""
EQUIBIAXIAL = np.array(
    [
        [1.03, 0.95], [1.07, 1.60], [1.12, 2.42], [1.14, 2.62], [1.20, 3.32], [1.31, 4.43],
        [1.42, 5.18], [1.68, 6.60], [1.94, 7.78], [2.49, 9.79], [3.03, 12.6],
    ]
).T  # fmt: skip
RANGES = ((2.42, 1.94), (3.02, 2.49), (5.36, 3.03))
"""(largest uniaxial, largest equibiaxial stretch) of each fit; the first is the study's."""


def _design(uniaxial: np.ndarray, equibiaxial: np.ndarray) -> np.ndarray:
    """Columns: the nominal stress per unit C10, C01, C20, C30 (incompressible)."""
    rows = []
    for stretch in uniaxial:
        x, f = stretch**2 + 2 / stretch - 3, 2 * (stretch - stretch**-2)
        rows.append([f, f / stretch, 2 * f * x, 3 * f * x**2])
    for stretch in equibiaxial:
        x, f = 2 * stretch**2 + stretch**-4 - 3, 2 * (stretch - stretch**-5)
        rows.append([f, f * stretch**2, 2 * f * x, 3 * f * x**2])
    return np.array(rows)


def treloar_fit() -> None:
    print("(a) Treloar (1944) fit, uniaxial + equibiaxial, relative residuals (MPa)")
    for top_u, top_b in RANGES:
        u, b = UNIAXIAL[:, UNIAXIAL[0] <= top_u], EQUIBIAXIAL[:, EQUIBIAXIAL[0] <= top_b]
        design, stress = _design(u[0], b[0]), np.concatenate([u[1], b[1]]) * KGF_CM2
        weight = 1 / stress
        out = {}
        for name, columns in (("NH", [0]), ("MR", [0, 1]), ("Yeoh", [0, 2, 3])):
            fit = np.linalg.lstsq(design[:, columns] * weight[:, None], stress * weight)[0]
            rms = np.sqrt(np.mean(((design[:, columns] @ fit - stress) * weight) ** 2))
            out[name] = (fit, rms)
        (nh, nh_rms), (mr, mr_rms), (ye, ye_rms) = out["NH"], out["MR"], out["Yeoh"]
        print(
            f"  stretch <= {top_u} / {top_b}: NH C10 {nh[0]:.4f} (rms {nh_rms:.3f});"
            f" MR C10 {mr[0]:.4f} C01 {mr[1]:.4f} r {mr[1] / mr.sum():.3f} (rms {mr_rms:.3f});"
            f" Yeoh C10 {ye[0]:.4f} C20 {ye[1]:.5f} C30 {ye[2]:.6f} c2 {ye[1] / ye[0]:.4f}"
            f" c3 {ye[2] / ye[0]:.5f} (rms {ye_rms:.3f})"
        )


CASES = (
    (0.5, RubberModel()),
    (0.5, rubber_model("mooney-rivlin", 0.085)),
    (0.5, rubber_model("mooney-rivlin", 0.3)),
    (0.5, rubber_model("yeoh", yeoh=(-0.101, 0.0127))),
    (0.5, rubber_model("gent", gent_limit=97.2)),
    (0.3, RubberModel()),
    (0.3, rubber_model("neo-hookean", volumetric="logarithmic")),
    (0.3, rubber_model("yeoh", yeoh=(-0.101, 0.0127), volumetric="logarithmic")),
)
"""(nu2, model): Treloar's fits, a strong I2 term, Gent's Jm = 97.2, both volumetric energies."""


def _assembly_seconds(result) -> float:
    system, x = result.curve.system, result.steps[-1].solution
    start = time.process_time()
    for _ in range(3):
        state = system.state(x)
        system.residual(x, state)
        system.tangent_data(x, state)
    return (time.process_time() - start) / 3


def forces_at_x_c() -> None:
    indenter = PowerLawIndenter(5.0, 1.5)
    print(f"(b, c) the force at the linear x_c per model, default mesh; load {os.getloadavg()}")
    reference: dict[float, tuple[float, float]] = {}
    for nu, model in CASES:
        body = Material(7.5e6, nu)
        depths = default_depths(indenter, body)
        start = time.perf_counter()
        result = run_finite_study(indenter, body, depths, FINITE_MESH, model)
        seconds = time.perf_counter() - start
        step = result.steps[-1]
        reference.setdefault(nu, (step.force, seconds))
        force, base = reference[nu]
        print(
            f"  nu2 {nu}: {model.to_dict()}: x_c {step.depth * 1e3:.3f} mm, P/P_lin "
            f"{step.force / step.force_linear:.4f}, P/P_NH {step.force / force:.4f}, a/a_lin "
            f"{step.contact_radius / step.contact_radius_linear:.4f}, p(0)/p_lin "
            f"{step.central_pressure / step.central_pressure_linear:.4f}, p0/pavg "
            f"{step.central_pressure / step.mean_pressure:.3f}; {seconds:.1f} s "
            f"({seconds / base:.2f} x NH), assembly {_assembly_seconds(result):.3f} s CPU"
        )


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--sections", default="ab", help="a: the fit; b: forces and cost")
    sections = parser.parse_args().sections
    if "a" in sections:
        treloar_fit()
    if "b" in sections:
        forces_at_x_c()


if __name__ == "__main__":
    main()
