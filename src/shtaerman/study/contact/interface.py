"""The checks of a contact study whose indenter is bonded or Coulomb's, and its findings.

Shtaerman's (frictionless) solution stays the reference where the interface cannot change the
contact (:func:`shtaerman_applies`: mu = 0, or nu2 = 0.5). Elsewhere the departures from it are
the interface's effect (:class:`InterfaceEffect`), and :func:`interface_checks` checks what is
exact for it: the force exponent (n + 1)/n, a bonded indenter's no-slip identity
P (n + 1) / (2 E* a d n) = chi(nu), the FEM-tabulated impact against the FEM-fitted one. What
is not checked, and why: benchmarks/FEM_NOTES.md, "Study error estimates".
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ...problem import Interface
from ...theory.bonded import bonded_punch_factor, no_slip_ratio
from ..checks import Check
from .accuracy import AccuracyResult
from .indentation import IndentationResult
from .loader import Study

__all__ = [
    "InterfaceEffect",
    "interface_checks",
    "interface_effect",
    "no_slip_departures",
    "shtaerman_applies",
]

IMPACT_KEYS = ("x_c", "P_c", "t_c")
"""The impact maxima checked (tabulated against fitted) and reported (against the analytic)."""
NOT_CHECKED = (
    "force, beta, contact radius and central pressure against Shtaerman's frictionless solution, "
    "and the impacts against the analytic one (the interface's effect, reported)"
)
"""What a bonded or Coulomb study does not check, in the findings' words."""


def shtaerman_applies(interface: Interface, poisson_ratio: float) -> bool:
    """Whether Shtaerman's frictionless solution is the exact reference of a half-space of
    ``poisson_ratio`` under ``interface``: frictionless, Coulomb's mu = 0, or nu2 = 0.5."""
    return interface.coefficient in (None, 0.0) or poisson_ratio == 0.5


def _ratios(contact: IndentationResult) -> np.ndarray:
    """P (n + 1) / (2 E* a d n) per depth (:func:`shtaerman.theory.bonded.no_slip_ratio`)."""
    steps = contact.steps
    return no_slip_ratio(
        [step.force for step in steps],
        [step.contact_radius for step in steps],
        [step.depth for step in steps],
        contact.exact.modulus,
        contact.indenter.exponent,
    )


def no_slip_departures(contact: IndentationResult) -> np.ndarray:
    """P (n + 1) / (2 E* a d n) / chi(nu2) - 1 per depth of a linear power-law curve: 0 for
    the exact no-slip contact (:mod:`shtaerman.theory.bonded`)."""
    return _ratios(contact) / bonded_punch_factor(contact.half_space.poisson_ratio) - 1.0


def _estimate(accuracy: AccuracyResult) -> dict[str, float]:
    """The ladder's estimated relative errors by quantity ({} without a ladder)."""
    return accuracy.error_estimate() if accuracy.estimates else {}


def _identity(study: Study, contact: IndentationResult, accuracy: AccuracyResult) -> Check:
    """The no-slip identity's worst relative departure over the depths, within
    ``tolerances.identity`` plus the estimated errors of the force and the contact radius."""
    chi = bonded_punch_factor(study.half_space.poisson_ratio)
    departures = no_slip_departures(contact)
    worst = float(departures[np.argmax(np.abs(departures))])
    estimate = _estimate(accuracy)
    bar = estimate.get("force", 0.0) + estimate.get("contact_radius", 0.0)
    return Check(
        f"contact no-slip identity P(n+1)/(2E* a d n) / chi - 1 (chi(nu) = {chi:.5g})",
        worst,
        study.tolerances.identity + bar,
    )


def interface_checks(
    study: Study,
    contact: IndentationResult,
    impacts: dict[str, dict[str, float]],
    accuracy: AccuracyResult,
) -> list[Check]:
    """The checks of a bonded or Coulomb study where Shtaerman's is not its reference
    (:func:`shtaerman_applies` False): see the module's docstring."""
    exponent = abs(contact.fit.exponent / contact.analytic.exponent - 1.0)
    checks = [Check("contact exponent", exponent, study.tolerances.exponent)]
    if study.interface.friction is None:
        checks.append(_identity(study, contact, accuracy))
    fitted, tabulated = impacts["fem_fitted"], impacts["fem_tabulated"]
    checks += [
        Check(
            f"impact fem_tabulated {key} against fem_fitted",
            tabulated[key] / fitted[key] - 1.0,
            study.tolerances.impact,
        )
        for key in IMPACT_KEYS
    ]
    return checks


@dataclass(frozen=True)
class InterfaceEffect:
    """A bonded or Coulomb indenter's departures from Shtaerman's frictionless solution.

    Attributes
    ----------
    kind : str
        ``bonded`` or ``coulomb``.
    friction : float or None
        Coulomb's mu (None: no slip).
    departures : dict of str to float
        Relative, signed: ``force``, ``contact_radius``, ``central_pressure`` at the deepest
        depth, ``beta``, and the FEM-tabulated impact's ``x_c``, ``P_c``, ``t_c``.
    errors : dict of str to float
        The ladder's estimated relative errors of the contact's departures (empty without).
    ratio : float
        P (n + 1) / (2 E* a d n) at the deepest depth (1 frictionless, chi(nu) no slip).
    chi : float
        Mossakovskii's chi(nu2).
    """

    kind: str
    friction: float | None
    departures: dict[str, float]
    errors: dict[str, float]
    ratio: float
    chi: float

    @property
    def share(self) -> float:
        """(ratio - 1) / (chi - 1): 0 frictionless, 1 no slip (Coulomb lies between, within
        the mesh's error)."""
        return (self.ratio - 1.0) / (self.chi - 1.0)

    def to_dict(self) -> dict[str, object]:
        """JSON-ready, with the reference named and what is not checked."""
        return {
            "reference": "Shtaerman's frictionless solution",
            "kind": self.kind,
            "friction": self.friction,
            "departures": self.departures,
            "error_estimate": self.errors,
            "no_slip_ratio": self.ratio,
            "chi": self.chi,
            "no_slip_share": self.share,
            "not_checked": NOT_CHECKED,
        }


def interface_effect(
    study: Study,
    contact: IndentationResult,
    impacts: dict[str, dict[str, float]],
    accuracy: AccuracyResult,
) -> InterfaceEffect:
    """What the study's bonded or Coulomb indenter changes against Shtaerman's solution."""
    deepest = contact.step_table()[-1]
    departures = {
        key: deepest[key] / deepest[f"{key}_analytic"] - 1.0
        for key in ("force", "contact_radius", "central_pressure")
    }
    departures["beta"] = contact.fit.beta_fixed_exponent / contact.analytic.beta - 1.0
    exact, tabulated = impacts["analytic"], impacts["fem_tabulated"]
    departures |= {key: tabulated[key] / exact[key] - 1.0 for key in IMPACT_KEYS}
    estimate = _estimate(accuracy)
    errors = {key: estimate[key] for key in departures if key in estimate}
    return InterfaceEffect(
        kind=study.interface.name,
        friction=study.interface.friction,
        departures=departures,
        errors=errors,
        ratio=float(_ratios(contact)[-1]),
        chi=bonded_punch_factor(study.half_space.poisson_ratio),
    )
