"""The sweep file: a TOML grid of cases of one kind, read and checked before any computation.

::

    name = "nu-grid"
    kind = "contact"          # contact | finite-strain | dynamic | impact | layer
    [parameters]              # fixed inputs, named like the CLI options in snake_case
    shape_coefficient = 3.3
    [axes]                    # the grid: every combination is one case
    exponent = [1.3, 1.8]
    nu2 = [0.0, 0.25, 0.4, 0.5]

Cases are numbered 0, 1, ... in the order of :func:`itertools.product` over the axes as written
(the last axis varies fastest). Every mistake raises :class:`SweepError`, one line naming the
file, the key and what was expected. A case beyond a validity limit of the model
(:class:`~shtaerman.validation.LimitError`: the depth's reach, the wave speed, a sphere's
equator, a layer's thickness against the contact) is no mistake: it is kept, with its reason,
in :attr:`SweepSpec.refused`, and the sweep records it as a "refused" row; a sweep whose every
case is refused is refused whole.
"""

from __future__ import annotations

import importlib.resources
import itertools
import math
import os
import re
import stat
import tomllib
from collections.abc import Mapping
from dataclasses import dataclass, field, replace
from pathlib import Path
from typing import Any

from ..problem import worded
from ..validation import InputError, LimitError, shown
from ..vocabulary import VOCABULARY, DeprecatedKeyWarning, deprecated, suggestion
from .kinds import KINDS, Kind, Parameter, check_rubber_options, get_kind

__all__ = [
    "MAX_CASES",
    "Case",
    "DeprecatedKeyWarning",
    "SweepError",
    "SweepSpec",
    "find_sweep",
    "load_sweep",
    "parse_sweep",
    "shipped_sweeps",
    "sweeps_folder",
]

MAX_CASES = 100_000
MAX_FILE_BYTES = 16 << 20
"""Largest sweep file read (a 100,000-value axis takes about 2 MB)."""
TOP_LEVEL = ("name", "kind", "description", "parameters", "axes")
_PLAIN_NAME = re.compile(r"[A-Za-z0-9_][A-Za-z0-9_.-]*")
_ENTRIES = {item.name: item for item in VOCABULARY}


class SweepError(InputError):
    """A sweep file that cannot be used; the message names the file and the key."""


FORMER_SWEEP_KEYS = ("steps",)
"""Sweep parameters of earlier releases that were renamed (``steps``: ``time_steps`` of the
dynamic kind, ``depth_steps`` of the finite-strain one). The study-file names among the
vocabulary's old names (``youngs_modulus``, ...) never were sweep keys: they stay unknown."""


def _renamed(where: str, table: str, kind: Kind, keys: dict[str, Any]) -> dict[str, Any]:
    """``keys`` with each old parameter name replaced by the kind's new one, with a one-line
    :class:`DeprecatedKeyWarning` naming the new key."""
    out = {}
    for key, value in keys.items():
        new = next(
            (
                item.name
                for item in VOCABULARY
                if key in FORMER_SWEEP_KEYS
                and key in item.old_names
                and item.name in kind.parameters
            ),
            None,
        )
        if key not in kind.parameters and new is not None:
            if new in keys:
                raise SweepError(
                    f"{where}: {table}: {key!r} and {new!r} name one input; keep {new!r}"
                )
            deprecated(where, f"{table}.{key}", f"{table}.{new}")
            key = new
        out[key] = value
    return out


@dataclass(frozen=True)
class Case:
    """One point of the grid: its index and every input of the kind (defaults filled in)."""

    index: int
    axis_values: dict[str, Any]
    params: dict[str, Any]


@dataclass(frozen=True)
class SweepSpec:
    """A checked sweep file.

    Attributes
    ----------
    path : Path
        The file it was read from.
    name, kind : str
        The sweep's name (a plain folder name) and the registered kind it runs.
    parameters : dict
        Fixed inputs from ``[parameters]``.
    axes : dict of str to list
        The grid, in file order.
    data : dict
        The whole parsed file (compared on ``--resume``).
    text : str
        The file as written (copied into the result folder).
    refused : dict of int to str
        The cases beyond a validity limit of the model, by index: the one-line reason, in
        the file's key words (they are recorded "refused", not run).
    """

    path: Path
    name: str
    kind: str
    description: str
    parameters: dict[str, Any]
    axes: dict[str, list[Any]]
    data: dict[str, Any]
    text: str = ""
    refused: dict[int, str] = field(default_factory=dict)

    @property
    def kind_spec(self) -> Kind:
        """The registered :class:`~shtaerman.sweep.kinds.Kind`."""
        return get_kind(self.kind)

    @property
    def outputs(self) -> dict[str, str]:
        """Output name -> unit: the kind's outputs and the optional ones switched on (in
        ``[parameters]``, by default, or for some case of an axis)."""
        kind = self.kind_spec
        flags = {**kind.defaults(), **self.parameters}
        flags |= {k: any(v) for k, v in self.axes.items() if k in kind.optional_outputs}
        return kind.outputs_for(flags)

    def cases(self) -> list[Case]:
        """Every case of the grid, numbered from 0 (last axis fastest)."""
        base = {**self.kind_spec.defaults(), **self.parameters}
        names = list(self.axes)
        cases = []
        for index, values in enumerate(itertools.product(*self.axes.values())):
            at = dict(zip(names, values, strict=True))
            params = {**base, **at}
            if params.get("sphere_radius") is not None or params.get("profile") is not None:
                params |= {"shape_coefficient": None, "exponent": None}  # not the power law
            cases.append(Case(index, at, params))
        return cases

    def to_dict(self) -> dict[str, Any]:
        """The spec as JSON-able data (for ``results.json``)."""
        return {
            "file": str(self.path),
            "name": self.name,
            "kind": self.kind,
            "description": self.description,
            "parameters": self.parameters,
            "axes": self.axes,
        }


def load_sweep(path: str | Path) -> SweepSpec:
    """Read, check and return a sweep file; every case's inputs are built and checked too.

    Raises
    ------
    SweepError
        One line: the file, the key, what was expected.
    """
    path = Path(path)
    try:
        handle = os.open(path, os.O_RDONLY | os.O_NONBLOCK)
    except OSError as error:
        raise SweepError(f"{path}: cannot read the sweep file ({error.strerror})") from None
    with os.fdopen(handle, "rb") as stream:
        info = os.fstat(handle)
        if not stat.S_ISREG(info.st_mode):
            raise SweepError(f"{path}: not a regular file; name a sweep file (.toml)")
        if info.st_size > MAX_FILE_BYTES:
            raise SweepError(
                f"{path}: {info.st_size} bytes; a sweep file has at most {MAX_FILE_BYTES} bytes"
            )
        data = stream.read(MAX_FILE_BYTES + 1)
    try:
        text = data.decode("utf-8")
    except UnicodeDecodeError as error:
        raise SweepError(
            f"{path}: not UTF-8 text (byte {data[error.start]:#04x} at offset {error.start})"
        ) from None
    return parse_sweep(text, path)


def parse_sweep(text: str, path: str | Path = "<sweep>") -> SweepSpec:
    """Check the TOML ``text`` of a sweep file (``path`` only names it in messages)."""
    path = Path(path)
    try:
        data = tomllib.loads(text)
    except tomllib.TOMLDecodeError as error:
        raise SweepError(f"{path}: not valid TOML ({error})") from None
    except RecursionError:
        raise SweepError(f"{path}: not valid TOML (nested too deeply)") from None
    where = str(path)
    unknown = sorted(set(data) - set(TOP_LEVEL))
    if unknown:
        raise SweepError(f"{where}: unknown key {unknown[0]!r}. Pick from {list(TOP_LEVEL)}")
    name = _name(where, data)
    kind = _kind(where, data)
    description = data.get("description", "")
    if not isinstance(description, str):
        raise SweepError(f"{where}: description must be a string, got {shown(description)}")
    parameters = _renamed(
        where, "parameters", kind, _table(where, data, "parameters", required=False)
    )
    axes = _renamed(where, "axes", kind, _table(where, data, "axes", required=True))
    for key, value in parameters.items():
        parameters[key] = _value(where, f"parameters.{key}", kind, key, value)
    if not axes:
        raise SweepError(f"{where}: [axes] is empty; give at least one axis, e.g. nu2 = [0.3, 0.5]")
    for key, values in axes.items():
        if key in parameters:
            raise SweepError(
                f"{where}: {key!r} is both in [parameters] and in [axes]; keep it in one"
            )
        axes[key] = _axis(where, kind, key, values)
    _striker(where, path, parameters, axes)
    _prony_files(where, path, parameters, axes)
    count = math.prod(len(values) for values in axes.values())
    if count > MAX_CASES:
        raise SweepError(f"{where}: [axes] makes {count} cases; at most {MAX_CASES} are allowed")
    spec = SweepSpec(path, name, kind.name, description, parameters, axes, data, text)
    return replace(spec, refused=_check_cases(where, spec))


STRIKER_KEYS = ("shape_coefficient", "exponent", "sphere_radius", "profile")
"""The keys of the striker's profile: the power law's pair, or one of the two others."""


def _striker(where: str, path: Path, parameters: dict[str, Any], axes: dict[str, Any]) -> None:
    """Refuse two striker profiles in a sweep (the power law's keys beside ``sphere_radius``
    or ``profile``, or both of those) and a ``profile`` axis (a file is fixed); read the
    ``profile`` CSV now, its path made absolute (given relative to the sweep file), so a bad
    table is refused at load naming the key, and the cases find it from any folder."""
    from ..theory.profiles import TabulatedIndenter

    if "profile" in axes:
        raise SweepError(
            f"{where}: axes.profile: a tabulated profile is fixed: give it in [parameters] "
            "(sphere_radius or the power law's keys can be axes)"
        )
    given = [key for key in STRIKER_KEYS if key in parameters or key in axes]
    others = [key for key in given if key in ("sphere_radius", "profile")]
    if others and len(given) > 1:
        table = "axes" if others[0] in axes else "parameters"
        raise SweepError(
            f"{where}: {table}.{others[0]}: one striker profile per case: shape_coefficient "
            "and exponent (z = A r^n), sphere_radius (m) or profile (a CSV of r, z in m), "
            f"got {given}"
        )
    if "profile" in parameters:
        table = _beside(path, parameters["profile"])
        try:
            TabulatedIndenter.from_csv(table)
        except InputError as error:
            raise SweepError(f"{where}: parameters.profile: {_unnamed(error)}") from None
        parameters["profile"] = str(table)


def _beside(path: Path, given: str) -> Path:
    """The file ``given`` in a sweep file ``path``, absolute (a relative one from its folder)."""
    file = Path(given).expanduser()
    return (file if file.is_absolute() else path.parent / file).resolve()


def _unnamed(error: InputError) -> str:
    """The reason of ``error`` without its leading parameter name (the key says it)."""
    return str(error).removeprefix(f"{error.parameter}: ")


def _prony_files(where: str, path: Path, parameters: dict[str, Any], axes: dict[str, Any]) -> None:
    """Read now each Prony series a sweep gives as a CSV file (``prony``, fixed or an axis),
    its path made absolute (given relative to the sweep file, as ``profile``), so a bad file
    is refused at load naming its key, and the cases find it from any folder."""
    from ..theory.prony_sources import prony_input

    given = [("parameters.prony", parameters, "prony")] if "prony" in parameters else []
    given += [(f"axes.prony[{i}]", axes["prony"], i) for i in range(len(axes.get("prony", ())))]
    for key, holder, index in given:
        value = holder[index]
        if isinstance(value, str) and value.strip().lower().endswith(".csv"):
            csv = _beside(path, value.strip())
            try:
                prony_input(str(csv), "prony")
            except InputError as error:
                raise SweepError(f"{where}: {key}: {_unnamed(error)}") from None
            holder[index] = str(csv)


def _name(where: str, data: Mapping[str, Any]) -> str:
    if "name" not in data:
        raise SweepError(f"{where}: missing key 'name' (a plain folder name, e.g. \"nu-grid\")")
    name = data["name"]
    if (
        not isinstance(name, str)
        or len(name) > 100
        or ".." in name
        or not _PLAIN_NAME.fullmatch(name)
    ):
        raise SweepError(
            f"{where}: name must be a plain folder name (letters, digits, '_', '-', '.'; no "
            f"'/', '..' or leading dot; at most 100 characters), got {shown(name)}"
        )
    return name


def _kind(where: str, data: Mapping[str, Any]) -> Kind:
    sweepable = sorted(n for n, kind in KINDS.items() if kind.case or kind.unavailable)
    if "kind" not in data:
        raise SweepError(f"{where}: missing key 'kind'. Pick one of {sweepable}")
    name = data["kind"]
    if not isinstance(name, str) or name not in sweepable:
        raise SweepError(f"{where}: kind: unknown kind {name!r}. Pick one of {sweepable}")
    try:
        return get_kind(name)
    except InputError as error:
        raise SweepError(f"{where}: kind: {error}") from None


def _table(where: str, data: Mapping[str, Any], key: str, *, required: bool) -> dict[str, Any]:
    if key not in data:
        if required:
            raise SweepError(f"{where}: missing table [{key}]")
        return {}
    table = data[key]
    if not isinstance(table, dict):
        raise SweepError(f"{where}: {key} must be a table [{key}], got {shown(table)}")
    return dict(table)


def _parameter(where: str, key: str, kind: Kind, name: str) -> Parameter:
    """The kind's parameter ``name`` (given at ``key``), or SweepError naming the ones it has
    (or, for a part its case does not combine with, why: :func:`_unsupported`)."""
    unsupported = _unsupported(kind, name)
    if unsupported is not None:
        raise SweepError(f"{where}: {key}: {worded(unsupported, 'file')}")
    if name not in kind.parameters:
        others = [other.name for other in KINDS.values() if name in other.parameters]
        hint = (  # a key of another kind is no misspelling: 'estimate' read 'gent_limit'
            f" (a parameter of kind{'s' * (len(others) > 1)} {', '.join(map(repr, others))})"
            if others
            else suggestion(name, kind.parameters)
        )
        raise SweepError(
            f"{where}: {key}: unknown parameter {name!r} for kind {kind.name!r}{hint}. "
            f"Pick one of {sorted(kind.parameters)}"
        )
    return kind.parameters[name]


RELAXING = ("prony", "rate")
"""The inputs of a viscoelastic contact curve (a Prony series and its pressing speed)."""


def _unsupported(kind: Kind, name: str) -> str | None:
    """The support table's refusal (:func:`shtaerman.problem.refusal`) of a viscoelastic
    input ``name`` in a finite-strain case, a rubber's contact curve, which does not combine
    with one (``shtaerman contact --model ... --prony`` is refused in the same words, but
    for its remedy: a finite-strain case has no linear model, the contact kind is the linear
    curve, which takes a Prony series); None for any other kind or name."""
    from ..problem import LINEAR_BODY, Cell, refusal

    if kind.name != "finite-strain" or name not in RELAXING:
        return None
    limit = refusal(Cell("rubber", True, "half-space", "frictionless", "curve"))
    if limit is None:
        return None
    return limit.reason.removesuffix(LINEAR_BODY) + ', or sweep kind = "contact" (linear)'


def _value(where: str, key: str, kind: Kind, name: str, value: Any) -> Any:
    """``value`` of parameter ``name`` converted to its declared type, or raise."""
    parameter = _parameter(where, key, kind, name)
    item = _ENTRIES.get(name)
    if item is not None and item.infinite and value == "inf":
        value = math.inf  # a rigid striker, as a study file spells it too
    converted = _convert(parameter, value)
    ranges = RANGES_OF.get(kind.name, kind.name)
    ranged = item is not None and ranges in item.kinds  # the vocabulary's range for this kind
    numeric = ranged and parameter.type in ("float", "int")  # a non-number: named with it
    if converted is None and not numeric:
        raise SweepError(f"{where}: {key} must be {_expected(parameter)}, got {shown(value)}")
    if ranged:
        assert item is not None
        try:
            converted = item.check(value if converted is None else converted, ranges, called=key)
        except InputError as error:
            raise SweepError(f"{where}: {error}") from None
    return converted


RANGES_OF = {"effects": "dynamic"}
"""A kind whose parameters are another's (:mod:`.kinds`) -> that kind, whose vocabulary ranges
they take."""


def _convert(parameter: Parameter, value: Any) -> Any:
    """The value in its declared type, or ``None`` when it does not fit."""
    is_number = isinstance(value, int | float) and not isinstance(value, bool)
    if parameter.type == "float":
        return float(value) if is_number else None
    if parameter.type == "int":
        return value if isinstance(value, int) and not isinstance(value, bool) else None
    if parameter.type == "path":
        return value if isinstance(value, str) and value else None
    if parameter.type == "str":
        ok = isinstance(value, str) and (not parameter.choices or value in parameter.choices)
        return value if ok else None
    if parameter.type == "bool":
        return value if isinstance(value, bool) else None
    if parameter.type == "floats":
        if not isinstance(value, list) or not value:
            return None
        if not all(isinstance(v, int | float) and not isinstance(v, bool) for v in value):
            return None
        return [float(v) for v in value]
    raise AssertionError(f"unknown parameter type {parameter.type!r}")


def _expected(parameter: Parameter) -> str:
    unit = f" in {parameter.unit}" if parameter.unit else ""
    return {
        "float": f"a number{unit}",
        "int": "an integer",
        "str": f"one of {list(parameter.choices)}" if parameter.choices else "a string",
        "floats": f"a non-empty list of numbers{unit}",
        "path": "a file path (relative to the sweep file)",
        "bool": "true or false",
    }[parameter.type]


def _axis(where: str, kind: Kind, name: str, values: Any) -> list[Any]:
    key = f"axes.{name}"
    _parameter(where, key, kind, name)
    if not isinstance(values, list):
        raise SweepError(f"{where}: {key} must be a list of values, got {shown(values)}")
    if not values:
        raise SweepError(f"{where}: {key} is empty; give at least one value")
    converted = [_value(where, f"{key}[{i}]", kind, name, v) for i, v in enumerate(values)]
    seen = set()
    for i, value in enumerate(converted):
        hashable = tuple(value) if isinstance(value, list) else value
        if hashable in seen:
            raise SweepError(f"{where}: {key} lists {values[i]!r} twice")
        seen.add(hashable)
    return converted


def _check_cases(where: str, spec: SweepSpec) -> dict[int, str]:
    """Build every case's inputs (cheap) so a value out of its physical range fails now;
    returns the cases beyond a validity limit (:class:`~shtaerman.validation.LimitError`) by
    index, each with its reason, unless every case is (then the sweep is refused)."""
    check = spec.kind_spec.check
    if "model" in spec.kind_spec.parameters:
        defaults = {**spec.kind_spec.defaults(), **spec.parameters}
        try:
            check_rubber_options(defaults, spec.axes)
        except InputError as error:
            raise SweepError(f"{where}: {error}") from None
    if check is None:
        return {}
    cases, refused, first = spec.cases(), {}, ""
    for case in cases:
        try:
            check(case.params)
        except (InputError, ValueError) as error:
            at = ", ".join(f"{k} = {v!r}" for k, v in case.axis_values.items())
            reason = worded(str(error), "file")
            said = f"{where}: case {case.index} ({at}): {reason}"
            if not isinstance(error, LimitError):
                raise SweepError(said) from None
            refused[case.index], first = reason, first or said
    if len(refused) == len(cases):  # nothing to run: refused whole, as a bad input
        every = f" (all {len(cases)} cases are outside the model's validity)"
        raise SweepError(first + (every if len(cases) > 1 else ""))
    return refused


def sweeps_folder() -> Path:
    """The shipped sweeps: ``shtaerman/sweeps`` in a wheel, the repository's ``sweeps/`` else."""
    packaged = importlib.resources.files("shtaerman") / "sweeps"
    if packaged.is_dir():
        return Path(str(packaged))
    return Path(__file__).resolve().parents[3] / "sweeps"


def shipped_sweeps() -> list[str]:
    """Names of the sweeps shipped with shtaerman (``shtaerman sweep NAME``)."""
    return sorted(path.stem for path in sweeps_folder().glob("*.toml"))


def find_sweep(argument: str | Path) -> Path:
    """The sweep file named by ``argument``: a path to a file, or the name of a shipped sweep."""
    path = Path(argument).expanduser()
    if path.exists() and (path.suffix == ".toml" or not path.is_dir()):
        return path  # load_sweep refuses what is not a regular file
    text = str(argument)
    if "/" not in text and not text.endswith(".toml"):
        shipped = sweeps_folder() / f"{text}.toml"
        if shipped.is_file():
            return shipped
        raise SweepError(
            f"sweep: no file {text!r} and no shipped sweep of that name. "
            f"Pick a file or one of {shipped_sweeps()}"
        )
    if path.is_dir():
        raise SweepError(f"sweep: {text!r} is a folder; give a sweep file (.toml) or its name")
    raise SweepError(f"sweep: no file {text!r}")
