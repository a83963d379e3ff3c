"""Session 67's small fixes found by the adversary's trial (adv67)."""

from shtaerman.sweep.cli import _cases


def test_one_case_is_not_cases():
    # adv67: a one-case sweep reported "sweep s (impact): 1 cases, 1 ok, ..."
    assert [_cases(n) for n in (0, 1, 2)] == ["0 cases", "1 case", "2 cases"]
