"""The exact quasi-static forward models a fit compares a measurement with.

- indentation: P = beta x^q, the power-law (Shtaerman, Hertz) contact law (Sneddon's of a
  sphere or a table), linear in E*;
- force history: the Ateb quasi-static impact, or with a Prony series the viscoelastic one
  (Lee-Radok while loading, Ting while unloading), shifted by a time offset and a baseline;
- rebound and resilience: the restitution e and contact time t_c of the same impacts at each
  drop velocity (the elastic impact rebounds with e = 1); the resilience is e^2.

Every model depends on the moduli only through the combined modulus E*, 1/E* = Q1 + Q2,
Q = (1 - nu^2)/E: E2 and nu2 are fitted as E* (:func:`modulus_report`). Each model's
parameters live in a transformed space (logarithms of positive scales) with finite bounds.
"""

from __future__ import annotations

import dataclasses
import math
import sys
from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass

import numpy as np

from ..theory.materials import Material, effective_modulus
from ..theory.sneddon import Indenter, contact_law
from ..theory.viscoelastic import PronySeries, elastic_impact
from ..validation import InputError
from .corrections import Correction, RowCorrection, exact_impact, exact_rebound
from .data import Measurement

__all__ = ["UNKNOWNS", "Known", "Model", "Parameter", "all_values", "build_model", "prony_at"]

UNKNOWNS = {
    "indentation": ("E2", "nu2"),
    "force-history": ("E2", "nu2", "mass", "velocity", "time_offset", "baseline", "prony", "tau"),
    "rebound": ("E2", "nu2", "mass", "prony", "tau"),
    "resilience": ("E2", "nu2", "mass", "prony", "tau"),
}
"""Kind -> the names ``--fit`` takes."""
MODULUS_SPAN = 1e4
"""E* is sought within [E*_start / span, E*_start * span]."""
SCALE_SPAN = 10.0
"""Mass and velocity are sought within a factor of this of the given values."""
MAX_WEIGHT = 0.999
"""Upper bound of each fitted Prony weight g_i."""
TAU_SPAN = 100.0
"""A free relaxation time is sought within this factor beyond the measured time range."""
REBOUND_WINDOW = (0.01, 10.0)
"""The relaxation times rebound data can determine, in units of the shortest and the longest
contact time: a faster term has relaxed before the rebound, a slower one has barely begun."""


@dataclass(frozen=True)
class Known:
    """The known parts of the problem and the starting values of the unknowns (SI units)."""

    indenter: Indenter
    striker: Material
    E2: float
    nu2: float
    mass: float
    velocity: float
    prony: PronySeries | None = None
    time_offset: float | None = None
    """The time of first touch in s (a fitted one's start); None: 0, or read off the data
    when fitted."""
    baseline: float = 0.0
    steps: int = 200
    correction: Correction | RowCorrection | None = None
    """The FE correction of a force history or of rebound data (a pad, waves, finite
    strain), held fixed."""

    @property
    def modulus(self) -> float:
        """The combined modulus E* in Pa of the given E2, nu2 and striker."""
        return effective_modulus(self.striker, Material(self.E2, self.nu2))


@dataclass(frozen=True)
class Parameter:
    """One fitted parameter: start, bounds (natural units) and whether it is fitted in log."""

    name: str
    start: float
    low: float
    high: float
    log: bool = False
    window: tuple[float, float] | None = None
    """The values the data can determine (natural units); outside it the parameter is
    reported not identifiable, whatever its Jacobian (a relaxation time outside the measured
    time range)."""
    tied: tuple[str, ...] = ()
    """The parameters not identifiable with this one (a Prony weight with its time)."""

    def to_space(self, value: float | np.ndarray) -> float | np.ndarray:
        """The natural value in the fitting space."""
        return np.log(value) if self.log else value

    def from_space(self, value: float | np.ndarray) -> float | np.ndarray:
        """The fitting space's value in natural units."""
        return np.exp(value) if self.log else value


@dataclass(frozen=True)
class Model:
    """What the solver needs: the parameters, the observed vector and its prediction."""

    parameters: tuple[Parameter, ...]
    observed: np.ndarray
    predict: Callable[[Mapping[str, float]], np.ndarray]
    relative: bool
    """Residuals relative to the observed values (rebound data) or in their unit."""
    unit: str
    """The residual's unit."""
    description: str
    trades: tuple[frozenset[str], ...] = ()
    """The parameters of each exact null direction of the model: moving them together along it
    leaves every prediction unchanged, so no data determine them, whatever the numerical rank
    of the Jacobian (:func:`trades`)."""


def all_values(known: Known, fitted: Mapping[str, float]) -> dict[str, float]:
    """Every parameter of the forward model: the fitted ones, else the known ones."""
    values = {
        "E_star": known.modulus,
        "mass": known.mass,
        "velocity": known.velocity,
        "time_offset": 0.0 if known.time_offset is None else known.time_offset,
        "baseline": known.baseline,
    }
    values.update(fitted)
    return values


def prony_at(known: Known, values: Mapping[str, float]) -> PronySeries | None:
    """The Prony series with the fitted weights g1, g2, ... and times tau1, tau2, ... in
    place of the given ones."""
    if known.prony is None:
        return None
    weights = [values.get(f"g{i}", g) for i, g in enumerate(known.prony.weights, start=1)]
    if math.fsum(weights) >= MAX_WEIGHT:  # the search went past the relaxed modulus: scale
        weights = [w * MAX_WEIGHT / math.fsum(weights) for w in weights]
    times = [values.get(f"tau{i}", tau) for i, tau in enumerate(known.prony.times, start=1)]
    return PronySeries(tuple(weights), tuple(times))


def force_history(known: Known, values: Mapping[str, float], time: np.ndarray) -> np.ndarray:
    """The force in N at ``time`` (s, the data's clock): the impact shifted by the time
    offset, with the known FE correction if any, plus the baseline."""
    t = np.asarray(time, dtype=float) - values["time_offset"]
    exact, peak, duration = exact_impact(known, values, prony_at(known, values))
    if known.correction is None:
        return exact(t) + values["baseline"]
    return known.correction.apply(exact, peak, duration, t) + values["baseline"]  # type: ignore[union-attr]


def _rebound_predict(known: Known, data: Measurement) -> Callable[..., np.ndarray]:
    """The predicted observations of rebound (or resilience) data, row by row."""
    names = [name for name in ("restitution", "contact_time", "resilience") if name in data.columns]

    def predict(fitted: Mapping[str, float]) -> np.ndarray:
        values = all_values(known, fitted)
        prony = prony_at(known, values)
        rows = [exact_rebound(known, values, v, prony) for v in data.columns["velocity"]]
        if isinstance(known.correction, RowCorrection):
            rows = known.correction.apply(rows)
        out = {
            "restitution": [e for e, _ in rows],
            "contact_time": [t for _, t in rows],
            "resilience": [e * e for e, _ in rows],
        }
        return np.concatenate([np.asarray(out[name]) for name in names])

    return predict


def _contact_words(indenter: Indenter) -> str:
    """The indentation's forward model in words."""
    if indenter.kind == "power-law":
        return "power-law contact P = beta x^q (Shtaerman; Hertz for n = 2), exact"
    return f"Sneddon's contact of the {indenter.kind} profile, exact (quadrature)"


def _check_sphere_reach(law: object, deepest: float) -> None:
    """Refuse a depth ``deepest`` (m) beyond the deepest that Sneddon's sphere law reaches in
    floating point (about 18 R, as a -> R); a tabulated profile's table refuses its own."""
    if not getattr(law, "sphere", False):
        return
    radius = law.max_contact_radius
    reach = float(law.depth(math.nextafter(radius, 0.0)))
    if deepest > reach:
        raise InputError(
            f"sphere_radius: the data's depth {deepest:.6g} m is {deepest / radius:.3g} times "
            f"the sphere's radius {radius:.6g} m, beyond Sneddon's contact of it (at most "
            f"{reach:.3g} m); give the sphere's radius in m (or the depths in m, --units)",
            "sphere_radius",
        )


def _modulus_start(known: Known, data: Measurement, kind: str) -> float:
    """A starting E* in Pa from the data: exact for an indentation (P linear in E*), from the
    peak force (P_c ~ E*^(1/(q+1))) or the contact time (t_c ~ E*^(-1/(q+1))) otherwise."""
    law = contact_law(known.indenter, known.modulus)
    q = law.force_exponent
    columns = data.columns
    if kind == "indentation":
        _check_sphere_reach(law, float(np.max(columns["depth"])))
        shape = law.force(columns["depth"]) / law.modulus
        return float(np.sum(columns["force"] * shape) / np.sum(shape * shape))
    if kind == "force-history":
        peak = float(np.max(columns["force"]) - known.baseline)
        model = elastic_impact(known.mass, known.velocity, law).P_c
        return known.modulus * (max(peak, 1e-300) / model) ** (q + 1.0)
    if "contact_time" in columns:
        model = [elastic_impact(known.mass, v, law).t_y for v in columns["velocity"]]
        ratio = float(np.median(np.asarray(model) / columns["contact_time"]))
        return known.modulus * ratio ** (q + 1.0)
    return known.modulus


def _checked_start(start: float, data: Measurement) -> float:
    """The starting E* in Pa, or InputError naming the data when its search range, start /
    MODULUS_SPAN to start * MODULUS_SPAN, is not one of positive normal floats (a force that
    does not rise above 0, values near the float range's ends: wrong signs or units)."""
    low, high = start / MODULUS_SPAN, start * MODULUS_SPAN
    if start < 0.0 and "force" in data.columns:  # they pull: the sign is wrong, not the size
        raise InputError(
            f"{data.source}: the data give a starting modulus E* = {start:.3g} Pa < 0 "
            f"(from the columns {', '.join(data.columns)}): a push is positive; check the "
            "force's sign",
            "data",
        )
    if not (low >= sys.float_info.min and math.isfinite(high)):
        raise InputError(
            f"{data.source}: the data give no usable starting modulus (E* = {start:.3g} Pa from "
            f"the columns {', '.join(data.columns)}); check their signs and units: the values "
            "must lie well inside the floating-point range",
            "data",
        )
    return start


def _time_offset_start(known: Known, data: Measurement) -> float:
    """The time of first touch read off the data: where the force first exceeds 5 % of its
    peak, moved back by a sixth of the rise to the peak."""
    time, force = data.columns["time"], data.columns["force"] - known.baseline
    peak = int(np.argmax(force))
    first = int(np.flatnonzero(force > 0.05 * force[peak])[0])
    return float(time[first] - (time[peak] - time[first]) / 6.0)


def _parameters(known: Known, data: Measurement, unknowns: Sequence[str]) -> tuple[Parameter, ...]:
    """The fitted parameters of ``unknowns`` with their starts and bounds."""
    params = []
    if "E2" in unknowns or "nu2" in unknowns:
        with np.errstate(all="ignore"):  # an overflow is refused, naming the data
            try:
                start = _modulus_start(known, data, data.kind)
            except OverflowError:  # a float's power beyond the range (a force of 1e300 N)
                start = math.inf
        start = _checked_start(start, data)
        params.append(Parameter("E_star", start, start / MODULUS_SPAN, start * MODULUS_SPAN, True))
    for name in ("mass", "velocity"):
        if name in unknowns:
            value = getattr(known, name)
            params.append(Parameter(name, value, value / SCALE_SPAN, value * SCALE_SPAN, True))
    if "time_offset" in unknowns:
        time = data.columns["time"]
        span = float(time[-1] - time[0])
        start = _time_offset_start(known, data) if known.time_offset is None else known.time_offset
        params.append(Parameter("time_offset", start, float(time[0]) - span, float(time[-1])))
    if "baseline" in unknowns:
        size = float(np.max(np.abs(data.columns["force"])))
        params.append(Parameter("baseline", known.baseline, -size, size))
    if "prony" in unknowns:
        for i, g in enumerate(known.prony.weights, start=1):  # type: ignore[union-attr]
            params.append(Parameter(f"g{i}", min(max(g, 1e-3), 0.9), 0.0, MAX_WEIGHT))
    if "tau" in unknowns:
        params.extend(_tau_parameters(known, data, "prony" in unknowns))
    return tuple(params)


def time_window(known: Known, data: Measurement) -> tuple[float, float]:
    """The measured time range in s: a force history's sampling step to its span; for
    rebound data :data:`REBOUND_WINDOW` times the shortest and the longest contact time (the
    measured ones, else the elastic impacts' at the starting values)."""
    if "time" in data.columns:
        time = data.columns["time"]
        return float(np.median(np.diff(time))), float(time[-1] - time[0])
    if "contact_time" in data.columns:
        times = data.columns["contact_time"]
    else:
        law = contact_law(known.indenter, known.modulus)
        times = np.array([elastic_impact(known.mass, v, law).t_y for v in data.columns["velocity"]])
    return REBOUND_WINDOW[0] * float(np.min(times)), REBOUND_WINDOW[1] * float(np.max(times))


def _tau_parameters(known: Known, data: Measurement, weights: bool) -> list[Parameter]:
    """The free relaxation times tau_i (fitted in log) within :data:`TAU_SPAN` beyond the
    measured time range; each outside that range is not identifiable, and its weight g_i
    (when fitted) with it: only g_i / tau_i is seen of a slow term, g_i alone of a fast one."""
    low, high = time_window(known, data)
    params = []
    for i, tau in enumerate(known.prony.times, start=1):  # type: ignore[union-attr]
        start = min(max(tau, low / TAU_SPAN), high * TAU_SPAN)
        tied = (f"g{i}",) if weights else ()
        params.append(Parameter(f"tau{i}", start, low / TAU_SPAN, high * TAU_SPAN, True,
                                (low, high), tied))  # fmt: skip
    return params


def _check_unknowns(kind: str, unknowns: Sequence[str], known: Known) -> None:
    for name in unknowns:
        if name not in UNKNOWNS[kind]:
            raise InputError(
                f"unknowns: {kind} data cannot fit {name!r}; choose from "
                f"{', '.join(UNKNOWNS[kind])}",
                "unknowns",
            )
    for name, what in (("prony", "the weights g_i"), ("tau", "the relaxation times tau_i")):
        if name in unknowns and known.prony is None:
            raise InputError(
                f"unknowns: {name!r} fits {what} of a given series (its number of terms); give "
                "prony (g1:tau1,...: the starting values)",
                "unknowns",
            )
    if not unknowns:
        raise InputError(f"unknowns: name at least one of {', '.join(UNKNOWNS[kind])}", "unknowns")


def build_model(
    known: Known,
    data: Measurement,
    unknowns: Sequence[str],
    starts: Mapping[str, float] | None = None,
) -> Model:
    """The forward model of ``data.kind`` with the parameters of ``unknowns``, started from
    ``starts`` (fitted name -> natural value; a previous optimum) where given."""
    kind = data.kind
    _check_unknowns(kind, unknowns, known)
    params = tuple(
        dataclasses.replace(p, start=min(max(starts[p.name], p.low), p.high))
        if starts and p.name in starts else p
        for p in _parameters(known, data, unknowns)
    )  # fmt: skip
    viscous = known.prony is not None
    impact = (
        "viscoelastic quasi-static impact (Lee-Radok, Ting; the striker's compliance added to "
        "the glassy half-space's)"
        if viscous
        else "quasi-static impact (Ateb functions)"
    )
    if kind == "indentation":
        law = contact_law(known.indenter, 1.0)  # P = E* times this law's force
        shape = law.force(data.columns["depth"])
        return Model(
            params, data.columns["force"], lambda f: all_values(known, f)["E_star"] * shape,
            False, "N", _contact_words(known.indenter),
        )  # fmt: skip
    if kind == "force-history":
        time = data.columns["time"]
        return Model(
            params, data.columns["force"],
            lambda f: force_history(known, all_values(known, f), time), False, "N",
            f"{impact}, force history with time offset and baseline",
        )  # fmt: skip
    observed = [data.columns[n] for n in ("restitution", "contact_time", "resilience")
                if n in data.columns]  # fmt: skip
    return Model(
        params, np.concatenate(observed), _rebound_predict(known, data), True, "1 (relative)",
        f"{impact}: restitution e and contact time per drop velocity (resilience e^2)",
        trades(known, data),
    )  # fmt: skip


def trades(known: Known, data: Measurement) -> tuple[frozenset[str], ...]:
    """The parameters on each exact null direction of rebound or resilience data: the impact
    sees the mass and E* only as M / E* (M x'' = -E* f(x)); without measured contact times, a
    power law's relaxation times only as t_c / tau_i, t_c ~ (M / E*)^(n/(2n+1)), so E* (or
    the mass) and all the tau_i trade too (ln tau_i -= n/(2n+1) per unit of ln E*)."""
    found = [frozenset({"E_star", "mass"})]
    power_law = getattr(known.indenter, "exponent", None) is not None
    if "contact_time" not in data.columns and power_law and known.prony is not None:
        times = {f"tau{i}" for i in range(1, len(known.prony.times) + 1)}
        found += [frozenset({"E_star", *times}), frozenset({"mass", *times})]
    return tuple(found)
