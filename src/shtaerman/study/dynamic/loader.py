"""The dynamic study file: one striker and body, the impact at several approach velocities.

A study of kind ``dynamic`` (e.g. ``fem/dynamic.toml``; ``shtaerman init-study --kind dynamic``
writes every key, commented) runs a case (:func:`.case.run_case`) per approach velocity
(:mod:`.runner`). Its physics (``[half_space]`` with density2 and prony, ``[layer]``,
``[impact]`` interface and friction, ``[rubber]``) builds one
:class:`shtaerman.problem.Problem`, checked at load; ``[sweep] loss`` (with a prony: any of
"waves", "hysteresis", "both") splits it into one study per loss.
"""

from __future__ import annotations

import dataclasses
import itertools
from collections.abc import Callable, Mapping
from dataclasses import dataclass, field
from pathlib import Path
from typing import Annotated, Any

import msgspec

from ...fem.contact.linear import validate_fem_inputs
from ...fem.dynamic_contact import (
    MAX_DOFS,
    MAX_SIZE,
    DynamicSettings,
    check_dynamic_impact,
    estimate_dofs,
)
from ...fem.mesh import HALF_SPACE, Geometry, growth_error
from ...problem import Problem, check_options, worded
from ...theory.materials import Material
from ...theory.sneddon import Indenter
from ...theory.viscoelastic import PronySeries
from ...validation import InputError, shown
from ...vocabulary import entry
from ..checks import Check
from ..ladder import WITHOUT_ESTIMATE
from ..schema import (
    BodyTable,
    LayerTable,
    Named,
    Positive,
    Relative,
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
    prony_of,
    ranged,
    refused,
    settings_of,
)
from .accuracy import check_ladder

__all__ = [
    "DynamicStudy",
    "DynamicTolerances",
    "dynamic_check_failures",
    "energy_checks",
    "load_dynamic",
    "unmeasured_reflection",
]


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


class _DynImpact(SurfaceImpactTable):
    velocity: Positive | list[Positive]
    figure_velocity: Positive | None = None


class _Quick(_Numerics):
    velocity: Positive | list[Positive] | None = None


class DynamicTolerances(Table):
    """Pass/fail limits of a dynamic study: the largest energy balance error (of the initial
    kinetic energy), the largest reflected energy (of the radiated), and the largest |measured
    loss / first-order estimate - 1|, checked where the estimated fraction is below
    ``estimate_below`` (first order in it)."""

    energy_balance: Relative = 1e-2
    reflected: Relative = 1e-2
    estimate: Relative = 0.2
    estimate_below: Relative = 0.08


LOSSES = ("waves", "hysteresis", "both")
"""The losses a ``[sweep] loss`` list may hold: one study each."""


class _DynSweep(Table):
    loss: list[str]


class _DynamicFile(StudyFile):
    half_space: BodyTable
    impact: _DynImpact
    numerics: _Numerics = _Numerics()
    quick: _Quick = _Quick()
    tolerances: DynamicTolerances = DynamicTolerances()
    layer: LayerTable | None = None
    rubber: RubberTable = RubberTable()
    sweep: _DynSweep | None = None


@dataclass(frozen=True)
class DynamicStudy(Named):
    """A dynamic study: one striker and half-space, several approach velocities (SI units)."""

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
    geometry: Geometry = HALF_SPACE
    """The body's shape: the half-space, or the ``[layer]`` (thickness resolved in m)."""
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
    exact: Mapping[float, Any] = field(default_factory=dict, compare=False, repr=False)
    """velocity -> the quasi-static impact the loader solved (:func:`..schema.exact_impacts`),
    the run's (each solved once)."""

    def problem(self, velocity: float) -> Problem:
        """The impact at ``velocity`` m/s (:class:`shtaerman.problem.Problem`)."""
        layer = self.geometry
        geometry = {} if layer.thickness is None else dataclasses.asdict(layer)
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
    settings = settings_of(path, table, raw, base)
    try:
        if raw.refine is not None:
            settings = settings.refined(raw.refine)
    except InputError as error:
        raise StudyError(f"{path}: key '{table}': {error}") from None
    dofs = estimate_dofs(settings)
    blamed = growth_error(settings, estimate_dofs, MAX_DOFS, MAX_SIZE) if dofs > MAX_DOFS else None
    if blamed is not None:
        reason = worded(str(blamed).removeprefix("growth: "), "file")
        raise StudyError(f"{path}: key '{table}.growth': {reason}")
    if dofs > MAX_DOFS:
        raise StudyError(
            f"{path}: key '{table}.mesh_size': the mesh would have about {dofs:.3g} "
            f"dofs, above the limit {MAX_DOFS}; coarsen size or growth"
        )
    return settings


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
    raw: _DynamicFile = decode(path, data, _DynamicFile, "dynamic")
    header = named(path, raw)
    indenter = indenter_of(path, raw.indenter)
    half_space = Material(raw.half_space.E2, raw.half_space.nu2)
    prony = prony_of(path, raw.half_space.prony, half_space.youngs_modulus)
    example = raw.impact.figure_velocity
    velocities = _velocities(path, "impact.velocity", raw.impact.velocity, example)
    if example is None:  # the middle velocity (of two, the upper)
        example = velocities[len(velocities) // 2]
    quick = raw.quick.velocity
    if quick is None:  # the smallest velocity and the example (or the example and the largest)
        quick = sorted({velocities[0], example} if example != velocities[0] else velocities[:2])
    exact = exact_impacts(raw.impact.mass, indenter, half_space)
    try:
        validate_fem_inputs(indenter, half_space)  # the FEM's ranges before the layer's impact
        geometry = Geometry(**layer_geometry(path, raw.layer, lambda: exact(example)))
    except InputError as error:
        raise refused(path, error, KEYS) from None
    settings = _settings(path, "numerics", raw.numerics, DynamicSettings())
    physics = impact_physics(raw)
    if physics.get("model", "linear") == "linear":
        _check_ladder(path, settings)
    study = DynamicStudy(
        **header,
        indenter=indenter,
        half_space=half_space,
        density=raw.half_space.density2,
        mass=raw.impact.mass,
        velocities=velocities,
        example=example,
        settings=settings,
        geometry=geometry,
        quick_velocities=_velocities(path, "quick.velocity", quick, example),
        quick_settings=_settings(path, "quick", raw.quick, settings),
        tolerances=raw.tolerances,
        prony=prony,
        prony_text=raw.half_space.prony or "",
        physics=physics,
    )
    try:  # the study's impact once, at its example velocity: its parts and how they combine
        problem = study.problem(study.example)
    except InputError as error:
        raise refused(path, error, KEYS) from None
    numerics = {
        "exact": {
            **_check_velocities(path, "impact.velocity", study, exact),
            **_check_velocities(path, "quick.velocity", study, exact, quick=True),
        },
        "finite_numerics": _finite_numerics(path, "numerics", raw.numerics, problem),
        "quick_finite_numerics": _finite_numerics(path, "quick", raw.quick, problem, raw.numerics),
    }
    return _split_losses(path, dataclasses.replace(study, **numerics), raw.sweep)


def _check_ladder(path: Path, settings: DynamicSettings) -> None:
    """The full study's ladder (:func:`.accuracy.check_ladder`; verify --quick runs none),
    refused naming its key (no estimate key: a study runs without it as [quick])."""
    try:
        check_ladder(settings)
    except InputError as error:
        key = ".".join(filter(None, ("numerics", error.parameter)))
        reason = str(error).removeprefix(f"{error.parameter}: ")
        quick = "; or give it in [quick], which verify --quick runs without the estimate"
        reason = reason.replace(WITHOUT_ESTIMATE, quick)
        raise StudyError(f"{path}: key '{key}': {reason}") from None


def impact_physics(raw: Any) -> dict[str, Any]:
    """The keywords of :meth:`Problem.impact` an impact's study file (dynamic, effects) gives
    beyond the striker, the body's elasticity, the Prony series and the layer: the model, its
    rubber options, the interface."""
    given = {**msgspec.structs.asdict(raw.rubber), "interface": raw.impact.interface}
    given["friction"] = raw.impact.friction
    defaults = {"model": "linear", "interface": "frictionless"}
    return {k: v for k, v in given.items() if v is not None and v != defaults.get(k)}


FINITE_NUMERICS = {"time_steps": None, "mesh_size": None, "refine": 1.0}
"""The numerical keywords of a rubber's impact (:func:`.case.finite_case`; None: the
finite-strain impact's default); which [numerics] keys it refuses is the problem's
(:data:`shtaerman.problem.OPTION_SUPPORT`)."""
KEYS = {name: f"impact.{name}" for name in ("interface", "friction")}
"""The study-file keys of the inputs a dynamic study holds elsewhere than a contact study."""


def _finite_numerics(
    path: Path,
    table: str,
    raw: _Numerics,
    problem: Problem,
    parent: _Numerics | None = None,
) -> dict[str, Any]:
    """A rubber's numerical keywords of :func:`shtaerman.dynamic` from ``raw`` (over those of
    ``parent``, the [numerics] of a [quick]); {} for the linear model. A key the problem does
    not take, every model, is refused as the command line refuses its option
    (:func:`shtaerman.problem.check_options`: ``layer_rate`` on a massless body)."""
    fields = _Numerics.__struct_fields__
    given = {key: getattr(raw, key) for key in fields if getattr(raw, key) is not None}
    try:
        check_options(problem, given)
    except InputError as error:
        reason = worded(str(error).removeprefix(f"{error.parameter}: "), "file")  # its keys
        raise StudyError(f"{path}: key '{table}.{error.parameter}': {reason}") from None
    if not problem.body.finite:
        return {}
    inherited = {} if parent is None else _finite_numerics(path, "numerics", parent, problem)
    given = {key: value for key, value in given.items() if key in FINITE_NUMERICS}
    return {**FINITE_NUMERICS, **inherited, **given}


def _check_velocities(
    path: Path, key: str, study: DynamicStudy, exact: Callable, quick: bool = False
) -> dict[float, Any]:
    """velocity -> the exact impact (``exact``, solved once each) of each velocity of the study
    (``quick``: of its quick run), refused at load, not after the velocities before it ran,
    where its run would refuse it: the Problem, the depth's reach first
    (:func:`~shtaerman.fem.impact.check_impact_reach`), the floating-point range, and for the
    linear body the impact's own checks with the study's settings (depth reach, speed against
    the waves', the layer's thickness: :func:`~shtaerman.fem.dynamic_contact.
    check_dynamic_impact`); a refusal names ``key`` or the keys at fault."""
    import warnings
    from functools import partial

    from ...fem.impact import check_impact_reach
    from ...theory.impact import impact_in_floats

    solved = {}
    settings = study.quick_settings if quick else study.settings
    inputs = (study.indenter, study.half_space, study.density)
    velocities = study.quick_velocities if quick else study.velocities
    for velocity in sorted(velocities, reverse=True):  # the most radiating first (force ~ x^q,
        problem = study.problem(velocity)  # q > 1): the density it names passes every velocity
        impact, friction = (study.mass, velocity), problem.interface.coefficient
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")  # the run's warnings are the run's
            solve = partial(exact, velocity)  # once: a profile's end is checked by its solve
            try:  # the reach first, in logs, as the run checks it
                check_impact_reach(
                    *inputs[:3], impact, study.finite, friction, study.geometry, study.prony, solve
                )
            except InputError as error:
                raise refused(path, error, {**KEYS, "velocity": key}) from None
            try:
                solved[velocity] = impact_in_floats(study.mass, velocity, solve)
            except InputError as error:
                raise StudyError(f"{path}: key '{key}': {error}") from None
            if study.finite:  # its reach: checked as the finite-strain impact starts
                continue
            physics = (problem.body.prony, friction, solved[velocity])
            try:  # a profile's sizing impact: the exact one here
                check_dynamic_impact(*inputs, *impact, settings, *physics, geometry=study.geometry)
            except InputError as error:
                raise refused(path, error, {**KEYS, "velocity": key}) from None
    return {velocity: solved[velocity] for velocity in velocities}


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


def reflection_reference(layered: bool, finite: bool) -> str:
    """What a run's reflected energy is a fraction of: the radiated energy for the linear body
    on the half-space (the energy inside R_a at the end), else M v0^2/2 (a pad's rise after
    separation; the rubber's kinetic energy beyond half its domain)."""
    return "M v0^2/2" if layered or finite else "the radiated"


def energy_checks(
    balance: float,
    reflected: float,
    *,
    where: str = "",
    tolerances: DynamicTolerances | None = None,
    reflects: bool = True,
    of: str = "the radiated",
    radiated: float | None = None,
) -> list[Check]:
    """The studies' own checks of one impact run (``tolerances``, default
    :class:`DynamicTolerances`), named "energy balance{where}" and "reflected energy{where}":
    its energy balance error (of M v0^2/2) and, where the body ``reflects`` (it has waves),
    the energy reflected back by the far boundary (of the radiated energy; ``of`` names the
    reference, M v0^2/2 on a layer). With ``radiated`` (1 - e^2, of M v0^2/2) a reflection of
    the radiated energy below :data:`NEGLIGIBLE_REFLECTION` of M v0^2/2 counts as none, and so
    does any (nan: 0/0) where less was radiated; one not measured (nan) of more fails."""
    limits = DynamicTolerances() if tolerances is None else tolerances
    if radiated is not None and of == "the radiated":  # nothing radiated: noise or 0/0
        if not radiated > NEGLIGIBLE_REFLECTION or reflected * radiated <= NEGLIGIBLE_REFLECTION:
            reflected = 0.0
    checks = [Check(f"energy balance{where}", balance, limits.energy_balance)]
    if reflects:
        checks.append(Check(f"reflected energy{where}", reflected, limits.reflected))
    return checks


FAILED = {
    "energy balance": "energy balance error {value:.1e} of M v0^2/2 exceeds {tolerance:g}: "
    "the mesh and time steps do not resolve this impact: refine them (mesh_size=...,"
    " time_steps=... or refine=...)",
    "reflected energy": "reflected energy {value:.1e} of {of} exceeds {tolerance:g}: the far "
    "boundary sends the waves back to the contact: absorb them further out (domain_factor=..."
    " or layer_rate=...)",
    "reflected energy nan": "reflected energy not measured, of a striker that radiated: no "
    "tail was stepped after separation (tail 0) or R_a = layer_start c_s t_y lay beyond half "
    "the domain: set tail > 0 or raise domain_factor=...",
}
"""The reason of each failed :func:`energy_checks` check, on the routes that state them, with the
inputs that cure it in Python's words (:func:`shtaerman.problem.worded` spells them per route)."""


def unmeasured_reflection(radiated: float) -> str:
    """Why the reflected energy (of the radiated) of an impact that radiated ``radiated`` of
    M v0^2/2 (1 - e^2) is nan."""
    if radiated > NEGLIGIBLE_REFLECTION:
        return FAILED["reflected energy nan"].replace("=...", "")
    return (
        f"nothing radiated (1 - e^2 below {NEGLIGIBLE_REFLECTION:g}): its reflected share is "
        "noise or 0/0, counted as none"
    )


def dynamic_check_failures(
    balance: float, reflected: float, of: str = "the radiated", radiated: float | None = None
) -> list[str]:
    """What a dynamic run fails of the studies' own checks (:func:`energy_checks` with the
    default tolerances), one reason each; [] when both hold (NaN fails)."""
    checks = energy_checks(balance, reflected, of=of, radiated=radiated)
    unmeasured = {"reflected energy": "reflected energy nan"} if reflected != reflected else {}
    return [
        FAILED[unmeasured.get(check.name, check.name)].format(
            value=check.value, tolerance=check.tolerance, of=of
        )
        for check in checks
        if not check.passed
    ]
