"""The dynamic study file: one striker and half-space, the impact at several approach velocities.

A study (kind ``dynamic``, e.g. ``fem/dynamic.toml``) runs a case (:func:`.case.run_case`) per
approach velocity (:mod:`.runner`)::

    kind = "dynamic"
    name = "dynamic"                      # optional; default: the file's stem
    description = "..."
    [indenter]   shape_coefficient = 5.0 (m^(1-n)), exponent = 1.5 (> 1; the striker is rigid),
                 or sphere_radius = 0.01 (m), or profile = "tip.csv" (r, z in m; relative to
                 the study file)
    [half_space] E2 = 7.5e6 (Pa), nu2 = 0.5 (in [0, 0.5]), density2 = 1100 (kg/m^3; 0:
                 massless), prony = "g1:tau1,g2:tau2,..." (optional: a viscoelastic
                 half-space, E2 and nu2 its instantaneous values; tau in s; or any form of
                 :func:`shtaerman.theory.prony_sources.prony_from_text`, e.g. a shipped name)
    [layer]      optional, as in a contact study: a layer on a rigid base instead of the
                 half-space: thickness (m) or thickness_ratio (H / a_c, a_c the half-space
                 contact radius at the quasi-static x_c of figure_velocity), base = "bonded"
                 (default) or "lubricated"
    [impact]     mass = 0.7 (kg), velocity = 3.0 or [...] (m/s, increasing),
                 figure_velocity = 3.0 (optional; m/s, one of the velocities: the figures and
                 the findings; default: the middle one, the upper of two),
                 interface = "frictionless" (default) or "bonded" (no slip at the striker),
                 friction = mu (bonded only: Coulomb friction; default none, no slip)
    [rubber]     optional: model = "linear" (default) or a rubber at finite strain
                 ("neo-hookean", "mooney-rivlin", "yeoh", "gent": the impact of
                 ``shtaerman dynamic --model``), mooney_ratio, yeoh = [c2, c3], gent_limit,
                 volumetric (:func:`shtaerman.fem.rubber.rubber_model`); a rubber's
                 [numerics] and [quick] take time_steps, mesh_size and refine only
    [numerics]   time_steps, mesh_size, mesh_margin, domain_factor, growth, axis_size,
                 layer_rate and the other DynamicSettings fields, optional; refine = K
                 divides the mesh sizes and the time step by K after them
    [quick]      velocity = [...] (must hold figure_velocity; default: the smallest velocity
                 and figure_velocity) and the numerics of ``verify --quick`` (default:
                 [numerics])
    [tolerances] energy_balance = 1e-2 (of M v0^2/2), reflected = 1e-2 (of the radiated),
                 estimate = 0.2 (measured loss / first-order estimate - 1, checked where the
                 estimate is below estimate_below = 0.08)
    [sweep]      optional, with a prony: loss = ["waves", "hysteresis", "both"] (any of them,
                 in order) splits the study into one per loss, named <name>-<loss>: waves is
                 the elastic half-space with density2 (no prony), hysteresis the massless one
                 (density2 = 0) with the prony, both the file as written
"""

from __future__ import annotations

import dataclasses
import itertools
from dataclasses import dataclass, field
from pathlib import Path
from typing import Annotated, Any

import msgspec

from ...fem.contact import validate_fem_inputs
from ...fem.dynamic_contact import (
    MAX_DOFS,
    MAX_SIZE,
    DynamicSettings,
    estimate_dofs,
)
from ...fem.mesh_budget import growth_error
from ...fem.viscoelastic import prony_input
from ...problem import RUBBER_OPTIONS, Problem
from ...theory.materials import RIGID, Material, effective_modulus, validate_density
from ...theory.sneddon import Indenter, contact_law
from ...theory.viscoelastic import PronySeries
from ...validation import InputError, shown
from ...vocabulary import entry
from ..contact.loader import LayerTable, layer_spec
from ..schema import (
    SETTINGS_FIELDS,
    IndenterTable,
    Poisson,
    Positive,
    Relative,
    StudyError,
    Table,
    decode,
    fem_input_error,
    indenter_of,
    ranged,
    validate_name,
)
from .accuracy import check_ladder
from .case import exact_impact

__all__ = ["DynamicStudy", "DynamicTolerances", "dynamic_check_failures", "load_dynamic"]


class _DynHalfSpace(Table):
    E2: Positive
    nu2: Poisson
    density2: Annotated[float, msgspec.Meta(ge=0)]  # 0: massless
    prony: str | None = None


class _Numerics(Table):
    refine: Positive | None = None
    time_steps: ranged("time_steps", "dynamic") | None = None
    mesh_margin: Positive | None = None
    mesh_size: Positive | None = None
    axis_size: Positive | None = None
    growth: Positive | None = None
    domain_factor: Positive | None = None
    layer_start: Positive | None = None
    layer_ramp: Positive | None = None
    layer_rate: ranged("layer_rate", "dynamic") | None = None
    tail: Annotated[float, msgspec.Meta(ge=0)] | None = None
    layer_width: Positive | None = None
    spectral_radius: Annotated[float, msgspec.Meta(ge=0, le=1)] | None = None


class _DynImpact(Table):
    mass: Positive
    velocity: Positive | list[Positive]
    figure_velocity: Positive | None = None
    interface: str = "frictionless"
    friction: Annotated[float, msgspec.Meta(ge=0)] | None = None


class RubberTable(Table):
    model: str = "linear"
    mooney_ratio: float | None = None
    yeoh: list[float] | None = None
    gent_limit: float | None = None
    volumetric: str | None = None


class _Quick(_Numerics):
    velocity: Positive | list[Positive] | None = None


class _DynTolerances(Table):
    energy_balance: Relative = 1e-2
    reflected: Relative = 1e-2
    estimate: Relative = 0.2
    estimate_below: Relative = 0.08


LOSSES = ("waves", "hysteresis", "both")
"""The losses a ``[sweep] loss`` list may hold: one study each."""


class _DynSweep(Table):
    loss: list[str]


class _DynamicFile(Table):
    indenter: IndenterTable
    half_space: _DynHalfSpace
    impact: _DynImpact
    name: str | None = None
    description: str = ""
    numerics: _Numerics = _Numerics()
    quick: _Quick = _Quick()
    tolerances: _DynTolerances = _DynTolerances()
    layer: LayerTable | None = None
    rubber: RubberTable = RubberTable()
    sweep: _DynSweep | None = None


@dataclass(frozen=True)
class DynamicTolerances:
    """Pass/fail limits of a dynamic study."""

    energy_balance: float = 1e-2
    """Largest energy balance error, of the initial kinetic energy."""
    reflected: float = 1e-2
    """Largest reflected energy, of the radiated energy."""
    estimate: float = 0.2
    """Largest |measured loss / first-order estimate - 1| ..."""
    estimate_below: float = 0.08
    """... checked where the estimated fraction is below this (first order in it)."""


@dataclass(frozen=True)
class DynamicStudy:
    """A dynamic study: one striker and half-space, several approach velocities (SI units)."""

    name: str
    description: str
    source: Path
    indenter: Indenter
    half_space: Material
    density: float
    mass: float
    velocities: tuple[float, ...]
    example: float
    """The velocity of the figures and the findings (one of ``velocities``)."""
    settings: DynamicSettings
    quick_velocities: tuple[float, ...]
    quick_settings: DynamicSettings
    tolerances: DynamicTolerances = field(default_factory=DynamicTolerances)
    kind: str = "dynamic"
    prony: PronySeries | None = None
    """Shear relaxation of the half-space (None: elastic)."""
    prony_text: str = ""
    """``prony`` as written in the file."""
    physics: dict[str, Any] = field(default_factory=dict)
    """The problem's parts besides the striker and the body's elasticity, as keywords of
    :meth:`shtaerman.problem.Problem.impact` (model, rubber options, interface, friction)."""
    finite_numerics: dict[str, Any] = field(default_factory=dict)
    """A rubber's numerical keywords of :func:`shtaerman.dynamic` (time_steps, mesh_size,
    refine; None: the finite-strain impact's default), and ``quick`` those of ``verify
    --quick``."""
    quick_finite_numerics: dict[str, Any] = field(default_factory=dict)

    def problem(self, velocity: float) -> Problem:
        """The impact at ``velocity`` m/s (:class:`shtaerman.problem.Problem`)."""
        layer = self.settings.thickness
        geometry = {} if layer is None else {"thickness": layer, "base": self.settings.base}
        return Problem.impact(
            self.indenter,
            Material(self.half_space.youngs_modulus, self.half_space.poisson_ratio, self.density),
            mass=self.mass,
            velocity=velocity,
            prony=self.prony,
            **geometry,
            **self.physics,
        )

    @property
    def finite(self) -> bool:
        """Whether the body is a rubber at finite strain."""
        return self.physics.get("model", "linear") != "linear"


def _settings(path: Path, table: str, raw: _Numerics, base: DynamicSettings) -> DynamicSettings:
    """``base`` with the table's numerics; an invalid value names its key."""
    keys = {SETTINGS_FIELDS.get(k, k): k for k in _Numerics.__struct_fields__}
    given = {
        setting: getattr(raw, key)
        for setting, key in keys.items()
        if getattr(raw, key) is not None and setting in DynamicSettings.__dataclass_fields__
    }
    for setting, value in given.items():
        try:
            dataclasses.replace(base, **{setting: value})
        except InputError as error:
            raise StudyError(f"{path}: key '{table}.{keys[setting]}': {error}") from None
    try:
        settings = dataclasses.replace(base, **given)
        if raw.refine is not None:
            settings = settings.refined(raw.refine)
    except InputError as error:
        raise StudyError(f"{path}: key '{table}': {error}") from None
    dofs = estimate_dofs(settings)
    blamed = growth_error(settings, estimate_dofs, MAX_DOFS, MAX_SIZE) if dofs > MAX_DOFS else None
    if blamed is not None:
        raise StudyError(f"{path}: key '{table}.growth': {str(blamed).removeprefix('growth: ')}")
    if dofs > MAX_DOFS:
        raise StudyError(
            f"{path}: key '{table}.mesh_size': the mesh would have about {dofs:.3g} "
            f"dofs, above the limit {MAX_DOFS}; coarsen size or growth"
        )
    return settings


def _layer(
    path: Path, raw: _DynamicFile, example: float, indenter: Indenter, body: Material
) -> DynamicSettings:
    """The default settings on the file's ``[layer]`` (none: the half-space), H / a_c
    resolved at the quasi-static impact of ``example`` m/s of ``indenter`` on the half-space
    of ``body``."""
    if raw.layer is None:
        return DynamicSettings()
    if raw.layer.dynamic:
        raise StudyError(
            f"{path}: key 'layer.dynamic': applies to a contact study (a dynamic study is one)"
        )
    spec = layer_spec(path, raw.layer, None)
    half_space = contact_law(indenter, effective_modulus(RIGID, body))
    spec = spec.resolved(float(exact_impact(raw.impact.mass, example, half_space).a_c))
    try:
        return DynamicSettings(thickness=spec.thickness, base=spec.base)
    except InputError as error:
        raise StudyError(f"{path}: key 'layer': {error}") from None


def _moved_layer(path: Path, data: dict[str, Any]) -> None:
    """Refuse the layer keys under ``[half_space]``: a layer is the ``[layer]`` table."""
    body = data.get("half_space")
    for key in ("thickness", "base"):
        if isinstance(body, dict) and key in body:
            raise StudyError(
                f"{path}: key 'half_space.{key}': the layer is the [layer] table, as in a "
                "contact study: thickness (m) or thickness_ratio (H / a_c), and base"
            )


def _velocities(
    path: Path, key: str, given: float | list[float], example: float | None
) -> tuple[float, ...]:
    """The velocities of ``key`` (one value or an increasing list), holding ``example``."""
    values = given if isinstance(given, list) else [given]
    most = entry("velocity").max_items
    if not 0 < len(values) <= most or any(b <= a for a, b in itertools.pairwise(values)):
        raise StudyError(
            f"{path}: key '{key}': expected a velocity > 0 (m/s) or a list of at most {most} "
            f"increasing ones, got {shown(given)}"
        )
    if example is not None and example not in values:
        raise StudyError(
            f"{path}: key '{key}': expected to hold impact.figure_velocity = {example!r} m/s, "
            f"got {given!r}"
        )
    return tuple(values)


def load_dynamic(path: Path, data: dict[str, Any]) -> list[DynamicStudy]:
    """The study of a parsed ``kind = "dynamic"`` file; :class:`StudyError` names file and key."""
    _moved_layer(path, data)
    raw: _DynamicFile = decode(path, data, _DynamicFile)
    try:
        name = validate_name(raw.name if raw.name is not None else path.stem, "name")
    except InputError as error:
        raise StudyError(f"{path}: key 'name': {error}") from None
    indenter = indenter_of(path, raw.indenter)
    half_space = Material(raw.half_space.E2, raw.half_space.nu2)
    try:
        validate_fem_inputs(indenter, half_space)
        validate_density("density2", raw.half_space.density2)
    except InputError as error:
        raise fem_input_error(path, error) from None
    try:
        prony = prony_input(_beside(path, raw.half_space.prony))
    except InputError as error:
        raise StudyError(f"{path}: key 'half_space.prony': {error}") from None
    example = raw.impact.figure_velocity
    velocities = _velocities(path, "impact.velocity", raw.impact.velocity, example)
    if example is None:  # the middle velocity (of two, the upper)
        example = velocities[len(velocities) // 2]
    quick = raw.quick.velocity
    if quick is None:  # the smallest velocity and the example (or the example and the largest)
        quick = sorted({velocities[0], example} if example != velocities[0] else velocities[:2])
    defaults = _layer(path, raw, example, indenter, half_space)
    settings = _settings(path, "numerics", raw.numerics, defaults)
    physics = _physics(raw)
    if physics.get("model", "linear") == "linear":
        try:
            check_ladder(settings)  # the full study runs the ladder; verify --quick does not
        except InputError as error:
            raise StudyError(f"{path}: key 'numerics': {error}") from None
    study = DynamicStudy(
        name=name,
        description=raw.description,
        source=path,
        indenter=indenter,
        half_space=half_space,
        density=raw.half_space.density2,
        mass=raw.impact.mass,
        velocities=velocities,
        example=example,
        settings=settings,
        quick_velocities=_velocities(path, "quick.velocity", quick, example),
        quick_settings=_settings(path, "quick", raw.quick, settings),
        tolerances=DynamicTolerances(**msgspec.structs.asdict(raw.tolerances)),
        prony=prony,
        prony_text=raw.half_space.prony or "",
        physics=physics,
        finite_numerics=_finite_numerics(path, "numerics", raw.numerics, physics),
        quick_finite_numerics=_finite_numerics(path, "quick", raw.quick, physics, raw.numerics),
    )
    _check_problem(path, study)
    _check_velocities(path, "impact.velocity", study, study.velocities)
    _check_velocities(path, "quick.velocity", study, study.quick_velocities)
    return _split_losses(path, study, raw.sweep)


def _beside(path: Path, prony: str | None) -> str | None:
    """``prony`` with a relative .csv path taken from the study file's folder."""
    if prony is None or not prony.strip().lower().endswith(".csv"):
        return prony
    csv = Path(prony.strip())
    return prony if csv.is_absolute() else str(path.parent / csv)


def _physics(raw: _DynamicFile) -> dict[str, Any]:
    """The keywords of :meth:`Problem.impact` the file gives beyond the striker, the body's
    elasticity, the Prony series and the layer: the model, its rubber options, the interface."""
    given = {**msgspec.structs.asdict(raw.rubber), "interface": raw.impact.interface}
    given["friction"] = raw.impact.friction
    defaults = {"model": "linear", "interface": "frictionless"}
    return {k: v for k, v in given.items() if v is not None and v != defaults.get(k)}


FINITE_NUMERICS = ("time_steps", "mesh_size", "refine")
"""The [numerics] keys a rubber's impact takes (the finite-strain impact of
:func:`shtaerman.dynamic`)."""
PHYSICS_KEYS = {
    **{name: f"rubber.{name}" for name in ("model", *RUBBER_OPTIONS)},
    **{name: f"impact.{name}" for name in ("interface", "friction")},
    **{name: f"layer.{name}" for name in ("thickness", "base")},
    "prony": "half_space.prony",
    "profile": "indenter",
    "sphere_radius": "indenter",
}
"""A problem part's keyword -> its study-file key (for a refusal of :class:`Problem`)."""


def _finite_numerics(
    path: Path,
    table: str,
    raw: _Numerics,
    physics: dict[str, Any],
    parent: _Numerics | None = None,
) -> dict[str, Any]:
    """A rubber's numerical keywords of :func:`shtaerman.dynamic` from ``raw`` (over those of
    ``parent``, the [numerics] of a [quick]); a key the finite-strain impact does not take is
    refused. {} for the linear model."""
    if physics.get("model", "linear") == "linear":
        return {}
    for key in _Numerics.__struct_fields__:
        if key not in FINITE_NUMERICS and getattr(raw, key) is not None:
            raise StudyError(
                f"{path}: key '{table}.{key}': not supported with model "
                f"{physics['model']!r} (the finite-strain impact takes "
                f"{', '.join(FINITE_NUMERICS)})"
            )
    inherited = {} if parent is None else _finite_numerics(path, "numerics", parent, physics)
    given = {key: getattr(raw, key) for key in FINITE_NUMERICS if getattr(raw, key) is not None}
    return {"time_steps": None, "mesh_size": None, "refine": 1.0, **inherited, **given}


def _check_problem(path: Path, study: DynamicStudy) -> None:
    """Build the study's impact once (at its example velocity): a part out of range, or parts
    that do not combine, is refused naming the file and the key."""
    try:
        study.problem(study.example)
    except InputError as error:
        parameter = error.parameter or str(error).partition(":")[0]  # "model: unknown ..."
        key = PHYSICS_KEYS.get(parameter, "rubber")
        text = str(error).removeprefix(f"{parameter}: ")
        raise StudyError(f"{path}: key '{key}': {text}") from None


def _check_velocities(path: Path, key: str, study: DynamicStudy, velocities: Any) -> None:
    """Refuse, naming ``key``, a velocity whose exact impact leaves the floating-point range
    (the first check of its run: it came after the velocities before it had run)."""
    import warnings

    from ...theory.impact import representable
    from .case import exact_impact

    for velocity in velocities:
        striker = study.problem(velocity).striker
        law = contact_law(striker.indenter, effective_modulus(striker.material, study.half_space))
        try:
            with warnings.catch_warnings():
                warnings.simplefilter("ignore")  # the run's warnings are the run's
                representable("v0^2", velocity * velocity, study.mass, velocity)
                exact_impact(study.mass, velocity, law)
        except InputError as error:
            raise StudyError(f"{path}: key '{key}': {error}") from None


def _split_losses(path: Path, study: DynamicStudy, sweep: _DynSweep | None) -> list[DynamicStudy]:
    """``study``, or one study per loss of ``[sweep] loss`` (:data:`LOSSES`)."""
    if sweep is None:
        return [study]
    losses = sweep.loss
    if not losses or any(loss not in LOSSES for loss in losses) or len(set(losses)) < len(losses):
        raise StudyError(
            f"{path}: key 'sweep.loss': expected distinct values of {', '.join(LOSSES)}, "
            f"got {shown(losses)}"
        )
    if study.prony is None or study.density <= 0:
        raise StudyError(
            f"{path}: key 'sweep.loss': splits the losses of a half-space with both a "
            "density2 > 0 and a prony series"
        )
    variants = {
        "waves": {"prony": None, "prony_text": ""},
        "hysteresis": {"density": 0.0},
        "both": {},
    }
    return [
        dataclasses.replace(study, name=f"{study.name}-{loss}", **variants[loss])  # type: ignore[arg-type]
        for loss in losses
    ]


NEGLIGIBLE_REFLECTION = 1e-4
"""Reflected energy, of M v0^2/2, below which no reflection is reported: it moves e by less
than 5e-5. An impact that radiates almost nothing (v0 = 1e-3 m/s: 1 - e^2 below the energy
balance's own error) has a reflected share of its radiation that is noise, or 0/0."""


def dynamic_check_failures(
    balance: float, reflected: float, of: str = "the radiated", radiated: float | None = None
) -> list[str]:
    """What a dynamic run fails of the studies' own checks (:class:`DynamicTolerances`): its
    energy balance error (of M v0^2/2) and the energy reflected back by the far boundary (of
    the radiated energy; ``of`` names the reference, M v0^2/2 on a layer), one reason each;
    [] when both hold (NaN fails). With ``radiated`` (1 - e^2, of M v0^2/2) a reflection of
    the radiated energy below :data:`NEGLIGIBLE_REFLECTION` of M v0^2/2 passes."""
    limits, failures = DynamicTolerances(), []
    if radiated is not None and of == "the radiated" and radiated <= NEGLIGIBLE_REFLECTION:
        reflected = 0.0  # nothing radiated to reflect: its share is noise or 0/0
    elif radiated is not None and of == "the radiated":
        reflected = reflected if reflected * radiated > NEGLIGIBLE_REFLECTION else 0.0
    if not balance <= limits.energy_balance:
        failures.append(
            f"energy balance error {balance:.1e} of M v0^2/2 exceeds {limits.energy_balance:g}: "
            "the mesh and time steps do not resolve this impact"
        )
    if not reflected <= limits.reflected:
        failures.append(
            f"reflected energy {reflected:.1e} of {of} exceeds {limits.reflected:g}: "
            "the far boundary sends the waves back to the contact (domain_factor or layer_rate "
            "do not absorb them)"
        )
    return failures
