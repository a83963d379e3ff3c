"""Bonded (no slip) or Coulomb contact of a rigid power-law indenter with a rubber body at
finite strain: the rules of :mod:`.constraints` on the finite-strain body.

A candidate node is free until its vertical gap closes; from then on it sticks (its current
radius held, its height on the indenter) or, with Coulomb friction mu, slides with its gap
closed under the friction mu N along the indenter's tangent. The static contact is loaded over
:func:`.constraints.depth_ladder` with a modified Newton (:func:`_newton`,
:func:`_slide_newton`) on the stepper of :class:`.finite.NewtonStepper`; the force P is the
sum of the contact nodes' vertical reactions (N). Derivation and measurements:
benchmarks/FEM_NOTES.md, "Moved from the docstrings", fem/contact/finite_stick.py."""

from __future__ import annotations

import functools
import math
import time
from collections.abc import Callable
from dataclasses import dataclass, field, replace
from typing import Any

import numpy as np
from numpy.typing import ArrayLike

from ...theory.contact import PowerLawContact
from ...theory.indenter import PowerLawIndenter
from ...theory.sneddon import SneddonContact
from ...validation import InputError, NumericalFailureError
from ..hyperelastic import HyperelasticSystem, NewtonError
from ..rubber import gent_locks, gent_stretch
from .constraints import (
    MAX_ACTIVE_SET_ITERATIONS,
    START_NODE,
    STEP_RATIO,
    check_loading,
    check_resolved,
    depth_ladder,
    in_halves,
    settle,
    unsettled,
    walk_ladder,
)
from .finite import (
    MAX_ITERATIONS,
    NEWTON_TOLERANCE,
    FiniteContactCurve,
    FiniteContactStep,
    NewtonStepper,
    column_product,
    eliminate_gaps,
    finite_step,
    pattern_entries,
    solve_finite_contact,
    start_curve,
    tip_exponent,
)

START_FRACTION = 0.05
"""The load steps start where the contact radius is this fraction of the smallest depth's:
the nodes inside it stick at their reference radii."""
KEPT_SETS = 4
"""The Coulomb Newton keeps the factorizations of this many contact sets."""
MAX_ADDED = 40
"""A modified Newton step reuses a factorization with at most this many stuck dofs added
since it was made (one solve each, :meth:`_Kept.constrained`)."""
MAX_LOAD_CUTS = 4
"""Halvings (in ln depth) of a load step of the curve whose Newton or stick and slip failed:
down to 1/16 of its ln(step_ratio) (:func:`_halves`)."""
RELEASE_BAND = 1e-6
"""A stuck node is released when its vertical reaction is below -this x the largest one (N)."""


@dataclass
class _Load:
    """The converged contact at one load step (per candidate node)."""

    held: np.ndarray
    """Current radius (m) of each stuck node; NaN when free."""
    x: np.ndarray
    radius: np.ndarray
    """Current radius R + u_r (m)."""
    gap: np.ndarray
    """Vertical gap (m)."""
    lam: np.ndarray
    """Vertical reaction (N, compression positive)."""
    iterations: int = 0
    corrections: list[float] = field(default_factory=list)
    slip: np.ndarray | None = None
    """Direction +-1 (along r) of each sliding node, 0 when stuck or free; None: no slip."""
    gripped: np.ndarray | None = None
    """Nodes in contact at the last load step, released and gripped anew within this one."""
    forces: np.ndarray | None = None
    """The body's residual at ``x`` (N; at the contact nodes, minus the contact's forces)."""
    stretch: float = 0.0
    """A Gent rubber's (I1bar - 3) / Jm at ``x`` (:func:`.rubber.gent_stretch`)."""

    def key(self) -> bytes:
        """The contact set: the nodes in contact and the slip directions."""
        return np.isnan(self.held).tobytes() + (b"" if self.slip is None else self.slip.tobytes())

    @classmethod
    def untouched(cls, stepper: NewtonStepper) -> _Load:
        """No node of ``stepper``'s candidates in contact, the body at rest."""
        m, radius = stepper.nodes.radius.size, stepper.nodes.radius
        x, heights = np.zeros(stepper.system.n_dofs), stepper.indenter.profile(radius)
        return cls(np.full(m, np.nan), x, radius.copy(), heights, np.zeros(m))


def bonded_ladder(
    stepper: NewtonStepper,
    depths: ArrayLike,
    step_ratio: float = STEP_RATIO,
    start: float | None = None,
) -> np.ndarray:
    """The load steps (m) of the bonded contact up to ``depths`` (m, increasing, included):
    :func:`.constraints.depth_ladder` from ``start`` (m) or by default from the later of the depth
    that reaches candidate node :data:`.constraints.START_NODE` and the depth whose contact radius
    is :data:`START_FRACTION` of the smallest depth's (Shtaerman's d ~ a^n)."""
    depths = np.atleast_1d(np.asarray(depths, dtype=float))
    if start is not None:
        return depth_ladder(start, depths, step_ratio)
    indenter = stepper.indenter
    radius = stepper.nodes.radius[min(START_NODE, stepper.nodes.radius.size - 1)]
    start = float(indenter.profile(radius))
    start = max(start, float(depths[0]) * START_FRACTION ** tip_exponent(indenter))
    return depth_ladder(start, depths, step_ratio)


def _targets(stepper: NewtonStepper, held: np.ndarray, depth: float) -> tuple[np.ndarray, ...]:
    """The stuck nodes' prescribed u_z and u_r: free-dof positions (sorted), their values (m)
    and the pattern entries of their rows and columns."""
    nodes, indenter = stepper.nodes, stepper.indenter
    stuck = np.flatnonzero(~np.isnan(held))
    radial = stuck[nodes.ur_free[stuck]]
    height = indenter.profile(held[stuck]) - depth
    positions = np.concatenate([nodes.uz[stuck], nodes.ur[radial]])
    values = np.concatenate([height, held[radial] - nodes.radius[radial]])
    slaves = stepper.position[positions]
    order = np.argsort(slaves)
    slaves, values = slaves[order], values[order]
    moved = pattern_entries(stepper.pattern, slaves) if slaves.size else np.zeros(0, np.int64)
    return slaves, values, moved


def _shift(
    stepper: NewtonStepper, x: np.ndarray, slaves: np.ndarray, values: np.ndarray
) -> np.ndarray:
    """The increment (m, free dofs) that puts the prescribed ``slaves`` of ``x`` on their
    ``values``, zero elsewhere."""
    shift = np.zeros(stepper.pattern.size)
    shift[slaves] = values - x[stepper.free][slaves]
    return shift


def _shifted_load(
    stepper: NewtonStepper, residual: np.ndarray, tangent: np.ndarray, shift: np.ndarray
) -> np.ndarray:
    """The free dofs' ``residual`` (N) plus the ``tangent``'s response to ``shift`` (m); a
    zero shift's (every Newton iteration after the first) is none."""
    moved = np.flatnonzero(shift)
    if not moved.size:
        return residual
    return residual + column_product(stepper.pattern, tangent, moved, shift[moved])


def _warm_newton(
    newton: Any,
    stepper: NewtonStepper,
    trial: _Load,
    at: tuple[float, float],
    warm: dict[bytes, tuple] | None,
) -> tuple[np.ndarray, np.ndarray, int, list[float]]:
    """``newton(stepper, trial, *at)`` (:func:`_newton`, :func:`_slide_newton`) started
    from the solution (x, lam) that an earlier solve of the time step found with
    ``trial``'s contact set, if ``warm`` holds one (else, or should that fail, from
    ``trial``); the solution is recorded in ``warm``."""
    if warm is None:
        return newton(stepper, trial, *at)
    key = trial.key()
    solved = None
    if key in warm:
        try:
            solved = newton(stepper, replace(trial, x=warm[key][0], lam=warm[key][1]), *at)
        except NewtonError:
            solved = None
    if solved is None:
        solved = newton(stepper, trial, *at)
    warm[key] = solved[:2]
    return solved


def _newton(
    stepper: BondedStepper, trial: _Load, depth: float, scale: float
) -> tuple[np.ndarray, np.ndarray, int, list[float]]:
    """Newton at ``depth`` (m) from ``trial.x`` with its stuck nodes (``held`` radii)
    prescribed; its corrections measured relative to ``scale`` (m). Returns x, ``trial.lam``,
    the iterations and corrections. A ``modified`` stepper reuses the last factorization
    (:func:`_reusable`)."""
    slaves, values, moved = _targets(stepper, trial.held, depth)

    def increment(x: np.ndarray, lam: np.ndarray, state: Any, *history: list) -> tuple:
        reuse = _reusable(stepper, slaves, *history)
        shift = _shift(stepper, x, slaves, values)
        du = _stuck_step(stepper, x, state, (slaves, moved, shift), reuse)
        return du, np.zeros(0, np.int64), np.zeros(0), reuse is None, True

    return stepper.iterate((trial.x, trial.lam), scale, increment)


@dataclass
class _Kept:
    """The bonded Newton's last factorization, for a modified Newton's reuse."""

    system: HyperelasticSystem
    slaves: np.ndarray
    """The prescribed (stuck) free-dof positions it was made with."""
    tangent: np.ndarray
    """The tangent's data (N/m, not reduced) in the stepper's pattern."""
    again: Callable[[np.ndarray], np.ndarray]
    """Solves with the reduced tangent."""
    size: int
    """Free dofs."""
    columns: dict[int, np.ndarray] = field(default_factory=dict)
    """Per free-dof position added to ``slaves``: the reduced tangent's inverse's column."""
    added: dict[bytes, tuple] = field(default_factory=dict)
    """The latest added dofs: their columns Z and the inverse of their capacitance C."""

    def constrained(self, slaves: np.ndarray) -> Callable[[np.ndarray], np.ndarray] | None:
        """A solve of the kept reduced tangent with ``slaves`` (sorted) prescribed instead of
        its own, or None where one of its own is not in ``slaves`` (a node released) or more
        than :data:`MAX_ADDED` are added. The added dofs are held at zero through the capacitance
        matrix (one kept solve per added dof)."""
        if slaves.size == self.slaves.size and np.array_equal(slaves, self.slaves):
            return self.again
        added = np.setdiff1d(slaves, self.slaves, assume_unique=True)
        if added.size + self.slaves.size != slaves.size or added.size > MAX_ADDED:
            return None
        key = added.tobytes()
        if key not in self.added:
            for dof in added.tolist():
                if dof not in self.columns:
                    unit = np.zeros(self.size)
                    unit[dof] = 1.0
                    self.columns[dof] = self.again(unit)
            inverse = np.stack([self.columns[dof] for dof in added.tolist()], axis=1)
            self.added = {key: (inverse, np.linalg.inv(inverse[added]))}
        inverse, capacitance = self.added[key]

        def solve(load: np.ndarray) -> np.ndarray:
            z = self.again(load)
            return z - inverse @ (capacitance @ z[added])

        return solve


def _stuck_step(
    stepper: BondedStepper, x: np.ndarray, state: Any, stuck: tuple, reuse: tuple | None
) -> np.ndarray:
    """Newton's increment of the free dofs (m) at ``x`` with ``stuck`` = (slaves, their
    pattern entries, the increment ``shift`` that puts them on their targets): with the
    ``reuse`` = (kept tangent, its solve with these slaves), or a fresh tangent, factorized
    (and kept where the stepper is ``modified``)."""
    slaves, moved, shift = stuck
    pattern = stepper.pattern
    residual = stepper.system.residual(x, state)[stepper.free]
    if reuse is None:
        tangent, again = stepper.system.tangent_data(x, state)[stepper.take], None
    else:
        tangent, again = reuse
    load = _shifted_load(stepper, residual, tangent, shift)
    load[slaves] = 0.0
    if again is not None:
        return again(-load) + shift
    solution, again = stepper.solver.factorized(_reduced(stepper, tangent, slaves, moved), -load)
    if stepper.modified:
        stepper.kept_stuck = _Kept(stepper.system, slaves, tangent, again, pattern.size)
    return solution + shift


def _reusable(
    stepper: BondedStepper, slaves: np.ndarray, corrections: list[float], fresh: list[bool]
) -> tuple | None:
    """The stepper's kept tangent and its solve with these stuck ``slaves``
    (:meth:`_Kept.constrained`) if the next step may reuse them
    (:meth:`.finite.NewtonStepper.may_reuse`); else None."""
    kept = stepper.kept_stuck
    if kept is None or not stepper.may_reuse(kept.system, corrections, fresh):
        return None
    again = kept.constrained(slaves)
    return None if again is None else (kept.tangent, again)


def _held(
    last: _Load, held: np.ndarray, enter: np.ndarray, radius: np.ndarray, gap: np.ndarray
) -> np.ndarray:
    """``held`` with the ``enter`` nodes stuck at the radius (m) where their gap closes,
    interpolated between ``last`` and the current ``radius`` and ``gap`` (m); a node released
    within this step that penetrates again grips where it is now."""
    before = last.gap[enter]
    closing = np.ones_like(before)
    opened = before > 0.0
    closing[opened] = before[opened] / (before[opened] - gap[enter][opened])
    held = held.copy()
    held[enter] = last.radius[enter] + closing * (radius[enter] - last.radius[enter])
    return held


def _load_step(
    stepper: NewtonStepper,
    last: _Load,
    guess: np.ndarray,
    at: tuple[float, float],
    friction: float = math.inf,
    warm: dict[bytes, tuple] | None = None,
) -> _Load:
    """The contact at depth ``at[0]`` (m) from the contact ``last`` at the previous load step,
    bonded (``friction`` inf) or with Coulomb ``friction``: stuck nodes that slide and sliding
    ones that stick again; :func:`.constraints.settle` changes the contact set. ``at[1]`` (m)
    measures Newton's corrections and the gaps (the depth, or where it may be <= 0 the
    impact's). ``warm``: the solutions of earlier solves from ``last`` by contact set
    (:func:`_warm_newton`), updated."""
    depth, scale = at
    bonded, m = math.isinf(friction), last.held.size
    # stuck at the start: last's, and the free nodes the predicted guess puts below the indenter
    radius, gap, _, _ = stepper.geometry(guess, depth)
    enter = np.isnan(last.held) & (gap < -stepper.tolerance * scale)
    held = _held(last, last.held, enter, radius, gap)
    start = _Load(held, guess, last.radius, last.gap, last.lam)
    if not bonded:
        start.slip = np.zeros(m) if last.slip is None else last.slip.copy()
        start.gripped = np.zeros(m, dtype=bool)
    newton = _newton if bonded else functools.partial(_slide_newton, friction=friction)
    total = 0

    def attempt(trial: _Load) -> tuple[tuple, list[np.ndarray], list[np.ndarray]]:
        nonlocal total
        x, lam, iterations, corrections = _warm_newton(newton, stepper, trial, at, warm)
        total += iterations
        radius, gap, _, _ = stepper.geometry(x, depth)
        state = stepper.system.state(x)
        forces = stepper.system.residual(x, state)
        # the stuck nodes' vertical reactions -dPi/du_z (N, compression positive)
        vertical = np.where(np.isnan(trial.held), 0.0, -forces[stepper.nodes.uz])
        now = replace(trial, x=x, radius=radius, gap=gap, lam=vertical, forces=forces)
        now.stretch = gent_stretch(stepper.system.material, state)
        now.iterations, now.corrections = total, corrections
        changes, excess, shear = _changes(stepper, now, last, friction, at)
        return (now, lam, shear), changes, excess

    def update(trial: _Load, solved: tuple, changes: list[np.ndarray]) -> _Load:
        (now, lam, shear), (release, enter, to_slip, to_stick) = solved, changes
        held = _held(last, trial.held, enter, now.radius, now.gap)
        held[release] = np.nan
        following = _Load(held, now.x, now.radius, now.gap, lam, total, now.corrections)
        if bonded:
            return following
        held[to_stick] = _origin(last, now)[to_stick]
        slip = trial.slip.copy()
        slip[to_slip] = -np.sign(shear[to_slip])
        slip[release | to_stick] = 0.0
        following.lam = np.where(slip != 0, np.where(to_slip, now.lam, lam), 0.0)
        following.slip, following.gripped = slip, trial.gripped | (enter & ~np.isnan(last.held))
        return following

    limit = MAX_ACTIVE_SET_ITERATIONS + (1 if bonded else 2) * m
    solved = settle(start, attempt, update, _Load.key, limit)
    if solved is None:
        raise unsettled(depth)
    load = solved[0]
    load.gap = np.where(np.isnan(load.held), np.maximum(load.gap, 0.0), 0.0)
    load.lam = np.maximum(load.lam, 0.0)
    return load


def _slide_newton(
    stepper: BondedStepper, trial: _Load, depth: float, scale: float, friction: float
) -> tuple[np.ndarray, np.ndarray, int, list[float]]:
    """Newton at ``depth`` (m) from ``trial`` (its ``lam``: the sliding nodes' starting
    multipliers, N) with its stuck nodes prescribed and its sliding nodes on the indenter,
    carrying the friction -slip ``friction`` lambda along the indenter's tangent, linearized
    (:func:`.finite.eliminate_gaps` with ``drag``). Returns x, the multipliers, the iterations
    and corrections."""
    system, pattern, nodes = stepper.system, stepper.pattern, stepper.nodes
    slip = trial.slip
    slaves, values, moved = _targets(stepper, np.where(slip != 0, np.nan, trial.held), depth)
    rows = np.flatnonzero(slip != 0)
    sliding = rows[nodes.ur_free[rows]]  # d(drag f')/du_r: the u_z row, the u_r column
    across = pattern.find(stepper.position[nodes.uz[sliding]], stepper.position[nodes.ur[sliding]])
    key = slaves.tobytes() + slip.tobytes()

    def increment(x: np.ndarray, lam: np.ndarray, state: Any, *history: list) -> tuple:
        _, gap, slope, curvature = stepper.geometry(x, depth)
        drag = slip * friction * lam
        residual = system.residual(x, state)
        np.subtract.at(residual, nodes.ur, lam * slope - drag)
        np.add.at(residual, nodes.uz, lam + drag * slope)
        reuse = _slide_reusable(stepper, key, *history)
        if reuse is None:
            tangent = system.tangent_data(x, state)[stepper.take]
            tangent[stepper.curvature_at] -= (lam * curvature)[nodes.ur_free]
            tangent[across] += (drag * curvature)[sliding]
            reduced, again = _reduced(stepper, tangent, slaves, moved), None
        else:
            tangent, reduced, again = reuse
        shift = _shift(stepper, x, slaves, values)
        load = _shifted_load(stepper, residual[stepper.free], tangent, shift)
        load[slaves] = -shift[slaves]
        du, dlam = eliminate_gaps(
            stepper, reduced, load, rows, slope, gap, slip * friction, again=again
        )
        if reuse is None and stepper.modified:
            sets = stepper.kept_slide  # this set's the newest, the oldest beyond KEPT_SETS dropped
            sets.pop(key, None)
            sets[key] = (system, tangent, reduced, stepper.factorization)
            while len(sets) > KEPT_SETS:
                del sets[next(iter(sets))]
        return du, rows, dlam, reuse is None, True

    return stepper.iterate((trial.x, np.where(slip != 0, trial.lam, 0.0)), scale, increment)


def _reduced(
    stepper: BondedStepper, tangent: np.ndarray, slaves: np.ndarray, moved: np.ndarray
) -> np.ndarray:
    """``tangent``'s data (N/m, the stepper's pattern) with the prescribed dofs ``slaves``
    eliminated: their rows and columns (``moved``: their pattern entries) zeroed, a unit
    diagonal."""
    reduced = tangent.copy()
    reduced[moved] = 0.0
    reduced[stepper.pattern.diagonal[slaves]] = 1.0
    return reduced


def _slide_reusable(
    stepper: BondedStepper, key: bytes, corrections: list[float], fresh: list[bool]
) -> tuple | None:
    """The kept tangent, its reduced form and factorization of the Coulomb Newton for the
    contact set ``key`` (stuck dofs and slip directions) if the next step may reuse them
    (:meth:`.finite.NewtonStepper.may_reuse`); else None."""
    kept = stepper.kept_slide.get(key)
    if kept is None or not stepper.may_reuse(kept[0], corrections, fresh):
        return None
    return kept[1:]


def _resolved(stepper: NewtonStepper, load: _Load, depth: float) -> tuple[np.ndarray, ...]:
    """The tangential force T along the indenter's tangent (1, f')/|.| and the normal force
    N on its normal (N, on the body) of each node: ``load``'s vertical reactions and radial
    forces resolved at its current radius."""
    nodes = stepper.nodes
    residual = load.forces
    _, _, slope, _ = stepper.geometry(load.x, depth)
    push = np.where(nodes.ur_free, residual[nodes.ur], 0.0)  # radial force on the body
    norm = np.sqrt(1.0 + slope**2)
    return (push - slope * load.lam) / norm, (slope * push + load.lam) / norm


def _changes(
    stepper: NewtonStepper,
    trial: _Load,
    last: _Load,
    friction: float,
    at: tuple[float, float],
) -> tuple[list[np.ndarray], list[np.ndarray], np.ndarray | None]:
    """The violated conditions (release, enter, stick to slip, slip to stick), their size and
    the tangential force T (N, on the body along the indenter's tangent (1, f')/|.|; None
    where the contact is bonded, ``friction`` inf: nothing slides).

    ``trial.lam`` holds the vertical reactions (N) of the nodes in contact; a stuck node
    slides where |T| exceeds ``friction`` x its normal force (:func:`_resolved`). ``at``: the
    depth (m) and the scale (m) that measures gaps and slips."""
    depth, scale = at
    band = RELEASE_BAND * np.abs(trial.lam).max(initial=0.0)
    contact = ~np.isnan(trial.held)
    release = contact & (trial.lam < -band)
    enter = ~contact & (trial.gap < -stepper.tolerance * scale)
    if math.isinf(friction):
        none = np.zeros_like(release)
        return [release, enter, none, none], [-trial.lam, -trial.gap, trial.lam, trial.lam], None
    shear, normal = _resolved(stepper, trial, depth)
    sliding = trial.slip != 0
    excess = np.abs(shear) - friction * normal
    to_slip = contact & ~sliding & stepper.nodes.ur_free & (excess > band)
    moved = trial.slip * (trial.radius - _origin(last, trial))
    to_stick = sliding & ~release & (moved < -stepper.tolerance * scale)
    changes = [release, enter, to_slip, to_stick]
    return changes, [-trial.lam, -trial.gap, excess, -moved], shear


def _origin(last: _Load, trial: _Load) -> np.ndarray:
    """Where a node's slip is measured from (m): its radius at the last load step if it was in
    contact then, else (it touched, or was gripped anew, in this step) its touching radius."""
    fresh = np.isnan(last.held)
    if trial.gripped is not None:
        fresh = fresh | trial.gripped
    return np.where(fresh, trial.held, last.radius)


class BondedStepper(NewtonStepper):
    """A :class:`.finite.NewtonStepper` that keeps the bonded and the Coulomb
    Newton's factorizations and reuses them (``modified``: :func:`_newton`,
    :func:`_slide_newton`), in the quasi-static curve and an impact's time steps."""

    redone_in_full = False  # a reused factorization's update that inverts an element is halved

    def __init__(self, *args: Any) -> None:
        super().__init__(*args)
        self.modified = True  # the full case: 42.5 -> 28.5 CPU s, results moved by < 3e-11
        self.kept_stuck: _Kept | None = None
        # by contact set: system, tangent, reduced tangent, factorization
        self.kept_slide: dict[bytes, tuple] = {}


class HistoryStepper(BondedStepper):
    """The bonded (``friction`` inf: no slip) or Coulomb contact of a time-stepped impact.

    Every :meth:`solve` is one load step (:func:`_load_step`) from the committed contact;
    :meth:`commit` makes the latest solve the committed one and adds the work of friction over
    the step to ``dissipated`` (J). The multipliers passed to :meth:`solve` are not used."""

    def __init__(
        self,
        system: HyperelasticSystem,
        indenter: PowerLawIndenter,
        candidate_radius: float,
        limits: tuple[float, int],
        friction: float,
    ) -> None:
        super().__init__(system, indenter, candidate_radius, *limits)
        self.friction = friction
        self.committed = _Load.untouched(self)
        self.normal = np.zeros(self.nodes.radius.size)  # the committed normal forces (N)
        self.latest: tuple[_Load, np.ndarray] | None = None
        self.warm: dict[bytes, tuple] = {}  # the solves from the committed contact, by set
        self.dissipated = 0.0

    def solve(
        self, depth: float, x: np.ndarray, lam: np.ndarray, scale: float | None = None
    ) -> tuple[np.ndarray, np.ndarray, int, list[float]]:
        """The contact at ``depth`` (m) from the committed one, Newton started at ``x``:
        x, the vertical reactions (N), iterations and corrections (relative to ``scale``, m)."""
        scale = depth if scale is None else scale
        load = _load_step(self, self.committed, x, (depth, scale), self.friction, self.warm)
        self.latest, self.stretch = (load, _resolved(self, load, depth)[1]), load.stretch
        return load.x, load.lam, load.iterations, load.corrections

    def commit(self, x: np.ndarray) -> None:
        """Make the latest solve, whose solution is ``x``, the committed contact."""
        assert self.latest is not None and self.latest[0].x is x, "commit the latest solve"
        load, normal = self.latest
        if load.slip is not None:
            before, sliding = self.committed, (load.slip != 0) & ~np.isnan(self.committed.held)
            moved = np.abs(load.radius - before.radius)[sliding]
            middle = 0.5 * (load.radius + before.radius)[sliding]
            slope = self.indenter.slope(middle)
            force = 0.5 * (normal + self.normal)[sliding]
            self.dissipated += self.friction * float(np.sum(force * moved * np.sqrt(1 + slope**2)))
        self.committed, self.normal, self.warm = load, normal, {}


def solve_finite_bonded_contact(
    system: HyperelasticSystem,
    indenter: PowerLawIndenter,
    depths: ArrayLike,
    candidate_radius: float,
    *,
    step_ratio: float = STEP_RATIO,
    start: float | None = None,
    tolerance: float = NEWTON_TOLERANCE,
    max_iterations: int = MAX_ITERATIONS,
    friction: float = math.inf,
) -> FiniteContactCurve:
    """Press a rigid power-law indenter that the rubber sticks to, in load steps.

    Parameters and result as :func:`.finite.solve_finite_contact`, with
    ``step_ratio`` > 1 the depth ratio of consecutive load steps and ``start`` (m, at most the
    smallest depth) the first (default and ladder: :func:`bonded_ladder`). Each step's
    ``multipliers`` are the vertical reactions (N) of the stuck nodes, its
    ``newton_iterations`` those of its load step (all contact sets tried) and its
    ``total_iterations`` those since the previous requested depth. ``friction`` >= 0 is
    the Coulomb coefficient (inf: no slip): a stuck node slides once its shear exceeds
    ``friction`` times its normal force, both resolved on the indenter's normal at its
    current radius; 0 is the frictionless contact, solved as such (no load steps). A load
    step that fails is taken in halves (:func:`_halves`), counted in the curve's ``cuts``.

    Raises
    ------
    NumericalFailureError
        A load step cut :data:`MAX_LOAD_CUTS` times did not converge, inverted an element or
        its stick and slip did not settle.
    GentLockError
        The Gent rubber reached its limit.
    ContactOutgrowsMeshError
        The contact zone reached the edge of the candidate region.
    """
    check_loading(step_ratio, friction)
    if friction == 0.0:  # nothing resists slip: no history, no load steps
        limits = {"tolerance": tolerance, "max_iterations": max_iterations}
        return solve_finite_contact(system, indenter, depths, candidate_radius, **limits)
    depths = np.atleast_1d(np.asarray(depths, dtype=float))
    begun = time.perf_counter()
    limits = (candidate_radius, tolerance, max_iterations)
    stepper, exact = start_curve(BondedStepper, system, indenter, depths, limits)
    if start is not None and not 0.0 < start <= depths[0]:
        raise InputError(f"start: must be in (0, {depths[0]:g}] m, got {start!r}", "start")
    ladder = bonded_ladder(stepper, depths, step_ratio, start)
    steps, cuts = _finite_ladder(stepper, exact, depths, ladder, friction)
    timings = {"contact": time.perf_counter() - begun}
    return FiniteContactCurve(steps, system, indenter, timings, cuts=cuts)


def _finite_ladder(
    stepper: NewtonStepper,
    exact: PowerLawContact | SneddonContact,
    depths: np.ndarray,
    ladder: np.ndarray,
    friction: float,
) -> tuple[list[FiniteContactStep], int]:
    """Load through the ``ladder`` (m) and keep the contact at each requested depth (Coulomb
    ``friction``; inf: no slip); each load step starts from the solution extrapolated linearly
    from the last two, and one that fails is taken in halves (:func:`_halves`; a Gent rubber
    that locks, :func:`.rubber.gent_locks`, is not cut: its limit is an input). Returns the
    steps and how many load steps of the ladder were cut."""
    last, previous, done, previous_depth = _Load.untouched(stepper), None, 0.0, 0.0
    cuts, iterations = 0, 0

    def step(start: float, depth: float) -> list[float]:
        nonlocal last, previous, done, previous_depth, iterations
        guess = last.x
        if previous is not None:
            guess = last.x + (depth - start) / (start - previous_depth) * (last.x - previous.x)
        state = _load_step(stepper, last, guess, (depth, depth), friction)
        check_resolved(stepper.nodes.radius, state.lam, depth, fewest=1)
        stepper.watch.accept(depth, state.stretch)
        previous, previous_depth, last, done = last, start, state, depth
        iterations += state.iterations
        return [depth]

    def give_up(error: Exception, start: float, depth: float, exhausted: bool) -> Any:
        locked = gent_locks(error, stepper.system, last.x, (start, depth), last=exhausted)
        return locked or (_exhausted(error, start, depth) if exhausted else None)

    def advance(depth: float) -> int:
        nonlocal cuts, iterations
        iterations = 0
        cuts += len(in_halves(step, done, depth, _halves, give_up, MAX_LOAD_CUTS)) > 1
        return iterations

    def record(depth: float, taken: int) -> FiniteContactStep:
        solved = (last.x, last.lam, last.iterations, taken, last.corrections)
        return finite_step(stepper, exact, depth, *solved)

    return walk_ladder(ladder, depths, advance, record), cuts


def _halves(done: float, depth: float) -> tuple[float, float]:
    """The halves of the load step from ``done`` to ``depth`` (m) whose Newton or stick and
    slip failed (:func:`.constraints.in_halves`): to the geometric middle sqrt(done depth),
    then to ``depth``; the first step, from depth 0, is cut at depth / 2."""
    return (math.sqrt(done * depth) if done > 0.0 else 0.5 * depth), depth


def _exhausted(error: Exception, done: float, depth: float) -> NumericalFailureError:
    """The failure of the load step from ``done`` to ``depth`` (m), cut
    :data:`MAX_LOAD_CUTS` times, with ``error``: what failed and the options that help."""
    failed = str(error) if isinstance(error, NewtonError) else "the stick and slip did not settle"
    return NumericalFailureError(
        f"depth {depth:g} m (bonded, from {done:g} m): {failed}, in a load step cut in halves "
        f"{MAX_LOAD_CUTS} times; refine the mesh (mesh_size=... or refine=...) or lower the "
        "deepest depth (depths=...)"
    )
