"""Whether a case is the paper's worked example (so that its text may name the paper)."""

from __future__ import annotations

import math
from collections.abc import Mapping

from .printed import load_printed

__all__ = ["PAPER_EXPONENT", "is_paper_case", "paper_case"]

PAPER_EXPONENT = 1.5
"""The exponent n of the paper's indenter z = A r^n (its A is in m^-1/2)."""
KEYS = {"shape_coefficient": "A", "E2": "E2", "nu2": "nu2", "mass": "M", "velocity": "v0"}
"""Input key (results.json ``inputs``) -> the paper example's symbol."""


def paper_case() -> dict[str, float]:
    """The paper's example by the inputs' keys: shape_coefficient (m^-1/2), exponent, E2 (Pa),
    nu2, mass (kg), velocity (m/s)."""
    printed = load_printed()["example"]["inputs"]
    return {"exponent": PAPER_EXPONENT} | {key: printed[s]["value"] for key, s in KEYS.items()}


def is_paper_case(inputs: Mapping[str, object]) -> bool:
    """Whether ``inputs`` (keys of :func:`paper_case`; others ignored) are the paper's example
    to 1e-9 relative; a missing key is not the paper's."""
    return all(
        isinstance(inputs.get(key), int | float)
        and math.isclose(float(inputs[key]), value, rel_tol=1e-9)
        for key, value in paper_case().items()
    )
