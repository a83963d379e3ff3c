"""Axisymmetric finite-strain neo-Hookean solid: total Lagrangian, mixed u-p (Taylor-Hood P2-P1).

Conventions as in :mod:`.elasticity` (SI; mesh x = R, y = Z <= 0 in the reference
configuration; u_z < 0 into the body; every integral carries the ring weight 2 pi R, so forces
are in N and energies in J; the pressure unknown p is positive in compression).

Kinematics
----------
With u = (u_r, u_z) the deformation gradient in (r, theta, z) has five nonzero entries,
ordered here as F = (F_rR, F_rZ, F_zR, F_zZ, F_tt) = (a, b, c, d, h):

    a = 1 + du_r/dR,  b = du_r/dZ,  c = du_z/dR,  d = 1 + du_z/dZ,  h = 1 + u_r/R  (hoop),

J = h (a d - b c), I1 = a^2 + b^2 + c^2 + d^2 + h^2. The variation of F along a field v is
dF(v) = (dv_r/dR, dv_r/dZ, dv_z/dR, dv_z/dZ, v_r/R).

Material (isochoric/volumetric split, mixed)
--------------------------------------------
    Psi(F, p) = mu/2 (J^(-2/3) I1 - 3) - p (J - 1) - p^2 / (2 K),

mu = E / (2 (1 + nu)), K = E / (3 (1 - 2 nu)) (1/K = 0 at nu = 0.5, exactly incompressible).
Stationarity in p gives p = -K (J - 1), and Psi = mu/2 (J^(-2/3) I1 - 3) + K/2 (J - 1)^2: the
compressible neo-Hookean solid whose small-strain limit is linear elasticity with E, nu, and
whose p is the linear code's pressure -K div u to first order. The discrete problem is
stationarity of Pi(u, p) = int Psi 2 pi R dA: internal forces dPi/du, the pressure equation
dPi/dp = -int q (J - 1 + p/K) 2 pi R dA = 0. At a solution, Pi is the stored strain energy
(at nu = 0.5 the P1 constraint makes int p (J - 1) vanish, so Pi = int mu/2 (I1bar - 3)).

Derivatives (hand-derived; checked against finite differences in the tests), with
Jg = dJ/dF = (h d, -h c, -h b, h a, a d - b c) and H = d2J/dF2 (nonzero: H_ad = h, H_bc = -h,
H_ah = d, H_dh = a, H_bh = -c, H_ch = -b, symmetric):

    S_k   = dPsi/dF_k = mu/2 (2 J^(-2/3) F_k - 2/3 J^(-5/3) I1 Jg_k) - p Jg_k   (first PK)
    D_kl  = d2Psi/dF_k dF_l = mu/2 (10/9 J^(-8/3) I1 Jg_k Jg_l
            - 2/3 J^(-5/3) (I1 H_kl + 2 Jg_k F_l + 2 F_k Jg_l) + 2 J^(-2/3) delta_kl) - p H_kl
    d2Psi/dF_k dp = -Jg_k,   d2Psi/dp2 = -1/K.

The Cauchy stress is sigma = P F^T / J with P the 3x3 first Piola-Kirchhoff stress
[[S_a, 0, S_b], [0, S_h, 0], [S_c, 0, S_d]].
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
import scipy.sparse as sp
from skfem import (
    Basis,
    BilinearForm,
    DiscreteField,
    ElementTriP1,
    ElementTriP2,
    ElementVector,
    Functional,
    LinearForm,
    MeshTri,
    asm,
)

from ..validation import InputError, validate_poisson, validate_positive
from .solver import factorize

__all__ = [
    "HyperelasticSystem",
    "Kinematics",
    "NeoHookean",
    "NewtonError",
    "NewtonResult",
    "assemble_hyperelastic",
    "kinematics",
    "solve_dirichlet",
    "variation",
]

TWO_PI = 2.0 * math.pi
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
        (5, 5, ...) D_kl = d2Psi/dF_k dF_l in Pa.
    volume_gradient : numpy.ndarray
        (5, ...) Jg_k = dJ/dF_k.
    constraint : numpy.ndarray
        J - 1 + p/K (zero where the pressure equation holds pointwise).
    energy_density : numpy.ndarray
        Psi in J/m^3.
    """

    F: np.ndarray
    J: np.ndarray
    stress: np.ndarray
    tangent: np.ndarray
    volume_gradient: np.ndarray
    constraint: np.ndarray
    energy_density: np.ndarray


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
    mu, inverse_bulk = material.shear_modulus, material.inverse_bulk
    a, b = 1.0 + grad[0, 0], grad[0, 1]
    c, d = grad[1, 0], 1.0 + grad[1, 1]
    h = 1.0 + u_r / radius
    F = np.stack([a, b, c, d, h])
    planar = a * d - b * c
    J = h * planar
    Jg = np.stack([h * d, -h * c, -h * b, h * a, planar])
    zero = np.zeros_like(a)
    H = np.array(
        [
            [zero, zero, zero, h, d],
            [zero, zero, -h, zero, -c],
            [zero, -h, zero, zero, -b],
            [h, zero, zero, zero, a],
            [d, -c, -b, a, zero],
        ]
    )
    I1 = np.sum(F**2, axis=0)
    # J - 1 and I1 - 3 from the displacement gradient, without cancellation: the energy of
    # the huge far-field elements would otherwise carry round-off of order eps mu R^3
    alpha, delta, eta = grad[0, 0], grad[1, 1], u_r / radius
    planar_m1 = alpha + delta + alpha * delta - b * c
    J_m1 = eta + planar_m1 + eta * planar_m1
    I1_m3 = 2.0 * (alpha + delta + eta) + alpha**2 + b**2 + c**2 + delta**2 + eta**2
    with np.errstate(divide="ignore", invalid="ignore"):  # J <= 0 is caught by the caller
        j23 = np.abs(J) ** (-2.0 / 3.0)
        j23_m1 = np.expm1(-(2.0 / 3.0) * np.log1p(J_m1))
    j53, j83 = j23 / J, j23 / J**2
    stress = 0.5 * mu * (2.0 * j23 * F - (2.0 / 3.0) * j53 * I1 * Jg) - p * Jg
    outer_jj = Jg[:, None] * Jg[None, :]
    mixed = Jg[:, None] * F[None, :] + F[:, None] * Jg[None, :]
    identity = np.eye(N_COMPONENTS).reshape(N_COMPONENTS, N_COMPONENTS, *([1] * a.ndim))
    tangent = (
        0.5
        * mu
        * (
            (10.0 / 9.0) * j83 * I1 * outer_jj
            - (2.0 / 3.0) * j53 * (I1 * H + 2.0 * mixed)
            + 2.0 * j23 * identity
        )
        - p * H
    )
    isochoric = j23_m1 * I1 + I1_m3  # J^(-2/3) I1 - 3
    energy = 0.5 * mu * isochoric - p * J_m1 - 0.5 * inverse_bulk * p**2
    return Kinematics(
        F=F,
        J=J,
        stress=stress,
        tangent=tangent,
        volume_gradient=Jg,
        constraint=J_m1 + inverse_bulk * p,
        energy_density=energy,
    )


# ---------------------------------------------------------------------------- weak forms
# The state enters through precomputed quadrature arrays (w.S, w.D, w.Jg, w.C, w.psi), so
# the material is evaluated once per Newton iteration, not once per pair of basis functions.


@LinearForm
def internal_force(v, w):
    """dPi/du . v = int S : dF(v) 2 pi R dA (N per m of v)."""
    r = w.x[0]
    dv = variation(v, r)
    S = np.asarray(w.S)
    return TWO_PI * r * sum(S[k] * dv[k] for k in range(N_COMPONENTS))


@LinearForm
def pressure_residual(q, w):
    """dPi/dp . q = -int q (J - 1 + p/K) 2 pi R dA (m^3 per Pa of q)."""
    return -TWO_PI * w.x[0] * np.asarray(w.C) * q


@BilinearForm
def material_tangent(u, v, w):
    """d2Pi/du2 = int dF(v) : D : dF(u) 2 pi R dA (N/m), material and geometric parts."""
    r = w.x[0]
    du, dv = np.array(variation(u, r)), np.array(variation(v, r))
    return TWO_PI * r * np.einsum("k...,km...,m...->...", dv, np.asarray(w.D), du, optimize=False)


@BilinearForm
def volume_coupling(u, q, w):
    """d2Pi/dp du = -int q Jg : dF(u) 2 pi R dA (trial u, test q)."""
    r = w.x[0]
    du = variation(u, r)
    Jg = np.asarray(w.Jg)
    return -TWO_PI * r * q * sum(Jg[k] * du[k] for k in range(N_COMPONENTS))


def pressure_compliance(inverse_bulk: float) -> BilinearForm:
    """d2Pi/dp2 = -int p q / K 2 pi R dA."""

    @BilinearForm
    def form(p, q, w):
        return -TWO_PI * w.x[0] * inverse_bulk * p * q

    return form


@Functional
def stored_energy(w):
    """Pi = int Psi 2 pi R dA in J."""
    return TWO_PI * w.x[0] * np.asarray(w.psi)


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
    pressure_mass : scipy.sparse.csr_matrix or None
        The constant block -int p q / K 2 pi R dA (None when incompressible).
    """

    mesh: MeshTri
    material: NeoHookean
    displacement_basis: Basis
    pressure_basis: Basis
    pressure_mass: sp.csr_matrix | None

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
        u, p = self.split(x)
        ufield = self.displacement_basis.interpolate(u)
        pfield = self.pressure_basis.interpolate(p)
        radius = self.displacement_basis.global_coordinates()[0]
        return kinematics(
            self.material, ufield.grad, np.asarray(ufield)[0], radius, np.asarray(pfield)
        )

    def residual(self, x: np.ndarray, state: Kinematics | None = None) -> np.ndarray:
        """Gradient dPi/dx: internal nodal forces (N) and the pressure equation (m^3)."""
        state = self.state(x) if state is None else state
        return np.concatenate(
            [
                asm(internal_force, self.displacement_basis, S=state.stress),
                asm(pressure_residual, self.pressure_basis, C=state.constraint),
            ]
        )

    def tangent(self, x: np.ndarray, state: Kinematics | None = None) -> sp.csr_matrix:
        """Consistent tangent d2Pi/dx2 (symmetric indefinite)."""
        state = self.state(x) if state is None else state
        stiffness = asm(material_tangent, self.displacement_basis, D=state.tangent)
        coupling = asm(
            volume_coupling,
            self.displacement_basis,
            self.pressure_basis,
            Jg=state.volume_gradient,
        )
        return sp.bmat([[stiffness, coupling.T], [coupling, self.pressure_mass]], format="csr")

    def energy(self, x: np.ndarray, state: Kinematics | None = None) -> float:
        """Pi(u, p) in J: the stored strain energy at a solution."""
        state = self.state(x) if state is None else state
        return float(asm(stored_energy, self.displacement_basis, psi=state.energy_density))

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
        values = factorize(asm(_mass, self.pressure_basis), backend="superlu").solve(rhs)
        nodal = self.pressure_basis.nodal_dofs[0]
        out = {name: values[nodal, k] for k, name in enumerate(components)}
        rr, tt, zz, rz = (out[k] for k in components)
        out["von_mises"] = np.sqrt(
            0.5 * ((rr - zz) ** 2 + (zz - tt) ** 2 + (tt - rr) ** 2) + 3.0 * rz**2
        )
        return out

    def vertex_displacement(self, x: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """(u_r, u_z) in m at the mesh vertices."""
        u, _ = self.split(x)
        nodal = self.displacement_basis.nodal_dofs
        return u[nodal[0]], u[nodal[1]]


@LinearForm
def _projection(v, w):
    return np.asarray(w.s) * v


@BilinearForm
def _mass(u, v, _):
    return u * v


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
    inverse_bulk = material.inverse_bulk
    if inverse_bulk > 0:
        pressure_mass = asm(pressure_compliance(inverse_bulk), pbasis).tocsr()
    else:
        pressure_mass = sp.csr_matrix((pbasis.N, pbasis.N))
    return HyperelasticSystem(mesh, material, ubasis, pbasis, pressure_mass)


@dataclass(frozen=True)
class NewtonResult:
    """A converged Newton solve.

    Attributes
    ----------
    x : numpy.ndarray
        Solution [u (m), p (Pa)].
    residuals : list of float
        Norm of the free residual before each iteration, then at convergence (N and m^3 rows
        mixed: use its decay, not its value).
    """

    x: np.ndarray
    residuals: list[float]


def solve_dirichlet(
    system: HyperelasticSystem,
    dofs: np.ndarray,
    values: np.ndarray | float,
    *,
    x0: np.ndarray | None = None,
    tolerance: float = 1e-11,
    max_iterations: int = 25,
) -> NewtonResult:
    """Newton's method for Pi stationary with prescribed displacement dofs (no contact).

    Parameters
    ----------
    system : HyperelasticSystem
    dofs : numpy.ndarray
        Prescribed displacement dofs.
    values : numpy.ndarray or float
        Their values in m.
    x0 : numpy.ndarray, optional
        Start (default zero).
    tolerance : float
        Converged when the free residual falls below ``tolerance`` times its first nonzero
        value.
    max_iterations : int

    Returns
    -------
    NewtonResult

    Raises
    ------
    NewtonError
        If Newton does not converge or an element inverts.
    """
    x = np.zeros(system.n_dofs) if x0 is None else np.array(x0, dtype=float)
    x[dofs] = values
    free = np.setdiff1d(np.arange(system.n_dofs), dofs)
    history: list[float] = []
    reference = 0.0
    for _ in range(max_iterations + 1):
        state = system.state(x)
        if np.min(state.J) <= 0 or not np.all(np.isfinite(state.J)):
            raise NewtonError("an element inverted (J <= 0); reduce the load step")
        rhs = system.residual(x, state)[free]
        norm = float(np.linalg.norm(rhs))
        history.append(norm)
        reference = reference or norm
        if norm <= tolerance * reference or norm == 0.0:
            return NewtonResult(x, history)
        matrix = system.tangent(x, state)[free][:, free].tocsc()
        x[free] -= factorize(matrix).solve(rhs)
    raise NewtonError(
        f"Newton did not converge in {max_iterations} iterations (residual {history[-1]:.3g})"
    )


class NewtonError(InputError):
    """Newton's method failed (no convergence, inverted element): a one-line message.

    An :class:`~shtaerman.validation.InputError`, so the CLI reports it as one line (exit 2).
    """
