"""A layer (rubber pad on a rigid base) from the public API's keywords, for every model."""

from __future__ import annotations

import dataclasses
from collections.abc import Mapping
from typing import TYPE_CHECKING, Any

from ..validation import InputError
from ..vocabulary import entry

if TYPE_CHECKING:
    from ..fem.mesh import MeshSettings

__all__ = ["layer_mesh"]


def layer_mesh(mesh: MeshSettings, options: Mapping[str, Any]) -> MeshSettings:
    """``mesh`` on a layer of ``thickness`` (m) on a ``base`` (None: the half-space)."""
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
