"""One sparse factorization that also yields the Schur complement on chosen "tail" unknowns.

The contact solver needs the surface compliance C = (K^-1)_tt on the candidate contact dofs t.
Ordering those dofs last in the elimination makes the trailing block of the LU factors the
Schur complement S = K_tt - K_ti K_ii^-1 K_it = L_tt U_tt, and C = S^-1: the compliance falls
out of the factorization at the cost of one small dense inversion, instead of one solve per
candidate dof. The factorization is :class:`.solver.OrderedLU` in nested-dissection order
with the tail moved to the end, scaled by :func:`.solver.symmetric_scaling`.
"""

from __future__ import annotations

import numpy as np
import scipy.linalg as la
import scipy.sparse as sp

from .solver import ACCURACY_CHECK, OrderedLU, backward_error, nested_dissection, symmetric_scaling

__all__ = ["TailFactorization", "TailPivotError"]


class TailPivotError(RuntimeError):
    """The tail-ordered factorization gives no usable Schur complement (fall back)."""


class TailFactorization(OrderedLU):
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
        self.tail = np.asarray(tail, dtype=np.int64)
        is_tail = np.zeros(n, dtype=bool)
        is_tail[self.tail] = True
        order = nested_dissection(matrix, groups)
        order = np.concatenate([order[~is_tail[order]], self.tail])
        super().__init__(matrix, order, symmetric_scaling(matrix))
        start = n - self.tail.size
        if not np.array_equal(self.lu.perm_r[start:], np.arange(start, n)):
            raise TailPivotError("the factorization pivoted the tail rows; no Schur complement")
        if backward_error(matrix, self) > ACCURACY_CHECK:
            raise TailPivotError("tail-ordered factorization is inaccurate")

    def tail_inverse(self) -> np.ndarray:
        """(K^-1)_tt = S^-1 = U_tt^-1 L_tt^-1 (dense, in tail order).

        S = K_tt - K_ti K_ii^-1 K_it = L_tt U_tt is the trailing block of the factors.
        """
        k = self.tail.size
        lower = self.lu.L[:, -k:][-k:].toarray()
        upper = self.lu.U[:, -k:][-k:].toarray()
        inverse_lower = la.solve_triangular(lower, np.eye(k), lower=True, unit_diagonal=True)
        d = self.scale[-k:]
        return d[:, None] * la.solve_triangular(upper, inverse_lower, lower=False) * d[None, :]
