"""A layer (rubber pad on a rigid base) from the public API's keywords, for every model."""

from __future__ import annotations

import dataclasses
from collections.abc import Mapping
from typing import Any, TypeVar

from ..validation import InputError
from ..vocabulary import entry

Settings = TypeVar("Settings")
"""Numerics with ``thickness`` and ``base`` fields (MeshSettings, DynamicSettings)."""

__all__ = ["layer_mesh"]


def layer_mesh(mesh: Settings, options: Mapping[str, Any]) -> Settings:
    """``mesh`` (settings with ``thickness`` and ``base`` fields) on a layer of ``thickness``
    (m) on a ``base`` (None: the half-space), both checked; a finite-strain ``model`` takes a
    bonded base only."""
    if options["thickness"] is None:
        if options["base"] is not None:
            raise InputError("base: applies to a layer only; give its thickness too", "base")
        return mesh
    base = entry("base").check(
        entry("base").default if options["base"] is None else options["base"]
    )
    thickness = entry("thickness").check(options["thickness"])
    if options["model"] != "linear" and base != "bonded":
        from ..fem.finite_contact import FINITE_BASE

        raise InputError(FINITE_BASE, "base")
    return dataclasses.replace(mesh, thickness=thickness, base=base)
