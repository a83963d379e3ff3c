"""One cross-check study: FEM contact curve -> fits -> the impact three ways -> pass or fail.

The impact is solved (a) with the exact analytic beta (Ateb solution), (b) with the FEM-fitted
beta and exponent through the same Ateb solution, and (c) by integrating M x'' = -P(x) on the
tabulated FEM force curve itself (no power-law assumption). In (b) and (c) the contact radius
a(t) and central pressure p(0, t) come from the FEM curves too.
"""

from __future__ import annotations

import time
import warnings
from collections.abc import Callable
from dataclasses import dataclass

import numpy as np
from scipy.integrate import IntegrationWarning

from ...fem.fit import fit_power_law
from ...guards import warn_outside_validity
from ...theory.impact import ImpactHistory, ImpactResult, solve_impact
from ...theory.impact_ode import integrate_impact
from ...theory.materials import effective_modulus
from ...theory.profile_impact import ProfileImpactResult
from ...theory.sneddon import SneddonContact, contact_law
from ...theory.viscoelastic import elastic_impact
from ..checks import Check, Outcome
from .accuracy import AccuracyResult, run_ladder
from .contact_law import FemContactLaw, fem_contact_law
from .convergence import ConvergenceStudy, convergence_study
from .indentation import IndentationResult, default_depths
from .interface import InterfaceEffect, interface_checks, interface_effect, shtaerman_applies
from .layer import LayerFindings, layer_checks, layer_findings, with_dynamic_impact
from .loader import DEPTH_OVERSHOOT, Study

__all__ = ["IMPACT_KEYS", "Check", "StudyOutcome", "run_contact_study"]

IMPACT_KEYS = ("beta", "x_c", "P_c", "a_c", "p_c", "t_c", "t_y")
"""SI keys of every impact entry (those of ``shtaerman impact --json``)."""
CHECKED_IMPACT_KEYS = ("x_c", "P_c", "t_c")
HISTORY_POINTS = 201

Progress = Callable[[str], None]


@dataclass(frozen=True)
class StudyOutcome(Outcome):
    """Everything a study produced (SI units)."""

    study: Study
    contact: IndentationResult
    law: FemContactLaw
    impacts: dict[str, dict[str, float]]
    """Maxima per variant: "analytic", "fem_fitted", "fem_tabulated"."""
    histories: dict[str, ImpactHistory]
    exact: ImpactResult | ProfileImpactResult
    """The exact quasi-static impact: Ateb's of the power law, Sneddon's of another profile."""
    checks: list[Check]
    seconds: float
    convergence: ConvergenceStudy | None = None
    """The study's mesh-convergence study, if it asks for one."""
    accuracy: AccuracyResult | None = None
    """The mesh ladder whose finest level (that passed) is ``contact``, with its error
    estimates (none when a level failed: :attr:`AccuracyResult.missing` says why)."""
    layer: LayerFindings | None = None
    """On a layer: its force against the half-space's and the impact on it."""
    interface_effect: InterfaceEffect | None = None
    """A bonded or Coulomb indenter's departures from Shtaerman's solution, where that is not
    its reference (:func:`.interface.shtaerman_applies`; its checks are then
    :func:`.interface.interface_checks`)."""

    def differences(self) -> dict[str, dict[str, float]]:
        """Relative differences of the FEM-fed impacts against the analytic one."""
        exact = self.impacts["analytic"]
        return {
            variant: {key: values[key] / exact[key] - 1.0 for key in IMPACT_KEYS[1:]}
            for variant, values in self.impacts.items()
            if variant != "analytic"
        }


def _study_depths(study: Study) -> np.ndarray:
    """The study's depths, m: as given, or eight up to 1.01 x_c of its impact (radii a/3 .. a
    of any profile)."""
    if study.depths is not None:
        return np.asarray(study.depths)
    impact = (study.mass, study.velocity, study.striker)
    return default_depths(study.indenter, study.half_space, *impact, overshoot=DEPTH_OVERSHOOT)


def tabulated_impact(
    study: Study, law: FemContactLaw, guess: float
) -> tuple[dict[str, float], ImpactHistory]:
    """The impact M x'' = -P(x) on a tabulated FEM curve: its maxima (beta NaN) and history.

    ``guess`` (m) sets the ODE's length scale (the exact impact's x_c).
    """
    with warnings.catch_warnings():  # its energy quadrature only scales the ODE (a layer's
        warnings.simplefilter("ignore", IntegrationWarning)  # kinked log-log law warns)
        numerical = integrate_impact(study.mass, study.velocity, law.force, guess)
    t = np.linspace(0.0, numerical.t_y, HISTORY_POINTS)
    x, v = numerical.sample(t)
    x = np.maximum(x, 0.0)
    x[-1] = 0.0
    a, p0 = law.contact_radius(x), law.central_pressure(x)
    history = ImpactHistory(t, x, v, law.force(x), a, p0)
    maxima = {
        "beta": float("nan"),  # no power law assumed
        "x_c": numerical.x_c,
        "P_c": numerical.P_c,
        "a_c": float(law.contact_radius(numerical.x_c)),
        "p_c": float(law.central_pressure(numerical.x_c)),
        "t_c": numerical.t_c,
        "t_y": numerical.t_y,
    }
    return maxima, history


def impact_maxima(result: ImpactResult | ProfileImpactResult) -> dict[str, float]:
    """beta and the maxima x_c, P_c, a_c, p_c, t_c, t_y of an impact (SI units)."""
    return {key: float(getattr(result, key)) for key in IMPACT_KEYS}


def _exact_fitted(study: Study, contact: IndentationResult, modulus: float) -> dict | None:
    """The impact maxima of beta x^q fitted to the exact forces at the FEM's depths as the
    FEM's are (None for the power law, whose exact impact is that already): the reference of
    the FEM-fitted impact of a sphere or a table, whose force is no power law, so that its
    check measures the FE error and not the fit's model error."""
    exact = contact.exact
    if not isinstance(exact, SneddonContact):
        return None
    depths = np.array([step.depth for step in contact.steps])
    fit = fit_power_law(depths, exact.force(depths), exact.force_exponent)
    scale = modulus / exact.modulus
    law = FemContactLaw(
        depths=depths,
        forces=scale * exact.force(depths),
        radii=exact.contact_radius(depths),
        central_pressures=scale * exact.central_pressure(depths),
        beta=scale * fit.beta,
        force_exponent=fit.exponent,
    )
    return impact_maxima(solve_impact(study.mass, study.velocity, law))


def _checks(
    study: Study, contact: IndentationResult, impacts: dict, fitted: dict | None = None
) -> list[Check]:
    """The contact curve's and the impacts' checks; the FEM-fitted impact against
    ``fitted`` (:func:`_exact_fitted`) where given, else the exact impact."""
    tolerances, errors = study.tolerances, contact.errors()
    checks = [
        Check(f"contact {key}", errors[key], getattr(tolerances, key))
        for key in ("force", "beta", "exponent", "contact_radius", "central_pressure")
    ]
    for variant in ("fem_fitted", "fem_tabulated"):
        exact = fitted if variant == "fem_fitted" and fitted else impacts["analytic"]
        checks += [
            Check(
                f"impact {variant} {key}",
                impacts[variant][key] / exact[key] - 1.0,
                tolerances.impact,
            )
            for key in CHECKED_IMPACT_KEYS
        ]
    return checks


def _reference_checks(
    study: Study, accuracy: AccuracyResult, impacts: dict, modulus: float
) -> tuple[list[Check], InterfaceEffect | None]:
    """The checks against Shtaerman's (Sneddon's) solution where it is the study's reference,
    else (a bonded or Coulomb indenter on nu2 < 0.5) the interface's checks and its effect
    (:mod:`.interface`)."""
    contact = accuracy.finest
    if study.layer is None and not shtaerman_applies(
        study.interface, study.half_space.poisson_ratio
    ):
        effect = interface_effect(study, contact, impacts, accuracy)
        return interface_checks(study, contact, impacts, accuracy), effect
    return _checks(study, contact, impacts, _exact_fitted(study, contact, modulus)), None


def run_contact_study(
    study: Study, quick: bool = False, progress: Progress | None = None
) -> StudyOutcome:
    """Run one study: the FEM contact curve, the fits and the three impacts.

    Parameters
    ----------
    study : Study
    quick : bool
        Use the study's coarse ``quick_mesh`` (CI) instead of its ``mesh``.
    progress : callable, optional
        Receives a short line per stage.
    """
    report = progress or (lambda _line: None)
    start = time.perf_counter()
    modulus = effective_modulus(study.striker, study.half_space)
    exact = elastic_impact(study.mass, study.velocity, contact_law(study.indenter, modulus))
    mesh, depths = study.quick_mesh if quick else study.mesh, _study_depths(study)
    report(f"{study.name}: FEM contact curve on a 3-mesh ladder (error estimates)")
    accuracy = run_ladder(  # partial: a failed level leaves the finest that passed, unestimated
        study.indenter,
        study.half_space,
        depths,
        mesh,
        refine=study.refine,
        friction=study.interface.coefficient,
        partial=True,
        geometry=study.geometry,
    )
    contact = accuracy.finest
    deepest, thickness = contact.steps[-1].depth, contact.mesh_stats.get("thickness")
    warn_outside_validity(study.indenter, deepest, thickness, False, "the deepest depth")
    if exact.x_c > deepest:  # the analytic impact goes deeper than the curve (depths given)
        warn_outside_validity(study.indenter, exact.x_c, None, False, "the exact impact's x_c")
    report(f"{study.name}: impact (analytic, FEM-fitted, FEM-tabulated)")
    law = fem_contact_law(contact, modulus)
    fitted = solve_impact(study.mass, study.velocity, law)
    tabulated, tabulated_history = tabulated_impact(study, law, exact.x_c)
    impacts = {
        "analytic": impact_maxima(exact),
        "fem_fitted": impact_maxima(fitted),
        "fem_tabulated": tabulated,
    }
    histories = {
        "analytic": exact.history(HISTORY_POINTS),
        "fem_fitted": fitted.history(HISTORY_POINTS),
        "fem_tabulated": tabulated_history,
    }
    convergence = _convergence(study, contact, quick, report)
    layer = None
    checks, effect = _reference_checks(study, accuracy, impacts, modulus)
    if study.layer is not None:
        layer = layer_findings(study.layer, accuracy, law, impacts["analytic"], tabulated)
        layer = _dynamic_layer(study, layer, quick, report)
        checks = layer_checks(layer, study.tolerances.force, study.tolerances.impact)
    return StudyOutcome(
        study=study,
        contact=contact,
        law=law,
        impacts=impacts,
        histories=histories,
        exact=exact,
        checks=checks,
        seconds=time.perf_counter() - start,
        convergence=convergence,
        accuracy=accuracy,
        layer=layer,
        interface_effect=effect,
    )


def _dynamic_layer(
    study: Study, layer: LayerFindings, quick: bool, report: Progress
) -> LayerFindings:
    """``layer`` with the dynamic impact on it where the study asks for it (``dynamic``)."""
    if not study.layer.dynamic:
        return layer
    report(f"{study.name}: dynamic FE impact on the layer (restitution)")
    impact = (study.mass, study.velocity)
    friction = study.interface.coefficient
    return with_dynamic_impact(
        layer, study.layer, study.indenter, study.half_space, impact, quick, friction
    )


def _convergence(
    study: Study, contact: IndentationResult, quick: bool, report: Progress
) -> ConvergenceStudy | None:
    """The study's mesh-convergence levels (the coarsest three in quick mode), or None."""
    sizes = study.convergence_sizes[:3] if quick else study.convergence_sizes
    if not sizes:
        return None
    report(f"{study.name}: mesh convergence, {len(sizes)} meshes")
    depths = [step.depth for step in contact.steps]
    return convergence_study(
        study.indenter,
        study.half_space,
        sizes,
        depths=depths,
        base=study.mesh,
        friction=study.interface.coefficient,
        geometry=study.geometry,
    )
