"""The finite-strain kind's text: findings, tables and ± strings from its outcome's numbers.

Relative errors throughout (a finite-strain estimate is relative, see
:class:`shtaerman.study.finite.accuracy.FiniteEstimates`), except in the depth limits
(:func:`depth_limit`), whose ± is in the value's unit like every kind's limits.
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from typing import Any

from ..paper.case import is_paper_case
from ..plots.labels import model_label, variant_label
from ..study.contact.interface import shtaerman_applies
from ..study.finite.runner import FiniteStudyOutcome, no_slip_checked
from ..study.ladder import LADDER_RATIO
from ..study.limits import resolved
from ..theory.sneddon import profile_inputs
from .case import VOLUMETRIC, case_words, rubber_constants, rubber_words
from .entry import text_entry
from .text_corrections import corrections_finding, corrections_table
from .wording import finest_passed, plus_minus

__all__ = [
    "QUICK_ERROR",
    "central_pressure_words",
    "depth_limit",
    "entry",
    "study_findings",
    "study_tables",
    "validity_rows",
]

QUICK_ERROR = (
    "Quick mode: one coarse mesh (about 3.7k dofs), no error estimates: the force is within "
    "~1.5 % of Shtaerman's at small depths, the impact ratios within ~1e-3 of the default run's."
)


def _pm(outcome: FiniteStudyOutcome, key: str, step: int | None = None) -> str:
    """ " ± e", e the estimated relative error of a scalar (or of ``key`` at depth ``step``);
    "" without a ladder (the tables, whose captions say so)."""
    if outcome.estimates is None:
        return ""
    estimates = outcome.estimates
    return plus_minus((estimates.scalars if step is None else estimates.steps[step])[key].error)


def _relative(outcome: FiniteStudyOutcome, key: str) -> float | None:
    """The estimated relative error of scalar ``key``; None without a ladder."""
    if outcome.estimates is None:
        return None
    return outcome.estimates.scalars[key].error


def _plain(error: float | None) -> str:
    """ " ± e" with one significant digit as a plain decimal (0.00005, never 5e-05: beside a
    value in its unit); "" as :func:`plus_minus` gives it."""
    if error is None or not math.isfinite(error) or error <= 0:
        return plus_minus(error)
    digits = max(0, -math.floor(math.log10(float(f"{error:.1g}"))))
    return plus_minus(error, f".{digits}f")


def _shift(outcome: FiniteStudyOutcome, key: str, ratio: float) -> str:
    """A ratio r as its shift in per cent, "+1.69 ± 0.04 %": the ± (r's estimated relative
    error times r) in percentage points, like the dynamic kind's findings."""
    error = _relative(outcome, key)
    spread = _plain(None if error is None else 100 * error * abs(ratio))
    return f"{100 * (ratio - 1):+.2f}{spread} %"


def _value(outcome: FiniteStudyOutcome, key: str, value: float, spec: str) -> str:
    """``value`` by ``spec`` ± its estimated error in the value's own unit."""
    error = _relative(outcome, key)
    return f"{value:{spec}}" + _plain(None if error is None else error * abs(value))


def rubber_finding(outcome: FiniteStudyOutcome) -> list[str]:
    """The rubber model's constants (none for the default neo-Hookean), and for nu2 < 0.5 the
    plain flag that the result depends on the volumetric energy."""
    rubber, nu = outcome.study.rubber, outcome.study.half_space.poisson_ratio
    out = []
    if rubber_constants(rubber):
        out.append(
            f"Rubber model: {model_label(rubber.name)} with {rubber_constants(rubber)}, the "
            "small-strain modulus kept at E2 (its departures from the neo-Hookean study are "
            "the model's)."
        )
    if nu < 0.5:
        out.append(
            f"Compressible (nu2 = {nu:g}): these numbers depend on the volumetric energy chosen, "
            f"here {VOLUMETRIC[rubber.volumetric]}, not only on E2 and nu2; the other choice "
            "(--volumetric) moves them (docs/findings.md, 'Rubber models')."
        )
    return out


def _inputs(outcome: FiniteStudyOutcome) -> dict[str, float]:
    study = outcome.study
    return {
        **profile_inputs(study.indenter),
        "E2": study.half_space.youngs_modulus,
        "nu2": study.half_space.poisson_ratio,
        "mass": study.mass,
        "velocity": study.velocity,
    }


def curve_finding(outcome: FiniteStudyOutcome) -> list[str]:
    """The study's indenter surface and layer where they are not the paper's (a frictionless
    half-space): one sentence saying what both FE curves solve and what the ratios hold."""
    layer, surface = outcome.study.geometry, outcome.study.interface
    parts = []
    if surface.kind == "bonded":
        slip = "no slip" if surface.friction is None else f"Coulomb friction {surface.friction:g}"
        parts.append(f"the rubber is bonded to the striker ({slip})")
    if layer.thickness is not None:
        parts.append(
            f"the body is a pad H = {layer.thickness * 1e3:.4g} mm on a {layer.base} rigid base"
        )
    if not parts:
        return []
    text = (
        f"Beyond the paper's frictionless half-space: {' and '.join(parts)}. The finite-strain "
        "and the same-mesh linear FEM both solve it, so P/P_linear-FEM isolates finite strain; "
        "the comparisons with the exact half-space hold these effects too."
    )
    return [text + _reference_words(outcome.study)]


def _reference_words(study: Any) -> str:
    """What the small-strain limit is checked against where Shtaerman's is not the
    reference (a bonded or Coulomb indenter on nu2 < 0.5; "" where it is)."""
    if shtaerman_applies(study.interface, study.half_space.poisson_ratio):
        return ""
    if no_slip_checked(study):
        how = ", and that FEM against the no-slip identity P(n+1)/(2E* a d n) = chi(nu2)."
    else:  # Coulomb's slipping annulus, another profile, a pad's stiffening
        how = " (no exact law of this contact to check that FEM by)."
    return (
        " Shtaerman's frictionless solution is no small-strain limit of this interface on "
        f"nu2 < 0.5, so the small-strain limit is checked against the same-mesh linear FEM{how}"
    )


def study_findings(outcome: FiniteStudyOutcome) -> list[str]:
    """Sentences for the report's opening section, with the measured numbers and, after a
    ladder, their estimated errors in each value's unit (± ...)."""
    study, ratios, at = outcome.study, outcome.ratios(), outcome.at_maximum()
    exact = outcome.impacts["linear_exact"]
    fem = {
        k: outcome.impacts["finite_strain"][k] / outcome.impacts["linear_fem"][k] - 1
        for k in ("x_c", "P_c", "t_c")
    }
    whose = "the paper's" if is_paper_case(_inputs(outcome)) else "this case's"
    law = outcome.finite.exact  # Shtaerman's, or Sneddon's for another profile
    author = "Shtaerman's" if study.indenter.kind == "power-law" else "Sneddon's"
    x_c = outcome.impacts["finite_strain"]["x_c"]
    linear_ratio = float(law.central_pressure(x_c) / law.mean_pressure(x_c))
    force_ratio = "P/(beta x^q)" if study.indenter.kind == "power-law" else "P/P_linear"

    model = model_label(study.rubber.name)
    return [
        f"Real rubber ({model}, nu2 = {study.half_space.poisson_ratio:g}) moves {whose} "
        f"impact ({study.mass:g} kg at {study.velocity:g} m/s): x_c "
        f"{_shift(outcome, 'x_c', ratios['x_c'])}, P_c {_shift(outcome, 'P_c', ratios['P_c'])}, "
        f"t_c {_shift(outcome, 't_c', ratios['t_c'])} against {author} "
        f"linear x_c = {exact['x_c'] * 1e3:.3f} mm, P_c = {exact['P_c']:.1f} N, "
        f"t_c = {exact['t_c'] * 1e3:.3f} ms (against the linear FEM on the same mesh, "
        f"which cancels the discretization: {_shift(outcome, 'x_c_vs_fem', 1 + fem['x_c'])}, "
        f"{_shift(outcome, 'P_c_vs_fem', 1 + fem['P_c'])}, "
        f"{_shift(outcome, 't_c_vs_fem', 1 + fem['t_c'])}).",
        f"At the finite-strain x_c (x/a = {at['depth_to_radius']:.2f}): {force_ratio} = "
        f"{_value(outcome, 'force_ratio_at_x_c', at['force_ratio'], '.4f')}, p(0)/p_avg = "
        f"{_value(outcome, 'central_to_mean_at_x_c', at['central_to_mean'], '.3f')} (linear "
        f"{linear_ratio:.2f}), a/a_linear = "
        f"{_value(outcome, 'radius_ratio_at_x_c', at['radius_ratio'], '.4f')}. "
        + central_pressure_words(at["central_pressure_ratio"], at["radius_ratio"], author),
        _validity_finding(outcome),
        *([] if outcome.start is None else [outcome.start.words()]),
        *rubber_finding(outcome),
        *curve_finding(outcome),
        _estimate_finding(outcome) if outcome.estimates is not None else _no_estimate(outcome),
        *_corrections(outcome, corrections_finding),
    ]


def _no_estimate(outcome: FiniteStudyOutcome) -> str:
    """Why the study has no error estimate: a quick run, or a level of its ladder failed
    (then the finest level that passed is reported)."""
    if not outcome.estimate_missing:
        return QUICK_ERROR
    return f"No error estimate: {finest_passed(outcome.estimate_missing, outcome.mesh_ladder)}."


def _corrections(outcome: FiniteStudyOutcome, text: Any) -> list[Any]:
    """``text(corrections, model label)`` in a list after a ``[corrections]`` table, else []."""
    if outcome.corrections is None:
        return []
    return [text(outcome.corrections, model_label(outcome.study.rubber.name))]


def central_pressure_words(
    pressure_ratio: float, radius_ratio: float, author: str = "Shtaerman's"
) -> str:
    """What a changed p(0)/p_avg means: whether p(0) itself lies below or above the linear
    exact one (``author``'s) at the same depth (``pressure_ratio`` = p(0) / p(0)_linear), and
    that the ratio also moves with the contact radius (``radius_ratio`` = a / a_linear),
    through p_avg = P / (pi a^2)."""
    pressure = "below" if pressure_ratio < 1 else "above"
    radius = "larger" if radius_ratio > 1 else "smaller"
    return (
        f"The central pressure p(0) itself is {100 * abs(pressure_ratio - 1):.1f} % {pressure} "
        f"{author} at the same depth; p(0)/p_avg moves also because the contact radius is "
        f"{100 * abs(radius_ratio - 1):.1f} % {radius} (p_avg = P/(pi a^2))."
    )


def _level(entry: Mapping[str, Any]) -> str:
    return f"{100 * entry['level']:g} %"


def depth_limit(entry: Mapping[str, Any] | None) -> str:
    """A depth limit (an entry of :meth:`FiniteStudyOutcome.limits`) in words, the one wording
    of the study's table, its findings and the report's "where the model holds" table: "up to
    x/a = 0.165 ± 0.002, depth 0.0554 ± 0.003 mm, reached at v0 = 0.00363 ± 0.0002 m/s
    (difference ± 0.03 %)" (± in the value's unit; the departure's estimated error in
    percentage points), "over the whole range computed (to the deepest depth, ...; the limit
    lies deeper; ...)", "not even at the first depth computed (...)", or "not resolved (...)"
    where the departure's estimated error is not below a fifth of the level
    (:func:`shtaerman.study.limits.resolved`); "-" without a limit."""
    if not entry or entry.get("depth_to_radius") is None:
        return "-"
    error, errors = entry.get("departure_error"), entry.get("errors") or {}
    spread = plus_minus(error, ".1g", 100)
    note = f"difference{spread} %" if spread else "no error estimate"
    if error is not None and not resolved(error, entry["level"]):
        fifth = f"not below a fifth of {_level(entry)}"
        return f"not resolved (difference ± {100 * error:.2g} %, {fifth})"

    def value(key: str, scale: float = 1.0) -> str:
        relative, shown = errors.get(key), entry[key] * scale
        return f"{shown:.3g}" + plus_minus(None if relative is None else relative * shown, ".1g")

    where = (
        f"x/a = {value('depth_to_radius')}, depth {value('depth', 1e3)} mm, reached at v0 = "
        f"{value('velocity')} m/s"
    )
    if entry["status"] == "beyond":
        return (
            f"over the whole range computed (to the deepest depth, {where}; the limit lies "
            f"deeper; {note})"
        )
    if entry["status"] == "below":
        return f"not even at the first depth computed ({where}; {note})"
    return f"up to {where} ({note})"


def _validity_finding(outcome: FiniteStudyOutcome) -> str:
    last = outcome.rows()[-1]["force_ratio_fem"]
    way = "falls below" if last < 1 else "rises above"
    return (
        f"Real rubber's force {way} the linear beta x^q as the depth grows; the linear force "
        "holds "
        + "; ".join(f"to {_level(e)} {depth_limit(e)}" for e in outcome.limits())
        + " (P against the linear FEM on the same mesh; crossings interpolated linearly in x/a "
        "between computed depths; velocities from the stored energy, v = sqrt(2 W / M))."
    )


NESTED_RULES = (
    "; 0.5-4.5 for a/a_linear, p(0)/p_avg and a_c, estimated at the contact edge's first "
    "order). P/P_linear-FEM and the ratios to the linear-FEM impact carry the sum of their "
    "two factors' relative estimates where both are Richardson's (a bound). Every per-depth "
    "number carries at least its neighbourhood's estimate (the depth and one on each side, "
    "Richardson on their largest difference, orders 0.5-4.5): the envelope of the contact "
    "edge's error, which changes sign from depth to depth."
)
"""The nested ladder's estimate rules, as the finding states them."""
INDEPENDENT_NOTE = (
    ": the ~1e-4 noise of non-nested meshes). A nested ladder (`[numerics] ladder = "
    '"nested"`, about 9 times the CPU time) falls back in a few of them.'
)
"""Why the independent ladder's estimates fall back, and the remedy."""


def _estimate_finding(outcome: FiniteStudyOutcome) -> str:
    estimates = outcome.estimates
    worst = estimates.worst_step()
    fallback, total = estimates.fallbacks()
    nested = estimates.ratio != LADDER_RATIO
    ladder = (
        "a nested ladder, one gmsh mesh with the study's sizes doubled and its two uniform "
        "refinements "
        if nested
        else "the study's mesh refined by 1/2, 1/sqrt(2) and 1 "
    )
    return (
        "± is the estimated error of the value, in its unit (percentage points for a shift "
        f"in %): Richardson extrapolation over {ladder}"
        f"({'/'.join(str(d) for d in estimates.dofs)} dofs, "
        f"{sum(estimates.cpu_seconds):.0f} s of CPU time in all). Largest over the depths: "
        f"P/(beta x^q) relative error {estimates.scalars['force_ratio_worst'].error:.1e} at x/a = "
        f"{outcome.rows()[worst]['depth_to_radius']:.3g}. {fallback} of {total} estimates "
        "fell back to the difference of the two finest meshes (differences not shrinking, "
        "or an observed order outside 1.5-4.5" + (NESTED_RULES if nested else INDEPENDENT_NOTE)
    )


def study_tables(outcome: FiniteStudyOutcome) -> list[dict[str, object]]:
    """The curve, the three impacts and the validity depths as display strings (after a
    ladder: value ± estimated relative error), after ``[corrections]`` its table."""
    return [
        _curve_table(outcome),
        _impact_table(outcome),
        _validity_table(outcome),
        *_corrections(outcome, corrections_table),
    ]


def _curve_table(outcome: FiniteStudyOutcome) -> dict[str, object]:
    columns = (
        ("force_ratio", "P/P_lin", ".4f"),
        ("force_ratio_fem", "P/P_linFEM", ".4f"),
        ("radius_ratio", "a/a_lin", ".4f"),
        ("central_to_mean", "p(0)/p_avg", ".3f"),
        ("strain_energy", "W (J)", ".4g"),
    )
    rows = [
        [
            f"{r['depth'] * 1e3:.4g}",
            f"{r['depth_to_radius']:.3f}",
            f"{r['force']:.4g}",
            *[f"{r[key]:{fmt}}{_pm(outcome, key, k)}" for key, _, fmt in columns],
            str(r["newton_iterations"]),
        ]
        for k, r in enumerate(outcome.rows())
    ]
    return {
        "title": "Finite-strain contact curve beside the linear solution"
        + ("" if outcome.estimates is None else " (± estimated relative error; P's is P/P_lin's)"),
        "header": ["x (mm)", "x/a", "P (N)", *[label for _, label, _ in columns], "Newton"],
        "rows": rows,
    }


def _impact_table(outcome: FiniteStudyOutcome) -> dict[str, object]:
    keys = (
        ("x_c", 1e3, "x_c (mm)"),
        ("P_c", 1.0, "P_c (N)"),
        ("a_c", 1e3, "a_c (mm)"),
        ("p_c", 1e-6, "p_c (MPa)"),
        ("t_c", 1e3, "t_c (ms)"),
        ("t_y", 1e3, "t_y (ms)"),
    )
    rows = [
        [
            variant_label(outcome, variant),
            *[
                f"{values[k] * s:.5g}{_pm(outcome, k) if variant == 'finite_strain' else ''}"
                for k, s, _ in keys
            ],
        ]
        for variant, values in outcome.impacts.items()
    ]
    finite, fem = outcome.impacts["finite_strain"], outcome.impacts["linear_fem"]
    ratios = outcome.ratios()
    rows += [
        [
            "finite strain / linear exact - 1",
            *[f"{ratios[k] - 1:+.2%}{_pm(outcome, k)}" for k, _, _ in keys],
        ],
        [
            "finite strain / linear FEM - 1",
            *[f"{finite[k] / fem[k] - 1:+.2%}{_pm(outcome, f'{k}_vs_fem')}" for k, _, _ in keys],
        ],
    ]
    return {
        "title": "Impact M x'' = -P(x): the paper's linear model and real rubber"
        + ("" if outcome.estimates is None else " (± estimated relative error)"),
        "header": ["model", *[label for _, _, label in keys]],
        "rows": rows,
    }


def _validity_table(outcome: FiniteStudyOutcome) -> dict[str, object]:
    return {
        "title": "Where the linear force holds (|P/P_linFEM - 1| <= level; crossings "
        "interpolated linearly in x/a between computed depths; ± the estimated error in the "
        "value's unit; 'difference ± e': the estimated error of the departure there, in "
        "percentage points; stated where it is below a fifth of the level)",
        "header": ["level", "the linear force holds"],
        "rows": [[_level(e), depth_limit(e)] for e in outcome.limits()],
    }


# --- the report's view of a results.json entry --------------------------------------------------


def entry(
    outcome: FiniteStudyOutcome,
    files: dict[str, str],
    output_seconds: float | None,
    figures: Mapping[str, str] | None,
) -> dict[str, object]:
    """The study's results.json entry (:func:`.entry.text_entry`) with its ``case`` in words:
    the body (half-space or pad), the rubber model with its constants and the interface."""
    study, surface = outcome.study, outcome.study.interface
    case = case_words(
        material=rubber_words(study.rubber, study.half_space.poisson_ratio),
        thickness=study.geometry.thickness,
        base=study.geometry.base,
        interface=surface.kind,
        friction=surface.friction,
    )
    return text_entry(
        outcome, (study_tables, study_findings), files, output_seconds, figures, case=case
    )


def validity_rows(name: str, study: Mapping[str, Any]) -> list[list[str]]:
    """The study's row of the report's "where the model holds" table."""
    if "validity" not in study:
        return []
    levels = {round(entry["level"], 4): entry for entry in study["validity"]}
    nu = study.get("inputs", {}).get("nu2")
    model = model_label(study.get("model", "neo-hookean"))
    return [
        [
            f"linear elasticity ({name}): beta x^q against {model} rubber"
            + (f", nu2 = {nu:g}" if nu is not None else ""),
            depth_limit(levels.get(0.01)),
            depth_limit(levels.get(0.05)),
        ]
    ]
