"""Axisymmetric linear elasticity of the half-space: mixed u-p (Taylor-Hood P2-P1) in scikit-fem.

Conventions (SI: m, Pa, N)
--------------------------
- Mesh coordinates x = r >= 0 and y = z <= 0: z points *up*, out of the body, so a surface
  point pressed into the body has u_z < 0.
- A surface pressure p(r) is positive in compression (it pushes the surface down, traction
  t_z = -p on z = 0). Stresses are positive in tension, so sigma_zz = -p on the loaded surface.
- Every integral carries the full ring weight 2 pi r: the system matrix, load vectors and
  reactions are 3-D quantities, forces in newtons (not "per radian").
- Unknowns x = [u, p]: ``u`` the P2 displacement (scikit-fem ``ElementVector`` numbering,
  components u_r = ``u^1``, u_z = ``u^2``), then ``p`` the P1 mean pressure
  p = -tr(sigma)/3 = -K div u (positive in compression).

Only the P2 displacement carries mass (:func:`consistent_mass`); the normal mass is taken off
the contact candidates (:func:`redistribute_normal_mass`, Khenous, Laborde and Renard 2008).
The weak form and why: benchmarks/FEM_NOTES.md, "Moved from the docstrings",
fem/elasticity.py.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass

import numpy as np
import scipy.sparse as sp
from skfem import (
    Basis,
    BilinearForm,
    ElementTriP1,
    ElementTriP2,
    ElementVector,
    FacetBasis,
    LinearForm,
    MeshTri,
    asm,
)

from ..validation import validate_poisson, validate_positive
from .solver import Factorization, factorize

__all__ = [
    "ElasticSolution",
    "ElasticSystem",
    "assemble",
    "clamped_dofs",
    "compressibility",
    "consistent_mass",
    "deviatoric_stiffness",
    "divergence_coupling",
    "dof_nodes",
    "mixed_matrix",
    "normal_surface_mass",
    "postprocess",
    "pressure_load",
    "redistribute_normal_mass",
    "scalar_mass",
    "solve",
    "weighted_mass",
]

TWO_PI = 2.0 * math.pi
_LOAD_ORDER = 8


def _strain(u, r):
    """Components (e_rr, e_tt, e_zz, e_rz) of the axisymmetric strain of u = (u_r, u_z)."""
    return u.grad[0, 0], u[0] / r, u.grad[1, 1], 0.5 * (u.grad[0, 1] + u.grad[1, 0])


def _divergence(u, r):
    """div u = du_r/dr + u_r/r + du_z/dz."""
    return u.grad[0, 0] + u[0] / r + u.grad[1, 1]


def deviatoric_stiffness(shear_modulus: float) -> BilinearForm:
    """Form int 2 mu dev e(u) : e(v) 2 pi r dA, with mu in Pa."""

    @BilinearForm
    def form(u, v, w):
        r = w.x[0]
        eu, ev = _strain(u, r), _strain(v, r)
        inner = eu[0] * ev[0] + eu[1] * ev[1] + eu[2] * ev[2] + 2.0 * eu[3] * ev[3]
        deviatoric = inner - _divergence(u, r) * _divergence(v, r) / 3.0
        return TWO_PI * r * 2.0 * shear_modulus * deviatoric

    return form


@BilinearForm
def divergence_coupling(u, q, w):
    """Form -int q div u 2 pi r dA (trial u, test q)."""
    r = w.x[0]
    return -TWO_PI * r * q * _divergence(u, r)


def compressibility(inverse_bulk: float) -> BilinearForm:
    """Form -int p q / K 2 pi r dA, with 1/K in 1/Pa (zero when incompressible)."""

    @BilinearForm
    def form(p, q, w):
        return -TWO_PI * w.x[0] * inverse_bulk * p * q

    return form


@BilinearForm
def normal_surface_mass(u, v, w):
    """Form int u_z v_z 2 pi r ds on the surface (m^2 per unit of u_z v_z)."""
    return TWO_PI * w.x[0] * u[1] * v[1]


@dataclass(frozen=True)
class ElasticSystem:
    """Assembled axisymmetric mixed system of an elastic half-space mesh.

    Attributes
    ----------
    mesh : skfem.MeshTri
        The mesh (x = r, y = z, m) with boundaries "axis", "surface", "far".
    displacement_basis, pressure_basis : skfem.Basis
        P2 vector and P1 scalar bases sharing one quadrature.
    youngs_modulus : float
        E in Pa.
    poisson_ratio : float
        nu in (-1, 0.5].
    matrix : scipy.sparse.csr_matrix
        Full symmetric indefinite matrix [[A, B^T], [B, -C]] (no boundary conditions), so that
        ``matrix @ x`` is the nodal force vector in N (displacement rows) for x in m and Pa.
    fixed_dofs : numpy.ndarray
        Clamped dofs: u_r on the axis, u_r and u_z on the far boundary (value 0).
    surface_dofs : numpy.ndarray
        Global indices of the free u_z dofs on z = 0 (P2 vertices and edge midpoints), sorted
        by r; the clamped one at r = R is left out.
    surface_r : numpy.ndarray
        Their radii in m (``surface_r[0] == 0``, the axis).
    surface_mass : scipy.sparse.csr_matrix
        Consistent surface matrix M_ij = int phi_i phi_j 2 pi r dr (m^2) on ``surface_dofs``:
        a pressure with nodal values p (Pa) gives downward nodal forces F = M p (N), i.e.
        ``pressure_load(...)[surface_dofs] == -M p`` for any p that P2 interpolates exactly,
        and nodal forces F give back p = M^-1 F. Use it instead of "force / area": the axis
        node carries almost no area.
    """

    mesh: MeshTri
    displacement_basis: Basis
    pressure_basis: Basis
    youngs_modulus: float
    poisson_ratio: float
    matrix: sp.csr_matrix
    fixed_dofs: np.ndarray
    surface_dofs: np.ndarray
    surface_r: np.ndarray
    surface_mass: sp.csr_matrix

    @property
    def shear_modulus(self) -> float:
        """mu = E / (2 (1 + nu)) in Pa."""
        return self.youngs_modulus / (2.0 * (1.0 + self.poisson_ratio))

    @property
    def n_displacement(self) -> int:
        """Number of displacement dofs (the first block of x)."""
        return self.displacement_basis.N

    @property
    def n_dofs(self) -> int:
        """Total number of dofs (displacement and pressure)."""
        return self.matrix.shape[0]

    def free_dofs(self, prescribed: np.ndarray | None = None) -> np.ndarray:
        """Dofs left free by the clamps and by extra ``prescribed`` dofs, sorted."""
        fixed = self.fixed_dofs if prescribed is None else np.union1d(self.fixed_dofs, prescribed)
        return np.setdiff1d(np.arange(self.n_dofs), fixed)

    def dof_nodes(self) -> np.ndarray:
        """Mesh node of every dof: vertex v -> v, edge midpoint e -> n_vertices + e."""
        return dof_nodes(self.displacement_basis, self.pressure_basis)

    def reduced_matrix(self, free: np.ndarray) -> sp.csc_matrix:
        """The matrix restricted to ``free`` rows and columns (CSC, ready to factorize)."""
        return self.matrix[free][:, free].tocsc()


def dof_nodes(ubasis: Basis, pbasis: Basis) -> np.ndarray:
    """Mesh node of every dof of a P2-P1 pair [u, p]: vertex v -> v, edge midpoint e ->
    n_vertices + e (the groups of a nested-dissection ordering, :mod:`.schur`)."""
    vertices = ubasis.mesh.p.shape[1]
    nodes = np.empty(ubasis.N + pbasis.N, dtype=np.int64)
    nodes[ubasis.nodal_dofs] = np.arange(vertices)
    nodes[ubasis.facet_dofs] = vertices + np.arange(ubasis.facet_dofs.shape[1])
    nodes[ubasis.N + pbasis.nodal_dofs[0]] = np.arange(vertices)
    return nodes


def assemble(mesh: MeshTri, youngs_modulus: float, poisson_ratio: float) -> ElasticSystem:
    """Assemble the mixed axisymmetric system on a half-space mesh.

    Parameters
    ----------
    mesh : skfem.MeshTri
        From :func:`shtaerman.fem.mesh.halfspace_mesh` (boundaries "axis", "surface", "far").
    youngs_modulus : float
        E in Pa, within the FEM's range of :mod:`shtaerman.vocabulary` (the entry points
        check it: beyond it the scaled factorization loses digits).
    poisson_ratio : float
        nu in (-1, 0.5]; 0.5 (incompressible) is exact, not approximated.

    Returns
    -------
    ElasticSystem
    """
    e_mod = validate_positive("youngs_modulus", youngs_modulus, "Pa")
    nu = validate_poisson("poisson_ratio", poisson_ratio)
    ubasis = Basis(mesh, ElementVector(ElementTriP2()))
    pbasis = ubasis.with_element(ElementTriP1())
    exterior = None
    if "base" in mesh.boundaries:  # a layer on a lubricated base: the exterior beyond r = L
        exterior = _exterior_layer(ubasis, e_mod / (2.0 * (1.0 + nu)))
    matrix = mixed_matrix(ubasis, pbasis, e_mod, nu, exterior)
    fixed = clamped_dofs(ubasis)
    # the fields in order: the bases, the moduli, the matrix, the clamped and the surface dofs
    surface = _surface(mesh, ubasis, fixed)
    return ElasticSystem(mesh, ubasis, pbasis, e_mod, nu, matrix, fixed, *surface)


def mixed_matrix(
    ubasis: Basis, pbasis: Basis, e_mod: float, nu: float, exterior: sp.spmatrix | None = None
) -> sp.csr_matrix:
    """The mixed u-p matrix [[A, B^T], [B, -C]] of E ``e_mod`` (Pa) and ``nu`` on the bases
    (the whole body's, or some of its elements'), ``exterior`` added to A (N/m)."""
    stiffness = asm(deviatoric_stiffness(e_mod / (2.0 * (1.0 + nu))), ubasis)
    if exterior is not None:
        stiffness = stiffness + exterior
    coupling = asm(divergence_coupling, ubasis, pbasis)
    inverse_bulk = 3.0 * (1.0 - 2.0 * nu) / e_mod
    pressure_block = asm(compressibility(inverse_bulk), pbasis) if inverse_bulk > 0 else None
    return sp.bmat([[stiffness, coupling.T], [coupling, pressure_block]], format="csr")


def clamped_dofs(ubasis: Basis) -> np.ndarray:
    """The clamped dofs: u_r on the axis, and every dof of the far boundary or u_z on a
    layer's lubricated base."""
    axis = ubasis.get_dofs("axis").all("u^1")
    if "base" in ubasis.mesh.boundaries:  # a layer's lubricated base: u_z = 0, free to slide
        return np.union1d(axis, ubasis.get_dofs("base").all("u^2")).astype(np.int64)
    far = ubasis.get_dofs("far").all()
    return np.union1d(axis, far).astype(np.int64)


def _exterior_layer(ubasis: Basis, shear_modulus: float) -> sp.csr_matrix:
    """Stiffness of a lubricated layer beyond its lateral edge r = L, int 2 mu u_r v_r / L dA.

    Far from the contact a layer free to slide on its base and free on top deforms as
    u_r = C / r, u_z = 0 (isochoric; sigma_zz = sigma_rz = 0, sigma_rr = -2 mu u_r / r): the
    exterior pulls the edge back with the traction -2 mu u_r / L, exact in the far field, where
    a clamp would stiffen the layer by O(a / L).
    """
    mesh = ubasis.mesh
    facets = mesh.boundaries["far"]
    edge = float(mesh.p[0, mesh.facets[:, facets]].max())
    fbasis = FacetBasis(mesh, ubasis.elem, facets=facets, intorder=4)

    @BilinearForm
    def spring(u, v, w):
        return TWO_PI * w.x[0] * 2.0 * shear_modulus / edge * u[0] * v[0]

    return asm(spring, fbasis)


def _surface(
    mesh: MeshTri, ubasis: Basis, fixed: np.ndarray
) -> tuple[np.ndarray, np.ndarray, sp.csr_matrix]:
    """Free surface u_z dofs sorted by r, their radii, and the surface matrix on them."""
    dofs = np.setdiff1d(ubasis.get_dofs("surface").all("u^2"), fixed).astype(np.int64)
    radii = ubasis.doflocs[0, dofs]
    order = np.argsort(radii)
    dofs, radii = dofs[order], radii[order]
    fbasis = FacetBasis(mesh, ubasis.elem, facets=mesh.boundaries["surface"], intorder=4)
    mass = asm(normal_surface_mass, fbasis).tocsr()[dofs][:, dofs]
    return dofs, radii, mass.tocsr()


def pressure_load(
    system: ElasticSystem, pressure: Callable[[np.ndarray], np.ndarray]
) -> np.ndarray:
    """Nodal force vector (N) of a normal surface pressure p(r), positive in compression.

    Parameters
    ----------
    system : ElasticSystem
    pressure : callable
        Vectorised p(r) in Pa of the radius r in m. Place its jumps at mesh vertices (the
        refined radius is one): it is integrated with a Gauss rule of order 8 per edge.

    Returns
    -------
    numpy.ndarray
        Right-hand side of length ``system.n_dofs`` (zero outside the surface u_z dofs).
    """
    fbasis = FacetBasis(
        system.mesh,
        system.displacement_basis.elem,
        facets=system.mesh.boundaries["surface"],
        intorder=_LOAD_ORDER,
    )

    @LinearForm
    def traction(v, w):
        r = w.x[0]
        return -TWO_PI * r * np.asarray(pressure(r), dtype=float) * v[1]

    load = np.zeros(system.n_dofs)
    load[: system.n_displacement] = asm(traction, fbasis)
    return load


@dataclass(frozen=True)
class ElasticSolution:
    """Solution of the half-space problem: fields at the mesh vertices.

    Attributes
    ----------
    system : ElasticSystem
    coefficients : numpy.ndarray
        Full solution vector x = [u (m), p (Pa)].
    reactions : numpy.ndarray
        ``matrix @ x - load`` in N: the forces the constraints exert on the body (zero on free
        dofs up to round-off). A punch pressing down has negative u_z reactions.
    r, z : numpy.ndarray
        Vertex coordinates in m.
    u_r, u_z : numpy.ndarray
        Displacement at the vertices in m (u_z < 0: the surface moves down, into the body).
    mean_pressure : numpy.ndarray
        p = -tr(sigma)/3 in Pa at the vertices (positive in compression), the mixed unknown.
    sigma_rr, sigma_zz, sigma_tt, sigma_rz : numpy.ndarray
        Stress components in Pa (positive in tension) at the vertices: the L2 projection
        (unweighted, dr dz) of the element-wise stress onto continuous P1.
    von_mises : numpy.ndarray
        Von Mises stress in Pa from the projected components.
    """

    system: ElasticSystem
    coefficients: np.ndarray
    reactions: np.ndarray
    r: np.ndarray
    z: np.ndarray
    u_r: np.ndarray
    u_z: np.ndarray
    mean_pressure: np.ndarray
    sigma_rr: np.ndarray
    sigma_zz: np.ndarray
    sigma_tt: np.ndarray
    sigma_rz: np.ndarray
    von_mises: np.ndarray

    @property
    def surface_r(self) -> np.ndarray:
        """Radii in m of the surface u_z dofs (vertices and edge midpoints), ascending."""
        return self.system.surface_r

    @property
    def surface_u_z(self) -> np.ndarray:
        """u_z in m at ``surface_r`` (negative: into the body)."""
        return self.coefficients[self.system.surface_dofs]


def solve(
    system: ElasticSystem,
    load: np.ndarray | None = None,
    *,
    prescribed_dofs: np.ndarray | None = None,
    prescribed_values: np.ndarray | float = 0.0,
    factorization: Factorization | None = None,
) -> ElasticSolution:
    """Solve the clamped half-space problem for a load and prescribed dof values.

    Parameters
    ----------
    system : ElasticSystem
    load : numpy.ndarray, optional
        Nodal forces in N (e.g. from :func:`pressure_load`); default zero.
    prescribed_dofs : numpy.ndarray, optional
        Extra constrained dofs (e.g. a subset of ``system.surface_dofs`` under a punch).
    prescribed_values : numpy.ndarray or float
        Their values in m (u_z < 0 pushes into the body).
    factorization : Factorization, optional
        Of ``system.reduced_matrix(system.free_dofs(prescribed_dofs))``, to reuse across calls.

    Returns
    -------
    ElasticSolution
    """
    free = system.free_dofs(prescribed_dofs)
    if factorization is None:
        factorization = factorize(system.reduced_matrix(free))
    if factorization.shape[0] != free.size:
        raise ValueError(f"factorization has size {factorization.shape[0]}, expected {free.size}")
    load = np.zeros(system.n_dofs) if load is None else np.asarray(load, dtype=float)
    x = np.zeros(system.n_dofs)
    if prescribed_dofs is not None:
        x[prescribed_dofs] = prescribed_values
    x[free] = factorization.solve(load[free] - system.matrix[free] @ x)
    return postprocess(system, x, load)


def postprocess(
    system: ElasticSystem, x: np.ndarray, load: np.ndarray, deviatoric: np.ndarray | None = None
) -> ElasticSolution:
    """The fields (vertex values, projected stresses) of a solution vector ``x`` under ``load``.

    Parameters
    ----------
    system : ElasticSystem
    x : numpy.ndarray
        Full solution vector [u (m), p (Pa)].
    load : numpy.ndarray
        The nodal forces (N) it was solved for; the reactions are ``matrix @ x - load``.
    deviatoric : numpy.ndarray, optional
        The deviatoric stress (rr, tt, zz, rz) in Pa at the quadrature points, shape
        (4, elements, points), in place of 2 mu dev e(u) (a viscoelastic body).
    """
    reactions = system.matrix @ x - load
    ubasis, pbasis = system.displacement_basis, system.pressure_basis
    u, p = x[: system.n_displacement], x[system.n_displacement :]
    nodal = ubasis.nodal_dofs
    stresses = (
        _projected_stresses(system, u, p)
        if deviatoric is None
        else _projected_given(system, p, deviatoric)
    )
    return ElasticSolution(
        system=system,
        coefficients=x,
        reactions=reactions,
        r=system.mesh.p[0],
        z=system.mesh.p[1],
        u_r=u[nodal[0]],
        u_z=u[nodal[1]],
        mean_pressure=p[pbasis.nodal_dofs[0]],
        **stresses,
        von_mises=_von_mises(**stresses),
    )


def _projected_stresses(system: ElasticSystem, u: np.ndarray, p: np.ndarray) -> dict:
    """L2 projection (dr dz) of sigma_rr, sigma_zz, sigma_tt, sigma_rz onto continuous P1."""
    ubasis, pbasis = system.displacement_basis, system.pressure_basis
    ufield, pfield = ubasis.interpolate(u), pbasis.interpolate(p)
    two_mu = 2.0 * system.shear_modulus
    names = ("sigma_rr", "sigma_tt", "sigma_zz", "sigma_rz")

    def component(k: int) -> LinearForm:
        @LinearForm
        def form(v, w):
            r = w.x[0]
            strain = _strain(w.u, r)
            spherical = two_mu * _divergence(w.u, r) / 3.0 + w.p
            return (two_mu * strain[k] - (spherical if k < 3 else 0.0)) * v

        return form

    rhs = np.column_stack([asm(component(k), pbasis, u=ufield, p=pfield) for k in range(4)])
    values = factorize(asm(scalar_mass, pbasis), backend="superlu").solve(rhs)
    nodal = pbasis.nodal_dofs[0]
    return {name: values[nodal, k] for k, name in enumerate(names)}


def _projected_given(system: ElasticSystem, p: np.ndarray, deviatoric: np.ndarray) -> dict:
    """As :func:`_projected_stresses`, for a deviatoric stress given at the quadrature points."""
    pbasis = system.pressure_basis
    pfield = pbasis.interpolate(p)

    def component(k: int) -> LinearForm:
        @LinearForm
        def form(v, w):
            return (w.s - (w.p if k < 3 else 0.0)) * v

        return form

    rhs = np.column_stack([asm(component(k), pbasis, p=pfield, s=deviatoric[k]) for k in range(4)])
    values = factorize(asm(scalar_mass, pbasis), backend="superlu").solve(rhs)
    nodal = pbasis.nodal_dofs[0]
    names = ("sigma_rr", "sigma_tt", "sigma_zz", "sigma_rz")
    return {name: values[nodal, k] for k, name in enumerate(names)}


@BilinearForm
def scalar_mass(u, v, _):
    """int u v dA (no 2 pi r weight): the projection's mass of a scalar field."""
    return u * v


def _von_mises(sigma_rr, sigma_zz, sigma_tt, sigma_rz) -> np.ndarray:
    normal = (sigma_rr - sigma_zz) ** 2 + (sigma_zz - sigma_tt) ** 2 + (sigma_tt - sigma_rr) ** 2
    return np.sqrt(0.5 * normal + 3.0 * sigma_rz**2)


# --- inertia --------------------------------------------------------------------------------------


def weighted_mass(
    system: ElasticSystem, weight: Callable[[np.ndarray], np.ndarray], ubasis: Basis | None = None
) -> sp.csr_matrix:
    """Matrix int w(R) u . v 2 pi r dA on the full [u, p] dofs (zero pressure block).

    Parameters
    ----------
    system : ElasticSystem
    weight : callable
        w(r, z), vectorised, e.g. the density (kg/m^3) or density times a damping rate (kg/m^3/s).
    ubasis : skfem.Basis, optional
        The displacement basis on some of the elements (default: the system's, all of them).

    Returns
    -------
    scipy.sparse.csr_matrix
        Size ``system.n_dofs``; units of ``weight`` times m^3.
    """

    @BilinearForm
    def form(u, v, w):
        r = w.x[0]
        return TWO_PI * r * weight(w.x[0], w.x[1]) * (u[0] * v[0] + u[1] * v[1])

    block = asm(form, system.displacement_basis if ubasis is None else ubasis).tocsr()
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
