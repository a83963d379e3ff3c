"""Inertia of the axisymmetric half-space: consistent mass, weighted mass, contact redistribution.

Only the P2 displacement carries mass; the P1 pressure of the mixed u-p formulation is a
constraint field with none, so every matrix here has zero pressure rows and columns and the
mixed formulation works unchanged in dynamics (nu = 0.5 included).

Mass redistribution (Khenous, Laborde and Renard 2008, Eur. J. Mech. A 27:918): with a
consistent mass on the contact nodes, implicit Newmark integration of unilateral contact
chatters (the contact dof bounces between steps) and the discrete energy jumps at each
impact. Taking the normal mass off the contact dofs makes their motion quasi-static (their
displacement is fixed by the contact force and the neighbours), the contact force Lipschitz in
time and the scheme free of chatter. The removed mass is a layer of one element on the
candidate zone (about rho pi a^2 h, negligible against the body); it is given back to the u_z
dofs of the same elements so that the total vertical mass is unchanged.
"""

from __future__ import annotations

from collections.abc import Callable

import numpy as np
import scipy.sparse as sp
from skfem import BilinearForm, asm

from .elasticity import TWO_PI, ElasticSystem

__all__ = [
    "consistent_mass",
    "redistribute_normal_mass",
    "total_vertical_mass",
    "weighted_mass",
]


def weighted_mass(
    system: ElasticSystem, weight: Callable[[np.ndarray], np.ndarray]
) -> sp.csr_matrix:
    """Matrix int w(R) u . v 2 pi r dA on the full [u, p] dofs (zero pressure block).

    Parameters
    ----------
    system : ElasticSystem
    weight : callable
        w(r, z), vectorised, e.g. the density (kg/m^3) or density times a damping rate (kg/m^3/s).

    Returns
    -------
    scipy.sparse.csr_matrix
        Size ``system.n_dofs``; units of ``weight`` times m^3.
    """

    @BilinearForm
    def form(u, v, w):
        r = w.x[0]
        return TWO_PI * r * weight(w.x[0], w.x[1]) * (u[0] * v[0] + u[1] * v[1])

    block = asm(form, system.displacement_basis).tocsr()
    n_pressure = system.n_dofs - system.n_displacement
    return sp.block_diag([block, sp.csr_matrix((n_pressure, n_pressure))], format="csr")


def consistent_mass(system: ElasticSystem, density: float) -> sp.csr_matrix:
    """Consistent mass int rho u . v 2 pi r dA in kg (full [u, p] dofs, zero pressure block)."""
    rho = float(density)
    return weighted_mass(system, lambda r, z: np.full_like(r, rho))


def redistribute_normal_mass(mass: sp.csr_matrix, dofs: np.ndarray) -> sp.csr_matrix:
    """Take the mass off ``dofs`` (the contact u_z dofs) and give it back to their neighbours.

    Rows and columns of ``dofs`` are zeroed. The vertical mass they carried,
    1^T M 1 restricted to the u_z dofs, is restored on the diagonal of the u_z dofs coupled to
    them (those sharing an element), in proportion to their diagonal entries, so the total
    vertical mass, and hence the momentum of a rigid vertical motion, is unchanged.

    Parameters
    ----------
    mass : scipy.sparse.csr_matrix
        Consistent mass (kg).
    dofs : numpy.ndarray
        Global indices of the contact u_z dofs.

    Returns
    -------
    scipy.sparse.csr_matrix
        The redistributed mass, symmetric positive semi-definite.
    """
    n = mass.shape[0]
    removed = np.zeros(n, dtype=bool)
    removed[dofs] = True
    keep = sp.diags((~removed).astype(float))
    neighbours = np.zeros(n, dtype=bool)
    neighbours[np.unique(mass[dofs].indices)] = True
    neighbours &= ~removed
    kept = keep @ mass @ keep
    # M has no r-z coupling, so every entry removed lies in u_z rows and columns: their sum is
    # the vertical mass lost, 1^T (M - kept) 1 = 2 (removed rows) - (removed block), summed
    # from those entries (M symmetric): the difference of the two totals would carry the
    # round-off of the whole body's mass, eps M_total / lost (4.5 % of it on a dynamic mesh)
    rows = mass[dofs]
    lost = float(2.0 * rows.sum() - rows[:, dofs].sum())
    diagonal = kept.diagonal() * neighbours
    if lost > 0 and diagonal.sum() > 0:
        kept = kept + sp.diags(lost * diagonal / diagonal.sum())
    return sp.csr_matrix(kept)


def total_vertical_mass(mass: sp.csr_matrix, uz_dofs: np.ndarray) -> float:
    """1^T M 1 over the u_z dofs, in kg: the mass of a rigid vertical translation."""
    ones = np.zeros(mass.shape[0])
    ones[uz_dofs] = 1.0
    return float(ones @ (mass @ ones))
