"""Frictionless contact of a rigid indenter pressed at a constant rate into a linear body that
relaxes in shear by a Prony series (:func:`press_at_rate`).

Quasi-static time steps, uniform between consecutive requested depths: at each, the history
force of the Prony branches shifts the indenter's clearance by the surface displacement it
alone would cause, and the complementarity problem is solved as in the elastic contact. The
equations and their accuracy: benchmarks/FEM_NOTES.md, "Moved from the docstrings",
fem/contact/rate.py."""

from __future__ import annotations

import itertools
import math
import time
from dataclasses import dataclass, replace

import numpy as np
from threadpoolctl import threadpool_limits

from ...theory.viscoelastic import PronySeries
from ...validation import InputError
from ..elasticity import ElasticSystem
from ..solver import Factorization
from ..viscoelastic import ShearMemory, ViscoelasticShear, viscoelastic_shear
from .linear import (
    ContactCurve,
    Profile,
    SurfaceCompliance,
    complementarity,
    factorize_stiffness,
    step_from_forces,
    surface_compliance,
    timed_curve,
)

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

    Parameters as :func:`.linear.solve_contact` (``system`` with E2, nu2 the instantaneous moduli;
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
