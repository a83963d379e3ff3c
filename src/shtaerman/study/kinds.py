"""Kinds of study: what a study file's ``kind`` key selects (contact, dynamic, finite-strain).

A kind is three functions, found by name so that no module imports another kind's code:

- ``load(path, data) -> list[study]``: check a parsed TOML file of this kind and build its
  studies (each with ``name``, ``description``, ``source`` and ``kind``); raise
  :class:`~shtaerman.study.schema.StudyError` naming file and key.
- ``run(study, quick, progress) -> outcome``: compute one study. The outcome has ``study``,
  ``checks`` (list of :class:`~shtaerman.study.checks.Check`), ``passed``, ``seconds`` and
  ``document()``: its JSON for results.json, with optional display keys ``tables`` (a list of
  ``{"title", "header", "rows"}``, strings, shown by both reports) and ``findings`` (sentences
  for the report's opening section).
- ``write(outcome, folder, root, figure_format) -> (files, figures)`` (in
  :mod:`shtaerman.output`): its files and pictures, as ``{stem: path}`` and ``{caption: path}``
  relative to ``root`` (PNGs; ``figure_format`` "svg" or "pdf" adds vector charts beside them).
"""

from __future__ import annotations

import importlib
from collections.abc import Callable
from typing import Any

from ..validation import InputError

__all__ = ["KINDS", "kind_function"]

KINDS: dict[str, dict[str, str]] = {
    "contact": {
        "load": "shtaerman.study.schema:load_contact",
        "run": "shtaerman.study.run:run_contact_study",
        "write": "shtaerman.output.folder:write_contact_study",
    },
    "dynamic": {
        "load": "shtaerman.study.dynamic:load_dynamic",
        "run": "shtaerman.study.dynamic:run_dynamic_study",
        "write": "shtaerman.output.dynamic:write_dynamic_study",
    },
    "finite-strain": {
        "load": "shtaerman.study.finite:load_finite",
        "run": "shtaerman.study.finite:run_finite_strain_study",
        "write": "shtaerman.output.finite:write_finite_study",
    },
}
"""Kind name -> role -> "module:function"."""


def kind_function(kind: str, role: str) -> Callable[..., Any]:
    """The ``role`` function ("load", "run", "write") of study kind ``kind``."""
    if kind not in KINDS:
        raise InputError(f"Unknown study kind {kind!r}. Pick one of {sorted(KINDS)}")
    module, _, name = KINDS[kind][role].partition(":")
    try:
        return getattr(importlib.import_module(module), name)
    except (ImportError, AttributeError):
        raise InputError(f"study kind {kind!r} is not available in this version") from None
