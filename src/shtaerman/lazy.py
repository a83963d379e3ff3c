"""Names of a package imported from their modules on first use (PEP 562's module
``__getattr__``), so that importing the package loads none of them."""

from __future__ import annotations

import importlib
import sys
from collections.abc import Callable, Mapping
from typing import Any


def lazy_names(package: str, homes: Mapping[str, tuple[str, ...]]) -> Callable[[str], Any]:
    """A module ``__getattr__`` for ``package`` that imports each name of ``homes`` from its
    module on first use and keeps it in the package's namespace.

    Parameters
    ----------
    package : str
        The package's ``__name__``.
    homes : mapping of str to tuple of str
        Each module (relative to ``package``, e.g. ``".spec"``, ``"..problem"``) and the
        names it provides.
    """
    home_of = {name: home for home, names in homes.items() for name in names}

    def attribute(name: str) -> Any:
        if name not in home_of:
            raise AttributeError(f"module {package!r} has no attribute {name!r}")
        value = getattr(importlib.import_module(home_of[name], package), name)
        vars(sys.modules[package])[name] = value
        return value

    return attribute
