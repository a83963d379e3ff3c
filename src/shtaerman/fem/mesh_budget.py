"""The setting to blame when an estimated mesh exceeds its limit of unknowns.

Growth alone sets the graded far field, about pi ln(g D / s) / g^2 elements (g the growth, s the
size, D the domain): a growth far below the size's proportion makes the mesh too large at any
refinement. The static and the dynamic meshes, on every route (the CLI, study files, sweeps, the
API), then name the growth and the range that fits, not the limit of unknowns.
"""

from __future__ import annotations

import dataclasses
import math
import sys
from collections.abc import Callable
from typing import Any

from ..validation import InputError, bound_text

__all__ = ["growth_error"]

_SCALED = ("growth", "axis_size", "axis_growth")
"""The settings a refinement divides with the size (besides it)."""
_HALVINGS = 60
"""Bisection steps of ln(growth) between the smallest normal float and 1: the bound to 1e-15."""


def growth_error(
    settings: Any,
    estimate: Callable[[Any], float],
    limit: float,
    coarsest_size: float,
    also: str = "",
) -> InputError | None:
    """An InputError naming ``growth`` and the range that fits, when the growth alone makes the
    mesh of ``settings`` (a dataclass with ``size`` and ``growth``) exceed ``limit`` unknowns;
    None when a uniform coarsening (size and growth scaled together up to ``coarsest_size``,
    as a lower refine does) brings it within, or when no growth in (0, 1] can (another
    setting is at fault).

    ``estimate`` maps settings to their estimated unknowns (non-increasing in the growth);
    ``also`` ends the message with another remedy (``"; or raise --max-dofs"``).
    """

    def fits(**changed: float) -> bool:
        return estimate(dataclasses.replace(settings, **changed)) <= limit

    coarser = coarsest_size / settings.size  # the coarsest uniform coarsening (refine < 1)
    scaled = {f.name for f in dataclasses.fields(settings)} & set(_SCALED)
    coarsest = {name: min(getattr(settings, name) * coarser, 1.0) for name in scaled}
    if fits(**coarsest, size=coarsest_size) or not fits(growth=1.0):
        return None  # the mesh is uniformly too fine, or growth is not alone at fault
    low, high = math.log(sys.float_info.min), 0.0  # ln(growth): too many unknowns, within
    for _ in range(_HALVINGS):
        middle = 0.5 * (low + high)
        low, high = (low, middle) if fits(growth=math.exp(middle)) else (middle, high)
    least = bound_text(math.exp(high), "low")
    return InputError(
        f"growth: must lie in [{least}, 1] for a mesh within {limit:.3g} unknowns at size "
        f"{settings.size:.3g}, got {settings.growth:.3g} (the mesh's, after --refine divides "
        f"--growth; about {estimate(settings):.3g} unknowns; a coarser --mesh-size cannot "
        f"make up for it: raise --growth or lower --refine){also}",
        "growth",
    )
