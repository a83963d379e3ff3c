"""Sparse direct factorization: ordering, scaling, backward error and the backends.

Every factorization of :mod:`shtaerman.fem` is made here:

- :func:`factorize`: a checked factorization of one matrix, SuperLU (minimum-degree ordering,
  diagonal pivots, stricter pivoting if needed) or MKL PARDISO through the optional
  ``pypardiso`` package (``pip install shtaerman[pardiso]``).
- :class:`OrderedLU`: SuperLU in a given symmetric order (natural columns, diagonal pivots),
  for instance :func:`nested_dissection` of the mesh-node graph; :class:`TailFactorization`
  builds on it.
- :func:`factorize_scaled`: row-max scaled, nested-dissection ordered, checked against a
  tolerance, with :func:`factorize` as the fallback (the dynamic effective matrix).
- :class:`PatternSolver`: many matrices of one sparsity pattern, analysed once (Newton),
  by QDLDL's LDL^T (the ``qdldl`` package).
- Scalings (:func:`symmetric_scaling`, :func:`row_max_scaling`) that take the units out of
  the pivots, and the componentwise backward error (:func:`backward_error`).

The contact solver needs the surface compliance C = (K^-1)_tt on the candidate contact dofs t.
:class:`TailFactorization` orders those dofs last in the elimination, so that the trailing
block of the LU factors is the Schur complement S = K_tt - K_ti K_ii^-1 K_it = L_tt U_tt and
C = S^-1: the compliance falls out of the factorization at the cost of one small dense
inversion, instead of one solve per candidate dof (:class:`OrderedLU` in nested-dissection
order with the tail moved to the end, scaled by :func:`symmetric_scaling`).

Newton's method assembles the same element connectivity at every iteration, and scipy's COO to
CSR/CSC conversion sorts the element entries every time. A :class:`Pattern` does the sort
once: :func:`pattern_of` returns it and, for every element entry, its index in ``data``; an
assembly is then one ``np.bincount``. Submatrices (free dofs), symmetric permutations (a
fill-reducing ordering) and transposes become fixed gathers of ``data`` too.

Factorize once per matrix and reuse the object for every right-hand side: ``solve`` takes a
vector or a 2-D array of many right-hand sides (one per column).
"""

from __future__ import annotations

import contextlib
import importlib.util
import warnings
import weakref
from collections.abc import Callable
from dataclasses import dataclass
from functools import cached_property
from typing import ClassVar, Protocol

import numpy as np
import pymetis
import qdldl
import scipy.linalg as la
import scipy.sparse as sp
import scipy.sparse.linalg as spla

from ..signals import call_trapping
from ..validation import InputError, caller_stacklevel

__all__ = [
    "ACCURACY_CHECK",
    "BACKENDS",
    "Factorization",
    "OrderedLU",
    "PardisoFactorization",
    "Pattern",
    "PatternSolver",
    "ScaledFactorization",
    "SuperLUFactorization",
    "TailFactorization",
    "TailPivotError",
    "available_backends",
    "backward_error",
    "factorize",
    "factorize_scaled",
    "nested_dissection",
    "pattern_of",
    "row_max_scaling",
    "solution_backward_error",
    "symmetric_scaling",
]

BACKENDS = ("superlu", "pardiso")
"""Known backends, fastest last."""

SUPERLU_ORDERING = "MMD_AT_PLUS_A"
"""SuperLU column ordering: minimum degree on A + A^T (the pattern is symmetric)."""
SUPERLU_PIVOT_THRESHOLD = 0.0
"""SuperLU diag_pivot_thresh: 0 keeps every nonzero diagonal pivot, so the factorization
follows the symmetric ordering (least fill); SuperLU still pivots off the diagonal where a
pivot is exactly zero (the pressure block at nu = 0.5)."""
FALLBACK_PIVOT_THRESHOLDS = (0.01, 1.0)
"""Retried in turn if the diagonal-pivot factorization fails the accuracy check."""
ACCURACY_CHECK = 1e-8
"""Largest accepted componentwise backward error of a test solve."""


class Factorization(Protocol):
    """A factorized square sparse matrix."""

    backend: str
    shape: tuple[int, int]

    def solve(self, rhs: np.ndarray) -> np.ndarray:
        """Solve A x = rhs for a vector (n,) or many right-hand sides (n, k)."""
        ...


def available_backends() -> list[str]:
    """Backends importable here, in :data:`BACKENDS` order."""
    found = ["superlu"]
    if importlib.util.find_spec("pypardiso") is not None:
        found.append("pardiso")
    return found


def check_backend(backend: str) -> str:
    """``backend`` if this machine has it (``"auto"``, ``"superlu"``, ``"pardiso"`` with
    pypardiso installed), or InputError naming ``solver``."""
    choices = ("auto", *BACKENDS)
    if backend not in choices:
        raise InputError(f"solver: unknown solver {backend!r}. Pick one of {choices}", "solver")
    if backend != "auto" and backend not in available_backends():
        raise InputError(
            f"solver {backend!r} needs the package pypardiso (pip install pypardiso), not "
            "installed here; use 'superlu' or 'auto'",
            "solver",
        )
    return backend


def factorize(matrix: sp.spmatrix, backend: str = "auto") -> Factorization:
    """Factorize a square sparse matrix.

    Parameters
    ----------
    matrix : scipy.sparse matrix
        Square, nonsingular (symmetric indefinite for the mixed system).
    backend : str
        ``"auto"`` (SuperLU), ``"superlu"`` or ``"pardiso"``.

    Returns
    -------
    Factorization
        With ``.solve(rhs)`` and ``.backend``. Its componentwise backward error on a test
        solve is below ``ACCURACY_CHECK`` (else PARDISO falls back to SuperLU, and SuperLU to
        stricter pivoting).

    Raises
    ------
    shtaerman.validation.InputError
        For an unknown or unavailable backend.
    RuntimeError
        If the matrix is singular to working precision.
    """
    requested = check_backend(backend)
    backend = "superlu" if requested == "auto" else requested
    if matrix.shape[0] != matrix.shape[1]:
        raise ValueError(f"matrix must be square, got shape {matrix.shape}")
    if backend == "pardiso":
        factorization = _checked_pardiso(matrix, explicit=requested == "pardiso")
        if factorization is not None:
            return factorization
    return _checked_superlu(matrix)


def _checked_pardiso(matrix: sp.spmatrix, explicit: bool) -> PardisoFactorization | None:
    """PARDISO if it loads and is accurate; else None (a warning) to fall back to SuperLU."""
    try:
        factorization = PardisoFactorization(matrix)
    except (ImportError, OSError) as error:  # pypardiso present, MKL library missing
        if explicit:
            raise InputError(f"solver 'pardiso' cannot load MKL: {error}", "solver") from None
        warnings.warn(
            f"PARDISO unavailable ({error}); using SuperLU", stacklevel=caller_stacklevel()
        )
        return None
    if backward_error(matrix, factorization, symmetric_scaling(matrix)) <= ACCURACY_CHECK:
        return factorization
    warnings.warn(
        "PARDISO factorization inaccurate; falling back to SuperLU", stacklevel=caller_stacklevel()
    )
    return None


def _checked_superlu(matrix: sp.spmatrix) -> SuperLUFactorization:
    """Diagonal pivoting first; stricter pivoting only if the backward error says so."""
    for threshold in (SUPERLU_PIVOT_THRESHOLD, *FALLBACK_PIVOT_THRESHOLDS):
        try:
            factorization = SuperLUFactorization(matrix, pivot_threshold=threshold)
        except RuntimeError:  # an exactly zero pivot
            continue
        if backward_error(matrix, factorization, factorization.scale) <= ACCURACY_CHECK:
            return factorization
    raise RuntimeError("matrix is singular to working precision (check the constraints)")


# --- ordering and scaling ---------------------------------------------------------------------


def nested_dissection(pattern: sp.spmatrix, groups: np.ndarray) -> np.ndarray:
    """Order the unknowns by METIS nested dissection of the graph of their groups.

    METIS traps SIGTERM itself while it orders; :func:`.signals.call_trapping` passes the
    signal on to Python's handler.

    Parameters
    ----------
    pattern : scipy.sparse matrix
        Square; its nonzeros couple unknowns.
    groups : numpy.ndarray
        Group (mesh node) of each unknown, integers 0..g-1: the unknowns of one node are
        ordered together, on a graph about 4x smaller than that of the unknowns.

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


def symmetric_scaling(matrix: sp.spmatrix) -> np.ndarray:
    """d with D A D (D = diag d) free of units, for the mixed u-p system.

    d_i = A_ii^-1/2 on rows of positive diagonal (the displacements), and on the others (the
    pressures: zero or negative diagonal) d_i = 1 / max_j |A_ij| d_j over the former, so that
    every coupling is at most 1. The blocks scale differently with the modulus E and the
    length L (u-u ~ E L, u-p ~ L^2, p-p ~ L^3 / E): unscaled, SuperLU's pivoting depends on
    the units chosen.
    """
    csr = sp.csr_matrix(matrix)
    diagonal = csr.diagonal()
    positive = diagonal > 0
    d = np.ones(csr.shape[0])
    d[positive] = 1.0 / np.sqrt(diagonal[positive])
    coupling = abs(csr) @ sp.diags(np.where(positive, d, 0.0))
    largest = coupling.max(axis=1).toarray().ravel()
    others = ~positive & (largest > 0)
    d[others] = 1.0 / largest[others]
    return d


def row_max_scaling(matrix: sp.spmatrix) -> np.ndarray:
    """d = (max_j |A_ij|)^-1/2 per row: D A D (D = diag d) has rows of size ~1, stays symmetric.

    For matrices whose entries span many decades (a graded mesh's stiffness and mass);
    every row must hold a nonzero.
    """
    return 1.0 / np.sqrt(np.asarray(abs(matrix).max(axis=1).todense()).ravel())


# --- backward error ---------------------------------------------------------------------------


def solution_backward_error(matrix: sp.spmatrix, x: np.ndarray, rhs: np.ndarray) -> float:
    """Componentwise backward error max |A x - b| / (|A| |x| + |b|) of a solution x of A x = b."""
    scale = abs(matrix) @ abs(x) + abs(rhs)
    return float(np.max(abs(matrix @ x - rhs) / np.where(scale > 0, scale, 1.0)))


def backward_error(
    matrix: sp.spmatrix, factorization: Factorization, scale: np.ndarray | None = None
) -> float:
    """Componentwise backward error of a test solve with ``factorization`` of ``matrix``.

    The right-hand side is A x for x = D z, z a fixed random vector (seed 0, reproducible)
    and D = diag ``scale`` (None: D = I). With the :func:`symmetric_scaling` of a mixed u-p
    matrix, x has the displacement-to-pressure ratio of a solution (L / E), so the value is
    unit-free; with D = I the pressures of x are off theirs by E / L in SI units and the
    value grew as (E / L)^-1 below 1 Pa/m (benchmarks/bench_units.py).
    """
    exact = np.random.default_rng(0).standard_normal(matrix.shape[0])
    if scale is not None:
        exact = scale * exact
    rhs = matrix @ exact
    return solution_backward_error(matrix, factorization.solve(rhs), rhs)


# --- the factorizations -----------------------------------------------------------------------


def _superlu_in_order(matrix: sp.csc_matrix) -> spla.SuperLU:
    """SuperLU of a matrix already in its elimination order: natural columns, diagonal pivots.

    Raises RuntimeError on an exactly zero pivot.
    """
    return spla.splu(
        matrix,
        permc_spec="NATURAL",
        diag_pivot_thresh=0.0,
        options={"SymmetricMode": True, "Equil": False},
    )


class SuperLUFactorization:
    """scipy SuperLU of D A D (:func:`symmetric_scaling`) with a symmetric ordering.

    Parameters
    ----------
    matrix : scipy.sparse matrix
    ordering : str
        SuperLU ``permc_spec``.
    pivot_threshold : float
        SuperLU ``diag_pivot_thresh`` in [0, 1].

    Attributes
    ----------
    scale : numpy.ndarray
        d of D.
    """

    backend = "superlu"

    def __init__(
        self,
        matrix: sp.spmatrix,
        ordering: str = SUPERLU_ORDERING,
        pivot_threshold: float = SUPERLU_PIVOT_THRESHOLD,
    ) -> None:
        self.shape = matrix.shape
        self.scale = symmetric_scaling(matrix)
        scale = sp.diags(self.scale)
        self._lu = spla.splu(
            sp.csc_matrix(scale @ matrix @ scale),
            permc_spec=ordering,
            diag_pivot_thresh=pivot_threshold,
            options={"SymmetricMode": pivot_threshold < 1.0},
        )

    @property
    def fill(self) -> int:
        """Nonzeros of L + U."""
        return int(self._lu.L.nnz + self._lu.U.nnz)

    def solve(self, rhs: np.ndarray) -> np.ndarray:
        """Solve for a vector (n,) or many right-hand sides (n, k), one column at a time
        (faster than SuperLU's own multi-column solve)."""
        rhs = np.asarray(rhs, dtype=float)
        d = self.scale
        if rhs.ndim == 2:
            solution = np.empty_like(rhs)
            for column in range(rhs.shape[1]):
                solution[:, column] = d * self._lu.solve(d * rhs[:, column])
            return solution
        return d * self._lu.solve(d * rhs)


class OrderedLU:
    """SuperLU of D P A P^T D in a given symmetric order P (natural columns, diagonal pivots).

    Parameters
    ----------
    matrix : scipy.sparse matrix
        Square, nonsingular.
    order : numpy.ndarray
        Elimination order of the unknowns (a permutation), e.g. :func:`nested_dissection`.
    scale : numpy.ndarray, optional
        d of D = diag(d) in the original numbering; None: no scaling.
    symmetric : bool
        Whether A = A^T: a vector is then solved with the transposed factors, A^T x = b
        (SuperLU's transposed triangular solves gather by dot products instead of scattering
        updates: on the 11k-dof dynamic effective matrix 12 % less CPU and a backward error
        of 1e-14 .. 6e-13 against 1e-12 .. 2e-10, benchmarks/FEM_NOTES.md), many right-hand
        sides with SuperLU's blocked solve (the transposed one takes twice as long there).

    Raises
    ------
    RuntimeError
        On an exactly zero pivot.
    """

    backend = "superlu-nd"

    def __init__(
        self,
        matrix: sp.spmatrix,
        order: np.ndarray,
        scale: np.ndarray | None = None,
        symmetric: bool = False,
    ) -> None:
        self.shape = matrix.shape
        self.order = np.asarray(order)
        self.vector_trans = "T" if symmetric else "N"
        """SuperLU's ``trans`` for a single right-hand side."""
        permuted = sp.csc_matrix(matrix)[self.order][:, self.order]
        self.scale = None if scale is None else np.asarray(scale)[self.order]
        """d in elimination order (None: unscaled)."""
        if self.scale is not None:
            permuted = sp.diags(self.scale) @ permuted @ sp.diags(self.scale)
        self.lu = _superlu_in_order(permuted.tocsc())
        """The SuperLU object of D P A P^T D."""

    def solve(self, rhs: np.ndarray) -> np.ndarray:
        """Solve for a vector (n,) or many right-hand sides (n, k)."""
        rhs = np.asarray(rhs, dtype=float)
        solution = np.empty_like(rhs)
        trans = self.vector_trans if rhs.ndim == 1 else "N"
        if self.scale is None:
            solution[self.order] = self.lu.solve(rhs[self.order], trans=trans)
            return solution
        d = self.scale if rhs.ndim == 1 else self.scale[:, None]
        solution[self.order] = d * self.lu.solve(d * rhs[self.order], trans=trans)
        return solution


class ScaledFactorization:
    """A factorization of D A D (D = diag ``scale``) that solves A x = b.

    Attributes
    ----------
    scale : numpy.ndarray
        d of D.
    backward_error : float
        Componentwise backward error of a test solve of the scaled system.
    backend : str
        The backend of the inner factorization.
    """

    def __init__(self, inner: Factorization, scale: np.ndarray, error: float) -> None:
        self._inner = inner
        self.scale = scale
        self.backward_error = error
        self.backend = inner.backend
        self.shape = inner.shape

    def solve(self, rhs: np.ndarray) -> np.ndarray:
        """Solve A x = rhs for a vector (n,) or many right-hand sides (n, k)."""
        rhs = np.asarray(rhs, dtype=float)
        scale = self.scale if rhs.ndim == 1 else self.scale[:, None]
        return scale * self._inner.solve(scale * rhs)


def factorize_scaled(
    matrix: sp.spmatrix, groups: np.ndarray | None, tolerance: float
) -> ScaledFactorization:
    """Factorize D A D with :func:`row_max_scaling`, checked by its backward error.

    In turn: :class:`OrderedLU` in :func:`nested_dissection` order of ``groups`` (skipped
    for None or an exactly zero pivot; a vector solved with the transposed factors, as the
    matrix is symmetric), :class:`SuperLUFactorization`, and if the backward
    error of a test solve is above ``tolerance``, :func:`factorize` (checked at
    ``ACCURACY_CHECK``).

    Parameters
    ----------
    matrix : scipy.sparse matrix
        Square, nonsingular, symmetric; entries may span many decades.
    groups : numpy.ndarray or None
        Group (mesh node) of each unknown, for the ordering.
    tolerance : float
        Largest accepted backward error of the first two.

    Raises
    ------
    RuntimeError
        If the matrix is singular to working precision.
    """
    scale = row_max_scaling(matrix)
    scaling = sp.diags(scale)
    scaled = (scaling @ matrix @ scaling).tocsc()
    factorization = None
    if groups is not None:
        with contextlib.suppress(RuntimeError):  # an exactly zero pivot: fall back
            order = nested_dissection(scaled, groups)
            factorization = OrderedLU(scaled, order, symmetric=True)
    if factorization is None:
        factorization = SuperLUFactorization(scaled)
    error = backward_error(scaled, factorization)
    if not error <= tolerance:
        factorization = factorize(scaled)
        error = backward_error(scaled, factorization)
    return ScaledFactorization(factorization, scale, error)


class PatternSolver:
    """Solve with many matrices of one fixed sparsity pattern (Newton's), analysed once.

    Each matrix is row-max scaled (:func:`row_max_scaling`) and factorized by QDLDL (LDL^T
    with diagonal pivots, of the upper triangle) in the approximate-minimum-degree order of
    the pattern's first factorization; later matrices reuse that analysis (one set of factors
    per solve still in use). A matrix that is not symmetric (a Coulomb slip's tangent: its
    entries and their mirrors differ by more than ``ACCURACY_CHECK`` after the scaling) is
    factorized by SuperLU in the :func:`nested_dissection` order of ``groups``, and so is every
    matrix after a zero pivot in QDLDL's order (QDLDL does not pivot). A solve whose
    componentwise backward error exceeds ``ACCURACY_CHECK`` is redone by :func:`factorize`
    (its own ordering, stricter pivoting if needed).

    Parameters
    ----------
    pattern : Pattern
        The sparsity pattern of every matrix (symmetric, every diagonal entry stored).
    groups : numpy.ndarray
        Group (mesh node) of each unknown, for the nested-dissection order.
    """

    def __init__(self, pattern: Pattern, groups: np.ndarray) -> None:
        self.pattern, self.groups = pattern, groups
        self._upper_take = np.flatnonzero(pattern.indices <= pattern.columns)
        self._mirror_take = pattern.transpose[self._upper_take]
        per_column = np.bincount(pattern.columns[self._upper_take], minlength=pattern.size)
        self._upper = sp.csc_matrix(
            (np.zeros(self._upper_take.size), pattern.indices[self._upper_take],
             _pointers(per_column)),
            shape=(pattern.size, pattern.size),
        )  # fmt: skip
        self._analysed: list[list] | None = []
        """[QDLDL solver, weak reference to the solve using its factors] per set of factors;
        None after a zero pivot."""

    def solve(self, data: np.ndarray, rhs: np.ndarray) -> np.ndarray:
        """Solve A x = rhs, A with ``data`` in the pattern.

        Raises
        ------
        RuntimeError
            If the matrix is singular to working precision.
        """
        return self.factorized(data, rhs)[0]

    def factorized(
        self, data: np.ndarray, rhs: np.ndarray
    ) -> tuple[np.ndarray, Callable[[np.ndarray], np.ndarray]]:
        """The solution of A x = rhs, and a function solving A x = b for other b with the same
        factorization (a modified Newton's reuse).

        Raises
        ------
        RuntimeError
            If the matrix is singular to working precision.
        """
        pattern = self.pattern
        scale = 1.0 / np.sqrt(pattern.row_max(np.abs(data)))
        scaled = data * scale[pattern.indices]
        scaled *= np.repeat(scale, np.diff(pattern.indptr))  # the columns' scale, in order
        upper = scaled[self._upper_take]
        symmetric = np.max(abs(upper - scaled[self._mirror_take])) <= ACCURACY_CHECK
        inner = self._ldl_solve(upper) if symmetric and self._analysed is not None else None
        inner = inner or self._ordered_solve(scaled)
        scaled_rhs = scale * rhs
        if inner is not None:
            solution = inner(scaled_rhs)
            error = solution_backward_error(pattern.matrix(scaled), solution, scaled_rhs)
            if error <= ACCURACY_CHECK:
                solve = _ScaledSolve(scale, inner)
                return scale * solution, solve
        solve = _ScaledSolve(scale, factorize(pattern.matrix(scaled)).solve)
        return solve(rhs), solve

    def _ldl_solve(self, upper: np.ndarray) -> Callable[[np.ndarray], np.ndarray] | None:
        """QDLDL's solve of the scaled symmetric matrix of upper triangle ``upper`` (its data),
        in factors no held solve uses; None (and QDLDL no more for this pattern) on a zero
        pivot."""
        self._upper.data = upper
        free = [entry for entry in self._analysed if entry[1]() is None]
        try:
            if free:
                free[0][0].update(self._upper, upper=True)
            else:
                free = [[qdldl.Solver(self._upper, upper=True), _unused]]
                self._analysed.append(free[0])
        except RuntimeError:  # a zero pivot in this order
            self._analysed = None
            return None
        inner = _FactorsSolve(free[0][0].solve)
        free[0][1] = weakref.ref(inner)  # these factors stay while the solve is held
        return inner

    def _ordered_solve(self, scaled: np.ndarray) -> Callable[[np.ndarray], np.ndarray] | None:
        """SuperLU's solve of the scaled matrix in nested-dissection order, or None on a zero
        pivot."""
        order, ordered, take = self._nested_dissection
        try:
            lu = _superlu_in_order(ordered.matrix(scaled[take]))
        except RuntimeError:  # an exactly zero pivot
            return None

        def inner(rhs: np.ndarray) -> np.ndarray:
            out = np.empty_like(rhs)
            out[order] = lu.solve(rhs[order])
            return out

        return inner

    @cached_property
    def _nested_dissection(self) -> tuple[np.ndarray, Pattern, np.ndarray]:
        """The order of ``groups``, the ordered pattern and its gather."""
        pattern = self.pattern
        order = nested_dissection(pattern.matrix(np.ones(pattern.nnz)), self.groups)
        return order, *pattern.permuted(order)


def _unused() -> None:
    """The weak reference of factors no solve uses."""


class _ScaledSolve:
    """x = D inner(D b): a solve of A x = b from a solve of the scaled D A D."""

    def __init__(self, scale: np.ndarray, inner: Callable[[np.ndarray], np.ndarray]) -> None:
        self.scale, self.inner = scale, inner

    def __call__(self, rhs: np.ndarray) -> np.ndarray:
        return self.scale * self.inner(self.scale * rhs)


class _FactorsSolve:
    """A solve with one set of QDLDL factors: while it is referenced, they are not updated."""

    def __init__(self, solve: Callable[[np.ndarray], np.ndarray]) -> None:
        self.solve = solve

    def __call__(self, rhs: np.ndarray) -> np.ndarray:
        return self.solve(rhs)


class PardisoFactorization:
    """MKL PARDISO through pypardiso, in real symmetric indefinite mode (mtype -2).

    Only the upper triangle is factorized, with METIS nested dissection, symmetric weighted
    matching and scaling (PARDISO's setting for saddle-point systems; without them the
    nu = 0.5 system fails) and 1e-8 pivot perturbation. Iterative refinement is off, so a
    solve with k right-hand sides costs k triangular solves; :func:`factorize` checks the
    backward error once instead.

    Parameters
    ----------
    matrix : scipy.sparse matrix
        Symmetric.
    """

    backend = "pardiso"
    _IPARM: ClassVar[dict[int, int]] = {1: 1, 2: 2, 8: 0, 10: 8, 11: 1, 13: 1}
    """1-based iparm: custom values, METIS, no refinement, eps 1e-8, scaling, matching."""

    def __init__(self, matrix: sp.spmatrix) -> None:
        import pypardiso

        self.shape = matrix.shape
        self._upper = _upper_triangle_with_diagonal(matrix)
        self._solver = pypardiso.PyPardisoSolver(mtype=-2)
        for index, value in self._IPARM.items():
            self._solver.set_iparm(index, value)
        self._solver.factorize(self._upper)

    def solve(self, rhs: np.ndarray) -> np.ndarray:
        """Solve for a vector (n,) or many right-hand sides (n, k)."""
        rhs = np.asarray(rhs, dtype=float)
        return self._solver.solve(self._upper, rhs).reshape(rhs.shape)

    def __del__(self) -> None:
        solver = getattr(self, "_solver", None)
        if solver is not None:
            solver.free_memory(everything=True)


def _upper_triangle_with_diagonal(matrix: sp.spmatrix) -> sp.csr_matrix:
    """CSR upper triangle storing every diagonal entry, zeros included (PARDISO needs them)."""
    upper = sp.triu(matrix, format="coo")
    diagonal = np.arange(matrix.shape[0])
    result = sp.csr_matrix(
        (
            np.concatenate([upper.data, np.zeros(diagonal.size)]),
            (np.concatenate([upper.row, diagonal]), np.concatenate([upper.col, diagonal])),
        ),
        shape=matrix.shape,
    )
    result.sort_indices()
    return result


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
        scale = symmetric_scaling(matrix)
        super().__init__(matrix, order, scale)
        start = n - self.tail.size
        if not np.array_equal(self.lu.perm_r[start:], np.arange(start, n)):
            raise TailPivotError("the factorization pivoted the tail rows; no Schur complement")
        if backward_error(matrix, self, scale) > ACCURACY_CHECK:
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


@dataclass(frozen=True, eq=False)
class Pattern:
    """Structure of a square sparse matrix in CSC form, rows sorted within each column.

    Attributes
    ----------
    indptr : numpy.ndarray
        (size + 1,) start of each column in ``data``.
    indices : numpy.ndarray
        (nnz,) row of each stored entry.
    size : int
        Number of rows and columns.
    """

    indptr: np.ndarray
    indices: np.ndarray
    size: int

    @property
    def nnz(self) -> int:
        """Number of stored entries (explicit zeros included)."""
        return int(self.indices.size)

    @cached_property
    def columns(self) -> np.ndarray:
        """(nnz,) column of each stored entry."""
        return np.repeat(np.arange(self.size), np.diff(self.indptr))

    @cached_property
    def _keys(self) -> np.ndarray:
        return self.columns.astype(np.int64) * self.size + self.indices

    @cached_property
    def diagonal(self) -> np.ndarray:
        """(size,) index in ``data`` of each diagonal entry (all must be stored)."""
        return self.find(np.arange(self.size), np.arange(self.size))

    @cached_property
    def transpose(self) -> np.ndarray:
        """Gather ``data[transpose]``: the data of A^T in this (symmetric) pattern."""
        return self.find(self.columns, self.indices)

    def find(self, rows: np.ndarray, cols: np.ndarray) -> np.ndarray:
        """Index in ``data`` of the entries (rows, cols).

        Raises
        ------
        KeyError
            If an entry is not in the pattern.
        """
        keys = np.asarray(cols, dtype=np.int64) * self.size + np.asarray(rows)
        where = np.minimum(np.searchsorted(self._keys, keys), self.nnz - 1)
        if not np.array_equal(self._keys[where], keys):
            raise KeyError("entries outside the sparsity pattern")
        return where

    def matrix(self, data: np.ndarray) -> sp.csc_matrix:
        """The CSC matrix with this pattern and values ``data`` (not copied)."""
        matrix = sp.csc_matrix((data, self.indices, self.indptr), shape=(self.size, self.size))
        matrix.has_sorted_indices = True
        return matrix

    def row_max(self, data: np.ndarray) -> np.ndarray:
        """(size,) max_j data_ij per row (``data`` non-negative; no empty rows).

        A scatter-max over the rows (``np.maximum.at``): 2.1 ms against 5.2 ms for the gather
        ``data[transpose]`` and a segmented max on a 38,639-dof Newton tangent (1.1e6
        entries), the same values (a max does not round).
        """
        largest = np.zeros(self.size)
        np.maximum.at(largest, self.indices, data)
        return largest

    def submatrix(self, keep: np.ndarray) -> tuple[Pattern, np.ndarray]:
        """The pattern of A[keep][:, keep] and the gather ``take`` with its data = data[take].

        ``keep`` is increasing, so rows stay sorted.
        """
        position = np.full(self.size, -1, dtype=np.int64)
        position[keep] = np.arange(keep.size)
        inside = (position[self.indices] >= 0) & (position[self.columns] >= 0)
        take = np.flatnonzero(inside)
        counts = np.bincount(position[self.columns[take]], minlength=keep.size)
        indices = position[self.indices[take]].astype(np.int32)
        return Pattern(_pointers(counts), indices, int(keep.size)), take

    def permuted(self, order: np.ndarray) -> tuple[Pattern, np.ndarray]:
        """The pattern of A[order][:, order] and the gather ``take`` with its data = data[take]."""
        inverse = np.empty_like(order)
        inverse[order] = np.arange(order.size)
        pattern, where = pattern_of(inverse[self.indices], inverse[self.columns], self.size)
        take = np.empty_like(where)
        take[where] = np.arange(where.size)
        return pattern, take


def pattern_of(rows: np.ndarray, cols: np.ndarray, size: int) -> tuple[Pattern, np.ndarray]:
    """The pattern of the entries (rows, cols) of a size x size matrix, duplicates summed.

    Returns
    -------
    pattern : Pattern
    where : numpy.ndarray
        Index in ``data`` of each entry: ``np.bincount(where, values, pattern.nnz)`` assembles.
    """
    keys = np.asarray(cols, dtype=np.int64).ravel() * size + np.asarray(rows).ravel()
    unique, where = np.unique(keys, return_inverse=True)
    counts = np.bincount(unique // size, minlength=size)
    return Pattern(_pointers(counts), (unique % size).astype(np.int32), size), where


def _pointers(counts: np.ndarray) -> np.ndarray:
    """CSC column pointers (int32, as SuperLU takes them) from the entries per column."""
    return np.concatenate([[0], np.cumsum(counts)]).astype(np.int32)
