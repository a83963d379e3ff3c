"""The frictionless contact curve of a viscoelastic body pressed at a constant rate.

A rigid indenter z = f(r) - d(t), d = V t, is pressed into a body that relaxes in shear by a
Prony series (:mod:`.viscoelastic`, recursive convolution). The body is quasi-static (no
inertia): at each time step t_n, with the step's stiffness K (the elastic one at the step's
effective shear modulus) and the history force h^n of the Prony branches,

    K x = -S F - h^n,   g = f(r) - d_n + C F + (K^-1 h^n)_c >= 0,   F >= 0,   F . g = 0,

with C = S^T K^-1 S the surface compliance of :mod:`.contact`: the history shifts the
indenter's clearance by the surface displacement it alone would cause, and the linear
complementarity problem of the elastic contact is solved as it is there. The steps are uniform
between consecutive requested depths (each such interval has its own dt, its own
factorization, and the branches' history carried over, :meth:`.ViscoelasticShear.resume`), so
every requested depth is an instant of the march. With all g_i = 0 every step is the elastic
contact (the same matrix, the history exactly 0).

At nu2 = 1/2 the discrete contact obeys Lee and Radok's correspondence exactly while it grows:
the force is the hereditary integral of the elastic FEM force, with the force linear in time
over each step (exact kernels), so the time error is second order in dt.
"""

from __future__ import annotations

import dataclasses
import itertools
import math
import time
from collections.abc import Callable

import numpy as np
from threadpoolctl import threadpool_limits

from ..theory.viscoelastic import PronySeries
from ..validation import InputError
from .contact import (
    ContactCurve,
    ContactStep,
    SurfaceCompliance,
    complementarity,
    factorize_tail,
    step_from_forces,
    surface_compliance,
)
from .elasticity import ElasticSystem
from .solver import Factorization
from .viscoelastic import ShearMemory, ViscoelasticShear, viscoelastic_shear

__all__ = ["CURVE_STEPS", "press_at_rate", "time_grid"]

CURVE_STEPS = 200
"""Time steps from first touch to the deepest depth, by default. On the paper's case (default
mesh) the forces change by 2.3e-5 (1 m/s) and 8.7e-5 (0.01 m/s, where the contact's node
arrivals within V tau dominate) from 200 to 400 steps, below the mesh's error there (1.3e-4);
the mesh ladder does not estimate this time error (benchmarks/FEM_NOTES.md)."""
MAX_CURVE_STEPS = 100_000
"""Most time steps of one curve."""

Profile = Callable[[np.ndarray], np.ndarray]


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


@dataclasses.dataclass
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
    stepped = dataclasses.replace(system, matrix=shear.stiffness)
    candidates = np.flatnonzero(system.surface_r <= radius * (1 + 1e-12))
    position = np.searchsorted(free, system.surface_dofs[candidates])
    factorization = factorize_tail(stepped, free, position, backend)
    return _Interval(shear, factorization, surface_compliance(stepped, factorization, free, radius))


def _step(
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


def _record(
    compliance: SurfaceCompliance,
    shifted: np.ndarray,
    depth: float,
    solved: tuple[np.ndarray, np.ndarray, int],
    aligned: bool,
) -> ContactStep:
    """The contact at a requested depth (as :func:`.contact.contact_step`, the clearance
    shifted by the history)."""
    return step_from_forces(compliance, shifted, depth, solved, aligned)


def press_at_rate(
    system: ElasticSystem,
    profile: Profile,
    depths: np.ndarray,
    candidate_radius: float,
    prony: PronySeries,
    rate: float,
    *,
    steps: int = CURVE_STEPS,
    backend: str = "auto",
    aligned: bool = True,
) -> ContactCurve:
    """Press a rigid frictionless indenter z = f(r) into the viscoelastic body at ``rate``.

    Parameters
    ----------
    system : ElasticSystem
        The assembled body (E2, nu2 its instantaneous moduli).
    profile : callable
        f(r) in m of r in m, vectorised, f(0) = 0.
    depths : numpy.ndarray
        Depths in m, positive and increasing (checked where they entered), reached at d / V.
    candidate_radius : float
        Surface nodes with r <= this radius (m) may touch.
    prony : PronySeries
        The body's shear relaxation.
    rate : float
        Pressing speed V in m/s (> 0).
    steps : int
        Time steps from first touch to the deepest depth (:func:`time_grid`).
    backend : str
        Sparse solver, see :func:`shtaerman.fem.solver.factorize`.
    aligned : bool
        Forces of the vertex-aligned contacts at the instant's history (as
        :func:`.contact.solve_contact`), or the nodal sums.

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
                solved, shifted, x, memory = _step(part, memory, heights, depth, free)
            steps_out.append(_record(part.compliance, shifted, depth, solved, aligned))
            solutions.append(x)
    return ContactCurve(
        steps=steps_out,
        compliance=part.compliance,
        system=system,
        solutions=np.array(solutions),
        timings={"factorization": factorized, "contact": time.perf_counter() - start - factorized},
        backend=getattr(part.factorization, "backend", backend),
    )
