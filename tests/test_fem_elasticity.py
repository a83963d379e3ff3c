"""Axisymmetric mixed elasticity and the sparse solver, proven against closed forms.

Closed forms (Johnson, Contact Mechanics, ch. 3; Timoshenko & Goodier, sec. 138), with
E* = E / (1 - nu^2):
- uniform pressure q on r <= c: w(0) = 2 q c / E*, w(c) = 4 q c / (pi E*); on the axis at depth
  s: sigma_zz = -q (1 - s^3 / (c^2 + s^2)^(3/2)), sigma_rr = sigma_tt =
  -q/2 ((1 + 2 nu) - 2 (1 + nu) s / sqrt(c^2 + s^2) + s^3 / (c^2 + s^2)^(3/2));
- Hertz pressure p0 sqrt(1 - r^2/c^2): w(r) = pi p0 (2 c^2 - r^2) / (4 c E*) for r <= c;
- rigid flat punch of radius c pushed to depth d: P = 2 c E* d.

Meshes are coarse (smallest size c/20, growth 0.25, ~5000 dofs, R = 1e5 c by default) so each
solve takes a few hundredths of a second; tolerances are the errors observed on these meshes
with a margin, stated at each assertion. Their sources: growth 0.25 leaves ~1e-4 in the
displacements (it shrinks like growth^3), R = 1e5 c ~1e-5, and the punch's square-root edge
singularity gives a first-order error ~0.07 h/c (see benchmarks/bench_fem.py).
"""

from __future__ import annotations

import math

import numpy as np
import pytest
import scipy.sparse as sp
import scipy.sparse.linalg as spla

from shtaerman.fem.elasticity import assemble, pressure_load, solve
from shtaerman.fem.mesh import halfspace_mesh
from shtaerman.fem.solver import available_backends, factorize
from shtaerman.validation import InputError

C = 0.01  # load / punch radius, m
E = 7.5e6  # Young's modulus, Pa (the paper's rubber)
Q = 1.0e5  # pressure, Pa
GROWTH = 0.25
NUS = (0.0, 0.3, 0.5)


@pytest.fixture(scope="module")
def meshes():
    return {n: halfspace_mesh(C, smallest_size=C / n, growth=GROWTH) for n in (20, 40)}


@pytest.fixture(scope="module")
def systems(meshes):
    return {(n, nu): assemble(mesh, E, nu) for n, mesh in meshes.items() for nu in NUS}


def _uniform(r):
    return np.where(r <= C, Q, 0.0)


def _surface_w(solution):
    """Surface deflection w = -u_z (m, positive into the body) at the surface dofs."""
    return solution.surface_r, -solution.surface_u_z


def _punch_force(system, depth):
    dofs = system.surface_dofs[system.surface_r <= C * (1 + 1e-12)]
    solution = solve(system, prescribed_dofs=dofs, prescribed_values=-depth)
    return -solution.reactions[dofs].sum()


def _punch_error(system):
    e_star = E / (1 - system.poisson_ratio**2)
    return _punch_force(system, 1e-4) / (2 * C * e_star * 1e-4) - 1


@pytest.mark.parametrize("nu", NUS)
def test_uniform_pressure_centre_and_edge_deflection(systems, nu):
    system = systems[20, nu]
    r, w = _surface_w(solve(system, pressure_load(system, _uniform)))
    e_star = E / (1 - nu**2)
    assert r[0] == 0.0
    # observed |error| <= 1.3e-4 (nu = 0, 0.3, 0.5): allow 3e-4
    assert w[0] == pytest.approx(2 * Q * C / e_star, rel=3e-4)
    # the slope of w is log-singular at r = c and the error there depends on the local mesh:
    # observed |error| <= 9.9e-4 on meshes of h = c/20 to c/80, allow 2e-3
    edge = np.argmin(np.abs(r - C))
    assert r[edge] == pytest.approx(C, rel=1e-12)
    assert w[edge] == pytest.approx(4 * Q * C / (math.pi * e_star), rel=2e-3)


@pytest.mark.parametrize("nu", NUS)
def test_hertz_pressure_gives_a_parabolic_deflection(systems, nu):
    system = systems[20, nu]
    solution = solve(
        system, pressure_load(system, lambda r: Q * np.sqrt(np.clip(1 - (r / C) ** 2, 0, 1)))
    )
    r, w = _surface_w(solution)
    inside = r <= C
    exact = math.pi * Q * (2 * C**2 - r[inside] ** 2) / (4 * C * E / (1 - nu**2))
    # observed max error 2.7e-4 of w(0) (nu = 0, 0.5), 2.3e-4 (nu = 0.3): allow 1e-3
    assert np.max(np.abs(w[inside] - exact)) < 1e-3 * exact[0]


@pytest.mark.parametrize("nu", NUS)
def test_flat_punch_force(systems, nu):
    error = _punch_error(systems[20, nu])
    # a conforming discretization of a displacement-driven problem is stiffer, and so is the
    # clamped truncated domain: the error is positive. Observed 1.7e-3 (nu = 0.5), 3.6e-3
    # (nu = 0.3), 5.5e-3 (nu = 0): allow 8e-3.
    assert 0 < error < 8e-3


@pytest.mark.parametrize("nu", (0.3, 0.5))
def test_flat_punch_converges_at_first_order(systems, nu):
    coarse, fine = _punch_error(systems[20, nu]), _punch_error(systems[40, nu])
    rate = math.log2(coarse / fine)
    # the edge singularity sigma ~ (c - r)^(-1/2) gives energy (stiffness) errors ~ h^1;
    # observed rates 1.11 (nu = 0.5) and 1.10 (nu = 0.3)
    assert 0.75 < rate < 1.25


@pytest.mark.parametrize("nu", (0.3, 0.5))
def test_axis_stresses_match_the_closed_form(systems, nu):
    solution = solve(systems[20, nu], pressure_load(systems[20, nu], _uniform))
    on_axis = (solution.r == 0) & (solution.z < 0) & (solution.z > -3 * C)
    s = -solution.z[on_axis]
    cube = s**3 / (C**2 + s**2) ** 1.5
    sigma_zz = -Q * (1 - cube)
    sigma_rr = -Q / 2 * ((1 + 2 * nu) - 2 * (1 + nu) * s / np.hypot(C, s) + cube)
    # observed max error 4.9e-3 q (the mesh is h = c/20 + 0.25 s deep down): allow 1e-2 q
    for computed, exact in [
        (solution.sigma_zz, sigma_zz),
        (solution.sigma_rr, sigma_rr),
        (solution.sigma_tt, sigma_rr),
    ]:
        assert np.max(np.abs(computed[on_axis] - exact)) < 1e-2 * Q
    assert np.max(np.abs(solution.sigma_rz[on_axis])) < 1e-2 * Q


def test_loaded_surface_carries_sigma_zz_equal_to_minus_the_pressure(systems):
    solution = solve(systems[40, 0.3], pressure_load(systems[40, 0.3], _uniform))
    loaded = (solution.z == 0) & (solution.r < 0.8 * C)
    unloaded = (solution.z == 0) & (solution.r > 1.2 * C)
    # the L2-projected stress smears the jump at r = c over ~2 elements; away from it the
    # observed error is 1.0e-4 q (loaded), 6.5e-4 q (unloaded): allow 3e-3 q
    np.testing.assert_allclose(solution.sigma_zz[loaded], -Q, atol=3e-3 * Q)
    np.testing.assert_allclose(solution.sigma_zz[unloaded], 0.0, atol=3e-3 * Q)
    assert np.all(solution.u_z[(solution.z == 0) & (solution.r <= C)] < 0)
    assert np.all(solution.von_mises >= 0)


def test_incompressible_displacement_is_discretely_divergence_free(systems):
    system = systems[20, 0.5]
    solution = solve(system, pressure_load(system, _uniform))
    n = system.n_displacement
    u = solution.coefficients[:n]
    coupling = system.matrix[n:, :n]
    # B u = 0 is an equation of the mixed system: it holds to round-off
    scale = np.abs(coupling) @ np.abs(u)
    assert np.max(np.abs(coupling @ u)) < 1e-10 * np.max(scale)
    # the mean pressure at the loaded centre is 2 (1 + nu) q / 3 = q (Boussinesq; observed
    # error 3e-5 q)
    centre = np.flatnonzero((solution.r == 0) & (solution.z == 0))[0]
    assert solution.mean_pressure[centre] == pytest.approx(Q, rel=2e-2)


def test_reactions_balance_the_applied_force_in_newtons(systems):
    system = systems[20, 0.3]
    load = pressure_load(system, _uniform)
    # the 2 pi r ring weight is kept: the load is the 3-D force, -pi c^2 q in z
    z_load = load[: system.n_displacement][1::2]
    assert z_load.sum() == pytest.approx(-math.pi * C**2 * Q, rel=1e-12)
    solution = solve(system, load)
    z_reactions = solution.reactions[: system.n_displacement][1::2]
    assert z_reactions.sum() == pytest.approx(math.pi * C**2 * Q, rel=1e-9)


def test_surface_mass_converts_pressure_and_nodal_forces(systems):
    system = systems[20, 0.3]

    def pressure(r):
        return Q * np.clip(1 - (r / C) ** 2, 0, None)  # piecewise quadratic, kink at a vertex

    forces = -pressure_load(system, pressure)[system.surface_dofs]
    nodal = pressure(system.surface_r)
    # P2 interpolates the pressure exactly, so M p is the consistent load to round-off
    np.testing.assert_allclose(system.surface_mass @ nodal, forces, atol=1e-12 * forces.max())
    recovered = spla.spsolve(system.surface_mass.tocsc(), forces)
    # the axis dof carries ~no area, yet its pressure comes back exactly
    assert recovered[0] == pytest.approx(Q, rel=1e-9)
    np.testing.assert_allclose(recovered, nodal, atol=1e-9 * Q)
    assert np.all(np.diff(system.surface_r) > 0)
    # every surface dof is free: the clamped corner at r = R is left out
    assert np.intersect1d(system.surface_dofs, system.fixed_dofs).size == 0
    assert system.surface_r[-1] < system.mesh.p[0].max()


@pytest.mark.parametrize("backend", available_backends())
def test_factorization_solves_many_right_hand_sides(systems, backend):
    system = systems[20, 0.5]
    free = system.free_dofs()
    matrix = system.reduced_matrix(free)
    factorization = factorize(matrix, backend=backend)
    assert factorization.backend == backend
    rhs = np.random.default_rng(1).standard_normal((free.size, 7))
    exact = spla.spsolve(matrix, rhs)
    # backward stable solves of a system with condition ~1e8: agree to 1e-8
    np.testing.assert_allclose(
        factorization.solve(rhs), exact, rtol=0, atol=1e-8 * np.abs(exact).max()
    )
    np.testing.assert_allclose(
        factorization.solve(rhs[:, 0]), exact[:, 0], atol=1e-8 * np.abs(exact).max()
    )


def test_a_factorization_is_reused_and_must_match(systems):
    system = systems[20, 0.3]
    load = pressure_load(system, _uniform)
    factorization = factorize(system.reduced_matrix(system.free_dofs()))
    reused = solve(system, load, factorization=factorization)
    fresh = solve(system, load)
    np.testing.assert_allclose(reused.coefficients, fresh.coefficients, rtol=1e-10, atol=1e-20)
    with pytest.raises(ValueError, match="factorization"):
        solve(system, load, prescribed_dofs=system.surface_dofs[:3], factorization=factorization)


def test_solver_rejects_unknown_backends_and_singular_matrices():
    with pytest.raises(InputError, match="superlu"):
        factorize(sp.eye(3, format="csc"), backend="umfpack")
    singular = sp.csc_matrix(np.array([[1.0, 1.0], [1.0, 1.0]]))
    with pytest.raises(RuntimeError, match="singular"):
        factorize(singular, backend="superlu")


@pytest.mark.parametrize(
    ("e_mod", "nu", "name"), [(-1.0, 0.3, "youngs_modulus"), (E, 0.6, "poisson_ratio")]
)
def test_invalid_material_raises_input_error(meshes, e_mod, nu, name):
    with pytest.raises(InputError, match=name):
        assemble(meshes[20], e_mod, nu)
