"""What a sweep can compute: the sweep roles of the kinds (parameters, outputs, case function).

A kind is one computation of the suite run on one set of inputs, registered in the one registry
of kinds (:mod:`shtaerman.study.kinds`, which ``verify`` uses too); its parameters, names and
defaults come from :mod:`shtaerman.vocabulary`. Adding one is a registration::

    register_kind(
        Kind(
            name="my-kind",
            description="one line for messages",
            parameters={"mass": Parameter(0.7, "kg"), "E2": Parameter(7.5e6, "Pa")},
            outputs={"x_c": "m", "P_c": "N"},
            case=my_case,        # my_case(params: dict) -> CaseResult(outputs, failures)
            check=my_inputs,     # optional: builds and validates the inputs, raises InputError
            optional_outputs={"estimate": {"error_x_c": ""}},  # optional: when a bool is true
        )
    )

``case`` receives every parameter (defaults, the sweep file's ``[parameters]``, the case's axis
values) as a plain dict of Python values and returns a :class:`CaseResult`: a flat dict of
scalar outputs named as in ``outputs``, and the reasons its own checks fail (``()`` for a kind
without checks). It must be a module-level function (it is shipped to dask workers by
reference) and deterministic. ``check`` runs in the client on every case before any
computation: it should build the inputs the case would build (cheap) so that a value out of its
physical range is a one-line :class:`~shtaerman.validation.InputError` at load time, not a
failed case later.

This is the only module of :mod:`shtaerman.sweep` that imports the computations of the suite.
"""

from __future__ import annotations

import dataclasses
import functools
import math
import time
from collections.abc import Mapping
from dataclasses import dataclass
from typing import Any

from .. import vocabulary
from ..problem import RUBBER_SHAPES
from ..study.kinds import (
    KINDS,
    Kind,
    KindNotAvailableError,
    Parameter,
    get_kind,
    register_kind,
    vocabulary_parameters,
)
from ..study.limits import LEVELS
from ..validation import InputError

__all__ = [
    "KINDS",
    "CaseResult",
    "Kind",
    "KindNotAvailableError",
    "Parameter",
    "get_kind",
    "register_kind",
    "unit_suffix",
]


@dataclass(frozen=True)
class CaseResult:
    """What every kind's case returns: its outputs and its verdict.

    :func:`shtaerman.sweep.engine.execute_case` turns it into the case's status, the one place
    that does for every kind: "ok" when ``failures`` is empty, else "failed" with these reasons
    and the outputs kept. ``failures`` has no default, so a kind states its checks' verdict (or
    ``()``, a kind without checks); a case that returns anything else is recorded failed.

    Attributes
    ----------
    outputs : Mapping of str to float
        The case's scalar outputs (units as the kind's ``outputs`` declare).
    failures : tuple of str
        One line per failed check of the case's own (those ``verify`` applies to a study).
    estimate_missing : str
        Why the case's error estimate is missing ("" when it has one or none was asked): a
        level of its ladder failed, the outputs are the finest level's that passed and its
        error outputs NaN. The case stays "ok"; its record and row say why.
    """

    outputs: Mapping[str, float]
    failures: tuple[str, ...]
    estimate_missing: str = ""


def unit_suffix(name: str, unit: str) -> str:
    """Column name with its unit, for CSV headers as everywhere in the package (``name [unit]``,
    :func:`shtaerman.output.files.csv_header`): ``x_c`` + ``m`` -> ``x_c [m]``; a pure number
    keeps its bare name."""
    return f"{name} [{unit}]" if unit else name


def _sweepable(name: str, outputs: Mapping[str, str], case: Any, check: Any, **roles: Any) -> Kind:
    """Register the sweep roles of kind ``name`` (:func:`register_kind`): its parameters (the
    vocabulary's, :func:`vocabulary_parameters`, unless ``roles`` give them), its ``outputs``
    (``seconds``, where one, is a timing: nondeterministic), ``case`` and ``check``, and the
    other ``roles``; the description its study kind registered unless ``roles`` give one."""
    roles.setdefault("parameters", vocabulary_parameters(name))
    timed = ("seconds",) if "seconds" in outputs else ()
    kind = Kind(name, roles.pop("description", ""), outputs=outputs, case=case, check=check)
    return register_kind(dataclasses.replace(kind, nondeterministic=timed, **roles))


# --- impact: the exact quasi-static model --------------------------------------------------------


# A case's parameters were checked against the vocabulary's ranges for its kind as the sweep
# file was read (:mod:`.spec`): the functions below build the inputs, they do not check them.


def _indenter(p: dict[str, Any]):
    """The case's striker profile: an exact sphere (``sphere_radius``), a tabulated z(r)
    (``profile``, an absolute path since the sweep file was read) or the power law."""
    from ..theory.indenter import PowerLawIndenter
    from ..theory.profiles import SphereIndenter

    if p.get("sphere_radius") is not None:
        return SphereIndenter(p["sphere_radius"])
    if p.get("profile") is not None:
        return _tabulated(p["profile"])
    return PowerLawIndenter(p["shape_coefficient"], p["exponent"])


@functools.lru_cache(maxsize=4)
def _tabulated(path: str):
    """The tabulated profile of the CSV at ``path``, read once per process (every case of a
    sweep has the same one)."""
    from ..theory.profiles import TabulatedIndenter

    return TabulatedIndenter.from_csv(path)


def _material(p: dict[str, Any], young: str, poisson: str):
    from ..theory.materials import RIGID, Material

    if young == "E1" and math.isinf(p.get(young, math.inf)):  # the kinds without E1: rigid
        return RIGID
    return Material(p[young], p[poisson])


def _impact_inputs(p: dict[str, Any]):
    """Mass, velocity and the exact contact law (Shtaerman's, or Sneddon's of a sphere or a
    table) of an impact case."""
    from ..theory.materials import effective_modulus
    from ..theory.sneddon import contact_law

    striker, half_space = _material(p, "E1", "nu1"), _material(p, "E2", "nu2")
    law = contact_law(_indenter(p), effective_modulus(striker, half_space))
    return p["mass"], p["velocity"], law


IMPACT_OUTPUTS = {
    "beta": "N/m^q",
    "x_c": "m",
    "P_c": "N",
    "a_c": "m",
    "p_c": "Pa",
    "t_c": "s",
    "t_y": "s",
}


def _quasi_static(check: Any = None) -> Any:
    """The quasi-static impact of the case's mass and velocity (a closed form, well under a
    millisecond) followed by ``check``, so inputs whose x_c, P_c or t_c leave the
    floating-point range are refused at load rather than as failed cases."""
    import warnings

    from ..theory.viscoelastic import elastic_impact

    def checked(p: dict[str, Any]) -> Any:
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")  # a validity warning is the case's to record
            elastic_impact(*_impact_inputs(p))  # first: velocity 1e300 overflowed
        return None if check is None else check(p)

    return checked


def impact_case(p: dict[str, Any]) -> CaseResult:
    """Maxima and durations of the exact quasi-static impact (``shtaerman impact --json``): a
    closed form (Ateb) for the power law, Sneddon's quadrature for a sphere or a table (beta
    NaN: no power law); without checks of its own. It is :func:`shtaerman.impact`'s, whose
    validity warnings the row records."""
    from ..api.quasi_static import impact

    half_space, striker = _material(p, "E2", "nu2"), _material(p, "E1", "nu1")
    result = impact(
        _indenter(p), half_space, mass=p["mass"], velocity=p["velocity"], striker=striker
    )
    return CaseResult({name: float(getattr(result, name)) for name in IMPACT_OUTPUTS}, ())


_sweepable(
    "impact",
    IMPACT_OUTPUTS,
    impact_case,
    _quasi_static(),
    description="exact quasi-static impact M x'' = -P(x) (Ateb functions; Sneddon's "
    "quadrature for a sphere or a table)",
)


# --- contact: the linear FEM indentation against Shtaerman's solution ----------------------------

_MESH = vocabulary.fields(
    ("mesh_size", "mesh_margin", "domain_factor", "growth", "axis_size", "axis_growth", "max_dofs")
)
"""Sweep parameter -> MeshSettings field."""


def _mesh(p: dict[str, Any]) -> tuple[Any, Any]:
    """The case's mesh settings and them refined by ``refine`` (an InputError naming refine
    now, not at run time)."""
    from ..fem.mesh import MeshSettings

    mesh = MeshSettings(**{field_name: p[name] for name, field_name in _MESH.items()})
    return mesh, mesh if p["refine"] == 1.0 else mesh.refined(p["refine"])


def _curve_inputs(p: dict[str, Any]):
    """Indenter, half-space, depths and mesh of a contact curve (linear or finite strain)."""
    import numpy as np

    indenter, half_space = _indenter(p), _material(p, "E2", "nu2")
    depths = None if p["depths"] is None else np.array(p["depths"], dtype=float)
    _, mesh = _mesh(p)
    mesh.check_size()  # at load, as the contact CLI does: not a failed case at run time
    return indenter, half_space, depths, mesh


CURVE_PARTS = ("model", "prony", "rate", "interface", "friction", "thickness", "base")
"""The parts of a contact curve a contact or finite-strain case may set (as ``shtaerman
contact`` takes them), checked by :meth:`~shtaerman.problem.Problem.curve`."""


def _curve_problem(p: dict[str, Any], indenter: Any, half_space: Any) -> Any:
    """The case's contact curve as :meth:`shtaerman.problem.Problem.curve` builds and checks
    it (its parts: a Prony text, an interface, a friction, a layer; :data:`~shtaerman.problem.
    SUPPORT` refuses what does not combine, one line naming the key)."""
    from ..problem import RUBBER_OPTIONS, Problem

    model = p.get("model") or "linear"
    given = {name: p.get(name) for name in CURVE_PARTS}
    given |= {
        name: p.get(name)
        for name in RUBBER_OPTIONS
        if RUBBER_SHAPES.get(name, model) == model and model != "linear"
    }
    if given["thickness"] is None:
        given["base"] = None  # the half-space: base's default is a layer's
    return Problem.curve(indenter, half_space, **given)


def _contact_inputs(p: dict[str, Any]):
    """A contact case's inputs (its curve checked as a problem, :func:`_curve_problem`); a
    sphere's or a table's deepest depth (the given ``depths``, else the default ones: the
    paper's impact's x_c) within its FE profile, as `shtaerman contact` and a contact study
    refuse it at load."""
    from ..fem.solver import check_backend
    from ..guards import check_profile_reach
    from ..theory.materials import RIGID, effective_modulus

    indenter, half_space, depths, mesh = _curve_inputs(p)
    problem = _curve_problem(p, indenter, half_space)
    impact = (vocabulary.entry("mass").default, vocabulary.entry("velocity").default)
    modulus = effective_modulus(RIGID, half_space)  # default_depths' striker
    # the default depths are the paper's impact's (a contact case has no mass or velocity)
    check_profile_reach(indenter, modulus, depths, impact, note=", or give depths=...")
    physics = {"friction": problem.interface.coefficient, "geometry": problem.geometry}
    if problem.body.prony is not None:
        physics |= {"prony": problem.body.prony, "rate": problem.loading.rate}
    return indenter, half_space, depths, mesh, check_backend(p["solver"]), physics


CONTACT_OUTPUTS = {
    "beta_fem": "N/m^q",
    "exponent_fem": "",
    "beta_analytic": "N/m^q",
    "error_force": "",
    "error_beta": "",
    "error_exponent": "",
    "error_contact_radius": "",
    "error_central_pressure": "",
    "dofs": "",
    "seconds": "s",
}


def contact_case(p: dict[str, Any]) -> CaseResult:
    """FEM contact curve: fitted beta and exponent, worst relative errors, size and time (the
    errors are the case's outputs, mapped over the grid, not checks)."""
    from ..guards import warn_outside_validity
    from ..study.contact.indentation import run_indentation

    indenter, half_space, depths, mesh, solver, physics = _contact_inputs(p)
    start = time.perf_counter()
    result = run_indentation(indenter, half_space, depths, mesh, backend=solver, **physics)
    seconds = time.perf_counter() - start
    deepest = result.steps[-1].depth  # recorded in the case's warnings, as the API warns
    warn_outside_validity(indenter, deepest, None, False, "the deepest depth")
    errors = result.errors()
    outputs = {
        "beta_fem": float(result.fit.beta_fixed_exponent),
        "exponent_fem": float(result.fit.exponent),
        "beta_analytic": float(result.analytic.beta),  # a profile's: fitted as the FEM's
        **{
            f"error_{key}": float(errors[key])
            for key in ("force", "beta", "exponent", "contact_radius", "central_pressure")
        },
        "dofs": int(result.mesh_stats["dofs"]),
        "seconds": seconds,
    }
    return CaseResult(outputs, ())


_sweepable("contact", CONTACT_OUTPUTS, contact_case, _contact_inputs)


# --- dynamic: the elastodynamic FE impact against the quasi-static one ------------------------


def _layer_given(p: dict[str, Any], required: bool) -> bool:
    """Whether the case has a layer: its thickness in m or as H / a_c, not both (refused;
    and, where ``required``, neither); a ``base`` only with a layer."""
    given = [key for key in ("thickness", "thickness_ratio") if p.get(key) is not None]
    if len(given) > 1 or (required and not given):
        raise InputError(
            "thickness: give the layer's thickness (m) or its thickness_ratio (H / a_c), "
            f"exactly one of them; got {' and '.join(given) or 'neither'}",
            "thickness",
        )
    if not given and p.get("base", "bonded") != "bonded":
        raise InputError(
            "base: applies to a layer only; give thickness (m) or thickness_ratio too", "base"
        )
    return bool(given)


def _layer(p: dict[str, Any]) -> dict[str, Any]:
    """The case's layer as keywords of :meth:`~shtaerman.problem.Problem.impact`: its
    ``thickness`` (given in m, or as H / a_c at the case's quasi-static impact on the
    half-space) and ``base``; {} without one (the half-space)."""
    from ..study.contact.layer import LayerSpec
    from ..study.schema import exact_impacts

    if not _layer_given(p, required=False):
        return {}
    exact = exact_impacts(p["mass"], _indenter(p), _material(p, "E2", "nu2"))(p["velocity"])
    layer = LayerSpec(p["thickness"], p["thickness_ratio"], p["base"]).resolved(float(exact.a_c))
    return {"thickness": layer.thickness, "base": layer.base}


DYNAMIC_OUTPUTS = {
    "restitution": "",
    "energy_radiated_fraction": "",
    "estimate_energy_fraction": "",
    "x_max": "m",
    "P_max": "N",
    "t_x_max": "s",
    "t_contact": "s",
    "x_c": "m",
    "P_c": "N",
    "t_c": "s",
    "t_y": "s",
    "difference_x": "",
    "difference_P": "",
    "difference_t": "",
    "difference_worst": "",
    "energy_balance_error": "",
    "reflected_energy_fraction": "",
    "dofs": "",
    "seconds": "s",
}
"""difference_*: quasi-static / dynamic - 1 for x_c / x_max, P_c / P_max and t_c against
t_contact / 2 (= t_y / t_contact); difference_worst: the largest of their magnitudes.
energy_radiated_fraction is 1 - e^2, all the energy left in the body (with a ``prony`` series
waves and hysteresis together: :data:`DYNAMIC_LOSSES` splits it)."""
DYNAMIC_ERRORS = {
    "error_x_max": "",
    "error_P_max": "",
    "error_t_contact": "",
    "error_restitution": "",
    "error_energy_radiated_fraction": "",
    "error_difference_x": "",
    "error_difference_P": "",
    "error_difference_t": "",
    "error_difference_worst": "",
}
"""With ``estimate = true`` (:mod:`shtaerman.study.dynamic.accuracy`: two coarser runs, about
0.75 of the case's cost again): the Richardson estimates of the FEM's error. error_x_max ..
error_energy_radiated_fraction are relative; error_difference_x, _P, _t are absolute, in the
unit of the difference (estimated on the difference's own values over the ladder);
error_difference_worst is the largest of those three."""
DYNAMIC_LOSSES = {
    "energy_dissipated_fraction": "",
    "energy_wave_fraction": "",
    "energy_hysteresis_fraction": "",
}
"""With a ``prony`` series: the energy dissipated by the end of the run and the single-run split
of 1 - e^2 (energy_radiated_fraction) into waves beyond the monitor radius and hysteresis,
fractions of M v0^2/2 (:attr:`~shtaerman.fem.impact_run.ImpactRun.losses`;
empty for an elastic case of a prony axis)."""


def dynamic_case(p: dict[str, Any]) -> CaseResult:
    """The dynamic FE impact of the case (:func:`shtaerman.dynamic` on its problem, the command
    line's numbers, every body) beside the quasi-static one and the first-order radiation
    estimate (a rubber has none: NaN); failed, as ``shtaerman dynamic`` warns, when its energy
    balance or its reflected energy exceed what the studies allow."""
    import warnings

    from ..api.dynamic_result import check_failures
    from ..api.fem_dynamic import dynamic

    problem, numerics = _dynamic(p)
    start = time.perf_counter()
    result = dynamic(problem, **numerics)
    seconds = time.perf_counter() - start
    if p["volumetric"] is not None and p["nu2"] == 0.5:  # as the command line warns
        warnings.warn(
            "volumetric has no effect at nu2 0.5 (no volumetric energy): ignored", stacklevel=2
        )
    dyn, quasi, radiation = result.dynamic, result.quasi_static, result.radiation_estimate
    differences = {key: float(result.differences[f"{key}_c"]) for key in ("x", "P", "t")}
    outputs = {
        **{key: float(dyn[key]) for key in (*DYNAMIC_OUTPUTS, *DYNAMIC_LOSSES) if key in dyn},
        "estimate_energy_fraction": math.nan if radiation is None else radiation["energy_fraction"],
        **{key: float(quasi[key]) for key in ("x_c", "P_c", "t_c", "t_y")},
        **{f"difference_{key}": value for key, value in differences.items()},
        "difference_worst": max(abs(value) for value in differences.values()),
        "dofs": int(result.mesh["dofs"]),
        "seconds": seconds,
        **_result_errors(result, p["estimate"]),
    }
    missing = result.estimate_missing or ""
    return CaseResult(outputs, tuple(check_failures(result, problem)), missing)


def _result_errors(result: Any, estimate: bool) -> dict[str, float]:
    """:data:`DYNAMIC_ERRORS` of a case's :class:`~shtaerman.DynamicResult` run with its
    ladder, ``estimate`` ({} without one; NaN where the ladder gave none, e.g. 1 - e^2 of a
    massless elastic body, 0 to round-off, and all NaN when a level failed: the result's
    ``estimate_missing``)."""
    if result.error_estimate is None:
        return dict.fromkeys(DYNAMIC_ERRORS, math.nan) if estimate else {}
    relative = ("x_max", "P_max", "t_contact", "restitution", "energy_radiated_fraction")
    out = {f"error_{key}": float(result.error_estimate.get(key, math.nan)) for key in relative}
    for key, name in (("x", "x_c"), ("P", "P_c"), ("t", "t_c")):
        out[f"error_difference_{key}"] = float(result.differences_error[name])
    out["error_difference_worst"] = max(out[f"error_difference_{key}"] for key in "xPt")
    return out


def _struck_case(p: dict[str, Any]) -> tuple[Any, ...]:
    """The striker, the body and the keywords of a dynamic or effects case's impact, as
    :meth:`shtaerman.problem.Problem.impact` and :func:`shtaerman.problem.parts` take them
    (a rubber option only for the case's own model, as a study file's swept model takes it)."""
    from ..problem import RUBBER_OPTIONS
    from ..theory.materials import Material

    rubber = {
        name: p[name]
        for name in RUBBER_OPTIONS
        if p[name] is not None and RUBBER_SHAPES.get(name, p["model"]) == p["model"]
    }
    body = Material(p["E2"], p["nu2"], p["density2"])
    names = ("mass", "velocity", "model", "prony", "interface", "friction")  # prony: its text
    keywords = {name: p.get(name) for name in names}  # checked by the problem's parts
    return _indenter(p), body, {**keywords, **_layer(p), **rubber}


def _dynamic(p: dict[str, Any]) -> tuple[Any, dict[str, Any]]:
    """A dynamic case as the command line builds it: its
    :class:`~shtaerman.problem.Problem` (the rubber options of its model, as a study file's
    swept model takes them) and the keywords of :func:`shtaerman.dynamic`: the numerics set to
    other than the kind's defaults (an ``axis_size`` as the linear body's settings, refused
    for a rubber by :data:`shtaerman.problem.OPTION_SUPPORT`)."""
    from ..api.fem_dynamic import SETTINGS_OPTIONS
    from ..fem.dynamic_contact import DynamicSettings
    from ..problem import Problem, check_options

    indenter, body, keywords = _struck_case(p)
    problem = Problem.impact(indenter, body, **keywords)
    numerics = _changed(p, "dynamic", SETTINGS_OPTIONS)
    axis = _changed(p, "dynamic", ("axis_size",))
    check_options(problem, axis)  # a study-file key: the table refuses it for a rubber
    if axis:
        numerics["settings"] = DynamicSettings(**axis)
    return problem, {**numerics, "refine": p["refine"], "estimate": p["estimate"]}


def _changed(p: dict[str, Any], kind: str, names: tuple[str, ...]) -> dict[str, Any]:
    """The parameters ``names`` of a case of ``kind`` set to other than their defaults."""
    defaults = KINDS[kind].defaults()
    return {name: p[name] for name in names if p[name] != defaults[name]}


def _dynamic_check(p: dict[str, Any]) -> None:
    """Every input of a dynamic case checked at load as ``shtaerman dynamic`` checks them
    (:func:`shtaerman.api.fem_dynamic.check_dynamic`: the problem's parts and options, the
    numerics' ranges and ladder, the impact's floating-point range, a layer's thickness and a
    half-space's depth against the impact), nothing computed."""
    from ..api.fem_dynamic import check_dynamic

    problem, numerics = _dynamic(p)
    check_dynamic(problem, **numerics)


_sweepable(
    "dynamic",
    DYNAMIC_OUTPUTS,
    dynamic_case,
    _dynamic_check,
    optional_outputs={"estimate": DYNAMIC_ERRORS, "prony": DYNAMIC_LOSSES},
    levels={f"difference_{key}": LEVELS for key in ("x", "P", "t", "worst")},
)


# --- effects: which effect of the impact moves P_max, x_max, t_contact and e ---------------------

EFFECT_NAMES = ("pad", "waves", "finite strain", "viscoelasticity", "friction")
"""The effects of :mod:`shtaerman.api.effect_table.variants`, in its order: an effects case's
``dominant_<quantity>`` is the index of the dominant one here (NaN: none ran)."""
EFFECT_QUANTITIES = ("P_max", "x_max", "t_contact", "restitution")
EFFECTS_OUTPUTS = {
    **{f"dominant_{key}": "" for key in EFFECT_QUANTITIES},
    **{f"resolved_{key}": "" for key in EFFECT_QUANTITIES},
    **{f"change_{key}": "" for key in EFFECT_QUANTITIES},
    **{f"interaction_{key}": "" for key in EFFECT_QUANTITIES},
    "seconds": "s",
}
"""Per quantity (the table's ``dominant``, :meth:`~shtaerman.api.effect_table.EffectTable.
to_dict`): ``dominant_<q>`` the index in :data:`EFFECT_NAMES` of the effect whose change alone
is largest, ``resolved_<q>`` 1 when the error bars resolve that ranking, 0 when not, NaN when a
bar is missing (estimate = false); ``change_<q>`` the full problem's change against the paper's
quasi-static value (a fraction; e - 1 for the restitution), ``interaction_<q>`` the full
change minus the sum of the single ones (NaN where a run is refused)."""


def _effects_inputs(p: dict[str, Any]) -> tuple[dict[str, Any], dict[str, Any]]:
    """The case's problem as parts (:func:`shtaerman.problem.parts`: they need not combine as
    a whole, the variants that do run) and the numerical keywords of :func:`shtaerman.effects`
    set to other than the kind's defaults (in their ranges since the file was read); what the
    table refuses as a whole (:func:`shtaerman.api.effect_table.run.check_runs`) is refused
    here, at load."""
    from ..api.effect_table.run import check_runs
    from ..api.effect_table.variants import parts_of, variants
    from ..api.fem_dynamic import SETTINGS_OPTIONS
    from ..problem import parts

    indenter, body, keywords = _struck_case(p)
    found = parts(indenter, body, **keywords)
    numerics = _changed(p, "effects", (*SETTINGS_OPTIONS, "refine"))
    numerics["estimate"] = p["estimate"]  # the sweep's default (false), not the API's
    check_runs(variants(parts_of(found))[0], numerics)
    return found, numerics


def effects_case(p: dict[str, Any]) -> CaseResult:
    """The effect table of the case's impact (:func:`shtaerman.effects`, the command line's
    ``shtaerman effects``): per quantity its dominant effect, whether resolved, the full
    change and the interaction; without checks of its own (a refused variant is a row of the
    table, not a failure); with ``estimate``, the runs whose ladder lost a level, and why, in
    its ``estimate_missing``."""
    from ..api.effect_table import effects

    found, numerics = _effects_inputs(p)
    start = time.perf_counter()
    table = effects(found, **numerics).to_dict()
    seconds = time.perf_counter() - start
    outputs: dict[str, float] = {"seconds": seconds}
    full = next(run for run in table["runs"] if run["label"] == "full")["changes"]
    for key in EFFECT_QUANTITIES:
        dominant = table["dominant"][key]
        effect, resolved = dominant["effect"], dominant["resolved"]
        outputs[f"dominant_{key}"] = math.nan if effect is None else EFFECT_NAMES.index(effect)
        outputs[f"resolved_{key}"] = math.nan if resolved is None else float(resolved)
        outputs[f"change_{key}"] = _number(full[key]["change"])
        outputs[f"interaction_{key}"] = _number(table["interaction"][key]["change"])
    missing = [f"{run['label']}: {run['error_note']}" for run in table["runs"] if run["error_note"]]
    return CaseResult(outputs, (), "; ".join(missing) if p["estimate"] else "")


def _number(value: float | None) -> float:
    """A table's change (None: n/a) as a sweep output (NaN)."""
    return math.nan if value is None else float(value)


_sweepable(
    "effects",
    EFFECTS_OUTPUTS,
    effects_case,
    _quasi_static(lambda p: _effects_inputs(p)),
    categories={f"dominant_{key}": EFFECT_NAMES for key in EFFECT_QUANTITIES},
    parameters={
        name: parameter
        for name, parameter in vocabulary_parameters("dynamic").items()
        if name != "axis_size"  # the effect table's runs grade their own axis
    },
)


# --- layer: the FEM contact on a layer against Shtaerman's half-space, and the impact on it ----


def _layer_study(p: dict[str, Any]):
    """The contact study of a layer case (its thickness resolved at the impact's x_c), on
    the study file's path (:func:`~shtaerman.study.contact.loader.contact_study`)."""
    from ..study.contact.layer import LayerSpec
    from ..study.contact.loader import contact_study

    _layer_given(p, required=True)
    mesh, _ = _mesh(p)
    layer = LayerSpec(p["thickness"], p["thickness_ratio"], p["base"], p["dynamic"], p["density2"])
    return contact_study(
        takes_depths=False,  # a layer case's depths are its impact's
        indenter=_indenter(p),
        striker=_material(p, "E1", "nu1"),
        half_space=_material(p, "E2", "nu2"),
        **{name: p[name] for name in ("mass", "velocity", "refine")},
        depths=None,
        mesh=mesh,
        quick_mesh=mesh,
        layer=layer,
    )


LAYER_OUTPUTS = {
    "H": "m",
    "H_over_a_c": "",
    "a_c": "m",
    "force_ratio": "",
    "error_force_ratio": "",
    "x_c": "m",
    "P_c": "N",
    "x_max_layer": "m",
    "P_max_layer": "N",
    "x_max_ratio": "",
    "P_max_ratio": "",
    "checks_passed": "",
    "dofs": "",
    "seconds": "s",
}
"""H and H / a_c: the layer (a_c the half-space contact radius at the half-space impact's x_c);
force_ratio: P_layer / P_Shtaerman at x_c, error_force_ratio its estimated relative error (the
3-mesh ladder's Richardson estimate of the force, worst depth, plus the interpolation to x_c);
x_c, P_c: the half-space impact (exact); x_max_layer, P_max_layer: the quasi-static impact
integrated on the layer's tabulated FE law, and their ratios x_max_ratio, P_max_ratio to x_c
and P_c."""
LAYER_DYNAMIC_OUTPUTS = {
    "restitution": "",
    "x_max_dynamic": "m",
    "P_max_dynamic": "N",
    "energy_balance_error": "",
}
"""With ``dynamic = true``: the dynamic FE impact on the layer (rigid striker, density2): its
restitution, maxima and energy balance error (of M v0^2/2)."""


def layer_case(p: dict[str, Any]) -> CaseResult:
    """One layer study (3-mesh ladder, the impact on its FE law) reduced to scalars; failed
    when the study's checks fail (as ``verify`` judges it)."""
    from ..study.checks import failures
    from ..study.contact.runner import run_contact_study

    outcome = run_contact_study(_layer_study(p))
    layer, half_space = outcome.layer, outcome.impacts["analytic"]
    outputs = {
        "H": layer.thickness,
        "H_over_a_c": layer.thickness_ratio,
        "a_c": layer.contact_radius,
        "force_ratio": layer.force_ratio,
        "error_force_ratio": layer.force_ratio_error,
        "x_c": half_space["x_c"],
        "P_c": half_space["P_c"],
        "x_max_layer": float(layer.x_max),
        "P_max_layer": float(layer.P_max),
        "x_max_ratio": float(layer.x_max_ratio),
        "P_max_ratio": float(layer.P_max_ratio),
        "checks_passed": float(outcome.passed),
        "dofs": int(outcome.contact.mesh_stats["dofs"]),
        "seconds": outcome.seconds,
        **_layer_dynamic(layer),
    }
    return CaseResult(outputs, failures(outcome.checks), outcome.accuracy.missing)


def _layer_dynamic(layer: Any) -> dict[str, float]:
    """:data:`LAYER_DYNAMIC_OUTPUTS` of a layer's findings ({} without its dynamic impact)."""
    if layer.restitution is None:
        return {}
    return {
        "restitution": float(layer.restitution),
        "x_max_dynamic": float(layer.x_max_dynamic),
        "P_max_dynamic": float(layer.P_max_dynamic),
        "energy_balance_error": float(layer.dynamic_energy_balance),
    }


_sweepable(
    "layer",
    LAYER_OUTPUTS,
    layer_case,
    _quasi_static(_layer_study),
    description="FEM contact on a layer on a rigid base against Shtaerman's half-space at "
    "the impact's x_c, and the quasi-static impact on the layer's FE law",
    optional_outputs={"dynamic": LAYER_DYNAMIC_OUTPUTS},
)


# --- finite-strain: neo-Hookean contact against Shtaerman, and the impact on it ----------------

FORCE_RATIO_AT = (0.1, 0.25, 0.5, 0.75)
"""x/a (linear contact radius) at which a finite-strain case reports P / P_linear-FEM."""


def check_rubber_options(parameters: Mapping[str, Any], axes: Mapping[str, list[Any]]) -> None:
    """Refuse, in one line naming it, a rubber option that no case of the sweep uses: a shape
    option whose model no case has, or
    ``volumetric`` where every case is linear. With ``model`` an axis each option applies to
    the cases of its model, as a study file's swept model takes them."""
    from ..problem import RUBBER_OPTIONS

    models = set(axes.get("model", [parameters.get("model")]))
    for name in RUBBER_OPTIONS:
        values = axes.get(name, [parameters.get(name)])
        if all(value is None for value in values):
            continue
        owner = RUBBER_SHAPES.get(name)
        if owner is not None and owner not in models:
            raise InputError(
                f"{name}: applies to the {owner} model only; this sweep's model is "
                f"{', '.join(sorted(models))}: set model = {owner!r} or leave {name} out",
                name,
            )
        if owner is None and models <= {"linear"}:
            raise InputError(
                f"{name}: applies to the finite-strain models only (model one of "
                "neo-hookean, mooney-rivlin, yeoh, gent); this sweep's model is linear",
                name,
            )


def _finite_inputs(p: dict[str, Any]):
    """The finite-strain study of a case, on the study file's path
    (:func:`~shtaerman.study.finite.loader.finite_study`: its profile's reach checked): the
    rubber ``model`` with its own shape parameters and ``volumetric``."""
    from ..study.finite.loader import Ladder, finite_study, rubber_of

    indenter, half_space, depths, mesh = _curve_inputs(p)
    problem = _curve_problem(p, indenter, half_space)
    shapes = {k: p[k] for k, owner in RUBBER_SHAPES.items() if owner == p["model"]}
    rubber = rubber_of(half_space, p["model"], volumetric=p["volumetric"], **shapes)
    ladder = Ladder(*(p[name] for name in ("reach", "depth_steps", "small_ratio", "small_steps")))
    return finite_study(
        indenter=indenter,
        half_space=half_space,
        mass=p["mass"],
        velocity=p["velocity"],
        ladder=ladder,
        quick_ladder=ladder,
        mesh=mesh,
        quick_mesh=mesh,
        depths=None if depths is None else tuple(float(d) for d in depths),
        rubber=rubber,
        interface=problem.interface,
        geometry=problem.geometry,
    )


def _finite_check(p: dict[str, Any]) -> Any:
    """A finite-strain case's inputs, and its depths against the finite-strain contact's
    reach (x/a in [1e-6, 1.2]) as its run checks them: the given ``depths``, or the ladder up
    to ``reach`` x the case's linear x_c (naming mass and velocity); at load, not as a failed
    case. The quasi-static impact is solved first (its floating-point range), once."""
    import warnings

    import numpy as np

    from ..fem.contact.finite import check_finite_depths
    from ..study.finite.runner import ladder
    from ..study.schema import exact_impacts
    from ..theory.materials import RIGID, effective_modulus

    with warnings.catch_warnings():
        warnings.simplefilter("ignore")  # a validity warning is the case's to record
        study = _finite_inputs(p)
        model, modulus = study.rubber.name, effective_modulus(RIGID, study.half_space)
        impact = (study.mass, study.velocity)
        x_c = exact_impacts(study.mass, study.indenter, study.half_space)(study.velocity).x_c
    if study.depths is not None:
        check_finite_depths(study.indenter, np.asarray(study.depths), model)
        return study
    depths = ladder(study.indenter, modulus, x_c, study.ladder)
    check_finite_depths(study.indenter, depths, model, impact)
    return study


FINITE_OUTPUTS = {
    **{f"force_ratio_xa{round(100 * r):02d}": "" for r in FORCE_RATIO_AT},
    "x_c": "m",
    "P_c": "N",
    "t_c": "s",
    "x_c_ratio": "",
    "P_c_ratio": "",
    "t_c_ratio": "",
    "xa_within_1pct": "",
    "xa_within_5pct": "",
    "velocity_within_1pct": "m/s",
    "velocity_within_5pct": "m/s",
    "checks_passed": "",
    "dofs": "",
    "seconds": "s",
}
"""force_ratio_xaNN: P_finite / P_linear-FEM (same mesh) at x/a = NN/100, interpolated linearly
in x/a (NaN outside the computed depths); x_c, P_c, t_c: the impact on the tabulated
finite-strain curve, and their ratios to Shtaerman's exact linear impact; xa/velocity_within_*:
the depth (as x/a, and as the impact velocity whose x_c reaches it) up to which P stays within
1 % / 5 % of the linear force (NaN if the computed depths never leave it)."""


def finite_strain_case(p: dict[str, Any]) -> CaseResult:
    """One finite-strain study (the study kind's run, on the case's mesh alone: no
    error-estimate ladder) reduced to scalars; failed when the study's checks fail."""
    import numpy as np

    from ..study.checks import failures
    from ..study.finite.runner import run_finite_strain_study

    outcome = run_finite_strain_study(_finite_inputs(p), estimate=False)
    rows = outcome.rows()
    ratio = np.array([row["depth_to_radius"] for row in rows])
    force = np.array([row["force_ratio_fem"] for row in rows])
    out: dict[str, float] = {
        f"force_ratio_xa{round(100 * r):02d}": float(np.interp(r, ratio, force))
        if ratio[0] <= r <= ratio[-1]
        else math.nan
        for r in FORCE_RATIO_AT
    }
    finite, ratios = outcome.impacts["finite_strain"], outcome.ratios()
    out |= {key: float(finite[key]) for key in ("x_c", "P_c", "t_c")}
    out |= {f"{key}_ratio": float(ratios[key]) for key in ("x_c", "P_c", "t_c")}
    for entry in outcome.validity():
        level = f"{round(100 * entry['level'])}pct"
        known = entry["status"] == "interpolated"
        out[f"xa_within_{level}"] = float(entry["depth_to_radius"]) if known else math.nan
        out[f"velocity_within_{level}"] = float(entry["velocity"]) if known else math.nan
    out |= {
        "checks_passed": float(outcome.passed),
        "dofs": int(outcome.finite.curve.mesh_stats["dofs"]),
        "seconds": outcome.seconds,
    }
    return CaseResult(out, failures(outcome.checks))


_sweepable("finite-strain", FINITE_OUTPUTS, finite_strain_case, _finite_check)
