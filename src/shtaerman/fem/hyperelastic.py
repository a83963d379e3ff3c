"""Axisymmetric finite-strain neo-Hookean solid: total Lagrangian, mixed u-p (Taylor-Hood P2-P1).

Conventions as in :mod:`.elasticity` (SI; mesh x = R, y = Z <= 0 in the reference
configuration; u_z < 0 into the body; every integral carries the ring weight 2 pi R, so forces
are in N and energies in J; the pressure unknown p is positive in compression). The
deformation gradient is the 5-vector F = (F_rR, F_rZ, F_zR, F_zZ, F_tt) = (a, b, c, d, h), and

    Psi(F, p) = mu/2 (J^(-2/3) I1 - 3) - p (J - 1) - p^2 / (2 K),

mu = E / (2 (1 + nu)), K = E / (3 (1 - 2 nu)) (1/K = 0 at nu = 0.5). The kinematics, the
hand-derived stress and tangent (checked against finite differences in the tests) and the
Cauchy stress: benchmarks/FEM_NOTES.md, "Moved from the docstrings", fem/hyperelastic.py."""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass, field
from functools import cached_property, partial
from typing import ClassVar

import numpy as np
import scipy.sparse as sp
from skfem import (
    Basis,
    DiscreteField,
    ElementTriP1,
    ElementTriP2,
    ElementVector,
    LinearForm,
    MeshTri,
    asm,
)

from ..validation import NumericalFailureError, validate_poisson, validate_positive
from .elasticity import TWO_PI, scalar_mass
from .solver import Pattern, factorize, pattern_of

__all__ = [
    "HyperelasticSystem",
    "Kinematics",
    "NeoHookean",
    "NewtonError",
    "assemble_hyperelastic",
    "deformation",
    "kinematics",
    "variation",
]

N_COMPONENTS = 5
"""(F_rR, F_rZ, F_zR, F_zZ, F_tt)."""


@dataclass(frozen=True)
class NeoHookean:
    """Compressible (or incompressible) neo-Hookean material, isochoric/volumetric split.

    Parameters
    ----------
    youngs_modulus : float
        Small-strain Young's modulus E in Pa.
    poisson_ratio : float
        Small-strain Poisson's ratio nu in (-1, 0.5]; 0.5 is exactly incompressible.
    """

    youngs_modulus: float
    poisson_ratio: float
    model: ClassVar[str] = "neo-hookean"  # as a :class:`.rubber.Rubber` names its model

    def __post_init__(self) -> None:
        validate_positive("youngs_modulus", self.youngs_modulus, "Pa")
        validate_poisson("poisson_ratio", self.poisson_ratio)

    @property
    def shear_modulus(self) -> float:
        """mu = E / (2 (1 + nu)) in Pa."""
        return self.youngs_modulus / (2.0 * (1.0 + self.poisson_ratio))

    @property
    def inverse_bulk(self) -> float:
        """1/K = 3 (1 - 2 nu) / E in 1/Pa (0 when incompressible)."""
        return 3.0 * (1.0 - 2.0 * self.poisson_ratio) / self.youngs_modulus


def variation(v: DiscreteField, radius: np.ndarray) -> tuple[np.ndarray, ...]:
    """dF(v) = (dv_r/dR, dv_r/dZ, dv_z/dR, dv_z/dZ, v_r/R) of a vector field v (R in m)."""
    return (v.grad[0, 0], v.grad[0, 1], v.grad[1, 0], v.grad[1, 1], v[0] / radius)


@dataclass(frozen=True)
class Kinematics:
    """Deformation and material response at the quadrature points (arrays (elements, points)).

    Attributes
    ----------
    F : numpy.ndarray
        (5, ...) entries (a, b, c, d, h) of the deformation gradient.
    J : numpy.ndarray
        det F.
    stress : numpy.ndarray
        (5, ...) first Piola-Kirchhoff entries S_k = dPsi/dF_k in Pa.
    tangent : numpy.ndarray
        (..., 5, 5) D_kl = d2Psi/dF_k dF_l in Pa (components last: the element matrices are
        batched matrix products over the points); made by ``make_tangent`` when first asked
        (a modified Newton step, a residual or an energy needs none).
    volume_gradient : numpy.ndarray
        (5, ...) Jg_k = dJ/dF_k.
    constraint : numpy.ndarray
        J - 1 + p/K (zero where the pressure equation holds pointwise).
    energy_density : numpy.ndarray
        Psi in J/m^3, made by ``make_energy`` when first asked (only converged states need it).
    """

    F: np.ndarray
    J: np.ndarray
    stress: np.ndarray
    make_tangent: Callable[[], np.ndarray] = field(repr=False)
    volume_gradient: np.ndarray
    constraint: np.ndarray
    make_energy: Callable[[], np.ndarray] = field(repr=False)

    @cached_property
    def tangent(self) -> np.ndarray:
        """D (Pa, (..., 5, 5)), made once."""
        return self.make_tangent()

    @cached_property
    def energy_density(self) -> np.ndarray:
        """Psi (J/m^3), made once."""
        return self.make_energy()


def kinematics(
    material: NeoHookean, grad: np.ndarray, u_r: np.ndarray, radius: np.ndarray, p: np.ndarray
) -> Kinematics:
    """Evaluate F, J, the stress and the consistent tangent pointwise.

    Parameters
    ----------
    material : NeoHookean
    grad : numpy.ndarray
        (2, 2, ...) displacement gradient du_i/dX_j (dimensionless).
    u_r : numpy.ndarray
        Radial displacement in m.
    radius : numpy.ndarray
        Reference radius R in m (> 0 at quadrature points).
    p : numpy.ndarray
        Pressure unknown in Pa (compression positive).

    Returns
    -------
    Kinematics
    """
    if getattr(material, "uses_invariants", False):  # a rubber model beyond neo-Hookean
        return material.kinematics(grad, u_r, radius, p)
    mu, inverse_bulk = material.shear_modulus, material.inverse_bulk
    F, J, Jg, eta, planar_m1, J_m1 = deformation(grad, u_r, radius)
    I1 = np.sum(F**2, axis=0)
    alpha, b, c, delta = grad[0, 0], grad[0, 1], grad[1, 0], grad[1, 1]
    I1_m3 = 2.0 * (alpha + delta + eta) + alpha**2 + b**2 + c**2 + delta**2 + eta**2
    with np.errstate(divide="ignore", invalid="ignore"):  # J <= 0 is caught by the caller
        j23 = np.abs(J) ** (-2.0 / 3.0)
    j53, j83 = j23 / J, j23 / J**2
    # mu J^(-2/3) (F - I1/(3J) Jg), its O(1) parts cancelled by hand (see deviatoric_direction)
    stress = mu * j23 * deviatoric_direction(grad, eta, planar_m1, I1_m3 - 3.0 * J_m1, J, Jg)
    stress -= p * Jg
    # D = mu/2 (10/9 J^(-8/3) I1 Jg Jg^T - 2/3 J^(-5/3) (I1 H + 2 (Jg F^T + F Jg^T))
    #     + 2 J^(-2/3) 1) - p H, collected by term
    terms = {
        "outer": (5.0 / 9.0) * mu * j83 * I1,
        "mixed": -(2.0 / 3.0) * mu * j53,
        "identity": mu * j23,
        "hessian": -(1.0 / 3.0) * mu * j53 * I1 - p,
    }

    def energy() -> np.ndarray:
        isochoric = j23 * invariant_excess(grad, eta, J_m1)  # J^(-2/3) I1 - 3
        return 0.5 * mu * isochoric - p * J_m1 - 0.5 * inverse_bulk * p**2

    return Kinematics(
        F=F,
        J=J,
        stress=stress,
        make_tangent=partial(_tangent, F, Jg, **terms),
        volume_gradient=Jg,
        constraint=J_m1 + inverse_bulk * p,
        make_energy=energy,
    )


def deformation(grad: np.ndarray, u_r: np.ndarray, radius: np.ndarray) -> tuple[np.ndarray, ...]:
    """F (5-vector), J, Jg = dJ/dF, eta = u_r/R, the in-plane determinant minus 1 and J - 1
    (the last two without cancellation) from the displacement gradient (dimensionless), u_r
    and R (m), as :func:`kinematics` takes them."""
    alpha, b, c, delta = grad[0, 0], grad[0, 1], grad[1, 0], grad[1, 1]
    eta = u_r / radius
    a, d, h = 1.0 + alpha, 1.0 + delta, 1.0 + eta
    planar = a * d - b * c
    Jg = np.stack([h * d, -h * c, -h * b, h * a, planar])
    planar_m1 = alpha + delta + alpha * delta - b * c
    J_m1 = eta + planar_m1 + eta * planar_m1
    return np.stack([a, b, c, d, h]), h * planar, Jg, eta, planar_m1, J_m1


SERIES_BOUND = 0.01
"""Below this |y| :func:`power_excess` sums its series (10 terms: 1e-20 of the last kept)."""


def power_excess(y: np.ndarray, k: float) -> np.ndarray:
    """(1 + y)^k - 1 - k y, O(y^2), without cancellation: its binomial series (Horner, in
    place) for |y| < :data:`SERIES_BOUND`, else expm1(k log1p(y)) - k y (nan for y <= -1)."""
    coefficients = [k * (k - 1.0) / 2.0]  # of y^2, y^3, ..., y^11
    for m in range(2, 11):
        coefficients.append(coefficients[-1] * (k - m) / (m + 1.0))
    excess = np.full_like(y, coefficients[-1])
    for coefficient in reversed(coefficients[:-1]):
        excess *= y
        excess += coefficient
    excess *= y * y
    large = np.abs(y) >= SERIES_BOUND  # few points: the contact's
    if large.any():
        with np.errstate(divide="ignore", invalid="ignore"):
            excess[large] = np.expm1(k * np.log1p(y[large])) - k * y[large]
    return excess


def invariant_excess(grad: np.ndarray, eta: np.ndarray, J_m1: np.ndarray) -> np.ndarray:
    """I1 - 3 J^(2/3) (= J^(2/3) (I1bar - 3), second order in the strain) from the displacement
    gradient, without the first-order cancellation of I1 - 3 against 3 (J^(2/3) - 1): the
    second-order terms of I1 - 2 J written out, less 3 :func:`power_excess` (J - 1, 2/3)."""
    alpha, b, c, delta = grad[0, 0], grad[0, 1], grad[1, 0], grad[1, 1]
    planar_2 = alpha * delta - b * c
    squares = alpha**2 + b**2 + c**2 + delta**2 + eta**2
    poly = squares - 2.0 * planar_2 - 2.0 * eta * (alpha + delta + planar_2)
    return poly - 3.0 * power_excess(J_m1, 2.0 / 3.0)


def deviatoric_direction(
    grad: np.ndarray,
    eta: np.ndarray,
    planar_m1: np.ndarray,
    invariant_excess: np.ndarray,
    J: np.ndarray,
    Jg: np.ndarray,
) -> np.ndarray:
    """F - I/(3J) Jg (5-vector; = dIbar/dF / (2 J^(-2/3)) for I = I1) from the displacement
    gradient, without cancellation.

    F and Jg are the identity's (1, 0, 0, 1, 1) plus O(strain) and I/J is 3 plus O(strain):
    written as F - Jg - (s/3) Jg with s = (I - 3J)/J (``invariant_excess`` I - 3J), every term
    is of the strain's order, so the stress keeps its relative accuracy at any strain (the
    plain form loses eps/strain, which the huge far-field elements amplify into the contact
    force). ``eta`` is u_r/R, ``planar_m1`` the in-plane determinant minus 1, J and Jg as in
    :func:`kinematics`.
    """
    alpha, b, c, delta = grad[0, 0], grad[0, 1], grad[1, 0], grad[1, 1]
    h = 1.0 + eta
    excess = np.stack(
        [
            alpha - eta - delta - eta * delta,  # a - h d
            b + h * c,
            c + h * b,
            delta - eta - alpha - eta * alpha,  # d - h a
            eta - planar_m1,  # h - (a d - b c)
        ]
    )
    return excess - (invariant_excess / (3.0 * J)) * Jg


HESSIAN_TERMS = (
    (0, 3, 1.0, 4),  # H_ad = h
    (1, 2, -1.0, 4),  # H_bc = -h
    (0, 4, 1.0, 3),  # H_ah = d
    (3, 4, 1.0, 0),  # H_dh = a
    (1, 4, -1.0, 2),  # H_bh = -c
    (2, 4, -1.0, 1),  # H_ch = -b
)
"""The nonzero entries of H = d2J/dF2 above the diagonal, (k, m, sign, f): H_km = H_mk =
sign F_f, with F = (a, b, c, d, h)."""


def _tangent(
    F: np.ndarray,
    Jg: np.ndarray,
    *,
    outer: np.ndarray,
    mixed: np.ndarray,
    identity: np.ndarray,
    hessian: np.ndarray,
) -> np.ndarray:
    """(..., 5, 5) outer Jg Jg^T + mixed (Jg F^T + F Jg^T) + identity 1 + hessian H (Pa),
    built components first (the upper triangle, mirrored) and moved to components last."""
    tangent = np.empty((N_COMPONENTS, N_COMPONENTS, *F.shape[1:]))
    row = [outer * Jg[k] + mixed * F[k] for k in range(N_COMPONENTS)]
    scaled = [mixed * F[k] for k in range(N_COMPONENTS)]
    for k in range(N_COMPONENTS):
        for m in range(k, N_COMPONENTS):
            np.multiply(Jg[k], row[m], out=tangent[k, m])
            tangent[k, m] += scaled[k] * Jg[m]
        tangent[k, k] += identity
    for k, m, sign, f in HESSIAN_TERMS:
        tangent[k, m] += sign * hessian * F[f]
    for k in range(N_COMPONENTS):
        for m in range(k + 1, N_COMPONENTS):
            tangent[m, k] = tangent[k, m]
    return np.ascontiguousarray(np.moveaxis(tangent, (0, 1), (-2, -1)))


# ------------------------------------------------------------------------ element arrays
# Newton assembles the same integrals at every iteration with a new state: everything of the
# mesh (basis gradients, quadrature weights, the sparsity pattern) is computed once, and an
# assembly is a few batched matrix products and one np.bincount (faster than skfem's forms,
# evaluated pair of basis functions by pair, and a COO -> CSR sort per assembly). A state and a
# residual are one sparse product each with the mesh's map of the dofs to the point values
# (half the work of the element arrays: each vector basis function moves one component).


@dataclass(frozen=True, eq=False)
class _Quadrature:
    """The mesh's part of the integrals, arrays over elements e and quadrature points q.

    Attributes
    ----------
    variation : numpy.ndarray
        (E, Q, 5, 12) dF(v) of each local displacement basis function v (1/m).
    pressure : numpy.ndarray
        (E, Q, 3) the P1 basis functions.
    radius : numpy.ndarray
        (E, Q) reference radius R in m.
    weight : numpy.ndarray
        (E, Q) 2 pi R times the quadrature weight times |det J|, in m^3.
    dofs : numpy.ndarray
        (E, 15) global dofs of each element: 12 displacement, then 3 pressure (offset by the
        number of displacement dofs).
    points : scipy.sparse.csr_matrix
        (6 E Q, dofs) the values at the points of x = [u, p], rows (component, e, q) for the
        components (du_r/dR, du_r/dZ, du_z/dR, du_z/dZ, u_r, p): a state is one product.
    points_transpose : scipy.sparse.csr_matrix
        Its transpose: a residual is one product (no gather, no scatter).
    """

    variation: np.ndarray
    pressure: np.ndarray
    radius: np.ndarray
    weight: np.ndarray
    dofs: np.ndarray
    points: sp.csr_matrix
    points_transpose: sp.csr_matrix

    @property
    def stacked(self) -> np.ndarray:
        """(E, Q * 5, 12) view of :attr:`variation`: the points' rows stacked per element."""
        n_elements, n_points, _, n_local = self.variation.shape
        return self.variation.reshape(n_elements, n_points * N_COMPONENTS, n_local)


def _quadrature(ubasis: Basis, pbasis: Basis) -> _Quadrature:
    radius = np.asarray(ubasis.global_coordinates())[0]
    fields = [ubasis.basis[i][0] for i in range(ubasis.Nbfun)]
    dF = np.array([variation(v, radius) for v in fields])  # (12, 5, E, Q)
    radial = np.array([np.asarray(v)[0] for v in fields])  # (12, E, Q)
    pressure = np.array([np.asarray(pbasis.basis[a][0]) for a in range(pbasis.Nbfun)])
    dofs = np.vstack([ubasis.element_dofs, pbasis.element_dofs + ubasis.N]).T
    points = _point_map(dF[:, :4], radial, pressure, dofs, ubasis.N + pbasis.N)
    return _Quadrature(
        variation=np.ascontiguousarray(dF.transpose(2, 3, 1, 0)),
        pressure=np.ascontiguousarray(pressure.transpose(1, 2, 0)),
        radius=radius,
        weight=TWO_PI * radius * ubasis.dx,
        dofs=dofs,
        points=points,
        points_transpose=points.T.tocsr(),
    )


def _point_map(
    gradient: np.ndarray, radial: np.ndarray, pressure: np.ndarray, dofs: np.ndarray, size: int
) -> sp.csr_matrix:
    """(6 E Q, size) sparse map of the element dofs to the point values (see
    :attr:`_Quadrature.points`) from the local basis' gradient (12, 4, E, Q, 1/m), radial
    value (12, E, Q) and pressure basis (3, E, Q); the zeros of the vector basis (each
    function moves one component) are dropped."""
    n_u, _, n_elements, n_points = gradient.shape
    values = np.zeros((6, n_elements, n_points, dofs.shape[1]))
    values[:4, ..., :n_u] = gradient.transpose(1, 2, 3, 0)
    values[4, ..., :n_u] = radial.transpose(1, 2, 0)
    values[5, ..., n_u:] = pressure.transpose(1, 2, 0)
    rows = np.broadcast_to(
        np.arange(values[..., 0].size).reshape(values.shape[:-1])[..., None], values.shape
    )
    columns = np.broadcast_to(dofs[None, :, None, :], values.shape)
    keep = values != 0.0
    return sp.csr_matrix(
        (values[keep], (rows[keep], columns[keep])), shape=(values[..., 0].size, size)
    )


def _element_matrices(q: _Quadrature, state: Kinematics) -> np.ndarray:
    """(E, 12 * 12 + 2 * 3 * 12) the element blocks int dF(v) : D : dF(u) and -int q Jg : dF(v)
    (the latter twice, for both off-diagonal blocks), flat in the order of
    :func:`_split_where` (the pressure block is constant: the caller adds it)."""
    b = q.stacked
    stiffness_b = ((q.weight[..., None, None] * state.tangent) @ q.variation).reshape(b.shape)
    volume = q.weight[..., None] * np.moveaxis(state.volume_gradient, 0, -1)
    volume_b = (volume[:, :, None, :] @ q.variation)[:, :, 0, :]  # (E, Q, 12)
    coupling = (-q.pressure.transpose(0, 2, 1) @ volume_b).reshape(b.shape[0], -1)
    stiffness = (b.transpose(0, 2, 1) @ stiffness_b).reshape(b.shape[0], -1)
    return np.concatenate([stiffness, coupling, coupling], axis=1)


def _split_where(where: np.ndarray, n_u: int) -> np.ndarray:
    """The entries of ``where`` (E, 15, 15) that :func:`_element_matrices` gives, in its
    order: the displacement block, the (pressure, displacement) block and the (displacement,
    pressure) block transposed."""
    return np.concatenate(
        [
            where[:, :n_u, :n_u].reshape(len(where), -1),
            where[:, n_u:, :n_u].reshape(len(where), -1),
            where[:, :n_u, n_u:].transpose(0, 2, 1).reshape(len(where), -1),
        ],
        axis=1,
    ).ravel()


def _pressure_compliance(q: _Quadrature, inverse_bulk: float) -> np.ndarray:
    """(E, 15, 15) element blocks of d2Pi/dp2 = -int p q / K 2 pi R dA (pressure block only)."""
    n_elements, n_local = q.dofs.shape
    n_u = n_local - q.pressure.shape[-1]
    block = np.zeros((n_elements, n_local, n_local))
    weighted = -inverse_bulk * q.weight[..., None] * q.pressure
    block[:, n_u:, n_u:] = weighted.transpose(0, 2, 1) @ q.pressure
    return block


@dataclass(frozen=True, eq=False)
class HyperelasticSystem:
    """Mixed P2-P1 discretization of an axisymmetric neo-Hookean body.

    Attributes
    ----------
    mesh : skfem.MeshTri
        Reference configuration (x = R >= 0, y = Z, m).
    material : NeoHookean
    displacement_basis, pressure_basis : skfem.Basis
        P2 vector and P1 scalar bases sharing one quadrature.
    pattern : Pattern
        Sparsity of the tangent over all dofs (element connectivity; fixed).
    """

    mesh: MeshTri
    material: NeoHookean
    displacement_basis: Basis
    pressure_basis: Basis
    pattern: Pattern
    _quadrature: _Quadrature = field(repr=False)
    _where: np.ndarray = field(repr=False)
    """Index in the tangent's data of each entry of :func:`_element_matrices`."""
    _compliance: np.ndarray = field(repr=False)
    """The constant pressure block -int p q / K 2 pi R dA as tangent data."""

    @property
    def n_displacement(self) -> int:
        """Number of displacement dofs (first block of x = [u, p])."""
        return self.displacement_basis.N

    @property
    def n_dofs(self) -> int:
        """Total number of dofs."""
        return self.displacement_basis.N + self.pressure_basis.N

    def split(self, x: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """Views (u in m, p in Pa) of a full vector."""
        return x[: self.n_displacement], x[self.n_displacement :]

    def state(self, x: np.ndarray) -> Kinematics:
        """Kinematics of x = [u, p] at the quadrature points."""
        q = self._quadrature
        values = (q.points @ x).reshape(6, *q.weight.shape)
        return kinematics(
            self.material, values[:4].reshape(2, 2, *q.weight.shape), values[4], q.radius, values[5]
        )

    def residual(self, x: np.ndarray, state: Kinematics | None = None) -> np.ndarray:
        """Gradient dPi/dx: internal nodal forces (N) and the pressure equation (m^3).

        dPi/du . v = int S : dF(v) 2 pi R dA, dPi/dp . q = -int q (J - 1 + p/K) 2 pi R dA.
        """
        state = self.state(x) if state is None else state
        q = self._quadrature
        weighted = np.empty((6, *q.weight.shape))
        np.multiply(q.weight, state.stress[:4], out=weighted[:4])
        weighted[4] = q.weight * state.stress[4] / q.radius  # u_r's row: v_r, not v_r / R
        weighted[5] = -q.weight * state.constraint
        return q.points_transpose @ weighted.ravel()

    def tangent_data(self, x: np.ndarray, state: Kinematics | None = None) -> np.ndarray:
        """The consistent tangent d2Pi/dx2 as the data of :attr:`pattern` (see :meth:`tangent`)."""
        state = self.state(x) if state is None else state
        blocks = _element_matrices(self._quadrature, state)
        return np.bincount(self._where, weights=blocks.ravel(), minlength=self.pattern.nnz) + (
            self._compliance
        )

    def tangent(self, x: np.ndarray, state: Kinematics | None = None) -> sp.csc_matrix:
        """Consistent tangent d2Pi/dx2 (symmetric indefinite), in N/m, m^2 and m^3/Pa blocks.

        [[int dF(v) : D : dF(u), -int q Jg : dF(u)], [-int q Jg : dF(v), -int p q / K]], all
        with the ring weight 2 pi R dA: material and geometric stiffness, volume coupling and
        pressure compliance.
        """
        return self.pattern.matrix(self.tangent_data(x, state))

    def energy(self, x: np.ndarray, state: Kinematics | None = None) -> float:
        """Pi(u, p) = int Psi 2 pi R dA in J: the stored strain energy at a solution."""
        state = self.state(x) if state is None else state
        return float(np.sum(self._quadrature.weight * state.energy_density))

    def cauchy_stress(self, x: np.ndarray) -> dict[str, np.ndarray]:
        """Cauchy stress (Pa, tension positive) and von Mises at the vertices, deformed state.

        sigma = P F^T / J at the quadrature points, projected (L2, reference dR dZ) onto
        continuous P1. Keys ``sigma_rr``, ``sigma_tt``, ``sigma_zz``, ``sigma_rz``,
        ``von_mises``.
        """
        state = self.state(x)
        S, F = state.stress, state.F
        components = {
            "sigma_rr": (S[0] * F[0] + S[1] * F[1]) / state.J,
            "sigma_tt": S[4] * F[4] / state.J,
            "sigma_zz": (S[2] * F[2] + S[3] * F[3]) / state.J,
            "sigma_rz": (S[0] * F[2] + S[1] * F[3]) / state.J,
        }
        rhs = np.column_stack(
            [asm(_projection, self.pressure_basis, s=value) for value in components.values()]
        )
        values = factorize(asm(scalar_mass, self.pressure_basis), backend="superlu").solve(rhs)
        nodal = self.pressure_basis.nodal_dofs[0]
        out = {name: values[nodal, k] for k, name in enumerate(components)}
        rr, tt, zz, rz = (out[k] for k in components)
        out["von_mises"] = np.sqrt(
            0.5 * ((rr - zz) ** 2 + (zz - tt) ** 2 + (tt - rr) ** 2) + 3.0 * rz**2
        )
        return out

    def fields(self, x: np.ndarray) -> dict[str, np.ndarray]:
        """Vertex fields of the deformed state ``x`` for export (SI): ``r``, ``z`` (reference
        vertex coordinates, m), ``u_r``, ``u_z`` (m), ``mean_pressure`` (the P1 pressure
        unknown, Pa) and those of :meth:`cauchy_stress` (Pa)."""
        u_r, u_z = self.vertex_displacement(x)
        _, p = self.split(x)
        return {
            "r": self.mesh.p[0],
            "z": self.mesh.p[1],
            "u_r": u_r,
            "u_z": u_z,
            "mean_pressure": p[self.pressure_basis.nodal_dofs[0]],
            **self.cauchy_stress(x),
        }

    def vertex_displacement(self, x: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """(u_r, u_z) in m at the mesh vertices."""
        u, _ = self.split(x)
        nodal = self.displacement_basis.nodal_dofs
        return u[nodal[0]], u[nodal[1]]


@LinearForm
def _projection(v, w):
    return np.asarray(w.s) * v


def assemble_hyperelastic(mesh: MeshTri, material: NeoHookean) -> HyperelasticSystem:
    """Bases and constant blocks of the mixed neo-Hookean system on ``mesh``.

    Parameters
    ----------
    mesh : skfem.MeshTri
        Reference configuration, x = R >= 0 (m).
    material : NeoHookean

    Returns
    -------
    HyperelasticSystem
    """
    ubasis = Basis(mesh, ElementVector(ElementTriP2()))
    pbasis = ubasis.with_element(ElementTriP1())
    quadrature = _quadrature(ubasis, pbasis)
    dofs = quadrature.dofs
    pattern, where = pattern_of(
        np.broadcast_to(dofs[:, :, None], (*dofs.shape, dofs.shape[1])),
        np.broadcast_to(dofs[:, None, :], (*dofs.shape, dofs.shape[1])),
        ubasis.N + pbasis.N,
    )
    compliance = np.bincount(
        where,
        weights=_pressure_compliance(quadrature, material.inverse_bulk).ravel(),
        minlength=pattern.nnz,
    )
    where = _split_where(where.reshape(dofs.shape[0], *dofs.shape[1:], -1), ubasis.Nbfun)
    return HyperelasticSystem(
        mesh, material, ubasis, pbasis, pattern, quadrature, where, compliance
    )


class NewtonError(NumericalFailureError):
    """Newton's method failed (no convergence, inverted element): a one-line message.

    A numerical failure on valid input, not bad input: the CLI reports it as one line (exit 1).
    """
