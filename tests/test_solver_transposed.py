"""OrderedLU solves a vector of a symmetric matrix with the transposed factors (fem/solver.py).

The dynamic effective matrix is symmetric, and SuperLU's transposed triangular solves (dot
products, no scattered updates) cost 12 % less CPU there (benchmarks/bench_dynamic_step.py).
A saddle-point matrix of the mixed u-p kind (zero diagonal on the "pressure" rows) tests it.
"""

import numpy as np
import scipy.sparse as sp
import scipy.sparse.linalg as spla

from shtaerman.fem.solver import (
    OrderedLU,
    factorize_scaled,
    nested_dissection,
    solution_backward_error,
)

N = 12  # an N x N grid of "displacement" unknowns, (N - 1)^2 "pressure" unknowns


def _saddle_point() -> tuple[sp.csc_matrix, np.ndarray]:
    """[[A, B^T], [B, 0]]: A a shifted 2-D Laplacian, B cell averages; and the node groups."""
    line = sp.diags([-np.ones(N - 1), 2.0 * np.ones(N), -np.ones(N - 1)], [-1, 0, 1])
    stiffness = sp.kronsum(line, line) + 0.5 * sp.eye(N * N)
    average = sp.diags([np.ones(N - 1), np.ones(N - 1)], [0, 1], shape=(N - 1, N))
    coupling = 0.25 * sp.kron(average, average)
    matrix = sp.bmat([[stiffness, coupling.T], [coupling, None]], format="csc")
    cells = np.arange((N - 1) ** 2)
    groups = np.concatenate([np.arange(N * N), (cells // (N - 1)) * N + cells % (N - 1)])
    return matrix, groups


def _unsymmetric() -> sp.csc_matrix:
    rng = np.random.default_rng(3)
    random = sp.random(40, 40, density=0.1, random_state=rng, format="csc")
    return (random + 10.0 * sp.eye(40)).tocsc()


def test_a_symmetric_matrix_is_solved_as_accurately_both_ways():
    matrix, groups = _saddle_point()
    rhs = np.random.default_rng(0).standard_normal(matrix.shape[0])
    exact = spla.spsolve(matrix, rhs)
    order = nested_dissection(matrix, groups)
    for symmetric in (False, True):
        x = OrderedLU(matrix, order, symmetric=symmetric).solve(rhs)
        # 1e-12: a backward-stable solve of a matrix conditioned ~1e2 (entries O(1))
        assert solution_backward_error(matrix, x, rhs) < 1e-12
        np.testing.assert_allclose(x, exact, rtol=0, atol=1e-12 * np.abs(exact).max())


def test_the_flag_selects_the_transposed_factors():
    # on an unsymmetric matrix, symmetric=True solves A^T x = b: the flag is what decides
    matrix = _unsymmetric()
    rhs = np.arange(1.0, 41.0)
    order = np.arange(40)[::-1]
    plain = OrderedLU(matrix, order).solve(rhs)
    transposed = OrderedLU(matrix, order, symmetric=True).solve(rhs)
    # 1e-12 relative: round-off of a diagonally dominant 40 x 40 solve
    np.testing.assert_allclose(matrix @ plain, rhs, rtol=1e-12)
    np.testing.assert_allclose(matrix.T @ transposed, rhs, rtol=1e-12)
    assert np.abs(plain - transposed).max() > 1e-3 * np.abs(plain).max()


def test_factorize_scaled_solves_vectors_transposed_and_blocks_as_they_are():
    matrix, groups = _saddle_point()
    factorization = factorize_scaled(matrix, groups, 1e-6)
    assert factorization.backend == "superlu-nd"
    assert factorization.backward_error < 1e-12  # the test solve, a vector: transposed
    block = np.random.default_rng(1).standard_normal((matrix.shape[0], 3))
    columns = np.column_stack([factorization.solve(b) for b in block.T])
    # 1e-12 of the largest entry: the transposed and the blocked solves agree to round-off
    np.testing.assert_allclose(
        factorization.solve(block), columns, rtol=0, atol=1e-12 * np.abs(columns).max()
    )
