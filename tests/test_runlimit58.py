"""A validity limit a sweep case meets while it runs is a "refused" row, as one met at the
file's load is (issue 28, item 4): sweep/engine.py ``execute_case``, the one place a case's
outcome becomes its status. Before, the row was "failed" with "LimitError: ..." in its error
(the CLI's words), which made the sweep exit 1 for a case outside the model's validity."""

from __future__ import annotations

from pathlib import Path

from shtaerman.sweep.engine import SweepOutcome, execute_case
from shtaerman.sweep.kinds import CaseResult
from shtaerman.validation import InputError, LimitError

SAID = "velocity, density2: 0.7 kg at 50 m/s ...: velocity 26.1 m/s would pass"
"""A wave-speed refusal as raised, in Python's words (the CLI spells them as options:
tests/test_sweeprow57.py pins the real one); a sweep's row keeps the file's keys."""


def _raising(error: Exception):
    def case(params: dict) -> CaseResult:
        raise error

    return case


def test_a_limit_met_in_the_run_is_refused_in_the_files_words():
    row = execute_case(_raising(LimitError(SAID, "velocity")), 3, {"velocity": 50.0})
    assert row["status"] == "refused" and row["outputs"] == {}
    assert row["error"] == SAID  # the file's keys, as the load's refusal says them (no type)
    assert row["index"] == 3


def test_any_other_error_or_a_failed_check_is_still_failed():
    row = execute_case(_raising(InputError("--mass must be > 0 kg, got -1", "mass")), 0, {})
    assert row["status"] == "failed" and row["error"].startswith("InputError: ")
    row = execute_case(lambda p: CaseResult({"x": 1.0}, ("balance 0.3 > 0.01",), ""), 0, {})
    assert row["status"] == "failed" and row["error"] == "check failed: balance 0.3 > 0.01"
    assert row["outputs"] == {"x": 1.0}  # a case that ran keeps its outputs
    row = execute_case(lambda p: CaseResult({"x": 1.0}, (), ""), 0, {})
    assert row["status"] == "ok" and row["error"] is None


def test_a_sweep_whose_every_case_is_refused_exits_2_however_they_were_refused():
    def outcome(ok: int, failed: int, refused: int) -> SweepOutcome:
        total = ok + failed + refused
        return SweepOutcome(Path("."), total, ok, failed, 0, total, 0, 1.0, 1, refused=refused)

    assert outcome(0, 0, 3).exit_code == 2  # the CHANGELOG's policy: "2 when every case is refused"
    assert outcome(2, 0, 1).exit_code == 0 and outcome(1, 1, 1).exit_code == 1
    assert outcome(3, 0, 0).exit_code == 0
