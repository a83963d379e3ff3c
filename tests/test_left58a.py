"""Session 58's leftovers of issue 28 (the same guards and words on every route): the sweep and
verify share one check of the output folder and of a resume, and the public API exports the
error a validity limit raises."""

from __future__ import annotations

import shtaerman as sh
from shtaerman import validation


def test_the_limit_error_is_public_beside_the_input_error():
    assert "LimitError" in sh.__all__ and "InputError" in sh.__all__
    assert sh.LimitError is validation.LimitError and sh.InputError is validation.InputError
    assert issubclass(sh.LimitError, sh.InputError)
