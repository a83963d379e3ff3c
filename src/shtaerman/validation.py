"""Checks of user input, shared by the API and the CLI.

Every check raises :class:`InputError` (a :class:`ValueError`) whose message is one line naming
the parameter, the value given and the valid range; the CLI prints that line and exits with code 2.
"""

from __future__ import annotations

import math
from collections.abc import Sequence

import numpy as np

__all__ = [
    "InputError",
    "validate_increasing",
    "validate_poisson",
    "validate_positive",
]


class InputError(ValueError):
    """A parameter outside its valid range, or a value that is not a number."""


def _as_float(name: str, value: object, valid: str) -> float:
    try:
        number = float(value)  # type: ignore[arg-type]
    except (TypeError, ValueError):
        number = math.nan
    if not math.isfinite(number):
        raise InputError(f"{name} must be a finite number {valid}, got {value!r}")
    return number


def validate_positive(name: str, value: object, unit: str = "") -> float:
    """Return ``value`` as a float, or raise if it is not a finite number > 0."""
    valid = f"> 0 {unit}".rstrip()
    number = _as_float(name, value, valid)
    if number <= 0:
        raise InputError(f"{name} must be {valid}, got {value!r}")
    return number


def validate_poisson(name: str, value: object) -> float:
    """Return a Poisson's ratio, or raise if it lies outside the range (-1, 0.5]."""
    number = _as_float(name, value, "in (-1, 0.5]")
    if not -1.0 < number <= 0.5:
        raise InputError(f"{name} (Poisson's ratio) must lie in (-1, 0.5], got {value!r}")
    return number


def validate_increasing(name: str, values: Sequence[object], unit: str = "") -> np.ndarray:
    """Return positive, strictly increasing numbers as an array, or raise."""
    numbers = np.array([validate_positive(name, v, unit) for v in values], dtype=float)
    if numbers.size == 0:
        raise InputError(f"{name} must list at least one value")
    if np.any(np.diff(numbers) <= 0):
        raise InputError(f"{name} must be strictly increasing, got {list(values)!r}")
    return numbers
