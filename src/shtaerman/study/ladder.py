"""The refinement ladder every error estimate climbs: three levels K/2, K/sqrt(2), K."""

from __future__ import annotations

import math

from ..fem.mesh import MeshSettings
from ..validation import InputError

__all__ = ["LADDER_RATIO", "check_ladder", "ladder_factors"]

LADDER_RATIO = math.sqrt(2.0)
"""Element-size ratio of consecutive ladder levels (dofs ratio about 2)."""


def check_ladder(
    mesh: MeshSettings, refine: float = 1.0, refined_radius: float | None = None
) -> None:
    """Raise InputError unless every level of the ladder ending at ``refine`` is a valid
    mesh: the coarsest, refine / 2, must keep every size and growth of ``mesh`` <= 1, and the
    finest must pass the size guard (``max_dofs``) before the coarse levels cost anything
    (a layer's guard needs the ``refined_radius`` in m, see
    :meth:`~shtaerman.fem.mesh.MeshSettings.check_size`)."""
    smallest = LADDER_RATIO**2 * max(mesh.size, mesh.axis_size, mesh.growth, mesh.axis_growth)
    if not refine >= smallest * (1.0 - 1e-12):
        raise InputError(
            f"refine must be >= {smallest:.3g} with these mesh settings (the error-estimate "
            f"ladder's coarsest mesh, refine / 2, keeps every size and growth <= 1), got "
            f"{refine!r}"
        )
    mesh.refined(refine).check_size(refined_radius)


def ladder_factors(refine: float) -> list[float]:
    """Refinement factors of the three levels whose finest is ``refine``: K/2, K/sqrt(2), K."""
    return [refine / LADDER_RATIO**2, refine / LADDER_RATIO, refine]
