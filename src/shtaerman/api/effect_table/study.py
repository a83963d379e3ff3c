"""The effects study kind (``kind = "effects"``): the effect table of one impact, written as
``shtaerman effects --out`` writes it (effects.json, effects.csv, effects.md).

Its case is a dynamic study's (the same tables: ``[indenter]``, ``[half_space]``, ``[impact]``
with one velocity, ``[rubber]``, ``[layer]``; ``shtaerman init-study --kind effects`` writes
every key, commented); ``[numerics]`` and ``[quick]`` take :func:`shtaerman.effects`'s
keywords. Its roles are registered by name in :mod:`shtaerman.study.kinds` (the study layer
does not import the API).
"""

from __future__ import annotations

import time
from dataclasses import dataclass, field, replace
from pathlib import Path
from typing import Any

import msgspec

from ...problem import parts
from ...study.checks import Check, Outcome
from ...study.dynamic.loader import KEYS, impact_physics
from ...study.schema import (
    BodyTable,
    LayerTable,
    Named,
    Positive,
    RubberTable,
    StudyError,
    StudyFile,
    SurfaceImpactTable,
    Table,
    decode,
    exact_impacts,
    indenter_of,
    layer_geometry,
    named,
    ranged,
    refused,
)
from ...theory.materials import Material
from ...validation import InputError
from .report import write_table
from .run import checked_table, effects
from .table import EffectTable

__all__ = ["EffectsOutcome", "EffectsStudy", "load_effects", "run_effects", "write_effects"]


class _Numerics(Table):
    refine: Positive | None = None
    estimate: bool | None = None
    time_steps: ranged("time_steps", "dynamic") | None = None
    mesh_size: Positive | None = None
    mesh_margin: Positive | None = None
    domain_factor: Positive | None = None
    growth: Positive | None = None
    layer_rate: ranged("layer_rate", "dynamic") | None = None


class _EffectsFile(StudyFile):
    half_space: BodyTable
    impact: SurfaceImpactTable
    rubber: RubberTable = RubberTable()
    layer: LayerTable | None = None
    numerics: _Numerics = _Numerics()
    quick: _Numerics = _Numerics()


@dataclass(frozen=True)
class EffectsStudy(Named):
    """An effects study: the full problem's parts and the numerics of :func:`effects`."""

    parts: dict[str, Any]
    numerics: dict[str, Any]
    quick_numerics: dict[str, Any]
    kind: str = "effects"


@dataclass(frozen=True)
class EffectsOutcome(Outcome):
    """The effect table of a study (no pass/fail checks: a refused variant is a row)."""

    study: EffectsStudy
    table: EffectTable
    seconds: float
    checks: list[Check] = field(default_factory=list)
    quick: bool = False

    def document(self) -> dict[str, object]:
        """The table's JSON (``shtaerman effects --json``) for results.json."""
        return {"effects": self.table.to_dict()}


def load_effects(path: Path, data: dict[str, Any]) -> list[EffectsStudy]:
    """The study of a parsed ``kind = "effects"`` file; :class:`StudyError` names file and
    key."""
    raw: _EffectsFile = decode(path, data, _EffectsFile, "dynamic")  # its FE impact's ranges
    header = named(path, raw)
    indenter = indenter_of(path, raw.indenter)  # its refusal names file and key already
    body, impact = raw.half_space, raw.impact
    elastic = Material(body.E2, body.nu2)
    exact = exact_impacts(impact.mass, indenter, elastic)
    try:
        found = parts(
            indenter,
            replace(elastic, density=body.density2),
            mass=impact.mass,
            velocity=impact.velocity,
            prony=body.prony,
            **layer_geometry(path, raw.layer, lambda: exact(impact.velocity)),
            **impact_physics(raw),
        )
    except InputError as error:
        raise refused(path, error, KEYS) from None
    numerics = {k: v for k, v in msgspec.structs.asdict(raw.numerics).items() if v is not None}
    own = {k: v for k, v in msgspec.structs.asdict(raw.quick).items() if v is not None}
    quick = {**numerics, "estimate": False, **own}
    _check_numerics(path, found, numerics, "numerics")
    _check_numerics(path, found, quick, "quick", own)
    return [EffectsStudy(**header, parts=found, numerics=numerics, quick_numerics=quick)]


def _check_numerics(
    path: Path, found: dict, numerics: dict, table: str, own: dict | None = None
) -> None:
    """Refuse at load, naming its key, what :func:`effects` would refuse of the table with
    these numerics before any run (``verify --quick`` never runs ``[numerics]``' overridden
    keys, ``verify`` never ``[quick]``'s): ``[quick]`` inherits the keys it does not give
    (``own``) from ``[numerics]``."""
    options = {k: v for k, v in numerics.items() if k not in ("refine", "estimate")}
    try:
        checked_table(found, numerics.get("refine", 1.0), numerics.get("estimate", True), options)
    except InputError as error:
        if error.parameter not in _Numerics.__struct_fields__:
            raise refused(path, error, KEYS) from None
        key = f"{table if own is None or error.parameter in own else 'numerics'}.{error.parameter}"
        reason = str(error).removeprefix(f"{error.parameter}: ")
        raise StudyError(f"{path}: key '{key}': {reason}") from None


def run_effects(study: EffectsStudy, quick: bool = False, progress: Any = None) -> EffectsOutcome:
    """The effect table of the study (``quick``: its [quick] numerics)."""
    start = time.perf_counter()
    numerics = study.quick_numerics if quick else study.numerics
    table = effects(study.parts, **numerics, progress=progress)
    return EffectsOutcome(study, table, time.perf_counter() - start, quick=quick)


def write_effects(
    outcome: EffectsOutcome, folder: Path, root: Path, figure_format: str = "png"
) -> tuple[dict[str, str], dict[str, str]]:
    """effects.json, effects.csv, effects.md and the figure effects.png in ``folder`` (as
    ``shtaerman effects --out``; ``figure_format`` "svg" or "pdf": the figure also in that
    format beside its PNG)."""
    from .figure import EFFECTS_CAPTION

    folder.mkdir()
    write_table(outcome.table, folder)
    names = {"effects": "effects.json", "effects_csv": "effects.csv", "effects_md": "effects.md"}
    figure = outcome.table.plot(folder / "effects.png", figure_format)
    return (
        {stem: str((folder / name).relative_to(root)) for stem, name in names.items()},
        {EFFECTS_CAPTION: str(figure.relative_to(root))},
    )
