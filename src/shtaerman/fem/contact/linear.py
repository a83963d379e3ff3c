"""Frictionless unilateral contact of a rigid axisymmetric indenter with the FEM half-space.

With nodal contact forces F_i >= 0 (N, pushing down) on the candidate surface u_z dofs, the
surface moves by u_z = -C F, C the surface compliance (m/N) from the one factorization. At
each depth the nodal complementarity problem

    gap g = f(r) - d + C F >= 0,   F >= 0,   F_i g_i = 0

is solved by a primal-dual active-set iteration (:func:`complementarity`). The force is that
of the two vertex-aligned contacts around the depth (:func:`aligned_force`). The method and
the post-processing: benchmarks/FEM_NOTES.md, "Moved from the docstrings",
fem/contact/linear.py."""

from __future__ import annotations

import math
import time
from collections.abc import Callable
from dataclasses import dataclass, field
from functools import cached_property

import numpy as np
import scipy.linalg as la
from scipy.optimize import nnls
from threadpoolctl import threadpool_limits

from ...validation import InputError
from ...vocabulary import entry
from ..elasticity import ElasticSolution, ElasticSystem, postprocess
from ..solver import Factorization, TailFactorization, TailPivotError, factorize
from .constraints import (
    MAX_ACTIVE_SET_ITERATIONS,
    ROUND_OFF,
    SolvedContact,
    check_resolved,
    edge_and_centre,
)

Profile = Callable[[np.ndarray], np.ndarray]
MAX_DEPTHS = entry("depths").max_items
"""Most depths of one contact curve (:mod:`shtaerman.vocabulary`): every depth keeps its full
solution vector (depths x dofs x 8 bytes)."""


FEM_INPUTS = ("exponent", "shape_coefficient", "E2", "nu2")
"""The inputs whose range the FEM narrows (:mod:`shtaerman.vocabulary`, kind "contact")."""


def validate_fem_inputs(indenter: object, half_space: object) -> None:
    """Raise InputError unless the FEM contact applies: the indenter's exponent and shape
    coefficient and the half-space's E2 and nu2 within the FEM's ranges of the vocabulary
    (n > 1 keeps the central pressure bounded; A <= 1e100 keeps the depths from underflowing;
    E2 in [1e-3, 1e100] Pa keeps the scaled factorization accurate; nu2 in [0, 0.5] is the
    range the FEM is tested on; a sphere or a tabulated profile: E2 and nu2 only). Static,
    dynamic and finite-strain FEM alike."""
    profile = (
        (indenter.exponent, indenter.shape_coefficient) if indenter.kind == "power-law" else ()
    )
    values = (*profile, half_space.youngs_modulus, half_space.poisson_ratio)
    for name, value in zip(FEM_INPUTS[-len(values) :], values, strict=True):
        entry(name).check(value, "contact")


@dataclass(frozen=True, eq=False)
class SurfaceCompliance:
    """Surface compliance C (m/N) of the candidate u_z dofs r <= ``radius``.

    Attributes
    ----------
    r : numpy.ndarray
        Candidate radii in m, ascending, r[0] = 0 (the axis).
    matrix : numpy.ndarray
        C, symmetric positive definite: u_z = -C F for downward nodal forces F.
    mass : numpy.ndarray
        Surface matrix M (m^2) on the candidates: F = M p for a pressure p (Pa).
    vertex : numpy.ndarray
        True where the candidate is a mesh vertex, False at a P2 edge midpoint.
    """

    r: np.ndarray
    matrix: np.ndarray
    mass: np.ndarray
    vertex: np.ndarray
    dofs: np.ndarray = field(repr=False)
    radial_dofs: np.ndarray | None = field(default=None, repr=False)
    """Global u_r dofs of the candidates off the axis, where a bonded contact loads them."""
    coupled: np.ndarray | None = field(default=None, repr=False)
    """A bonded contact's compliance (m/N) on the u_z and then the ``radial_dofs``."""

    @cached_property
    def mass_factor(self) -> tuple[np.ndarray, tuple]:
        """Factor of ``mass`` for the pressure recovery, computed once."""
        return mass_factor(self.mass)


def _candidates(system: ElasticSystem, free: np.ndarray, radius: float) -> tuple[np.ndarray, ...]:
    """Surface indices, global dofs and positions in ``free`` of the u_z dofs r <= radius."""
    candidates = np.flatnonzero(system.surface_r <= radius * (1 + 1e-12))
    dofs = system.surface_dofs[candidates]
    return candidates, dofs, np.searchsorted(free, dofs)


def factorize_tail(
    system: ElasticSystem, free: np.ndarray, position: np.ndarray, backend: str = "auto"
) -> Factorization:
    """The one sparse factorization of the stiffness (free dofs), the dofs at ``position``
    (indices into ``free``) eliminated last where SuperLU allows.

    Should that factorization pivot a tail row away (the trailing block is then no Schur
    complement), the plain SuperLU factorization is used instead.
    """
    matrix = system.reduced_matrix(free)
    if backend in ("auto", "superlu"):
        try:
            return TailFactorization(matrix, position, system.dof_nodes()[free])
        except TailPivotError:
            backend = "superlu"
    return factorize(matrix, backend=backend)


def factorize_stiffness(
    system: ElasticSystem, free: np.ndarray, radius: float, backend: str = "auto"
) -> Factorization:
    """The one sparse factorization of the stiffness (free dofs).

    With SuperLU ("auto", "superlu") the candidate dofs r <= ``radius`` are eliminated last
    (:class:`.solver.TailFactorization`), so their compliance falls out of the factors. Should
    that factorization pivot a candidate row away or be inaccurate, the plain SuperLU
    factorization is used instead (the compliance then by unit-load solves: same results,
    slower).
    """
    _, _, position = _candidates(system, free, radius)
    return factorize_tail(system, free, position, backend)


def surface_compliance(
    system: ElasticSystem,
    factorization: Factorization,
    free: np.ndarray,
    radius: float,
    radial: np.ndarray | None = None,
) -> SurfaceCompliance:
    """Compliance of the surface u_z dofs r <= ``radius`` from the factorization, and with
    the global u_r dofs ``radial`` (a bonded contact's, eliminated after the u_z ones) the
    ``coupled`` compliance of both.

    The inverse of the trailing Schur block for a :class:`.solver.TailFactorization`, else one
    multi-RHS solve of unit loads.
    """
    candidates, dofs, position = _candidates(system, free, radius)
    if radial is not None:
        position = np.concatenate([position, np.searchsorted(free, radial)])
    # a downward force -F e_i moves the surface by -C F: C = (K^-1)_cc, symmetrised
    if hasattr(factorization, "tail_inverse"):  # a TailFactorization
        inverse = factorization.tail_inverse()
    else:
        unit_loads = np.zeros((free.size, position.size))
        unit_loads[position, np.arange(position.size)] = 1.0
        inverse = factorization.solve(unit_loads)[position]
    inverse = 0.5 * (inverse + inverse.T)
    mass = system.surface_mass[candidates][:, candidates].toarray()
    vertex = system.dof_nodes()[dofs] < system.mesh.p.shape[1]
    compliance = inverse[: dofs.size, : dofs.size]
    coupled = None if radial is None else inverse
    return SurfaceCompliance(
        system.surface_r[candidates], compliance, mass, vertex, dofs, radial, coupled
    )


@dataclass(frozen=True)
class ContactStep(SolvedContact):
    """The contact at one depth on the linear body: the :class:`.constraints.SolvedContact`
    (``force`` from the vertex-aligned contacts, :func:`aligned_force`, or the nodal sum) and

    Attributes
    ----------
    discrete_force : float
        Sum of the nodal forces at exactly this depth in N (differs from ``force`` by the
        O((h/a)^2) chord error of the piecewise-affine discrete curve).
    nodal_forces : numpy.ndarray
        F >= 0 in N on the candidate nodes.
    iterations : int
        Active-set iterations used.
    """

    discrete_force: float
    nodal_forces: np.ndarray = field(repr=False)
    iterations: int
    tangential_forces: np.ndarray | None = field(default=None, repr=False)
    """Bonded contact only: nodal forces (N) along +r on the body at ``radial_dofs``."""


def _least_squares_start(compliance: np.ndarray, clearance: np.ndarray) -> np.ndarray:
    """Active set from Lawson-Hanson NNLS, which terminates finitely on any SPD problem.

    min 1/2 F.C F + c.F with F >= 0 is min ||L^T F + L^-1 c|| for C = L L^T.
    """
    lower = la.cholesky(compliance, lower=True)
    target = -la.solve_triangular(lower, clearance, lower=True)
    forces, _ = nnls(lower.T, target, maxiter=50 * clearance.size)
    return forces > 0


def complementarity(
    compliance: np.ndarray, clearance: np.ndarray
) -> tuple[np.ndarray, np.ndarray, int]:
    """Solve F >= 0, g = clearance + C F >= 0, F g = 0 by a primal-dual active set; should it
    revisit an active set, it restarts from the active set of Lawson-Hanson NNLS.

    Parameters
    ----------
    compliance : numpy.ndarray
        C, symmetric positive definite (m/N).
    clearance : numpy.ndarray
        f(r_i) - d in m: the gap before the surface deforms.

    Returns
    -------
    forces, gap : numpy.ndarray
        The solution (N) and its gap (m; exactly 0 on the active set up to round-off).
    iterations : int
        Active-set steps taken (including the restart).
    """
    active, seen, iterations = clearance < 0, set(), 0
    while iterations < MAX_ACTIVE_SET_ITERATIONS:
        iterations += 1
        forces = np.zeros(clearance.size)
        if active.any():
            sub = compliance[np.ix_(active, active)]
            forces[active] = la.cho_solve(la.cho_factor(sub), -clearance[active])
        gap = clearance + compliance @ forces
        gap[active] = 0.0
        # round-off bands: the P2 axis node carries exactly zero force in theory (its 2 pi r
        # weighted shape function integrates to 0) and would flip between states otherwise
        force_band = ROUND_OFF * np.abs(forces).max(initial=0.0)
        gap_band = ROUND_OFF * np.abs(clearance).max()
        updated = np.where(active, forces > -force_band, gap < -gap_band)
        if np.array_equal(updated, active):
            return np.maximum(forces, 0.0), np.maximum(gap, 0.0), iterations
        seen.add(active.tobytes())
        active = updated
        if active.tobytes() in seen:
            active, seen = _least_squares_start(compliance, clearance), set()
    raise RuntimeError("the contact active set did not settle; refine the mesh near the edge")


def mass_factor(mass: np.ndarray) -> tuple[np.ndarray, tuple]:
    """Jacobi-scaled Cholesky factor of the surface matrix (axis rows of M are ~h^2 small)."""
    scale = 1.0 / np.sqrt(np.diag(mass))
    return scale, la.cho_factor(mass * np.outer(scale, scale))


def recover_pressure(factor: tuple[np.ndarray, tuple], forces: np.ndarray) -> np.ndarray:
    """Nodal pressure p (Pa) with M p = F, from :func:`mass_factor`."""
    scale, scaled = factor
    return scale * la.cho_solve(scaled, scale * forces)


def _aligned_contact(
    compliance: SurfaceCompliance, heights: np.ndarray, pressed: np.ndarray
) -> tuple[float, float]:
    """Depth (m) and force (N) at which the ``pressed`` nodes touch and the last carries none.

    With the pressed set S fixed the nodal forces are affine in the depth, F = d w - v with
    C_SS w = 1 and C_SS v = f_S; the last node's force vanishes at d = v_last / w_last.
    """
    factor = la.cho_factor(compliance.matrix[np.ix_(pressed, pressed)])
    unit = la.cho_solve(factor, np.ones(pressed.size))
    shape = la.cho_solve(factor, heights[pressed])
    depth = shape[-1] / unit[-1]
    return float(depth), float(depth * unit.sum() - shape.sum())


def aligned_force(
    compliance: SurfaceCompliance, heights: np.ndarray, forces: np.ndarray, depth: float
) -> float:
    """The contact force (N) at ``depth`` between the two vertex-aligned contacts around it.

    The force is interpolated as a power law (exact for any P = beta d^q) between the two
    contacts around ``depth`` whose edge lies on an element vertex, where the nodal sum's chord
    error is smallest; where the two do not bracket the depth, the nodal sum is returned.

    Parameters
    ----------
    compliance : SurfaceCompliance
    heights : numpy.ndarray
        The indenter profile f(r) (m) at the candidates.
    forces : numpy.ndarray
        The nodal forces (N) of the contact at ``depth`` (m).
    """
    loaded = np.flatnonzero(forces > 0)
    last = loaded[-1]
    below = last if compliance.vertex[last] else last - 1
    above = below + 1 + int(np.argmax(compliance.vertex[below + 1 :]))
    inner = loaded[loaded < below]
    low, high = (
        _aligned_contact(compliance, heights, np.concatenate([inner, np.arange(below, edge + 1)]))
        for edge in (below, above)
    )
    discrete = float(forces.sum())
    tolerance = 1e-9 * depth
    bracketed = low[0] - tolerance <= depth <= high[0] + tolerance and low[0] < high[0]
    aligned = compliance.vertex[below] and compliance.vertex[above]
    if not (aligned and bracketed and low[1] > 0 and high[1] > 0):
        return discrete
    exponent = math.log(high[1] / low[1]) / math.log(high[0] / low[0])
    return low[1] * (depth / low[0]) ** exponent


def contact_step(
    compliance: SurfaceCompliance, profile: Profile, depth: float, aligned: bool = True
) -> ContactStep:
    """The contact at one depth from the surface compliance (``aligned``: see
    :func:`solve_contact`)."""
    heights = np.asarray(profile(compliance.r), dtype=float)
    clearance = heights - depth
    if not (clearance < 0).any():
        raise InputError(
            f"depth {depth:g} m: the indenter profile never touches the surface "
            f"(f(r) - d > 0 at every candidate node); check the profile and depths"
        )
    solved = complementarity(compliance.matrix, clearance)
    return step_from_forces(compliance, heights, depth, solved, aligned)


def step_from_forces(
    compliance: SurfaceCompliance,
    heights: np.ndarray,
    depth: float,
    solved: tuple[np.ndarray, np.ndarray, int],
    aligned: bool = True,
    shear: np.ndarray | None = None,
) -> ContactStep:
    """The contact step at ``depth`` (m) from the complementarity solution ``solved`` (nodal
    forces in N, gaps in m, iterations) against the indenter's ``heights`` (m) at the
    candidate nodes (a viscoelastic body's shifted by its history); ``shear``: a bonded
    contact's tangential nodal forces (N)."""
    forces, gap, iterations = solved
    discrete = float(forces.sum())
    check_resolved(compliance.r, forces, depth)
    pressure = recover_pressure(compliance.mass_factor, forces)
    radius, centre = edge_and_centre(compliance.r, (forces, gap, pressure), depth)
    return ContactStep(
        depth=depth,
        force=aligned_force(compliance, heights, forces, depth) if aligned else discrete,
        discrete_force=discrete,
        contact_radius=radius,
        central_pressure=centre,
        nodal_forces=forces,
        pressure=pressure,
        gap=gap,
        iterations=iterations,
        tangential_forces=shear,
    )


@dataclass(frozen=True)
class ContactCurve:
    """The FEM contact over a sequence of depths, and what it cost.

    Attributes
    ----------
    steps : list of ContactStep
        One per depth, ascending.
    compliance : SurfaceCompliance
    system : ElasticSystem
    solutions : numpy.ndarray
        Shape (depths, dofs): the full solution vector x = [u (m), p (Pa)] at each depth,
        from one multi-right-hand-side solve after the contact (the factorization is not kept).
    timings : dict of str to float
        Seconds: ``factorization`` (exactly one sparse factorization of the full stiffness)
        and ``contact`` (everything after it: compliance, active sets, recovery, fields).
    backend : str
        The sparse solver used.
    """

    steps: list[ContactStep]
    compliance: SurfaceCompliance
    system: ElasticSystem
    solutions: np.ndarray = field(repr=False)
    timings: dict[str, float]
    backend: str

    def field_solution(self, index: int) -> ElasticSolution:
        """Displacements and stresses in the body at step ``index`` (negative counts back).

        Each call post-processes afresh (stress projection, about 0.05 s at 30k dofs); keep
        the result where it is needed more than once.
        """
        step, load = self.steps[index], np.zeros(self.system.n_dofs)  # the contact's forces
        load[self.compliance.dofs] = -step.nodal_forces
        if step.tangential_forces is not None:
            load[self.compliance.radial_dofs] = step.tangential_forces
        return postprocess(self.system, self.solutions[index], load)


def timed_curve(
    system: ElasticSystem,
    parts: tuple[SurfaceCompliance, list[ContactStep], np.ndarray],
    factorization: Factorization,
    backend: str,
    seconds: tuple[float, float],
) -> ContactCurve:
    """The :class:`ContactCurve` of ``parts`` (compliance, steps, solutions), the backend
    ``factorization`` used (``backend`` if it does not say) and the ``seconds`` spent on the
    factorization and on the contact."""
    compliance, steps, solutions = parts
    return ContactCurve(
        steps=steps,
        compliance=compliance,
        system=system,
        solutions=solutions,
        timings={"factorization": seconds[0], "contact": seconds[1]},
        backend=getattr(factorization, "backend", backend),
    )


def field_solutions(
    system: ElasticSystem,
    factorization: Factorization,
    free: np.ndarray,
    compliance: SurfaceCompliance,
    steps: list[ContactStep],
) -> np.ndarray:
    """Solution vectors of every depth by one solve with one right-hand side per depth (the
    normal nodal forces and, where a step has them, the tangential ones)."""
    loads = np.zeros((free.size, len(steps)))
    normal = np.searchsorted(free, compliance.dofs)
    radial = compliance.radial_dofs
    radial = None if radial is None else np.searchsorted(free, radial)
    for column, step in enumerate(steps):
        loads[normal, column] = -step.nodal_forces
        if step.tangential_forces is not None:
            loads[radial, column] = step.tangential_forces
    solutions = np.zeros((len(steps), system.n_dofs))
    solutions[:, free] = factorization.solve(loads).T
    return solutions


def solve_contact(
    system: ElasticSystem,
    profile: Profile,
    depths: np.ndarray,
    candidate_radius: float,
    *,
    backend: str = "auto",
    aligned: bool = True,
) -> ContactCurve:
    """Press a rigid frictionless indenter z = f(r) into the half-space to each depth.

    Parameters
    ----------
    system : ElasticSystem
        The assembled half-space (:func:`shtaerman.fem.elasticity.assemble`).
    profile : callable
        f(r) in m of r in m, vectorised, f(0) = 0 (e.g. ``PowerLawIndenter.profile``).
    depths : array_like
        Depths d in m, positive and strictly increasing (the entry points check them).
    candidate_radius : float
        Surface nodes with r <= this radius (m) may touch; keep it within the refined zone.
    backend : str
        Sparse solver, see :func:`shtaerman.fem.solver.factorize`.
    aligned : bool
        Report the force of the vertex-aligned contacts (:func:`aligned_force`); False gives
        the nodal sum at each depth, the discretization of the finite-strain solver, for
        same-mesh comparisons with it.

    Returns
    -------
    ContactCurve
    """
    depths = np.atleast_1d(np.asarray(depths, dtype=float))  # checked where they entered
    if depths.size > MAX_DEPTHS:
        raise InputError(f"depths: at most {MAX_DEPTHS} per curve, got {depths.size}", "depths")
    free = system.free_dofs()
    start = time.perf_counter()
    factorization = factorize_stiffness(system, free, candidate_radius, backend)
    factorized = time.perf_counter()
    compliance = surface_compliance(system, factorization, free, candidate_radius)
    with threadpool_limits(limits=1, user_api="blas"):  # small dense solves: threads only hurt
        steps = [contact_step(compliance, profile, float(depth), aligned) for depth in depths]
    solutions = field_solutions(system, factorization, free, compliance, steps)
    done = time.perf_counter()
    seconds = (factorized - start, done - factorized)
    return timed_curve(system, (compliance, steps, solutions), factorization, backend, seconds)
