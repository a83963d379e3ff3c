"""A fixed sparsity pattern: repeated assemblies fill the ``data`` of one CSC matrix.

Newton's method assembles the same element connectivity at every iteration. scipy's COO to
CSR/CSC conversion sorts the element entries every time. Here the sort is done once:
:func:`pattern_of` returns the pattern and, for every element entry, its index in ``data``;
an assembly is then one ``np.bincount``. Submatrices (free dofs), symmetric permutations (a
fill-reducing ordering) and transposes become fixed gathers of ``data`` too.
"""

from __future__ import annotations

from dataclasses import dataclass
from functools import cached_property

import numpy as np
import scipy.sparse as sp

__all__ = ["Pattern", "pattern_of"]


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
