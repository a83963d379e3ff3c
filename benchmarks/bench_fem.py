"""Benchmarks of the FEM foundation: truncation, solvers, mesh convergence.

Run ``python benchmarks/bench_fem.py`` (``--quick`` skips the ~200k-dof solver case and the
finest meshes). Prints tables; nothing is asserted (wall-clock times depend on the machine).

(a) Half-space truncation: the clamped far boundary at R stiffens the body by O(a/R). Relative
    errors of the Boussinesq centre deflection (uniform pressure on r <= a) and of the flat
    punch force versus R/a, against the closed forms and against R/a = 1e7 on the same near
    field mesh (which isolates the truncation from the discretization error).
(b) Sparse direct solvers on the nu = 0.5 system (symmetric indefinite, zero pressure block):
    SuperLU with scipy's default COLAMD and partial pivoting, SuperLU with MMD_AT_PLUS_A and
    diagonal pivoting (this package's default), MKL PARDISO (if pypardiso is installed):
    factorization time, fill, and the time of 200 right-hand sides at once.
(c) Mesh convergence: closed-form errors (Boussinesq centre and edge, Hertz deflection, flat
    punch) versus the smallest element size and the growth rate, with timings.
"""

from __future__ import annotations

import argparse
import math
import time
from collections.abc import Callable

import numpy as np

from shtaerman.fem.elasticity import ElasticSystem, assemble, pressure_load, solve
from shtaerman.fem.mesh import DEFAULTS, halfspace_mesh
from shtaerman.fem.solver import (
    PardisoFactorization,
    SuperLUFactorization,
    available_backends,
    backward_error,
    factorize,
)

A = 1.0  # load / punch radius = refined radius, m
E = 1.0  # Young's modulus, Pa (all errors are relative)
N_RHS = 200


def _e_star(nu: float) -> float:
    return E / (1.0 - nu**2)


def boussinesq_errors(system: ElasticSystem, factorization=None) -> tuple[float, float]:
    """Relative errors of w(0) = 2 q a / E* and w(a) = 4 q a / (pi E*) for q = 1."""
    load = pressure_load(system, lambda r: np.where(r <= A, 1.0, 0.0))
    solution = solve(system, load, factorization=factorization)
    w, r = -solution.surface_u_z, solution.surface_r
    e_star = _e_star(system.poisson_ratio)
    edge = np.argmin(np.abs(r - A))
    return w[0] / (2 * A / e_star) - 1, w[edge] / (4 * A / (math.pi * e_star)) - 1


def hertz_error(system: ElasticSystem, factorization=None) -> float:
    """Max |w - pi (2a^2 - r^2) / (4 a E*)| over r <= a, over w(0), for p = sqrt(1 - r^2/a^2)."""
    load = pressure_load(system, lambda r: np.sqrt(np.clip(1 - (r / A) ** 2, 0, None)))
    solution = solve(system, load, factorization=factorization)
    inside = solution.surface_r <= A
    r = solution.surface_r[inside]
    exact = math.pi * (2 * A**2 - r**2) / (4 * A * _e_star(system.poisson_ratio))
    return float(np.max(np.abs(-solution.surface_u_z[inside] - exact)) / exact[0])


def punch_error(system: ElasticSystem) -> float:
    """Relative error of the flat punch force P = 2 a E* d."""
    dofs = system.surface_dofs[system.surface_r <= A * (1 + 1e-12)]
    solution = solve(system, prescribed_dofs=dofs, prescribed_values=-1.0)
    return -solution.reactions[dofs].sum() / (2 * A * _e_star(system.poisson_ratio)) - 1


def _timed(function: Callable, *args, **kwargs):
    start = time.perf_counter()
    result = function(*args, **kwargs)
    return result, time.perf_counter() - start


def truncation_table(nu: float = 0.5) -> None:
    """(a) Errors versus the domain radius R/a at the default element size and growth."""
    print(f"\n(a) Truncation error vs domain radius (nu = {nu}, h0 = a/100, growth = 0.15)")
    reference = {}
    rows = []
    for exponent in (7, 2, 3, 4, 5, 6):
        mesh = halfspace_mesh(A, domain_radius=10.0**exponent)
        system = assemble(mesh, E, nu)
        centre, _ = boussinesq_errors(system)
        punch = punch_error(system)
        if exponent == 7:
            reference = {"centre": centre, "punch": punch}
            continue
        rows.append((exponent, system.n_dofs, centre, punch))
    print(
        f"{'R/a':>6} {'dofs':>7} | {'Boussinesq w(0) error':>22} {'vs R=1e7':>10}"
        f" | {'punch force error':>18} {'vs R=1e7':>10}"
    )
    for exponent, dofs, centre, punch in rows:
        print(
            f"{'1e' + str(exponent):>6} {dofs:7d} | {centre:22.2e} "
            f"{(1 + centre) / (1 + reference['centre']) - 1:10.2e} | {punch:18.2e} "
            f"{(1 + punch) / (1 + reference['punch']) - 1:10.2e}"
        )


def _solver_cases(quick: bool) -> list[tuple[str, float, float]]:
    cases = [("~20k", 1 / 100, 0.15), ("~60k", 1 / 300, 0.1)]
    return cases if quick else [*cases, ("~200k", 1 / 800, 0.07)]


def _superlu_row(matrix, rhs, ordering: str, threshold: float) -> tuple[float, float, int, float]:
    factorization, seconds = _timed(
        SuperLUFactorization, matrix, ordering=ordering, pivot_threshold=threshold
    )
    _, solve_seconds = _timed(factorization.solve, rhs)
    return seconds, solve_seconds, factorization.fill, backward_error(matrix, factorization)


def _solver_line(size: str, dofs: object, name: str, *columns: object) -> str:
    widths = (10, 11, 10, 9)
    cells = " ".join(f"{c:>{w}}" for c, w in zip(columns, widths, strict=False))
    return f"{size:>6} {dofs:>7} {name:>32} {cells}"


def solver_table(quick: bool) -> None:
    """(b) Factorization and 200-RHS solve times on the nu = 0.5 system."""
    print(f"\n(b) Sparse solvers, nu = 0.5 system, {N_RHS} right-hand sides (seconds)")
    print(
        _solver_line("size", "dofs", "solver", "factorize", f"{N_RHS} solves", "nnz(LU)", "bwd err")
    )
    variants = [
        ("SuperLU COLAMD, partial pivoting", "COLAMD", 1.0),
        ("SuperLU MMD_AT_PLUS_A, diagonal", "MMD_AT_PLUS_A", 0.0),
    ]
    for label, h0, growth in _solver_cases(quick):
        system = assemble(halfspace_mesh(A, smallest_size=h0, growth=growth), E, 0.5)
        matrix = system.reduced_matrix(system.free_dofs())
        n = matrix.shape[0]
        rhs = np.random.default_rng(0).standard_normal((n, N_RHS))
        for name, ordering, threshold in variants:
            seconds, solve_seconds, fill, error = _superlu_row(matrix, rhs, ordering, threshold)
            timings = (f"{seconds:.2f}", f"{solve_seconds:.2f}", f"{fill:.3e}", f"{error:.0e}")
            print(_solver_line(label, n, name, *timings))
        if "pardiso" in available_backends():
            factorization, seconds = _timed(PardisoFactorization, matrix)
            _, solve_seconds = _timed(factorization.solve, rhs)
            error = backward_error(matrix, factorization)
            timings = (f"{seconds:.2f}", f"{solve_seconds:.2f}", "", f"{error:.0e}")
            print(_solver_line(label, n, "PARDISO symmetric indefinite", *timings))
            del factorization


def convergence_row(nu: float, size_factor: float, growth: float) -> str:
    mesh, t_mesh = _timed(halfspace_mesh, A, smallest_size=size_factor * A, growth=growth)
    system, t_assemble = _timed(assemble, mesh, E, nu)
    free = system.free_dofs()
    factorization, t_factor = _timed(factorize, system.reduced_matrix(free), backend="superlu")
    centre, edge = boussinesq_errors(system, factorization)
    hertz = hertz_error(system, factorization)
    punch = punch_error(system)
    return (
        f"{round(1 / size_factor):>6} {growth:6.2f} {system.n_dofs:7d} |"
        f" {centre:+9.2e} {edge:+9.2e} {hertz:9.2e} {punch:+9.2e} |"
        f" {t_mesh:5.2f} {t_assemble:5.2f} {t_factor:5.2f}"
    )


def convergence_table(quick: bool) -> None:
    """(c) Closed-form errors versus element size and growth, at R = 1e5 a."""
    header = (
        f"{'a/h0':>6} {'growth':>6} {'dofs':>7} | {'w(0)':>9} {'w(a)':>9} {'Hertz':>9} {'punch':>9}"
        f" | {'mesh':>5} {'asm':>5} {'fact':>5}"
    )
    sizes = (25, 50, 100, 200) if quick else (25, 50, 100, 200, 400, 800)
    for nu in (0.3, 0.5):
        print(f"\n(c) Relative errors vs smallest size (growth {DEFAULTS.growth}), nu = {nu}")
        print(header)
        for n in sizes:
            print(convergence_row(nu, 1 / n, DEFAULTS.growth))
        print(f"    ... vs growth (h0 = a/{round(1 / DEFAULTS.size)})")
        for growth in (0.3, 0.25, 0.2, 0.15, 0.1):
            print(convergence_row(nu, DEFAULTS.size, growth))


def default_mesh_timings() -> None:
    """Dofs and timings of the default mesh (refined radius a, nu = 0.5)."""
    mesh, t_mesh = _timed(halfspace_mesh, A)
    system, t_assemble = _timed(assemble, mesh, E, 0.5)
    free = system.free_dofs()
    factorization, t_factor = _timed(factorize, system.reduced_matrix(free))
    rhs = np.zeros((free.size, N_RHS))
    rhs[np.searchsorted(free, system.surface_dofs[:N_RHS]), np.arange(N_RHS)] = -1.0
    _, t_solve = _timed(factorization.solve, rhs)
    print(
        f"\nDefault mesh (h0 = a/{round(1 / DEFAULTS.size)}, growth {DEFAULTS.growth},"
        f" R = 1e5 a), nu = 0.5: {mesh.p.shape[1]} vertices, {mesh.t.shape[1]} triangles,"
        f" {system.n_dofs} dofs; mesh {t_mesh:.2f} s, assembly {t_assemble:.2f} s,"
        f" factorization ({factorization.backend}) {t_factor:.2f} s,"
        f" {N_RHS} unit surface loads {t_solve:.2f} s"
    )


def main(argv: list[str] | None = None) -> None:
    """Print the benchmark tables."""
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--quick", action="store_true", help="skip the largest cases")
    args = parser.parse_args(argv)
    default_mesh_timings()
    truncation_table()
    convergence_table(args.quick)
    solver_table(args.quick)


if __name__ == "__main__":
    main()
