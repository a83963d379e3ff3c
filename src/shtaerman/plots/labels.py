"""Readable names of the quantities a figure shows: key -> label, unit, shown in per cent or not.

Every axis, colour bar and title of the figures (:mod:`shtaerman.plots` and the sweep's) takes
its words from :data:`LABELS`, so a reader sees "Energy left in the half-space 1 − e² (%)" and
not ``energy_radiated_fraction``. A quantity marked ``percent`` is stored as a fraction and
shown multiplied by 100 (:func:`scale`). Errors ``error_<key>`` (against the exact solution, or
estimated) are fractions, relative or absolute for a difference that is itself a fraction: they
are shown in per cent.
"""

from __future__ import annotations

from dataclasses import dataclass

__all__ = ["LABELS", "Label", "axis_label", "describe", "is_percent", "scale"]


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
NU, RHO = "\N{GREEK SMALL LETTER NU}", "\N{GREEK SMALL LETTER RHO}"
_DIFFERENCE = f"quasi-static / dynamic {MINUS} 1"
LABELS: dict[str, Label] = {
    # inputs
    "mass": Label("Striker mass M", "kg"),
    "velocity": Label("Approach velocity v0", "m/s"),
    "shape_coefficient": Label("Shape coefficient A", "m^(1-n)"),
    "exponent": Label("Profile exponent n"),
    "E1": Label("Striker Young's modulus E1", "Pa"),
    "nu1": Label(f"Striker Poisson's ratio {NU}1"),
    "E2": Label("Half-space Young's modulus E2", "Pa"),
    "nu2": Label(f"Half-space Poisson's ratio {NU}2"),
    "density2": Label(f"Half-space density {RHO}2", "kg/m³"),
    "depths": Label("Depths", "m"),
    "mesh_size": Label("Smallest element size / refined-zone radius"),
    "mesh_margin": Label("Refined-zone radius / contact radius"),
    "domain_factor": Label("Domain radius / refined-zone radius"),
    "growth": Label("Element size growth from the refined zone"),
    "axis_size": Label("Element size at the first contact point / refined-zone radius"),
    "axis_growth": Label("Element size growth from the first contact point"),
    "layer_rate": Label("Absorbing layer rate"),
    "refine": Label("Mesh refinement factor"),
    "solver": Label("Linear solver"),
    "estimate": Label("Error estimates"),
    "steps": Label("Steps"),
    "reach": Label("Deepest depth / linear x_c"),
    "small_ratio": Label("x/a of the smallest depth"),
    "small_steps": Label("Depth steps up to the first regular depth"),
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
    "energy_radiated_fraction": Label(f"Energy left in the half-space 1 {MINUS} e²", percent=True),
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
    "error_exponent": Label("Error of the FEM force exponent q", percent=True),
    # cost
    "dofs": Label("Unknowns (degrees of freedom)"),
    "seconds": Label("Wall time", "s"),
}
"""Quantity key (the JSON and sweep key) -> its label. The FEM errors ``force``,
``contact_radius``, ... are relative errors against the exact solution."""


def describe(key: str) -> Label:
    """The label of ``key``: from :data:`LABELS`, derived for ``error_<key>`` and
    ``force_ratio_xaNN``, else the key itself (a quantity this table does not know)."""
    if key in LABELS:
        return LABELS[key]
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
    shown = "%" if label.percent else (label.unit if key in LABELS else unit)
    return f"{label.text} ({shown})" if shown else label.text
