"""The contact kind's text and results.json entry: the impact three ways, the error estimates,
the finding, the times and the cross-check summary row, from the entry's numbers."""

from __future__ import annotations

import math
from collections.abc import Mapping
from typing import Any

from ..study.contact.runner import IMPACT_KEYS, StudyOutcome
from ..theory.sneddon import profile_inputs
from .case import case_words, interface_words, prefixed
from .entry import kind_entry
from .wording import finest_passed, number, plus_minus, seconds, times_text

__all__ = [
    "CONTACT_COLUMNS",
    "IMPACT_COLUMNS",
    "entry",
    "findings",
    "summary_row",
    "tables",
    "timing_text",
]

UNITS = {"beta": "N/m^q", "x_c": "m", "P_c": "N", "a_c": "m", "p_c": "Pa", "t_c": "s", "t_y": "s"}
VARIANTS = {
    "analytic": "exact (analytic beta, Ateb)",
    "fem_fitted": "FEM-fitted beta, Ateb",
    "fem_tabulated": "FEM P(x) tabulated, ODE",
}
CONTACT_COLUMNS = {
    "force": "force",
    "beta": "beta",
    "exponent": "exponent",
    "contact_radius": "radius",
    "central_pressure": "p(0)",
}
"""Contact error -> its column in the cross-check summary."""
IMPACT_COLUMNS = ("x_c", "P_c", "t_c")
"""Impact maxima in the cross-check summary."""
ESTIMATED = CONTACT_COLUMNS | {"contact_radius": "contact radius"}
"""Estimated quantity -> its row in the error estimates table."""


def _timings(outcome: StudyOutcome, output: float | None) -> dict[str, float | None]:
    """Wall times of one study in s (``output``: writing its files and figures, if known)."""
    fem = float(outcome.contact.timings.get("total", float("nan")))
    levels = outcome.convergence.levels if outcome.convergence is not None else []
    convergence = sum(float(level.get("timings", {}).get("total", 0.0)) for level in levels)
    return {
        "fem_curve": fem,
        "convergence": convergence,
        "computation": outcome.seconds,
        "output": output,
        "total": outcome.seconds + (output or 0.0),
    }


def entry(
    outcome: StudyOutcome,
    files: dict[str, str],
    output_seconds: float | None = None,
    figures: Mapping[str, str] | None = None,
) -> dict[str, object]:
    """One contact study's entry of results.json.

    ``timings`` splits the study's wall time in s: ``fem_curve`` (the FEM contact curve),
    ``convergence`` (its meshes), ``computation`` (= ``seconds``), ``output`` (files and
    figures) and ``total``; ``figures``: caption to PNG path relative to the result folder.
    """
    study, layer = outcome.study, outcome.study.layer
    document = {
        "case": case_words(
            thickness=None if layer is None else layer.thickness,
            base=None if layer is None else layer.base,
            interface=study.interface.kind,
            friction=study.interface.friction,
        ),
        "interface": {"kind": study.interface.kind, "friction": study.interface.friction},
        "inputs": {
            **profile_inputs(study.indenter),
            "E1": study.striker.youngs_modulus,
            "nu1": study.striker.poisson_ratio,
            "E2": study.half_space.youngs_modulus,
            "nu2": study.half_space.poisson_ratio,
            "mass": study.mass,
            "velocity": study.velocity,
        },
        "contact": outcome.contact.to_dict(),
        "impact": outcome.impacts,
        "differences": outcome.differences(),
    }
    if outcome.layer is not None:
        document["layer"] = outcome.layer.to_dict()
    if outcome.interface_effect is not None:
        document["interface_effect"] = outcome.interface_effect.to_dict()
    result = kind_entry(outcome, document, files, output_seconds, figures)
    result["timings"] = _timings(outcome, output_seconds)
    if outcome.convergence:
        result["convergence"] = outcome.convergence.to_dict()
    if outcome.accuracy:
        result["accuracy"] = outcome.accuracy.to_dict()
    return result


LAYER_VARIANTS = {
    "analytic": "half-space (Shtaerman, Ateb)",
    "fem_fitted": "layer: FEM power-law fit, Ateb",
    "fem_tabulated": "layer: FEM P(x) tabulated, ODE",
}
"""The variants' labels on a layer: the analytic impact is the half-space's."""


def exact_law(study: Mapping[str, Any]) -> tuple[str, str]:
    """Whose exact contact law the study's striker has, and how its impact is solved:
    Shtaerman's and Ateb's for z = A r^n, Sneddon's and the quadrature for a sphere or a
    tabulated profile (``inputs.profile``)."""
    profile = study.get("inputs", {}).get("profile")
    if profile is None:
        return "Shtaerman's", "Ateb"
    return f"Sneddon's ({profile['kind']} profile)", "quadrature"


def _impact_table(study: Mapping[str, Any]) -> dict[str, object]:
    variants = LAYER_VARIANTS if study.get("layer") else VARIANTS
    name, solution = exact_law(study)
    if solution != "Ateb":
        variants = variants | {
            "analytic": variants["analytic"]
            .replace("analytic beta, Ateb", f"{name} law, {solution}")
            .replace("Shtaerman, Ateb", f"{name} law, {solution}")
        }
    rows = [
        [label] + [number(study["impact"][variant][key], ".6g") for key in IMPACT_KEYS]
        for variant, label in variants.items()
        if variant in study["impact"]
    ]
    header = ["impact", *(f"{k} ({UNITS[k]})" for k in IMPACT_KEYS)]
    return {"title": "The impact three ways", "header": header, "rows": rows}


def _estimate_table(study: Mapping[str, Any]) -> dict[str, object] | None:
    """FEM value ± its Richardson estimate, the true error and their ratio (effectivity)."""
    accuracy = study.get("accuracy")
    if not accuracy or accuracy.get("estimate_missing"):  # a level failed: the findings say
        return None
    ladder = ", ".join(str(level["dofs"]) for level in accuracy["mesh_ladder"])
    rows = []
    depths = accuracy.get("extrapolated_depth", {})
    for key, label in ESTIMATED.items():
        if key not in accuracy["error_estimate"]:
            continue
        details = accuracy["estimate_details"][key]
        where = f" at depth {depths[key]:.4e} m (the worst)" if key in depths else ""
        rows.append(
            [
                label + where,
                number(details["value"], ".6g") + plus_minus(accuracy["error_estimate"][key]),
                number(accuracy.get("true_error", {}).get(key), ".1e"),  # none: no exact
                number(accuracy.get("effectivity", {}).get(key), ".2f"),
                details["method"] + (f" ({details['reason']})" if details["reason"] else ""),
            ]
        )
    return {
        "title": f"Error estimates (3-mesh ladder, {ladder} dofs): value ± estimated relative "
        "error, the true error against the exact solution, and their ratio",
        "header": ["quantity", "FEM value ± estimate", "true error", "effectivity", "method"],
        "rows": rows,
    }


def tables(study: Mapping[str, Any]) -> list[dict[str, object]]:
    """The impact three ways and, after a ladder, the error estimates."""
    return [table for table in (_impact_table(study), _estimate_table(study)) if table]


def _layer_findings(
    layer: Mapping[str, Any], interface: Mapping[str, Any], law: str = "Shtaerman's"
) -> str:
    """What the layer does to the contact and the impact (whose striker has the curve's
    ``interface``), with the FE error estimate; ``law`` names the half-space's exact law."""
    striker = interface_words(interface.get("kind", "frictionless"), interface.get("friction"))
    excess, error = layer["force_ratio"] - 1.0, layer["force_ratio_error"]
    bar, note = "", "no error estimate: a ladder level failed"
    if error is not None and math.isfinite(error):  # None: NaN in results.json
        bar = f" ± {100 * error * layer['force_ratio']:.1g} %"
        note = "FE estimate and interpolation to x_c"
    return (
        f"a {1e3 * layer['thickness']:.3g} mm layer on a {layer['base']} rigid base "
        f"(H / a_c = {layer['thickness_ratio']:.3g}, a_c = {1e3 * layer['contact_radius']:.3g} "
        f"mm the half-space contact radius at x_c) carries {100 * excess:.3g} %{bar} more "
        f"force than {law} half-space at the same depth x_c ({note}). The quasi-static "
        "impact on its FE force-depth "
        f"law reaches x_max = {number(layer['x_max'], '.4g')} m "
        f"({100 * (layer['x_max_ratio'] - 1.0):+.3g} % of x_c) and P_max = "
        f"{number(layer['P_max'], '.4g')} N ({100 * (layer['P_max_ratio'] - 1.0):+.3g} % of "
        "P_c); "
        + (
            "the restitution on a layer needs the dynamic impact, not computed here."
            if layer.get("restitution") is None
            else f"the dynamic FE impact on the layer (elastic waves, rigid {striker}) has "
            f"restitution {layer['restitution']:.4f}, x_max = "
            f"{number(layer['x_max_dynamic'], '.4g')} m and P_max = "
            f"{number(layer['P_max_dynamic'], '.4g')} N."
        )
    )


def findings(name: str, study: Mapping[str, Any]) -> list[str]:
    """How closely the FEM reproduces the contact law, and its own estimate of that; on a
    layer, what the layer does to the contact and the impact; for a bonded or Coulomb
    indenter on nu2 < 0.5, what it changes against Shtaerman (:func:`effect_words`)."""
    if study.get("layer"):
        layer, interface = study["layer"], study.get("interface", {})
        text = _layer_findings(layer, interface, exact_law(study)[0])
        return [prefixed(name, study, text), *_missing_finding(name, study)]
    if study.get("interface_effect"):  # no errors to quote: Shtaerman's is not its solution
        text = effect_words(study["interface_effect"])
        return [prefixed(name, study, text + "."), *_missing_finding(name, study)]
    errors = study["contact"]["errors"]
    text = (
        f"the FEM reproduces {exact_law(study)[0]} contact law within a relative "
        f"{number(errors['force'], '.1e')} in the force, {number(errors['beta'], '.1e')} in "
        f"beta and {number(errors['central_pressure'], '.1e')} in p(0) (the largest errors "
        "over the depths, on the study's mesh)"
    )
    accuracy = study.get("accuracy")
    if accuracy and not accuracy.get("estimate_missing"):
        text += (
            "; its own error estimate, which needs no exact solution, says "
            f"{number(accuracy['error_estimate']['force'], '.1e')} (force) and "
            f"{number(accuracy['error_estimate']['beta'], '.1e')} (beta)"
        )
    return [prefixed(name, study, text + "."), *_missing_finding(name, study)]


def effect_words(effect: Mapping[str, Any]) -> str:
    """One finding from :meth:`InterfaceEffect.to_dict`: the effect with its sign."""
    signed, errors = effect["departures"], effect["error_estimate"]

    def percent(key: str) -> str:
        bar = f" ± {100 * errors[key]:.1g}" if math.isfinite(errors.get(key, math.nan)) else ""
        return f"{100 * signed[key]:+.3g}{bar} %"

    surface = "no-slip" if effect["friction"] is None else f"Coulomb (mu = {effect['friction']:g})"
    text = (
        f"the {surface} indenter against Shtaerman's frictionless solution (the reference; "
        f"the interface's effect, not an error): force {percent('force')}, contact radius "
        f"{percent('contact_radius')}, p(0) {percent('central_pressure')} at the deepest depth, "
        f"beta {percent('beta')}; the impact on the FEM curve x_c {percent('x_c')}, P_c "
        f"{percent('P_c')}, t_c {percent('t_c')}. P(n+1)/(2E* a d n) = "
        f"{effect['no_slip_ratio']:.5f} against Mossakovskii's chi = {effect['chi']:.5f}"
    )
    if effect["friction"] is not None:
        text += (
            f" ({100 * effect['no_slip_share']:.3g} % of the no-slip effect; the identity holds "
            "for no slip only and the bounds frictionless <= Coulomb <= no slip are not "
            "guaranteed on a coarse mesh, so neither is checked)"
        )
    return f"{text}. Not checked: {effect['not_checked']}"


def _missing_finding(name: str, study: Mapping[str, Any]) -> list[str]:
    """ "no error estimate: <why>" when a level of the study's ladder failed ([] else): the
    numbers are the finest level's that passed."""
    accuracy = study.get("accuracy") or {}
    if not accuracy.get("estimate_missing"):
        return []
    text = finest_passed(accuracy["estimate_missing"], accuracy["mesh_ladder"])
    return [prefixed(name, study, f"no error estimate: {text}.")]


def timing_text(study: Mapping[str, Any]) -> str:
    """The FEM curve's stages, the convergence study, the computation, files and total."""
    timings = study.get("timings") or {}
    contact = study["contact"]["timings"]
    parts = [
        f"FEM curve {seconds(timings.get('fem_curve', contact.get('total')))} s (mesh "
        f"{seconds(contact.get('mesh'))}, assembly {seconds(contact.get('assembly'))}, "
        f"factorization {seconds(contact.get('factorization'))}, contact "
        f"{seconds(contact.get('contact'))})"
    ]
    if timings.get("convergence"):
        parts.append(f"mesh-convergence study {seconds(timings['convergence'])} s")
    return "; ".join([*parts, times_text(study, "computation in all")])


def summary_row(name: str, study: Mapping[str, Any]) -> list[str] | None:
    """The study's row of the contact cross-check: worst contact errors and impact differences
    (None on a layer, or for a bonded or Coulomb indenter on nu2 < 0.5: its departures from
    Shtaerman are its findings, not errors)."""
    if study.get("layer") or study.get("interface_effect"):
        return None
    errors = study["contact"]["errors"]
    differences = [study["differences"][v] for v in ("fem_fitted", "fem_tabulated")]
    worst = {
        key: max((abs(d[key]) for d in differences if d.get(key) is not None), default=float("nan"))
        for key in IMPACT_COLUMNS
    }
    timings = study.get("timings") or {}
    return [
        name,
        "PASS" if study["passed"] else "FAIL",
        *(number(errors.get(key), ".1e") for key in CONTACT_COLUMNS),
        *(number(worst[key], ".1e") for key in IMPACT_COLUMNS),
        seconds(timings.get("fem_curve", study["contact"]["timings"].get("total"))),
    ]
