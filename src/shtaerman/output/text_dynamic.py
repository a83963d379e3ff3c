"""The dynamic kind's text: findings, tables and ± strings from its outcome's numbers.

± is the estimated error in the value's unit (percentage points for the differences).
"""

from __future__ import annotations

import math
from collections.abc import Callable, Mapping
from typing import Any

from ..paper.case import is_paper_case
from ..plots.labels import model_label
from ..problem import worded
from ..study.dynamic.case import COMPARED, compare
from ..study.dynamic.runner import DynamicStudyOutcome
from ..study.limits import LEVELS as LIMIT_LEVELS
from ..study.richardson import Estimate
from ..theory.bonded import bonded_punch_factor
from ..theory.prony_sources import prony_input
from ..theory.sneddon import profile_inputs
from .case import body_words, case_words, interface_words, prony_words, rubber_words
from .entry import text_entry
from .wording import plus_minus

__all__ = [
    "RELATIVE_ESTIMATES",
    "assumptions",
    "entry",
    "study_findings",
    "study_tables",
    "validity_rows",
    "velocity_limit",
]

RELATIVE_ESTIMATES = {
    "x_max": "x_max",
    "P_max": "P_max",
    "t_contact": "t_contact",
    "restitution": "e",
    "energy_radiated_fraction": "1 - e^2",
}
"""Results whose estimated relative error the study reports -> their names in the text."""
NAMES = {"x": "x_c", "P": "P_c", "t": "t_c", "all": "all three"}
"""Compared quantity (and "all") -> its name in the text."""
LEVELS = tuple(f"{100 * level:g}%" for level in LIMIT_LEVELS)
"""The keys of the levels in :meth:`DynamicStudyOutcome.limits`: "1%", "5%"."""


def _ratio(difference: float, error: float) -> float:
    return math.inf if error == 0 else abs(difference) / error


def _plus_minus(estimates: dict[str, Estimate]) -> Callable[..., str]:
    """``pm(key, scale=1)``: " ± <scale x the absolute error of key>", "" without estimates."""

    def pm(key: str, scale: float = 1.0) -> str:
        estimate = estimates.get(key)
        return "" if estimate is None else plus_minus(estimate.absolute_error, ".1g", scale)

    return pm


def slowest_difference(differences: Mapping[str, float] | None, key: str) -> float | None:
    """The difference ``key`` ("x", "P", "t"; "all": the largest in magnitude of the three)
    of the slowest velocity's ``differences`` (None: not known)."""
    if not differences or key != "all":
        return (differences or {}).get(key)
    return max((differences[k] for k in COMPARED), key=abs)


def velocity_limit(
    limit: Mapping[str, Any] | None, level: str, slowest: float, difference: float | None = None
) -> str:
    """A velocity limit (:func:`shtaerman.study.limits.thresholds`) to ``level`` ("1%") in
    words, the one wording of the study's table, its findings and the report's "where the
    model holds" table: "up to v0 = 0.715 ± 0.007 m/s (difference ± 0.007 %)", "over the whole
    range computed (to v0 = 5 m/s, the fastest; the limit lies beyond; ...)", "not even at v0 =
    0.5 m/s (the slowest computed; ...)" (``slowest``, m/s), or "not resolved (...)" where the
    difference's estimated error (in percentage points) is not below a fifth of the level,
    unless the slowest velocity's ``difference`` lies beyond the level by more than that
    error (then the limit is below the range: "not even at ..., outside the 1 % limit");
    "-" without a limit."""
    if not limit:
        return "-"
    error = limit.get("error")
    spread = plus_minus(error, ".1g", 100)
    note = f"difference{spread} %" if spread else "no error estimate"
    beyond = None not in (error, difference) and limit["bound"] == "none"
    if beyond and abs(difference) - error > float(level[:-1]) / 100:  # type: ignore[operator]
        return (  # beyond the level by more than its error: resolved, outside
            f"not even at v0 = {slowest:.3g} m/s (the slowest computed: difference "
            f"{100 * difference:+.3g}{spread} %, outside the {level[:-1]} % limit "
            "beyond its error)"
        )
    if not limit.get("resolved"):
        if error is None:
            return f"not resolved ({note})"
        return (
            f"not resolved (difference ± {100 * error:.2g} %, not below a fifth of {level[:-1]} %)"
        )
    if limit["bound"] == "none":
        return f"not even at v0 = {slowest:.3g} m/s (the slowest computed; {note})"
    if limit["bound"] == "all":
        return (
            f"over the whole range computed (to v0 = {limit['velocity']:.3g} m/s, the fastest; "
            f"the limit lies beyond; {note})"
        )
    speed = f"{limit['velocity']:.3g}{plus_minus(limit.get('velocity_error'), '.1g')}"
    return f"up to v0 = {speed} m/s ({note})"


def _estimate_finding(outcome: DynamicStudyOutcome) -> str:
    """One sentence: the largest estimated errors over the velocities, or why none."""
    if not outcome.estimated:
        why = _missing(outcome) or (
            "a quick run skips the 3-level ladder (mesh x2 and x sqrt 2, time steps / 2 and / "
            "sqrt 2)"
        )
        return f"No error estimates: {why}, so the study states no 1 % / 5 % velocity limits."
    estimates = [case.estimates() for case in outcome.cases]
    worst = {  # a massless rubber's 1 - e^2 is 0 by construction: not estimated
        key: max(e[key].error for e in estimates)
        for key in RELATIVE_ESTIMATES
        if all(key in e for e in estimates)
    }
    signal = [
        (_ratio(d, e[f"difference_{k}"].absolute_error), k, case.velocity)
        for case, e in zip(outcome.cases, estimates, strict=True)
        for k, d in compare(case.quasi, case.result).items()
    ]
    ratio, key, velocity = min(signal)
    largest = max(e[f"difference_{k}"].absolute_error for e in estimates for k in COMPARED)
    fallbacks = sum(e.method != "richardson" for case in estimates for e in case.values())
    example = outcome.example
    levels = ", ".join(
        f"{r.mesh['dofs']} dofs/{level.steps} steps"
        for level, r in zip(example.ladder.settings, example.ladder.results, strict=True)
    )
    return (
        "Error estimates (Richardson over a 3-level ladder refining mesh and time step "
        f"together: {levels} at {example.velocity:g} m/s), the largest over the "
        "velocities: relative "
        + ", ".join(f"{RELATIVE_ESTIMATES[k]} {v:.1e}" for k, v in worst.items())
        + f"; of the differences quasi-static / dynamic - 1, at most {100 * largest:.2g} "
        f"percentage points, at least {ratio:.0f} times smaller than the difference itself (the "
        f"closest: {COMPARED[key][0]} at {velocity:g} m/s). {fallbacks} of the "
        f"{sum(map(len, estimates))} estimates are the largest difference between "
        "consecutive levels instead (no clean observed order: the levels scatter)."
    )


def _missing(outcome: DynamicStudyOutcome) -> str:
    """Why the ladder of a case lost a level, per such case ("" for none): that run reports
    its finest level that passed."""
    missing = [
        f"at v0 = {case.velocity:g} m/s {worded(case.ladder.missing, 'file')}"
        for case in outcome.cases
        if case.ladder is not None and case.ladder.missing
    ]
    return "; ".join(missing) + " (the finest level that passed reported)" if missing else ""


def _case_words(outcome: DynamicStudyOutcome) -> str:
    """ "At the paper's example (...) assumed)" for the paper's inputs on its elastic
    half-space (the paper gives no density), else "In this case (...)"."""
    study, velocity = outcome.study, outcome.example.velocity
    inputs = {
        **profile_inputs(study.indenter),
        "E2": study.half_space.youngs_modulus,
        "nu2": study.half_space.poisson_ratio,
        "mass": study.mass,
        "velocity": velocity,
    }
    details = f"M = {study.mass:g} kg, v0 = {velocity:g} m/s, rubber density {study.density:g}"
    if not _model_words(outcome) and is_paper_case(inputs):  # the paper's elastic half-space
        return f"At the paper's example ({details} kg/m^3 assumed)"
    return f"In this case ({details} kg/m^3)"


def _model_words(outcome: DynamicStudyOutcome) -> str:
    """ " (Shtaerman's elastic half-space)" where the study's body is not: on a pad, with a
    Prony series, a rubber or a bonded striker (with what the grip adds, :func:`_grip_words`);
    "" otherwise."""
    study = outcome.study
    if study.prony is None and outcome.study.geometry.thickness is None and not study.physics:
        return ""
    grip = _grip_words(outcome)
    return f" (Shtaerman's {'frictionless ' if grip else ''}elastic half-space{grip})"


def _grip_words(outcome: DynamicStudyOutcome) -> str:
    """For a bonded or Coulomb striker on a linear half-space of nu2 < 0.5: that the
    frictionless model omits the static stiffening of the grip (Mossakovskii's chi, exact for
    no slip), so the differences include it; "" elsewhere."""
    study = outcome.study
    nu2 = study.half_space.poisson_ratio
    exact = study.geometry.thickness is None and not study.finite  # chi: the linear half-space's
    if study.physics.get("interface") != "bonded" or nu2 >= 0.5 or not exact:
        return ""
    chi = f"P (n + 1)/(2 E* a d n) = {bonded_punch_factor(nu2):.4f} against 1"
    if study.physics.get("friction") is None:
        grip = f"the no-slip grip on nu2 = {nu2:g} stiffens the static contact, {chi}"
    else:
        grip = (
            f"Coulomb friction on nu2 = {nu2:g} stiffens the static contact, by at most the "
            f"no-slip grip's {chi}"
        )
    return f"; {grip} (Mossakovskii), so these differences include a static part"


def _reflection_words(outcome: DynamicStudyOutcome) -> str:
    """A pad's measured reflection at the example: the energy that came back near the contact
    after separation (from its lateral absorber and edge), of M v0^2/2."""
    reflected = outcome.example.result.reflected_energy_fraction
    return f"{reflected:.1e} of M v0^2/2 came back near the contact after separation"


def _loss_words(outcome: DynamicStudyOutcome) -> str:
    """What 1 - e^2 of the example went to: elastic waves (with the first-order estimate on
    the half-space, the measured reflection on a pad), or a viscoelastic body's hysteresis
    (and waves, with the single-run split; ± its estimated error in percentage points where
    the study ran its ladder)."""
    case, pad = outcome.example, outcome.study.geometry.thickness is not None
    if outcome.study.finite:
        return _rubber_loss_words(outcome)
    losses, pm = case.result.losses, _plus_minus(case.estimates())
    if not losses and outcome.study.density == 0:
        return "(a massless elastic body: no waves, no hysteresis; 1 - e^2 is numerical residue)"
    if not losses:
        if pad:
            return (
                f"as waves along the pad ({_reflection_words(outcome)}; the half-space's "
                "first-order radiation estimate does not apply to a pad)"
            )
        return (
            f"as elastic waves (first-order estimate {100 * case.estimate.energy_fraction:.1f} "
            f"%, e = {case.estimate.restitution:.4f})"
        )

    def share(key: str) -> str:
        return f"{100 * losses[key]:.2f}{pm(key, 100)} %"

    heat = f"{share('energy_dissipated_fraction')} of M v0^2/2 dissipated by the end"
    reflection = f"; {_reflection_words(outcome)}" if pad else ""
    if outcome.study.density == 0:
        return f"as hysteresis (massless body: no waves; {heat} of the run{reflection})"
    return (
        f"as waves and hysteresis ({heat} of the run; the single-run split: waves beyond R_a "
        f"{share('energy_wave_fraction')}, hysteresis {share('energy_hysteresis_fraction')}"
        f"{reflection})"
    )


def _rubber_loss_words(outcome: DynamicStudyOutcome) -> str:
    """What 1 - e^2 of a rubber's impact went to (:func:`~shtaerman.plots.impact_energy.
    loss_kinds`: waves, a Prony series' hysteresis, Coulomb slip; their dissipated share), no
    first-order estimate (it is the linear half-space's)."""
    from ..plots.impact_energy import loss_kinds  # here: verify imports no renderer early

    study, result = outcome.study, outcome.example.result
    model = model_label(study.physics["model"])
    kinds = [kind for kind, has in loss_kinds(result).items() if has]
    listed = f"{', '.join(kinds[:-1])} and {kinds[-1]}" if len(kinds) > 1 else "".join(kinds)
    what = f"as {listed}"
    if study.density == 0:
        what = f"{what} (massless body: no waves)" if kinds else "(massless body)"
    dissipated = result.losses.get("energy_dissipated_fraction")
    heat = "" if dissipated is None else f"; {100 * dissipated:.2f} % of M v0^2/2 dissipated"
    return (
        f"{what} (the {model} rubber at finite strain{heat}; the linear half-space's first-order "
        "radiation estimate does not apply)"
    )


def _maxima_finding(outcome: DynamicStudyOutcome) -> str:
    """How far the quasi-static x_c, P_c and t_c lie from the example's dynamic impact."""
    case = outcome.example
    d, dyn, quasi = case.differences(), case.result, case.quasi
    pm = _plus_minus(case.estimates())

    def off(key: str) -> str:
        return _off(d[key], key, pm(f"difference_{key}", 100))

    return (
        f"{_case_words(outcome)} the quasi-static model{_model_words(outcome)} {off('x')} "
        f"({quasi.x_c * 1e3:.3f} mm against the dynamic x_max {dyn.x_max * 1e3:.3f} mm), "
        f"{off('P')} ({quasi.P_c:.1f} N against P_max {dyn.P_max:.1f} N) and {off('t')} "
        f"({quasi.t_c * 1e3:.3f} ms against half the dynamic contact time, "
        f"{0.5e3 * dyn.t_contact:.3f} ms; the same as t_y against t_contact); the dynamic "
        f"maximum approach comes at {dyn.t_x_max * 1e3:.3f} ms.{_trend(outcome)}"
    )


def study_findings(outcome: DynamicStudyOutcome) -> list[str]:
    """Sentences for the report's opening section."""
    dyn, pm = outcome.example.result, _plus_minus(outcome.example.estimates())
    found = [
        _maxima_finding(outcome),
        f"The striker rebounds with e = {dyn.restitution:.4f}{pm('restitution')} "
        f"(quasi-static: 1): {100 * dyn.energy_radiated_fraction:.2f}"
        f"{pm('energy_radiated_fraction', 100)} % of its kinetic energy stays in the "
        f"{body_words(outcome.study.geometry.thickness, outcome.study.geometry.base)} "
        f"{_loss_words(outcome)}{_loss_trend(outcome)}.",
        _estimate_finding(outcome),
    ]
    limits, slowest = outcome.limits(), outcome.velocities[0]
    first = {key: slowest_difference(outcome.cases[0].differences(), key) for key in NAMES}
    for level in LEVELS if outcome.estimated else ():
        parts = [
            f"{NAMES[key]} {velocity_limit(limits[key][level], level, slowest, first[key])}"
            for key in NAMES
        ]
        found.append(
            f"The quasi-static values hold to {level[:-1]} % of the dynamic ones: "
            + "; ".join(parts)
            + f" (computed at v0 = {', '.join(f'{v:g}' for v in outcome.velocities)} m/s; "
            "the limits are interpolated linearly between them)."
        )
    return found


def _off(difference: float, key: str, spread: str) -> str:
    """ "overestimates x_c by 3.00 ± 0.1 %" for quasi-static / dynamic - 1 = +0.03."""
    way = "over" if difference > 0 else "under"
    return f"{way}estimates {NAMES[key]} by {100 * abs(difference):.2f}{spread} %"


def _grows(first: float, last: float) -> str:
    return "grows" if abs(last) > abs(first) else "shrinks"


def _trend(outcome: DynamicStudyOutcome) -> str:
    """ " The largest of the three differences grows with v0: ... at v0 = a m/s, ... at b m/s."
    over the computed velocities; "" for one velocity."""
    if len(outcome.cases) < 2:
        return ""
    first, last = outcome.cases[0], outcome.cases[-1]
    worst = [
        max(abs(v) for k, v in c.differences().items() if k in COMPARED) for c in (first, last)
    ]
    return (
        f" The largest of the three differences {_grows(*worst)} with v0: "
        f"{100 * worst[0]:.2f} % at {first.velocity:g} m/s, {100 * worst[1]:.2f} % at "
        f"{last.velocity:g} m/s."
    )


def _loss_trend(outcome: DynamicStudyOutcome) -> str:
    """ "; the fraction grows with v0, from ... % at a m/s to ... % at b m/s"; "" for one v0."""
    if len(outcome.cases) < 2:
        return ""
    first, last = (c.result.energy_radiated_fraction for c in (outcome.cases[0], outcome.cases[-1]))
    return (
        f"; the fraction {_grows(first, last)} with v0, from {100 * first:.2f} % at "
        f"{outcome.cases[0].velocity:g} m/s to {100 * last:.2f} % at "
        f"{outcome.cases[-1].velocity:g} m/s"
    )


HEADER = [
    "v0 (m/s)",
    "x_max (mm)",
    "x_c/x_max-1",
    "P_max (N)",
    "P_c/P_max-1",
    "t_contact (ms)",
    "t_y/t_contact-1",
    "e",
    "1-e^2",
    "estimate",
    "balance",
    "reflected",
]
"""Columns of the per-velocity table."""


def _case_rows(outcome: DynamicStudyOutcome) -> list[list[str]]:
    """One row per velocity (the half-space's first-order estimate "-" on a pad, a rubber)."""
    rows, pad = [], outcome.study.geometry.thickness is not None or outcome.study.finite
    for case in outcome.cases:
        r, d, pm = case.result, case.differences(), _plus_minus(case.estimates())
        rows.append(
            [
                f"{case.velocity:g}",
                f"{r.x_max * 1e3:.4f}{pm('x_max', 1e3)}",
                f"{100 * d['x']:+.2f}{pm('difference_x', 100)} %",
                f"{r.P_max:.1f}{pm('P_max')}",
                f"{100 * d['P']:+.2f}{pm('difference_P', 100)} %",
                f"{r.t_contact * 1e3:.4f}{pm('t_contact', 1e3)}",
                f"{100 * d['t']:+.2f}{pm('difference_t', 100)} %",
                f"{r.restitution:.4f}{pm('restitution')}",
                f"{r.energy_radiated_fraction:.4f}{pm('energy_radiated_fraction')}",
                "-" if pad else f"{case.estimate.energy_fraction:.4f}",
                f"{r.energy_balance_error:.1e}",
                f"{r.reflected_energy_fraction:.1e}",
            ]
        )
    return rows


def study_tables(outcome: DynamicStudyOutcome) -> list[dict[str, object]]:
    """The report's tables (strings): per velocity, and the velocity limits."""
    limits, slowest = outcome.limits(), outcome.velocities[0]
    first = {key: slowest_difference(outcome.cases[0].differences(), key) for key in NAMES}
    limit_rows = [
        [NAMES[key], *(velocity_limit(limits[key][lv], lv, slowest, first[key]) for lv in LEVELS)]
        for key in NAMES
    ]
    errors = (
        "± the estimated error (Richardson, 3-level ladder) in the value's unit"
        if outcome.estimated
        else f"no error estimates: {_missing(outcome) or 'a quick run skips the ladder'}"
    )
    estimate = "first-order radiated fraction"
    reflected = "reflected: of the radiated energy"
    if outcome.study.geometry.thickness is not None:
        estimate = "the half-space's first-order radiated fraction, not given on a pad"
        reflected = "reflected: energy come back near the contact after separation, of M v0^2/2"
    return [
        {
            "title": "Dynamic FE impact against the quasi-static model (differences: "
            f"quasi-static / dynamic - 1; {errors}; estimate: {estimate}; {reflected}; "
            "balance: energy balance error, of M v0^2/2)",
            "header": HEADER,
            "rows": _case_rows(outcome),
        },
        {
            "title": "Velocity up to which the quasi-static value holds (linear "
            "interpolation between the computed velocities, ± in m/s; 'difference ± e': the "
            "estimated error of the difference at the deciding velocities, in percentage "
            "points; stated where it is below a fifth of the level)",
            "header": ["quantity", "to 1 %", "to 5 %"],
            "rows": limit_rows,
        },
    ]


# --- the report's view of a results.json entry --------------------------------------------------


def entry(
    outcome: DynamicStudyOutcome,
    files: dict[str, str],
    output_seconds: float | None,
    figures: Mapping[str, str] | None,
) -> dict[str, object]:
    """The study's results.json entry (:func:`.entry.text_entry`) with its ``case`` in words:
    the half-space or the pad, the Prony series, the frictionless indenter."""
    study = outcome.study
    case = case_words(
        material=_material_words(study),
        prony=study.prony,
        thickness=study.geometry.thickness,
        base=study.geometry.base,
        interface=study.physics.get("interface", "frictionless"),
        friction=study.physics.get("friction"),
    )
    return text_entry(
        outcome, (study_tables, study_findings), files, output_seconds, figures, case=case
    )


def _material_words(study: Any) -> str:
    """ "linear elastic", or the rubber with its constants (:func:`.case.rubber_words`)."""
    if not study.finite:
        return "linear elastic"
    rubber = study.problem(study.example).body.rubber()
    return rubber_words(rubber, study.half_space.poisson_ratio)


def assumptions(study: Mapping[str, Any]) -> str:
    """The quasi-static model's assumptions a dynamic study's results.json entry tests, by
    what its FE impact has: "half-space, not the 20 mm pad on a bonded rigid base; no elastic
    waves; no hysteresis (Prony series g:tau = 0.5:2e-3 s)"."""
    inputs, tested = study.get("inputs", {}), []
    if inputs.get("thickness") is not None:
        tested.append(f"half-space, not the {body_words(inputs['thickness'], inputs['base'])}")
    if inputs.get("density2", 1.0) > 0:
        tested.append("no elastic waves")
    if inputs.get("prony"):
        tested.append(f"no hysteresis ({prony_words(prony_input(inputs['prony']))})")
    if inputs.get("model", "linear") != "linear":
        tested.append(f"small strain, not the {model_label(inputs['model'])} rubber")
    if inputs.get("interface", "frictionless") != "frictionless":
        surface = interface_words(inputs["interface"], inputs.get("friction"))
        tested.append(f"a frictionless striker, not a {surface}")
    return "; ".join(tested) or "none (a massless elastic half-space)"


def validity_rows(name: str, study: Mapping[str, Any]) -> list[list[str]]:
    """The study's rows of the report's "where the model holds" table: the assumptions it
    tests (:func:`assumptions`) for each compared quantity."""
    limits = study.get("limits", {})
    labels = {"all": "x_c, P_c and t_c", "P": "P_c", "x": "x_c", "t": "t_c"}
    tested, velocities = assumptions(study), study.get("inputs", {}).get("velocities")
    first = (study.get("cases") or [{}])[0].get("differences")
    return [
        [
            f"{tested} ({name}): quasi-static {label} against the dynamic FE impact",
            *(
                velocity_limit(
                    limits[key].get(level), level, velocities[0], slowest_difference(first, key)
                )
                for level in LEVELS
            ),
        ]
        for key, label in labels.items()
        if key in limits
    ]


# --- the viscoelastic quasi-static reference in ``shtaerman dynamic``'s text --------------------

VISCOELASTIC_NAMES = {"x_max": "x", "P_max": "P", "t_contact": "t_contact", "restitution": "e"}
"""The viscoelastic differences' keys -> their names in the text."""


def viscoelastic_words(
    reference: Mapping[str, Any], massless: bool = True, layer: bool = False
) -> str:
    """Which viscoelastic quasi-static impact the reference is, and its own step error:
    "quasi-static viscoelastic (Lee-Radok/Ting), exact; 2000 steps per t_c, relative step error
    1.2e-07"; a rubber's "small-strain", a compressible body's "incompressible" reference;
    with inertia (not ``massless``) it is exact without the waves; on a ``layer`` it is the
    half-space's."""
    if layer:
        kind = "the half-space's, not the layer's"
    elif reference["small_strain"]:
        kind = "the small-strain reference of the rubber"
    elif reference["exact"]:
        kind = "exact" if massless else "exact without inertia (no waves)"
    else:
        kind = "the incompressible reference (nu2 < 0.5, elastic bulk: approximate)"
    return (
        f"quasi-static viscoelastic (Lee-Radok/Ting), {kind}; {reference['steps']} steps "
        f"per t_c, relative step error {reference['step_error']:.1e}"
    )


def difference_cells(
    differences: Mapping[str, float],
    errors: Mapping[str, float] | None,
    names: Mapping[str, str] | None = None,
) -> str:
    """ "x_c -6.60 ± 0.01 %, ...": ``differences`` (reference / dynamic - 1) in per cent, ±
    their estimated ``errors`` where there are some, each under its name in ``names`` (default
    its key)."""
    errors, names = errors or {}, names or {}
    cells = []
    for key, value in differences.items():
        error = errors.get(key)
        spread = f" ± {100 * error:.2f}" if error is not None else ""
        cells.append(f"{names.get(key, key)} {100 * value:+.2f}{spread} %")
    return ", ".join(cells)


def fe_words(report: Mapping[str, Any]) -> str:
    """The FE impact a difference is taken against: "massless FE" or "FE with inertia"."""
    return "massless FE" if report["parameters"]["density2"] == 0 else "FE with inertia"


def differences_text(report: Mapping[str, Any]) -> str:
    """The paper's elastic quasi-static impact / the FE impact - 1 (%, ± the estimated errors),
    naming the FE impact and so what the difference measures."""
    cells = difference_cells(report["differences"], report.get("differences_error"))
    measures = (
        "no waves: the body's other effects, if any"
        if report["parameters"]["density2"] == 0
        else "the waves and the body's other effects, if any"
    )
    return (
        f"  paper (elastic quasi-static) / {fe_words(report)} - 1:  {cells}\n"
        f"      (x_c against x_max, P_c against P_max, t_c against t_contact / 2; {measures})"
    )


def _viscoelastic_differences(report: Mapping[str, Any], label: str) -> str:
    """The viscoelastic reference / dynamic - 1 line, ± the estimated error where there is one."""
    differences = report["viscoelastic_differences"]
    errors = report.get("viscoelastic_differences_error")
    return f"  {label}  " + difference_cells(differences, errors, VISCOELASTIC_NAMES)


def viscoelastic_rows(report: Mapping[str, Any], dynamic: str = "dynamic FEM") -> list[str]:
    """The rows of a viscoelastic body's quasi-static reference beside the FE impact (column
    ``dynamic``) and their differences, "viscoelastic quasi-static / massless FE - 1" (on a
    massless half-space it is exact: what the FE impact converges to) or "... / FE with inertia
    - 1"; [] for an elastic body."""
    reference = report.get("viscoelastic_quasi_static")
    if reference is None:
        return []
    dyn, ref = ({k: math.nan if v is None else v for k, v in part.items()}
                for part in (report["dynamic"], reference))  # fmt: skip
    layer = "thickness" in report.get("mesh", {})
    massless = report["parameters"]["density2"] == 0
    return [
        f"  {viscoelastic_words(reference, massless, layer)}:",
        f"                          {dynamic:<14}  quasi-static viscoelastic",
        f"  max approach x (m)      {dyn['x_max']:<14.6e}  {ref['x_max']:.6e}",
        f"  max force P (N)         {dyn['P_max']:<14.6e}  {ref['P_max']:.6e}",
        f"  time of max x (s)       {dyn['t_x_max']:<14.6e}  {ref['t_x_max']:.6e}",
        f"  contact duration (s)    {dyn['t_contact']:<14.6e}  {ref['t_contact']:.6e}",
        f"  restitution e           {dyn['restitution']:<14.6f}  {ref['restitution']:.6f}",
        f"  energy lost 1-e^2       {round(dyn['energy_radiated_fraction'], 6) + 0.0:<14.6f}  "
        f"{ref['energy_lost_fraction']:.6f}",
        _viscoelastic_differences(report, f"viscoelastic quasi-static / {fe_words(report)} - 1:"),
    ]
