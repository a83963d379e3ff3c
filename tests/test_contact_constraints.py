"""The contact constraints written once (:mod:`shtaerman.fem.contact.constraints`): the
active-set loop that both bodies' bonded and Coulomb contacts run, and the load ladder."""

import numpy as np

from shtaerman.fem.contact.constraints import depth_ladder, settle, walk_ladder


def _key(state: np.ndarray) -> bytes:
    return state.tobytes()


def test_settle_changes_every_violation_at_once_until_none_is_left():
    """Two nodes that must enter: one update takes both, the second attempt is the answer."""
    target = np.array([True, True, False])

    def attempt(state):
        enter = target & ~state
        return ("solved", state.copy()), [np.zeros(3, bool), enter], [np.zeros(3), -1.0 * enter]

    def update(state, solved, changes):
        return state | changes[1]

    attempts = []
    result = settle(np.zeros(3, bool), lambda s: attempts.append(s) or attempt(s), update, _key, 10)
    assert result[0] == "solved" and result[1].tolist() == target.tolist()
    assert len(attempts) == 2  # all at once: not one node per attempt


def test_settle_goes_one_node_at_a_time_after_a_cycle_and_gives_up_on_a_second():
    """A set that flips between two states is retried cautiously (the worst node only); a
    cycle in that mode too returns None, the caller's "did not settle"."""
    flips = []

    def attempt(state):
        change = np.ones(3, bool)  # every node always wants to flip: a cycle
        return "solved", [change], [np.arange(3.0)]

    def update(state, solved, changes):
        flips.append(np.flatnonzero(changes[0]).tolist())
        return state ^ changes[0]

    assert settle(np.zeros(3, bool), attempt, update, _key, 100) is None
    # all at once until the set repeats, then the node of the largest excess (2) alone
    assert flips == [[0, 1, 2], [0, 1, 2], [2], [2]]


def test_settle_stops_after_its_limit():
    """Never more attempts than ``limit``, each state new (no cycle to detect)."""
    count = []

    def attempt(state):
        count.append(1)
        return None, [np.ones(1, bool)], [np.ones(1)]

    assert settle(np.zeros(1), attempt, lambda state, solved, changes: state + 1, _key, 7) is None
    assert len(count) == 7


def test_the_ladder_keeps_each_requested_depth_with_the_work_since_the_last():
    """Every requested depth is a load step; the work of the steps between is summed."""
    depths = np.array([1e-4, 2e-4])
    ladder = depth_ladder(1e-5, depths, 1.5)
    assert set(depths.tolist()) <= set(ladder.tolist())
    assert np.all(np.diff(ladder) > 0) and ladder[0] == 1e-5
    kept = walk_ladder(ladder, depths, lambda depth: 2, lambda depth, work: (depth, work))
    first = int(np.searchsorted(ladder, 1e-4)) + 1  # steps up to and with the first depth
    assert kept == [(1e-4, 2 * first), (2e-4, 2 * (ladder.size - first))]
