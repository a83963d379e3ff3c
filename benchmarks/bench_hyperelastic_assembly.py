"""The cost of one Newton iteration's assembly of the finite-strain system, against one sparse
factorization of the same system's tangent, measured in the same run.

A cylinder 0 <= R <= 1, -1 <= Z <= 0 (m) on a tensor mesh, strained by a smooth displacement
(about 10 % compression, some shear and hoop stretch) with a nonzero pressure, for each rubber
model of tests/test_support_matrix.py RUBBER_MODELS. Per model it prints the CPU milliseconds
of the kinematics with the stress (``state``), of the material tangent D alone (``tangent``),
of the residual, and of the tangent's sparse data (``assembly``: element matrices and the
scatter), each also as a ratio to one LU factorization of the tangent (``factorize``, the
lower displacement ``u_z`` held so that it is nonsingular). The load is printed beside: CPU
times on a shared machine are indicative, the ratios less so than on an idle one.

Run: python benchmarks/bench_hyperelastic_assembly.py [--cells N] [--repeat K]
"""

import argparse
import os
import sys
import time
from pathlib import Path

import numpy as np
from skfem import MeshTri

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "tests"))

from test_support_matrix import RUBBER_MODELS

from shtaerman.fem.hyperelastic import assemble_hyperelastic
from shtaerman.fem.rubber import rubber_model
from shtaerman.fem.solver import factorize


def cpu_ms(function, repeat: int) -> float:
    """Least CPU milliseconds of ``repeat`` calls of ``function`` (the least is the least
    disturbed by the other processes of a shared machine)."""
    best = np.inf
    for _ in range(repeat):
        start = time.process_time()
        function()
        best = min(best, time.process_time() - start)
    return 1e3 * best


def strained(system) -> np.ndarray:
    """x = [u, p] of a smooth strained state (m, Pa)."""
    basis = system.displacement_basis

    def displacement(x):
        r, z = x
        return np.array([0.04 * r * (1.0 + z) + 0.02 * z * r, -0.1 * (z + 1.0) + 0.03 * r**2])

    x = np.zeros(system.n_dofs)
    x[: system.n_displacement] = basis.project(displacement)
    x[system.n_displacement :] = 1e5 * (1.0 + np.arange(system.pressure_basis.N) % 7 / 7.0)
    return x


def held(system) -> np.ndarray:
    """The free dofs: all but u_z on the bottom Z = -1."""
    basis = system.displacement_basis
    bottom = basis.get_dofs(lambda x: np.isclose(x[1], -1.0)).nodal["u^2"]
    return np.setdiff1d(np.arange(system.n_dofs), bottom)


def costs(system, repeat: int) -> str:
    """The factorization's CPU ms, then each part's CPU ms and its ratio to it."""
    x = strained(system)
    free = held(system)
    matrix = system.tangent(x)[free][:, free].tocsc()
    reference = cpu_ms(lambda: factorize(matrix), repeat)
    parts = (
        lambda: system.state(x),
        lambda: system.state(x).tangent,
        lambda: system.residual(x),
        lambda: system.tangent_data(x),
    )
    row = f"{reference:7.1f}ms"
    for function in parts:
        ms = cpu_ms(function, repeat)
        row += f" {ms:7.1f}ms {ms / reference:5.2f}x"
    return row


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--cells", type=int, default=60, help="tensor cells per side")
    parser.add_argument("--repeat", type=int, default=5)
    args = parser.parse_args()
    ticks = np.linspace(0.0, 1.0, args.cells + 1)
    mesh = MeshTri.init_tensor(ticks, ticks - 1.0)
    print(f"load at start {os.getloadavg()[0]:.2f} on {os.cpu_count()} cores")
    header = f"{'model':14s} {'dofs':>6s} {'factorize':>9s}"
    print(header + "".join(f" {k:>16s}" for k in ("state", "tangent", "residual", "assembly")))
    for name, shape in RUBBER_MODELS.items():
        system = assemble_hyperelastic(mesh, rubber_model(name, **shape).material(7.5e6, 0.5))
        row = f"{name:14s} {system.n_dofs:6d} " + costs(system, args.repeat)
        print(row, flush=True)
    print(f"load at end {os.getloadavg()[0]:.2f}")


if __name__ == "__main__":
    main()
