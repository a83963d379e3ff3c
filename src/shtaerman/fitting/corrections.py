"""The FE correction of a force history: a pad, waves and finite strain at the fitted point.

The FE impact (:func:`shtaerman.dynamic`) at the fitted point corrects the exact model,
F(t) = c_P [F_ex(t / c_t) + P_ex delta(t / (c_t T_ex))], held fixed while it is fitted again
(docs/fit.md, "A pad, waves and finite strain: the FE corrections").
"""

from __future__ import annotations

import dataclasses
import math
from collections.abc import Callable, Mapping
from dataclasses import dataclass
from typing import TYPE_CHECKING, Protocol

import numpy as np

from ..problem import Problem
from ..theory.materials import RIGID, Material
from ..theory.sneddon import Indenter, contact_law
from ..theory.viscoelastic import PronySeries, elastic_impact, viscoelastic_impact
from ..validation import InputError, NumericalFailureError

if TYPE_CHECKING:  # the api package imports the fit's result: a cycle at run time
    from ..api.dynamic_result import DynamicResult

__all__ = [
    "Correction",
    "RowCorrection",
    "check_striker_reach",
    "exact_impact",
    "exact_rebound",
    "fe_correction",
    "fe_parts",
    "fe_rows",
    "needs_fe",
    "relative_error",
    "youngs_modulus",
]


class KnownParts(Protocol):
    """What the corrections read of the fit's known parts (:class:`.models.Known`)."""

    indenter: Indenter
    striker: Material
    nu2: float
    steps: int


SHAPE_POINTS = 400
"""Samples of the shape difference delta over the FE contact."""


@dataclass(frozen=True)
class Correction:
    """The FE / exact correction of a force history, measured at one point."""

    force_scale: float
    """c_P = P_max(FE) / P_max(exact)."""
    time_scale: float
    """c_t = t_contact(FE) / t_contact(exact)."""
    tau: np.ndarray
    """Time over the FE contact time, 0 ... 1."""
    shape: np.ndarray
    """delta(tau): the FE shape minus the exact shape, each over its peak."""
    errors: Mapping[str, float]
    """The FE run's relative error estimates of P_max and t_contact (NaN if not estimated)."""
    at: Mapping[str, float]
    """The point of the FE run: E2, nu2, mass, velocity and the Prony weights."""

    def apply(self, exact: Callable[[np.ndarray], np.ndarray], peak: float, duration: float,
              t: np.ndarray) -> np.ndarray:  # fmt: skip
        """The corrected force in N at ``t`` (s from the touch) from the exact history
        ``exact`` (peak ``peak`` N, contact time ``duration`` s)."""
        stretched = t / self.time_scale
        delta = np.interp(stretched / duration, self.tau, self.shape, left=0.0, right=0.0)
        return self.force_scale * (exact(stretched) + peak * delta)

    runs = 1
    """FE impacts behind this correction."""

    def moved(self, key: str) -> Correction:
        """This correction with the ratio of ``key`` (P_max or t_contact) moved by its FE
        error estimate."""
        scale = {"P_max": "force_scale", "t_contact": "time_scale"}[key]
        factor = 1.0 + self.errors[key]
        return dataclasses.replace(self, **{scale: getattr(self, scale) * factor})

    def entry(self, problem: Problem) -> dict[str, object]:
        """The correction as the result's JSON (``corrections``)."""
        return {
            "name": f"FE impact: {fe_parts(problem)}",
            "force_scale": self.force_scale,
            "time_scale": self.time_scale,
            "shape_max": float(np.max(np.abs(self.shape))),
            "fe_error": dict(self.errors),
            "at": dict(self.at),
        }


def needs_fe(problem: Problem) -> bool:
    """Whether ``problem`` has a part the exact models lack: a pad, density or finite strain."""
    density = problem.body.material.density
    return (problem.geometry.thickness is not None or bool(density)
            or problem.body.model != "linear")  # fmt: skip


def fe_parts(problem: Problem) -> str:
    """What an FE run of ``problem`` stands for beyond the exact models, in words: a pad,
    waves, finite strain (:func:`needs_fe`)."""
    parts = []
    if problem.geometry.thickness is not None:
        parts.append(f"pad {problem.geometry.thickness:g} m ({problem.geometry.base} base)")
    if problem.body.material.density:
        parts.append(f"waves (density2 {problem.body.material.density:g} kg/m^3)")
    if problem.body.model != "linear":
        parts.append(f"finite strain ({problem.body.model})")
    return ", ".join(parts)


def exact_impact(known: KnownParts, values: Mapping[str, float], prony: PronySeries | None,
                 ) -> tuple[Callable[[np.ndarray], np.ndarray], float, float]:  # fmt: skip
    """(force in N at times in s from the touch, peak force in N, contact time in s) of the
    exact quasi-static impact (the Ateb impact, or the viscoelastic one with ``prony``)."""
    law = contact_law(known.indenter, values["E_star"])
    if prony is None:
        result = elastic_impact(values["mass"], values["velocity"], law)

        def elastic(t: np.ndarray) -> np.ndarray:
            inside = (t > 0.0) & (t < result.t_y)
            force = np.zeros_like(t)
            force[inside] = result.history(times=t[inside]).P
            return force

        return elastic, float(result.P_c), float(result.t_y)
    run = viscoelastic_impact(values["mass"], values["velocity"], law, prony, steps=known.steps)
    history = run.history

    def relaxing(t: np.ndarray) -> np.ndarray:
        return np.interp(t, history["t"], history["P"], left=0.0, right=0.0)

    return relaxing, float(run.P_max), float(run.t_contact)


def exact_rebound(known: KnownParts, values: Mapping[str, float], velocity: float,
                  prony: PronySeries | None) -> tuple[float, float]:  # fmt: skip
    """(restitution, contact time in s) of the exact quasi-static impact at ``velocity`` m/s:
    the elastic one (e = 1), or the viscoelastic one with ``prony``."""
    law = contact_law(known.indenter, values["E_star"])
    if prony is None:
        return 1.0, elastic_impact(values["mass"], velocity, law).t_y
    result = viscoelastic_impact(values["mass"], velocity, law, prony, steps=known.steps)
    return result.restitution, result.t_contact


def _point(problem: Problem, known: KnownParts, values: Mapping[str, float],
           prony: PronySeries | None) -> tuple[Problem, dict[str, float]]:  # fmt: skip
    """The problem at the fitted ``values`` (E2 from E* at the known nu2) and that point; a
    density left unset is no waves, the massless FE impact (density 0); the striker rigid, as
    the FE impact's is."""
    check_striker_reach(known, values["E_star"])
    e2 = youngs_modulus(known, values["E_star"], known.nu2)
    body = problem.body
    density = body.material.density
    material = Material(e2, known.nu2, 0.0 if density is None else density)
    striker = dataclasses.replace(problem.striker, mass=values["mass"], material=RIGID,
                                  velocity=values["velocity"])  # fmt: skip
    body = dataclasses.replace(body, material=material, prony=prony)
    at = {"E2": e2, "nu2": known.nu2, "mass": values["mass"], "velocity": values["velocity"]}
    if prony is not None:
        at.update({f"g{i}": g for i, g in enumerate(prony.weights, start=1)})
    return dataclasses.replace(problem, striker=striker, body=body), at


def check_striker_reach(known: KnownParts, modulus: float) -> None:
    """NumericalFailureError naming E1 when the combined modulus ``modulus`` (Pa) the data
    need is at or above the striker's own E1 / (1 - nu1^2): no E2 gives it."""
    limit = 1.0 / known.striker.compliance if known.striker.compliance > 0 else math.inf
    if modulus >= limit:
        raise NumericalFailureError(
            f"E1={known.striker.youngs_modulus:g}: the data's E* = {modulus:.4g} Pa exceeds what "
            f"this striker allows at any E2 (E* < E1 / (1 - nu1^2) = {limit:.4g} Pa): raise "
            "E1=... or fit E2 with a rigid striker (E1=inf)"
        )


def check_rigid_striker(striker: Material, nu2: float, young: float, error: float,
                        runs: str) -> None:  # fmt: skip
    """NumericalFailureError naming E1 when the striker's compliance (1 - nu1^2) / E1 is more
    than ``error``, the FE ``runs``' estimated relative error, of the body's at E2 ``young``
    (Pa): the FE striker is rigid, so a softer one would be silently dropped (a steel ball on
    rubber: 5e-5). An unknown error (NaN) checks nothing."""
    ratio = striker.compliance * young / (1.0 - nu2 * nu2)
    if ratio > error:
        raise NumericalFailureError(
            f"E1={striker.youngs_modulus:g}: the FE {runs} press a rigid striker, and this "
            f"one's compliance is {ratio:.2g} of the body's at E2 near {young:.3g} Pa, more "
            f"than their error {error:.2g}: give E1=inf, or leave out the pad, waves and finite "
            "strain (the exact models take E1)"
        )


def youngs_modulus(known: KnownParts, modulus: float, nu2: float) -> float:
    """E2 in Pa giving the combined modulus ``modulus`` (Pa) with the striker and ``nu2``
    (inf where the striker alone is softer)."""
    rest = 1.0 / modulus - known.striker.compliance
    return (1.0 - nu2 * nu2) / rest if rest > 0 else float("inf")


def _fe_impact(case: Problem, at: Mapping[str, float], refine: float) -> DynamicResult:
    """The FE impact of ``case`` at the fitted point ``at`` (with its error-estimate ladder at
    ``refine``). Its refusal (InputError) says the point: the E2 it was checked at is the
    fit's, not the starting value given, and the values it names hold at that E2, which the
    next rounds of the fit move."""
    from ..api.fem_dynamic import dynamic
    from ..study.ladder import WITHOUT_ESTIMATE

    try:
        return dynamic(case, refine=refine, estimate=True)
    except InputError as error:
        said = str(error).removesuffix(WITHOUT_ESTIMATE)
        raise InputError(
            f"{said}; this is the FE impact that corrects the fit, at the fitted E2 = "
            f"{at['E2']:.4g} Pa (not the starting value): the values named hold at this E2, "
            "which the next rounds of the fit move",
            error.parameter,
        ) from None


def fe_correction(problem: Problem, known: KnownParts, values: Mapping[str, float],
                  prony: PronySeries | None, refine: float) -> Correction:  # fmt: skip
    """The :class:`Correction` measured by one FE impact of ``problem`` at ``values`` (with
    its error-estimate ladder at ``refine``)."""
    case, at = _point(problem, known, values, prony)
    run = _fe_impact(case, at, refine)
    check_rigid_striker(known.striker, known.nu2, at["E2"], relative_error(run, "P_max"), "impacts")
    exact, peak, duration = exact_impact(known, values, prony)
    history = run.history()
    c_p, c_t = run.P_max / peak, run.t_contact / duration
    tau = np.linspace(0.0, 1.0, SHAPE_POINTS)
    fe = np.interp(tau * run.t_contact, history["t"], history["P"]) / run.P_max
    ex = exact(tau * duration) / peak
    errors = {k: relative_error(run, k) for k in ("P_max", "t_contact")}
    return Correction(c_p, c_t, tau, fe - ex, errors, at)


def relative_error(run: DynamicResult, key: str) -> float:
    """The FE run's estimated relative error of ``key``; NaN when its ladder gave none (the
    result's fe_error is then null and no FE error enters the interval)."""
    value = (run.error_estimate or {}).get(key)
    return float(value) if value is not None and math.isfinite(value) else math.nan


@dataclass(frozen=True)
class RowCorrection:
    """The FE / exact ratios of the restitution and the contact time at each drop velocity
    of rebound data, measured at one point (one FE run per velocity)."""

    restitution: np.ndarray
    """e(FE) / e(exact) per velocity."""
    contact_time: np.ndarray
    """t_contact(FE) / t_contact(exact) per velocity."""
    errors: Mapping[str, float]
    """The FE runs' largest relative error estimates of e (restitution) and t_contact."""
    at: Mapping[str, float]
    """The point of the FE runs."""

    @property
    def runs(self) -> int:
        """FE impacts behind this correction (one per velocity)."""
        return len(self.restitution)

    def apply(self, rows: list[tuple[float, float]]) -> list[tuple[float, float]]:
        """The corrected (restitution, contact time) of the exact ``rows``."""
        ratios = zip(self.restitution, self.contact_time, strict=True)
        return [(e * r, t * c) for (e, t), (r, c) in zip(rows, ratios, strict=True)]

    def moved(self, key: str) -> RowCorrection:
        """This correction with the ratios of ``key`` (restitution or t_contact) moved by
        their FE error estimate."""
        name = {"restitution": "restitution", "t_contact": "contact_time"}[key]
        return dataclasses.replace(self, **{name: getattr(self, name) * (1 + self.errors[key])})

    def entry(self, problem: Problem) -> dict[str, object]:
        """The correction as the result's JSON (``corrections``)."""
        return {
            "name": f"FE impact: {fe_parts(problem)}",
            "restitution_scale": self.restitution.tolist(),
            "time_scale": self.contact_time.tolist(),
            "fe_error": dict(self.errors),
            "at": dict(self.at),
        }


def fe_rows(problem: Problem, known: KnownParts, values: Mapping[str, float],
            prony: PronySeries | None, refine: float, velocities: np.ndarray,
            ) -> RowCorrection:  # fmt: skip
    """The :class:`RowCorrection` measured by one FE impact of ``problem`` at ``values`` per
    drop velocity (each with its error-estimate ladder at ``refine``)."""
    ratios, errors = [], {"restitution": 0.0, "t_contact": 0.0}
    for velocity in velocities:
        point = {**values, "velocity": float(velocity)}
        case, at = _point(problem, known, point, prony)
        run = _fe_impact(case, at, refine)
        error = relative_error(run, "t_contact")
        check_rigid_striker(known.striker, known.nu2, at["E2"], error, "impacts")
        e, t_c = exact_rebound(known, values, velocity, prony)
        ratios.append((run.restitution / e, run.t_contact / t_c))
        for key, known_error in errors.items():  # NaN if any run has none
            error = relative_error(run, key)
            errors[key] = math.nan if math.isnan(error) else max(known_error, error)
    at.pop("velocity")
    ratio = np.array(ratios)
    return RowCorrection(ratio[:, 0], ratio[:, 1], errors, at)
