"""The refinement ladders the error estimates climb: three gmsh levels K/2, K/sqrt(2), K, or
a nested ladder (one gmsh mesh refined uniformly once and twice, element-size ratio 2)."""

from __future__ import annotations

import math
from dataclasses import dataclass, fields

from skfem import MeshTri

from ..fem.mesh import HALF_SPACE, Geometry, MeshSettings
from ..validation import InputError

__all__ = [
    "LADDER_RATIO",
    "NESTED_LEVELS",
    "NESTED_RATIO",
    "NestedMeshSettings",
    "check_ladder",
    "ladder_factors",
    "nested_factors",
    "nested_ladder",
]

LADDER_RATIO = math.sqrt(2.0)
"""Element-size ratio of consecutive ladder levels (dofs ratio about 2)."""


def check_ladder(
    mesh: MeshSettings,
    refine: float = 1.0,
    refined_radius: float | None = None,
    geometry: Geometry = HALF_SPACE,
    *,
    estimate: bool = True,
    sized: bool = True,
    advice: str = "",
) -> None:
    """Raise InputError unless every level of the ladder ending at ``refine`` (only that level
    without ``estimate``) is a valid mesh: the coarsest, refine / 2, must keep every size and
    growth of ``mesh`` <= 1, and (``sized``) the finest must pass the size guard
    (``max_dofs``) before the coarse levels cost anything (the guard of the layer of
    ``geometry`` needs the ``refined_radius`` in m, see
    :meth:`~shtaerman.fem.mesh.MeshSettings.check_size`);
    ``advice`` ends the refusal."""
    ratio = LADDER_RATIO**2 if estimate else 1.0
    smallest = ratio * max(mesh.size, mesh.axis_size, mesh.growth, mesh.axis_growth)
    if not refine >= smallest * (1.0 - 1e-12):
        coarsest = "the error-estimate ladder's coarsest mesh, refine / 2," if estimate else "it"
        raise InputError(
            f"refine must be >= {smallest:.3g} with these mesh settings ({coarsest} keeps every "
            f"size and growth <= 1), got {refine!r}{advice}",
            "refine",
        )
    if sized:
        mesh.refined(refine).check_size(refined_radius, geometry)


WITHOUT_ESTIMATE = "; or run without the estimate (estimate=False)"
"""The advice that ends a refusal of the error-estimate ladder."""


def ladder_factors(refine: float) -> list[float]:
    """Refinement factors of the three levels whose finest is ``refine``: K/2, K/sqrt(2), K."""
    return [refine / LADDER_RATIO**2, refine / LADDER_RATIO, refine]


NESTED_RATIO = 2.0
"""Element-size ratio of consecutive nested levels (one uniform refinement: dofs ratio 4)."""
NESTED_LEVELS = 3
"""Levels of a nested ladder: the coarse gmsh mesh and its two uniform refinements."""


@dataclass(frozen=True)
class NestedMeshSettings(MeshSettings):
    """Mesh settings whose gmsh mesh is then refined uniformly ``nested`` times.

    Each refinement splits every triangle into four (scikit-fem's ``refined``): the element
    size halves everywhere, the coarse vertices stay (first, in their order), boundaries and
    the refined radius' vertex are kept, and the Taylor-Hood spaces of consecutive levels are
    nested. ``nested = 0`` builds the same mesh as :class:`MeshSettings`.

    Attributes
    ----------
    nested : int
        Uniform refinements after meshing (>= 0).
    """

    nested: int = 0

    def __post_init__(self) -> None:
        super().__post_init__()
        whole = isinstance(self.nested, int) and not isinstance(self.nested, bool)
        if not (whole and 0 <= self.nested <= 4):
            raise InputError(f"nested must be an integer in [0, 4], got {self.nested!r}")

    @property
    def estimated_dofs(self) -> int:
        """Unknowns estimated before meshing: the gmsh mesh's times 4 per refinement."""
        return round(MeshSettings(**_fields(self)).estimated_dofs * 4**self.nested)

    def build(self, refined_radius: float, geometry: Geometry = HALF_SPACE) -> MeshTri:
        """The gmsh mesh of :meth:`MeshSettings.build`, refined uniformly ``nested`` times
        (the size guard counts the refined mesh)."""
        mesh = super().build(refined_radius, geometry)
        for _ in range(self.nested):
            mesh = mesh.refined()
        return mesh


def _fields(settings: MeshSettings) -> dict[str, object]:
    return {f.name: getattr(settings, f.name) for f in fields(MeshSettings)}


def nested_ladder(mesh: MeshSettings) -> list[NestedMeshSettings]:
    """The nested ladder whose middle level has the size field of ``mesh``: one gmsh mesh
    with ``mesh``'s sizes doubled (refine / 2), and its first and second uniform refinements
    (sizes / 2 per level, :data:`NESTED_RATIO`). Every level and the finest's size guard
    are checked before any meshing.

    Raises
    ------
    shtaerman.validation.InputError
        If the coarse level coarsens a size or growth beyond 1, or the finest level
        exceeds ``max_dofs``.
    """
    coarse = _fields(mesh.refined(1.0 / NESTED_RATIO))
    levels = [NestedMeshSettings(**coarse, nested=k) for k in range(NESTED_LEVELS)]
    levels[-1].check_size()
    return levels


def nested_factors(refine: float = 1.0) -> list[float]:
    """Equivalent refinement factors of :func:`nested_ladder`'s levels: refine / 2, refine,
    2 refine."""
    return [refine * NESTED_RATIO ** (k - 1) for k in range(NESTED_LEVELS)]
