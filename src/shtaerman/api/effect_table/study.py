"""The effects study kind (``kind = "effects"``): the effect table of one impact, written as
``shtaerman effects --out`` writes it (effects.json, effects.csv, effects.md)::

    kind = "effects"
    name = "..."; description = "..."   # optional
    [indenter]   shape_coefficient (m^(1-n)), exponent; or sphere_radius (m); or profile
                 (a CSV of r, z in m, relative to the study file)
    [half_space] E2 (Pa), nu2, density2 (kg/m^3; 0: massless), prony (optional)
    [impact]     mass (kg), velocity (m/s), interface, friction (as a dynamic study's)
    [rubber]     optional: model and its options (as a dynamic study's)
    [layer]      optional: thickness (m) or thickness_ratio (H / a_c), base
    [numerics]   refine, estimate (default true), time_steps, mesh_size, mesh_margin,
                 domain_factor, growth, layer_rate (:func:`shtaerman.effects`'s)
    [quick]      the [numerics] keys for ``verify --quick`` (default: no estimate)

The study's schema reuses the dynamic study's tables; its roles are registered by name in
:mod:`shtaerman.study.kinds` (the study layer does not import the API).
"""

from __future__ import annotations

import time
from dataclasses import dataclass, field
from pathlib import Path
from typing import Annotated, Any

import msgspec

from ...problem import parts
from ...study.checks import Check
from ...study.contact.loader import LayerTable
from ...study.dynamic.loader import PHYSICS_KEYS, RubberTable
from ...study.schema import (
    IndenterTable,
    Poisson,
    Positive,
    StudyError,
    Table,
    decode,
    indenter_of,
    validate_name,
)
from ...theory.materials import Material
from ...validation import InputError
from .report import write_table
from .run import effects
from .table import EffectTable

__all__ = ["EffectsOutcome", "EffectsStudy", "load_effects", "run_effects", "write_effects"]


class _Numerics(Table):
    refine: Positive | None = None
    estimate: bool | None = None
    time_steps: int | None = None
    mesh_size: Positive | None = None
    mesh_margin: Positive | None = None
    domain_factor: Positive | None = None
    growth: Positive | None = None
    layer_rate: float | None = None


class _HalfSpace(Table):
    E2: Positive
    nu2: Poisson
    density2: Annotated[float, msgspec.Meta(ge=0)]  # 0: massless
    prony: str | None = None


class _Impact(Table):
    mass: Positive
    velocity: Positive
    interface: str = "frictionless"
    friction: float | None = None


class _EffectsFile(Table):
    indenter: IndenterTable
    half_space: _HalfSpace
    impact: _Impact
    name: str | None = None
    description: str = ""
    rubber: RubberTable = RubberTable()
    layer: LayerTable | None = None
    numerics: _Numerics = _Numerics()
    quick: _Numerics = _Numerics()


@dataclass(frozen=True)
class EffectsStudy:
    """An effects study: the full problem's parts and the numerics of :func:`effects`."""

    name: str
    description: str
    source: Path
    parts: dict[str, Any]
    numerics: dict[str, Any]
    quick_numerics: dict[str, Any]
    kind: str = "effects"


@dataclass(frozen=True)
class EffectsOutcome:
    """The effect table of a study (no pass/fail checks: a refused variant is a row)."""

    study: EffectsStudy
    table: EffectTable
    seconds: float
    checks: list[Check] = field(default_factory=list)
    quick: bool = False

    @property
    def passed(self) -> bool:
        """Always true: the table has no tolerances."""
        return True

    def document(self) -> dict[str, object]:
        """The table's JSON (``shtaerman effects --json``) for results.json."""
        return {"effects": self.table.to_dict()}


def _geometry(path: Path, raw: _EffectsFile) -> dict[str, Any]:
    """The layer's thickness (m) and base ({} for the half-space); thickness_ratio resolved at
    the quasi-static impact on the half-space, as a dynamic study does."""
    from ...study.contact.loader import layer_spec
    from ...study.dynamic.case import exact_impact
    from ...theory.materials import RIGID, effective_modulus
    from ...theory.sneddon import contact_law

    if raw.layer is None:
        return {}
    if raw.layer.dynamic:
        raise StudyError(f"{path}: key 'layer.dynamic': applies to a contact study")
    body = Material(raw.half_space.E2, raw.half_space.nu2)
    law = contact_law(indenter_of(path, raw.indenter), effective_modulus(RIGID, body))
    a_c = float(exact_impact(raw.impact.mass, raw.impact.velocity, law).a_c)
    spec = layer_spec(path, raw.layer, None).resolved(a_c)
    return {"thickness": spec.thickness, "base": spec.base}


def _numerics(raw: _Numerics, base: dict[str, Any]) -> dict[str, Any]:
    given = {k: v for k, v in msgspec.structs.asdict(raw).items() if v is not None}
    return {**base, **given}


def load_effects(path: Path, data: dict[str, Any]) -> list[EffectsStudy]:
    """The study of a parsed ``kind = "effects"`` file; :class:`StudyError` names file and
    key."""
    raw: _EffectsFile = decode(path, data, _EffectsFile)
    try:
        name = validate_name(raw.name if raw.name is not None else path.stem, "name")
    except InputError as error:
        raise StudyError(f"{path}: key 'name': {error}") from None
    rubber = {k: v for k, v in msgspec.structs.asdict(raw.rubber).items() if v is not None}
    indenter = indenter_of(path, raw.indenter)  # its refusal names file and key already
    try:
        found = parts(
            indenter,
            Material(raw.half_space.E2, raw.half_space.nu2, raw.half_space.density2),
            mass=raw.impact.mass,
            velocity=raw.impact.velocity,
            prony=raw.half_space.prony,
            interface=raw.impact.interface,
            friction=raw.impact.friction,
            **_geometry(path, raw),
            **rubber,
        )
    except InputError as error:
        parameter = error.parameter or str(error).partition(":")[0]
        known = parameter.isidentifier()  # else a message of mass and velocity together
        key = PHYSICS_KEYS.get(parameter, f"half_space.{parameter}" if known else "impact")
        raise StudyError(f"{path}: key '{key}': {error}") from None
    numerics = _numerics(raw.numerics, {})
    quick = _numerics(raw.quick, {**numerics, "estimate": False})
    study = EffectsStudy(name, raw.description, path, found, numerics, quick)
    return [study]


def run_effects(study: EffectsStudy, quick: bool = False, progress: Any = None) -> EffectsOutcome:
    """The effect table of the study (``quick``: its [quick] numerics)."""
    start = time.perf_counter()
    numerics = study.quick_numerics if quick else study.numerics
    table = effects(study.parts, **numerics, progress=progress)
    return EffectsOutcome(study, table, time.perf_counter() - start, quick=quick)


def write_effects(
    outcome: EffectsOutcome, folder: Path, root: Path, figure_format: str = "png"
) -> tuple[dict[str, str], dict[str, str]]:
    """effects.json, effects.csv and effects.md in ``folder`` (as ``shtaerman effects
    --out``); no figures."""
    folder.mkdir()
    write_table(outcome.table, folder)
    files = {stem: str((folder / f"{stem}.json").relative_to(root)) for stem in ("effects",)}
    files["effects_csv"] = str((folder / "effects.csv").relative_to(root))
    files["effects_md"] = str((folder / "effects.md").relative_to(root))
    return files, {}
