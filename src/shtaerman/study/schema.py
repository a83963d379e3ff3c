"""The schema helpers every study kind shares: typed TOML tables, decoding with messages that
name the file and the key, old keys renamed, and finding and loading a study file of any kind.

A study file is decoded into typed structures by msgspec (``forbid_unknown_fields``, numeric
constraints): it rejects unknown keys, wrong types and out-of-range values and reports where.
Every mistake raises :class:`StudyError` naming the file, the key and what
was expected, and everything (including what the FEM needs: n > 1, nu2 >= 0) is checked when
the file is loaded, before any computing.
"""

from __future__ import annotations

import contextlib
import copy
import functools
import importlib.resources
import math
import re
import sys
import tomllib
from collections.abc import Callable, Iterator, Mapping, Sequence
from dataclasses import dataclass, replace
from pathlib import Path
from typing import TYPE_CHECKING, Annotated, Any, Literal, get_args, get_type_hints

import msgspec

from ..fem.contact.linear import validate_fem_inputs
from ..problem import RUBBER_OPTIONS, worded
from ..validation import InputError, bound_text
from ..vocabulary import MAX_STUDIES, VOCABULARY, deprecated, fields, suggestion
from ..vocabulary import entry as vocabulary_entry
from .kinds import kind_function, study_kinds

if TYPE_CHECKING:
    from ..theory.sneddon import Indenter

__all__ = [
    "EXTENDED_STUDIES",
    "BodyTable",
    "LayerTable",
    "Named",
    "RubberTable",
    "StudyError",
    "StudyFile",
    "SurfaceImpactTable",
    "SweepTable",
    "built",
    "exact_impacts",
    "find_study",
    "indenter_of",
    "layer_geometry",
    "layer_spec",
    "load_study",
    "named",
    "normalized",
    "prony_of",
    "refused",
    "replaced",
    "settings_of",
    "shipped_studies",
    "study_name",
    "swept",
    "validate_name",
]

EXPECTED = {
    **{
        item.name: ("" if item.type == "int" else "a number ")
        + ("in " if item.range_text()[:1] in "([" else "")
        + item.range_text()
        + (f" ({item.unit})" if item.unit else "")
        for item in VOCABULARY
        if item.type in ("float", "int") and item.group != "output"
    },
    "E1": f'a number in {vocabulary_entry("E1").range_for().text()} (Pa), or "inf" for a rigid '
    "striker",
    "velocity": "a number > 0 (m/s), or (a dynamic study) a list of increasing ones",
    "depths": f"a list of 2 to {vocabulary_entry('depths').max_items} increasing depths > 0 (m), "
    'or "impact"',
    "sizes": "a list of at least 2 decreasing sizes in (0, 1) (element / refined radius)",
    "ladder": "independent or nested (the error-estimate mesh ladder)",
    "name": "a string",
    "description": "a string",
    "base": 'one of "bonded", "lubricated"',
    "loss": 'a list of distinct values of "waves", "hysteresis", "both"',
    "layer": "a [layer] table: thickness (m) or thickness_ratio (H / a_c), and base",
    "estimate": "true or false (each run's error bar)",
}
"""What each leaf key expects, for the error messages (tolerances: a number in (0, 1])."""
NAME_PATTERN = re.compile(r"[A-Za-z0-9][A-Za-z0-9_.+-]{0,99}")
"""A study name becomes a folder name: letters, digits, _ . + -, at most 100 characters."""


class StudyError(InputError):
    """A study file that cannot be used; the message names the file and the key."""


SMALLEST = sys.float_info.min
"""The least number > 0 a study file takes: a subnormal (1e-320) has lost its digits."""
Positive = Annotated[float, msgspec.Meta(ge=SMALLEST)]
Relative = Annotated[float, msgspec.Meta(gt=0, le=1)]
Poisson = Annotated[float, msgspec.Meta(gt=-1, le=0.5)]


def ranged(name: str, kind: str | None = None) -> Any:
    """The study-file type of vocabulary input ``name``: its number type constrained to its
    valid range in computation ``kind`` (:mod:`shtaerman.vocabulary`)."""
    item = vocabulary_entry(name)
    valid = item.range_for(kind)
    number = int if item.type == "int" else float
    bounds: dict[str, float] = {}
    if valid is not None and valid.low is not None:
        bounds["gt" if valid.low_open else "ge"] = number(valid.low)
        if valid.low == 0 and valid.low_open and number is float:
            bounds = {"ge": SMALLEST}
    if valid is not None and valid.high is not None:
        bounds["lt" if valid.high_open else "le"] = number(valid.high)
    return Annotated[number, msgspec.Meta(**bounds)]


class Table(msgspec.Struct, forbid_unknown_fields=True, frozen=True):
    """A TOML table: unknown keys are errors."""


class SweepTable(Table):
    """A study file's ``[sweep]``: exactly one of its fields, a list of values (a kind's
    subclass declares the fields it may sweep)."""

    def chosen(self) -> tuple[str, list[float]]:
        """The swept key and its values."""
        given = {k: v for k, v in msgspec.structs.asdict(self).items() if v is not None}
        if len(given) != 1 or not next(iter(given.values())):
            raise ValueError(
                f"expected exactly one of {sorted(self.__struct_fields__)} with a list of values"
            )
        key, values = next(iter(given.items()))
        if len(values) > MAX_STUDIES:
            raise ValueError(
                f"expected at most {MAX_STUDIES} values of {key} (each is a study), got "
                f"{len(values)}"
            )
        return key, values

    def __post_init__(self) -> None:
        self.chosen()


class IndenterTable(Table):
    """``[indenter]``: the striker's profile: z = A r^n (``shape_coefficient`` A in m^(1-n)
    and ``exponent`` n), an exact sphere (``sphere_radius``, m) or a tabulated z(r)
    (``profile``, a CSV path, relative to the study file): :func:`indenter_of`."""

    shape_coefficient: Positive | None = None
    exponent: Positive | None = None
    sphere_radius: Positive | None = None
    profile: str | None = None


def indenter_of(path: Path, raw: IndenterTable) -> Indenter:
    """The profile of ``[indenter]``: exactly one of the power law (shape_coefficient and
    exponent), sphere_radius or profile; a refusal names the file and the key."""
    from ..theory.indenter import PowerLawIndenter
    from ..theory.profiles import SphereIndenter, TabulatedIndenter

    given = [k for k in IndenterTable.__struct_fields__ if getattr(raw, k) is not None]
    power_law = [k for k in given if k in ("shape_coefficient", "exponent")]
    others = [k for k in given if k not in power_law]
    if len(others) > 1 or (others and power_law) or (not others and len(power_law) < 2):
        raise StudyError(
            f"{path}: key 'indenter': expected one striker profile: shape_coefficient and "
            f"exponent (z = A r^n), sphere_radius (m) or profile (a CSV of r, z in m), got "
            f"{given or 'none'}"
        )
    key = others[0] if others else "exponent"
    try:
        if key == "sphere_radius":
            return SphereIndenter(raw.sphere_radius)
        if key == "profile":
            table = Path(raw.profile).expanduser()
            return TabulatedIndenter.from_csv(table if table.is_absolute() else path.parent / table)
        return PowerLawIndenter(raw.shape_coefficient, raw.exponent)
    except InputError as error:
        raise StudyError(f"{path}: key 'indenter.{key}': {error}") from None


class StrikerTable(Table):
    E1: Positive | Literal["inf"]
    nu1: Poisson


class MaterialTable(Table):
    """The half-space."""

    E2: Positive
    nu2: Poisson


class ImpactTable(Table):
    """``[impact]``: striker mass in kg, approach velocity in m/s."""

    mass: Positive
    velocity: Positive


class SurfaceImpactTable(ImpactTable):
    """The ``[impact]`` of an impact's study file (dynamic, effects): the striker's surface
    too, ``interface`` and Coulomb's ``friction`` (:func:`.dynamic.loader.impact_physics`)."""

    interface: str = "frictionless"
    friction: float | None = None


class StudyFile(Table):
    """The tables of every kind's study file: ``[indenter]``, ``[half_space]`` and
    ``[impact]`` (a kind's subclass gives the last two its own types, in this order, and adds
    its tables), the study's ``name`` (default: the file's stem) and ``description``."""

    indenter: IndenterTable
    half_space: MaterialTable
    impact: ImpactTable
    name: str | None = None
    description: str = ""


@dataclass(frozen=True)
class Named:
    """The first fields of every kind's study: its name (a plain folder name), its
    description and the file it was read from (a kind's dataclass adds its own)."""

    name: str
    description: str
    source: Path


def named(path: Path, raw: StudyFile) -> dict[str, Any]:
    """The :class:`Named` fields of the study file ``raw`` read from ``path``, as keywords."""
    return {"name": study_name(path, raw.name), "description": raw.description, "source": path}


def built(path: Path, build: Callable[[], Any], keys: Sequence[str] = ()) -> Any:
    """``build()``, a refusal (InputError) it raises as a StudyError naming the file: one of
    a parameter in ``keys`` naming its study key too (:func:`refused`), a StudyError as it is."""
    try:
        return build()
    except StudyError:
        raise
    except InputError as error:
        if error.parameter in keys:
            raise refused(path, error) from None
        raise StudyError(f"{path}: {error}") from None


def swept(study: Any, sweep: SweepTable | None, change: Callable, symbols: Mapping) -> list:
    """``study``, or one study per value of the ``[sweep]``'s key: ``change(key, value)``
    named ``{study.name}-{symbols[key]}{value}`` (a number in ``g`` format)."""
    if sweep is None:
        return [study]
    key, values = sweep.chosen()
    shown = [value if isinstance(value, str) else f"{value:g}" for value in values]
    return [
        replace(change(key, value), name=f"{study.name}-{symbols[key]}{text}")
        for value, text in zip(values, shown, strict=True)
    ]


class BodyTable(MaterialTable):
    """The half-space of an impact study: its density (0: massless) and Prony series."""

    density2: Annotated[float, msgspec.Meta(ge=0)]
    prony: str | None = None


class RubberTable(Table):
    """``[rubber]``: the body's model (None: the kind's default) and its shape options."""

    model: str | None = None
    mooney_ratio: float | None = None
    yeoh: list[float] | None = None
    gent_limit: float | None = None
    volumetric: str | None = None


class LayerTable(Table):
    """``[layer]``: a layer on a rigid base instead of the half-space."""

    thickness: Positive | None = None
    thickness_ratio: ranged("thickness_ratio") | None = None  # type: ignore[valid-type]
    base: Literal["bonded", "lubricated"] = "bonded"
    dynamic: bool = False


SETTINGS_FIELDS = fields(item.name for item in VOCABULARY if item.setting)
"""Study-file key -> MeshSettings / DynamicSettings field, where the two differ."""


class MeshTable(Table):
    """The [numerics] of a static FEM study (MeshSettings)."""

    refine: Positive | None = None
    mesh_margin: Positive | None = None
    mesh_size: Positive | None = None
    domain_factor: Positive | None = None
    growth: Positive | None = None
    axis_size: Positive | None = None
    axis_growth: Positive | None = None
    max_dofs: Positive | None = None


def replaced(base: Any, given: Mapping[str, Any]) -> Any:
    """``base`` (MeshSettings or DynamicSettings) with the numerics ``given`` (key -> value,
    None: not given; the key's field per :data:`SETTINGS_FIELDS`) it has a field for, each
    value checked alone first so that a refusal (InputError) names its key."""
    chosen = {
        SETTINGS_FIELDS.get(key, key): (key, value)
        for key, value in given.items()
        if value is not None and SETTINGS_FIELDS.get(key, key) in base.__dataclass_fields__
    }
    for setting, (key, value) in chosen.items():
        try:
            replace(base, **{setting: value})
        except InputError as error:
            raise InputError(f"{key}: {error}", key) from None
    return replace(base, **{setting: value for setting, (_, value) in chosen.items()})


def settings_of(path: Path, table: str, raw: Table, base: Any) -> Any:
    """:func:`replaced` with the numerics of the study file's ``[table]`` (``refine`` is the
    caller's); a refusal names the file and the key."""
    try:
        return replaced(base, msgspec.structs.asdict(raw))
    except InputError as error:
        text = str(error).removeprefix(f"{error.parameter}: ")
        raise StudyError(f"{path}: key '{table}.{error.parameter}': {text}") from None


def study_name(path: Path, name: str | None) -> str:
    """The study's ``name`` (default: the file's stem), a plain name; StudyError else."""
    try:
        return validate_name(path.stem if name is None else name, "name")
    except InputError as error:
        raise StudyError(f"{path}: key 'name': {error}") from None


def layer_spec(path: Path, layer: Any, swept: str | None) -> Any:
    """The layer of a ``[layer]`` table (a :class:`LayerTable` or a kind's own, without
    ``dynamic``; unresolved, a :class:`.contact.layer.LayerSpec`), its thickness given
    exactly once: in the table (m or H / a_c) or as the swept key ``swept``;
    :class:`StudyError` otherwise."""
    from .contact.layer import LayerSpec

    if layer is None:
        return LayerSpec()
    given = [key for key in ("thickness", "thickness_ratio") if getattr(layer, key) is not None]
    if len(given) > 1 or (given and swept):
        where = f"sweep.{swept}" if len(given) == 1 else "layer.thickness_ratio"
        raise StudyError(
            f"{path}: key '{where}': expected the layer's thickness once: layer.thickness (m), "
            "layer.thickness_ratio (H / a_c) or one of them in [sweep]"
        )
    if not given and not swept:
        raise StudyError(
            f"{path}: key 'layer': expected thickness (a number > 0, m) or thickness_ratio "
            f"({EXPECTED['thickness_ratio']}, H / a_c) (required)"
        )
    dynamic = getattr(layer, "dynamic", False)
    return LayerSpec(layer.thickness, layer.thickness_ratio, layer.base, dynamic)


def prony_of(path: Path, prony: str | None, youngs_modulus: float | None = None) -> Any:
    """The Prony series of ``[half_space] prony`` (None: unset), a relative .csv path taken
    from the study file's folder, of a body of ``youngs_modulus`` E2 in Pa
    (:func:`~shtaerman.theory.prony_sources.prony_input`); :class:`StudyError` naming the key."""
    from ..theory.prony_sources import prony_input

    if prony is not None and prony.strip().lower().endswith(".csv"):
        csv = Path(prony.strip())
        prony = prony if csv.is_absolute() else str(path.parent / csv)
    try:
        return prony_input(prony, youngs_modulus=youngs_modulus)
    except InputError as error:
        reason = str(error).removeprefix("prony: ")  # the key names it once
        reason = worded(reason, "file", {"E2": "half_space.E2"})
        raise StudyError(f"{path}: key 'half_space.prony': {reason}") from None


def exact_impacts(mass: float, indenter: Indenter, body: Any) -> Callable[[float], Any]:
    """velocity (m/s) -> the quasi-static impact of ``mass`` kg with the rigid ``indenter`` on
    the half-space of ``body`` (:func:`..theory.viscoelastic.elastic_impact`), solved once per
    velocity however often it is asked (the loader's checks, a layer's H / a_c and the run
    share it)."""
    from ..theory.viscoelastic import rigid_impact

    @functools.cache
    def solved(velocity: float) -> Any:
        return rigid_impact(indenter, body, mass, velocity)()

    return solved


def layer_geometry(
    path: Path, layer: LayerTable | None, exact: Callable[[], Any]
) -> dict[str, Any]:
    """The impact's layer as keywords of :class:`shtaerman.problem.Problem` (thickness in m,
    base; {} on the half-space): H / a_c resolved at the quasi-static impact ``exact()`` of
    the rigid striker on the half-space (:func:`exact_impacts`)."""
    if layer is None:
        return {}
    if layer.dynamic:
        raise StudyError(
            f"{path}: key 'layer.dynamic': applies to a contact study (this one is an impact)"
        )
    spec = layer_spec(path, layer, None).resolved(float(exact().a_c))
    return {"thickness": spec.thickness, "base": spec.base}


def validate_name(name: object, what: str = "name") -> str:
    """Return a plain study name (it becomes a folder), or raise InputError."""
    if not isinstance(name, str) or not NAME_PATTERN.fullmatch(name) or set(name) == {"."}:
        raise InputError(
            f"{what} must be a plain name (letters, digits, _ . + -, starting with a letter or "
            f"digit, at most 100 characters), got {name!r}"
        )
    return name


def _allowed_keys(path: list[str], root: type) -> list[str]:
    """The keys of the table at ``path`` in the schema ``root``."""
    struct: Any = root
    for key in path:
        hint = get_type_hints(struct)[key]
        candidates = [hint, *get_args(hint)]
        struct = next(c for c in candidates if isinstance(c, type) and issubclass(c, Table))
    return sorted(struct.__struct_fields__)


def _homes(name: str, root: type) -> list[str]:
    """The tables of the schema ``root`` that take the key ``name`` (a study kind's own: the
    friction of a contact study is [contact]'s, of a dynamic one [impact]'s), before any
    look-alike name."""
    found = []
    for table in root.__struct_fields__:
        if table in ("sweep", "quick"):  # a swept list, the quick run's numerics: not a home
            continue
        with contextlib.suppress(StopIteration):  # not a table (name, description)
            if name in _allowed_keys([table], root):
                found.append(table)
    return found


_TABLES = ("indenter", "half_space", "impact", "striker", "dynamic", "material")
"""Required keys that are tables, for the "missing" message."""


def _value(data: Any, keys: list[str]) -> Any:
    """The value at ``keys`` in the TOML data (or a marker when it is not there)."""
    for key in keys:
        if not isinstance(data, dict) or key not in data:
            return msgspec.UNSET
        data = data[key]
    return data


def _expectation(keys: list[str], text: str) -> str:
    """A readable expectation for a leaf key (msgspec's own words as a fallback)."""
    leaf = keys[-1] if keys else ""
    if keys and keys[0] in ("tolerances",):  # before EXPECTED: tolerances.exponent is no n
        return "a relative tolerance in (0, 1]"
    if leaf in EXPECTED:
        return EXPECTED[leaf]
    if len(keys) > 1 and keys[0] in ("numerics", "quick", "sweep"):
        return "a number > 0" if keys[0] != "sweep" else "a non-empty list of numbers > 0"
    return text.replace("`", "").removeprefix("Expected ").removeprefix("expected ")


def _vocabulary_says(keys: list[str], value: Any, kind: str | None) -> str | None:
    """The refusal of a number ``value`` at key path ``keys`` (``[table] key``) in the words
    the command line and the sweep files use for that input
    (:meth:`shtaerman.vocabulary.Entry.check`, in ``kind``'s range), or None where the key is
    no vocabulary number of its table or the check passes."""
    names = {item.name for item in VOCABULARY if item.type in ("float", "int")}
    own = len(keys) == 2 and keys[0] not in ("tolerances", "sweep", "corrections")
    if not own or keys[-1] not in names or isinstance(value, list | dict | type(msgspec.UNSET)):
        return None  # a tolerance, a swept list: the schema's own words
    try:
        vocabulary_entry(keys[-1]).check(value, kind)
    except InputError as error:
        return str(error)
    return None


def _located(
    message: str, data: dict[str, Any], root: type, kind: str | None = None
) -> tuple[list[str], str]:
    """Split a msgspec message into the key path and what it says: the vocabulary's refusal
    of a number (:func:`_vocabulary_says`), else what was expected, with the value given."""
    text, _, where = message.partition(" - at `$")
    keys = [k for k in re.split(r"\.|\[\d+\]", where.rstrip("`")) if k]
    unknown = re.fullmatch(r"Object contains unknown field `([^`]+)`", text)  # any TOML key
    missing = re.fullmatch(r"Object missing required field `(\w+)`", text)
    if unknown:
        allowed = _allowed_keys(keys, root)
        homes = [table for table in _homes(unknown[1], root) if table not in keys]
        hint = suggestion(unknown[1], allowed).replace(" (", ": ", 1).removesuffix(")")
        if homes:
            hint = f": it belongs in [{homes[0]}]"
        if not keys and unknown[1] in KIND_OF_TABLE:
            hint = f": [{unknown[1]}] belongs in a study of kind = {KIND_OF_TABLE[unknown[1]]!r}"
        return [*keys, unknown[1]], f"expected one of {allowed} (unknown key{hint})"
    if missing:
        leaf = missing[1]
        expected = EXPECTED.get(leaf, f"a [{leaf}] table" if leaf in _TABLES else "a value")
        return [*keys, leaf], f"expected {expected} (required)"
    field_error = re.fullmatch(r"(\w+): (.*)", text)
    if field_error:
        keys = [*keys, field_error[1]]
    given = _value(data, keys)
    if keys == ["striker", "E1"] and isinstance(given, str):  # "inf": the one string it takes
        valid = vocabulary_entry("E1").range_for().text()
        return keys, (
            f'expected a number in {valid} (Pa), unquoted, or inf or "inf" (the one string '
            f"it takes) for a rigid striker, got {given!r}"
        )
    said = _vocabulary_says(keys, given, kind)
    if said is not None:
        return keys, said
    expectation = _expectation(keys, text).split(", got ")[0]  # msgspec may say "got" itself
    shown = "" if given is msgspec.UNSET else f", got {given!r}"
    if isinstance(given, float) and 0 < given < SMALLEST:
        shown = f" and at least {bound_text(SMALLEST, 'low', 4)} (the smallest normal float){shown}"
    return keys, f"expected {expectation}{shown}"


def decode(path: Path, data: dict[str, Any], root: type, kind: str | None = None) -> Any:
    """``data`` as the schema ``root`` (a :class:`Table`) of a study of ``kind``, or
    :class:`StudyError` naming the file, the key and what was expected (a vocabulary number
    in the command line's words: ``mass must be > 0 kg, got -1.0``)."""
    try:
        decoded = msgspec.convert(data, root)
    except msgspec.ValidationError as error:
        keys, said = _located(str(error), data, root, kind)
        raise StudyError(f"{path}: key '{'.'.join(keys)}': {said}") from None
    _check_ranges(path, data, kind)
    for keys, value in _numbers(data):
        if not math.isfinite(value) and keys not in INFINITE_ALLOWED:
            said = _vocabulary_says(list(keys), value, kind)
            if said is not None:
                raise StudyError(f"{path}: key '{'.'.join(keys)}': {said}")
            declared = EXPECTED.get(keys[-1], "")  # its range, where declared
            bound = declared.removeprefix("a number ") if declared.startswith("a number ") else ""
            expected = f"a finite number {bound}".rstrip()
            raise StudyError(f"{path}: key '{'.'.join(keys)}': expected {expected}, got {value!r}")
    return decoded


def _check_ranges(path: Path, data: dict[str, Any], kind: str | None) -> None:
    """Refuse a finite number of a table's own key outside ``kind``'s valid range for that
    input, in the command line's words (``exponent must lie in (1, 20]``): before the theory
    objects are built, whose own ranges (the exact theory's n in [0.25, 20]) are wider."""
    if kind is None:
        return
    for table, values in data.items():
        for key, value in values.items() if isinstance(values, dict) else ():
            number = isinstance(value, int | float) and not isinstance(value, bool)
            said = _vocabulary_says([table, key], value, kind) if number else None
            if said is not None and math.isfinite(value):
                raise StudyError(f"{path}: key '{table}.{key}': {said}")


INFINITE_ALLOWED = (("striker", "E1"),)
"""The keys where TOML's ``inf`` means something (a rigid striker); elsewhere it is refused."""


def _numbers(data: Any, keys: tuple[str, ...] = ()) -> Iterator[tuple[tuple[str, ...], float]]:
    """Every float in the TOML data with its key path (list items under their list's key)."""
    if isinstance(data, dict):
        for key, value in data.items():
            yield from _numbers(value, (*keys, str(key)))
    elif isinstance(data, list):
        for item in data:
            yield from _numbers(item, keys)
    elif isinstance(data, float):
        yield keys, data


TABLE_OF = {
    **{name: "indenter" for name in ("shape_coefficient", "exponent", "sphere_radius", "profile")},
    **{name: "striker" for name in ("E1", "nu1")},
    **{name: "half_space" for name in ("E2", "nu2", "density2")},
    **{name: "impact" for name in ("mass", "velocity", "figure_velocity")},
    **{
        name: "contact" for name in ("depths", "reach", "depth_steps", "small_ratio", "small_steps")
    },
    **{item.name: "numerics" for item in VOCABULARY if item.group == "numerics"},
    **{name: "layer" for name in ("thickness", "thickness_ratio", "base", "dynamic")},
}
"""A vocabulary key written at the top level of a study file -> the table it belongs to."""
STUDY_KEYS = {
    **{name: f"{table}.{name}" for name, table in TABLE_OF.items()},
    **{name: f"rubber.{name}" for name in ("model", *RUBBER_OPTIONS)},
    "prony": "half_space.prony",
    "density": "half_space.density2",
    "interface": "contact.interface",
    "friction": "contact.friction",
    "rate": "contact.rate",
}
"""An input's study-file key, for a refusal (:func:`refused`; a kind's own tables first)."""
KIND_OF_TABLE = {"corrections": "finite-strain", "rubber": "finite-strain"}
"""A table that only one kind of study file has -> that kind."""
OLD_TABLES = {"mesh": "numerics", "quick_mesh": "quick"}
"""Tables of earlier releases -> their name now."""
_NUMERICS_RENAMED = {
    "size": "mesh_size",
    "margin": "mesh_margin",
    "domain": "domain_factor",
    "steps": "time_steps",
}
OLD_KEYS = {
    "striker": {"youngs_modulus": "E1", "poisson_ratio": "nu1"},
    "half_space": {"youngs_modulus": "E2", "poisson_ratio": "nu2", "density": "density2"},
    "impact": {"velocities": "velocity", "example": "figure_velocity"},
    "contact": {"steps": "depth_steps"},
    "numerics": _NUMERICS_RENAMED,
    "quick": {**_NUMERICS_RENAMED, "velocities": "velocity"},
    "sweep": {"poisson_ratio": "nu2"},
}
"""Table -> key of earlier releases -> its name now (the finite-strain [quick] steps are depth
steps: :data:`OLD_KEYS_BY_KIND`)."""
OLD_KEYS_BY_KIND = {"finite-strain": {"quick": {**OLD_KEYS["quick"], "steps": "depth_steps"}}}


def _rename(path: Path, table: dict[str, Any], renames: dict[str, str], where: str) -> None:
    """Rename the old keys of ``table`` in place, each with a deprecation warning."""
    for old, new in renames.items():
        if old not in table:
            continue
        if new in table:
            raise StudyError(
                f"{path}: keys '{where}{old}' and '{where}{new}' name one input; "
                f"keep '{where}{new}'"
            )
        deprecated(str(path), f"{where}{old}", f"{where}{new}")
        table[new] = table.pop(old)


def normalized(path: Path, kind: str, data: dict[str, Any]) -> dict[str, Any]:
    """The parsed study file in today's keys: old tables and keys renamed (with a deprecation
    warning each), ``[quick.mesh]`` merged into ``[quick]``, and vocabulary keys written at the
    top level moved into their tables."""
    data = copy.deepcopy(data)
    _rename(path, data, OLD_TABLES, "")
    quick = data.get("quick")
    if isinstance(quick, dict) and isinstance(quick.get("mesh"), dict):
        deprecated(str(path), "quick.mesh", "quick")
        for key, value in quick.pop("mesh").items():
            if key in quick:
                raise StudyError(f"{path}: key 'quick.{key}' given twice ([quick.mesh] too)")
            quick[key] = value
    for key in [k for k in data if k in TABLE_OF]:
        table = data.setdefault(TABLE_OF[key], {})
        if not isinstance(table, dict):
            break  # the decoder names the table that is not one
        if key in table:
            raise StudyError(
                f"{path}: key '{key}' given twice (at the top and in [{TABLE_OF[key]}])"
            )
        table[key] = data.pop(key)
    renames = {**OLD_KEYS, **OLD_KEYS_BY_KIND.get(kind, {})}
    for name, table in data.items():
        if isinstance(table, dict) and name in renames:
            _rename(path, table, renames[name], f"{name}.")
    return data


MAX_STUDY_BYTES = 16 << 20
"""Largest study file read."""


def load_study(path: str | Path) -> list[Any]:
    """Read and check a study file of any kind; a ``[sweep]`` may expand it into several.

    The top-level ``kind`` (default "contact") selects the schema (:mod:`.kinds`).

    Raises
    ------
    StudyError
        If the file is missing, not TOML, or a key is missing or invalid (the message names
        the file, the key and what was expected), or the FEM cannot run it.
    """
    path = Path(path)
    if path.exists() and not path.is_file():  # a FIFO would hang, /dev/zero fill the memory
        raise StudyError(f"{path}: not a regular file; name a study file (.toml)")
    try:
        if path.stat().st_size > MAX_STUDY_BYTES:
            raise StudyError(f"{path}: a study file has at most {MAX_STUDY_BYTES} bytes")
        data = tomllib.loads(path.read_text(encoding="utf-8"))
    except FileNotFoundError:
        raise StudyError(f"{path}: study file not found") from None
    except (OSError, UnicodeDecodeError) as error:
        raise StudyError(f"{path}: cannot read the study file ({error})") from None
    except tomllib.TOMLDecodeError as error:
        raise StudyError(f"{path}: not valid TOML ({error})") from None
    except RecursionError:
        raise StudyError(f"{path}: not valid TOML (nested too deeply)") from None
    kind = data.pop("kind", "contact")
    if kind not in study_kinds():
        raise StudyError(
            f"{path}: key 'kind': expected one of {study_kinds()}"
            f"{suggestion(str(kind), study_kinds())}, got {kind!r}"
        )
    return kind_function(kind, "load")(path, normalized(path, kind, data))


def refused(path: Path, error: InputError, keys: dict[str, str] | None = None) -> StudyError:
    """``error`` (a refusal of the Problem, the FEM's ranges or a guard) as a StudyError naming
    the file and the study key of its parameter: ``keys`` (the kind's own tables) first, then
    the vocabulary's table (:data:`TABLE_OF`); a StudyError is returned as it is."""
    if isinstance(error, StudyError):
        return error
    parameter = error.parameter or str(error).partition(":")[0]  # "model: unknown ..."
    table = {**STUDY_KEYS, **(keys or {})}
    head, _, rest = str(error).partition(": ")
    names = head.split(", ")
    if len(names) > 1 and parameter in names:  # inputs together ("mass, velocity: ..."): each
        found = ", ".join(repr(table.get(name, f"half_space.{name}")) for name in names)
        return StudyError(f"{path}: keys {found}: {worded(rest, 'file', table)}")
    key = table.get(parameter, "half_space")
    if not parameter.isidentifier():  # no name: mass and velocity together, their table
        key = table.get("mass", "impact.mass").partition(".")[0]
    reason = worded(str(error).removeprefix(f"{parameter}: "), "file", table)
    return StudyError(f"{path}: key '{key}': {reason}")


def validated(path: Path, studies: list) -> list:
    """``studies`` after the name and FEM-input checks, or a StudyError naming file and key."""
    for study in studies:
        try:
            validate_name(study.name)
        except InputError as error:
            raise StudyError(f"{path}: {error}") from None
        try:
            validate_fem_inputs(study.indenter, study.half_space)
        except InputError as error:
            raise refused(path, error) from None
    return studies


def studies_folder() -> Path:
    """The shipped studies: ``shtaerman/studies`` in a wheel, the repository's ``fem/`` else."""
    packaged = importlib.resources.files("shtaerman") / "studies"
    if packaged.is_dir():
        return Path(str(packaged))
    return Path(__file__).resolve().parents[3] / "fem"


EXTENDED_STUDIES = "extended"
"""Subfolder of the shipped studies that ``verify`` runs only with ``--extended`` (minutes)."""


def shipped_studies(*, extended: bool = False) -> list[Path]:
    """The study files shipped with shtaerman, sorted by name; ``extended``: followed by the
    slower ones of the :data:`EXTENDED_STUDIES` subfolder."""
    folder = studies_folder()
    paths = sorted(folder.glob("*.toml"))
    return paths + sorted((folder / EXTENDED_STUDIES).glob("*.toml")) if extended else paths


def find_study(name_or_path: str) -> Path:
    """A study file path, or the shipped study of that name (``paper`` -> ``paper.toml``).

    Raises
    ------
    StudyError
        If it is neither an existing file nor a shipped study's name.
    """
    path = Path(name_or_path).expanduser()
    if path.suffix == ".toml" or path.exists() or "/" in name_or_path:
        return path
    shipped = {p.stem: p for p in shipped_studies(extended=True)}
    if name_or_path not in shipped:
        raise StudyError(
            f"study {name_or_path!r} is neither a file nor a shipped study; "
            f"pick one of {sorted(shipped)} or give a .toml path"
        )
    return shipped[name_or_path]
