"""The contact study file (the default kind): indenter, materials, depths, mesh, impact and the
tolerances that decide pass or fail.

``shtaerman init-study --kind contact`` writes every key of it, commented (see also
``fem/paper.toml``); the keys are the vocabulary's (:mod:`shtaerman.vocabulary`: the CLI's
words in snake_case), read and checked by the shared schema (:mod:`shtaerman.study.schema`):
every mistake raises :class:`~shtaerman.study.schema.StudyError` naming the file, the key and
what was expected. A ``[sweep]`` of one key ("shape_coefficient", "exponent",
"sphere_radius", "mass", "velocity", "thickness", "thickness_ratio") runs the study once per
value.
"""

from __future__ import annotations

import itertools
from dataclasses import dataclass, field, replace
from pathlib import Path
from typing import Annotated, Any, Literal

import msgspec
import numpy as np

from ...fem.mesh import HALF_SPACE, Geometry, MeshSettings
from ...guards import DEPTHS_INSTEAD, check_profile_reach
from ...problem import Interface, Problem
from ...theory.materials import RIGID, Material, effective_modulus
from ...theory.profiles import SphereIndenter
from ...theory.sneddon import Indenter, contact_law
from ...theory.viscoelastic import elastic_impact
from ...validation import InputError
from ...vocabulary import entry
from ..schema import (
    EXPECTED,
    LayerTable,
    MaterialTable,
    MeshTable,
    Named,
    Positive,
    Relative,
    StrikerTable,
    StudyError,
    StudyFile,
    SweepTable,
    Table,
    built,
    decode,
    indenter_of,
    layer_spec,
    named,
    prony_of,
    ranged,
    refused,
    settings_of,
    swept,
    validated,
)
from .indentation import check_force_range, refined_radius
from .layer import LayerSpec, check_thickness, layer_depths

__all__ = [
    "QUICK_MESH",
    "Study",
    "Tolerances",
    "contact_study",
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
    rate: ranged("rate") | None = None  # type: ignore[valid-type]

    def __post_init__(self) -> None:
        if self.depths != "impact" and (
            not 2 <= len(self.depths) <= entry("depths").max_items
            or any(b <= a for a, b in itertools.pairwise(self.depths))
        ):
            raise ValueError(f"depths: {EXPECTED['depths']}")


ThicknessRatio = ranged("thickness_ratio")


class _HalfSpace(MaterialTable):
    density2: Positive | None = None
    prony: str | None = None


class Tolerances(Table):
    """Relative tolerances that decide pass or fail (``impact``: x_c, P_c and t_c of the
    FEM-fed impacts against the exact one)."""

    force: Relative = 1e-3
    beta: Relative = 1e-3
    exponent: Relative = 1e-3
    contact_radius: Relative = 1e-2
    central_pressure: Relative = 1e-2
    impact: Relative = 2e-3
    identity: Relative = 3e-3
    """A bonded indenter's no-slip identity P (n+1) / (2 E* a d n) = chi(nu2), beside the
    ladder's estimates of the force and the contact radius (:mod:`.interface`; measured
    departures: benchmarks/FEM_NOTES.md, "Study error estimates")."""


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


class _StudyFile(StudyFile):
    half_space: _HalfSpace
    striker: StrikerTable | None = None
    contact: _Contact = _Contact()
    numerics: MeshTable = MeshTable()
    quick: MeshTable = MeshTable()
    tolerances: Tolerances = Tolerances()
    convergence: _Convergence = _Convergence()
    layer: LayerTable | None = None
    sweep: _Sweep | None = None


@dataclass(frozen=True)
class Study(Named):
    """One cross-check: a contact curve and the impact it implies (SI units)."""

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
    interface: Interface = field(default_factory=Interface)
    """The indenter's surface: frictionless, bonded, or Coulomb's friction."""

    @property
    def geometry(self) -> Geometry:
        """The body's shape: the half-space, or the (resolved) layer."""
        return HALF_SPACE if self.layer is None else self.layer.geometry


def _mesh(path: Path, table: str, raw: MeshTable, default: MeshSettings) -> MeshSettings:
    """The mesh of ``[table]`` over ``default`` (unrefined), its refined size checked now."""
    settings = settings_of(path, table, raw, default)
    try:
        settings.refined(1.0 if raw.refine is None else raw.refine).check_size()
    except InputError as error:
        raise StudyError(f"{path}: key '{table}': {error}") from None
    return settings


def _convergence_sizes(path: Path, raw: _StudyFile) -> tuple[float, ...]:
    """The convergence sizes, each level's mesh checked now (size guard, growth <= 1)."""
    base = settings_of(path, "numerics", raw.numerics, MeshSettings())
    for size in raw.convergence.sizes:
        try:
            base.refined(base.size / size).check_size()
        except InputError as error:
            raise StudyError(f"{path}: key 'convergence.sizes': size {size!r}: {error}") from None
    return tuple(raw.convergence.sizes)


VISCOELASTIC = (
    "a contact study feeds its curve to the quasi-static impact M x'' = -P(x), and a "
    "viscoelastic body's force depends on the history of the pressing, not on the depth "
    "alone: run shtaerman contact --prony ... --rate ... for the curve (against Lee-Radok), "
    'or a study of kind = "dynamic" with [half_space] prony for the impact'
)
"""Why a contact study refuses ``[half_space] prony`` (the command line's curve takes it)."""


def _surface(path: Path, raw: _StudyFile) -> Interface:
    """The indenter's surface of the study, its curve's parts (interface, friction, prony,
    rate) checked as the problem's contact curve (:meth:`~shtaerman.problem.Problem.curve`,
    refusals in the file's words); a viscoelastic body refused (:data:`VISCOELASTIC`)."""
    contact, half_space = raw.contact, raw.half_space
    parts = {"interface": contact.interface, "friction": contact.friction}
    parts |= {"prony": prony_of(path, half_space.prony, half_space.E2), "rate": contact.rate}
    try:
        parts["striker"] = _striker(raw)
        body = Material(half_space.E2, half_space.nu2)
        problem = Problem.curve(indenter_of(path, raw.indenter), body, **parts)
    except InputError as error:
        raise refused(path, error) from None
    if problem.body.prony is not None:
        raise StudyError(f"{path}: key 'half_space.prony': {VISCOELASTIC}")
    return problem.interface


def _check_checkable(path: Path, raw: _StudyFile, surface: Interface) -> None:
    """Refuse, for a bonded or Coulomb indenter on nu2 < 0.5 (whose solution Shtaerman's, or
    Sneddon's, frictionless law is not: :mod:`.interface`), another profile than z = A r^n
    (its checks, the exponent and the no-slip identity, are the self-similar power law's) and
    a mesh-convergence study (it measures errors against the frictionless law). A layer's
    checks are its own (:func:`.layer.layer_checks`), for every interface."""
    swept = raw.sweep.chosen()[0] if raw.sweep is not None else None
    if raw.layer is not None or swept in ("thickness", "thickness_ratio"):
        return
    if surface.coefficient in (None, 0.0) or raw.half_space.nu2 == 0.5:
        return
    if raw.convergence.sizes:
        raise StudyError(
            f"{path}: key 'convergence': expected no mesh-convergence study of a bonded or "
            "Coulomb indenter on nu2 < 0.5 (it measures errors against Shtaerman's "
            "frictionless solution, from which the interface departs; the 3-mesh ladder gives "
            "its error estimates)"
        )
    if raw.indenter.sphere_radius is not None or raw.indenter.profile is not None:
        raise StudyError(
            f"{path}: key 'contact.interface': a bonded or Coulomb indenter on nu2 < 0.5 takes "
            "a power-law [indenter] (its checks are the self-similar z = A r^n's); give "
            'interface = "frictionless" or nu2 = 0.5'
        )


def _striker(raw: _StudyFile) -> Material:
    """The striker's elasticity of ``[striker]`` (rigid without it, or with E1 = "inf")."""
    striker = raw.striker
    rigid = striker is None or striker.E1 == "inf"
    return RIGID if rigid else Material(striker.E1, striker.nu1)


def _build(path: Path, raw: _StudyFile) -> Study:
    contact = raw.contact
    surface = _surface(path, raw)
    _check_checkable(path, raw, surface)
    mesh, quick = (
        _mesh(path, key, getattr(raw, key), default)
        for key, default in (("numerics", MeshSettings()), ("quick", QUICK_MESH))
    )
    return Study(
        **named(path, raw),
        indenter=indenter_of(path, raw.indenter),
        striker=_striker(raw),
        half_space=Material(raw.half_space.E2, raw.half_space.nu2),
        mass=raw.impact.mass,
        velocity=raw.impact.velocity,
        depths=None if contact.depths == "impact" else tuple(contact.depths),
        mesh=mesh,
        quick_mesh=quick,
        tolerances=raw.tolerances,
        convergence_sizes=_convergence_sizes(path, raw),
        refine=1.0 if raw.numerics.refine is None else raw.numerics.refine,
        layer=_layer(path, raw),
        interface=surface,
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


def on_layer(study: Study) -> Study:
    """``study`` with its layer resolved (H and H / a_c at its impact's x_c) and meshed.

    Raises
    ------
    InputError
        If the thickness is outside what the mesh resolves at the study's deepest depth.
    """
    if study.layer is None:
        return study

    law = contact_law(study.indenter, effective_modulus(study.striker, study.half_space))
    exact = elastic_impact(study.mass, study.velocity, law)
    layer = study.layer.resolved(float(exact.a_c))

    def refined_at(velocity: float | None) -> list[float]:
        """The refined radius (m) of each mesh at the deepest depth: the study's (None), or
        its impact's at ``velocity`` m/s."""
        deepest = study.depths[-1] if study.depths else DEPTH_OVERSHOOT * exact.x_c
        if velocity not in (None, study.velocity):
            deepest = DEPTH_OVERSHOOT * elastic_impact(study.mass, velocity, law).x_c
        meshes, at = (study.mesh, study.quick_mesh), np.array([deepest])
        return [refined_radius(study.indenter, at, mesh, layer.geometry) for mesh in meshes]

    # a velocity fits a thickness given in m, not one given as H / a_c (that moves with it)
    moves = study.layer.thickness is not None and not study.depths
    exponent = getattr(study.indenter, "exponent", 2.0)
    velocity = study.velocity if moves else None
    check_thickness(layer.thickness, refined_at, velocity, exponent, "at this study's depths")
    return replace(study, layer=layer)


def _expanded(path: Path, study: Study, sweep: _Sweep | None) -> list[Study]:
    key = sweep.chosen()[0] if sweep is not None else None
    if key in SWEPT_PROFILES and study.indenter.kind != SWEPT_PROFILES[key]:
        raise StudyError(
            f"{path}: key 'sweep.{key}': varies a {SWEPT_PROFILES[key]} striker, but "
            f"[indenter] is a {study.indenter.kind} one; sweep a key of its own profile or "
            "change [indenter]"
        )

    def change(key: str, value: float) -> Study:
        if key in ("shape_coefficient", "exponent"):
            return replace(study, indenter=replace(study.indenter, **{key: value}))
        if key == "sphere_radius":
            return replace(study, indenter=SphereIndenter(value))
        if key in ("thickness", "thickness_ratio"):
            return replace(study, layer=replace(study.layer, **{key: value}))
        return replace(study, **{key: value})

    return swept(study, sweep, change, SYMBOLS)


SWEPT_PROFILES = {
    "shape_coefficient": "power-law",
    "exponent": "power-law",
    "sphere_radius": "sphere",
}
"""A swept key of the striker's profile -> the [indenter] it varies."""


def contact_study(*, takes_depths: bool = True, **values: Any) -> Study:
    """The contact study of ``values`` (:class:`Study`'s fields; a sweep case's name, no
    description, source "sweep" by default), as every contact study, a study file's
    (:func:`load_contact`) or a sweep case's, is checked and resolved: its profile's reach
    (:func:`check_profile_reach`, its refusal offering depths where the route
    ``takes_depths``: a study file does, a layer sweep does not), then its layer
    (:func:`on_layer`).

    Raises
    ------
    InputError
        Naming the parameter.
    """
    study = Study(**{"name": "case", "description": "", "source": Path("sweep"), **values})
    modulus = effective_modulus(study.striker, study.half_space)
    impact = (study.mass, study.velocity)
    note = DEPTHS_INSTEAD if takes_depths else ""
    absolute = study.layer is not None and study.layer.thickness is not None  # not H / a_c
    meshes = (study.mesh, study.quick_mesh)
    layer = layer_depths(study.layer.geometry, study.indenter, *meshes) if absolute else None
    reach = (DEPTH_OVERSHOOT, False, note, layer)
    check_profile_reach(study.indenter, modulus, study.depths, impact, *reach)
    if study.depths is not None:  # the command line's check of given depths
        check_force_range(study.indenter, study.half_space, study.depths)
    return on_layer(study)


PROFILE_KEYS = (
    "depths",
    "sphere_radius",
    "profile",
    "thickness",
    "mass",
    "velocity",
    "shape_coefficient",
)
"""The parameters a refusal of :func:`contact_study` names (its profile's reach, a power
law's impact beyond it: :func:`shtaerman.guards.check_reach`; its layer's thickness:
:func:`on_layer`)."""


def load_contact(path: Path, data: dict[str, Any]) -> list[Study]:
    """The studies of a parsed contact study file (the default kind)."""
    raw = decode(path, data, _StudyFile, "contact")
    studies = built(path, lambda: _expanded(path, _build(path, raw), raw.sweep))
    checked = [vars(study) for study in studies]  # then each checked and resolved
    return validated(path, built(path, lambda: [contact_study(**s) for s in checked], PROFILE_KEYS))
