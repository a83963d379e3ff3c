"""Running one study of any kind: the kind registry (:mod:`.kinds`) picks its runner."""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

from ..validation import InputError
from .kinds import kind_function

__all__ = ["Progress", "run_study"]

Progress = Callable[[str], None]
"""Receives one line of progress."""


def run_study(study: Any, *, quick: bool = False, progress: Progress | None = None) -> Any:
    """Run one study of any kind (its ``kind`` attribute; see :mod:`.kinds`).

    Raises
    ------
    InputError
        An input the FEM refuses only once it runs (e.g. a contact smaller than the mesh
        resolves), prefixed with the study file and the study's name.
    """
    run = kind_function(getattr(study, "kind", "contact"), "run")
    try:
        return run(study, quick, progress)
    except InputError as error:
        where = f"{study.source}: study {study.name!r}"
        raise InputError(f"{where}: {error}", error.parameter) from None
