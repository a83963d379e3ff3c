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
sparse factorization with both dofs of every candidate eliminated last (:mod:`.schur`). Each
depth step is :func:`.stick_slip.stick_slip_step` with reach f(r) - d and no radial offset
(the contact-set update the time steps of the impact share).

The force reported is the sum of the nodal normal forces (the frictionless solver's nodal sum;
its vertex alignment needs a history-free contact). The tangential nodal forces (N, on the
body, along +r) are kept per depth for the fields.
"""

from __future__ import annotations

import math
import time
from dataclasses import dataclass

import numpy as np
from threadpoolctl import threadpool_limits

from ..validation import InputError, NumericalFailureError
from .contact import (
    ContactCurve,
    ContactStep,
    Profile,
    SurfaceCompliance,
    central_pressure,
    check_resolved,
    edge_radius,
    factorize_tail,
    field_solutions,
    recover_pressure,
    surface_compliance,
    tail_compliance,
)
from .elasticity import ElasticSystem
from .stick_slip import CoupledCompliance, StickState, radial_dofs, stick_slip_step

__all__ = [
    "STEP_RATIO",
    "depth_ladder",
    "solve_bonded_contact",
    "unsettled",
]

STEP_RATIO = 1.02
"""Default depth ratio of consecutive load steps (benchmarks/FEM_NOTES.md, "Interface
friction", measures the force's convergence in it)."""
START_NODE = 4
"""The first load step is the depth at which the indenter reaches this candidate node (counted
from the axis): the history before it is taken as one step."""


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


def _contact_step(
    normal: SurfaceCompliance, heights: np.ndarray, depth: float, state: StickState, iterations: int
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
    coupled: CoupledCompliance,
    normal: SurfaceCompliance,
    profile: Profile,
    depths: np.ndarray,
    loading: tuple[float, float],
) -> list[ContactStep]:
    """Load through :func:`depth_ladder` (``loading``: step ratio, friction coefficient) and
    keep the contact at each requested depth."""
    ratio, friction = loading
    heights = np.asarray(profile(normal.r), dtype=float)
    state, offset = StickState.untouched(heights), np.zeros(coupled.radial_dofs.size)
    wanted, steps, taken = set(depths.tolist()), [], 0
    start = float(heights[min(START_NODE, heights.size - 1)])
    for depth in depth_ladder(start if start > 0 else depths[0], depths, ratio):
        solved = stick_slip_step(coupled, heights - depth, offset, state, friction)
        if solved is None:
            raise unsettled(float(depth))
        state = solved
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
    radial, radial_node = radial_dofs(system, system.surface_r[inside])
    tail = np.concatenate([normal_dofs, radial])
    position = np.searchsorted(free, tail)
    factorization = factorize_tail(system, free, position, backend)
    factorized = time.perf_counter()
    inverse = tail_compliance(factorization, free.size, position)
    m = normal_dofs.size
    normal = surface_compliance(system, _Known(inverse[:m, :m]), free, candidate_radius)
    normal = SurfaceCompliance(
        normal.r, normal.matrix, normal.mass, normal.vertex, normal.dofs, radial
    )
    coupled = CoupledCompliance(inverse, radial_node, radial)
    with threadpool_limits(limits=1, user_api="blas"):
        steps = _load_history(coupled, normal, profile, depths, (step_ratio, friction))
    solutions = field_solutions(system, factorization, free, normal, steps)
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
