"""The one registry of kinds (contact, dynamic, finite-strain, impact), for ``verify`` and sweeps.

A :class:`Kind` names what a study file's or a sweep file's ``kind`` selects. Its study roles are
three functions, found by name so that no module imports another kind's code (or a layer above):

- ``load(path, data) -> list[study]``: check a parsed TOML file of this kind and build its
  studies (each with ``name``, ``description``, ``source`` and ``kind``); raise
  :class:`~shtaerman.study.schema.StudyError` naming file and key.
- ``run(study, quick, progress) -> outcome``: compute one study. The outcome has ``study``,
  ``checks`` (list of :class:`~shtaerman.study.checks.Check`), ``passed``, ``seconds`` and
  ``document()``: its JSON for results.json.
- ``write(outcome, folder, root, figure_format) -> (files, figures)`` (in
  :mod:`shtaerman.output`): its files and pictures, as ``{stem: path}`` and ``{caption: path}``
  relative to ``root`` (PNGs; ``figure_format`` "svg" or "pdf" adds vector charts beside them).

Its sweep roles (``parameters``, ``outputs``, ``case``, ...) are registered by
:mod:`shtaerman.sweep.kinds` with :func:`register_kind`, into the same entry.
"""

from __future__ import annotations

import dataclasses
import importlib
from collections.abc import Callable, Mapping
from dataclasses import dataclass, field
from typing import Any

from ..validation import InputError
from ..vocabulary import inputs_of

__all__ = [
    "KINDS",
    "Kind",
    "KindNotAvailableError",
    "Parameter",
    "get_kind",
    "kind_function",
    "register_kind",
    "vocabulary_parameters",
]

CaseFunction = Callable[[dict[str, Any]], Mapping[str, float]]


@dataclass(frozen=True)
class Parameter:
    """One sweep input of a kind.

    Attributes
    ----------
    default : object
        The value when the sweep file does not set it; ``None`` means "computed from the other
        inputs" (e.g. the contact depths).
    unit : str
        SI unit for messages and headers ("" for a pure number).
    type : {"float", "int", "str", "floats", "bool"}
        What the TOML value must be.
    choices : tuple of str, optional
        Allowed strings for ``type="str"``.
    """

    default: Any
    unit: str = ""
    type: str = "float"
    choices: tuple[str, ...] = ()


@dataclass(frozen=True)
class Kind:
    """A computation: its study-file roles and its sweep roles (either may be absent)."""

    name: str
    description: str
    parameters: Mapping[str, Parameter] = field(default_factory=dict)
    outputs: Mapping[str, str] = field(default_factory=dict)
    """Sweep output name -> SI unit ("" for a pure number)."""
    case: CaseFunction | None = None
    check: Callable[[dict[str, Any]], object] | None = None
    unavailable: str | None = None
    """Why the kind cannot run yet (``None`` when it can)."""
    nondeterministic: tuple[str, ...] = field(default=())
    """Outputs that vary from run to run (timings); everything else is reproducible."""
    optional_outputs: Mapping[str, Mapping[str, str]] = field(default_factory=dict)
    """Outputs the case adds when a ``bool`` parameter is true: parameter -> {output: unit}."""
    levels: Mapping[str, tuple[float, ...]] = field(default_factory=dict)
    """Relative differences (output -> levels of its magnitude) whose heat maps draw the levels
    as contours where the output's estimated error ``error_<name>`` resolves them."""
    categories: Mapping[str, tuple[str, ...]] = field(default_factory=dict)
    """Outputs that are an index into a list of names (output -> the names): the figures show
    the names, results.json lists them."""
    load: str | None = None
    """``"module:function"`` reading a study file of this kind (``None``: no study files)."""
    run: str | None = None
    write: str | None = None

    def defaults(self) -> dict[str, Any]:
        """The default value of every sweep parameter."""
        return {name: p.default for name, p in self.parameters.items()}

    def outputs_for(self, flags: Mapping[str, Any]) -> dict[str, str]:
        """:attr:`outputs` and the optional outputs of the flags that are true."""
        extra = [
            outputs for flag, outputs in self.optional_outputs.items() if flags.get(flag, False)
        ]
        return {**self.outputs, **{k: v for outputs in extra for k, v in outputs.items()}}


class KindNotAvailableError(InputError):
    """A registered kind whose computation is not in this version yet."""


KINDS: dict[str, Kind] = {}
"""Every registered kind by name."""


def register_kind(kind: Kind) -> Kind:
    """Add a kind to :data:`KINDS`; for a name already registered, set the roles ``kind``
    gives (the study roles and the sweep roles are registered by their own layers). Returns
    the entry."""
    old = KINDS.get(kind.name)
    if old is not None:
        given = {
            item.name: getattr(kind, item.name)
            for item in dataclasses.fields(kind)
            if getattr(kind, item.name) not in (None, "", (), {})
        }
        kind = dataclasses.replace(old, **given)
    KINDS[kind.name] = kind
    return kind


def get_kind(name: str) -> Kind:
    """The kind called ``name``; raises :class:`InputError` for an unknown or unavailable one."""
    if name not in KINDS:
        raise InputError(f"Unknown kind {name!r}. Pick one of {sorted(KINDS)}")
    kind = KINDS[name]
    if kind.unavailable:
        raise KindNotAvailableError(f"kind {name!r} is not available yet: {kind.unavailable}")
    return kind


def study_kinds() -> list[str]:
    """The kinds a study file can name (those with a loader)."""
    return sorted(name for name, kind in KINDS.items() if kind.load)


def kind_function(kind: str, role: str) -> Callable[..., Any]:
    """The ``role`` function ("load", "run", "write") of study kind ``kind``."""
    if kind not in KINDS or getattr(KINDS[kind], role) is None:
        raise InputError(f"Unknown study kind {kind!r}. Pick one of {study_kinds()}")
    module, _, name = getattr(KINDS[kind], role).partition(":")
    try:
        return getattr(importlib.import_module(module), name)
    except (ImportError, AttributeError):
        raise InputError(f"study kind {kind!r} is not available in this version") from None


def vocabulary_parameters(kind: str) -> dict[str, Parameter]:
    """The sweep parameters of ``kind`` from :mod:`shtaerman.vocabulary` (defaults by kind)."""
    return {
        name: Parameter(item.sweep_default_for(kind), item.unit, item.type, item.choices)
        for name, item in inputs_of(kind).items()
    }


for kind in (
    Kind(
        "contact",
        "linear FEM frictionless contact against Shtaerman's exact solution",
        load="shtaerman.study.contact.loader:load_contact",
        run="shtaerman.study.contact.runner:run_contact_study",
        write="shtaerman.output.folder:write_contact_study",
    ),
    Kind(
        "dynamic",
        "dynamic FE impact (elastic waves) against the quasi-static impact",
        load="shtaerman.study.dynamic.loader:load_dynamic",
        run="shtaerman.study.dynamic.runner:run_dynamic_study",
        write="shtaerman.output.dynamic:write_dynamic_study",
    ),
    Kind(
        "finite-strain",
        "rubber finite-strain contact against Shtaerman, and the impact on it",
        load="shtaerman.study.finite.loader:load_finite",
        run="shtaerman.study.finite.runner:run_finite_strain_study",
        write="shtaerman.output.finite:write_finite_study",
    ),
    Kind(
        "effects",
        "the effect table of an impact: which effect moves P_max, x_max, t_contact and e",
        # the table is the API's (sh.effects); named here, imported only when a study runs
        load="shtaerman.api.effect_table.study:load_effects",
        run="shtaerman.api.effect_table.study:run_effects",
        write="shtaerman.api.effect_table.study:write_effects",
    ),
):
    register_kind(kind)
del kind  # the loop variable: not a name of this module
