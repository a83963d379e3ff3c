"""Frictionless contact of a rigid power-law indenter with a neo-Hookean half-space, finite strain.

A candidate surface node (reference radius R_i, displacement (u_r, u_z)) keeps the vertical gap

    g_i(u) = f(R_i + u_{r,i}) - d - u_{z,i} >= 0,

f evaluated at the current radius; the multipliers lambda_i >= 0 (N) sum to the indenter force
P. A semi-smooth (primal-dual active-set) Newton solves the KKT system with the consistent
tangent, the active constraints eliminated (:func:`eliminate_gaps`); a modified Newton reuses
factorizations on the depth ladder and in an impact's time steps. A depth step that fails is
halved up to ``max_cuts`` times, then a :class:`~shtaerman.fem.hyperelastic.NewtonError` is
raised. Derivation, convergence rules and measurements: benchmarks/FEM_NOTES.md, "Moved from
the docstrings", fem/contact/finite.py."""

from __future__ import annotations

import time
from collections.abc import Callable
from dataclasses import dataclass, field, replace
from typing import Any

import numpy as np
import scipy.sparse as sp
import scipy.sparse.linalg as spla
from numpy.typing import ArrayLike

from ...guards import (
    DEPTHS_INSTEAD,
    MAX_DEPTH_RATIO,
    MIN_DEPTH_RATIO,
    MIN_FINITE_DEPTH_RATIO,
    LockingWatch,
    check_reach,
    deepest_depth_remedy,
    depth_ratio,
)
from ...theory.contact import PowerLawContact
from ...theory.indenter import PowerLawIndenter
from ...theory.materials import Material
from ...theory.sneddon import Indenter, SneddonContact, contact_law
from ...validation import InputError, LimitError, NumericalFailureError, validate_poisson
from ..elasticity import clamped_dofs, dof_nodes
from ..hyperelastic import (
    HyperelasticSystem,
    NeoHookean,
    NewtonError,
    assemble_hyperelastic,
)
from ..mesh import FINITE_MESH, HALF_SPACE, Geometry, MeshSettings
from ..rubber import GentLimitError, RubberModel, gent_locks, gent_stretch
from ..solver import Pattern, PatternSolver
from .constraints import SolvedContact, check_resolved, edge_and_centre

NEWTON_TOLERANCE = 1e-8
"""Converged when the active set repeats and the last correction max |du| <= this * depth;
below ``ROUND_OFF_FLOOR`` a correction that no longer shrinks (ratio > 1/2) counts as converged."""
ROUND_OFF_FLOOR = 1e-6
CONTRACTION = 0.2
"""A modified Newton step (the last factorization reused) must shrink the correction by this
factor, else the next step takes a fresh tangent."""
BORDER = 8
"""Candidates at which the active set of a curve's first Newton step at a depth may differ
from that of the factorization kept from the depth before, for the step to reuse it
(:func:`bordered_step`: one back-solve more per candidate, against a factorization)."""
MAX_ITERATIONS = 30
MAX_CUTS = 8
GENT_BACKTRACKS = 2
"""Halvings of a Newton update whose iterate passes a Gent rubber's limit, in every stepper
(other updates only where ``backtracks`` is set)."""
SQUEEZED_J = 0.5
"""Pointwise det F below which a failed contact is put down to the elements about the tip,
not to the mesh size (:func:`squeeze_note`)."""
TIP_SLOPE = 0.1
"""A power law's slope f'(h) at the finest axis element h above which the curve's mesh is
graded at the axis no finer than :data:`NEAR_CONE_AXIS` (:func:`tip_mesh`)."""
NEAR_CONE_AXIS = 0.06
"""The axis element / the smallest element size of a near-cone's mesh (1e-3 of the refined
radius on :data:`.mesh.FINITE_MESH`): the first Newton step from the undeformed body is
linear, its strain beside the tip about f'(h) ln(a / h), and on the 1e-6 grading it inverted
the tip elements for z = 0.5 r^1.05 (f'(h) = 0.19) and z = 0.8 r^1.1 (0.13) at every halving
of the step, while 0.5 r^1.1 (0.07) runs (benchmarks/FEM_NOTES.md, "Near a cone")."""
_GAUSS = np.polynomial.legendre.leggauss(4)


@dataclass(frozen=True)
class FiniteContactStep(SolvedContact):
    """Converged finite-strain contact at one depth: the :class:`.constraints.SolvedContact`
    (``force`` P = sum lambda; the contact radius in the current configuration; the Cauchy
    pressures; ``gap`` vertical) and

    Attributes
    ----------
    strain_energy : float
        Stored strain energy Pi of the whole body in J.
    newton_iterations : int
        Newton iterations of the last sub-step that reached this depth (all sub-steps: see
        ``total_iterations``).
    total_iterations : int
        Newton iterations over all sub-steps since the previous depth.
    force_linear, contact_radius_linear, central_pressure_linear : float
        Shtaerman's exact linear values at the same depth (N, m, Pa).
    solution : numpy.ndarray
        Converged x = [u (m), p (Pa)] (see :class:`shtaerman.fem.hyperelastic.HyperelasticSystem`).
    multipliers : numpy.ndarray
        lambda >= 0 (N) on the candidate nodes.
    current_radius : numpy.ndarray
        R + u_r (m) of the candidate nodes.
    surface_u_z : numpy.ndarray
        u_z (m) of the candidate nodes: the gap is f(current_radius) - depth - surface_u_z.
    corrections : list of float
        max |du| / depth of each Newton iteration of the last sub-step.
    """

    strain_energy: float
    newton_iterations: int
    total_iterations: int
    force_linear: float
    contact_radius_linear: float
    central_pressure_linear: float
    solution: np.ndarray = field(repr=False)
    multipliers: np.ndarray = field(repr=False)
    current_radius: np.ndarray = field(repr=False)
    surface_u_z: np.ndarray = field(repr=False)
    corrections: list[float] = field(repr=False)


@dataclass(frozen=True, eq=False)
class _Candidates:
    """Surface nodes that may touch: u_z and u_r dofs, reference radii, sorted by R."""

    uz: np.ndarray
    ur: np.ndarray
    radius: np.ndarray
    ur_free: np.ndarray  # False on the axis (u_r clamped)

    @classmethod
    def of(cls, system: HyperelasticSystem, radius: float, fixed: np.ndarray) -> _Candidates:
        """The surface nodes with R <= ``radius`` (m) of ``system`` (``fixed``: its clamped
        dofs)."""
        ubasis = system.displacement_basis
        partner = np.full(ubasis.N, -1, dtype=np.int64)
        partner[ubasis.nodal_dofs[1]] = ubasis.nodal_dofs[0]
        partner[ubasis.facet_dofs[1]] = ubasis.facet_dofs[0]
        uz = ubasis.get_dofs("surface").all("u^2")
        uz = np.setdiff1d(uz, ubasis.get_dofs("far").all())
        r = ubasis.doflocs[0, uz]
        keep = r <= radius * (1 + 1e-12)
        uz, r = uz[keep], r[keep]
        order = np.argsort(r)
        uz, r = uz[order], r[order]
        if r.size % 2 == 0 or r[0] != 0.0:
            raise InputError(
                "candidate_radius must fall on a surface vertex of the mesh (the refined radius)"
            )
        ur = partner[uz]
        return cls(uz, ur, r, ~np.isin(ur, fixed))


@dataclass
class _Sets:
    """The active sets of one Newton solve (:meth:`NewtonStepper.solve`): the last two
    iterations' and whether the axis candidate (index 0) is tied to its ring: once it has
    flipped twice while the first edge's midside candidate (index 1) is in contact, it is in
    contact wherever that one is."""

    previous: np.ndarray | None = None
    before: np.ndarray | None = None
    tied: bool = False

    def next(self, active: np.ndarray) -> np.ndarray | None:
        """Record this iteration's ``active`` set (the axis candidate tied in place); return
        the previous iteration's (None on the first)."""
        previous, before = self.previous, self.before
        if not self.tied and before is not None and active.size > 1:
            self.tied = bool(active[1] and active[0] == before[0] != previous[0])
        if self.tied and active[1]:
            active[0] = True
        self.before, self.previous = previous, active
        return previous


def _surface_mass(x: np.ndarray) -> np.ndarray:
    """P2 matrix int N_i N_j 2 pi r dr on the current radii x (edges = consecutive triples)."""
    points, weights = _GAUSS
    xi = 0.5 * (points + 1.0)
    weights = 0.5 * weights
    shapes = np.array([(1 - xi) * (1 - 2 * xi), 4 * xi * (1 - xi), xi * (2 * xi - 1)])
    slopes = np.array([4 * xi - 3, 4 - 8 * xi, 4 * xi - 1])
    mass = np.zeros((x.size, x.size))
    for k in range(0, x.size - 2, 2):
        nodes = x[k : k + 3]
        position, jacobian = nodes @ shapes, nodes @ slopes
        weight = weights * 2 * np.pi * position * jacobian
        mass[k : k + 3, k : k + 3] += (shapes * weight) @ shapes.T
    return mass


@dataclass(frozen=True, eq=False)
class FiniteContactCurve:
    """Finite-strain contact over a depth ladder, and what it cost.

    Attributes
    ----------
    steps : list of FiniteContactStep
        One per requested depth, ascending.
    system : HyperelasticSystem
    indenter : PowerLawIndenter
    timings : dict of str to float
        Seconds: ``contact`` (all Newton steps), and after :func:`run_finite_indentation`
        also ``mesh``, ``assembly`` and ``total``.
    mesh_stats : dict
        ``nodes``, ``elements``, ``dofs``, ``contact_candidates`` ...
    cuts : int or None
        The bonded or Coulomb curve's load steps cut in halves where they failed
        (:func:`.finite_stick.solve_finite_bonded_contact`); None for the frictionless
        curve, whose sub-steps adapt by design.
    """

    steps: list[FiniteContactStep]
    system: HyperelasticSystem
    indenter: PowerLawIndenter
    timings: dict[str, float]
    mesh_stats: dict[str, float] = field(default_factory=dict)
    cuts: int | None = None


class NewtonStepper:
    """Newton with active set for one depth increment; state kept between increments."""

    redone_in_full = True
    """A solve whose reused factorization's update inverts an element fails, and :meth:`solve`
    redoes it as a full Newton (False: the update is halved, as a fresh one's)."""

    def __init__(
        self,
        system: HyperelasticSystem,
        indenter: PowerLawIndenter,
        candidate_radius: float,
        tolerance: float,
        max_iterations: int,
    ) -> None:
        self.system = system
        self.indenter = indenter
        self.fixed = clamped_dofs(system.displacement_basis)
        self.free = np.setdiff1d(np.arange(system.n_dofs), self.fixed)
        self.position = np.full(system.n_dofs, -1, dtype=np.int64)
        self.position[self.free] = np.arange(self.free.size)
        self.nodes = _Candidates.of(system, candidate_radius, self.fixed)
        self.n_free_u = int(np.searchsorted(self.free, system.n_displacement))
        self.pattern, self.take = system.pattern.submatrix(self.free)
        self.curvature_at = self.pattern.diagonal[self.position[self.nodes.ur[self.nodes.ur_free]]]
        nodes = dof_nodes(system.displacement_basis, system.pressure_basis)[self.free]
        self.solver = PatternSolver(self.pattern, nodes)
        self.tolerance = tolerance
        self.max_iterations = max_iterations
        self.backtracks = 0  # halvings of an update that inverts an element (0: raise)
        self.factorization: Callable[[np.ndarray], np.ndarray] | None = None  # the last one
        self.kept: tuple | None = None  # system, rows, tangent, factorization of a fresh step
        self.modified = False  # reuse factorizations (curves and impacts set it)
        self.border = 0  # candidates a reused factorization's set may differ at (a curve's)
        material = system.material
        # complementarity weight c (N/m): lambda_i and c g_i of comparable size
        self.weight = material.shear_modulus * candidate_radius / self.nodes.radius.size
        self.stretch = 0.0  # a Gent rubber's, of the last solve whose converged state it has
        self.watch = LockingWatch(getattr(material, "gent_limit", np.inf))  # the run's states

    def folded(self, x: np.ndarray) -> bool:
        """Whether the candidates' current radii (m) have crossed (or the axis)."""
        r = self.nodes.radius + x[self.nodes.ur]
        return bool(np.any(r[1:] <= 0) or np.any(np.diff(r) <= 0))

    def geometry(self, x: np.ndarray, depth: float) -> tuple[np.ndarray, ...]:
        """Current radii, gap g, f'(r) and f''(r) at the candidates."""
        if self.folded(x):
            raise NewtonError("the contact surface folded (candidate nodes crossed)")
        r = np.maximum(self.nodes.radius + x[self.nodes.ur], 0.0)
        gap = self.indenter.profile(r) - depth - x[self.nodes.uz]
        # the axis node's u_r is clamped: its curvature never enters
        return r, gap, self.indenter.slope(r), self.indenter.curvature(r)

    def solve(
        self,
        depth: float,
        x: np.ndarray,
        lam: np.ndarray,
        scale: float | None = None,
        *,
        reach: float | None = None,
        base: tuple[np.ndarray, np.ndarray] | None = None,
    ) -> tuple[np.ndarray, np.ndarray, int, list[float]]:
        """Newton from (x, lambda) at ``depth`` (from ``base``, the last converged (x, lambda),
        where that guess is no state of the body); raises NewtonError on failure. The corrections
        are measured relative to ``scale`` (m, default ``depth``; give it where depth <= 0).
        ``reach`` (m): the first iteration's active set leaves out the candidates beyond it
        (:func:`predict_reach`). A ``modified`` Newton that fails after reusing a factorization is
        redone as a full one."""
        scale = depth if scale is None else scale
        system, nodes, sets = self.system, self.nodes, _Sets()
        reused: list[bool] = []  # per step: whether it reused a factorization

        def increment(x: np.ndarray, lam: np.ndarray, state: Any, *history: list) -> Any:
            _, gap, slope, curvature = self.geometry(x, depth)
            active = lam - self.weight * gap > 0
            if reach is not None and sets.previous is None:  # the guess overshoots the edge
                active &= nodes.radius < reach
            previous = sets.next(active)
            lam[~active] = 0.0
            if previous is not None and self.settled(active, previous, lam, gap, scale):
                if self.converged(*history):
                    return check_axis_ring(lam, sets.tied)
            residual = system.residual(x, state)
            np.subtract.at(residual, nodes.ur, lam * slope)
            np.add.at(residual, nodes.uz, lam)
            rows = np.flatnonzero(active)
            reuse = self.reusable(rows, *history)
            reused.append(reuse)
            contact = (rows, slope, gap, curvature)
            du, dlam = self.linear_step(x, lam, state, residual, contact, reuse)
            return du, rows, dlam, not reuse, False

        try:
            return self.iterate((x, lam), scale, increment, base)
        except NewtonError:
            if not self.modified:
                raise
            if not any(reused):  # a full Newton already: the redo would repeat it exactly
                self.kept = self.kept if reused else None  # as the redo would leave it
                raise
        # a modified Newton that failed is redone in full: it fails only where full Newton does
        self.modified, self.kept, sets = False, None, _Sets()
        try:
            return self.iterate((x, lam), scale, increment, base)
        finally:
            self.modified = True

    def iterate(
        self,
        start: tuple[np.ndarray, np.ndarray],
        scale: float,
        increment: Callable[..., Any],
        base: tuple[np.ndarray, np.ndarray] | None = None,
    ) -> tuple[np.ndarray, np.ndarray, int, list[float]]:
        """Newton's loop from ``start`` = (x, the multipliers lambda (N) of the candidates), or
        from ``base`` where ``start`` is no state of the body.

        ``increment(x, lambda, state, corrections, fresh)`` gives (du, the candidates its
        dlambda acts on, dlambda, whether made with a fresh tangent, whether to test the
        convergence after it), or None where the iterate before it has converged. An update
        that inverts an element fails the solve where it reused a factorization
        (``redone_in_full``), else is halved, up to ``backtracks`` times. Returns x, lambda, the
        iterations and the corrections (max |du| / ``scale``).

        Raises
        ------
        NewtonError
            No convergence in ``max_iterations``, or an element inverted.
        GentLimitError
            An iterate past a Gent rubber's limit after its halvings, or no convergence where
            iterates passed it (:func:`.rubber.gent_locks`).
        """
        admitted = self.admit(start[0])
        if admitted[1] is not None and base is not None:
            start, admitted = base, self.admit(base[0])
        x, lam = start[0].copy(), start[1].copy()
        corrections: list[float] = []
        fresh: list[bool] = []  # per correction: made with a fresh tangent (else reused)
        step, halvings, limited = None, 0, False
        for iteration in range(1, self.max_iterations + 1):
            state, outside = admitted if iteration == 1 else self.admit(x)
            if outside is not None:
                if step is not None and not fresh[-1] and self.redone_in_full:
                    raise NewtonError(f"an update of a reused factorization: {outside}")
                gent = isinstance(outside, GentLimitError)
                limited |= gent
                most = max(self.backtracks, GENT_BACKTRACKS) if gent else self.backtracks
                if step is None or halvings == most:
                    raise outside
                halvings += 1  # back-track: halve the last update
                step = (0.5 * step[0], step[1], 0.5 * step[2])
                x[self.free] -= step[0]
                lam[step[1]] -= step[2]
                continue
            halvings = 0
            try:
                made = increment(x, lam, state, corrections, fresh)
            except NewtonError:  # a RuntimeError too: its own message (a folded surface)
                raise
            except RuntimeError as error:
                raise NewtonError(f"singular Newton matrix ({error})") from None
            if made is None:  # x's state is at hand: its Gent stretch costs no evaluation
                self.stretch = gent_stretch(self.system.material, state)
                return x, lam, iteration - 1, corrections
            du, rows, dlam, tangent_fresh, test = made
            fresh.append(tangent_fresh)
            x[self.free] += du
            lam[rows] += dlam
            step = (du, rows, dlam)
            corrections.append(float(np.max(np.abs(du[: self.n_free_u]))) / scale)
            if not np.isfinite(corrections[-1]):
                break
            if test and self.converged(corrections, fresh):
                return x, lam, iteration, corrections
        failed = f"Newton did not converge in {self.max_iterations} iterations"
        if limited:  # the rubber's limit in the way: a lock where the step starts undeformed
            raise GentLimitError(f"{failed}, its iterates passing the gent limit")
        raise NewtonError(failed)

    def admit(self, x: np.ndarray) -> tuple[Any, NewtonError | None]:
        """The kinematics of the iterate x, and why it is no state of the body (None where it
        is one): an element inverted, a Gent rubber past its limit (a GentLimitError), or, where
        the stepper back-tracks, a folded contact surface."""
        try:
            state = self.system.state(x)
        except GentLimitError as error:
            return None, error
        inverted = not np.all(np.isfinite(state.J)) or np.min(state.J) <= 0  # J <= 0 or nan
        if inverted or (self.backtracks and self.folded(x)):
            return state, NewtonError("an element inverted (J <= 0)")
        return state, None

    def settled(
        self,
        active: np.ndarray,
        previous: np.ndarray,
        lam: np.ndarray,
        gap: np.ndarray,
        scale: float,
    ) -> bool:
        """Whether the ``active`` set repeats ``previous``: equal, or differing only at
        candidates where |lambda_i| <= ``tolerance`` * P (N, P = sum |lambda|) and the gap
        |g_i| <= ``tolerance * scale`` (m)."""
        changed = active != previous
        if not changed.any():
            return True
        force = self.tolerance * float(np.abs(lam).sum())
        return bool(
            np.all(np.abs(lam[changed]) <= force)
            and np.all(np.abs(gap[changed]) <= self.tolerance * scale)
        )

    def reusable(self, rows: np.ndarray, corrections: list[float], fresh: list[bool]) -> bool:
        """Whether the next step may reuse the last factorization (:meth:`may_reuse`), made for
        the active set ``rows`` (on a solve's first step, for one that differs from ``rows`` at
        no more than ``border`` candidates: :func:`bordered_step`)."""
        kept = self.kept
        if kept is None or not self.may_reuse(kept[0], corrections, fresh):
            return False
        if np.array_equal(kept[1], rows):
            return True
        return not fresh and np.setxor1d(kept[1], rows).size <= self.border

    def may_reuse(self, made_for: Any, corrections: list[float], fresh: list[bool]) -> bool:
        """Whether a kept tangent ``made_for`` a system may serve the next step: the stepper is
        ``modified``, the system is its own, and the last step was fresh or the solve's first, or
        its correction shrank by :data:`CONTRACTION`."""
        slowed = len(fresh) > 1 and not fresh[-1] and not self.contracting(corrections)
        return self.modified and made_for is self.system and not slowed

    def contracting(self, corrections: list[float]) -> bool:
        """Whether the last correction is at most :data:`CONTRACTION` times the one before."""
        return len(corrections) > 1 and corrections[-1] <= CONTRACTION * corrections[-2]

    def converged(self, corrections: list[float], fresh: list[bool]) -> bool:
        """:func:`newton_converged` after a fresh tangent's step; after a reused one, also a
        contraction by :data:`CONTRACTION` and no round-off floor."""
        if fresh[-1]:
            return newton_converged(corrections, self.tolerance)
        return corrections[-1] <= self.tolerance and self.contracting(corrections)

    def linear_step(
        self,
        x: np.ndarray,
        lam: np.ndarray,
        state: Any,
        residual: np.ndarray,
        contact: tuple[np.ndarray, ...],
        reuse: bool,
    ) -> tuple[np.ndarray, np.ndarray]:
        """Newton's (du, dlambda) for the active ``rows`` with the consistent tangent at x,
        factorized and kept; or, if ``reuse``, with the kept tangent and factorization."""
        rows, slope, gap, curvature = contact
        if reuse:
            tangent, again = self.kept[2], self.kept[3]
            if not np.array_equal(self.kept[1], rows):
                sets = (self.kept[1], rows)
                return bordered_step(self, tangent, residual[self.free], sets, slope, gap)
            return eliminate_gaps(self, tangent, residual[self.free], rows, slope, gap, again=again)
        tangent = self.system.tangent_data(x, state)[self.take]  # free dofs
        tangent[self.curvature_at] -= (lam * curvature)[self.nodes.ur_free]  # -lam d2g/du_r^2
        step = eliminate_gaps(self, tangent, residual[self.free], rows, slope, gap)
        self.kept = (self.system, rows, tangent, self.factorization)
        return step


def squeeze_note(system: Any, x: np.ndarray, steps: str) -> str | None:
    """What a failed contact's message says where its last converged state x (of ``system``)
    squeezes some element below J = :data:`SQUEEZED_J` (None where none); ``steps``: the
    caller's own steps, in its options' words ("more time_steps=...")."""
    J = system.state(x).J
    if np.min(J) >= SQUEEZED_J:
        return None
    element = np.unravel_index(np.argmin(J), J.shape)[0]
    mesh = system.displacement_basis.mesh
    r, z = mesh.p[:, mesh.t[:3, element]].mean(axis=1)
    return (
        f"the last converged state squeezes the element at R {r:.2g} m, {-z:.2g} m below the "
        f"surface, to J = {np.min(J):.2g} (det F, pointwise; 1 in an undeformed body): the "
        "elements beside the indenter's tip no longer follow the deformation, a limit that "
        f"neither a finer mesh_size=... nor {steps} move"
    )


class SqueezedTipError(NumericalFailureError):
    """A time step of the body with inertia failed, in every cut, from a state that squeezes
    an element beside the striker's tip below :data:`SQUEEZED_J` (:func:`squeeze_note`)."""


def check_axis_ring(lam: np.ndarray, tied: bool) -> None:
    """Accept a converged solve whose axis candidate was ``tied`` to its ring (:class:`_Sets`)
    unless its pull -lambda_0 (N) exceeds the push lambda_1 of the first edge's midside
    candidate (NewtonError: the surface lifts off the indenter's tip)."""
    if tied and lam[0] + lam[1] < 0:
        raise NewtonError(
            f"the axis node pulls the indenter by {-lam[0]:.3g} N where the ring about it "
            f"pushes {lam[1]:.3g} N: the surface lifts off the indenter's tip"
        )


def newton_converged(corrections: list[float], tolerance: float) -> bool:
    last = corrections[-1]
    if last <= tolerance:
        return True
    stalled = len(corrections) > 1 and last > 0.5 * corrections[-2]
    return last <= ROUND_OFF_FLOOR and stalled


def eliminate_gaps(
    stepper: NewtonStepper,
    tangent: np.ndarray,
    residual: np.ndarray,
    rows: np.ndarray,
    slope: np.ndarray,
    gap: np.ndarray,
    drag: np.ndarray | None = None,
    again: Callable[[np.ndarray], np.ndarray] | None = None,
) -> tuple[np.ndarray, np.ndarray]:
    """Newton step (du, dlambda) of the saddle system [[K, -G_A^T], [-G_A, 0]] by eliminating
    the constraints.

    The active node i's linearized constraint fixes du_z = f'(r_i) du_r + g_i; with
    du = T y + c the step solves T^T K T y = -T^T (R + K c) in K's fixed pattern, and
    dlam_i = -(R + K du)_{u_z,i}. ``tangent`` is K's data in ``stepper.pattern``. ``drag``
    (per candidate, slip direction x Coulomb coefficient; None: 0) turns each multiplier's
    push from the normal to the friction cone's edge (Q^T K T, no longer symmetric).
    ``again``: solve with this factorization of an earlier T^T K T instead of factorizing;
    else the new factorization is left in ``stepper.factorization``."""
    pattern = stepper.pattern
    slaves, ok, target, coefficient = elimination(stepper, rows, slope)
    left, normal = coefficient, 1.0
    if drag is not None:
        normal = 1.0 + drag[rows] * slope[rows]
        left = coefficient.copy()
        left[slaves[ok]] = ((slope[rows] - drag[rows]) / normal)[ok]
    shift = np.zeros(pattern.size)
    shift[slaves] = gap[rows]
    load = residual + column_product(pattern, tangent, slaves, gap[rows])  # K shift
    rhs = -np.bincount(target, weights=left * load, minlength=pattern.size)  # -Q^T load
    if again is None:
        reduced = reduce_tangent(pattern, tangent, slaves, target, left, coefficient)
        solution, stepper.factorization = stepper.solver.factorized(reduced, rhs)
    else:
        solution = again(rhs)
    du = coefficient * solution[target] + shift
    dlam = -(residual[slaves] + row_product(pattern, tangent, slaves, du)) / normal
    return du, dlam


def elimination(
    stepper: NewtonStepper, rows: np.ndarray, slope: np.ndarray
) -> tuple[np.ndarray, ...]:
    """T of :func:`eliminate_gaps` for the active ``rows`` (``slope``: f'(r) at the
    candidates): the slaves (u_z of ``rows``, positions among the free dofs), which of them
    have a free u_r, each dof's ``target`` (the slave's u_r, else itself) and its
    ``coefficient`` (f'(r) for a slave with a free u_r, 0 for the axis slave, else 1)."""
    nodes, position, size = stepper.nodes, stepper.position, stepper.pattern.size
    slaves = position[nodes.uz[rows]]
    ok = nodes.ur_free[rows]
    target = np.arange(size)
    target[slaves[ok]] = position[nodes.ur[rows][ok]]
    coefficient = np.ones(size)
    coefficient[slaves] = 0.0
    coefficient[slaves[ok]] = slope[rows][ok]
    return slaves, ok, target, coefficient


def bordered_step(
    stepper: NewtonStepper,
    tangent: np.ndarray,
    residual: np.ndarray,
    sets: tuple[np.ndarray, np.ndarray],
    slope: np.ndarray,
    gap: np.ndarray,
) -> tuple[np.ndarray, np.ndarray]:
    """A modified Newton step (du, dlambda) for the active ``rows`` with the kept tangent K
    (``tangent``) and the kept factorization of its reduced matrix for another active set
    (``sets`` = (kept, rows)): the step of :func:`eliminate_gaps` for ``rows``, solved by
    bordering the kept factorization with the changed candidates (one solve each) and a small
    Schur complement."""
    kept, rows = sets
    nodes, position, size = stepper.nodes, stepper.position, stepper.pattern.size
    again = stepper.kept[3]
    _, _, target, coefficient = elimination(stepper, kept, slope)
    matrix = stepper.pattern.matrix(tangent)
    common = np.intersect1d(kept, rows)
    shift = np.zeros(size)
    shift[position[nodes.uz[common]]] = gap[common]
    load = residual + matrix @ shift
    released = position[nodes.uz[np.setdiff1d(kept, rows)]]
    added = np.setdiff1d(rows, kept)
    border = np.zeros((size, released.size + added.size))
    for k, z in enumerate(released):  # P = T^T K E
        weights = coefficient * matrix[:, [z]].toarray()[:, 0]
        border[:, k] = np.bincount(target, weights=weights, minlength=size)
    for k, j in enumerate(added, start=released.size):  # the constraint's gradient g_j
        border[position[nodes.uz[j]], k] = 1.0
        if nodes.ur_free[j]:
            border[position[nodes.ur[j]], k] = -slope[j]
    solved = np.column_stack([again(column) for column in border.T])
    first = again(-np.bincount(target, weights=coefficient * load, minlength=size))
    schur = -border.T @ solved
    schur[: released.size, : released.size] += matrix[released][:, released].toarray()
    rhs = np.concatenate([-load[released], gap[added]]) - border.T @ first
    w = np.linalg.solve(schur, rhs)
    y = first - solved @ w
    du = coefficient * y[target] + shift
    du[released] += w[: released.size]
    dlam = -(residual + matrix @ du)[position[nodes.uz[rows]]]
    return du, dlam


def reduce_tangent(
    pattern: Pattern,
    tangent: np.ndarray,
    slaves: np.ndarray,
    target: np.ndarray,
    left: np.ndarray,
    coefficient: np.ndarray,
) -> np.ndarray:
    """Q^T K T's data in ``pattern``: the slaves' rows and columns moved onto their
    ``target`` masters with the weights ``left`` (rows) and ``coefficient`` (columns), the
    slaves kept as decoupled unit rows (see :func:`eliminate_gaps`)."""
    moved = pattern_entries(pattern, slaves)
    i, j = pattern.indices[moved], pattern.columns[moved]
    reduced = tangent.copy()
    reduced[moved] = 0.0
    np.add.at(
        reduced,
        pattern.find(target[i], target[j]),
        left[i] * coefficient[j] * tangent[moved],
    )
    reduced[pattern.diagonal[slaves]] = 1.0
    return reduced


def pattern_entries(pattern: Pattern, columns: np.ndarray) -> np.ndarray:
    """Indices in ``data`` of the entries in the rows or columns ``columns`` (sorted, unique)."""
    in_columns, _ = _column_entries(pattern, columns)
    both = np.sort(np.concatenate([in_columns, pattern.transpose[in_columns]]))
    first = np.ones(both.size, dtype=bool)  # np.union1d's, for 1/10 of its CPU (numpy 2.4)
    first[1:] = both[1:] != both[:-1]
    return both[first]


def _column_entries(pattern: Pattern, columns: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Indices in ``data`` of the entries of ``columns``, column by column, and their counts."""
    starts = pattern.indptr[columns]
    counts = pattern.indptr[columns + 1] - starts
    shifts = np.repeat(starts - np.cumsum(counts) + counts, counts)  # start - entries before
    return shifts + np.arange(shifts.size), counts


def column_product(
    pattern: Pattern, data: np.ndarray, columns: np.ndarray, values: np.ndarray
) -> np.ndarray:
    """A v for A of ``data`` in ``pattern`` and v zero but ``values`` at ``columns``
    (unique): the sums of ``pattern.matrix(data) @ v`` (column by column, in increasing
    order) without its zero columns, so bitwise the same at a fraction of its cost."""
    order = np.argsort(columns)
    entries, counts = _column_entries(pattern, columns[order])
    weights = data[entries] * np.repeat(values[order], counts)
    return np.bincount(pattern.indices[entries], weights=weights, minlength=pattern.size)


def row_product(pattern: Pattern, data: np.ndarray, rows: np.ndarray, x: np.ndarray) -> np.ndarray:
    """(A x)[rows] for A of ``data`` in the symmetric ``pattern``: row i's entries (those of
    column i, mirrored) summed in increasing column order, as ``pattern.matrix(data) @ x``
    sums them, so bitwise its entries ``rows``."""
    entries, counts = _column_entries(pattern, rows)
    weights = data[pattern.transpose[entries]] * x[pattern.indices[entries]]
    return np.bincount(np.repeat(np.arange(rows.size), counts), weights, minlength=rows.size)


def solve_finite_contact(
    system: HyperelasticSystem,
    indenter: PowerLawIndenter,
    depths: ArrayLike,
    candidate_radius: float,
    *,
    tolerance: float = NEWTON_TOLERANCE,
    max_iterations: int = MAX_ITERATIONS,
    max_cuts: int = MAX_CUTS,
) -> FiniteContactCurve:
    """Press a rigid power-law indenter into the neo-Hookean half-space to each depth.

    Parameters
    ----------
    system : HyperelasticSystem
        On a half-space mesh (boundaries "axis", "surface", "far"; u_r clamped on the axis,
        everything on the far arc).
    indenter : PowerLawIndenter
        z = A r^n with n > 1.
    depths : array_like
        Depths in m, positive and strictly increasing (the entry points check them); any
        ladder (sub-steps are internal).
    candidate_radius : float
        Surface nodes with reference R <= this (m, a mesh vertex: the refined radius) may touch.
    tolerance : float
        Newton tolerance on max |du| / depth.
    max_iterations : int
        Newton iterations per sub-step before the step is cut.
    max_cuts : int
        Halvings of a failing sub-step before giving up.

    Returns
    -------
    FiniteContactCurve

    Raises
    ------
    NewtonError
        A sub-step failed ``max_cuts`` times (no convergence, or an inverted element).
    ContactOutgrowsMeshError
        The contact zone reached the edge of the candidate region.
    """
    depths = np.atleast_1d(np.asarray(depths, dtype=float))  # checked where they entered
    start = time.perf_counter()
    limits = (candidate_radius, tolerance, max_iterations)
    stepper, exact = start_curve(NewtonStepper, system, indenter, depths, limits)
    stepper.border = BORDER
    history = [(0.0, np.zeros(system.n_dofs), np.zeros(stepper.nodes.radius.size))]
    steps = []
    for target in depths:
        history, iterations, total, corrections = _reach(stepper, history, target, max_cuts, exact)
        _, x, lam = history[-1]
        steps.append(finite_step(stepper, exact, target, x, lam, iterations, total, corrections))
    timings = {"contact": time.perf_counter() - start}
    return FiniteContactCurve(steps, system, indenter, timings)


def start_curve(
    kind: type[NewtonStepper],
    system: HyperelasticSystem,
    indenter: PowerLawIndenter,
    depths: np.ndarray,
    limits: tuple[float, float, int],
) -> tuple[NewtonStepper, PowerLawContact | SneddonContact]:
    """The ``modified`` stepper ``kind(system, indenter, *limits)`` of a contact curve to the
    ``depths`` (m; ``limits``: candidate radius in m, Newton tolerance, iterations) and the
    small-strain contact whose exact values each step reports, after refusing an exponent
    <= 1 and a smallest depth the mesh cannot resolve (:func:`check_smallest_depth`)."""
    if indenter.kind == "power-law" and indenter.exponent <= 1.0:
        raise InputError(
            f"exponent must be > 1 for the finite-strain contact, got {indenter.exponent!r}"
        )
    stepper = kind(system, indenter, *limits)
    stepper.modified = True
    check_smallest_depth(stepper, contact_law(indenter, 1.0), float(depths[0]))
    material = system.material
    modulus = material.youngs_modulus / (1.0 - material.poisson_ratio**2)
    return stepper, contact_law(indenter, modulus)


def _reach(
    stepper: NewtonStepper, history: list, target: float, max_cuts: int, law: Any = None
) -> tuple[list, int, int, list[float]]:
    """Sub-step from the last converged state of ``history`` to the depth ``target`` (m).

    A failing sub-step is halved, a converged one doubles the next; the first Newton iteration
    of each ends at :func:`predict_reach`'s edge (``law``: the small-strain contact). Returns
    the last two converged states (depth, x, lambda), the Newton iterations of the last
    sub-step and of all, and the corrections of the last.

    Raises
    ------
    InputError
        If ``target`` is not beyond the last converged depth.
    NewtonError
        After ``max_cuts`` consecutive halvings.
    GentLockError
        A Gent rubber that locks (:func:`.rubber.gent_locks`).
    ContactOutgrowsMeshError
        The contact zone reached the edge of the candidate region.
    """
    done = history[-1][0]
    if not target > done:  # the depths are checked where they enter; a direct caller too
        raise InputError(f"depths must be strictly increasing, got {target:g} m after {done:g} m")
    increment = target - done
    total = 0
    cuts = 0
    while done < target:
        trial = min(done + increment, target)
        if target - trial < 1e-9 * target:
            trial = target
        guess_x, guess_lam = extrapolate(history, trial)
        reach = predict_reach(stepper.nodes.radius, history, trial, law) if cuts == 0 else None
        last = (history[-1][1], history[-1][2])
        try:
            x, lam, iterations, corrections = stepper.solve(
                trial, guess_x, guess_lam, reach=reach, base=last
            )
        except NewtonError as error:
            cuts += 1
            step = (done, trial)
            locked = gent_locks(error, stepper.system, history[-1][1], step, last=cuts > max_cuts)
            if locked is not None:
                raise locked from None
            if cuts > max_cuts:
                raise _failed_step(stepper, history[-1][1], step, max_cuts, error) from None
            increment *= 0.5
            continue
        total += iterations
        history = [*history[-1:], (trial, x, lam)]
        stepper.watch.accept(trial, stepper.stretch)
        done = trial
        cuts = 0  # count consecutive failures only
        increment *= 2.0
        check_resolved(stepper.nodes.radius, lam, trial, fewest=1)
    return history, iterations, total, corrections


def _failed_step(
    stepper: NewtonStepper, x: np.ndarray, step: tuple[float, float], cuts: int, error: Exception
) -> NewtonError:
    """The failure of the load ``step`` (from, to: m) from the converged x, halved ``cuts``
    times. From the undeformed body of a near-cone (:func:`_steep_tip` at its first
    surface node) it names the shape coefficient: the first Newton step is linear, its strain
    beside the tip about f'(h) ln(a / h), which no smaller step lowers."""
    done, trial = step
    at = f"depth {trial:.6g} m (a load step of {trial - done:.3g} m from {done:.6g} m"
    radius = stepper.nodes.radius
    if done == 0.0 and _steep_tip(stepper.indenter, float(np.min(radius[radius > 0.0]))):
        return NewtonError(
            f"{at}, the first, halved {cuts} times): {error}; its first Newton step is linear, "
            "its strain beside the indenter's tip grows with the tip's slope and hardly shrinks "
            "with the step: lower shape_coefficient=... (a blunter tip)"
        )
    steps = "smaller load steps"  # halved max_cuts times already
    note = squeeze_note(stepper.system, x, steps) or (
        "a finer mesh_size=... or refine=... helps only where the mesh is the cause"
    )
    return NewtonError(
        f"{at}, halved {cuts} times): {error}; lower the deepest of depths=... ({note})"
    )


def _steep_tip(indenter: Indenter, axis: float) -> bool:
    """Whether ``indenter`` is a power law whose slope f'(h) at the axis element h = ``axis``
    (m) exceeds :data:`TIP_SLOPE`: a near-cone, whose first load step strains the tip's
    elements by about f'(h) ln(a / h) at any depth (:data:`NEAR_CONE_AXIS`)."""
    return indenter.kind == "power-law" and float(indenter.slope(axis)) > TIP_SLOPE


def check_smallest_depth(
    stepper: NewtonStepper, law: PowerLawContact | SneddonContact, depth: float
) -> None:
    """Refuse, before any Newton step, a smallest ``depth`` (m) whose small-strain contact
    radius covers no surface node besides the axis: its results would be those of no contact.
    (One or two nodes run: a study's coarse ladder levels start there and mark such points
    unresolved; the linear model asks :data:`.constraints.MIN_CONTACT_NODES`.)"""
    radius = float(law.contact_radius(depth))
    covered = int(np.count_nonzero((stepper.nodes.radius > 0) & (stepper.nodes.radius < radius)))
    if covered == 0:
        raise InputError(
            f"depth {depth:g} m: its contact (radius {radius:.3g} m) covers no surface node "
            f"besides the axis: smaller than this mesh resolves; raise the smallest depth or "
            f"refine the mesh",
            "depths",
        )


def extrapolate(history: list, depth: float) -> tuple[np.ndarray, np.ndarray]:
    """The solution x and the multipliers lambda >= 0 (N) at ``depth`` (m), extrapolated
    linearly in depth from the last two converged states (depth, x, lambda) of ``history``."""
    d1, x1, lam1 = history[-1]
    if len(history) < 2:
        return x1, lam1
    d0, x0, lam0 = history[-2]
    if d1 == d0:
        return x1, lam1
    t = (depth - d1) / (d1 - d0)
    return x1 + t * (x1 - x0), np.maximum(lam1 + t * (lam1 - lam0), 0.0)


def predict_reach(radius: np.ndarray, history: list, depth: float, law: Any = None) -> float | None:
    """The reference radius (m) the contact reaches at ``depth`` (m), predicted from the last
    two converged states of ``history`` (depth, x, lambda) on the candidates' reference radii
    ``radius`` (m): each contact edge taken midway between its last loaded node and the next,
    extrapolated by the power law a ~ d^p through the two. With one contact known, ``law``'s
    (the small-strain contact, ``contact_radius(depth)``) growth from it; with none, ``law``'s
    radius. None without two contacts and without ``law``."""
    contacts = [
        (d, edge)
        for d, _, lam in history[-2:]
        if d > 0 and (edge := _edge(radius, lam)) is not None
    ]
    if len(contacts) == 2 and contacts[1][0] > contacts[0][0]:
        (d0, a0), (d1, a1) = contacts
        return float(a1 * (depth / d1) ** (np.log(a1 / a0) / np.log(d1 / d0)))
    if law is None:
        return None
    if contacts:
        d1, a1 = contacts[-1]
        return float(a1 * law.contact_radius(depth) / law.contact_radius(d1))
    return float(law.contact_radius(depth))


def _edge(radius: np.ndarray, lam: np.ndarray) -> float | None:
    """Midway between the last loaded candidate (``lam`` > 0) and the next (m); None if none
    is loaded or the last one is."""
    loaded = np.flatnonzero(lam > 0)
    if loaded.size == 0 or loaded[-1] + 1 >= radius.size:
        return None
    return float(0.5 * (radius[loaded[-1]] + radius[loaded[-1] + 1]))


def finite_step(
    stepper: NewtonStepper,
    exact: PowerLawContact,
    depth: float,
    x: np.ndarray,
    lam: np.ndarray,
    iterations: int,
    total: int,
    corrections: list[float],
) -> FiniteContactStep:
    """The :class:`FiniteContactStep` of the converged ``x`` and vertical contact forces
    ``lam`` (N) at ``depth`` (m), beside ``exact``'s linear values."""
    r, gap, _, _ = stepper.geometry(x, depth)
    gap = np.where(lam > 0, 0.0, np.maximum(gap, 0.0))
    pressure = spla.spsolve(sp.csc_matrix(_surface_mass(r)), lam)  # M p = F, M banded
    radius, centre = edge_and_centre(r, (lam, gap, pressure), depth)
    return FiniteContactStep(
        depth=float(depth),
        force=float(lam.sum()),
        contact_radius=radius,
        central_pressure=centre,
        strain_energy=stepper.system.energy(x),
        newton_iterations=iterations,
        total_iterations=total,
        force_linear=float(exact.force(depth)),
        contact_radius_linear=float(exact.contact_radius(depth)),
        central_pressure_linear=float(exact.central_pressure(depth)),
        solution=x,
        multipliers=lam,
        gap=gap,
        current_radius=r,
        surface_u_z=x[stepper.nodes.uz],
        pressure=pressure,
        corrections=corrections,
    )


def check_finite_depths(
    indenter: PowerLawIndenter,
    depths: ArrayLike,
    model: str = "neo-hookean",
    impact: tuple[float, float] | None = None,
) -> None:
    """Refuse, before any work, depths (m) the finite-strain contact cannot resolve: d/a
    (a: Shtaerman's contact radius) outside [:data:`MIN_DEPTH_RATIO`, :data:`MAX_DEPTH_RATIO`].
    ``model`` names the rubber model in the message; ``impact`` (mass in kg, velocity in m/s):
    the depths were set by that impact's x_c, and the message names those inputs instead
    (:func:`shtaerman.guards.check_reach` where the deepest is out of the finite-strain impact's
    reach, from :data:`MIN_FINITE_DEPTH_RATIO`).

    Raises
    ------
    shtaerman.validation.LimitError
        Naming the depth, its d/a and the range.
    """
    depths = np.atleast_1d(np.asarray(depths, dtype=float))
    ratios = [(float(d), depth_ratio(indenter, float(d))) for d in (depths[0], depths[-1])]
    (small, low), (deep, high) = ratios
    valid = f"[{MIN_DEPTH_RATIO:g}, {MAX_DEPTH_RATIO:g}]"
    if impact is not None and not MIN_FINITE_DEPTH_RATIO <= high <= MAX_DEPTH_RATIO:  # its words
        check_reach(indenter, deep, impact, finite=True, note=DEPTHS_INSTEAD)
    if low < MIN_DEPTH_RATIO:
        reason = (
            f"{small:g} m gives depth / contact radius {low:.2g}, below the {model} model's "
            f"{valid}: strains this small lose their digits in F = I + grad u"
        )
        _refuse_depths(reason, "raise the smallest depth (the linear model is exact there)", impact)
    if high > MAX_DEPTH_RATIO:
        reason = (
            f"{deep:g} m gives depth / contact radius {high:.3g}, beyond the {model} model's "
            f"{valid}: the finite-strain contact does not converge there"
        )
        _refuse_depths(reason, deepest_depth_remedy(indenter, deep, high), impact)


def _refuse_depths(reason: str, remedy: str, impact: tuple[float, float] | None) -> None:
    """The refusal of depths out of reach, naming the depths, or the impact that set them."""
    if impact is None:
        raise LimitError(f"depths: {reason}; {remedy}", "depths")
    raise LimitError(
        f"mass, velocity: the depths reach the x_c of {impact[0]:g} kg at {impact[1]:g} m/s, "
        f"and {reason}; change mass=... or velocity=...{DEPTHS_INSTEAD}",
        "velocity",
    )


FINITE_BASE = (
    "base: a layer at finite strain is bonded only (the lubricated base's exterior stiffness "
    "beyond the lateral edge is linear): take a bonded base or the linear model"
)
"""The refusal of a lubricated layer at finite strain."""


def geometric_radius(indenter: Indenter, depth: float) -> float:
    """Radius in m where the undeformed profile reaches the depth d (m): (d / A)^(1/n)."""
    return float(indenter.radius_at(depth))


def tip_exponent(indenter: Indenter) -> float:
    """The power law's n, or a smooth tip's 2 (a sphere's, a tabulated profile's): the
    exponent a layer's bulge of the contact zone is sized by."""
    return indenter.exponent if indenter.kind == "power-law" else 2.0


def tip_mesh(mesh: MeshSettings, indenter: Indenter, refined: float) -> MeshSettings:
    """``mesh`` for a refined zone of ``refined`` m, its axis grading coarsened to
    :data:`NEAR_CONE_AXIS` times its smallest size where ``indenter`` is a power law whose
    slope at the finest axis element exceeds :data:`TIP_SLOPE` (a near-cone, whose pressure
    cusp r^(n-1) no grading resolves); else ``mesh`` itself."""
    finest = min(mesh.axis_size, mesh.size)
    if not _steep_tip(indenter, finest * refined):
        return mesh
    return replace(mesh, axis_size=max(finest, NEAR_CONE_AXIS * mesh.size))


def indentation_mesh(
    indenter: Indenter, deepest: float, mesh: MeshSettings, geometry: Geometry
) -> tuple[MeshSettings, float]:
    """The mesh settings and the refined radius (m) of a curve to ``deepest`` (m): ``margin``
    times the geometric contact radius (times a layer's :meth:`Geometry.zone_factor`), graded
    at the axis by :func:`tip_mesh` (the study's ladder plans on it too)."""
    refined = mesh.margin * geometric_radius(indenter, deepest)
    refined *= geometry.zone_factor(tip_exponent(indenter))  # 1 on the half-space
    return tip_mesh(mesh, indenter, refined), refined


def run_finite_indentation(
    indenter: PowerLawIndenter,
    half_space: Material,
    depths: ArrayLike,
    mesh: MeshSettings | None = None,
    rubber: RubberModel | None = None,
    solve: Callable[..., FiniteContactCurve] | None = None,
    geometry: Geometry = HALF_SPACE,
    **options: float,
) -> FiniteContactCurve:
    """Mesh, assemble and press a rigid power-law indenter into a rubber half-space (or the
    layer of ``geometry``, whose ``base`` must be bonded: the lubricated base's exterior
    spring is linear).

    Parameters
    ----------
    indenter : PowerLawIndenter
        z = A r^n, n > 1.
    half_space : Material
        E2 (Pa) and nu2 in [0, 0.5] of the small-strain limit.
    depths : array_like
        Depths in m, positive, increasing (the entry points check them).
    mesh : MeshSettings, optional
        Default :data:`FINITE_MESH`; the refined zone is ``margin`` times the geometric
        contact radius (d_max / A)^(1/n) (times :meth:`Geometry.zone_factor` on a layer);
        near a cone graded coarser at the axis (:func:`tip_mesh`).
    rubber : RubberModel, optional
        The rubber model (default neo-Hookean, :mod:`shtaerman.fem.rubber`).
    solve : callable, optional
        The contact solver (default :func:`solve_finite_contact`, frictionless; a bonded or
        Coulomb indenter: :func:`.finite_stick.solve_finite_bonded_contact`).
    **options
        Passed to ``solve`` (``tolerance``, ``max_iterations``, ``max_cuts`` of
        :func:`solve_finite_contact`).

    Returns
    -------
    FiniteContactCurve
    """
    validate_poisson("nu2", half_space.poisson_ratio, low=0.0)  # the FEM's tested range
    depths = np.atleast_1d(np.asarray(depths, dtype=float))  # checked where they entered
    check_finite_depths(indenter, depths, "neo-hookean" if rubber is None else rubber.name)
    mesh = FINITE_MESH if mesh is None else mesh
    thickness = geometry.thickness
    if thickness is not None and geometry.base != "bonded":
        raise InputError(FINITE_BASE, "base")
    mesh, refined = indentation_mesh(indenter, depths[-1], mesh, geometry)
    start = time.perf_counter()
    skfem_mesh = mesh.build(refined, geometry)
    meshed = time.perf_counter()
    constants = (half_space.youngs_modulus, half_space.poisson_ratio)
    material = NeoHookean(*constants) if rubber is None else rubber.material(*constants)
    system = assemble_hyperelastic(skfem_mesh, material)
    assembled = time.perf_counter()
    curve = (solve or solve_finite_contact)(system, indenter, depths, refined, **options)
    stats = {
        "nodes": int(skfem_mesh.p.shape[1]),
        "elements": int(skfem_mesh.t.shape[1]),
        "dofs": int(system.n_dofs),
        "contact_candidates": int(curve.steps[0].multipliers.size),
        "refined_radius": refined,
        "domain_radius": float(skfem_mesh.p[0].max()) if thickness else mesh.domain * refined,
        "smallest_size": mesh.size * refined,
        **({"thickness": thickness, "base": geometry.base} if thickness else {}),
    }
    timings = {
        "mesh": meshed - start,
        "assembly": assembled - meshed,
        **curve.timings,
        "total": time.perf_counter() - start,
    }
    return replace(curve, timings=timings, mesh_stats=stats)
