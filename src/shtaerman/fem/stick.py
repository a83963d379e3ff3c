"""Bonded contact (no slip, or Coulomb friction) of a rigid axisymmetric indenter, loaded in steps.

Once a surface point touches the rigid indenter it sticks to it. The indenter moves only
vertically, so a point in contact keeps the radial displacement it had when it touched and its
vertical one follows the indenter, u_z = f(r) - d. The contact is history dependent: it is
solved by incremental loading over a geometric ladder of depths (ratio ``step_ratio``) from the
depth at which the indenter reaches candidate node :data:`START_NODE` (the axis grading of the
mesh makes it a tiny fraction of the first depth) up to the last, the requested depths
included.

The surface compliance G (m/N) couples the candidates' u_z and u_r dofs: u = G f for nodal
forces f on the body (f_z = -F for a downward contact force F >= 0). It comes from the one
sparse factorization with both dofs of every candidate eliminated last (:mod:`.schur`). In each
depth step a primal-dual active-set iteration on the nodes in contact:

- a free node whose gap turns negative enters the contact; its radial displacement is frozen at
  the value interpolated linearly between the last depth and the current iterate, at the point
  where its gap closes;
- a node in contact whose normal force turns tensile is released and forgets its radial
  displacement (it would get a new one on re-entry);
- with a finite Coulomb coefficient mu, a stuck node whose shear exceeds mu F slides (its shear
  is then mu F against the direction of its slip), and a sliding node whose slip reverses
  sticks again at its radial displacement of the last depth.

The force reported is the sum of the nodal normal forces (the frictionless solver's nodal sum;
its vertex alignment needs a history-free contact). The tangential nodal forces (N, on the
body, along +r) are kept per depth for the fields.
"""

from __future__ import annotations

import math
import time
from dataclasses import dataclass

import numpy as np
import scipy.linalg as la
from threadpoolctl import threadpool_limits

from ..validation import InputError, NumericalFailureError
from .contact import (
    MAX_ACTIVE_SET_ITERATIONS,
    ROUND_OFF,
    ContactCurve,
    ContactStep,
    Profile,
    SurfaceCompliance,
    central_pressure,
    check_resolved,
    edge_radius,
    factorize_tail,
    recover_pressure,
    surface_compliance,
    tail_compliance,
)
from .elasticity import ElasticSystem
from .solver import Factorization

__all__ = ["STEP_RATIO", "depth_ladder", "solve_bonded_contact"]

STEP_RATIO = 1.02
"""Default depth ratio of consecutive load steps (benchmarks/FEM_NOTES.md, "Interface
friction", measures the force's convergence in it)."""
START_NODE = 4
"""The first load step is the depth at which the indenter reaches this candidate node (counted
from the axis): the history before it is taken as one step."""


@dataclass(frozen=True, eq=False)
class _Coupled:
    """G (m/N) on [u_z of the m candidates, u_r of the candidates off the axis]."""

    matrix: np.ndarray
    radial_node: np.ndarray
    """Candidate index of every radial dof."""
    radial_dofs: np.ndarray


@dataclass(frozen=True, eq=False)
class _State:
    """The contact at one load step, per candidate: ``held`` u_r (m) of the stuck nodes (NaN
    off the contact), ``radial`` u_r (m; 0 on the axis), ``slip`` 0 (stuck or free) or the
    direction +-1 of a sliding node; the nodal ``forces`` and ``shear`` (N) once solved."""

    active: np.ndarray
    held: np.ndarray
    radial: np.ndarray
    gap: np.ndarray
    slip: np.ndarray
    forces: np.ndarray | None = None
    shear: np.ndarray | None = None


def unsettled(depth: float) -> NumericalFailureError:
    """The failure of a load step at ``depth`` (m) whose stick and slip sets keep cycling."""
    return NumericalFailureError(
        f"depth {depth:g} m: the contact's stick and slip did not settle; refine the mesh near "
        "the edge or take smaller load steps"
    )


def depth_ladder(start: float, depths: np.ndarray, step_ratio: float) -> np.ndarray:
    """Load steps (m): geometric with ``step_ratio`` from ``start`` (at most depths[0]) to
    depths[-1], merged with ``depths`` (each requested depth is one of them)."""
    start = min(start, depths[0])
    count = int(np.ceil(np.log(depths[-1] / start) / np.log(step_ratio)))
    ladder = start * step_ratio ** np.arange(count)
    return np.union1d(ladder[ladder < depths[-1]], depths)


def _radial_dofs(system: ElasticSystem, candidates: np.ndarray) -> tuple[np.ndarray, ...]:
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


def _field_solutions(
    system: ElasticSystem,
    factorization: Factorization,
    free: np.ndarray,
    compliance: SurfaceCompliance,
    steps: list[ContactStep],
) -> np.ndarray:
    """Solution vectors of every depth (normal and tangential nodal forces) by one solve."""
    loads = np.zeros((free.size, len(steps)))
    normal = np.searchsorted(free, compliance.dofs)
    radial = np.searchsorted(free, compliance.radial_dofs)
    for column, step in enumerate(steps):
        loads[normal, column] = -step.nodal_forces
        loads[radial, column] = step.tangential_forces
    solutions = np.zeros((len(steps), system.n_dofs))
    solutions[:, free] = factorization.solve(loads).T
    return solutions


def _solve_stuck(
    coupled: _Coupled, heights: np.ndarray, depth: float, state: _State, friction: float
) -> tuple[np.ndarray, ...]:
    """Nodal normal forces F (N), shear (N), u_z (m) at the candidates and u_r (m) at the
    radial dofs with the ``state.active`` nodes on the indenter (u_z = f - d): stuck ones at
    u_r = ``state.held``, sliding ones (``state.slip`` = +-1, the direction of the slip) under
    the shear -slip ``friction`` F."""
    m, node_of = heights.size, coupled.radial_node
    nodes = np.flatnonzero(state.active)
    on = state.active[node_of]
    stuck = np.flatnonzero(on & (state.slip[node_of] == 0))
    sliding = np.flatnonzero(on & (state.slip[node_of] != 0))
    rows = np.concatenate([nodes, m + stuck])
    target = np.concatenate([heights[nodes] - depth, state.held[node_of[stuck]]])
    forces, shear = np.zeros(m), np.zeros(node_of.size)
    displacement = np.zeros(coupled.matrix.shape[0])
    if rows.size:
        block = coupled.matrix[np.ix_(rows, rows)]
        if sliding.size:  # shear = slip mu f_z: a column of the sliding node's f_z
            scale = state.slip[node_of[sliding]] * friction
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
    return forces, shear, displacement[:m], displacement[m:]


def worst_only(changes: list[np.ndarray], excess: list[np.ndarray]) -> list[np.ndarray]:
    """``changes`` (boolean masks, in order of priority) cut to the single node of the first
    non-empty one with the largest ``excess`` (the cautious update after a cycle)."""
    cut = [np.zeros_like(change) for change in changes]
    for change, amount, one in zip(changes, excess, cut, strict=True):
        if change.any():
            one[np.flatnonzero(change)[np.argmax(amount[change])]] = True
            break
    return cut


def _changes(
    state: _State, solved: tuple[np.ndarray, ...], gap: np.ndarray, band: float, friction: float
) -> tuple[list[np.ndarray], list[np.ndarray]]:
    """The violated conditions (release, enter, stick to slip, slip to stick) and their size;
    ``solved`` holds per candidate F, shear and u_r, ``band`` the gap's round-off (m)."""
    forces, traction, radial = solved
    moved = state.slip * (radial - state.radial)
    release = state.active & (forces < -ROUND_OFF * np.abs(forces).max(initial=0.0))
    enter = ~state.active & (gap < -band)
    excess = np.full(forces.size, -np.inf)
    if np.isfinite(friction):
        excess = np.abs(traction) - friction * forces
    to_slip = state.active & (state.slip == 0) & (excess > ROUND_OFF * np.abs(forces).max())
    to_stick = state.active & (moved < -ROUND_OFF * np.abs(radial).max(initial=0.0))
    return [release, enter, to_slip, to_stick], [-forces, -gap, excess, -moved]


def _load_step(
    coupled: _Coupled, heights: np.ndarray, depth: float, last: _State, friction: float
) -> _State:
    """The contact at ``depth`` from the contact ``last`` at the previous load step.

    All violated conditions change at once; should a contact state repeat, one at a time."""
    state = _State(last.active, last.held.copy(), last.radial, last.gap, last.slip.copy())
    band = ROUND_OFF * np.abs(heights - depth).max()
    seen: set[bytes] = set()
    cautious = False
    for _ in range(MAX_ACTIVE_SET_ITERATIONS + 2 * heights.size):
        forces, shear, u_z, u_r = _solve_stuck(coupled, heights, depth, state, friction)
        gap = np.where(state.active, 0.0, heights - depth - u_z)
        traction, radial = np.zeros(heights.size), np.zeros(heights.size)
        traction[coupled.radial_node], radial[coupled.radial_node] = shear, u_r
        changes, excess = _changes(state, (forces, traction, radial), gap, band, friction)
        if not any(change.any() for change in changes):
            gap, forces = np.maximum(gap, 0.0), np.maximum(forces, 0.0)
            return _State(state.active, state.held, radial, gap, state.slip, forces, shear)
        if cautious:
            changes = worst_only(changes, excess)
        release, enter, to_slip, to_stick = changes
        seen.add(state.active.tobytes() + state.slip.tobytes())
        closing = last.gap[enter] / (last.gap[enter] - gap[enter])
        held, slip = state.held, state.slip
        held[enter] = last.radial[enter] + closing * (radial[enter] - last.radial[enter])
        held[release] = np.nan
        held[to_stick] = last.radial[to_stick]
        slip[to_slip] = -np.sign(traction[to_slip])
        slip[release | to_stick] = 0
        active = (state.active & ~release) | enter
        state = _State(active, held, last.radial, last.gap, slip)
        if active.tobytes() + slip.tobytes() in seen:
            if cautious:
                break
            cautious, seen = True, set()
    raise unsettled(depth)


def _contact_step(
    normal: SurfaceCompliance, heights: np.ndarray, depth: float, state: _State, iterations: int
) -> ContactStep:
    """The :class:`.contact.ContactStep` of a requested depth (force: the nodal sum)."""
    check_resolved(normal.r, state.forces, depth)
    pressure = recover_pressure(normal.mass_factor, state.forces)
    radius = edge_radius(normal.r, state.forces, state.gap)
    total = float(state.forces.sum())
    return ContactStep(
        depth=depth,
        force=total,
        discrete_force=total,
        contact_radius=radius,
        central_pressure=central_pressure(normal.r, pressure, radius),
        nodal_forces=state.forces,
        pressure=pressure,
        gap=state.gap,
        iterations=iterations,
        tangential_forces=state.shear,
    )


def _load_history(
    coupled: _Coupled,
    normal: SurfaceCompliance,
    profile: Profile,
    depths: np.ndarray,
    loading: tuple[float, float],
) -> list[ContactStep]:
    """Load through :func:`depth_ladder` (``loading``: step ratio, friction coefficient) and
    keep the contact at each requested depth."""
    ratio, friction = loading
    heights = np.asarray(profile(normal.r), dtype=float)
    m = heights.size
    state = _State(np.zeros(m, bool), np.full(m, np.nan), np.zeros(m), heights.copy(), np.zeros(m))
    wanted, steps, taken = set(depths.tolist()), [], 0
    start = float(heights[min(START_NODE, heights.size - 1)])
    for depth in depth_ladder(start if start > 0 else depths[0], depths, ratio):
        state = _load_step(coupled, heights, float(depth), state, friction)
        taken += 1
        if float(depth) in wanted:
            steps.append(_contact_step(normal, heights, float(depth), state, taken))
            taken = 0
    return steps


def solve_bonded_contact(
    system: ElasticSystem,
    profile: Profile,
    depths: np.ndarray,
    candidate_radius: float,
    *,
    backend: str = "auto",
    step_ratio: float = STEP_RATIO,
    friction: float = math.inf,
) -> ContactCurve:
    """Press a rigid indenter z = f(r) that the surface sticks to, in load steps.

    Parameters and result as :func:`.contact.solve_contact` (without ``aligned``: the force
    is the nodal sum), with ``step_ratio`` > 1 the depth ratio of consecutive load steps and
    ``friction`` >= 0 the Coulomb coefficient (inf: no slip; a node in contact slides once its
    shear exceeds ``friction`` times its normal force). Each step's ``iterations`` counts the
    load steps since the previous depth; its ``tangential_forces`` are the nodal forces (N)
    along +r on the body at the radial dofs ``compliance.radial_dofs``.
    """
    if not step_ratio > 1.0:
        raise InputError(f"step_ratio: must be > 1, got {step_ratio!r}", "step_ratio")
    if not friction >= 0.0:
        raise InputError(f"friction: must be >= 0 (inf: no slip), got {friction!r}", "friction")
    free = system.free_dofs()
    start = time.perf_counter()
    inside = system.surface_r <= candidate_radius * (1 + 1e-12)
    normal_dofs = system.surface_dofs[inside]
    radial_dofs, radial_node = _radial_dofs(system, system.surface_r[inside])
    tail = np.concatenate([normal_dofs, radial_dofs])
    position = np.searchsorted(free, tail)
    factorization = factorize_tail(system, free, position, backend)
    factorized = time.perf_counter()
    inverse = tail_compliance(factorization, free.size, position)
    m = normal_dofs.size
    normal = surface_compliance(system, _Known(inverse[:m, :m]), free, candidate_radius)
    normal = SurfaceCompliance(
        normal.r, normal.matrix, normal.mass, normal.vertex, normal.dofs, radial_dofs
    )
    coupled = _Coupled(inverse, radial_node, radial_dofs)
    with threadpool_limits(limits=1, user_api="blas"):
        steps = _load_history(coupled, normal, profile, depths, (step_ratio, friction))
    solutions = _field_solutions(system, factorization, free, normal, steps)
    done = time.perf_counter()
    return ContactCurve(
        steps=steps,
        compliance=normal,
        system=system,
        solutions=solutions,
        timings={"factorization": factorized - start, "contact": done - factorized},
        backend=getattr(factorization, "backend", backend),
    )


@dataclass(frozen=True)
class _Known:
    """A stand-in factorization whose tail inverse is already known."""

    inverse: np.ndarray

    def tail_inverse(self) -> np.ndarray:
        return self.inverse
