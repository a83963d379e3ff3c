"""The fixed sparsity pattern: every gather against scipy's own sparse operations."""

from __future__ import annotations

import numpy as np
import pytest
import scipy.sparse as sp

from shtaerman.fem.solver import pattern_of


@pytest.fixture(scope="module")
def triplets():
    """Random 'element' entries of a 30 x 30 matrix: 40 elements of 4 dofs, every pair."""
    rng = np.random.default_rng(3)
    dofs = np.array([rng.choice(30, 4, replace=False) for _ in range(40)])
    rows = np.repeat(dofs[:, :, None], 4, axis=2)
    cols = np.repeat(dofs[:, None, :], 4, axis=1)
    dofs_seen = np.unique(dofs)
    extra = np.setdiff1d(np.arange(30), dofs_seen)  # isolated dofs: a diagonal entry each
    rows = np.concatenate([rows.ravel(), extra])
    cols = np.concatenate([cols.ravel(), extra])
    return rows, cols, rng.standard_normal(rows.size)


def _reference(rows, cols, values):
    return sp.coo_matrix((values, (rows, cols)), shape=(30, 30)).tocsc()


def test_assembly_is_scipys_sum_of_duplicates(triplets):
    rows, cols, values = triplets
    pattern, where = pattern_of(rows, cols, 30)
    data = np.bincount(where, weights=values, minlength=pattern.nnz)
    reference = _reference(rows, cols, values)
    # the same sums in another order: round-off only
    assert abs(pattern.matrix(data) - reference).max() <= 1e-14 * abs(reference).max()
    assert pattern.nnz == reference.nnz and pattern.indices.dtype == np.int32


def test_gathers(triplets):
    rows, cols, values = triplets
    pattern, where = pattern_of(rows, cols, 30)
    data = np.bincount(where, weights=values, minlength=pattern.nnz)
    matrix = pattern.matrix(data).toarray()
    assert np.array_equal(pattern.matrix(data[pattern.transpose]).toarray(), matrix.T)
    assert np.array_equal(data[pattern.diagonal], np.diag(matrix))
    assert np.array_equal(pattern.row_max(np.abs(data)), np.abs(matrix).max(axis=1))
    keep = np.array([0, 3, 4, 8, 15, 16, 29])
    sub, take = pattern.submatrix(keep)
    assert np.array_equal(sub.matrix(data[take]).toarray(), matrix[np.ix_(keep, keep)])
    order = np.random.default_rng(4).permutation(30)
    permuted, take = pattern.permuted(order)
    assert np.array_equal(permuted.matrix(data[take]).toarray(), matrix[np.ix_(order, order)])


def test_entries_outside_the_pattern_are_refused(triplets):
    rows, cols, _ = triplets
    pattern, _ = pattern_of(rows, cols, 30)
    dense = pattern.matrix(np.ones(pattern.nnz)).toarray()
    i, j = np.argwhere(dense == 0)[0]
    with pytest.raises(KeyError, match="outside the sparsity pattern"):
        pattern.find(np.array([i]), np.array([j]))


def _saddle_point(
    seed: int, pressure: float = -1e-3
) -> tuple[sp.coo_matrix, np.ndarray, np.ndarray]:
    """A mixed u-p matrix [[K, B^T], [B, pressure I]] (K SPD; pressure < 0: nu < 0.5,
    quasi-definite, LDL^T needs no pivoting in any order; 0: nu = 0.5, stored zeros) as COO,
    and its rows and columns."""
    rng = np.random.default_rng(seed)
    n, m = 40, 10
    stiffness = sp.random(n, n, density=0.1, random_state=rng)
    stiffness = stiffness @ stiffness.T + 10.0 * sp.eye(n)
    coupling = sp.random(m, n, density=0.2, random_state=rng) + sp.eye(m, n)
    block = sp.coo_matrix((np.full(m, pressure), (np.arange(m), np.arange(m))), shape=(m, m))
    matrix = sp.bmat([[stiffness, coupling.T], [coupling, block]]).tocoo()
    return matrix, matrix.row, matrix.col


def test_pattern_solver_factors_stay_valid_while_their_solve_is_held():
    """A modified Newton keeps the solve of an older matrix while the next is factorized: the
    older solve must still solve its own matrix (QDLDL refactorizes in place; the solver
    keeps one set of factors per solve in use)."""
    from shtaerman.fem.solver import PatternSolver

    first, rows, cols = _saddle_point(0)
    pattern, where = pattern_of(rows, cols, first.shape[0])
    solver = PatternSolver(pattern, np.arange(pattern.size))
    data = [np.bincount(where, first.data, pattern.nnz)]
    data.append(data[0] * (1.0 + 0.5 * np.random.default_rng(1).random(pattern.nnz)))
    data[1] = 0.5 * (data[1] + data[1][pattern.transpose])  # symmetric again
    rhs = np.arange(1.0, first.shape[0] + 1.0)
    _, kept = solver.factorized(data[0], rhs)
    _, latest = solver.factorized(data[1], rhs)
    for values, solve in zip(data, (kept, latest), strict=True):
        matrix = pattern.matrix(values)
        # a direct solve of a well-conditioned 50 x 50 system: ~1e-14 (a solve with the other
        # matrix's factors is off by O(1))
        assert np.max(abs(matrix @ solve(rhs) - rhs)) <= 1e-10 * np.max(abs(rhs))


def test_pattern_solver_after_a_zero_pivot_is_superlu_in_nested_dissection_order(monkeypatch):
    """A zero pressure block whose pressures have the lowest degree: QDLDL's order eliminates a
    pressure first, a zero pivot; SuperLU in nested-dissection order solves it, for this and
    every later matrix (QDLDL is not tried again)."""
    from shtaerman.fem import solver

    matrix, rows, cols = _saddle_point(0, pressure=0.0)
    pattern, where = pattern_of(rows, cols, matrix.shape[0])
    groups = np.arange(pattern.size)  # one unknown per node: pressures stay after their rows
    tried = []
    original = solver.PatternSolver._ldl_solve
    monkeypatch.setattr(
        solver.PatternSolver, "_ldl_solve", lambda *a: tried.append(1) or original(*a)
    )
    monkeypatch.setattr(solver, "factorize", lambda m: pytest.fail("fell back to factorize"))
    pattern_solver = solver.PatternSolver(pattern, groups)
    data = np.bincount(where, matrix.data, pattern.nnz)
    rhs = np.arange(1.0, pattern.size + 1.0)
    for _ in range(2):
        solution = pattern_solver.solve(data, rhs)
        # a direct solve of a 50 x 50 system: ~1e-14
        assert np.max(abs(pattern.matrix(data) @ solution - rhs)) <= 1e-10 * np.max(abs(rhs))
    assert tried == [1]


def test_pattern_solver_solves_an_unsymmetric_matrix_without_qdldl(monkeypatch):
    """A Coulomb slip's tangent is not symmetric: QDLDL (the upper triangle's LDL^T) would
    solve its symmetric part, so it is not tried; SuperLU in nested-dissection order solves
    the matrix itself."""
    from shtaerman.fem import solver

    matrix, rows, cols = _saddle_point(0)
    pattern, where = pattern_of(rows, cols, matrix.shape[0])
    data = np.bincount(where, matrix.data, pattern.nnz)
    skew = np.random.default_rng(2).random(pattern.nnz) * (pattern.indices < pattern.columns)
    data += 0.1 * skew  # the upper triangle only: an asymmetry of 0.1 of the entries
    monkeypatch.setattr(solver.PatternSolver, "_ldl_solve", lambda *_: pytest.fail("QDLDL"))
    monkeypatch.setattr(solver, "factorize", lambda m: pytest.fail("fell back to factorize"))
    rhs = np.arange(1.0, pattern.size + 1.0)
    solution = solver.PatternSolver(pattern, np.arange(pattern.size)).solve(data, rhs)
    # a direct solve of a 50 x 50 system: ~1e-14 (the symmetric part's solution: O(0.1))
    assert np.max(abs(pattern.matrix(data) @ solution - rhs)) <= 1e-10 * np.max(abs(rhs))
