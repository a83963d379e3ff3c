"""A layer (rubber pad on a rigid base) of a problem, in the numerical settings of every model."""

from __future__ import annotations

import dataclasses
from typing import TypeVar

from ..problem import Geometry

Settings = TypeVar("Settings")
"""Numerics with ``thickness`` and ``base`` fields (MeshSettings)."""

__all__ = ["layer_mesh"]


def layer_mesh(mesh: Settings, geometry: Geometry) -> Settings:
    """``mesh`` (settings with ``thickness`` and ``base`` fields) on the problem's layer (or
    unchanged on the half-space); the geometry was checked when the problem was built."""
    if geometry.thickness is None:
        return mesh
    return dataclasses.replace(mesh, thickness=geometry.thickness, base=geometry.base)
