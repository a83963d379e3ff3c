"""Bonded (no slip) or Coulomb contact of a rigid indenter on the linear body: the contact-set
update of one step (:func:`stick_slip_step`, the rules of :mod:`.constraints`) and the static
contact loaded in steps (:func:`solve_bonded_contact`; the impact's time steps:
:mod:`shtaerman.fem.stepper`).

In a step the candidates' displacements are affine in the nodal contact forces f on the body,
u = u_step + A f, with A (m/N) symmetric positive definite (:class:`CoupledCompliance`). The
static contact is loaded over :func:`.constraints.depth_ladder`; its force is the sum of the
nodal normal forces. The formulation: benchmarks/FEM_NOTES.md, "Moved from the docstrings",
fem/contact/stick.py."""

from __future__ import annotations

import math
import time
from dataclasses import dataclass

import numpy as np
import scipy.linalg as la
from threadpoolctl import threadpool_limits

from ...validation import NumericalFailureError
from ..elasticity import ElasticSystem
from .constraints import (
    CUTS,
    MAX_ACTIVE_SET_ITERATIONS,
    ROUND_OFF,
    START_NODE,
    STEP_RATIO,
    SUB_STEPS,
    check_loading,
    cut_step,
    depth_ladder,
    settle,
    unsettled,
    walk_ladder,
)
from .linear import (
    ContactCurve,
    ContactStep,
    Profile,
    SurfaceCompliance,
    factorize_tail,
    field_solutions,
    step_from_forces,
    surface_compliance,
    timed_curve,
)


@dataclass(frozen=True, eq=False)
class CoupledCompliance:
    """A (m/N) on [u_z of the m candidates, u_r of the candidates off the axis]."""

    matrix: np.ndarray
    radial_node: np.ndarray
    """Candidate index of every radial dof."""
    radial_dofs: np.ndarray


@dataclass(frozen=True, eq=False)
class StickState:
    """The contact after one step, per candidate: ``held`` u_r (m) of the stuck nodes (NaN
    off the contact), ``radial`` u_r (m; 0 on the axis), ``slip`` 0 (stuck or free) or the
    direction +-1 of a sliding node; the nodal ``forces`` F and ``shear`` (N, per radial dof)
    once solved."""

    active: np.ndarray
    held: np.ndarray
    radial: np.ndarray
    gap: np.ndarray
    slip: np.ndarray
    forces: np.ndarray | None = None
    shear: np.ndarray | None = None

    @classmethod
    def untouched(cls, gap: np.ndarray) -> StickState:
        """No node in contact, the surface at rest, at the candidates' ``gap`` (m)."""
        m = gap.size
        return cls(np.zeros(m, bool), np.full(m, np.nan), np.zeros(m), gap.copy(), np.zeros(m))


def radial_dofs(system: ElasticSystem, candidates: np.ndarray) -> tuple[np.ndarray, ...]:
    """The free surface u_r dofs at the ``candidates`` radii (m, ascending), sorted by r, and
    the candidate index of each."""
    ubasis = system.displacement_basis
    dofs = np.setdiff1d(ubasis.get_dofs("surface").all("u^1"), system.fixed_dofs)
    radii = ubasis.doflocs[0, dofs]
    keep = radii <= candidates[-1]
    dofs, radii = dofs[keep], radii[keep]
    order = np.argsort(radii)
    dofs, radii = dofs[order].astype(np.int64), radii[order]
    node = np.searchsorted(candidates, radii)
    if not np.array_equal(candidates[np.minimum(node, candidates.size - 1)], radii):
        raise NumericalFailureError("the surface u_r and u_z dofs do not share their nodes")
    return dofs, node


def _solve_stuck(
    coupled: CoupledCompliance, steps: tuple[np.ndarray, np.ndarray], state: StickState, mu: float
) -> tuple[np.ndarray, ...]:
    """Nodal normal forces F (N), shear (N), the response (A f)_z (m) at the candidates and
    u_r (m) at the radial dofs with the ``state.active`` nodes on the indenter ((A f)_z =
    reach), stuck ones at u_r = ``state.held``, sliding ones (``state.slip`` = +-1, the
    direction of the slip) under the shear -slip ``mu`` F; ``steps``: (reach, offset)."""
    (reach, offset), node_of = steps, coupled.radial_node
    m = reach.size
    nodes = np.flatnonzero(state.active)
    on = state.active[node_of]
    stuck = np.flatnonzero(on & (state.slip[node_of] == 0))
    sliding = np.flatnonzero(on & (state.slip[node_of] != 0))
    rows = np.concatenate([nodes, m + stuck])
    target = np.concatenate([reach[nodes], state.held[node_of[stuck]] - offset[stuck]])
    forces, shear = np.zeros(m), np.zeros(node_of.size)
    displacement = np.zeros(coupled.matrix.shape[0])
    if rows.size:
        block = coupled.matrix[np.ix_(rows, rows)]
        if sliding.size:  # shear = slip mu f_z: a column of the sliding node's f_z
            scale = state.slip[node_of[sliding]] * mu
            column = np.searchsorted(nodes, node_of[sliding])
            block[:, column] += coupled.matrix[np.ix_(rows, m + sliding)] * scale
            loads = la.solve(block, target)
            shear[sliding] = scale * loads[column]
            displacement = coupled.matrix[:, m + sliding] @ shear[sliding]
        else:
            loads = la.cho_solve(la.cho_factor(block), target)
        forces[nodes] = -loads[: nodes.size]
        shear[stuck] = loads[nodes.size :]
        displacement = displacement + coupled.matrix[:, rows] @ loads
    return forces, shear, displacement[:m], offset + displacement[m:]


def _changes(
    state: StickState, solved: tuple[np.ndarray, ...], gap: np.ndarray, band: float, mu: float
) -> tuple[list[np.ndarray], list[np.ndarray]]:
    """The violated conditions (release, enter, stick to slip, slip to stick) and their size;
    ``solved`` holds per candidate F, shear and u_r, ``band`` the gap's round-off (m)."""
    forces, traction, radial = solved
    moved = state.slip * (radial - state.radial)
    release = state.active & (forces < -ROUND_OFF * np.abs(forces).max(initial=0.0))
    enter = ~state.active & (gap < -band)
    excess = np.full(forces.size, -np.inf)
    if np.isfinite(mu):
        excess = np.abs(traction) - mu * forces
    to_slip = state.active & (state.slip == 0) & (excess > ROUND_OFF * np.abs(forces).max())
    to_stick = state.active & (moved < -ROUND_OFF * np.abs(radial).max(initial=0.0))
    return [release, enter, to_slip, to_stick], [-forces, -gap, excess, -moved]


def stick_slip_step(
    coupled: CoupledCompliance,
    reach: np.ndarray,
    offset: np.ndarray,
    last: StickState,
    friction: float,
) -> StickState | None:
    """The contact of one step from the contact ``last`` of the step before.

    Parameters
    ----------
    coupled : CoupledCompliance
        A (m/N) of the step.
    reach : numpy.ndarray
        Per candidate, m: the u_z response (A f)_z that puts a node on the indenter; a free
        node's gap is reach - (A f)_z.
    offset : numpy.ndarray
        Per radial dof, m: its u_r without new contact forces (u_r = offset + (A f)_r).
    last : StickState
        The contact of the step before (solved).
    friction : float
        Coulomb coefficient mu >= 0 (inf: no slip).

    Returns
    -------
    StickState or None
        The solved contact (F >= 0, gap >= 0), or None if the stick and slip sets keep cycling.
        All violated conditions change at once; should a contact state repeat, one at a time.
    """
    band = ROUND_OFF * np.abs(reach).max()
    m = reach.size

    def attempt(state: StickState) -> tuple[tuple, list[np.ndarray], list[np.ndarray]]:
        forces, shear, response, u_r = _solve_stuck(coupled, (reach, offset), state, friction)
        gap = np.where(state.active, 0.0, reach - response)
        traction, radial = np.zeros(m), np.zeros(m)
        traction[coupled.radial_node], radial[coupled.radial_node] = shear, u_r
        changes, excess = _changes(state, (forces, traction, radial), gap, band, friction)
        forces, kept = np.maximum(forces, 0.0), np.maximum(gap, 0.0)
        solved = StickState(state.active, state.held, radial, kept, state.slip, forces, shear)
        return (solved, gap, traction), changes, excess

    def update(state: StickState, solved: tuple, changes: list[np.ndarray]) -> StickState:
        (now, gap, traction), (release, enter, to_slip, to_stick) = solved, changes
        closing = last.gap[enter] / (last.gap[enter] - gap[enter])
        closing[last.active[enter]] = 1.0  # released in this step: where it touches now
        held, slip, radial = state.held, state.slip, now.radial
        held[enter] = last.radial[enter] + closing * (radial[enter] - last.radial[enter])
        held[release] = np.nan
        origin = state.radial.copy()  # a node touching in this step slides from its touch
        origin[enter] = held[enter]
        held[to_stick] = origin[to_stick]
        slip[to_slip] = -np.sign(traction[to_slip])
        slip[release | to_stick] = 0
        active = (state.active & ~release) | enter
        return StickState(active, held, origin, last.gap, slip)

    start = StickState(last.active, last.held.copy(), last.radial, last.gap, last.slip.copy())
    limit = MAX_ACTIVE_SET_ITERATIONS + 2 * m
    solved = settle(
        start, attempt, update, lambda state: state.active.tobytes() + state.slip.tobytes(), limit
    )
    return None if solved is None else solved[0]


def _load_history(
    coupled: CoupledCompliance,
    normal: SurfaceCompliance,
    profile: Profile,
    depths: np.ndarray,
    loading: tuple[float, float],
) -> list[ContactStep]:
    """Load through :func:`.constraints.depth_ladder` (``loading``: step ratio, friction
    coefficient) and keep the contact at each requested depth (force: the nodal sum)."""
    ratio, friction = loading
    heights = np.asarray(profile(normal.r), dtype=float)
    state, offset = StickState.untouched(heights), np.zeros(coupled.radial_dofs.size)
    start = float(heights[min(START_NODE, heights.size - 1)])
    previous = 0.0

    def step(depth: float, last: StickState) -> StickState | None:
        return stick_slip_step(coupled, heights - depth, offset, last, friction)

    def advance(depth: float) -> int:
        nonlocal state, previous
        solved, taken = cut_step(step, state, (previous, depth), CUTS)
        if solved is None:
            raise unsettled(depth, SUB_STEPS**CUTS)
        state, previous = solved, depth
        return taken

    def record(depth: float, taken: int) -> ContactStep:
        solved = (state.forces, state.gap, taken)
        return step_from_forces(normal, heights, depth, solved, aligned=False, shear=state.shear)

    ladder = depth_ladder(start if start > 0 else depths[0], depths, ratio)
    return walk_ladder(ladder, depths, advance, record)


def solve_bonded_contact(
    system: ElasticSystem,
    profile: Profile,
    depths: np.ndarray,
    candidate_radius: float,
    *,
    friction: float = math.inf,
    step_ratio: float = STEP_RATIO,
    backend: str = "auto",
) -> ContactCurve:
    """Press a rigid indenter z = f(r) that the surface sticks to, in load steps.

    Parameters and result as :func:`.linear.solve_contact` (without ``aligned``: the force
    is the nodal sum), with ``step_ratio`` > 1 the depth ratio of consecutive load steps and
    ``friction`` >= 0 the Coulomb coefficient (inf: no slip; a node in contact slides once its
    shear exceeds ``friction`` times its normal force). Each step's ``iterations`` counts the
    load steps since the previous depth; its ``tangential_forces`` are the nodal forces (N)
    along +r on the body at the radial dofs ``compliance.radial_dofs``.
    """
    check_loading(step_ratio, friction)
    free = system.free_dofs()
    start = time.perf_counter()
    inside = system.surface_r <= candidate_radius * (1 + 1e-12)
    radial, radial_node = radial_dofs(system, system.surface_r[inside])
    position = np.searchsorted(free, np.concatenate([system.surface_dofs[inside], radial]))
    factorization = factorize_tail(system, free, position, backend)
    factorized = time.perf_counter()
    normal = surface_compliance(system, factorization, free, candidate_radius, radial)
    coupled = CoupledCompliance(normal.coupled, radial_node, radial)
    with threadpool_limits(limits=1, user_api="blas"):
        steps = _load_history(coupled, normal, profile, depths, (step_ratio, friction))
    solutions = field_solutions(system, factorization, free, normal, steps)
    done = time.perf_counter()
    seconds = (factorized - start, done - factorized)
    return timed_curve(system, (normal, steps, solutions), factorization, backend, seconds)
