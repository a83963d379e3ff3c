"""The finite-strain study file: how far real (neo-Hookean) rubber departs from Shtaerman.

A study file with ``kind = "finite-strain"`` (``fem/finite_strain.toml``; ``shtaerman
init-study --kind finite-strain`` writes every key, commented) runs in :mod:`.runner`: a depth
ladder (``[contact]`` reach, depth_steps, small_ratio, small_steps) pressed into the
``[rubber]`` body on a mesh ladder (``[numerics] ladder`` "independent": three gmsh meshes
K/2, K/sqrt(2), K; "nested": one gmsh mesh at K/2 refined uniformly once and twice), and the
impacts of ``[corrections]`` (:mod:`.corrections`). ``[contact]`` interface and friction
and a ``[layer]`` (a pad on a bonded base) are the command line's (``contact --model ...
--interface --friction --thickness``), checked as the problem's curve. A ``[sweep]`` takes one
of nu2, mass, velocity, model, volumetric.
"""

from __future__ import annotations

from dataclasses import dataclass, field, replace
from pathlib import Path
from typing import Any, Literal

import msgspec

from ... import vocabulary
from ...fem.mesh import FINITE_MESH, HALF_SPACE, Geometry, MeshSettings
from ...fem.rubber import RubberModel
from ...guards import DEPTHS_INSTEAD, check_profile_reach
from ...problem import MODELS, RUBBER_SHAPES, Body, Interface, Problem
from ...theory.materials import RIGID, Material, effective_modulus
from ...theory.sneddon import Indenter
from ...validation import InputError
from ..contact.layer import layer_depths
from ..contact.loader import PROFILE_KEYS
from ..ladder import check_ladder, nested_ladder
from ..schema import (
    MeshTable,
    Named,
    Poisson,
    Positive,
    Relative,
    RubberTable,
    StudyError,
    StudyFile,
    SweepTable,
    Table,
    built,
    decode,
    exact_impacts,
    indenter_of,
    layer_spec,
    named,
    ranged,
    refused,
    settings_of,
    swept,
    validated,
)

__all__ = [
    "QUICK_FINITE_MESH",
    "Corrections",
    "FiniteStudy",
    "FiniteTolerances",
    "Ladder",
    "finite_study",
    "load_finite",
    "rubber_of",
]

QUICK_FINITE_MESH = MeshSettings(size=1 / 24, growth=0.45, axis_size=1e-4, axis_growth=0.35)
"""Coarse mesh of ``verify --quick`` (one mesh, no error estimates)."""
SWEEPABLE = {"nu2": "nu", "mass": "M", "velocity": "v0", "model": "", "volumetric": ""}


class _Contact(Table):
    reach: ranged("reach") = vocabulary.entry("reach").default
    depth_steps: ranged("depth_steps") = vocabulary.entry("depth_steps").default
    small_ratio: ranged("small_ratio") = vocabulary.entry("small_ratio").default
    small_steps: ranged("small_steps") = vocabulary.entry("small_steps").default
    interface: str = vocabulary.entry("interface").default  # checked by the Problem's parts
    friction: ranged("friction") | None = None  # type: ignore[valid-type]


class _Layer(Table):
    """``[layer]``: a pad on a bonded rigid base (a finite-strain study runs no dynamic impact
    on it: its [corrections] do)."""

    thickness: Positive | None = None
    thickness_ratio: ranged("thickness_ratio") | None = None  # type: ignore[valid-type]
    base: str = vocabulary.entry("base").default  # checked by the Problem's parts


class _Numerics(MeshTable):
    ladder: Literal["independent", "nested"] = "independent"


class _Quick(MeshTable):
    depth_steps: ranged("depth_steps") = 6
    small_steps: ranged("small_steps") = 2
    small_ratio: ranged("small_ratio") = 0.02
    small_strain: Relative = 2e-2


class FiniteTolerances(Table):
    """``[tolerances]``: the checks that need no reference (relative; the runner widens the
    small-strain ones on the quick mesh and at a ladder start moved deeper)."""

    small_strain: Relative = 5e-3
    """|P / P_Shtaerman - 1| at the first (tiny) depth: physics (~0.06 x/a) plus the mesh
    (where Shtaerman's is the reference: not for a bonded or Coulomb indenter on nu2 < 0.5)."""
    small_strain_fem: Relative = 2e-3
    """|P / P_linear-FEM - 1| there, same mesh: the finite-strain effect alone."""
    identity: Relative = 3e-3
    """A bonded indenter on nu2 < 0.5: the same-mesh linear FEM's no-slip identity
    P (n+1) / (2 E* a d n) = chi(nu2) at the deepest depth
    (:mod:`shtaerman.study.contact.interface`)."""
    conservation: Relative = 2e-3
    """|Simpson's Int P dx / stored energy - 1|."""
    newton: Relative = 1e-6
    """Last Newton correction max |du| / depth at every depth (round-off floor 1e-6)."""
    complementarity: Relative = 1e-6
    """Largest |gap| on contact, or penetration off it, / depth."""


class _Sweep(SweepTable):
    nu2: list[Poisson] | None = None
    mass: list[Positive] | None = None
    velocity: list[Positive] | None = None
    model: list[str] | None = None
    volumetric: list[str] | None = None


class _Corrections(Table):  # values checked by _corrections, whose messages name the range
    velocities: list[Any]
    density2: Any = vocabulary.entry("density2").default


class _FiniteFile(StudyFile):
    contact: _Contact = _Contact()
    numerics: _Numerics = _Numerics()
    quick: _Quick = _Quick()
    tolerances: FiniteTolerances = FiniteTolerances()
    rubber: RubberTable = RubberTable()
    sweep: _Sweep | None = None
    corrections: _Corrections | None = None
    layer: _Layer | None = None


@dataclass(frozen=True)
class Corrections:
    """The ``[corrections]`` table: impact velocities (m/s) and the body's density (kg/m^3)
    of the dynamic impacts that test whether the wave and finite-strain corrections add."""

    velocities: tuple[float, ...]
    density: float


@dataclass(frozen=True)
class Ladder:
    """Depth ladder: ``steps`` equal steps to ``reach`` x_c after ``small_steps`` geometric
    depths from x/a = ``small_ratio``."""

    reach: float
    steps: int
    small_ratio: float
    small_steps: int


@dataclass(frozen=True)
class FiniteStudy(Named):
    """One finite-strain study (SI units)."""

    indenter: Indenter
    """The rigid striker's profile: z = A r^n, an exact sphere or a tabulated z(r)."""
    half_space: Material
    mass: float
    velocity: float
    ladder: Ladder
    quick_ladder: Ladder
    mesh: MeshSettings
    quick_mesh: MeshSettings
    tolerances: FiniteTolerances = field(default_factory=FiniteTolerances)
    quick_small_strain: float = 2e-2
    """The small-strain tolerance against Shtaerman on the quick mesh (its error ~1e-2)."""
    depths: tuple[float, ...] | None = None
    """Explicit depths in m instead of the ladder (a sweep's ``depths``), increasing."""
    kind: str = "finite-strain"
    rubber: RubberModel = field(default_factory=RubberModel)
    """The rubber model (default neo-Hookean, K/2 (J - 1)^2)."""
    mesh_ladder: str = "independent"
    """The error-estimate ladder (``[numerics] ladder``): ``independent``, ``mesh`` the finest
    of three gmsh meshes; ``nested``, ``mesh`` the middle of one gmsh mesh refined twice."""
    corrections: Corrections | None = None
    """The dynamic impacts of ``[corrections]``; None: none run."""
    interface: Interface = field(default_factory=Interface)
    """The indenter's surface: frictionless, bonded, or Coulomb's friction."""
    geometry: Geometry = HALF_SPACE
    """The body's shape: the half-space, or the ``[layer]`` (thickness resolved in m)."""


def rubber_of(half_space: Material, model: str | None, **options: Any) -> RubberModel:
    """The rubber pressed by a finite-strain study: ``model`` (None: neo-Hookean) with its
    ``options``, checked as the problem's :class:`~shtaerman.problem.Body` checks it.

    Raises
    ------
    InputError
        Naming the option, or ``model`` for the linear model (a finite-strain study presses
        a rubber).
    """
    model = model or "neo-hookean"
    body = Body(half_space, model, **options)
    if not body.finite:
        raise InputError(
            f"model: a finite-strain study presses a rubber: pick one of "
            f"{', '.join(MODELS[1:])}, got {model!r}",
            "model",
        )
    return body.rubber()


def _rubber(path: Path, raw: _FiniteFile, **chosen: str) -> RubberModel:
    """The ``[rubber]`` table's model with ``chosen`` (a swept model or volumetric) in place
    (:func:`rubber_of`; a refusal names its key); shape keys of another model than the one
    chosen are left out."""
    given = msgspec.structs.asdict(raw.rubber) | chosen
    model = given.pop("model") or "neo-hookean"
    if "model" in chosen:
        given = {k: v for k, v in given.items() if RUBBER_SHAPES.get(k, model) == model}
    try:
        return rubber_of(Material(raw.half_space.E2, raw.half_space.nu2), model, **given)
    except InputError as error:
        raise refused(path, error) from None


def _mesh(
    path: Path, table: str, raw: MeshTable, default: MeshSettings, nested: bool = False
) -> MeshSettings:
    settings = settings_of(path, table, raw, default)
    refine = 1.0 if raw.refine is None else raw.refine
    try:
        settings.refined(refine).check_size()
        if table == "numerics":  # the study's mesh is the finest (middle if nested) level
            check_ladder(settings, refine)
            if nested:  # the finest level: sizes / (2 refine)
                nested_ladder(settings.refined(refine))
        return settings.refined(refine)
    except InputError as error:
        raise StudyError(f"{path}: key '{table}': {error}") from None


def _curve(path: Path, raw: _FiniteFile, rubber: RubberModel) -> tuple[Interface, Geometry]:
    """The ``[contact]`` interface and friction and the ``[layer]`` of the study, checked as
    the problem's contact curve (:meth:`~shtaerman.problem.Problem.curve`: a lubricated
    rubber layer refused, in the file's words with this kind's way out); a layer's
    ``thickness_ratio`` resolved at the linear impact's a_c."""
    layer, contact = raw.layer, raw.contact
    indenter = indenter_of(path, raw.indenter)
    half_space = Material(raw.half_space.E2, raw.half_space.nu2)
    parts = {"interface": contact.interface, "friction": contact.friction}
    if layer is not None:
        exact = exact_impacts(raw.impact.mass, indenter, half_space)(raw.impact.velocity)
        spec = layer_spec(path, layer, None).resolved(float(exact.a_c))
        parts |= {"thickness": spec.thickness, "base": layer.base}
    try:
        problem = Problem.curve(indenter, half_space, **_body_keywords(rubber), **parts)
    except InputError as error:
        if error.parameter == "base":  # the Problem's other way out, a linear model, is not ours
            why = str(error).removeprefix("base: ").partition(": take ")[0]
            raise StudyError(
                f"{path}: key 'layer.base': {why}: take [layer] base = \"bonded\", or a study "
                f'of kind "contact" for a linear lubricated pad'
            ) from None
        raise refused(path, error) from None
    return problem.interface, problem.geometry


def _body_keywords(rubber: RubberModel) -> dict[str, Any]:
    """The :class:`~shtaerman.problem.Body` keywords of ``rubber``: its model, its own shape
    option and its volumetric energy."""
    shapes = {k: getattr(rubber, k) for k, owner in RUBBER_SHAPES.items() if owner == rubber.name}
    return {"model": rubber.name, "volumetric": rubber.volumetric, **shapes}


def _build(path: Path, raw: _FiniteFile) -> FiniteStudy:
    contact, quick, ladder = raw.contact, raw.quick, raw.numerics.ladder
    rubber = RubberModel() if _sweeps_model(raw) else _rubber(path, raw)
    interface, geometry = _curve(path, raw, rubber)
    return FiniteStudy(
        **named(path, raw),
        indenter=indenter_of(path, raw.indenter),
        half_space=Material(raw.half_space.E2, raw.half_space.nu2),
        mass=raw.impact.mass,
        velocity=raw.impact.velocity,
        ladder=Ladder(contact.reach, contact.depth_steps, contact.small_ratio, contact.small_steps),
        quick_ladder=Ladder(contact.reach, quick.depth_steps, quick.small_ratio, quick.small_steps),
        mesh=_mesh(path, "numerics", raw.numerics, FINITE_MESH, ladder == "nested"),
        quick_mesh=_mesh(path, "quick", quick, QUICK_FINITE_MESH),
        tolerances=raw.tolerances,
        quick_small_strain=quick.small_strain,
        rubber=rubber,
        mesh_ladder=ladder,
        corrections=_corrections(path, raw.corrections),
        interface=interface,
        geometry=geometry,
    )


def _number(value: object) -> bool:
    return isinstance(value, int | float) and not isinstance(value, bool)


def _corrections(path: Path, table: _Corrections | None) -> Corrections | None:
    """The ``[corrections]`` table checked: 1 to MAX_VELOCITIES velocities > 0 (m/s), and a
    density (kg/m^3) of a body with inertia (density2's range without the massless 0)."""
    if table is None:
        return None
    most, velocities = vocabulary.MAX_VELOCITIES, table.velocities
    numbers = all(_number(v) and v > 0 for v in velocities)
    if not (1 <= len(velocities) <= most and numbers and len(set(velocities)) == len(velocities)):
        raise StudyError(
            f"{path}: key 'corrections.velocities': expected a list of 1 to {most} distinct "
            f"velocities > 0 (m/s), got {velocities!r}"
        )
    valid = vocabulary.entry("density2").valid
    if not (_number(table.density2) and valid.low <= table.density2 <= valid.high):
        raise StudyError(
            f"{path}: key 'corrections.density2': expected a density in [{valid.low:g}, "
            f"{valid.high:g}] (kg/m^3, a body with inertia), got {table.density2!r}"
        )
    return Corrections(tuple(float(v) for v in velocities), float(table.density2))


def _sweeps_model(raw: _FiniteFile) -> bool:
    """Whether the ``[sweep]`` chooses the model (each study's rubber is built there)."""
    return raw.sweep is not None and raw.sweep.model is not None


def _expanded(path: Path, study: FiniteStudy, raw: _FiniteFile) -> list[FiniteStudy]:
    def change(key: str, value: Any) -> FiniteStudy:
        if key == "nu2":
            return replace(study, half_space=replace(study.half_space, poisson_ratio=value))
        if key in ("model", "volumetric"):
            return replace(study, rubber=_rubber(path, raw, **{key: value}))
        return replace(study, **{key: value})

    return swept(study, raw.sweep, change, SWEEPABLE)


def finite_study(*, takes_depths: bool = True, **values: Any) -> FiniteStudy:
    """The finite-strain study of ``values`` (:class:`FiniteStudy`'s fields; a sweep case's
    name, no description, source "sweep" by default), as every finite-strain study, a study
    file's (:func:`load_finite`) or a sweep case's, is checked: its profile's reach to its
    depths or ``reach`` x_c (:func:`~shtaerman.guards.check_profile_reach`), the finite-strain
    contact's (a study presses a rubber), as the API checks it; its refusal offers depths
    where the route ``takes_depths`` (a sweep does, a study file does not).

    Raises
    ------
    InputError
        Naming the parameter.
    """
    defaults = {"name": "case", "description": "", "source": Path("sweep")}
    study = FiniteStudy(**{**defaults, **values})
    modulus, impact = effective_modulus(RIGID, study.half_space), (study.mass, study.velocity)
    reach = study.ladder.reach
    note = DEPTHS_INSTEAD if takes_depths else ""
    layer = layer_depths(study.geometry, study.indenter, study.mesh, study.quick_mesh)
    check_profile_reach(study.indenter, modulus, study.depths, impact, reach, True, note, layer)
    return study


def load_finite(path: Path, data: dict[str, Any]) -> list[FiniteStudy]:
    """The studies of a parsed finite-strain study file (``kind`` removed).

    Raises
    ------
    StudyError
        Naming the file and the key, for any unknown key, wrong type or value out of range,
        or inputs the finite-strain FEM cannot run (n <= 1, nu2 < 0).
    """
    raw = decode(path, data, _FiniteFile, "finite-strain")
    studies = built(path, lambda: _expanded(path, _build(path, raw), raw))
    checked = [vars(study) for study in studies]  # the deepest depth: reach x_c

    def each() -> list[FiniteStudy]:  # a study file has no depths: its impact sets them
        return [finite_study(takes_depths=False, **s) for s in checked]

    return validated(path, built(path, each, PROFILE_KEYS))
