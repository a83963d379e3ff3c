"""The edges of the dynamic body: the absorbing layer, and a layer's mesh and lateral absorber.

The absorbing layer (:class:`AbsorbingLayer`, Semblat, Lenti and Gandomzadeh 2011) is
mass-proportional damping -rho zeta(R) v growing with distance from the radius R_a; optional on
the half-space (``DynamicSettings.layer_rate``), always present on a layer of thickness H on a
rigid base (zeta_max t_y = ``layer_rate``, or ``LATERAL_RATE`` when it is 0), whose mesh keeps
at least ``LAYER_ELEMENTS`` elements through the thickness at the contact and whose edge lies
beyond the absorber and at least ``LAYER_EXTENT`` thicknesses out (no absorber beyond
``MAX_LATERAL`` thicknesses). The shapes, the placement of R_a and why:
benchmarks/FEM_NOTES.md, "Moved from the docstrings", fem/dynamic_layer.py."""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass
from typing import Protocol

import numpy as np
from skfem import MeshTri

from ..validation import InputError
from .mesh import (
    DOFS_PER_ELEMENT,
    LAYER_EXTENT,
    Geometry,
    check_thickness_range,
    layer_mesh,
    layer_triangles,
)


class DynamicSettings(Protocol):
    """The fields of :class:`.dynamic_contact.DynamicSettings` a layer reads."""

    size: float
    growth: float
    axis_size: float
    layer_start: float
    layer_ramp: float
    layer_rate: float
    layer_width: float | None


__all__ = [
    "LATERAL_RATE",
    "MAX_LATERAL",
    "AbsorbingLayer",
    "check_layer_rate",
    "lateral_absorber",
    "layer_dofs",
    "layer_impact_mesh",
]

LAYER_ELEMENTS = 8.0
"""Elements through the thickness at the contact at the default size."""
LAYER_LARGEST_SIZE = 4.0
"""Largest element size over the size through the thickness at the contact."""
LATERAL_RATE = 10.0
"""Peak damping rate zeta_max t_y of a layer's lateral absorber when ``layer_rate`` is 0."""
MAX_LATERAL = 3000.0
"""Farthest edge of the lateral absorber, in thicknesses (beyond it: no absorber)."""
_SIZE = 1.0 / 40.0
"""The dynamic default mesh size (``DynamicSettings.size``), at which the layer has
``LAYER_ELEMENTS`` elements through its thickness at the contact."""
_AXIS_GROWTH = 0.1
"""Growth of the element size from the axis (as on the dynamic half-space)."""


@dataclass(frozen=True)
class AbsorbingLayer:
    """Damping profile of the absorbing layer (SI units).

    Attributes
    ----------
    start : float
        R_a in m: the damping is zero inside R < R_a.
    ramp : float
        L in m: zeta rises as ((R - R_a)/L)^2 over R_a <= R <= R_a + L.
    rate : float
        zeta_max in 1/s, the plateau (or bump peak) damping rate.
    width : float or None
        W in m: a bump zeta = zeta_max sin^2(pi (R - R_a) / W) on R_a < R < R_a + W, zero
        beyond; None: the ramp-plateau profile.
    lateral : bool
        True: R is the radius r alone (the lateral absorber of a layer on a rigid base, whose
        base reflects); False: R = sqrt(r^2 + z^2).
    """

    start: float
    ramp: float
    rate: float
    width: float | None = None
    lateral: bool = False

    def damping_rate(self, r: np.ndarray, z: np.ndarray) -> np.ndarray:
        """zeta(R) in 1/s at points (r, z) in m."""
        distance = np.abs(r) if self.lateral else np.hypot(r, z)
        phase = np.clip((distance - self.start) / self.ramp, 0.0, 1.0)
        if self.width is None:
            return self.rate * phase**2
        inside = (distance > self.start) & (distance < self.start + self.width)
        return np.where(
            inside, self.rate * np.sin(np.pi * (distance - self.start) / self.width) ** 2, 0.0
        )

    def weight(self, density: float) -> Callable[[np.ndarray, np.ndarray], np.ndarray]:
        """rho zeta(R) in kg/(m^3 s), the weight of the damping matrix."""
        return lambda r, z: density * self.damping_rate(r, z)


def check_layer_rate(layer_rate: float | None, thickness: float | None) -> None:
    """Raise InputError for ``layer_rate`` 0 on a layer (``thickness`` in m, None: the
    half-space), where it cannot mean "no absorber": None is the geometry's own rate."""
    if layer_rate == 0 and thickness is not None:
        raise InputError(
            "layer_rate: a layer always has its lateral absorber (its guided waves would "
            "reflect at its edge), 0 is for the half-space only: give a rate in (0, 1e4] or "
            f"leave the default ({LATERAL_RATE:g} on a layer)",
            "layer_rate",
        )


def lateral_absorber(
    settings: DynamicSettings,
    thickness: float,
    shear_wave_speed: float,
    t_y: float,
    refined: float,
) -> tuple[AbsorbingLayer, float, bool]:
    """The lateral absorber of a layer of ``thickness`` m, its edge radius L in m and whether
    it is on; ``shear_wave_speed`` in m/s, ``t_y`` the quasi-static impact duration in s,
    ``refined`` the refined radius in m.
    """
    scale = shear_wave_speed * t_y
    rate = settings.layer_rate if settings.layer_rate > 0 else LATERAL_RATE
    width = None if settings.layer_width is None else settings.layer_width * scale
    layer = AbsorbingLayer(
        start=settings.layer_start * scale,
        ramp=settings.layer_ramp * scale,
        rate=rate / t_y,
        width=width,
        lateral=True,
    )
    end = layer.start + (2.0 * layer.ramp if width is None else width)
    static = refined + LAYER_EXTENT * thickness
    if end > MAX_LATERAL * thickness:
        return layer, static, False
    return layer, max(static, end), True


def _thickness_size(settings: DynamicSettings, thickness: float) -> float:
    """Element size through ``thickness`` m at the contact, m."""
    return thickness / LAYER_ELEMENTS * settings.size / _SIZE


def layer_dofs(settings: DynamicSettings, thickness: float, refined: float, extent: float) -> int:
    """Unknowns of the layer mesh estimated before meshing: a quadrature of Int dA / h^2 over
    the rectangle, as :func:`.mesh.estimate_elements` (within about 30 %).

    Raises
    ------
    shtaerman.validation.InputError
        If the thickness lies outside ``MIN_THICKNESS`` to ``MAX_THICKNESS`` refined radii.
    """
    check_thickness_range(thickness, refined, "for this impact")
    cap = _thickness_size(settings, thickness) / refined
    elements = layer_triangles(thickness / refined, extent / refined, cap, settings, _AXIS_GROWTH)
    return round(DOFS_PER_ELEMENT * float(elements))


def layer_impact_mesh(
    settings: DynamicSettings, layer: Geometry, refined: float, extent: float
) -> MeshTri:
    """The mesh of the dynamic impact on ``layer`` (a Geometry with a thickness; ``refined``
    and ``extent`` in m), its thickness and size checked before
    (:func:`.dynamic_contact.check_dynamic_impact`)."""
    thickness = layer.thickness
    assert thickness is not None
    return layer_mesh(
        refined,
        thickness,
        lateral_extent=extent,
        smallest_size=settings.size * refined,
        growth=settings.growth,
        axis_size=min(settings.axis_size, settings.size) * refined,
        axis_growth=_AXIS_GROWTH,
        thickness_size=_thickness_size(settings, thickness),
        largest_size=LAYER_LARGEST_SIZE * _thickness_size(settings, thickness),
        bonded=layer.base == "bonded",
    )
