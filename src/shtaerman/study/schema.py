"""Cross-check studies as data: TOML files naming indenter, materials, depths, mesh, impact and
the tolerances that decide pass or fail.

A study file (see ``fem/paper.toml``)::

    name = "paper"                       # optional; default: the file's stem
    description = "..."
    [indenter]   shape_coefficient = 5.0 (m^(1-n)), exponent = 1.5
    [striker]    youngs_modulus = 2e11 (Pa, or "inf" for rigid), poisson_ratio = 0.25
    [half_space] youngs_modulus = 7.5e6 (Pa), poisson_ratio = 0.5
    [impact]     mass = 0.7 (kg), velocity = 3.0 (m/s)
    [contact]    depths = "impact" (8 depths up to the impact's x_c) or a list in m
    [mesh]       MeshSettings fields (optional); [quick_mesh] for ``verify --quick``
    [tolerances] relative: force, beta, exponent, contact_radius, central_pressure, impact
    [convergence] optional: sizes = [...] (smallest element / refined radius, decreasing): a
                 mesh-convergence study refining the whole mesh (``verify --quick``: the
                 coarsest three)
    [sweep]      optional: one parameter ("shape_coefficient", "exponent", "mass",
                 "velocity") and a list of values; the study runs once per value.

Every mistake raises :class:`StudyError` naming the file, the key and what was expected.
"""

from __future__ import annotations

import importlib.resources
import itertools
import math
import tomllib
from dataclasses import dataclass, field, fields, replace
from pathlib import Path
from typing import Any

from ..fem.mesh import MeshSettings
from ..theory.indenter import PowerLawIndenter
from ..theory.materials import RIGID, Material
from ..validation import InputError

__all__ = [
    "QUICK_MESH",
    "Study",
    "StudyError",
    "Tolerances",
    "find_study",
    "load_study",
    "shipped_studies",
]

QUICK_MESH = MeshSettings(size=1 / 90, domain=1e4, growth=0.3, axis_size=1e-5, axis_growth=0.2)
"""Coarse mesh of ``verify --quick`` (about 5k dofs; errors about 2x the default's)."""

SWEEPABLE = {
    "shape_coefficient": "indenter",
    "exponent": "indenter",
    "mass": "impact",
    "velocity": "impact",
}
SYMBOLS = {"shape_coefficient": "A", "exponent": "n", "mass": "M", "velocity": "v0"}


class StudyError(InputError):
    """A study file that cannot be used; the message names the file and the key."""


@dataclass(frozen=True)
class Tolerances:
    """Relative tolerances that decide pass or fail (the FEM issue's acceptance limits)."""

    force: float = 1e-3
    beta: float = 1e-3
    exponent: float = 1e-3
    contact_radius: float = 1e-2
    central_pressure: float = 1e-2
    impact: float = 2e-3
    """For x_c, P_c and t_c of the FEM-fed impacts against the exact one."""


@dataclass(frozen=True)
class Study:
    """One cross-check: a contact curve and the impact it implies (SI units)."""

    name: str
    description: str
    source: Path
    indenter: PowerLawIndenter
    striker: Material
    half_space: Material
    mass: float
    velocity: float
    depths: tuple[float, ...] | None
    mesh: MeshSettings
    quick_mesh: MeshSettings
    tolerances: Tolerances = field(default_factory=Tolerances)
    convergence_sizes: tuple[float, ...] = ()
    """Smallest-element sizes / refined radius of a mesh-convergence study (empty: none)."""


class _Reader:
    """Typed access to one table of a study file, with errors that name file and key."""

    def __init__(self, path: Path, data: dict[str, Any], prefix: str = "") -> None:
        self.path, self.data, self.prefix = path, data, prefix

    def error(self, key: str, expected: str, got: object = None) -> StudyError:
        shown = "" if got is None else f", got {got!r}"
        return StudyError(f"{self.path}: key '{self.prefix}{key}': expected {expected}{shown}")

    def table(self, key: str, required: bool = True) -> _Reader:
        value = self.data.get(key, None if required else {})
        if not isinstance(value, dict):
            raise self.error(key, "a table [" + key + "]", value)
        return _Reader(self.path, value, f"{self.prefix}{key}.")

    def number(self, key: str, expected: str, default: float | None = None) -> float:
        value = self.data.get(key, default)
        if isinstance(value, bool) or not isinstance(value, int | float) or math.isnan(value):
            raise self.error(key, expected, value)
        return float(value)

    def text(self, key: str, default: str) -> str:
        value = self.data.get(key, default)
        if not isinstance(value, str):
            raise self.error(key, "a string", value)
        return value

    def check_keys(self, allowed: set[str]) -> None:
        unknown = sorted(set(self.data) - allowed)
        if unknown:
            raise self.error(unknown[0], f"one of {sorted(allowed)} (unknown key)")


def _material(reader: _Reader, allow_rigid: bool) -> Material:
    reader.check_keys({"youngs_modulus", "poisson_ratio"})
    modulus = reader.data.get("youngs_modulus")
    if allow_rigid and modulus == "inf":
        return RIGID
    expected = "a number > 0 in Pa" + (' or "inf" (rigid)' if allow_rigid else "")
    modulus = reader.number("youngs_modulus", expected)
    if modulus <= 0:
        raise reader.error("youngs_modulus", expected, modulus)
    ratio = reader.number("poisson_ratio", "a Poisson's ratio in (-1, 0.5]")
    if not -1 < ratio <= 0.5:
        raise reader.error("poisson_ratio", "a Poisson's ratio in (-1, 0.5]", ratio)
    return Material(modulus, ratio)


def _positive(reader: _Reader, key: str, unit: str, default: float | None = None) -> float:
    value = reader.number(key, f"a number > 0 ({unit})", default)
    if value <= 0:
        raise reader.error(key, f"a number > 0 ({unit})", value)
    return value


def _mesh(reader: _Reader, default: MeshSettings) -> MeshSettings:
    names = {f.name for f in fields(MeshSettings)}
    reader.check_keys(names)
    values = {key: _positive(reader, key, "relative size") for key in reader.data}
    try:
        return replace(default, **values)
    except InputError as error:
        raise StudyError(f"{reader.path}: [{reader.prefix.rstrip('.')}] {error}") from None


def _depths(reader: _Reader) -> tuple[float, ...] | None:
    reader.check_keys({"depths"})
    depths = reader.data.get("depths", "impact")
    if depths == "impact":
        return None
    expected = 'a list of at least 2 increasing depths > 0 in m, or "impact"'
    if not isinstance(depths, list) or len(depths) < 2:
        raise reader.error("depths", expected, depths)
    values = []
    for value in depths:
        if isinstance(value, bool) or not isinstance(value, int | float) or value <= 0:
            raise reader.error("depths", expected, depths)
        values.append(float(value))
    if any(b <= a for a, b in itertools.pairwise(values)):
        raise reader.error("depths", expected, depths)
    return tuple(values)


def _convergence(reader: _Reader) -> tuple[float, ...]:
    reader.check_keys({"sizes"})
    sizes = reader.data.get("sizes", [])
    expected = "a list of at least 2 decreasing sizes in (0, 1) (element / refined radius)"
    if not isinstance(sizes, list) or len(sizes) == 1:
        raise reader.error("sizes", expected, sizes)
    for size in sizes:
        if isinstance(size, bool) or not isinstance(size, int | float) or not 0 < size < 1:
            raise reader.error("sizes", expected, sizes)
    if any(b >= a for a, b in itertools.pairwise(sizes)):
        raise reader.error("sizes", expected, sizes)
    return tuple(float(size) for size in sizes)


def _tolerances(reader: _Reader) -> Tolerances:
    names = {f.name for f in fields(Tolerances)}
    reader.check_keys(names)
    return Tolerances(**{key: _positive(reader, key, "relative tolerance") for key in reader.data})


def _parse(path: Path, data: dict[str, Any]) -> Study:
    root = _Reader(path, data)
    root.check_keys(
        {
            "name",
            "description",
            "indenter",
            "striker",
            "half_space",
            "impact",
            "contact",
            "mesh",
            "quick_mesh",
            "tolerances",
            "sweep",
            "convergence",
        }
    )
    indenter = root.table("indenter")
    indenter.check_keys({"shape_coefficient", "exponent"})
    impact = root.table("impact")
    impact.check_keys({"mass", "velocity"})
    try:
        shape = PowerLawIndenter(
            _positive(indenter, "shape_coefficient", "m^(1-n)"), _positive(indenter, "exponent", "")
        )
    except InputError as error:
        raise StudyError(f"{path}: [indenter] {error}") from None
    return Study(
        name=root.text("name", path.stem),
        description=root.text("description", ""),
        source=path,
        indenter=shape,
        striker=_material(root.table("striker"), allow_rigid=True) if "striker" in data else RIGID,
        half_space=_material(root.table("half_space"), allow_rigid=False),
        mass=_positive(impact, "mass", "kg"),
        velocity=_positive(impact, "velocity", "m/s"),
        depths=_depths(root.table("contact", required=False)),
        mesh=_mesh(root.table("mesh", required=False), MeshSettings()),
        quick_mesh=_mesh(root.table("quick_mesh", required=False), QUICK_MESH),
        tolerances=_tolerances(root.table("tolerances", required=False)),
        convergence_sizes=_convergence(root.table("convergence", required=False)),
    )


def _sweep(study: Study, reader: _Reader) -> list[Study]:
    if len(reader.data) != 1:
        raise reader.error("", f"exactly one of {sorted(SWEEPABLE)} with a list of values")
    [(key, values)] = reader.data.items()
    if key not in SWEEPABLE:
        raise reader.error(key, f"one of {sorted(SWEEPABLE)}")
    if not isinstance(values, list) or not values:
        raise reader.error(key, "a non-empty list of numbers > 0", values)
    studies = []
    for value in values:
        number = _positive(_Reader(reader.path, {key: value}, reader.prefix), key, "sweep value")
        if SWEEPABLE[key] == "indenter":
            changed = replace(study, indenter=replace(study.indenter, **{key: number}))
        else:
            changed = replace(study, **{key: number})
        studies.append(replace(changed, name=f"{study.name}-{SYMBOLS[key]}{number:g}"))
    return studies


def load_study(path: str | Path) -> list[Study]:
    """Read a study file; a ``[sweep]`` expands it into one study per value.

    Raises
    ------
    StudyError
        If the file is missing, not TOML, or a key is missing or invalid (the message names
        the file, the key and what was expected).
    """
    path = Path(path)
    try:
        data = tomllib.loads(path.read_text(encoding="utf-8"))
    except FileNotFoundError:
        raise StudyError(f"{path}: study file not found") from None
    except (OSError, UnicodeDecodeError) as error:
        raise StudyError(f"{path}: cannot read the study file ({error})") from None
    except tomllib.TOMLDecodeError as error:
        raise StudyError(f"{path}: not valid TOML ({error})") from None
    study = _parse(path, data)
    if "sweep" in data:
        return _sweep(study, _Reader(path, data).table("sweep"))
    return [study]


def studies_folder() -> Path:
    """The shipped studies: ``shtaerman/studies`` in a wheel, the repository's ``fem/`` else."""
    packaged = importlib.resources.files("shtaerman") / "studies"
    if packaged.is_dir():
        return Path(str(packaged))
    return Path(__file__).resolve().parents[3] / "fem"


def shipped_studies() -> list[Path]:
    """The study files shipped with shtaerman, sorted by name."""
    return sorted(studies_folder().glob("*.toml"))


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
    shipped = {p.stem: p for p in shipped_studies()}
    if name_or_path not in shipped:
        raise StudyError(
            f"study {name_or_path!r} is neither a file nor a shipped study; "
            f"pick one of {sorted(shipped)} or give a .toml path"
        )
    return shipped[name_or_path]
