"""Readable names of the quantities a figure shows: key -> label, unit, shown in per cent or not.

Every axis, colour bar and title of the figures (:mod:`shtaerman.plots` and the sweep's) takes
its words from the inputs' labels of :mod:`shtaerman.vocabulary` and the outputs' of
:data:`LABELS`, so a reader sees "Energy left in the body 1 − e² (%)" and
not ``energy_radiated_fraction``. A quantity marked ``percent`` is stored as a fraction and
shown multiplied by 100 (:func:`scale`). Errors ``error_<key>`` (against the exact solution, or
estimated) are fractions, relative or absolute for a difference that is itself a fraction: they
are shown in per cent.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

from .. import vocabulary
from ..validation import InputError

__all__ = [
    "LABELS",
    "MODEL_LABELS",
    "VARIANTS",
    "Label",
    "axis_label",
    "describe",
    "is_percent",
    "model_label",
    "scale",
    "variant_label",
]


@dataclass(frozen=True)
class Label:
    """How one quantity is named on a figure."""

    text: str
    """Words and symbol, e.g. "Approach velocity v0"."""
    unit: str = ""
    """SI unit of the stored value ("" for a pure number)."""
    percent: bool = False
    """Stored as a fraction, shown in per cent."""


MINUS = "\N{MINUS SIGN}"
_DIFFERENCE = f"quasi-static / dynamic {MINUS} 1"
_EFFECT_HEADS = {
    "dominant": "Dominant single effect on {}",
    "resolved": "Dominant effect on {} resolved (1 yes, 0 no)",
    "change": "Change of {} from the paper's, full problem",
    "interaction": "Interaction on {}: full minus the single effects",
}
_EFFECT_SHOWN = {"P_max": "P_max", "x_max": "x_max", "t_contact": "t_contact", "restitution": "e"}
LABELS: dict[str, Label] = {
    # the quasi-static impact
    "beta": Label("Contact law coefficient β", "N/m^q"),
    "x_c": Label("Quasi-static maximum approach x_c", "m"),
    "P_c": Label("Quasi-static maximum force P_c", "N"),
    "a_c": Label("Quasi-static maximum contact radius a_c", "m"),
    "p_c": Label("Quasi-static maximum central pressure p_c", "Pa"),
    "t_c": Label("Quasi-static time to maximum t_c", "s"),
    "t_y": Label("Quasi-static contact time t_y", "s"),
    # the dynamic impact
    "restitution": Label("Restitution e"),
    "energy_radiated_fraction": Label(f"Energy left in the body 1 {MINUS} e²", percent=True),
    "energy_dissipated_fraction": Label("Energy dissipated in the rubber", percent=True),
    "energy_wave_fraction": Label(f"Part of 1 {MINUS} e² lost to waves", percent=True),
    "energy_hysteresis_fraction": Label(f"Part of 1 {MINUS} e² lost to hysteresis", percent=True),
    "estimate_energy_fraction": Label("First-order estimate of the energy left λ", percent=True),
    "x_max": Label("Dynamic maximum approach x_max", "m"),
    "P_max": Label("Dynamic maximum force P_max", "N"),
    "t_x_max": Label("Dynamic time to maximum approach", "s"),
    "t_contact": Label("Dynamic contact time", "s"),
    "difference_x": Label(f"Maximum approach, {_DIFFERENCE}: x_c/x_max {MINUS} 1", percent=True),
    "difference_P": Label(f"Maximum force, {_DIFFERENCE}: P_c/P_max {MINUS} 1", percent=True),
    "difference_t": Label(f"Contact time, {_DIFFERENCE}: t_y/t_contact {MINUS} 1", percent=True),
    "difference_worst": Label(f"Largest |{_DIFFERENCE}| of x, P and t", percent=True),
    "energy_balance_error": Label("Energy balance error", percent=True),
    "reflected_energy_fraction": Label("Energy reflected by the boundary", percent=True),
    # the FEM contact curve
    "beta_fem": Label("FEM contact law coefficient β", "N/m^q"),
    "beta_analytic": Label("Exact contact law coefficient β", "N/m^q"),
    "exponent_fem": Label("FEM force exponent q"),
    "force": Label("Force P", percent=True),
    "contact_radius": Label("Contact radius a", percent=True),
    "central_pressure": Label("Central pressure p(0)", percent=True),
    "pressure_profile": Label("Pressure profile p(r)", percent=True),
    # finite strain
    "x_c_ratio": Label("Finite-strain / linear maximum approach x_c"),
    "P_c_ratio": Label("Finite-strain / linear maximum force P_c"),
    "t_c_ratio": Label("Finite-strain / linear time to maximum t_c"),
    "xa_within_1pct": Label("x/a up to which P is within 1 % of linear"),
    "xa_within_5pct": Label("x/a up to which P is within 5 % of linear"),
    "velocity_within_1pct": Label("v0 up to which P is within 1 % of linear", "m/s"),
    "velocity_within_5pct": Label("v0 up to which P is within 5 % of linear", "m/s"),
    "checks_passed": Label("Checks passed"),
    # a layer on a rigid base
    "H": Label("Layer thickness H", "m"),
    "H_over_a_c": Label("Layer thickness / half-space contact radius H/a_c"),
    "force_ratio": Label("Layer / half-space force P/P_Shtaerman at x_c"),
    "x_max_layer": Label("Quasi-static maximum approach on the layer", "m"),
    "P_max_layer": Label("Quasi-static maximum force on the layer", "N"),
    "x_max_ratio": Label("Layer / half-space maximum approach x_max/x_c"),
    "P_max_ratio": Label("Layer / half-space maximum force P_max/P_c"),
    "x_max_dynamic": Label("Dynamic maximum approach on the layer", "m"),
    "P_max_dynamic": Label("Dynamic maximum force on the layer", "N"),
    "model": Label("Rubber model"),
    "error_exponent": Label("Error of the FEM force exponent q", percent=True),
    # the effect table (its sweep kind)
    **{
        f"{head}_{key}": Label(words.format(shown), percent=head in ("change", "interaction"))
        for head, words in _EFFECT_HEADS.items()
        for key, shown in _EFFECT_SHOWN.items()
    },
    # cost
    "dofs": Label("Unknowns (degrees of freedom)"),
    "seconds": Label("Wall time", "s"),
}
"""Quantity key (the JSON and sweep key) -> its label. The FEM errors ``force``,
``contact_radius``, ... are relative errors against the exact solution."""


def describe(key: str) -> Label:
    """The label of ``key``: an input's from :mod:`shtaerman.vocabulary`, an output's from
    :data:`LABELS`, derived for ``error_<key>`` and ``force_ratio_xaNN``, else the key itself
    (a quantity neither table knows)."""
    if key in LABELS:
        return LABELS[key]
    try:
        item = vocabulary.entry(key)
    except InputError:
        item = None
    if item is not None and item.name == key:
        return Label(item.label, item.unit.replace("^3", "³"))
    if key.startswith("error_"):
        inner = describe(key.removeprefix("error_")).text
        return Label(f"Error of {inner[0].lower()}{inner[1:]}", percent=True)
    if key.startswith("force_ratio_xa") and key[14:].isdigit():
        return Label(f"P / P of the linear FEM at x/a = {int(key[14:]) / 100:g}")
    return Label(key)


def is_percent(key: str) -> bool:
    """Whether ``key`` is shown in per cent."""
    return describe(key).percent


def scale(key: str) -> float:
    """Factor from the stored value of ``key`` to the shown one: 100 for per cent, else 1."""
    return 100.0 if is_percent(key) else 1.0


def axis_label(key: str, unit: str = "") -> str:
    """ "Text (unit)", "Text (%)" or "Text": an axis or colour-bar label of ``key``.

    ``unit`` is used for a quantity the table does not know; a per-cent quantity is in %.
    """
    label = describe(key)
    shown = "%" if label.percent else (label.unit or unit)
    return f"{label.text} ({shown})" if shown else label.text


MODEL_LABELS = {"neo-hookean": "neo-Hookean", "mooney-rivlin": "Mooney-Rivlin", "yeoh": "Yeoh"}
"""A rubber model's name in the findings, tables and legends."""
VARIANTS = {
    "linear_exact": "Shtaerman, linear (the paper's)",
    "linear_fem": "linear FEM, same mesh",
    "finite_strain": "neo-Hookean finite strain",
}
"""The finite-strain study's impact variants: key -> label."""


def model_label(model: str) -> str:
    """ "neo-Hookean", "Mooney-Rivlin", "Yeoh", "Gent"."""
    return MODEL_LABELS.get(model, model.capitalize())


def variant_label(outcome: Any, variant: str) -> str:
    """The impact variant's label (in the tables and the impact figure's legend): the linear
    exact one Sneddon's for another profile, the finite-strain one naming the rubber model."""
    if variant == "linear_exact" and outcome.study.indenter.kind != "power-law":
        return f"Sneddon, linear ({outcome.study.indenter.kind} profile)"
    if variant != "finite_strain":
        return VARIANTS[variant]
    return f"{model_label(outcome.study.rubber.name)} finite strain"
