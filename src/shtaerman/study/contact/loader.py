"""The contact study file (the default kind): indenter, materials, depths, mesh, impact and the
tolerances that decide pass or fail.

A study file (``shtaerman init-study`` writes a commented one; see also ``fem/paper.toml``)
names every input as the vocabulary does (:mod:`shtaerman.vocabulary`: the CLI's words in
snake_case)::

    name = "paper"                       # optional; default: the file's stem (a plain name)
    description = "..."
    [indenter]   shape_coefficient = 5.0 (m^(1-n)), exponent = 1.5 (z = A r^n), or
                 sphere_radius = 0.01 (m; an exact sphere, Sneddon's law), or profile =
                 "tip.csv" (a tabulated z(r): r, z in m; relative to the study file)
    [striker]    E1 = 2e11 (Pa, or "inf" for rigid), nu1 = 0.25
    [half_space] E2 = 7.5e6 (Pa), nu2 = 0.5
    [impact]     mass = 0.7 (kg), velocity = 3.0 (m/s)
    [contact]    depths = "impact" (8 depths up to the impact's x_c) or a list in m;
                 interface = "frictionless" (default) or "bonded" (no slip at the indenter);
                 friction = mu (bonded only: Coulomb friction; default none, no slip)
    [numerics]   refine = K (divides the whole size field; default 1), mesh_size, mesh_margin,
                 domain_factor, growth, axis_size, axis_growth, max_dofs (optional, for experts)
    [quick]      the [numerics] keys for ``verify --quick``
    [tolerances] relative, in (0, 1]: force, beta, exponent, contact_radius, central_pressure,
                 impact
    [convergence] optional: sizes = [...] (smallest element / refined radius, decreasing): a
                 mesh-convergence study refining the whole mesh (``verify --quick``: the
                 coarsest three)
    [layer]      optional: a layer on a rigid base instead of the half-space: thickness (m)
                 or thickness_ratio (H / a_c, a_c the half-space contact radius at the
                 impact's x_c; in [0.05, 500]), and base = "bonded" (default) or "lubricated"
                 dynamic = true (optional, about 5 s per study) adds the dynamic FE impact
                 on the layer (rigid striker, [half_space] density2 = 1100 kg/m^3 by
                 default): its restitution, x_max and P_max
    [sweep]      optional: one parameter ("shape_coefficient", "exponent", "sphere_radius",
                 "mass", "velocity", "thickness", "thickness_ratio") and a list of values;
                 the study runs once per value (the power law's keys of a power law, the
                 sphere_radius of a sphere).

A vocabulary key may also be written at the top level (``E2 = 4e6``): it goes to its table.
The keys of earlier releases (``youngs_modulus``, ``[mesh] size``, ``[quick_mesh]``, ...) still
work for one release with a one-line :class:`~shtaerman.vocabulary.DeprecatedKeyWarning`
naming the new key; an unknown key names the likely one.

It is checked by the shared schema helpers (:mod:`shtaerman.study.schema`): every mistake raises
:class:`~shtaerman.study.schema.StudyError` naming the file, the key and what was expected.
"""

from __future__ import annotations

import itertools
from dataclasses import dataclass, field, replace
from pathlib import Path
from typing import Annotated, Any, Literal

import msgspec
import numpy as np

from ...fem.contact import check_contact_scale
from ...fem.mesh import INTERFACES, MeshSettings
from ...theory.materials import RIGID, Material, effective_modulus
from ...theory.profiles import SphereIndenter
from ...theory.sneddon import Indenter, contact_law
from ...validation import InputError
from ...vocabulary import entry
from ..dynamic.case import exact_impact
from ..schema import (
    EXPECTED,
    ImpactTable,
    IndenterTable,
    MaterialTable,
    MeshTable,
    Positive,
    Relative,
    StrikerTable,
    StudyError,
    SweepTable,
    Table,
    decode,
    indenter_of,
    ranged,
    validate_name,
    validated,
)
from .indentation import refined_radius
from .layer import LayerSpec, check_thickness

__all__ = [
    "QUICK_MESH",
    "LayerTable",
    "Study",
    "Tolerances",
    "check_profile_depths",
    "check_profile_reach",
    "layer_spec",
    "load_contact",
    "on_layer",
]

QUICK_MESH = MeshSettings(size=1 / 90, domain=1e4, growth=0.3, axis_size=1e-5, axis_growth=0.2)
"""Coarse mesh of ``verify --quick``."""

SYMBOLS = {
    "shape_coefficient": "A",
    "exponent": "n",
    "sphere_radius": "R",
    "mass": "M",
    "velocity": "v0",
    "thickness": "H",
    "thickness_ratio": "Ha",
}
"""Sweepable parameters and the symbol that names each expanded study."""


DEPTH_OVERSHOOT = 1.01
"""The FEM depths reach 1.01 x_c so the FEM-fed impacts interpolate, not extrapolate."""


class _Contact(Table):
    depths: list[Positive] | Literal["impact"] = "impact"
    interface: str = "frictionless"
    friction: Annotated[float, msgspec.Meta(ge=0)] | None = None

    def __post_init__(self) -> None:
        if self.interface not in INTERFACES:
            raise ValueError(f"interface: one of {list(INTERFACES)}")
        if self.depths != "impact" and (
            not 2 <= len(self.depths) <= entry("depths").max_items
            or any(b <= a for a, b in itertools.pairwise(self.depths))
        ):
            raise ValueError(f"depths: {EXPECTED['depths']}")


ThicknessRatio = ranged("thickness_ratio")


class LayerTable(Table):
    """``[layer]``: a layer on a rigid base (the contact and the dynamic study files)."""

    thickness: Positive | None = None
    thickness_ratio: ThicknessRatio | None = None
    base: Literal["bonded", "lubricated"] = "bonded"
    dynamic: bool = False


class _HalfSpace(MaterialTable):
    density2: Positive | None = None


class _Tolerances(Table):
    force: Relative = 1e-3
    beta: Relative = 1e-3
    exponent: Relative = 1e-3
    contact_radius: Relative = 1e-2
    central_pressure: Relative = 1e-2
    impact: Relative = 2e-3


class _Convergence(Table):
    sizes: list[Annotated[float, msgspec.Meta(gt=0, lt=1)]] = []  # noqa: RUF012 (a msgspec.Struct copies it)

    def __post_init__(self) -> None:
        if len(self.sizes) == 1 or any(b >= a for a, b in itertools.pairwise(self.sizes)):
            raise ValueError(f"sizes: {EXPECTED['sizes']}")


class _Sweep(SweepTable):
    shape_coefficient: list[Positive] | None = None
    exponent: list[Positive] | None = None
    sphere_radius: list[Positive] | None = None
    mass: list[Positive] | None = None
    velocity: list[Positive] | None = None
    thickness: list[Positive] | None = None
    thickness_ratio: list[ThicknessRatio] | None = None


class _StudyFile(Table):
    indenter: IndenterTable
    half_space: _HalfSpace
    impact: ImpactTable
    name: str | None = None
    description: str = ""
    striker: StrikerTable | None = None
    contact: _Contact = _Contact()
    numerics: MeshTable = MeshTable()
    quick: MeshTable = MeshTable()
    tolerances: _Tolerances = _Tolerances()
    convergence: _Convergence = _Convergence()
    layer: LayerTable | None = None
    sweep: _Sweep | None = None


@dataclass(frozen=True)
class Tolerances:
    """Relative tolerances that decide pass or fail."""

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
    indenter: Indenter
    """The striker's profile: z = A r^n, an exact sphere or a tabulated z(r)."""
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
    refine: float = 1.0
    """Refinement factor of the whole size field ([mesh] refine; the ladder adds K/2, K/sqrt2)."""
    kind: str = "contact"
    layer: LayerSpec | None = None
    """A layer on a rigid base instead of the half-space (resolved: thickness and H / a_c)."""


def _convergence_sizes(path: Path, raw: _StudyFile) -> tuple[float, ...]:
    """The convergence sizes, each level's mesh checked now (size guard, growth <= 1)."""
    base = raw.numerics.settings(MeshSettings(), "numerics")
    for size in raw.convergence.sizes:
        try:
            base.refined(base.size / size).check_size()
        except InputError as error:
            raise StudyError(f"{path}: key 'convergence.sizes': size {size!r}: {error}") from None
    return tuple(raw.convergence.sizes)


def _material(table: StrikerTable) -> Material:
    if table.E1 == "inf":
        return RIGID
    return Material(table.E1, table.nu1)


def _build(path: Path, raw: _StudyFile) -> Study:
    try:
        name = validate_name(raw.name if raw.name is not None else path.stem, "name")
    except InputError as error:
        raise StudyError(f"{path}: key 'name': {error}") from None
    return Study(
        name=name,
        description=raw.description,
        source=path,
        indenter=indenter_of(path, raw.indenter),
        striker=RIGID if raw.striker is None else _material(raw.striker),
        half_space=Material(raw.half_space.E2, raw.half_space.nu2),
        mass=raw.impact.mass,
        velocity=raw.impact.velocity,
        depths=None if raw.contact.depths == "impact" else tuple(raw.contact.depths),
        mesh=raw.numerics.settings(MeshSettings(), "numerics"),
        quick_mesh=raw.quick.settings(QUICK_MESH, "quick"),
        tolerances=Tolerances(**msgspec.structs.asdict(raw.tolerances)),
        convergence_sizes=_convergence_sizes(path, raw),
        refine=1.0 if raw.numerics.refine is None else raw.numerics.refine,
        layer=_layer(path, raw),
    )


def _layer(path: Path, raw: _StudyFile) -> LayerSpec | None:
    """The study file's layer as given (thickness or H / a_c, unresolved), or None."""
    layer, swept = raw.layer, raw.sweep.chosen()[0] if raw.sweep is not None else None
    swept = swept if swept in ("thickness", "thickness_ratio") else None
    density = raw.half_space.density2
    if density is not None and not (layer is not None and layer.dynamic):
        raise StudyError(
            f"{path}: key 'half_space.density2': applies to the dynamic impact on a layer only; "
            "give layer.dynamic = true too"
        )
    if layer is None and swept is None:
        return None
    if raw.convergence.sizes:
        raise StudyError(
            f"{path}: key 'convergence': expected no mesh-convergence study on a layer (it "
            "measures errors against Shtaerman's half-space, from which a layer departs; the "
            "3-mesh ladder gives a layer's error estimates)"
        )
    spec = layer_spec(path, layer, swept)
    return spec if density is None else replace(spec, density=density)


def layer_spec(path: Path, layer: LayerTable | None, swept: str | None) -> LayerSpec:
    """The layer of a ``[layer]`` table (unresolved), its thickness given exactly once: in
    the table (m or H / a_c) or as the swept key ``swept``; :class:`StudyError` otherwise."""
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
    return LayerSpec(layer.thickness, layer.thickness_ratio, layer.base, layer.dynamic)


def on_layer(study: Study) -> Study:
    """``study`` with its layer resolved (H and H / a_c at its impact's x_c) and meshed.

    Raises
    ------
    InputError
        If the thickness is outside what the mesh resolves at the study's deepest depth.
    """
    if study.layer is None:
        return study

    modulus = effective_modulus(study.striker, study.half_space)
    exact = exact_impact(study.mass, study.velocity, contact_law(study.indenter, modulus))
    layer = study.layer.resolved(float(exact.a_c))
    deepest = study.depths[-1] if study.depths else DEPTH_OVERSHOOT * exact.x_c
    mesh, quick = layer.on(study.mesh), layer.on(study.quick_mesh)
    if not study.depths:  # the impact's x_c set them: a huge one names mass and velocity
        radius = refined_radius(study.indenter, np.array([deepest]), mesh)
        check_contact_scale(study.half_space.youngs_modulus, radius, (study.mass, study.velocity))
    for settings in (mesh, quick):
        check_thickness(settings, study.indenter, deepest)
    return replace(study, layer=layer, mesh=mesh, quick_mesh=quick)


def _with_interface(path: Path, study: Study, raw: _StudyFile) -> Study:
    """``study`` with the indenter's surface ([contact] interface) in each of its meshes."""
    if raw.contact.friction is not None and raw.contact.interface != "bonded":
        raise StudyError(
            f"{path}: key 'contact.friction': applies to a bonded indenter only; give "
            'interface = "bonded" too'
        )
    surface = {"interface": raw.contact.interface, "friction": raw.contact.friction}
    return replace(
        study, mesh=replace(study.mesh, **surface), quick_mesh=replace(study.quick_mesh, **surface)
    )


def _expanded(study: Study, sweep: _Sweep | None) -> list[Study]:
    if sweep is None:
        return [on_layer(study)]
    key, values = sweep.chosen()
    studies = []
    for value in values:
        if key in ("shape_coefficient", "exponent"):
            changed = replace(study, indenter=replace(study.indenter, **{key: value}))
        elif key == "sphere_radius":
            changed = replace(study, indenter=SphereIndenter(value))
        elif key in ("thickness", "thickness_ratio"):
            changed = replace(study, layer=replace(study.layer, **{key: value}))
        else:
            changed = replace(study, **{key: value})
        changed = on_layer(replace(changed, name=f"{study.name}-{SYMBOLS[key]}{value:g}"))
        studies.append(changed)
    return studies


SWEPT_PROFILES = {
    "shape_coefficient": "power-law",
    "exponent": "power-law",
    "sphere_radius": "sphere",
}
"""A swept key of the striker's profile -> the [indenter] it varies."""


def _check_swept_profile(path: Path, raw: _StudyFile) -> None:
    """Refuse a [sweep] of a profile key the [indenter] does not have (the power law's keys of
    a sphere or a table, sphere_radius of another profile), naming the swept key."""
    key = raw.sweep.chosen()[0] if raw.sweep is not None else None
    if key not in SWEPT_PROFILES:
        return
    kind = indenter_of(path, raw.indenter).kind
    if kind != SWEPT_PROFILES[key]:
        raise StudyError(
            f"{path}: key 'sweep.{key}': varies a {SWEPT_PROFILES[key]} striker, but "
            f"[indenter] is a {kind} one; sweep a key of its own profile or change [indenter]"
        )


def check_profile_reach(
    indenter: Indenter,
    modulus: float,
    depths: tuple[float, ...] | None,
    impact: tuple[float, float],
    overshoot: float = DEPTH_OVERSHOOT,
) -> None:
    """Refuse, before any work, a sphere's or a table's deepest depth (the last of ``depths``
    m, or ``overshoot`` x_c of the ``impact``, mass kg at velocity m/s, on E* = ``modulus``
    Pa) beyond what its FE profile is: a sphere's radius (its equator; beyond it the FE
    profile is flat) or a table's last row.

    Raises
    ------
    InputError
        Naming ``depths`` where they were given, else ``sphere_radius`` or ``profile``.
    """
    if indenter.kind == "power-law":
        return
    law = contact_law(indenter, modulus)
    if depths is not None:
        deepest, parameter = depths[-1], "depths"
        drive = f"depth {deepest:.6g} m"
    else:
        parameter = "sphere_radius" if indenter.kind == "sphere" else "profile"
        deepest = overshoot * exact_impact(*impact, law).x_c  # a table's names profile
        drive = (
            f"{impact[0]:g} kg at {impact[1]:g} m/s drive the striker to about {deepest:.3g} m "
            f"({overshoot:g} x_c, the deepest depth)"
        )
    if indenter.kind == "sphere" and deepest >= indenter.radius:
        raise InputError(
            f"{parameter}: {drive}, beyond the sphere's radius {indenter.radius:.6g} m (its "
            "equator, past which the FE profile is no sphere); give depths below the radius, "
            "a larger sphere, or a lower mass or velocity",
            parameter,
        )
    try:
        law.contact_radius(deepest)  # a table's contact within its last row
    except InputError as error:
        text = str(error).removeprefix(f"{error.parameter}: ")
        said = depths is not None and text.startswith(f"depth {deepest:.6g} m ")  # the table's
        raise InputError(f"{parameter}: {'' if said else drive + ': '}{text}", parameter) from None


PROFILE_KEYS = {
    "depths": "contact.depths",
    "sphere_radius": "indenter.sphere_radius",
    "profile": "indenter.profile",
}
"""A parameter of :func:`check_profile_reach`'s refusal -> its study-file key."""


def check_profile_depths(path: Path, indenter: Indenter, *reach: Any) -> None:
    """:func:`check_profile_reach` (its arguments after ``indenter``) in a study file: the
    refusal names the file and the key."""
    try:
        check_profile_reach(indenter, *reach)
    except InputError as error:
        text = str(error).removeprefix(f"{error.parameter}: ")
        raise StudyError(f"{path}: key '{PROFILE_KEYS[error.parameter]}': {text}") from None


def load_contact(path: Path, data: dict[str, Any]) -> list[Study]:
    """The studies of a parsed contact study file (the default kind)."""
    raw = decode(path, data, _StudyFile)
    _check_swept_profile(path, raw)
    try:
        studies = _expanded(_with_interface(path, _build(path, raw), raw), raw.sweep)
    except StudyError:
        raise
    except InputError as error:
        raise StudyError(f"{path}: {error}") from None
    for study in studies:
        modulus = effective_modulus(study.striker, study.half_space)
        impact = (study.mass, study.velocity)
        check_profile_depths(path, study.indenter, modulus, study.depths, impact)
    return validated(path, studies)
