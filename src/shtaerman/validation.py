"""Checks of user input, shared by the API and the CLI.

Every check raises :class:`InputError` (a :class:`ValueError`) whose message is one line naming
the parameter, the value given and the valid range; the CLI prints that line and exits with code 2.
"""

from __future__ import annotations

import math
import os
import re
import sys
from decimal import ROUND_HALF_EVEN, Decimal

import numpy as np

__all__ = [
    "InputError",
    "LimitError",
    "NumericalFailureError",
    "bound_text",
    "caller_stacklevel",
    "plain_float",
    "shown",
    "validate_poisson",
    "validate_positive",
]


class InputError(ValueError):
    """A parameter outside its valid range, or a value that is not a number.

    Attributes
    ----------
    parameter : str or None
        The name of the parameter at fault, where the check knows it (e.g. ``"E2"``).
    """

    def __init__(self, message: str, parameter: str | None = None) -> None:
        super().__init__(_abbreviated(message))
        self.parameter = parameter


class LimitError(InputError):
    """Valid inputs whose case lies beyond a validity limit of the model (the depth's reach
    x/a, the striker's speed against the body's waves, a sphere's equator, a table's last
    row): the physics of this case, not a typo. A single run refuses it as any
    :class:`InputError` (the CLI exits 2, in the same words); a sweep records its case as
    "refused" and runs the others (:mod:`shtaerman.sweep.spec`)."""


SHOWN_ITEMS = 4
"""A message shows this many items of a longer list, then how many it holds."""
SHOWN_CHARACTERS = 200
"""A message shows at most this many characters of a value."""
_FLAT_LIST = re.compile(r"\[([^\[\]'\"]*)\]")
_LONG_QUOTED = re.compile(rf"(?<!\w)'[^'\n]{{{SHOWN_CHARACTERS + 1},}}'(?!\w)")
"""A quoted text too long to show whole; its quotes not within a word, so that two
apostrophes of prose ("the body's ... the fit's") are no quoted text."""


SQUARABLE_VELOCITY = 2.0 * math.sqrt(sys.float_info.min)
"""Smallest velocity in m/s a refusal names where v0^2 must be a normal float: its square is 4
times the smallest (2.98e-154 m/s; the FE impact and the profile impact's clock take v0^2)."""


def shown(value: object) -> str:
    """``repr(value)`` for a message, short: a list, tuple or array of more than
    :data:`SHOWN_ITEMS` + 1 values shows its first ones and its length (``[1, 2, 3, 4, ...
    (100000 values)]``); any other long text is cut at :data:`SHOWN_CHARACTERS`."""
    listed = isinstance(value, list | tuple) or (isinstance(value, np.ndarray) and value.ndim)
    if listed and len(value) > SHOWN_ITEMS + 1:  # type: ignore[arg-type]
        head = ", ".join(shown(item) for item in list(value[:SHOWN_ITEMS]))
        return f"[{head}, ... ({len(value)} values)]"
    text = repr(value)
    if len(text) > SHOWN_CHARACTERS:  # a text's own length, not its repr's (4 for a NUL)
        count = len(value) if isinstance(value, str) else len(text)
        return f"{text[:SHOWN_CHARACTERS]}... ({count} characters)"
    return text


def bound_text(value: float, side: str, digits: int = 3) -> str:
    """A range end ``value`` for a message, at ``digits`` significant digits rounded inward:
    up for a lower end (``side="low"``), down for an upper end (``side="high"``).

    The one rule of every printed range: a number typed as printed inside a range (or on its
    closed end) is accepted by the check the range describes, and a refused number is never
    printed as inside it.
    """
    if not math.isfinite(value) or value == 0:
        return f"{value:.{digits}g}"
    exact = Decimal(value)
    quantum = Decimal(1).scaleb(exact.adjusted() - digits + 1)
    near = exact.quantize(quantum, rounding=ROUND_HALF_EVEN)
    if side == "low" and float(near) < value:
        near += quantum
    elif side == "high" and float(near) > value:
        near -= quantum
    return f"{float(near):.{digits}g}"


def _abbreviated(message: str) -> str:
    """``message`` with every long flat list and long quoted text written in it shortened as
    :func:`shown` does, whoever formatted it."""

    def short(match: re.Match[str]) -> str:
        items = match[1].split(", ")
        if len(items) <= SHOWN_ITEMS + 1:
            return match[0]
        return f"[{', '.join(items[:SHOWN_ITEMS])}, ... ({len(items)} values)]"

    def cut(match: re.Match[str]) -> str:  # a long quoted text: a pasted file, a typo'd list
        inside = match[0][1:-1]  # cut to SHOWN_CHARACTERS with "...": not cut again
        count = len(_ESCAPE.sub("_", inside))  # an escape of a repr (\x00) is 1 character
        return f"'{inside[: SHOWN_CHARACTERS - 3]}...' ({count} characters)"

    return _LONG_QUOTED.sub(cut, _FLAT_LIST.sub(short, message))


_ESCAPE = re.compile(r"\\(?:x[0-9a-f]{2}|u[0-9a-f]{4}|U[0-9a-f]{8}|.)")
"""One escape sequence of a ``repr``: the one character it stands for."""

_PACKAGE = os.path.dirname(os.path.abspath(__file__)) + os.sep


def caller_stacklevel() -> int:
    """The ``stacklevel`` for :func:`warnings.warn`, called in the function that calls this
    one, that makes the warning name the first frame outside this package: the user's line
    that called ``sh.*`` (or the command line's entry point), whatever the depth of the call
    inside the package (``warnings.warn(skip_file_prefixes=...)`` from Python 3.12)."""
    frame = sys._getframe(1)
    level = 1
    while frame is not None and frame.f_code.co_filename.startswith(_PACKAGE):
        frame = frame.f_back
        level += 1
    return level


class NumericalFailureError(RuntimeError):
    """A computation whose own checks failed on valid input (an unstable time stepping, a
    solver that did not converge); the message says what to change. The CLI exits with 1."""


def plain_float(text: str) -> float:
    """``float(text)`` for a number written in ASCII without ``_`` (``1e3``, ``-0.5``, ``inf``,
    ``nan``): a typed ``1_000`` or ``\u0661`` (an Arabic-Indic one), which Python's float reads,
    raises ValueError, as any text that is no number does."""
    if not text.isascii() or "_" in text:
        raise ValueError(f"not a number written in ASCII digits: {text!r}")
    return float(text)


def _as_float(name: str, value: object, valid: str) -> float:
    if isinstance(value, bool | np.bool_):  # True == 1, but a flag is no quantity
        raise InputError(f"{name} must be a finite number {valid}, got {shown(value)}", name)
    if isinstance(value, str | bytes | np.str_):  # numpy would not convert it where it is used
        raise InputError(
            f"{name} must be a finite number {valid}, not a string: got {shown(value)}", name
        )
    try:
        number = float(value)  # type: ignore[arg-type]
    except (TypeError, ValueError, OverflowError):
        number = math.nan
    if not math.isfinite(number):
        raise InputError(f"{name} must be a finite number {valid}, got {shown(value)}", name)
    return number


def validate_positive(name: str, value: object, unit: str = "") -> float:
    """Return ``value`` as a float, or raise if it is not a finite number > 0."""
    valid = f"> 0 {unit}".rstrip()
    number = _as_float(name, value, valid)
    if number <= 0:
        raise InputError(f"{name} must be {valid}, got {shown(value)}", name)
    if number < sys.float_info.min:  # subnormal: the number itself has lost its digits
        raise InputError(
            f"{name} must be {valid} and at least {bound_text(sys.float_info.min, 'low', 4)} (the "
            f"smallest normal float), got {shown(value)}",
            name,
        )
    return number


def validate_poisson(name: str, value: object, low: float = -1.0) -> float:
    """Return a Poisson's ratio, or raise if it lies outside its range.

    The one check of Poisson's ratio. The thermodynamic range is (-1, 0.5] (``low = -1``,
    open at -1); a narrower range [low, 0.5] applies where a method was validated only there
    (the FEM contact: ``low = 0``).
    """
    valid = "(-1, 0.5]" if low == -1.0 else f"[{low:g}, 0.5]"
    number = _as_float(name, value, f"in {valid}")
    inside = -1.0 < number <= 0.5 if low == -1.0 else low <= number <= 0.5
    if not inside:
        raise InputError(f"{name} (Poisson's ratio) must lie in {valid}, got {shown(value)}", name)
    return number
