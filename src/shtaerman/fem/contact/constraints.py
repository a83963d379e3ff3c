"""The contact constraints of a rigid indenter written once, for any body: the active-set
loop of a history-dependent contact (bonded or Coulomb), the load ladder of the static
contact, the halving of a failing load or time step (:func:`in_halves`), and what is read
off a solved contact (its edge, its central pressure, whether the mesh resolves it).

A body supplies the solve of one contact set (the linear body: :mod:`.stick`; the
finite-strain body: :mod:`.finite_stick`) and :func:`settle` changes the set until no
condition is violated (enter, release, stick to slip, slip to stick); all violated conditions
change at once, and should a contact set repeat, one node at a time (:func:`worst_only`).
The rules: benchmarks/FEM_NOTES.md, "Moved from the docstrings", fem/contact/constraints.py."""

from __future__ import annotations

import itertools
from collections.abc import Callable, Iterable
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from ...validation import InputError, NumericalFailureError

MAX_ACTIVE_SET_ITERATIONS = 100
ROUND_OFF = 1e-10
"""Relative band within which a force or gap counts as zero in the active-set update."""
EDGE_MARGIN = 3
"""Candidate nodes that must stay free beyond the contact edge, or the zone is too small."""
MIN_CONTACT_NODES = 3
"""Fewest loaded surface nodes of a contact (the axis node carries none): fewer cannot resolve
the force and the radius."""


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


def edge_and_centre(r: np.ndarray, solved: tuple, depth: float) -> tuple[float, float]:
    """The contact radius (m, :func:`edge_radius`) and the central pressure (Pa,
    :func:`central_pressure`) of the contact at ``depth`` (m) on the candidates at radii ``r``
    (m), from ``solved`` = (nodal forces in N, gaps in m, recovered pressure in Pa)."""
    forces, gap, pressure = solved
    try:
        radius = edge_radius(r, forces, gap)
    except NumericalFailureError as error:
        raise NumericalFailureError(
            f"depth {depth:g} m: {error}; lower the deepest depth"
        ) from None
    return radius, central_pressure(r, pressure, radius)


@dataclass(frozen=True)
class SolvedContact:
    """What a contact at one depth reports, on any body (SI units).

    Attributes
    ----------
    depth : float
        Indenter depth d in m.
    force : float
        Total indenter force P in N.
    contact_radius : float
        Contact radius a in m, located between nodes (:func:`edge_radius`).
    central_pressure : float
        Pressure at the axis p(0) in Pa (:func:`central_pressure`).
    pressure : numpy.ndarray
        Recovered pressure p (Pa) at the candidate nodes.
    gap : numpy.ndarray
        Gap g >= 0 in m at the candidate nodes (0 in contact).
    """

    depth: float
    force: float
    contact_radius: float
    central_pressure: float
    pressure: np.ndarray = field(repr=False)
    gap: np.ndarray = field(repr=False)

    @property
    def mean_pressure(self) -> float:
        """P / (pi a^2) in Pa."""
        return self.force / (np.pi * self.contact_radius**2)


class ContactOutgrowsMeshError(InputError):
    """The contact zone reached the edge of the candidate (refined) region."""


class UnresolvedContactError(InputError):
    """A contact on fewer surface nodes than resolve it: its ``depth`` (m), the nodes it
    ``loaded`` and the ``fewest`` it needs (attributes set by :func:`check_resolved`)."""

    depth: float
    loaded: int
    fewest: int


def check_resolved(
    r: np.ndarray, forces: np.ndarray, depth: float, fewest: int = MIN_CONTACT_NODES
) -> None:
    """InputError unless the contact at ``depth`` (m) loads at least ``fewest`` surface nodes
    (nodal ``forces`` > 0, N; :class:`UnresolvedContactError`) and stays ``EDGE_MARGIN``
    nodes inside the candidates (radii ``r``, m; :class:`ContactOutgrowsMeshError`)."""
    loaded = np.flatnonzero(forces > 0)
    if loaded.size < fewest:
        error = UnresolvedContactError(
            f"depth {depth:g} m: the contact loads {loaded.size} surface node(s), fewer than "
            f"{fewest}: smaller than this mesh resolves; raise the smallest depth or "
            "refine the mesh (mesh_size=..., refine=...)"  # each route words it
        )
        error.depth, error.loaded, error.fewest = depth, int(loaded.size), fewest
        raise error
    if loaded[-1] + EDGE_MARGIN >= r.size:
        raise ContactOutgrowsMeshError(
            f"depth {depth:g} m: the contact zone reaches r = {r[loaded[-1]]:.4g} m, "
            f"the edge of the refined region ({r[-1]:.4g} m); mesh a larger region (raise "
            "--mesh-margin)"
        )


def worst_only(changes: list[np.ndarray], excess: list[np.ndarray]) -> list[np.ndarray]:
    """``changes`` (boolean masks, in order of priority) cut to the single node of the first
    non-empty one with the largest ``excess`` (the cautious update after a cycle)."""
    cut = [np.zeros_like(change) for change in changes]
    for change, amount, one in zip(changes, excess, cut, strict=True):
        if change.any():
            one[np.flatnonzero(change)[np.argmax(amount[change])]] = True
            break
    return cut


def settle(
    state: Any,
    attempt: Callable[[Any], tuple[Any, list[np.ndarray], list[np.ndarray]]],
    update: Callable[[Any, Any, list[np.ndarray]], Any],
    key: Callable[[Any], bytes],
    limit: int,
) -> Any:
    """The active-set loop of a history-dependent contact, from the contact set ``state``.

    ``attempt(state)`` solves the body with that set and returns (solved, changes, excess):
    the violated conditions (release, enter, stick to slip, slip to stick: boolean masks per
    candidate) and their size; ``update(state, solved, changes)`` the next set; ``key(state)``
    identifies a set. All violated conditions change at once; should a set repeat, one node at
    a time (:func:`worst_only`). Returns the solved contact with no condition violated, or
    None if the sets keep cycling (or after ``limit`` attempts).
    """
    seen: set[bytes] = set()
    cautious = False
    for _ in range(limit):
        solved, changes, excess = attempt(state)
        if not any(change.any() for change in changes):
            return solved
        if cautious:
            changes = worst_only(changes, excess)
        seen.add(key(state))
        state = update(state, solved, changes)
        if key(state) in seen:
            if cautious:
                return None
            cautious, seen = True, set()
    return None


STEP_RATIO = 1.02
"""Default depth ratio of consecutive load steps (benchmarks/FEM_NOTES.md, "Interface
friction", measures the force's convergence in it)."""
START_NODE = 4
"""The first load step is the depth at which the indenter reaches this candidate node (counted
from the axis): the history before it is taken as one step."""


def check_loading(step_ratio: float, friction: float) -> None:
    """InputError unless ``step_ratio`` > 1 and the Coulomb ``friction`` >= 0 (inf: no slip)."""
    if not step_ratio > 1.0:
        raise InputError(f"step_ratio: must be > 1, got {step_ratio!r}", "step_ratio")
    if not friction >= 0.0:
        raise InputError(f"friction: must be >= 0 (inf: no slip), got {friction!r}", "friction")


SUB_STEPS = 4
"""A load step whose stick and slip sets cycle is taken again as this many geometric
sub-steps (:func:`cut_step`)..."""
CUTS = 2
"""... and each sub-step that cycles again likewise, down to 1 / SUB_STEPS**CUTS of the step."""


def unsettled(depth: float, cut: int = 1) -> NumericalFailureError:
    """The failure of a load step at ``depth`` (m) whose stick and slip sets keep cycling,
    even in load steps ``cut`` times smaller (:func:`cut_step`)."""
    smaller = f", even in load steps {cut} times smaller" if cut > 1 else ""
    return NumericalFailureError(
        f"depth {depth:g} m: the contact's stick and slip did not settle{smaller}; refine the "
        "mesh (refine=...) or take another mesh size (mesh_size=...)"
    )


def cut_step(
    step: Callable[[float, Any], Any | None], state: Any, depths: tuple[float, float], cuts: int
) -> tuple[Any | None, int]:
    """The contact at ``depths[1]`` (m) from ``state``, the contact at ``depths[0]``:
    ``step(depth, state)`` (None when its sets cycle) or, should it cycle, :data:`SUB_STEPS`
    geometric sub-steps, each cut again the same way up to ``cuts`` times. Returns the
    contact (None if a sub-step still cycles) and the steps taken."""
    solved = step(depths[1], state)
    if solved is not None or cuts == 0 or not depths[0] > 0.0:
        return solved, 1
    taken = 1
    for start, end in itertools.pairwise(np.geomspace(*depths, SUB_STEPS + 1)):
        state, count = cut_step(step, state, (float(start), float(end)), cuts - 1)
        taken += count
        if state is None:
            break
    return state, taken


def in_halves(
    step: Callable[[Any, Any], list],
    start: Any,
    span: Any,
    halve: Callable[[Any, Any], tuple[Any, Any]],
    give_up: Callable[[NumericalFailureError, Any, Any, bool], Exception | None],
    limit: int,
    ended: Callable[[Any], bool] = lambda reached: False,
) -> list:
    """``step(start, span)``: what one step over ``span`` (a load step's target depth, a time
    step's dt) reaches from ``start``, committed (a list; its last is the next start); where it
    fails (a NumericalFailureError), two halves (``halve(start, span)``: their spans), each
    committed before the next and cut again where it fails, at most ``limit`` deep; the second
    is skipped where the first ``ended`` the contact. ``give_up(error, start, span, last)``: the
    error to raise instead of a cut (``error`` itself too), or None to cut (``last``: no cut
    left, where None raises ``error``)."""

    def taken(start: Any, span: Any, cut: int) -> list:
        try:
            return step(start, span)
        except NumericalFailureError as error:
            refusal = give_up(error, start, span, cut == limit)
            if refusal is not None:
                raise refusal from None
            if cut == limit:
                raise
        first, second = halve(start, span)
        done = taken(start, first, cut + 1)
        return done if ended(done[-1]) else done + taken(done[-1], second, cut + 1)

    return taken(start, span, 0)


def depth_ladder(start: float, depths: np.ndarray, step_ratio: float) -> np.ndarray:
    """Load steps (m): geometric with ``step_ratio`` from ``start`` (at most depths[0]) to
    depths[-1], merged with ``depths`` (each requested depth is one of them)."""
    start = min(start, depths[0])
    count = int(np.ceil(np.log(depths[-1] / start) / np.log(step_ratio)))
    ladder = start * step_ratio ** np.arange(count)
    return np.union1d(ladder[ladder < depths[-1]], depths)


def walk_ladder(
    ladder: Iterable[float],
    depths: np.ndarray,
    advance: Callable[[float], int],
    record: Callable[[float, int], Any],
) -> list:
    """Load through ``ladder`` (m): ``advance(depth)`` takes one load step and returns its
    work (load steps, Newton iterations); at each of the requested ``depths`` (m) the result
    ``record(depth, work since the previous one)`` is kept."""
    wanted, kept, taken = set(np.asarray(depths).tolist()), [], 0
    for depth in map(float, ladder):
        taken += advance(depth)
        if depth in wanted:
            kept.append(record(depth, taken))
            taken = 0
    return kept
