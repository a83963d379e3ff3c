"""Validity limits: up to which input a model's relative difference stays within a level.

The dynamic study and the validity sweep state where the quasi-static model holds to 1 % and
5 % (:data:`LEVELS`) of the dynamic FE impact. The limit is interpolated linearly between the
computed points where |difference| crosses the level, and it is a conclusion only where the
FEM's own estimated error of the difference (Richardson, :mod:`.dynamic.accuracy`) is below
a fifth of the level (:data:`RESOLUTION`) at the points that decide it: the two points around
the crossing, the smallest input when already it is off, the largest difference when every
point holds. Elsewhere the limit is "not resolved". Pure Python: imported by the sweep kinds.
"""

from __future__ import annotations

from collections.abc import Sequence

__all__ = ["LEVELS", "RESOLUTION", "resolved", "thresholds"]

LEVELS = (0.01, 0.05)
"""Relative differences for which the limit is stated."""
RESOLUTION = 5.0
"""A limit is stated only where the estimated error of the difference is below level / 5."""


def resolved(error: float | None, level: float) -> bool:
    """Whether an estimated absolute error of a difference resolves ``level`` (``None``: no
    estimate, not resolved)."""
    return error is not None and error < level / RESOLUTION


def _crossing(size: list[float], level: float) -> tuple[str, list[int]]:
    """The bound ("none", "interpolated", "all") and the indices of the points deciding it."""
    if size[0] > level:
        return "none", [0]
    for i in range(len(size) - 1):
        if size[i + 1] > level:
            return "interpolated", [i, i + 1]
    return "all", [max(range(len(size)), key=size.__getitem__)]


def thresholds(
    inputs: Sequence[float],
    differences: Sequence[float],
    level: float,
    errors: Sequence[float] | None = None,
) -> dict:
    """Up to which input |difference| <= level, interpolated linearly between the points.

    Parameters
    ----------
    inputs : sequence of float
        The computed points, increasing (e.g. velocities in m/s).
    differences : sequence of float
        Relative differences there (dimensionless; growing in magnitude with the input).
    level : float
        The level, e.g. 0.01.
    errors : sequence of float, optional
        Estimated absolute errors of ``differences`` (same unit); ``None``: no estimate.

    Returns
    -------
    dict
        ``velocity``: the limit (``None`` when already the first point is off; the largest
        input, a lower bound, when every point holds), ``bound``: "interpolated", "all" or
        "none", ``error``: the largest estimated error at the deciding points (``None``
        without estimates), ``resolved``: whether it is below level / :data:`RESOLUTION`, and
        ``velocity_error``: for an interpolated limit, that error carried to the input through
        the slope between the two deciding points (input units; ``None`` otherwise).
    """
    size = [abs(d) for d in differences]
    bound, deciding = _crossing(size, level)
    error = None if errors is None else max(float(errors[i]) for i in deciding)
    velocity, velocity_error = {"none": None, "all": inputs[-1]}.get(bound), None
    if bound == "interpolated":
        i, j = deciding
        slope = (size[j] - size[i]) / (inputs[j] - inputs[i])
        velocity = inputs[i] + (level - size[i]) / slope
        velocity_error = None if error is None else error / slope
    ok = resolved(error, level)
    return {
        "velocity": velocity,
        "bound": bound,
        "error": error,
        "resolved": ok,
        "velocity_error": velocity_error,
    }
