"""``shtaerman.dynamic``: the elastodynamic FE impact against the quasi-static theory."""

from __future__ import annotations

import dataclasses
import json
import math
from collections.abc import Mapping
from pathlib import Path
from typing import TYPE_CHECKING, Any

from ..plots.formats import check_figure_format
from ..problem import (
    LOADING_KEYWORDS,
    Problem,
    check_keywords,
    check_options,
    check_outputs,
    in_python_words,
)
from ..theory.materials import Material
from ..validation import InputError
from ..vocabulary import checked_positive, entry, fields
from .dynamic_result import DIFFERENCES, DynamicResult, check_separated, warn_failed_checks

if TYPE_CHECKING:
    from ..fem.dynamic_contact import DynamicSettings
    from ..fem.finite_dynamic import FiniteImpactSettings
    from ..study.dynamic.case import DynamicCase
    from ..theory.sneddon import Indenter
    from ..theory.viscoelastic import PronySeries

__all__ = [
    "DIFFERENCES",
    "SETTINGS_OPTIONS",
    "DynamicResult",
    "check_dynamic",
    "checked_options",
    "dynamic",
    "dynamic_settings",
]

SETTINGS_OPTIONS = (
    "time_steps",
    "mesh_size",
    "mesh_margin",
    "domain_factor",
    "growth",
    "layer_rate",
)
"""Numerical keywords (the vocabulary's: ``time_steps`` is ``--time-steps``, ``mesh_size``
``--mesh-size``, ...): each sets the DynamicSettings field :func:`shtaerman.vocabulary.fields`
names."""


def checked_options(options: Mapping[str, object]) -> dict[str, object]:
    """The numerical ``options`` (of :data:`SETTINGS_OPTIONS`) that are not None, each checked
    against the dynamic impact's range (InputError naming it)."""
    return {k: entry(k).check(v, "dynamic") for k, v in options.items() if v is not None}


def dynamic_settings(
    base: DynamicSettings | None, options: Mapping[str, object]
) -> DynamicSettings:
    """``base`` (default ``DynamicSettings()``) with the options of :data:`SETTINGS_OPTIONS`
    that are not None, each checked against its range (InputError naming it)."""
    from ..fem.dynamic_contact import DynamicSettings

    base = DynamicSettings() if base is None else base
    if not isinstance(base, DynamicSettings):
        raise InputError(
            f"settings must be a shtaerman.DynamicSettings, got "
            f"{type(base).__name__}; the keywords time_steps, mesh_size, ... set single fields",
            "settings",
        )
    names = fields(SETTINGS_OPTIONS)
    chosen = {names[k]: v for k, v in checked_options(options).items()}
    return dataclasses.replace(base, **chosen)  # type: ignore[arg-type]


def _viscoelastic(
    case: DynamicCase, problem: Problem
) -> tuple[dict[str, Any] | None, dict[str, float] | None, dict[str, float] | None]:
    """A viscoelastic body's quasi-static reference (once per run, not per ladder level), its
    differences from the dynamic FE impact and their estimated errors (None where there is no
    Prony series, no estimate)."""
    from ..study.dynamic.case import viscoelastic_compare, viscoelastic_reference

    reference = viscoelastic_reference(problem, case.quasi.t_c)
    if reference is None:
        return None, None, None
    differences = viscoelastic_compare(reference, case.result)
    errors = None
    if case.estimated:
        errors = {
            key: case.ladder.estimate(
                lambda r, key=key: viscoelastic_compare(reference, r)[key]
            ).absolute_error
            for key in differences
        }
    return reference, differences, errors


def _result(case: DynamicCase, problem: Problem) -> DynamicResult:
    """The result of ``problem``'s case, with its ladder's keys where it ran one (the
    differences' errors None where the estimate is missing); a rubber, a pad and a massless
    body have no radiation estimate (the first-order estimate is of the waves of the linear
    elastic half-space)."""
    from ..study.dynamic.case import compare

    document = dataclasses.replace(case, ladder=None).document()
    differences = compare(case.quasi, case.result)
    ladder, errors = case.ladder, None
    if case.estimated:
        estimates = case.estimates()
        errors = {DIFFERENCES[k]: estimates[f"difference_{k}"].absolute_error for k in DIFFERENCES}
    if ladder is not None:
        document.update(ladder.to_dict())
    body, indenter = problem.body, problem.striker.indenter
    series, pad = body.prony, problem.geometry.thickness is not None
    waveless = body.finite or pad or body.material.density == 0  # no half-space waves
    viscous, viscous_differences, viscous_errors = _viscoelastic(case, problem)
    return DynamicResult(
        quasi_static=document["quasi_static"],
        dynamic=document["dynamic"],
        differences={DIFFERENCES[k]: value for k, value in differences.items()},
        radiation_estimate=None if waveless else document["radiation_estimate"],
        mesh=document["mesh"],
        timings=document["timings"],
        parameters=document["parameters"],
        model=body.model,
        rubber=body.rubber().to_dict() if body.finite else None,
        prony=None if series is None else series.text(),
        differences_error=errors,
        error_estimate=document.get("error_estimate"),
        extrapolated=document.get("extrapolated"),
        estimate_details=document.get("estimate_details"),
        mesh_ladder=tuple(document["mesh_ladder"]) if ladder is not None else None,
        estimate_missing=document.get("estimate_missing"),
        profile={"kind": indenter.kind, "parameters": indenter.parameters},
        viscoelastic_quasi_static=viscous,
        viscoelastic_differences=viscous_differences,
        viscoelastic_differences_error=viscous_errors,
        solution=case.result,
        ladder=ladder,
    )


def _write_figures(case: DynamicCase, folder: Path, figure_format: str) -> None:
    """The figures of the case (:func:`shtaerman.output.dynamic.write_case_figures`)."""
    from ..signals import deferred

    with deferred():  # VTK's modules: an interrupt in their import was a segfault at times
        from ..output.dynamic import write_case_figures

    write_case_figures(case, folder, figure_format)


def _write_folder(result: DynamicResult, problem: Problem, folder: Path) -> None:
    """dynamic.json, history.csv, energies.csv and one VTU per snapshot time (a rubber's:
    :func:`shtaerman.output.finite.write_impact_fields`)."""
    import meshio

    from ..output.export import field_mesh
    from ..output.files import write_csv
    from ..output.finite import write_impact_fields

    solution = result.solution
    (folder / "dynamic.json").write_text(json.dumps(result.to_dict(), indent=2))
    write_csv(folder / "history.csv", result.history())
    write_csv(
        folder / "energies.csv",
        {"t [s]": solution.t, **{f"{k} [J]": v for k, v in solution.energies.items()}},
    )
    for index, requested in enumerate(solution.snapshots):
        actual, fields, _ = solution.field_solution(requested)
        meshio.write(folder / f"field_{index}_t{actual:.6e}s.vtu", field_mesh(fields))
    if solution.kept is not None:
        striker, body = problem.striker.indenter, problem.body
        write_impact_fields(solution, striker, body.material, body.model, folder)


def _snapshots(quasi: Any) -> tuple[float, ...]:
    """The field snapshots of an ``out`` folder: half, all and 1.5 x the compression time."""
    return (0.5 * quasi.t_c, quasi.t_c, 1.5 * quasi.t_c)


def _density(body: Material) -> float:
    if body.density is None:
        raise InputError(
            "density: the dynamic impact needs the body's density in kg/m^3, e.g. "
            "Material(youngs_modulus, poisson_ratio, density=1100.0)",
            "density",
        )
    return body.density


@in_python_words
def dynamic(
    indenter: Indenter | Problem,
    body: Material | None = None,
    *,
    mass: float | None = None,
    velocity: float | None = None,
    thickness: float | None = None,
    base: str | None = None,
    refine: float = 1.0,
    estimate: bool = True,
    settings: DynamicSettings | None = None,
    time_steps: int | None = None,
    mesh_size: float | None = None,
    mesh_margin: float | None = None,
    domain_factor: float | None = None,
    growth: float | None = None,
    layer_rate: float | None = None,
    prony: PronySeries | str | None = None,
    out: str | Path | None = None,
    force: bool = False,
    figure_format: str = "png",
    model: str = "linear",
    **rubber: Any,
) -> DynamicResult:
    """The dynamic FE impact of a rigid striker on an elastic half-space.

    Parameters
    ----------
    indenter : PowerLawIndenter, SphereIndenter, TabulatedIndenter or Problem
        The rigid striker's profile (z = A r^n, n > 1; the exact sphere or a tabulated z(r),
        on every body :data:`shtaerman.problem.SUPPORT` runs); or the whole impact
        (:class:`shtaerman.Problem`), then only numerical and output keywords follow.
    body : Material
        The half-space: E2 in Pa, nu2 in [0, 0.5] and its density in kg/m^3 (required).
    mass, velocity : float
        Striker mass in kg and approach velocity in m/s.
    thickness : float, optional
        Thickness H in m of a layer of ``body`` on a rigid base, whose waves reflect at the
        base; None: the half-space. The ``quasi_static`` values stay the half-space's.
    base : {"bonded", "lubricated"}, optional
        The layer's base: bonded (u = 0, the default with ``thickness``) or lubricated
        (u_z = 0, free to slide); only with ``thickness``.
    refine : float
        Divide the mesh size field and the time step by it together.
    estimate : bool
        Run the two coarser levels of the ladder (refine/2, refine/sqrt 2) for the error
        estimates (about 0.75 of the run's cost again).
    settings : DynamicSettings, optional
        The numerical controls; ``time_steps``, ``mesh_size``, ``mesh_margin``, ``domain_factor``,
        ``growth`` and ``layer_rate`` (the ``--time-steps`` ... options) override its fields.
    prony : PronySeries or str, optional
        Shear relaxation of the half-space, or its text ``g1:tau1,g2:tau2,...`` (tau in s):
        ``body`` then gives the instantaneous E2 and nu2 and the bulk stays elastic (with a
        finite-strain ``model``: the isochoric stress relaxes). None: elastic.
    out : path, optional
        A new folder for dynamic.json, history.csv, energies.csv and the figures, and the
        fields at the steps nearest 0.5, 1 and 1.5 t_c (three VTU files; the linear body's
        with their pictures; a rubber with a Prony series none); an existing one is replaced
        only with ``force``.
    figure_format : {"png", "svg", "pdf"}
        "svg" or "pdf" also writes each chart in that format beside its PNG.
    model : str
        ``linear`` (default), or a rubber at finite strain (``neo-hookean``,
        ``mooney-rivlin``, ``yeoh``, ``gent``, options ``**rubber``): then
        :func:`shtaerman.study.dynamic.case.finite_settings` (``refine`` and ``estimate``
        as here; the ladder of :mod:`shtaerman.study.dynamic.accuracy`; density 0: the
        massless body; ``time_steps`` default 50, 100 with inertia; ``mesh_size`` the
        finite-strain contact's).

    Returns
    -------
    DynamicResult

    Raises
    ------
    shtaerman.validation.InputError
        If an input lies outside its range, or the body has no density (nothing is computed).
    """
    from ..output.files import output_folder, staged_folder
    from ..study.dynamic.case import problem_case

    physics = dict(model=model, prony=prony, thickness=thickness, base=base, **rubber)
    problem = _problem(indenter, body, mass, velocity, physics)
    options = dict(time_steps=time_steps, mesh_size=mesh_size, mesh_margin=mesh_margin)
    options.update(domain_factor=domain_factor, growth=growth, layer_rate=layer_rate)
    outputs = dict(out=out, force=force, figure_format=figure_format)
    # the impact's own checks (seconds on a long table) are the run's first step
    checked = check_dynamic(problem, refine, estimate, settings, **options, **outputs, impact=False)
    folder = output_folder(out, force=force)  # checked before the run
    shots = _snapshots if folder is not None else None
    case = problem_case(problem, checked, snapshots=shots, ladder=estimate, refine=refine)
    check_separated(case.result.summary(), float(case.result.t[-1]))
    result = _result(case, problem)
    if folder is not None:
        with staged_folder(folder, force=force) as stage:
            _write_folder(result, problem, stage)
            _write_figures(case, stage, figure_format)
    warn_failed_checks(result, problem)
    return result


def check_dynamic(
    problem: Problem,
    refine: float = 1.0,
    estimate: bool = True,
    settings: DynamicSettings | None = None,
    *,
    out: str | Path | None = None,
    force: bool = False,
    figure_format: str = "png",
    impact: bool = True,
    **options: Any,
) -> DynamicSettings | FiniteImpactSettings:
    """Every input of ``dynamic(problem, ...)`` (the same keywords; ``options`` the
    ``time_steps`` ... ``layer_rate`` ones) checked, nothing computed: what a run would refuse
    for its inputs alone, it refuses now (:func:`shtaerman.effects` and a sweep's load check
    all their runs so); without ``impact``, the impact's own checks are left to the run,
    which makes them first.

    Returns
    -------
    DynamicSettings or FiniteImpactSettings
        The settings of the ladder's finest level (of refinement ``refine``).

    Raises
    ------
    shtaerman.validation.InputError
        As :func:`dynamic`.
    """
    from ..fem.contact.linear import validate_fem_inputs
    from ..fem.dynamic_layer import check_layer_rate
    from ..study.dynamic.accuracy import check_ladder
    from ..study.dynamic.case import finite_settings

    unknown = sorted(set(options) - set(SETTINGS_OPTIONS))
    if unknown:
        raise TypeError(f"unexpected keyword arguments {unknown}")
    options = {name: options.get(name) for name in SETTINGS_OPTIONS}
    check_outputs(out, force=force, estimate=estimate, figure_format=figure_format)
    numerics = {name: options[name] for name in ("mesh_margin", "domain_factor", "growth")}
    numerics.update(layer_rate=options["layer_rate"], settings=settings, out=out)
    numerics.update(force=force or None, refine=refine != 1.0 or None)
    numerics.update(estimate=not estimate or None, figure_format=figure_format != "png" or None)
    check_options(problem, [name for name, value in numerics.items() if value is not None])
    _density(problem.body.material)
    refine = checked_positive("refine", refine)  # before the ladder
    if problem.striker.material.youngs_modulus != math.inf:
        raise InputError(
            "striker: the FE impact's striker is rigid (its elasticity is not modelled, E1 "
            "would be ignored): drop striker=..., or take the exact quasi-static impact "
            "(shtaerman.impact), which takes it",
            "striker",
        )
    if problem.body.finite:
        numbers = dict(time_steps=options["time_steps"], mesh_size=options["mesh_size"])
        chosen = finite_settings(problem, **numbers, refine=refine, estimate=estimate)
    else:
        check_layer_rate(options["layer_rate"], problem.geometry.thickness)
        chosen = dynamic_settings(settings, options)
        validate_fem_inputs(problem.striker.indenter, problem.body.material)
        finest = chosen.refined(refine)  # first: its refusal names the refine given
        if estimate:
            check_ladder(chosen, refine)
        chosen = finest
    check_figure_format(figure_format)
    if impact:
        _check_impact(problem, None if problem.body.finite else chosen)
    return chosen


def _check_impact(problem: Problem, settings: DynamicSettings | None) -> None:
    """The impact's own checks as the run makes them first (its warnings are the run's): its
    reach (:func:`shtaerman.fem.impact.check_impact_reach`), the floating-point range,
    the exact impact and the depth it reaches; the linear body's layer thickness against it,
    mesh size and viscoelastic duration (``settings``; None: a rubber)."""
    import warnings

    from ..fem.dynamic_contact import check_dynamic_impact
    from ..fem.finite_dynamic import check_finite_reach, pad_reach_note
    from ..fem.impact import check_impact_reach
    from ..theory.impact import impact_in_floats
    from ..theory.materials import effective_modulus, validate_density
    from ..theory.profile_impact import ProfileImpactResult
    from ..theory.sneddon import contact_law
    from ..theory.viscoelastic import rigid_impact

    striker, body = problem.striker, problem.body.material
    inputs = (striker.indenter, body, _density(body), striker.mass, striker.velocity)
    law = contact_law(striker.indenter, effective_modulus(striker.material, body))
    friction, geometry, prony = problem.interface.coefficient, problem.geometry, problem.body.prony
    exact = rigid_impact(*inputs[:2], *inputs[3:5])  # the striker is rigid: one solve for all
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        check_impact_reach(
            *inputs[:3], inputs[3:5], settings is None, friction, geometry, prony, exact
        )
        quasi = impact_in_floats(*inputs[3:5], exact)  # the floating-point range first
        if settings is not None:
            sizing = quasi if isinstance(quasi, ProfileImpactResult) else None
            check_dynamic_impact(*inputs, settings, prony, friction, sizing, geometry)
            return
    validate_density("density2", body.density)
    pad = geometry.thickness is not None  # it stops the striker short of x_c
    note = pad_reach_note(pad, friction, inputs[2])  # None: the floor alone
    reach = (striker.indenter, law, inputs[3:5], prony)
    check_finite_reach(reach, note, None, (quasi.x_c, quasi.t_y))


def _problem(
    indenter: Indenter | Problem,
    body: Material | None,
    mass: float | None,
    velocity: float | None,
    physics: dict[str, Any],
) -> Problem:
    """The impact of :func:`dynamic`: ``indenter`` itself when it is a :class:`Problem` (then
    no other part may be given), else built from the keywords (``density`` in kg/m^3, of a
    finite-strain impact, replaces the body's)."""
    check_keywords(physics, "dynamic()", extra=("density",), without=LOADING_KEYWORDS)
    if isinstance(indenter, Problem):
        parts = dict(body=body, mass=mass, velocity=velocity, **physics)
        return indenter.alone("dynamic", "impact", **parts)
    density = physics.pop("density", None)
    if density is not None and isinstance(body, Material):
        body = dataclasses.replace(body, density=density)
    return Problem.impact(indenter, body, mass=mass, velocity=velocity, **physics)
