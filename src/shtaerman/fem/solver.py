"""Sparse direct factorization of the (symmetric indefinite) mixed elasticity system.

Backends
--------
``"superlu"``
    scipy's SuperLU, always available. Column ordering ``MMD_AT_PLUS_A`` (minimum degree on
    A + A^T: the pattern is symmetric, so this is the natural fill-reducing ordering; scipy's
    default COLAMD with partial pivoting fills 2-3x more here) in symmetric mode with
    diagonal pivots, off-diagonal only where a pivot is exactly zero (the zero pressure block
    at nu = 0.5). Every factorization is checked by its backward error on a test solve and
    redone with stricter pivoting if that fails (see benchmarks/bench_fem.py for timings).
``"pardiso"``
    MKL PARDISO (symmetric indefinite, upper triangle) through the optional ``pypardiso``
    package (``pip install shtaerman[pardiso]``). Slower than SuperLU below ~100k dofs here
    (its start-up cost), faster above; ``"auto"`` means SuperLU.

Factorize once per matrix and reuse the object for every right-hand side: :meth:`solve` takes
a vector or a 2-D array of many right-hand sides (one per column).
"""

from __future__ import annotations

import importlib.util
import warnings
from typing import ClassVar, Protocol

import numpy as np
import scipy.sparse as sp
import scipy.sparse.linalg as spla

from ..validation import InputError

__all__ = [
    "BACKENDS",
    "Factorization",
    "PardisoFactorization",
    "SuperLUFactorization",
    "available_backends",
    "backward_error",
    "factorize",
]

BACKENDS = ("superlu", "pardiso")
"""Known backends, fastest last."""

SUPERLU_ORDERING = "MMD_AT_PLUS_A"
SUPERLU_PIVOT_THRESHOLD = 0.0
"""SuperLU diag_pivot_thresh. 0 keeps every nonzero diagonal pivot, so the factorization
follows the symmetric minimum-degree ordering (least fill); SuperLU still pivots off the
diagonal where a pivot is exactly zero (the pressure block at nu = 0.5). On an 11k-dof
nu = 0.5 system, thresholds 0.01, 0.1 and 1 multiplied the fill by 4, 11 and 26 and the
factorization time by 13, 55 and 290."""

FALLBACK_PIVOT_THRESHOLDS = (0.01, 1.0)
"""Retried in turn if the diagonal-pivot factorization fails the accuracy check."""

ACCURACY_CHECK = 1e-8
"""Largest accepted componentwise backward error of a test solve (observed on the mixed
system: 1e-14 for nu < 0.5, 1e-12 to 3e-11 at nu = 0.5 up to 200k dofs, both backends)."""


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


def factorize(matrix: sp.spmatrix, backend: str = "auto") -> Factorization:
    """Factorize a square sparse matrix.

    Parameters
    ----------
    matrix : scipy.sparse matrix
        Square, nonsingular (symmetric indefinite for the mixed system).
    backend : str
        ``"auto"`` (SuperLU, the faster one below ~100k dofs here), ``"superlu"`` or
        ``"pardiso"``. Measured on the nu = 0.5 system (bench_fem.py): at 20k dofs SuperLU
        factorizes 3x faster and PARDISO solves 200 right-hand sides 2x faster (a tie
        overall); at 200k dofs PARDISO is 1.7x faster to factorize and 2.7x to solve.

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
    choices = ("auto", *BACKENDS)
    if backend not in choices:
        raise InputError(f"Unknown backend {backend!r}. Pick one of {list(choices)}")
    requested = backend
    if backend == "auto":  # SuperLU is the faster one at the sizes used here (bench_fem.py)
        backend = "superlu"
    if backend not in available_backends():
        raise InputError(f"backend {backend!r} needs the package pypardiso (pip install pypardiso)")
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
            raise InputError(f"backend 'pardiso' cannot load MKL: {error}") from None
        warnings.warn(f"PARDISO unavailable ({error}); using SuperLU", stacklevel=3)
        return None
    if backward_error(matrix, factorization) <= ACCURACY_CHECK:
        return factorization
    warnings.warn("PARDISO factorization inaccurate; falling back to SuperLU", stacklevel=3)
    return None


def _checked_superlu(matrix: sp.spmatrix) -> SuperLUFactorization:
    """Diagonal pivoting first; stricter pivoting only if the backward error says so."""
    for threshold in (SUPERLU_PIVOT_THRESHOLD, *FALLBACK_PIVOT_THRESHOLDS):
        try:
            factorization = SuperLUFactorization(matrix, pivot_threshold=threshold)
        except RuntimeError:  # an exactly zero pivot
            continue
        if backward_error(matrix, factorization) <= ACCURACY_CHECK:
            return factorization
    raise RuntimeError("matrix is singular to working precision (check the constraints)")


def symmetric_scaling(matrix: sp.spmatrix) -> np.ndarray:
    """d with D A D (D = diag d) free of units: d_i = A_ii^-1/2 on rows of positive diagonal
    (the displacements), and on the others (the pressures: zero or negative diagonal)
    d_i = 1 / max_j |A_ij| d_j over the former, so that every coupling is at most 1.

    The mixed u-p stiffness couples blocks that scale differently with the modulus E and the
    length L (u-u ~ E L, u-p ~ L^2 per unit pressure, p-p ~ L^3 / E at nu < 0.5): in SI units
    the pivots of the pressure rows were orders of magnitude off those of the displacement
    rows, which made SuperLU pivot the contact candidates away (E = 7.5 MPa, depth 1 mm) and
    lose the contact of a 1e-14 m or a 1e4 m contact radius.
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


def backward_error(matrix: sp.spmatrix, factorization: Factorization) -> float:
    """Componentwise backward error max |A x - b| / (|A| |x| + |b|) of a test solve.

    Parameters
    ----------
    matrix : scipy.sparse matrix
    factorization : Factorization
        Of ``matrix``.

    Returns
    -------
    float
        Observed 1e-14 (nu < 0.5) and 1e-12 to 3e-11 (nu = 0.5) for both backends.
    """
    exact = np.random.default_rng(0).standard_normal(matrix.shape[0])
    rhs = matrix @ exact
    x = factorization.solve(rhs)
    scale = abs(matrix) @ abs(x) + abs(rhs)
    return float(np.max(abs(matrix @ x - rhs) / np.where(scale > 0, scale, 1.0)))


class SuperLUFactorization:
    """scipy SuperLU with a symmetric ordering and (by default) diagonal pivoting.

    Parameters
    ----------
    matrix : scipy.sparse matrix
    ordering : str
        SuperLU ``permc_spec``.
    pivot_threshold : float
        SuperLU ``diag_pivot_thresh`` in [0, 1].
    """

    backend = "superlu"

    def __init__(
        self,
        matrix: sp.spmatrix,
        ordering: str = SUPERLU_ORDERING,
        pivot_threshold: float = SUPERLU_PIVOT_THRESHOLD,
    ) -> None:
        self.shape = matrix.shape
        self._scale = symmetric_scaling(matrix)
        scale = sp.diags(self._scale)
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
        """Solve for a vector (n,) or many right-hand sides (n, k).

        Many right-hand sides are solved one column at a time: SuperLU's own multi-column
        solve (scipy 1.x) was 27x slower on the 243 unit loads of a 10k-dof mesh (8.2 s
        against 0.30 s).
        """
        rhs = np.asarray(rhs, dtype=float)
        d = self._scale
        if rhs.ndim == 2:
            solution = np.empty_like(rhs)
            for column in range(rhs.shape[1]):
                solution[:, column] = d * self._lu.solve(d * rhs[:, column])
            return solution
        return d * self._lu.solve(d * rhs)


class PardisoFactorization:
    """MKL PARDISO through pypardiso, in real symmetric indefinite mode (mtype -2).

    Only the upper triangle is factorized (about half the fill of an LU), with METIS nested
    dissection, symmetric weighted matching and scaling (PARDISO's recommended setting for
    saddle-point systems; without them the nu = 0.5 system fails) and 1e-8 pivot perturbation.
    Iterative refinement is off, so a solve with k right-hand sides costs k triangular solves;
    :func:`factorize` checks the backward error once instead.

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
