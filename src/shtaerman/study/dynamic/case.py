"""The dynamic study: the elastodynamic FE impact against the quasi-static (Ateb) model over v0.

One case (:func:`run_case`, also what ``shtaerman dynamic`` runs) is the exact quasi-static
impact, the first-order radiation estimate (:mod:`shtaerman.theory.radiation`) and the dynamic
FE impact (:mod:`shtaerman.fem.dynamic_contact`) for the same striker and half-space. A study
(kind ``dynamic``, e.g. ``fem/dynamic.toml``) runs a case per approach velocity and states how
far the quasi-static x_c, P_c and t_c are from the dynamic x_max, P_max and t_contact / 2::

    kind = "dynamic"
    name = "dynamic"                      # optional; default: the file's stem
    description = "..."
    [indenter]   shape_coefficient = 5.0 (m^(1-n)), exponent = 1.5 (> 1; the striker is rigid)
    [half_space] E2 = 7.5e6 (Pa), nu2 = 0.5 (in [0, 0.5]), density2 = 1100 (kg/m^3)
    [impact]     mass = 0.7 (kg), velocity = 3.0 or [...] (m/s, increasing),
                 figure_velocity = 3.0 (optional; m/s, one of the velocities: the figures and
                 the findings; default: the middle one, the upper of two)
    [numerics]   time_steps, mesh_size, mesh_margin, domain_factor, growth, axis_size,
                 layer_rate and the other DynamicSettings fields, optional; refine = K
                 divides the mesh sizes and the time step by K after them
    [quick]      velocity = [...] (must hold figure_velocity; default: the smallest velocity
                 and figure_velocity) and the numerics of ``verify --quick`` (default:
                 [numerics])
    [tolerances] energy_balance = 1e-2 (of M v0^2/2), reflected = 1e-2 (of the radiated),
                 estimate = 0.2 (measured loss / first-order estimate - 1, checked where the
                 estimate is below estimate_below = 0.08)

The relative differences are quasi-static / dynamic - 1. Every velocity's run is the finest
level of an error-estimate ladder (:mod:`.dynamic_accuracy`; ``verify --quick`` skips it):
x_max, P_max, t_contact, e, 1 - e^2 and the differences themselves carry Richardson estimates.
The velocity up to which the quasi-static value holds to 1 % (5 %) is interpolated linearly
between the computed velocities where |difference| crosses the level (the differences grow
monotonically with v0), and stated only where the estimated error of the difference is below
a fifth of the level (:mod:`.limits`).
"""

from __future__ import annotations

import dataclasses
import itertools
import math
import time
from collections.abc import Callable, Sequence
from dataclasses import dataclass, field
from pathlib import Path
from typing import Annotated, Any

import msgspec

from ...fem.dynamic_contact import (
    MAX_DOFS,
    DynamicImpactResult,
    DynamicSettings,
    estimate_dofs,
    run_dynamic_impact,
    validate_density,
)
from ...theory.contact import PowerLawContact
from ...theory.impact import ImpactResult, solve_impact
from ...theory.indenter import PowerLawIndenter
from ...theory.materials import RIGID, Material, effective_modulus
from ...theory.radiation import RadiationEstimate, radiation_estimate
from ...validation import InputError
from ..checks import Check
from ..contact.indentation import validate_fem_inputs
from ..limits import LEVELS, thresholds
from ..richardson import Estimate
from ..schema import (
    MESH_FIELDS,
    Poisson,
    Positive,
    Relative,
    StudyError,
    Table,
    decode,
    fem_input_error,
    ranged,
    validate_name,
)
from .accuracy import DynamicLadder, check_ladder, complete_ladder

__all__ = [
    "COMPARED",
    "DynamicCase",
    "DynamicStudy",
    "DynamicStudyOutcome",
    "DynamicTolerances",
    "compare",
    "load_dynamic",
    "run_case",
    "run_dynamic_study",
]

QUASI_STATIC_KEYS = ("beta", "x_c", "P_c", "a_c", "p_c", "t_c", "t_y")
COMPARED = {
    "x": ("x_c", "x_max", "maximum approach"),
    "P": ("P_c", "P_max", "maximum force"),
    "t": ("t_c", "t_half", "compression time (against t_contact / 2)"),
}
"""Compared quantity -> (quasi-static key, dynamic key, words)."""
SEPARATION_SNAPSHOT = 1.05
"""The wave field after separation is kept at this multiple of the quasi-static t_y."""

Progress = Callable[[str], None]


# --- one case: quasi-static, estimate, dynamic -------------------------------------------------


def compare(quasi: ImpactResult, result: DynamicImpactResult) -> dict[str, float]:
    """Quasi-static / dynamic - 1 for x, P and t (keys of :data:`COMPARED`; t_c against
    t_contact / 2, the same as t_y against t_contact), dimensionless."""
    dynamic = {"x_max": result.x_max, "P_max": result.P_max, "t_half": 0.5 * result.t_contact}
    return {key: getattr(quasi, qs) / dynamic[dyn] - 1.0 for key, (qs, dyn, _) in COMPARED.items()}


@dataclass(frozen=True)
class DynamicCase:
    """One approach velocity: the quasi-static impact, the estimate and the dynamic FE impact
    (with its error-estimate ladder, or ``None`` when it was skipped)."""

    velocity: float
    quasi: ImpactResult
    estimate: RadiationEstimate
    result: DynamicImpactResult
    ladder: DynamicLadder | None = None

    def differences(self) -> dict[str, float]:
        """:func:`compare` and the measured loss against the first-order estimate."""
        out = compare(self.quasi, self.result)
        out["loss_vs_estimate"] = (
            self.result.energy_radiated_fraction / self.estimate.energy_fraction - 1.0
        )
        return out

    def estimates(self) -> dict[str, Estimate]:
        """Richardson estimates from the ladder ({} without one): x_max, P_max, t_contact,
        restitution, energy_radiated_fraction, and ``difference_x``, ``difference_P``,
        ``difference_t`` (:func:`compare` on every level; use ``absolute_error``)."""
        if self.ladder is None:
            return {}
        quasi = self.quasi
        differences = {
            f"difference_{key}": self.ladder.estimate(lambda r, key=key: compare(quasi, r)[key])
            for key in COMPARED
        }
        return {**self.ladder.estimates, **differences}

    def document(self) -> dict[str, object]:
        """The JSON of ``shtaerman dynamic --json`` (DESIGN.md interface contract), with the
        ladder's ``error_estimate``, ``extrapolated``, ``estimate_details``, ``mesh_ladder``."""
        maxima = self.quasi.maxima()
        return {
            "quasi_static": {key: maxima[key] for key in QUASI_STATIC_KEYS},
            "dynamic": self.result.summary(),
            "radiation_estimate": self.estimate.to_dict(),
            "mesh": self.result.mesh,
            "timings": self.result.timings,
            "parameters": self.result.parameters,
            **(self.ladder.to_dict(self.estimates()) if self.ladder is not None else {}),
        }


def run_case(
    indenter: PowerLawIndenter,
    half_space: Material,
    density: float,
    mass: float,
    velocity: float,
    settings: DynamicSettings | None = None,
    *,
    snapshots: Callable[[ImpactResult], Sequence[float]] | None = None,
    ladder: bool = False,
) -> DynamicCase:
    """Quasi-static impact, first-order radiation estimate and dynamic FE impact (SI units).

    Parameters
    ----------
    indenter : PowerLawIndenter
        The rigid striker's profile z = A r^n.
    half_space : Material
        E2 in Pa, nu2 in [0, 0.5].
    density : float
        Half-space density in kg/m^3.
    mass, velocity : float
        Striker mass in kg and approach velocity in m/s.
    settings : DynamicSettings, optional
        Numerical controls of the dynamic impact.
    snapshots : callable, optional
        Given the quasi-static impact, the times in s at which to keep the fields.
    ladder : bool
        Also run the two coarser levels of the error-estimate ladder
        (``settings.refined(1/2)`` must be valid).
    """
    law = PowerLawContact(indenter, effective_modulus(RIGID, half_space))
    quasi = solve_impact(mass, velocity, law)
    estimate = radiation_estimate(
        mass,
        velocity,
        law.beta,
        law.force_exponent,
        density,
        half_space.shear_modulus,
        half_space.poisson_ratio,
    )
    times = tuple(snapshots(quasi)) if snapshots is not None else ()
    settings = DynamicSettings() if settings is None else settings
    inputs = (indenter, half_space, density, mass, velocity)
    result = run_dynamic_impact(*inputs, settings, snapshot_times=times)
    levels = complete_ladder(result, *inputs, settings) if ladder else None
    return DynamicCase(velocity, quasi, estimate, result, levels)


# --- the study file ----------------------------------------------------------------------------


class _DynIndenter(Table):
    shape_coefficient: Positive
    exponent: Positive


class _DynHalfSpace(Table):
    E2: Positive
    nu2: Poisson
    density2: Positive


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


class _Quick(_Numerics):
    velocity: Positive | list[Positive] | None = None


class _DynTolerances(Table):
    energy_balance: Relative = 1e-2
    reflected: Relative = 1e-2
    estimate: Relative = 0.2
    estimate_below: Relative = 0.08


class _DynamicFile(Table):
    indenter: _DynIndenter
    half_space: _DynHalfSpace
    impact: _DynImpact
    name: str | None = None
    description: str = ""
    numerics: _Numerics = _Numerics()
    quick: _Quick = _Quick()
    tolerances: _DynTolerances = _DynTolerances()


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
    indenter: PowerLawIndenter
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


SETTINGS_FIELDS = {**MESH_FIELDS, "time_steps": "steps"}
"""Study-file key -> DynamicSettings field, where the two differ."""


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
    if estimate_dofs(settings) > MAX_DOFS:
        raise StudyError(
            f"{path}: key '{table}.mesh_size': the mesh would have about {estimate_dofs(settings)} "
            f"dofs, above the limit {MAX_DOFS}; coarsen size or growth"
        )
    return settings


def _velocities(
    path: Path, key: str, given: float | list[float], example: float | None
) -> tuple[float, ...]:
    """The velocities of ``key`` (one value or an increasing list), holding ``example``."""
    values = given if isinstance(given, list) else [given]
    if not values or any(b <= a for a, b in itertools.pairwise(values)):
        raise StudyError(
            f"{path}: key '{key}': expected a velocity > 0 (m/s) or a list of increasing ones, "
            f"got {given!r}"
        )
    if example is not None and example not in values:
        raise StudyError(
            f"{path}: key '{key}': expected to hold impact.figure_velocity = {example!r} m/s, "
            f"got {given!r}"
        )
    return tuple(values)


def load_dynamic(path: Path, data: dict[str, Any]) -> list[DynamicStudy]:
    """The study of a parsed ``kind = "dynamic"`` file; :class:`StudyError` names file and key."""
    raw: _DynamicFile = decode(path, data, _DynamicFile)
    try:
        name = validate_name(raw.name if raw.name is not None else path.stem, "name")
    except InputError as error:
        raise StudyError(f"{path}: key 'name': {error}") from None
    indenter = PowerLawIndenter(raw.indenter.shape_coefficient, raw.indenter.exponent)
    half_space = Material(raw.half_space.E2, raw.half_space.nu2)
    try:
        validate_fem_inputs(indenter, half_space)
        validate_density(raw.half_space.density2)
    except InputError as error:
        raise fem_input_error(path, error) from None
    example = raw.impact.figure_velocity
    velocities = _velocities(path, "impact.velocity", raw.impact.velocity, example)
    if example is None:  # the middle velocity (of two, the upper)
        example = velocities[len(velocities) // 2]
    quick = raw.quick.velocity
    if quick is None:  # the smallest velocity and the example (or the example and the largest)
        quick = sorted({velocities[0], example} if example != velocities[0] else velocities[:2])
    settings = _settings(path, "numerics", raw.numerics, DynamicSettings())
    try:
        check_ladder(settings)  # the full study runs the ladder; verify --quick does not
    except InputError as error:
        raise StudyError(f"{path}: key 'numerics': {error}") from None
    return [
        DynamicStudy(
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
        )
    ]


# --- running a study ---------------------------------------------------------------------------


@dataclass(frozen=True)
class DynamicStudyOutcome:
    """A dynamic study's cases, checks and summary (SI units)."""

    study: DynamicStudy
    cases: tuple[DynamicCase, ...]
    checks: list[Check]
    seconds: float
    quick: bool = False
    cpu_seconds: float = math.nan

    @property
    def passed(self) -> bool:
        """Whether every check passed."""
        return all(check.passed for check in self.checks)

    @property
    def example(self) -> DynamicCase:
        """The case at the study's example velocity."""
        return next(case for case in self.cases if case.velocity == self.study.example)

    @property
    def velocities(self) -> list[float]:
        return [case.velocity for case in self.cases]

    def estimate_curve(self, points: int = 60) -> dict[str, list[float]]:
        """The first-order estimate over the study's velocity range: ``velocity`` (m/s),
        ``energy_fraction`` lambda and ``restitution`` sqrt(1 - lambda)."""
        study, low, high = self.study, self.velocities[0], self.velocities[-1]
        law = PowerLawContact(study.indenter, effective_modulus(RIGID, study.half_space))
        curve: dict[str, list[float]] = {"velocity": [], "energy_fraction": [], "restitution": []}
        for i in range(points):
            v = low + (high - low) * i / (points - 1)
            estimate = radiation_estimate(
                study.mass,
                v,
                law.beta,
                law.force_exponent,
                study.density,
                study.half_space.shear_modulus,
                study.half_space.poisson_ratio,
            )
            curve["velocity"].append(v)
            curve["energy_fraction"].append(estimate.energy_fraction)
            curve["restitution"].append(estimate.restitution)
        return curve

    @property
    def estimated(self) -> bool:
        """Whether every case carries error estimates (a quick run skips the ladder)."""
        return all(case.ladder is not None for case in self.cases)

    def difference_errors(self) -> dict[str, list[float]] | None:
        """Per compared quantity (and "all": the largest of the three) the estimated absolute
        error of the difference at every velocity; ``None`` without estimates."""
        if not self.estimated:
            return None
        estimates = [case.estimates() for case in self.cases]
        errors = {
            key: [e[f"difference_{key}"].absolute_error for e in estimates] for key in COMPARED
        }
        errors["all"] = [max(errors[k][i] for k in COMPARED) for i in range(len(self.cases))]
        return errors

    def limits(self) -> dict[str, dict[str, dict]]:
        """Per compared quantity (x, P, t, and "all": the worst of them) and level ("1%",
        "5%"): the velocity limit of :func:`shtaerman.study.limits.thresholds`, with the
        estimated error deciding it and whether that resolves the level."""
        rows = {key: [case.differences()[key] for case in self.cases] for key in COMPARED}
        rows["all"] = [max(abs(rows[k][i]) for k in COMPARED) for i in range(len(self.cases))]
        errors = self.difference_errors()
        return {
            key: {
                f"{100 * level:g}%": thresholds(
                    self.velocities, values, level, None if errors is None else errors[key]
                )
                for level in LEVELS
            }
            for key, values in rows.items()
        }

    def document(self) -> dict[str, object]:
        """The study's numbers for results.json (:mod:`shtaerman.output.text_dynamic` adds the
        display ``tables`` and ``findings`` and the common keys)."""
        study, settings = self.study, self.settings
        return {
            "inputs": {
                "shape_coefficient": study.indenter.shape_coefficient,
                "exponent": study.indenter.exponent,
                "E2": study.half_space.youngs_modulus,
                "nu2": study.half_space.poisson_ratio,
                "density2": study.density,
                "mass": study.mass,
                "velocities": self.velocities,
                "example": study.example,
            },
            "settings": {k: v for k, v in dataclasses.asdict(settings).items()},
            "cases": [
                {"velocity": case.velocity, **case.document(), "differences": case.differences()}
                for case in self.cases
            ],
            "estimated": self.estimated,
            "limits": self.limits(),
            "cpu_seconds": self.cpu_seconds,
        }

    @property
    def settings(self) -> DynamicSettings:
        return self.study.quick_settings if self.quick else self.study.settings


def _checks(study: DynamicStudy, cases: Sequence[DynamicCase]) -> list[Check]:
    tol, checks = study.tolerances, []
    for case in cases:
        v, r = f"v0 = {case.velocity:g} m/s", case.result
        checks.append(Check(f"energy balance {v}", r.energy_balance_error, tol.energy_balance))
        checks.append(Check(f"reflected energy {v}", r.reflected_energy_fraction, tol.reflected))
        if case.estimate.energy_fraction < tol.estimate_below:
            checks.append(
                Check(
                    f"loss / first-order estimate - 1 {v}",
                    case.differences()["loss_vs_estimate"],
                    tol.estimate,
                )
            )
    return checks


def run_dynamic_study(
    study: DynamicStudy, quick: bool = False, progress: Progress | None = None
) -> DynamicStudyOutcome:
    """Run the dynamic impact at every velocity of the study (``quick``: its quick variant).

    The example velocity keeps the fields at the quasi-static t_c and at
    :data:`SEPARATION_SNAPSHOT` t_y for the wave-field pictures. Every velocity also runs the
    error-estimate ladder's two coarser levels, except in a quick run.
    """
    report = progress or (lambda _line: None)
    start, cpu = time.perf_counter(), time.process_time()
    velocities = study.quick_velocities if quick else study.velocities
    settings = study.quick_settings if quick else study.settings
    cases = []
    for velocity in velocities:
        report(
            f"{study.name}: dynamic impact at v0 = {velocity:g} m/s"
            + ("" if quick else " (and 2 coarser levels for the error estimates)")
        )
        snapshots = (
            (lambda q: (q.t_c, SEPARATION_SNAPSHOT * q.t_y)) if velocity == study.example else None
        )
        cases.append(
            run_case(
                study.indenter,
                study.half_space,
                study.density,
                study.mass,
                velocity,
                settings,
                snapshots=snapshots,
                ladder=not quick,
            )
        )
    return DynamicStudyOutcome(
        study=study,
        cases=tuple(cases),
        checks=_checks(study, cases),
        seconds=time.perf_counter() - start,
        quick=quick,
        cpu_seconds=time.process_time() - cpu,
    )
