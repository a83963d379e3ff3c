"""One sparse factorization that also yields the Schur complement on chosen "tail" unknowns.

The contact solver needs the surface compliance C = (K^-1)_tt on the candidate contact dofs t.
Ordering those dofs last in the elimination makes the trailing block of the LU factors the
Schur complement S = K_tt - K_ti K_ii^-1 K_it = L_tt U_tt, and C = S^-1: the compliance falls
out of the factorization at the cost of one small dense inversion, instead of one solve per
candidate dof (12x the factorization on the default mesh; see benchmarks/bench_contact.py).

Ordering: METIS nested dissection (pymetis) on the graph of mesh nodes (the dofs of one P2 node
taken together, a graph about 4x smaller than the dof graph), the tail dofs moved to the end.
METIS traps SIGTERM itself while it orders; :func:`.signals.call_trapping` passes the signal on.
On the default nu = 0.5 mesh it fills about as much as SuperLU's own minimum-degree ordering and
factorizes as fast. SuperLU then runs with the natural column order in symmetric mode with
diagonal pivots, and the factorization is checked: the tail rows must not have been pivoted
away, and the backward error of a test solve must be small.
"""

from __future__ import annotations

import numpy as np
import pymetis
import scipy.linalg as la
import scipy.sparse as sp
import scipy.sparse.linalg as spla

from .signals import call_trapping
from .solver import ACCURACY_CHECK, backward_error, symmetric_scaling

__all__ = ["TailFactorization", "TailPivotError", "nested_dissection"]


class TailPivotError(RuntimeError):
    """The tail-ordered factorization gives no usable Schur complement (fall back)."""


def nested_dissection(pattern: sp.spmatrix, groups: np.ndarray) -> np.ndarray:
    """Order the unknowns by METIS nested dissection of the graph of their groups.

    Parameters
    ----------
    pattern : scipy.sparse matrix
        Square; its nonzeros couple unknowns.
    groups : numpy.ndarray
        Group (mesh node) of each unknown, integers 0..g-1.

    Returns
    -------
    numpy.ndarray
        A permutation of the unknowns: groups in nested-dissection order, each group's
        unknowns together.
    """
    n, count = pattern.shape[0], int(groups.max()) + 1
    incidence = sp.csr_matrix((np.ones(n), (np.arange(n), groups)), shape=(n, count))
    graph = (incidence.T @ (abs(pattern) > 0).astype(float) @ incidence).tocsr()
    graph.setdiag(0)
    graph.eliminate_zeros()
    adjacency = pymetis.CSRAdjacency(graph.indptr, graph.indices)
    group_order, _ = call_trapping(lambda: pymetis.nested_dissection(adjacency))
    rank = np.empty(count, dtype=np.int64)
    rank[np.asarray(group_order)] = np.arange(count)
    return np.argsort(rank[groups], kind="stable")


class TailFactorization:
    """LU of a square sparse matrix with the ``tail`` unknowns eliminated last.

    Parameters
    ----------
    matrix : scipy.sparse matrix
        Square, nonsingular (symmetric indefinite for the mixed system).
    tail : numpy.ndarray
        Indices of the unknowns to eliminate last (the contact candidates).
    groups : numpy.ndarray
        Group (mesh node) of each unknown, for the ordering.

    Raises
    ------
    TailPivotError
        If the factorization is inaccurate or pivoted the tail (use :mod:`.solver` instead).
    """

    backend = "superlu-schur"

    def __init__(self, matrix: sp.spmatrix, tail: np.ndarray, groups: np.ndarray) -> None:
        n = matrix.shape[0]
        self.shape = matrix.shape
        self.tail = np.asarray(tail, dtype=np.int64)
        is_tail = np.zeros(n, dtype=bool)
        is_tail[self.tail] = True
        order = nested_dissection(matrix, groups)
        self._perm = np.concatenate([order[~is_tail[order]], self.tail])
        self._scale = symmetric_scaling(matrix)[self._perm]  # units out of the pivots
        permuted = sp.csc_matrix(matrix)[self._perm][:, self._perm]
        permuted = sp.diags(self._scale) @ permuted @ sp.diags(self._scale)
        self._lu = spla.splu(
            permuted.tocsc(),
            permc_spec="NATURAL",
            diag_pivot_thresh=0.0,
            options={"SymmetricMode": True, "Equil": False},
        )
        start = n - self.tail.size
        if not np.array_equal(self._lu.perm_r[start:], np.arange(start, n)):
            raise TailPivotError("the factorization pivoted the tail rows; no Schur complement")
        if backward_error(matrix, self) > ACCURACY_CHECK:
            raise TailPivotError("tail-ordered factorization is inaccurate")

    def solve(self, rhs: np.ndarray) -> np.ndarray:
        """Solve for a vector (n,) or many right-hand sides (n, k)."""
        rhs = np.asarray(rhs, dtype=float)
        solution = np.empty_like(rhs)
        d = self._scale if rhs.ndim == 1 else self._scale[:, None]
        solution[self._perm] = d * self._lu.solve(d * rhs[self._perm])
        return solution

    def tail_inverse(self) -> np.ndarray:
        """(K^-1)_tt = S^-1 = U_tt^-1 L_tt^-1 (dense, in tail order).

        S = K_tt - K_ti K_ii^-1 K_it = L_tt U_tt is the trailing block of the factors.
        """
        k = self.tail.size
        lower = self._lu.L[:, -k:][-k:].toarray()
        upper = self._lu.U[:, -k:][-k:].toarray()
        inverse_lower = la.solve_triangular(lower, np.eye(k), lower=True, unit_diagonal=True)
        d = self._scale[-k:]
        return d[:, None] * la.solve_triangular(upper, inverse_lower, lower=False) * d[None, :]
