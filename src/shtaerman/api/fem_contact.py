"""``shtaerman.contact``: the FEM contact curve of a rigid indenter, with estimates."""

from __future__ import annotations

import contextlib
import dataclasses
import json
import warnings
from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass, field
from pathlib import Path
from typing import TYPE_CHECKING, Any

import numpy as np

from ..fem.mesh import HALF_SPACE, Geometry
from ..output.files import json_safe
from ..plots.formats import check_figure_format
from ..problem import (
    KEYWORDS,
    MODELS,
    RUBBER_OPTIONS,
    Problem,
    check_options,
    check_outputs,
    in_python_words,
)
from ..theory.materials import RIGID, Material
from ..validation import InputError, validate_positive
from ..vocabulary import checked_positive, entry

if TYPE_CHECKING:
    from ..fem.mesh import MeshSettings
    from ..fem.rubber import RubberModel
    from ..theory.sneddon import Indenter
    from ..theory.viscoelastic import PronySeries

__all__ = [
    "MESH_OPTIONS",
    "MODELS",
    "RUBBER_OPTIONS",
    "ContactResult",
    "contact",
]

MESH_OPTIONS = ("mesh_size", "mesh_margin", "domain_factor", "growth", "max_dofs")
"""Mesh keywords (``--mesh-size``, ...): each sets the MeshSettings field
:func:`shtaerman.vocabulary.fields` names."""
NOT_IN_JSON = ("extra", "solution", "ladder", "key_order")
"""ContactResult fields that are not keys of the JSON."""


def _column(key: str, doc: str) -> Any:
    """A property: the array (float) of ``key`` over the steps."""
    return property(lambda self: np.array([step[key] for step in self.steps], dtype=float), doc=doc)


@dataclass(frozen=True)
class ContactResult:
    """The FEM contact curve: the keys of ``shtaerman contact --json`` (SI units).

    The per-depth values are in ``steps`` (one dict per depth) and, as arrays, in
    :attr:`depth`, :attr:`force`, :attr:`contact_radius`, :attr:`central_pressure`. The
    keys of the error-estimate ladder (``error_estimate``, ``extrapolated``, ...) are None
    when it did not run (``estimate=False``); ``error_estimate`` is the curve's (its worst
    depth's), ``step_error_estimate`` each depth's (relative); ``errors`` is the linear
    model's true error against Shtaerman's solution, ``departures_from_linear`` the
    neo-Hookean model's departure from it. A sphere's or a tabulated profile's curve has
    ``shape_coefficient`` and ``exponent`` None, its inputs in ``extra["profile"]`` (the
    JSON's ``profile``), and is compared with Sneddon's exact curve, whose ``beta_analytic``
    and ``exponent_analytic`` are the exact forces at the same depths fitted as the FEM's.
    ``solution`` is the finest FEM run (fields on demand), ``ladder`` the mesh ladder; neither
    is part of :meth:`to_dict`.
    ``mass`` (kg) and ``velocity`` (m/s) are those of the impact whose x_c the default depths
    reach (None, and not in the JSON, when the depths were given).
    """

    model: str
    shape_coefficient: float | None
    exponent: float | None
    E2: float
    nu2: float
    modulus: float
    beta_fem: float
    beta_analytic: float
    exponent_fem: float
    exponent_analytic: float
    beta_fem_free_exponent: float
    central_to_mean_analytic: float
    steps: tuple[dict[str, Any], ...]
    mesh: dict[str, Any]
    solver: str
    timings: dict[str, float]
    errors: dict[str, float] | None = None
    departures_from_linear: dict[str, float] | None = None
    error_estimate: dict[str, float] | None = None
    extrapolated: dict[str, float] | None = None
    estimate_details: dict[str, dict[str, Any]] | None = None
    step_error_estimate: tuple[dict[str, float], ...] | None = None
    true_error: dict[str, float] | None = None
    effectivity: dict[str, float] | None = None
    mesh_ladder: tuple[dict[str, Any], ...] | None = None
    accuracy_target: float | None = None
    mass: float | None = None
    velocity: float | None = None
    extra: dict[str, Any] = field(default_factory=dict, repr=False)
    solution: Any = field(default=None, repr=False, compare=False)
    ladder: Any = field(default=None, repr=False, compare=False)
    key_order: tuple[str, ...] = field(default=(), repr=False, compare=False)

    @classmethod
    def from_report(
        cls, report: Mapping[str, Any], solution: Any = None, ladder: Any = None
    ) -> ContactResult:
        """The result of a ``contact --json`` object (its key order kept for :meth:`to_dict`)."""
        names = {f.name for f in dataclasses.fields(cls)} - set(NOT_IN_JSON)
        values = {key: value for key, value in report.items() if key in names}
        values["steps"] = tuple(dict(step) for step in report["steps"])
        if "mesh_ladder" in report:
            values["mesh_ladder"] = tuple(dict(level) for level in report["mesh_ladder"])
        if report.get("step_error_estimate") is not None:
            values["step_error_estimate"] = tuple(map(dict, report["step_error_estimate"]))
        extra = {key: value for key, value in report.items() if key not in names}
        return cls(**values, extra=extra, solution=solution, ladder=ladder, key_order=tuple(report))

    depth = _column("depth", "Depths in m.")
    force = _column("force", "FEM force at each depth, N.")
    contact_radius = _column("contact_radius", "FEM contact radius at each depth, m.")
    central_pressure = _column(
        "central_pressure", "FEM pressure at the centre of the contact at each depth, Pa."
    )

    @property
    def finite(self) -> bool:
        """Whether the curve is a rubber's at finite strain (else the linear body's)."""
        return self.departures_from_linear is not None  # a rubber's report has no exact errors

    def to_dict(self) -> dict[str, Any]:
        """The JSON object of ``shtaerman contact --json`` (same keys, same order): non-finite
        numbers are None (the CLI's null)."""
        document: dict[str, Any] = {}
        for key in self.key_order:
            value = self.extra[key] if key in self.extra else getattr(self, key)
            if key in ("steps", "mesh_ladder", "step_error_estimate") and value is not None:
                value = [dict(row) for row in value]
            document[key] = value
        return json_safe(document)


def _with_impact(report: Mapping[str, Any], impact: tuple[float, float] | None) -> dict:
    """``report`` with, after ``nu2``, the ``mass`` (kg) and ``velocity`` (m/s) of the
    ``impact`` whose x_c the default depths reach; unchanged when the depths were given."""
    out: dict[str, Any] = {}
    for key, value in report.items():
        out[key] = value
        if key == "nu2" and impact is not None:
            out.update(mass=float(impact[0]), velocity=float(impact[1]))
    return out


def _check_coarsest(mesh: MeshSettings, refine: float, refined: float, geometry: Geometry) -> None:
    """Refuse at once a ladder whose coarsest level (refine / 2) is not a valid mesh (or
    whose finest is too large; the estimate of the layer of ``geometry`` needs its
    ``refined`` radius in m)."""
    from ..study.ladder import WITHOUT_ESTIMATE, check_ladder

    mesh.refined(refine).check_size(refined, geometry)  # no estimate makes the run's smaller
    try:
        check_ladder(mesh, refine, refined, geometry)
    except InputError as error:
        if error.parameter == "thickness":  # a layer the mesh cannot resolve, estimate or not
            raise
        raise InputError(f"{error}{WITHOUT_ESTIMATE}", error.parameter) from None


@dataclass(frozen=True)
class _Plan:
    """Checked inputs of one contact run."""

    indenter: Indenter
    body: Material
    depths: np.ndarray
    rubber: RubberModel | None
    mesh: MeshSettings
    refine: float
    estimate: bool
    tolerance: float | None
    max_time: float
    solver: str
    progress: Callable[[str], None] | None
    relaxing: dict[str, Any] = field(default_factory=dict)  # prony and rate, or nothing
    impact: tuple[float, float] | None = None  # whose x_c the default depths reach
    friction: float | None = None  # the indenter's surface (Interface.coefficient)
    geometry: Geometry = HALF_SPACE  # the body's shape

    @property
    def finite(self) -> bool:
        """Whether the body is a rubber at finite strain (it has a rubber model)."""
        return self.rubber is not None


def _solve(plan: _Plan) -> tuple[Any, Any]:
    """The finest FEM run and the ladder (None without the estimate)."""
    from ..study.contact.accuracy import run_ladder, run_mesh_ladder, run_to_accuracy
    from ..study.contact.indentation import run_indentation
    from ..study.finite.indentation import CURVE_ORDERS, run_finite_study

    inputs = (plan.indenter, plan.body, plan.depths)
    steps = {"progress": plan.progress, "refine": plan.refine, "partial": True}
    shape = plan.geometry
    linear = {"backend": plan.solver, "friction": plan.friction, "geometry": shape}
    rubber = (plan.rubber, plan.friction, shape)  # run_finite_study's after the mesh
    if not plan.estimate:
        finest = plan.mesh.refined(plan.refine)
        if plan.finite:
            return run_finite_study(*inputs, finest, *rubber), None
        return run_indentation(*inputs, finest, **linear, **plan.relaxing), None
    if plan.finite:  # exact=False: no exact finite-strain solution to take errors against
        solve = lambda level: run_finite_study(*inputs, level, *rubber)  # noqa: E731
        steps.update(exact=False, geometry=shape, orders=CURVE_ORDERS)
        ladder = run_mesh_ladder(solve, plan.mesh, **steps)
    elif plan.tolerance is None:
        ladder = run_ladder(*inputs, plan.mesh, **steps, **linear, **plan.relaxing)
    else:
        at = (plan.indenter, plan.body, plan.tolerance, plan.depths, plan.mesh)
        ladder = run_to_accuracy(*at, max_time=plan.max_time, progress=plan.progress, **linear)
    return ladder.finest, ladder


def _write(result: ContactResult, folder: Path, figure_format: str) -> None:
    """contact.json, the curve CSVs and VTU fields, and the curve figures (a finite-strain
    model: the force-depth curve against Shtaerman's linear one)."""
    from ..signals import deferred

    with deferred():  # VTK's modules: an interrupt in their import was a segfault at times
        from ..output import export
        from ..output.finite import write_finite_curve
        from ..plots.curves import plot_force_depth
        from ..plots.gallery import contact_figures

    if result.finite:
        write_finite_curve(result.solution, folder)
        plot_force_depth(result.solution, folder / "force_depth.png", figure_format=figure_format)
    else:
        export.write_indentation(result.solution, folder)
        contact_figures(result.solution, folder, figure_format)
    (folder / "contact.json").write_text(json.dumps(result.to_dict(), indent=2))


PHYSICS = tuple(name for name in KEYWORDS if name != "loading")
"""The keywords of :func:`contact` that describe the problem (the rest are numerics)."""


def _problem(indenter: Any, body: Any, options: Mapping[str, Any]) -> Problem:
    """The contact curve of :func:`contact`: ``indenter`` itself when it is a
    :class:`Problem` (then no other part may be given), else built from the keywords."""
    physics = {name: options[name] for name in PHYSICS}
    if isinstance(indenter, Problem):
        return indenter.alone("contact", "curve", body=body, **physics)
    if physics["striker"] is None:
        physics["striker"] = RIGID
    return Problem.curve(indenter, body, **physics)


def _impact(problem: Problem) -> tuple[float, float]:
    """The impact (mass kg, velocity m/s; default the vocabulary's) whose x_c the default
    depths reach."""
    striker = problem.striker
    mass = entry("mass").default if striker.mass is None else striker.mass
    return mass, entry("velocity").default if striker.velocity is None else striker.velocity


def _check_finite_depths(problem: Problem, depths: np.ndarray) -> None:
    """The depths (m) within the finite-strain contact's reach; default depths that are not
    name the impact that set them (its mass and velocity)."""
    from ..fem.contact.finite import check_finite_depths

    impact = None if problem.loading.depths is not None else _impact(problem)
    check_finite_depths(problem.striker.indenter, depths, problem.body.model, impact)


def _check_reach(problem: Problem, mesh: MeshSettings) -> None:
    """Refuse, before any work (the default depths too), depths beyond the FE model's reach
    (the finite-strain contact's in its words), a sphere's equator or a table's last radius
    (naming mass and velocity where the impact sets them; on a layer, a remedy that ``mesh``
    resolves)."""
    from ..guards import check_profile_reach
    from ..study.contact.layer import layer_depths
    from ..theory.materials import effective_modulus

    indenter, body = problem.striker.indenter, problem.body.material
    given = problem.loading.depths
    modulus = effective_modulus(problem.striker.material, body)  # a sphere, a table: their end
    layer = layer_depths(problem.geometry, indenter, mesh)
    impact, finite = _impact(problem), problem.body.finite
    check_profile_reach(indenter, modulus, given, impact, finite=finite, layer=layer)


def _check_depths(
    problem: Problem, depths: np.ndarray, mesh: Any, refine: float, estimate: bool
) -> None:
    """Refuse, before any work, depths the FEM cannot take: beyond the finite-strain reach
    (its first ones), too large a contact zone, forces outside the floating-point range, or a
    ladder whose coarsest level ``mesh`` / ``refine`` cannot hold them."""
    indenter, body = problem.striker.indenter, problem.body.material
    if problem.body.finite:
        _check_finite_depths(problem, depths)
        mesh.refined(refine)  # the finest level first: its message names refine's value
    elif problem.loading.depths is not None:
        from ..study.contact.indentation import check_force_range

        check_force_range(indenter, body, depths)
    if problem.geometry.thickness is not None and problem.loading.depths is None:
        _check_layer_depths(problem, depths, mesh)
    if estimate:
        from ..study.contact.indentation import refined_radius

        refined = refined_radius(indenter, depths, mesh, problem.geometry)
        _check_coarsest(mesh, refine, refined, problem.geometry)


def _check_layer_depths(problem: Problem, depths: np.ndarray, mesh: Any) -> None:
    """Refuse, before any work, a layer outside the thickness range at the impact's depths
    (:func:`shtaerman.study.contact.layer.check_thickness`, which names the velocity that fits
    it too, as a contact study's)."""
    from ..study.contact.indentation import default_depths, refined_radius
    from ..study.contact.layer import check_thickness

    indenter, geometry, (mass, velocity) = (
        problem.striker.indenter,
        problem.geometry,
        _impact(problem),
    )

    def refined_at(moved: float | None) -> list[float]:
        """The refined radius (m) at these depths (None), or at the impact's at ``moved``."""
        at = depths
        if moved not in (None, velocity):
            at = default_depths(
                indenter, problem.body.material, mass, moved, problem.striker.material
            )
        return [refined_radius(indenter, at, mesh, geometry)]

    exponent = getattr(indenter, "exponent", 2.0)
    check_thickness(geometry.thickness, refined_at, velocity, exponent, "at these depths")


def _plan(indenter: Any, body: Any, options: dict[str, Any]) -> _Plan:
    """Check every option of :func:`contact` before anything runs."""
    from ..fem.contact.linear import validate_fem_inputs
    from ..fem.mesh import DEFAULTS, FINITE_MESH, MeshSettings
    from ..fem.solver import check_backend
    from ..study.contact.indentation import default_depths
    from ..study.schema import replaced

    problem = _problem(indenter, body, options)
    outputs = {name: options[name] for name in ("force", "estimate", "figure_format")}
    check_outputs(options["out"], **outputs)
    indenter, body = problem.striker.indenter, problem.body.material
    estimate = bool(options["estimate"])
    check_figure_format(options["figure_format"])
    validate_fem_inputs(indenter, body)
    base = options["mesh"]
    if base is None:
        base = FINITE_MESH if problem.body.finite else DEFAULTS
    elif not isinstance(base, MeshSettings):
        raise InputError(
            f"mesh must be a shtaerman.MeshSettings, got {type(base).__name__}; the "
            "keywords mesh_size, mesh_margin, ... set single fields",
            "mesh",
        )
    mesh = replaced(base, {k: options[k] for k in MESH_OPTIONS})  # each named if refused
    refine = checked_positive("refine", options["refine"])
    accuracy = options["accuracy"]
    tolerance = None if accuracy is None else validate_positive("accuracy", accuracy)
    numerics = {"accuracy": accuracy, "refine": refine, "estimate": estimate}
    numerics.update(solver=options["solver"], max_time=options["max_time"])
    check_options(problem, {k: v for k, v in numerics.items() if v is not None})
    max_time = entry("max_time").default if options["max_time"] is None else options["max_time"]
    max_time = validate_positive("max_time", max_time, "s")
    check_backend(options["solver"])
    _check_reach(problem, mesh)
    with warnings.catch_warnings(record=True) as said:  # said after the checks: a refusal
        warnings.simplefilter("always")  # is the one line
        striker = problem.striker
        depths = (
            default_depths(indenter, body, striker.mass, striker.velocity, striker.material)
            if problem.loading.depths is None
            else np.array(problem.loading.depths)  # checked when the problem was built
        )
    _check_depths(problem, depths, mesh, refine, estimate)
    for warning in said:
        warnings.warn_explicit(warning.message, warning.category, warning.filename, warning.lineno)
    rest = (refine, estimate, tolerance, max_time, options["solver"], options["progress"])
    relaxing = {}
    if problem.body.prony is not None:
        relaxing = {"prony": problem.body.prony, "rate": problem.loading.rate}
    impact = None if problem.loading.depths is not None else _impact(problem)
    physics = (relaxing, impact, problem.interface.coefficient, problem.geometry)
    return _Plan(indenter, body, depths, problem.body.rubber(), mesh, *rest, *physics)


@in_python_words
def contact(
    indenter: Indenter | Problem,
    body: Material | None = None,
    *,
    mass: float | None = None,
    velocity: float | None = None,
    depths: Sequence[float] | np.ndarray | None = None,
    striker: Material | None = None,
    thickness: float | None = None,
    base: str | None = None,
    interface: str = "frictionless",
    friction: float | None = None,
    model: str = "linear",
    mooney_ratio: float | None = None,
    yeoh: str | Sequence[float] | None = None,
    gent_limit: float | None = None,
    volumetric: str | None = None,
    prony: PronySeries | str | None = None,
    rate: float | None = None,
    refine: float = 1.0,
    estimate: bool = True,
    accuracy: float | None = None,
    max_time: float | None = None,
    mesh: MeshSettings | None = None,
    mesh_size: float | None = None,
    mesh_margin: float | None = None,
    domain_factor: float | None = None,
    growth: float | None = None,
    max_dofs: float | None = None,
    solver: str = "auto",
    out: str | Path | None = None,
    force: bool = False,
    figure_format: str = "png",
    progress: Callable[[str], None] | None = None,
) -> ContactResult:
    """Press a rigid indenter z = A r^n into the FEM half-space; compare with Shtaerman.

    Parameters
    ----------
    indenter : PowerLawIndenter, SphereIndenter, TabulatedIndenter or Problem
        z = A r^n with n > 1 (against Shtaerman), the exact sphere or a tabulated z(r)
        (against Sneddon; an elastic body); or the whole contact curve
        (:meth:`shtaerman.Problem.curve`), then only numerical and output keywords follow.
    body : Material
        The half-space: E2 in Pa, nu2 in [0, 0.5] (the FEM's validated range).
    mass, velocity : float, optional
        The impact (kg, m/s; default 0.7 kg at 3 m/s) whose x_c the default depths reach,
        with ``striker`` (default rigid) as the striker's material; not with ``depths``.
    depths : sequence of float, optional
        Depths in m, increasing (default: eight up to that x_c, radii a_c/3 .. a_c).
    thickness : float, optional
        Thickness H in m of a layer of ``body`` on a rigid base (linear model); None: the
        half-space. The ``*_analytic`` values stay Shtaerman's half-space solution.
    base : {"bonded", "lubricated"}, optional
        The layer's base: bonded (u = 0, the default with ``thickness``) or lubricated
        (u_z = 0, free to slide); only with ``thickness``.
    interface : {"frictionless", "bonded"}
        The indenter's surface: frictionless, or bonded (a point that touches it sticks, solved
        in load steps; any model). The ``*_analytic`` values stay the frictionless ones.
    friction : float, optional
        Coulomb coefficient >= 0 of a bonded indenter: a point in contact slides where its
        shear exceeds friction x its pressure; None: no slip. Only with ``interface="bonded"``
        (any model; at finite strain resolved on the indenter's normal).
    model : {"linear", "neo-hookean", "mooney-rivlin", "yeoh", "gent"}
        Linear elasticity, or a rubber at finite strain with the same E2, nu2 at small strain.
    mooney_ratio, yeoh, gent_limit, volumetric : optional
        The rubber's shape: r = C01/(C10 + C01) in [0, 1) (Mooney-Rivlin, default 0), "c2,c3"
        or (c2, c3) = (C20, C30)/C10 (Yeoh, default 0,0), Jm > 0 (Gent, required), and the
        volumetric energy "quadratic" K/2 (J-1)^2 (default) or "logarithmic" K/2 (ln J)^2.
    prony : PronySeries or str, optional
        Shear relaxation ``g1:tau1,...`` (tau in s) of a linear body (E2, nu2 its instantaneous
        values), pressed at ``rate``; the ``*_analytic`` values are then Lee and Radok's (exact
        at nu2 = 0.5), the forces nodal sums.
    rate : float, optional
        Pressing speed in m/s (depth V t); required with ``prony``, only with it.
    refine : float
        Divide the mesh size field by it (dofs ~ refine^2).
    estimate : bool
        Run the 3-mesh ladder (refine/2, refine/sqrt 2, refine) for the error estimates.
    accuracy : float, optional
        Refine until the estimated force and beta errors are <= accuracy (linear model,
        within ``max_time`` s).
    max_time : float, optional
        The time budget in s of ``accuracy`` (only with it); None: 60 s.
    mesh : MeshSettings, optional
        The base mesh; ``mesh_size``, ``mesh_margin``, ``domain_factor``, ``growth`` and
        ``max_dofs`` (the ``--mesh-size`` ... options) override its fields.
    solver : {"auto", "superlu", "pardiso"}
        Sparse solver of the linear model.
    out : path, optional
        A new folder for contact.json, CSV curves, VTU fields and (linear) figures; an
        existing one is replaced only with ``force``.
    figure_format : {"png", "svg", "pdf"}
        "svg" or "pdf" also writes each chart in that format beside its PNG.
    progress : callable, optional
        Receives one line per ladder level.

    Returns
    -------
    ContactResult

    Raises
    ------
    shtaerman.validation.InputError
        If an input lies outside its range (nothing is computed).
    """
    options = dict(locals())
    plan = _plan(indenter, body, options)
    from ..output.files import output_folder, staged_folder

    folder = output_folder(out, force=force)
    with contextlib.ExitStack() as stack:  # the folder is reserved before the FEM starts
        stage = stack.enter_context(staged_folder(folder, force=force)) if folder else None
        solution, ladder = _solve(plan)
        report = {**solution.to_dict(), **(ladder.to_dict() if ladder is not None else {})}
        result = ContactResult.from_report(_with_impact(report, plan.impact), solution, ladder)
        if stage is not None:
            _write(result, stage, options["figure_format"])
    _warn_beyond_the_layer(plan)
    return result


def _warn_beyond_the_layer(plan: _Plan) -> None:
    """The validity limits the deepest depth (m) passed (:mod:`shtaerman.guards`)."""
    from ..guards import warn_outside_validity

    deepest = float(plan.depths[-1])
    where = "the deepest depth"
    warn_outside_validity(plan.indenter, deepest, plan.geometry.thickness, plan.finite, where)
