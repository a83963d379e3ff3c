"""Frictionless unilateral contact of a rigid axisymmetric indenter with the FEM half-space.

The indenter z = f(r) - d (f(0) = 0 at its tip, depth d > 0) presses the surface z = 0 down.
With nodal contact forces F_i >= 0 (N, pushing down) on the candidate surface u_z dofs, the
surface moves by u_z = -C F, where C = S^T K^-1 S is the surface compliance (m/N). It comes
once from the one factorization: with SuperLU the candidates are eliminated last and C is the
inverse of the trailing Schur block (:class:`.solver.TailFactorization`); otherwise (PARDISO,
or a tail the factorization pivoted) one multi-RHS solve of unit loads. The contact
conditions hold exactly at the nodes:

    gap g = f(r) - d + C F >= 0,   F >= 0,   F_i g_i = 0,

a linear complementarity problem with C symmetric positive definite (unique solution), solved
for each depth by a primal-dual active-set iteration (semi-smooth Newton) that ends when the
active set repeats; each iteration is one dense Cholesky solve on the active set.

Post-processing per depth: the force P from the two vertex-aligned contacts around the depth
(:func:`aligned_force`); the pressure recovered consistently from the
nodal forces with the surface matrix M (F = M p; the axis node carries no area, so no
"force / area"); the central pressure extrapolated to the axis from r = 1e-4 a .. 1e-2 a
(:func:`central_pressure`); the contact radius located between nodes from the gap, which opens
as (r - a)^(3/2) beyond a smooth contact edge.

A body that relaxes in shear by a Prony series (:mod:`.viscoelastic`) is pressed at a constant
rate, d = V t (:func:`press_at_rate`), quasi-statically: at each time step t_n, with the step's
stiffness K (the elastic one at the step's effective shear modulus) and the history force h^n
of the Prony branches,

    K x = -S F - h^n,   g = f(r) - d_n + C F + (K^-1 h^n)_c >= 0,   F >= 0,   F . g = 0:

the history shifts the indenter's clearance by the surface displacement it alone would cause,
and the complementarity problem is solved as in the elastic contact. The steps are uniform
between consecutive requested depths (each such interval has its own dt, its own
factorization, and the branches' history carried over, :meth:`.ViscoelasticShear.resume`), so
every requested depth is an instant of the march. With all g_i = 0 every step is the elastic
contact (the same matrix, the history exactly 0). At nu2 = 1/2 the discrete contact obeys Lee
and Radok's correspondence exactly while it grows: the force is the hereditary integral of the
elastic FEM force, with the force linear in time over each step (exact kernels), so the time
error is second order in dt.
"""

from __future__ import annotations

import itertools
import math
import time
from collections.abc import Callable
from dataclasses import dataclass, field, replace
from functools import cached_property

import numpy as np
import scipy.linalg as la
from scipy.optimize import nnls
from threadpoolctl import threadpool_limits

from ..theory.viscoelastic import PronySeries
from ..validation import InputError, NumericalFailureError
from ..vocabulary import entry
from .elasticity import ElasticSolution, ElasticSystem, postprocess
from .solver import Factorization, TailFactorization, TailPivotError, factorize
from .viscoelastic import ShearMemory, ViscoelasticShear, viscoelastic_shear

__all__ = [
    "CURVE_STEPS",
    "ContactCurve",
    "ContactStep",
    "SurfaceCompliance",
    "aligned_force",
    "check_resolved",
    "complementarity",
    "edge_radius",
    "factorize_stiffness",
    "factorize_tail",
    "field_solutions",
    "press_at_rate",
    "solve_contact",
    "step_from_forces",
    "tail_compliance",
    "time_grid",
    "timed_curve",
    "validate_fem_inputs",
]

Profile = Callable[[np.ndarray], np.ndarray]
MAX_ACTIVE_SET_ITERATIONS = 100
ROUND_OFF = 1e-10
"""Relative band within which a force or gap counts as zero in the active-set update."""
MIN_MODULUS_PER_LENGTH = 0.1
"""Smallest E / (contact zone radius) in Pa/m: the factorization's backward error grows as
its inverse."""
EDGE_MARGIN = 3
"""Candidate nodes that must stay free beyond the contact edge, or the zone is too small."""
MAX_DEPTHS = entry("depths").max_items
"""Most depths of one contact curve (:mod:`shtaerman.vocabulary`): every depth keeps its full
solution vector (depths x dofs x 8 bytes)."""
MIN_CONTACT_NODES = 3
"""Fewest loaded surface nodes of a contact (the axis node carries none): fewer cannot resolve
the force and the radius."""


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

    @cached_property
    def mass_factor(self) -> tuple[np.ndarray, tuple]:
        """Factor of ``mass`` for the pressure recovery, computed once."""
        return mass_factor(self.mass)


def _candidates(system: ElasticSystem, free: np.ndarray, radius: float) -> tuple[np.ndarray, ...]:
    """Surface indices, global dofs and positions in ``free`` of the u_z dofs r <= radius."""
    candidates = np.flatnonzero(system.surface_r <= radius * (1 + 1e-12))
    dofs = system.surface_dofs[candidates]
    return candidates, dofs, np.searchsorted(free, dofs)


def tail_compliance(factorization: Factorization, size: int, position: np.ndarray) -> np.ndarray:
    """(K^-1) on the dofs at ``position`` (of ``size`` free dofs), symmetrised (m/N).

    The inverse of the trailing Schur block for a :class:`.solver.TailFactorization`, else one
    multi-RHS solve of unit loads (any backend).
    """
    if hasattr(factorization, "tail_inverse"):  # a TailFactorization
        inverse = factorization.tail_inverse()
    else:
        unit_loads = np.zeros((size, position.size))
        unit_loads[position, np.arange(position.size)] = 1.0
        inverse = factorization.solve(unit_loads)[position]
    return 0.5 * (inverse + inverse.T)


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
    system: ElasticSystem, factorization: Factorization, free: np.ndarray, radius: float
) -> SurfaceCompliance:
    """Compliance of the surface u_z dofs r <= ``radius`` from the factorization.

    The inverse of the trailing Schur block for a :class:`.solver.TailFactorization`, else one
    multi-RHS solve of unit loads.
    """
    candidates, dofs, position = _candidates(system, free, radius)
    # a downward force -F e_i moves the surface by -C F: C = (K^-1)_cc, symmetrised
    compliance = tail_compliance(factorization, free.size, position)
    mass = system.surface_mass[candidates][:, candidates].toarray()
    vertex = system.dof_nodes()[dofs] < system.mesh.p.shape[1]
    return SurfaceCompliance(system.surface_r[candidates], compliance, mass, vertex, dofs)


@dataclass(frozen=True)
class ContactStep:
    """The contact at one depth (SI units).

    Attributes
    ----------
    depth : float
        Indenter depth d in m.
    force : float
        Total contact force P in N, from the vertex-aligned contacts (:func:`aligned_force`).
    discrete_force : float
        Sum of the nodal forces at exactly this depth in N (differs from ``force`` by the
        O((h/a)^2) chord error of the piecewise-affine discrete curve).
    contact_radius : float
        Contact radius a in m, located between nodes.
    central_pressure : float
        Pressure at the axis p(0) in Pa.
    nodal_forces : numpy.ndarray
        F >= 0 in N on the candidate nodes.
    pressure : numpy.ndarray
        Recovered pressure p (Pa) at the candidate nodes.
    gap : numpy.ndarray
        Gap g >= 0 in m at the candidate nodes (0 in contact).
    iterations : int
        Active-set iterations used.
    """

    depth: float
    force: float
    discrete_force: float
    contact_radius: float
    central_pressure: float
    nodal_forces: np.ndarray = field(repr=False)
    pressure: np.ndarray = field(repr=False)
    gap: np.ndarray = field(repr=False)
    iterations: int
    tangential_forces: np.ndarray | None = field(default=None, repr=False)
    """Bonded contact only: nodal forces (N) along +r on the body at ``radial_dofs``."""

    @property
    def mean_pressure(self) -> float:
        """P / (pi a^2) in Pa."""
        return self.force / (np.pi * self.contact_radius**2)


def _solve_active(matrix: np.ndarray, rhs: np.ndarray, active: np.ndarray) -> np.ndarray:
    forces = np.zeros(rhs.size)
    if active.any():
        sub = matrix[np.ix_(active, active)]
        forces[active] = la.cho_solve(la.cho_factor(sub), rhs[active])
    return forces


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
    """Solve F >= 0, g = clearance + C F >= 0, F g = 0 by a primal-dual active set.

    The active-set (semi-smooth Newton) iteration usually settles in 5-9 steps. It is proven
    only for M-matrices, and C is not one: if it revisits an active set, the iteration restarts
    from the active set of Lawson-Hanson NNLS, which is exact up to round-off.

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
        forces = _solve_active(compliance, -clearance, active)
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


EDGE_FIT_NODES = slice(3, 15)
"""Free nodes (counted past the last loaded one) fitted to locate the edge: the first few are
skipped, the FEM gap there is distorted over about one element."""


def edge_radius(r: np.ndarray, forces: np.ndarray, gap: np.ndarray) -> float:
    """Edge a from the gap beyond it, g^(2/3) ~ c (r - a)(1 + O(r - a)) at a smooth edge.

    A least-squares quadratic in r through g^(2/3) at free nodes 3..14 past the last loaded
    one, its root nearest the edge (second order). With too few free nodes, or no real root
    nearby, the two-node linear extrapolation is used. The discrete contact may
    carry a small force one node past the true edge, so the result is kept between the
    last-but-one loaded node and the first free one.

    Raises
    ------
    shtaerman.validation.NumericalFailureError
        If the gap does not open between the first two free nodes (the free surface lies on
        the indenter there): the edge is undefined.
    """
    last = np.flatnonzero(forces > 0)[-1]
    lowest, first = r[max(last - 1, 0)], r[last + 1]
    rise = gap[last + 2] ** (2 / 3) - gap[last + 1] ** (2 / 3)
    if rise == 0.0:
        raise NumericalFailureError(
            f"the free surface beyond the contact edge lies on the indenter (zero gap opening "
            f"at r = {first:.4g} m), so the contact radius is undefined"
        )
    linear = first - gap[last + 1] ** (2 / 3) * (r[last + 2] - first) / rise
    window = np.arange(r.size)[last + 1 :][EDGE_FIT_NODES]
    estimate = linear
    if window.size == EDGE_FIT_NODES.stop - EDGE_FIT_NODES.start:
        roots = np.roots(np.polyfit(r[window], gap[window] ** (2 / 3), 2))
        roots = roots[np.isreal(roots)].real
        near = roots[(roots >= lowest) & (roots <= first)]
        if near.size:
            estimate = near[np.argmin(np.abs(near - linear))]
    return float(np.clip(estimate, lowest, first))


CENTRE_SAMPLES = (1e-4, 1e-3, 1e-2)
"""Radii / a where the pressure is sampled to extrapolate it to the axis (ratio 10)."""


def mass_factor(mass: np.ndarray) -> tuple[np.ndarray, tuple]:
    """Jacobi-scaled Cholesky factor of the surface matrix (axis rows of M are ~h^2 small)."""
    scale = 1.0 / np.sqrt(np.diag(mass))
    return scale, la.cho_factor(mass * np.outer(scale, scale))


def recover_pressure(factor: tuple[np.ndarray, tuple], forces: np.ndarray) -> np.ndarray:
    """Nodal pressure p (Pa) with M p = F, from :func:`mass_factor`."""
    scale, scaled = factor
    return scale * la.cho_solve(scaled, scale * forces)


def central_pressure(r: np.ndarray, pressure: np.ndarray, contact_radius: float) -> float:
    """p(0) in Pa by Aitken's extrapolation of p at r = 1e-4 a, 1e-3 a, 1e-2 a.

    Near the axis p(r) = p0 + B r^s for a cusp of unknown order s > 0 (s = n - 1 for z = A r^n
    with n < 3), and on a geometric sequence of radii Aitken's delta-squared is exact for that
    form whatever s. The axis node's own value is not used: its basis function carries almost
    no 2 pi r weight, so the recovery there smears the cusp. Where the differences do not
    shrink geometrically toward the axis (a smooth centre, as for Hertz, or noise) the
    innermost sample is returned.
    """
    p1, p2, p3 = np.interp(contact_radius * np.asarray(CENTRE_SAMPLES), r, pressure)
    inner, outer = p2 - p1, p3 - p2
    if inner * outer <= 0 or abs(outer) <= abs(inner):
        return float(p1)
    return float(p1 - inner**2 / (outer - inner))


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

    Between two changes of the active set the discrete force is affine in the depth, so the
    discrete curve P(d) is a polygon whose chords cut the convex P ~ d^q: the nodal sum
    oscillates with the edge position. The polygon's corners, where the edge node carries no
    force, are discrete contacts whose edge lies on a node; on an element vertex no element
    straddles the edge, and the force error there is smallest. The force is interpolated as a
    power law (exact for any P = beta d^q) between the two vertex-aligned contacts around
    ``depth``: smooth in the depth. Where the two do not bracket the depth (an irregular
    active set), the nodal sum is returned.

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


def check_resolved(r: np.ndarray, forces: np.ndarray, depth: float) -> None:
    """InputError unless the contact at ``depth`` (m) loads at least ``MIN_CONTACT_NODES``
    surface nodes and stays ``EDGE_MARGIN`` nodes inside the candidates (radii ``r``, m)."""
    loaded = np.flatnonzero(forces > 0)
    if loaded.size < MIN_CONTACT_NODES:
        raise InputError(
            f"depth {depth:g} m: the contact loads {loaded.size} surface node(s), fewer than "
            f"{MIN_CONTACT_NODES}: smaller than this mesh resolves; raise the smallest depth or "
            f"refine the mesh (--mesh-size, --refine)"
        )
    if loaded[-1] + EDGE_MARGIN >= r.size:
        raise InputError(
            f"depth {depth:g} m: the contact zone reaches r = {r[loaded[-1]]:.4g} m, "
            f"the edge of the refined region ({r[-1]:.4g} m); mesh a larger region (raise "
            "--mesh-margin)"
        )


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
) -> ContactStep:
    """The contact step at ``depth`` (m) from the complementarity solution ``solved`` (nodal
    forces in N, gaps in m, iterations) against the indenter's ``heights`` (m) at the
    candidate nodes (a viscoelastic body's shifted by its history)."""
    forces, gap, iterations = solved
    discrete = float(forces.sum())
    check_resolved(compliance.r, forces, depth)
    pressure = recover_pressure(compliance.mass_factor, forces)
    radius = edge_radius(compliance.r, forces, gap)
    return ContactStep(
        depth=depth,
        force=aligned_force(compliance, heights, forces, depth) if aligned else discrete,
        discrete_force=discrete,
        contact_radius=radius,
        central_pressure=central_pressure(compliance.r, pressure, radius),
        nodal_forces=forces,
        pressure=pressure,
        gap=gap,
        iterations=iterations,
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
        step = self.steps[index]
        return postprocess(self.system, self.solutions[index], _contact_load(self, step))


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


def _contact_load(curve: ContactCurve, step: ContactStep) -> np.ndarray:
    load = np.zeros(curve.system.n_dofs)
    load[curve.compliance.dofs] = -step.nodal_forces
    if step.tangential_forces is not None:
        load[curve.compliance.radial_dofs] = step.tangential_forces
    return load


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


def check_contact_scale(
    youngs_modulus: float, radius: float, impact: tuple[float, float] | None = None
) -> None:
    """Refuse a contact zone of ``radius`` m on a body of ``youngs_modulus`` Pa whose ratio is
    below :data:`MIN_MODULUS_PER_LENGTH` Pa/m (the mixed u-p system loses digits there).
    ``impact``: the mass (kg) and velocity (m/s) whose x_c set the depths, named as the cause
    (None: the depths were given, E2 and the depths are named)."""
    ratio = youngs_modulus / radius
    if ratio >= MIN_MODULUS_PER_LENGTH:
        return
    where = (
        f"E2 / contact zone radius = {ratio:.3g} Pa/m is below {MIN_MODULUS_PER_LENGTH:g}: "
        "the mixed u-p system then loses digits (a soft body under a huge contact)"
    )
    if impact is None:
        raise InputError(f"E2, shape_coefficient: {where}; check them and the depths", "E2")
    raise InputError(
        f"mass, velocity: {impact[0]:g} kg at {impact[1]:g} m/s set the depths (up to the "
        f"impact's x_c), a contact zone of {radius:.3g} m: {where}; lower the mass or the "
        "velocity, or give the depths",
        "mass",
    )


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
    check_contact_scale(system.youngs_modulus, candidate_radius)
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


# --- a viscoelastic body pressed at a constant rate ----------------------------------------


CURVE_STEPS = 200
"""Time steps from first touch to the deepest depth, by default. On the paper's case (default
mesh) the forces change by 2.3e-5 (1 m/s) and 8.7e-5 (0.01 m/s, where the contact's node
arrivals within V tau dominate) from 200 to 400 steps, below the mesh's error there (1.3e-4);
the mesh ladder does not estimate this time error (benchmarks/FEM_NOTES.md)."""
MAX_CURVE_STEPS = 100_000
"""Most time steps of one curve."""


def time_grid(depths: np.ndarray, rate: float, steps: int) -> list[tuple[float, int]]:
    """The march's intervals between requested depths (m): (dt in s, count) each, uniform
    steps ending at the depth's instant d / V, ``steps`` over the whole curve (at least one
    per interval)."""
    if isinstance(steps, bool) or not isinstance(steps, int | np.integer):
        raise InputError(f"steps must be an integer >= 1, got {steps!r}", "steps")
    if not 1 <= steps <= MAX_CURVE_STEPS:
        raise InputError(f"steps must lie in [1, {MAX_CURVE_STEPS}], got {steps}", "steps")
    ends = np.concatenate([[0.0], np.asarray(depths, dtype=float) / rate])
    grid = []
    for start, end in itertools.pairwise(ends):
        count = max(1, math.ceil(steps * (end - start) / ends[-1] - 1e-9))
        grid.append(((end - start) / count, count))
    return grid


@dataclass
class _Interval:
    """One dt of the march: its Prony shear, factorization and surface compliance."""

    shear: ViscoelasticShear
    factorization: Factorization
    compliance: SurfaceCompliance


def _interval(
    system: ElasticSystem,
    prony: PronySeries,
    dt: float,
    free: np.ndarray,
    radius: float,
    backend: str,
) -> _Interval:
    """Assemble and factorize the step of ``dt`` s (candidates r <= ``radius`` m last)."""
    shear = viscoelastic_shear(system, prony, dt, radius)
    stepped = replace(system, matrix=shear.stiffness)
    factorization = factorize_stiffness(stepped, free, radius, backend)
    return _Interval(shear, factorization, surface_compliance(stepped, factorization, free, radius))


def _rate_step(
    part: _Interval, memory: ShearMemory, heights: np.ndarray, depth: float, free: np.ndarray
) -> tuple[tuple[np.ndarray, np.ndarray, int], np.ndarray, np.ndarray, ShearMemory]:
    """One time step at ``depth`` m: (forces, gap, active-set iterations), the heights
    shifted by the history, the full solution and the new memory."""
    compliance = part.compliance
    position = np.searchsorted(free, compliance.dofs)
    history = part.factorization.solve(memory.force[free])  # K^-1 h on the free dofs
    shifted = heights + history[position]
    forces, gap, iterations = complementarity(compliance.matrix, shifted - depth)
    load = -memory.force[free]
    load[position] -= forces
    x = np.zeros(memory.force.size)
    x[free] = part.factorization.solve(load)
    _, memory = part.shear.advance(memory, x)
    return (forces, gap, iterations), shifted, x, memory


def press_at_rate(
    system: ElasticSystem,
    profile: Profile,
    depths: np.ndarray,
    candidate_radius: float,
    prony: PronySeries,
    rate: float,
    *,
    backend: str = "auto",
    aligned: bool = True,
    steps: int = CURVE_STEPS,
) -> ContactCurve:
    """Press a rigid frictionless indenter z = f(r) into the viscoelastic body at ``rate``.

    Parameters as :func:`solve_contact` (``system`` with E2, nu2 the instantaneous moduli;
    each depth d reached at d / V; ``aligned``: the vertex-aligned forces at the instant's
    history, or the nodal sums), with ``prony`` the body's shear relaxation, ``rate`` the
    pressing speed V in m/s (> 0) and ``steps`` the time steps from first touch to the deepest
    depth (:func:`time_grid`).

    Returns
    -------
    ContactCurve
        One step per depth; ``timings``: ``factorization`` (all intervals') and ``contact``.
    """
    free = system.free_dofs()
    heights: np.ndarray | None = None
    memory: ShearMemory | None = None
    steps_out, solutions, parts, factorized = [], [], {}, 0.0
    start = time.perf_counter()
    with threadpool_limits(limits=1, user_api="blas"):
        for k, (dt, count) in enumerate(time_grid(depths, rate, steps)):
            clock = time.perf_counter()
            if dt not in parts:
                parts[dt] = _interval(system, prony, dt, free, candidate_radius, backend)
            part = parts[dt]
            factorized += time.perf_counter() - clock
            if heights is None:
                heights = np.asarray(profile(part.compliance.r), dtype=float)
            memory = part.shear.first_memory() if memory is None else part.shear.resume(memory)
            begin = 0.0 if k == 0 else float(depths[k - 1]) / rate
            for j in range(1, count + 1):
                depth = float(depths[k]) if j == count else rate * (begin + j * dt)
                solved, shifted, x, memory = _rate_step(part, memory, heights, depth, free)
            steps_out.append(step_from_forces(part.compliance, shifted, depth, solved, aligned))
            solutions.append(x)
    seconds = (factorized, time.perf_counter() - start - factorized)
    parts = (part.compliance, steps_out, np.array(solutions))
    return timed_curve(system, parts, part.factorization, backend, seconds)
