"""Exact references for a rigid striker on an incompressible viscoelastic half-space.

The half-space relaxes in shear by a Prony series on its instantaneous (glassy) modulus
(Abaqus' convention), its bulk response elastic and nu = 1/2, so the contact modulus relaxes as
E*(t) = E*_0 psi(t), psi(t) = g_inf + sum_i g_i exp(-t/tau_i), g_inf = 1 - sum_i g_i > 0.
Loading follows Lee & Radok (1960), unloading Ting (1966), for a power law or any axisymmetric
profile (:func:`elastic_shape`), with x and F piecewise linear in time (second-order error in
the spacing); pressed at a constant rate the response is the elastic one times
:func:`rate_factor`. The formulas: benchmarks/FEM_NOTES.md, "Moved from the docstrings",
theory/viscoelastic.py."""

from __future__ import annotations

import functools
import math
import re
import sys
from collections.abc import Callable
from dataclasses import dataclass, field
from numbers import Real

import numpy as np
from numpy.typing import ArrayLike
from scipy.optimize import brentq
from scipy.special import hyp1f1

from ..validation import InputError, NumericalFailureError, plain_float, validate_positive
from .contact import PowerLawContact
from .impact import ImpactResult, solve_impact
from .materials import RIGID, Material, effective_modulus
from .profile_impact import ProfileImpactResult, solve_profile_impact
from .sneddon import Indenter, SneddonContact, contact_law

Law = PowerLawContact | SneddonContact
"""An elastic contact law at the instantaneous modulus: the power law's or Sneddon's."""

__all__ = [
    "PronyFormError",
    "PronySeries",
    "RateContact",
    "ViscoelasticImpact",
    "constant_rate_contact",
    "constant_rate_pressure",
    "elastic_impact",
    "elastic_shape",
    "hereditary",
    "indentation_force",
    "limit_impacts",
    "rate_factor",
    "rigid_impact",
    "viscoelastic_impact",
]

_TERM = re.compile(r"^\s*([^:,\s]+)\s*:\s*([^:,\s]+)\s*$")


def _number(where: str, text: str) -> float:
    """``text`` as a float, or InputError naming the Prony series' term ``where``."""
    try:
        return plain_float(text)
    except ValueError:
        raise InputError(f"prony {where} must be a number, got {text!r}", "prony") from None


def _check_term(i: int, g: object, tau: object, typed: tuple[str, str] | None = None) -> None:
    """Refuse term ``i`` of a Prony series unless 0 <= g < 1 and 0 < tau < inf (s); the
    message shows the ``typed`` text (g, tau) where the series was written (1e999, not inf)."""
    shown_g, shown_tau = typed or (repr(g), repr(tau))
    if isinstance(g, bool) or not (isinstance(g, Real) and 0.0 <= g < 1.0):
        raise InputError(f"prony weight g{i} must lie in [0, 1), got {shown_g}", "prony")
    if isinstance(tau, bool) or not (
        isinstance(tau, Real) and sys.float_info.min <= tau < math.inf
    ):
        raise InputError(
            f"prony time tau{i} must be a finite number > 0 s, got {shown_tau}", "prony"
        )


class PronyFormError(InputError):
    """A Prony series' text not written in any of its forms: ``got`` is that text (the
    caller says the forms it takes, once)."""

    def __init__(self, message: str, got: str) -> None:
        super().__init__(message, "prony")
        self.got = got


@dataclass(frozen=True)
class PronySeries:
    """Shear relaxation G(t) = G0 [1 - sum_i g_i (1 - exp(-t/tau_i))] on the glassy G0.

    Parameters
    ----------
    weights : tuple of float
        g_i >= 0, dimensionless, with sum_i g_i < 1 (the relaxed modulus G0 g_inf stays > 0).
    times : tuple of float
        Relaxation times tau_i > 0 in s, one per weight.

    Raises
    ------
    shtaerman.validation.InputError
        If a value lies outside its range or the lengths differ.
    """

    weights: tuple[float, ...]
    times: tuple[float, ...]

    def __post_init__(self) -> None:
        weights, times = tuple(self.weights), tuple(self.times)
        if len(weights) != len(times):
            raise InputError(
                f"prony needs one relaxation time per weight, got {len(weights)} weights "
                f"and {len(times)} times",
                "prony",
            )
        for i, (g, tau) in enumerate(zip(weights, times, strict=True), start=1):
            _check_term(i, g, tau)
        if not math.fsum(weights) < 1.0:
            raise InputError(
                f"prony weights must sum to less than 1 (relaxed modulus > 0), got "
                f"sum g_i = {math.fsum(weights)!r}",
                "prony",
            )
        object.__setattr__(self, "weights", tuple(float(g) for g in weights))
        object.__setattr__(self, "times", tuple(float(tau) for tau in times))

    def text(self) -> str:
        """The series as ``g1:tau1,g2:tau2,...`` (tau in s; :meth:`parse` reads it back)."""
        return ",".join(f"{g:g}:{tau:g}" for g, tau in zip(self.weights, self.times, strict=True))

    @classmethod
    def parse(cls, text: str) -> PronySeries:
        """The series written ``g1:tau1,g2:tau2,...`` (tau in s), e.g. ``0.5:1e-3``."""
        pairs = [_TERM.match(term) for term in str(text).split(",")]
        if any(pair is None for pair in pairs):
            raise PronyFormError(
                f"prony must be written g1:tau1,g2:tau2,... (tau in s), got {text!r}", str(text)
            )
        weights = tuple(_number(f"weight g{i}", p[1]) for i, p in enumerate(pairs, 1))  # type: ignore[index]
        times = tuple(_number(f"time tau{i}", p[2]) for i, p in enumerate(pairs, 1))  # type: ignore[index]
        for i, (g, tau, pair) in enumerate(zip(weights, times, pairs, strict=True), start=1):
            _check_term(i, g, tau, typed=pair.groups())  # type: ignore[union-attr]
        return cls(weights, times)

    @property
    def g_inf(self) -> float:
        """Relaxed fraction g_inf = 1 - sum_i g_i = G(inf)/G0."""
        return 1.0 - math.fsum(self.weights)

    def relaxation(self, time: ArrayLike) -> np.ndarray:
        """psi(t) = G(t)/G0 at times t >= 0 in s (1 at t = 0, g_inf as t -> inf)."""
        t = np.asarray(time, dtype=float)
        psi = np.full_like(t, self.g_inf)
        for g, tau in zip(self.weights, self.times, strict=True):
            psi = psi + g * np.exp(-t / tau)
        return psi

    def dynamic_modulus(self, frequency: ArrayLike) -> np.ndarray:
        """E*(omega)/E0 = g_inf + sum_i g_i i omega tau_i / (1 + i omega tau_i) at angular
        frequencies omega in rad/s: its real part the storage ratio E'/E0, its imaginary part
        the loss ratio E''/E0, their ratio tan delta (the same for G at a constant nu)."""
        w = np.asarray(frequency, dtype=float)
        ratio = np.full(w.shape, self.g_inf, dtype=complex)
        for g, tau in zip(self.weights, self.times, strict=True):
            ratio = ratio + g * (1j * w * tau) / (1.0 + 1j * w * tau)
        return ratio

    def scaled(self, factor: float) -> PronySeries:
        """The same weights with every tau_i multiplied by ``factor`` (> 0)."""
        factor = validate_positive("factor", factor)
        return PronySeries(self.weights, tuple(tau * factor for tau in self.times))


def elastic_shape(law: Law) -> tuple[float, Callable[[ArrayLike], np.ndarray]]:
    """beta0 and F of the elastic force P = beta0 F(x) at E*_0 (x in m): the power law's beta
    and x^q, or 1 and Sneddon's force of another profile (N)."""
    if isinstance(law, PowerLawContact):
        q = law.force_exponent
        return law.beta, lambda x: np.asarray(x, dtype=float) ** q
    return 1.0, lambda x: np.asarray(law.force(x), dtype=float)


def elastic_impact(mass: float, velocity: float, law: Law) -> ImpactResult | ProfileImpactResult:
    """The exact elastic impact on ``law``: Ateb's of the power law, Sneddon's quadrature."""
    if isinstance(law, PowerLawContact):
        return solve_impact(mass, velocity, law)
    return solve_profile_impact(mass, velocity, law)


def rigid_impact(
    indenter: Indenter, half_space: Material, mass: float, velocity: float
) -> Callable[[], ImpactResult | ProfileImpactResult]:
    """:func:`elastic_impact` of the rigid ``indenter`` (``mass`` kg at ``velocity`` m/s) on
    ``half_space`` (E* = E2 / (1 - nu2^2)), solved at the first call and kept: one solve
    for a case's checks, its radiation estimate and its run."""

    @functools.cache
    def solved() -> ImpactResult | ProfileImpactResult:
        law = contact_law(indenter, effective_modulus(RIGID, half_space))
        return elastic_impact(mass, velocity, law)

    return solved


class _Memory:
    """The loading history: x and F = x^q linear in time between nodes t_0 < ... < t_m, with the
    kernels H_i, K_i at each node; evaluates the unloading quantities at any t1 in [t_0, t_m]."""

    def __init__(self, prony: PronySeries, beta: float) -> None:
        self.g = np.asarray(prony.weights, dtype=float)
        self.tau = np.asarray(prony.times, dtype=float)
        self.g_inf = prony.g_inf
        self.beta = beta
        self.nodes: list[tuple[float, float, float, np.ndarray, np.ndarray]] = []

    def append(self, t: float, x: float, F: float, H: np.ndarray, K: np.ndarray) -> None:
        """Record node (t, x, F, H_i, K_i) of the loading phase."""
        self.nodes.append((t, x, F, H, K))

    def freeze(self) -> None:
        """End of loading: the nodes and the pieces' slopes, in plain floats (evaluate() runs
        ~10 times a step on a few terms: numpy's per-call overhead on arrays this small was
        95 % of its cost)."""
        t, x, F, H, K = (np.array(column) for column in zip(*self.nodes, strict=True))
        step = np.diff(t)
        self.t, self.last = t.tolist(), len(t) - 1
        self._terms = list(zip(self.g.tolist(), self.tau.tolist(), strict=True))
        H, K = H.reshape(len(t), -1).tolist(), K.reshape(len(t), -1).tolist()
        self._nodes = list(zip(self.t, x.tolist(), F.tolist(), H, K, strict=True))
        self._rates = list(zip((np.diff(x) / step).tolist(), (np.diff(F) / step).tolist(),
                               strict=True))  # fmt: skip

    def evaluate(self, u: float, t: float, piece: int) -> tuple[float, float, float]:
        """x(u) in m, E(u) = sum_i g_i e^{-(t-u)/tau_i} H_i(u) in m and the unloading force
        P(u) = beta0 [g_inf F(u) + sum_i g_i e^{-(t-u)/tau_i} K_i(u)] in N, for u in piece
        [t_k, t_k+1] (k = ``piece``) and a later time t in s."""
        k = min(max(piece, 0), self.last - 1)
        t_k, x_k, F_k, H_k, K_k = self._nodes[k]
        x_rate, F_rate = self._rates[k]
        lag = u - t_k
        E_u = held = 0.0
        for (g, tau), H, K in zip(self._terms, H_k, K_k, strict=True):
            decay_node = math.exp(-(t - t_k) / tau)
            ramp = math.exp(-(t - u) / tau) * -math.expm1(-lag / tau) * tau
            E_u += g * (decay_node * H + x_rate * ramp)
            held += g * (decay_node * K + F_rate * ramp)
        force = self.beta * (self.g_inf * (F_k + F_rate * lag) + held)
        return x_k + x_rate * lag, E_u, force

    def edge_time(
        self, residual: Callable[[float, float, float], float], t: float, start: int
    ) -> tuple[float, int] | None:
        """The instant t1 in [t_0, t_m] where ``residual(x, E, P)`` (decreasing in t1) vanishes,
        and its piece; None when it is <= 0 already at t_0 (the contact is lost)."""

        def at(u: float, k: int) -> float:
            return residual(*self.evaluate(u, t, k))

        if at(self.t[0], 0) <= 0.0:
            return None
        j = min(max(start + 1, 1), self.last)
        while j < self.last and at(self.t[j], j - 1) > 0.0:
            j += 1
        if at(self.t[j], j - 1) > 0.0:
            return float(self.t[j]), j - 1
        while j > 1 and at(self.t[j - 1], j - 1) <= 0.0:
            j -= 1
        k = j - 1
        lo, hi = float(self.t[k]), float(self.t[j])
        root = brentq(lambda u: at(u, k), lo, hi, xtol=1e-15 * hi, rtol=8.9e-16)
        return float(root), k


def _validate_history(times: ArrayLike, depth: ArrayLike) -> tuple[np.ndarray, np.ndarray, int]:
    """Times, depths and the index of the (last) peak of one loading-unloading history."""
    t = np.atleast_1d(np.asarray(times, dtype=float))
    x = np.atleast_1d(np.asarray(depth, dtype=float))
    if t.ndim != 1 or t.shape != x.shape or t.size < 2:
        raise InputError("times and depth must be 1-D arrays of the same length >= 2", "times")
    if not (np.all(np.isfinite(t)) and np.all(np.diff(t) > 0)):
        raise InputError("times must be finite and strictly increasing (s)", "times")
    if not (np.all(np.isfinite(x)) and np.all(x >= 0) and x[0] == 0.0):
        raise InputError("depth must be finite, >= 0 m, and 0 at the first instant", "depth")
    peak = int(x.size - 1 - np.argmax(x[::-1]))
    if np.any(np.diff(x[: peak + 1]) < 0) or np.any(np.diff(x[peak:]) > 0):
        raise InputError(
            "depth must rise to one maximum and then fall (one loading, one unloading)", "depth"
        )
    if x[peak] == 0.0:
        raise InputError("depth must rise above 0 m at some instant", "depth")
    return t, x, peak


def indentation_force(
    times: ArrayLike, depth: ArrayLike, law: Law, prony: PronySeries
) -> tuple[np.ndarray, np.ndarray]:
    """Force and contact radius for a prescribed depth history: Lee-Radok, then Ting.

    x(t) and F = x^q are each taken linear in time between the instants given, and the kernels
    follow exactly over each piece (benchmarks/FEM_NOTES.md): the error is that of the
    interpolation, second order in the spacing for a smooth history, O(h^q) as the contact
    closes (t1 in the first pieces, where F ~ t^q).

    Parameters
    ----------
    times : array_like
        Instants t in s, strictly increasing, the first one at first touch.
    depth : array_like
        Depth x(t) in m at those instants: 0 at the first, rising to one maximum, then falling.
    law : PowerLawContact or SneddonContact
        The elastic contact at the instantaneous modulus E*_0 (gives beta0, F and a(x)).
    prony : PronySeries
        The half-space's shear relaxation.

    Returns
    -------
    force, contact_radius : ndarray
        P(t) in N and a(t) in m (both 0 once the contact is lost while unloading).
    """
    t, x, peak = _validate_history(times, depth)
    beta, shape = elastic_shape(law)
    memory = _Memory(prony, beta)
    g, tau = memory.g, memory.tau
    F = shape(x)
    H, K = np.zeros_like(g), np.zeros_like(g)
    force, radius = np.zeros_like(x), np.zeros_like(x)
    piece, lost = peak - 1, False
    for n in range(t.size):
        if n:
            h = t[n] - t[n - 1]
            decay, ramp = np.exp(-h / tau), -np.expm1(-h / tau) * tau / h
            H = decay * H + ramp * (x[n] - x[n - 1])
            K = decay * K + ramp * (F[n] - F[n - 1])
        if n <= peak:
            memory.append(t[n], x[n], F[n], H, K)
            force[n] = beta * (memory.g_inf * F[n] + float(g @ K))
            radius[n] = float(law.contact_radius(x[n]))
            continue
        if n == peak + 1:
            memory.freeze()
        total = memory.g_inf * x[n] + float(g @ H)
        found = (
            None
            if lost
            else memory.edge_time(
                lambda x_u, E_u, _P, total=total: total - memory.g_inf * x_u - E_u, t[n], piece
            )
        )
        if found is None:
            lost = True
            continue
        t1, piece = found
        x1, _, force[n] = memory.evaluate(t1, t[n], piece)
        radius[n] = float(law.contact_radius(x1))
    return force, radius


def rate_factor(exponent: float, time: ArrayLike, prony: PronySeries) -> np.ndarray:
    """R_m(t) = g_inf + sum_i g_i M(1, m + 1, -t/tau_i): a response growing as x^m elastically,
    pressed at a constant rate, is its glassy value times R_m(t) (benchmarks/FEM_NOTES.md;
    exact while the contact grows, nu2 = 1/2).

    Parameters
    ----------
    exponent : float
        m > 0 (the force: q = 1 + 1/n; the central pressure: (n - 1)/n).
    time : array_like
        t >= 0 in s since first touch.
    prony : PronySeries

    Returns
    -------
    numpy.ndarray
        R_m(t), dimensionless: 1 at t = 0, falling towards g_inf.
    """
    t = np.asarray(time, dtype=float)
    factor = np.full_like(t, prony.g_inf)
    for g, tau in zip(prony.weights, prony.times, strict=True):
        with np.errstate(over="ignore"):  # tau -> 0: z = inf, M = 0
            z = t / tau
        factor = factor + g * _kummer(exponent, z)
    return factor


KUMMER_ASYMPTOTIC = 1e8
"""z beyond which M(1, m + 1, -z) is its asymptotic m/z (1 + (1 - m)/z) (relative error
< 1e-16; scipy's series fails near z = 1e300)."""


def _kummer(exponent: float, z: np.ndarray) -> np.ndarray:
    """M(1, m + 1, -z) for z >= 0 (inf included: 0)."""
    with np.errstate(divide="ignore", over="ignore", invalid="ignore"):
        far = exponent / z * (1.0 + (1.0 - exponent) / z)
        return np.where(z > KUMMER_ASYMPTOTIC, far, hyp1f1(1.0, exponent + 1.0, -z))


def constant_rate_contact(
    depth: ArrayLike, rate: float, law: Law, prony: PronySeries
) -> dict[str, np.ndarray]:
    """Lee-Radok's contact of the rigid power-law indenter pressed at ``rate`` m/s, x = V t.

    Parameters
    ----------
    depth : array_like
        Depths x >= 0 in m (reached at t = x / V).
    rate : float
        Pressing speed V > 0 in m/s.
    law : PowerLawContact
        The elastic contact at the instantaneous modulus E*_0 (nu2 = 1/2).
    prony : PronySeries

    Returns
    -------
    dict of str to numpy.ndarray
        ``force`` P = beta0 x^q R_q(x/V) in N, ``contact_radius`` a(x) in m (the elastic
        geometry's, Lee-Radok) and ``central_pressure`` p(0) = p0_el(x) R_m(x/V) in Pa,
        m = (n - 1)/n.
    """
    rate = validate_positive("rate", rate, "m/s")
    x = np.asarray(depth, dtype=float)
    if isinstance(law, SneddonContact):
        return _profile_rate_contact(x, rate, law, prony)
    t, n = x / rate, law.indenter.exponent
    return {
        "force": law.force(x) * rate_factor(law.force_exponent, t, prony),
        "contact_radius": np.asarray(law.contact_radius(x), dtype=float),
        "central_pressure": law.central_pressure(x) * rate_factor((n - 1.0) / n, t, prony),
    }


RATE_STEPS = 2000
"""Equal steps in the contact radius of a profile's constant-rate contact (:func:`hereditary`
of its elastic force and central pressure, second order: a sphere's force within 2e-7 of the
quadrature of tests/test_viscoelastic_profile.py)."""


def _profile_rate_contact(
    x: np.ndarray, rate: float, law: SneddonContact, prony: PronySeries
) -> dict[str, np.ndarray]:
    """Lee-Radok's contact of a sphere or a table (Sneddon's ``law`` at E*_0) pressed at
    ``rate`` m/s to the depths ``x`` (m): the hereditary integrals of its elastic force and
    central pressure on :data:`RATE_STEPS` equal steps of the contact radius (denser in time
    near first touch; Sneddon's closed forms in the radius, no root per instant) and the
    depths' own radii."""
    radii = np.asarray(law.contact_radius(x), dtype=float)
    deepest = float(np.max(radii, initial=0.0))
    if deepest <= 0.0:
        zero = np.zeros_like(x)
        return {"force": zero, "contact_radius": zero, "central_pressure": zero}
    grid = np.union1d(np.linspace(0.0, deepest, RATE_STEPS + 1), radii)
    elastic = np.zeros((grid.size, 2))
    elastic[1:, 0] = law.force_at_radius(grid[1:])
    elastic[1:, 1] = law.central_pressure_at_radius(grid[1:])
    times = np.asarray(law.depth(grid), dtype=float) / rate
    response = hereditary(times, elastic, prony)[np.searchsorted(grid, radii)]
    return {
        "force": response[..., 0],
        "contact_radius": radii,
        "central_pressure": response[..., 1],
    }


def hereditary(times: ArrayLike, elastic: ArrayLike, prony: PronySeries) -> np.ndarray:
    """Int_0^t psi(t - s) dR(s) at each instant, R the glassy (elastic) response taken linear in
    time between the instants (exact kernels over each piece: second order in the spacing).

    Parameters
    ----------
    times : array_like
        Instants in s, increasing, the first at first touch.
    elastic : array_like
        R at those instants (first axis: time; any unit, 0 at the first instant).
    prony : PronySeries

    Returns
    -------
    numpy.ndarray
        The viscoelastic response, the shape of ``elastic``.
    """
    t, values = np.asarray(times, dtype=float), np.asarray(elastic, dtype=float)
    g, tau = np.asarray(prony.weights), np.asarray(prony.times)
    kernels = np.zeros((g.size, *values.shape[1:]))
    out = np.empty_like(values)
    out[0] = values[0]
    for k in range(1, t.size):
        h = t[k] - t[k - 1]
        decay, ramp = np.exp(-h / tau), -np.expm1(-h / tau) * tau / h
        change = values[k] - values[k - 1]
        kernels = decay.reshape(-1, *[1] * change.ndim) * kernels
        kernels = kernels + np.multiply.outer(ramp, change)
        out[k] = prony.g_inf * values[k] + np.tensordot(g, kernels, axes=1)
    return out


PROFILE_STEPS = 400
"""Time steps of :func:`constant_rate_pressure`: its profiles' relative L2 error is about 4e-5
(the paper's indenter, g = 0.5, against 4000 steps)."""


def constant_rate_pressure(
    radius: ArrayLike, depths: ArrayLike, rate: float, law: Law, prony: PronySeries
) -> np.ndarray:
    """Lee-Radok's pressure profiles p(r) in Pa, pressed at ``rate`` m/s, at each of ``depths``
    (m, increasing): the hereditary integral of the elastic p(r, V s) (:func:`hereditary`, on
    :data:`PROFILE_STEPS` steps and the depths' instants; the contact edge passing a radius
    costs O(h^1.5) there). Shape (depths, radii)."""
    rate = validate_positive("rate", rate, "m/s")
    r, x = np.asarray(radius, dtype=float), np.asarray(depths, dtype=float)
    times = np.union1d(np.linspace(0.0, x[-1] / rate, PROFILE_STEPS + 1), x / rate)
    if isinstance(law, SneddonContact):  # no self-similarity: each instant's own profile
        elastic = np.zeros((times.size, r.size))
        elastic[1:] = [law.pressure(r, rate * t) for t in times[1:]]
        return hereditary(times, elastic, prony)[np.searchsorted(times, x / rate)]
    # self-similar: p(r, x) = (x/X)^((n-1)/n) p(r (X/x)^(1/n), X), one call for every instant
    n, deepest = law.indenter.exponent, float(x[-1])
    scale = np.maximum(rate * times, 1e-300) / deepest
    elastic = law.pressure(np.outer(scale ** (-1.0 / n), r), deepest)
    elastic *= scale[:, None] ** ((n - 1.0) / n)
    elastic[0] = 0.0
    profiles = hereditary(times, elastic, prony)
    return profiles[np.searchsorted(times, x / rate)]


@dataclass(frozen=True)
class RateContact:
    """Lee-Radok's contact curve pressed at a constant rate, in the form of
    :class:`~shtaerman.theory.contact.PowerLawContact` (the FEM contact curve's reference).

    Its :attr:`force_exponent` is the elastic law's q, and its :attr:`beta` (N m^-q) the power
    law with that q fitted to its force at ``depths`` (the curve's depths), as the FEM curve
    is fitted: beta / beta0 is then the geometric mean of the force ratios P / (beta0 x^q),
    between the smallest and the largest. The force, radius and pressures are exact.

    Parameters
    ----------
    law : PowerLawContact or SneddonContact
        The elastic contact at the instantaneous modulus E*_0 (nu2 = 1/2).
    prony : PronySeries
    rate : float
        Pressing speed V in m/s (x = V t).
    depths : tuple of float
        The curve's depths in m, increasing.
    """

    law: Law
    prony: PronySeries
    rate: float
    depths: tuple[float, ...]

    @property
    def indenter(self) -> Indenter:
        """The striker's profile (z = A r^n, a sphere or a table)."""
        return self.law.indenter

    @property
    def modulus(self) -> float:
        """The instantaneous E*_0 in Pa."""
        return self.law.modulus

    @property
    def force_exponent(self) -> float:
        """q of the elastic law at E*_0 ((n + 1)/n; a profile's at its tip), which :attr:`beta`
        holds: the curve itself is no power law (its free fit is the study's)."""
        return self.law.force_exponent

    @property
    def beta(self) -> float:
        """beta in N m^-q, q = :attr:`force_exponent`: the exact forces at the depths fitted
        as the FEM's (least squares of log P - q log x)."""
        x = np.asarray(self.depths)
        return float(np.exp(np.mean(np.log(self.force(x)) - self.force_exponent * np.log(x))))

    @property
    def central_to_mean_ratio(self) -> float:
        """p(0)/p_avg at the deepest depth."""
        deepest = self.depths[-1]
        return float(self.central_pressure(deepest) / self.mean_pressure(deepest))

    def _at(self, depth: ArrayLike, key: str) -> np.ndarray:
        """:func:`constant_rate_contact`'s ``key`` at ``depth``, the last depths' kept: a row
        of a step table asks for the force, the radius and the central pressure in turn, each
        a hereditary integral on a profile's 2000 steps (the same numbers, once)."""
        x = np.asarray(depth, dtype=float)
        asked = (x.shape, x.tobytes())
        kept = self.__dict__.get("_last")
        if kept is None or kept[0] != asked:
            kept = (asked, constant_rate_contact(x, self.rate, self.law, self.prony))
            self.__dict__["_last"] = kept  # frozen: not a field, not compared
        return kept[1][key].copy()

    def contact_radius(self, depth: ArrayLike) -> np.ndarray:
        """a(x) in m: the elastic geometry's."""
        return self._at(depth, "contact_radius")

    def force(self, depth: ArrayLike) -> np.ndarray:
        """P in N at depth x (m), reached at t = x / V."""
        return self._at(depth, "force")

    def central_pressure(self, depth: ArrayLike) -> np.ndarray:
        """p(0) in Pa at depth x (m)."""
        return self._at(depth, "central_pressure")

    def mean_pressure(self, depth: ArrayLike) -> np.ndarray:
        """P / (pi a^2) in Pa at depth x (m)."""
        return self.force(depth) / (math.pi * self.contact_radius(depth) ** 2)

    def pressure(self, radius: ArrayLike, depth: float) -> np.ndarray:
        """p(r) in Pa at depth x (m) (:func:`constant_rate_pressure`)."""
        return constant_rate_pressure(radius, [depth], self.rate, self.law, self.prony)[0]


@dataclass(frozen=True)
class ViscoelasticImpact:
    """The quasi-static impact of a rigid striker on the viscoelastic half-space (SI units).

    Integrated by the trapezoidal (average-acceleration Newmark) rule, second order in the step;
    ``history`` holds the steps up to the one in which the contact is lost.
    """

    mass: float
    """Striker mass M in kg."""
    velocity: float
    """Approach velocity at first touch v0 in m/s."""
    x_max: float
    """Maximum approach in m."""
    P_max: float
    """Maximum force in N (reached before x_max: the force relaxes while x still grows)."""
    t_x_max: float
    """Time of maximum approach in s."""
    t_contact: float
    """Duration of the contact in s (first touch to P = 0)."""
    v_out: float
    """Approach velocity after separation in m/s (negative: the striker rebounds)."""
    restitution: float
    """e = -v_out / v0."""
    energy_lost: float
    """Energy the striker leaves in the half-space, M v0^2 (1 - e^2) / 2, in J."""
    work: float
    """Work of the contact force on the surface, the loop integral of P dx, in J."""
    energy_balance_error: float
    """|work - energy_lost| / (M v0^2 / 2)."""
    time_step: float
    """Step h in s."""
    history: dict[str, np.ndarray] = field(repr=False, compare=False)
    """Arrays t (s), x (m), v (m/s), P (N), a (m) over the steps."""

    def to_dict(self) -> dict[str, float]:
        """The scalar results by name."""
        names = (
            "mass", "velocity", "x_max", "P_max", "t_x_max", "t_contact", "v_out",
            "restitution", "energy_lost", "work", "energy_balance_error", "time_step",
        )  # fmt: skip
        return {name: float(getattr(self, name)) for name in names}


@dataclass
class _State:
    """One instant of the impact: time, depth, velocity, force and the kernels H_i, K_i."""

    t: float
    x: float
    v: float
    P: float
    H: np.ndarray
    K: np.ndarray
    a: float = 0.0
    F: float = 0.0
    p: float = 0.0


@dataclass(frozen=True)
class _Curve:
    """The elastic curve along the loading step's unknown p: the power law's p is the depth x,
    another profile's the contact radius a, where Sneddon's depth and force are explicit (at
    a given x each needs a root solve for a: 5x the cost of the whole step)."""

    law: Law

    def locate(self, depth: float) -> float:
        """p at a depth in m."""
        power = isinstance(self.law, PowerLawContact)
        return depth if power else float(self.law.contact_radius(depth))

    def along(self, p: float) -> tuple[float, float]:
        """The depth x in m and the force shape F (P = beta0 F, :func:`elastic_shape`) at p."""
        if isinstance(self.law, PowerLawContact):
            return p, float(np.asarray(p, dtype=float) ** self.law.force_exponent)
        return float(self.law.depth(p)), float(self.law.force_at_radius(p))

    def radius(self, p: float) -> float:
        """The contact radius in m at p."""
        power = isinstance(self.law, PowerLawContact)
        return float(self.law.contact_radius(p)) if power else p


def _loading_step(s: _State, h: float, mass: float, curve: _Curve, memory: _Memory
                  ) -> _State | None:  # fmt: skip
    """The next state while the contact grows (Lee-Radok), or None if x would decrease."""
    g, tau, beta = memory.g, memory.tau, memory.beta
    decay, ramp = np.exp(-h / tau), -np.expm1(-h / tau) * tau / h
    rest = float(g @ (decay * s.K - ramp * s.F))
    stiff = memory.g_inf + float(g @ ramp)

    def residual(p: float) -> float:
        x, F = curve.along(p)
        return x - s.x - h * s.v + h * h / (4.0 * mass) * (s.P + beta * (stiff * F + rest))

    if residual(s.p) > 0.0:
        return None
    upper = curve.locate(s.x + h * s.v)
    p = upper if residual(upper) <= 0.0 else brentq(residual, s.p, upper, xtol=1e-15 * upper)
    x, F = curve.along(p)
    P = beta * (stiff * F + rest)
    return _State(
        t=s.t + h,
        x=x,
        v=s.v - h / (2.0 * mass) * (s.P + P),
        P=P,
        H=decay * s.H + ramp * (x - s.x),
        K=decay * s.K + ramp * (F - s.F),
        a=curve.radius(p),
        F=F,
        p=p,
    )


def _unloading_step(
    s: _State, h: float, mass: float, law: Law, memory: _Memory, piece: int
) -> tuple[_State, int | None]:
    """The next state while the contact shrinks (Ting) and the piece of t1; piece None: the
    contact is lost within the step (P = 0 at its end)."""
    g, tau = memory.g, memory.tau
    decay, ramp = np.exp(-h / tau), -np.expm1(-h / tau) * tau / h
    base = float(g @ (decay * s.H - ramp * s.x))
    stiff = memory.g_inf + float(g @ ramp)
    free = s.x + h * s.v - h * h / (4.0 * mass) * s.P

    def residual(x_u: float, E_u: float, P_u: float) -> float:
        # Newmark's x_{n+1} for the force P(t1) minus the x_{n+1} making Phi(t1, t_{n+1}) = 0
        return free - h * h / (4.0 * mass) * P_u - (memory.g_inf * x_u + E_u - base) / stiff

    t = s.t + h
    found = memory.edge_time(residual, t, piece)
    if found is None:
        x, P, a, piece_next = free, 0.0, 0.0, None
    else:
        t1, piece_next = found
        x1, _, P = memory.evaluate(t1, t, piece_next)
        x, a = free - h * h / (4.0 * mass) * P, float(law.contact_radius(x1))
    state = _State(t, x, s.v - h / (2.0 * mass) * (s.P + P), P, decay * s.H + ramp * (x - s.x),
                   s.K, a)  # fmt: skip
    return state, piece_next


MAX_DURATION = 10.0
"""The integration gives up after this many relaxed impact durations (the elastic impact at
g_inf E*_0, the longest of the two limits) without separation."""


def _integrate(mass: float, velocity: float, law: Law, prony: PronySeries, h: float,
               limit: int) -> tuple[list[_State], float]:  # fmt: skip
    """All states from first touch to the step that loses contact, and the separation time."""
    memory, curve = _Memory(prony, elastic_shape(law)[0]), _Curve(law)
    zero = np.zeros(len(prony.weights))
    states = [_State(0.0, 0.0, velocity, 0.0, zero, zero)]
    memory.append(0.0, 0.0, 0.0, zero, zero)
    loading, piece = True, 0
    while len(states) <= limit:
        s = states[-1]
        if loading:
            nxt = _loading_step(s, h, mass, curve, memory)
            if nxt is not None:
                states.append(nxt)
                memory.append(nxt.t, nxt.x, nxt.F, nxt.H, nxt.K)
                continue
            loading, piece = False, len(states) - 2
            memory.freeze()
        nxt, piece = _unloading_step(s, h, mass, law, memory, piece)
        states.append(nxt)
        if piece is None:  # Phi(0, t) = g_inf x + sum g_i H_i crossed 0: interpolate linearly
            before = memory.g_inf * s.x + float(memory.g @ s.H)
            after = memory.g_inf * nxt.x + float(memory.g @ nxt.H)
            return states, s.t + h * before / (before - after)
    raise NumericalFailureError(
        f"no separation within {limit} steps of {h:g} s; report this case (mass, velocity, law "
        f"and prony)"
    )


def _peak_depth(t: np.ndarray, x: np.ndarray, v: np.ndarray) -> tuple[float, float]:
    """Maximum of the trapezoidal rule's own parabola over the step where v changes sign."""
    j = int(np.flatnonzero(v > 0.0)[-1])
    if j + 1 >= v.size:
        return float(x[j]), float(t[j])
    h = t[j + 1] - t[j]
    accel = (v[j + 1] - v[j]) / h
    lag = min(-v[j] / accel, h)
    return float(x[j] + v[j] * lag + 0.5 * accel * lag * lag), float(t[j] + lag)


def _peak_force(t: np.ndarray, P: np.ndarray) -> float:
    """Maximum of the parabola through the largest sampled force and its neighbours."""
    j = int(np.argmax(P))
    if j == 0 or j + 1 >= P.size:
        return float(P[j])
    low, mid, high = P[j - 1], P[j], P[j + 1]
    curvature = low - 2.0 * mid + high
    if curvature >= 0.0:
        return float(mid)
    return float(mid - (high - low) ** 2 / (8.0 * curvature))


def viscoelastic_impact(
    mass: float,
    velocity: float,
    law: Law,
    prony: PronySeries,
    *,
    steps: int = 2000,
    longest: float | None = None,
    t_c: float | None = None,
) -> ViscoelasticImpact:
    """The quasi-static impact M x'' = -P(t), x(0) = 0, x'(0) = v0, on the viscoelastic
    half-space: Lee-Radok while x grows, Ting while it falls, until P = 0.

    Parameters
    ----------
    mass : float
        Striker mass M in kg (> 0).
    velocity : float
        Approach velocity v0 in m/s (> 0).
    law : PowerLawContact or SneddonContact
        The elastic contact of the rigid striker at the instantaneous modulus E*_0 = E2/(1 -
        nu2^2), nu2 = 1/2 (beta0, F and a(x); a sphere's or a table's by Sneddon).
    prony : PronySeries
        The half-space's shear relaxation.
    steps : int
        Time steps per glassy compression time t_c (the elastic impact at E*_0), >= 20; the
        errors fall as steps^-2.
    longest : float, optional
        Contact time in s after which the integration gives up (NumericalFailureError); by
        default :data:`MAX_DURATION` relaxed impact durations.
    t_c : float, optional
        The glassy t_c in s (:func:`elastic_impact` on ``law``) when already solved; solved
        here otherwise.

    Returns
    -------
    ViscoelasticImpact
    """
    mass = validate_positive("mass", mass, "kg")
    velocity = validate_positive("velocity", velocity, "m/s")
    if isinstance(steps, bool) or not isinstance(steps, int | np.integer) or steps < 20:
        raise InputError(f"steps must be an integer >= 20 per t_c, got {steps!r}", "steps")
    if t_c is None:
        t_c = elastic_impact(mass, velocity, law).t_c
    h = validate_positive("t_c", t_c, "s") / int(steps)
    # in t_c; a profile's at its tip's q (the relaxed impact is shallower: nearer the tip)
    relaxed_duration = 2.0 * prony.g_inf ** (-1.0 / (law.force_exponent + 1.0))
    limit = math.ceil(MAX_DURATION * relaxed_duration * steps)
    if longest is not None:
        limit = min(limit, math.ceil(validate_positive("longest", longest, "s") / h))
    states, t_contact = _integrate(mass, velocity, law, prony, h, limit)
    t, x, v, P, a = (np.array([getattr(s, k) for s in states]) for k in ("t", "x", "v", "P", "a"))
    x_max, t_x_max = _peak_depth(t, x, v)
    kinetic = 0.5 * mass * velocity**2
    energy_lost = 0.5 * mass * (velocity**2 - v[-1] ** 2)
    work = float(np.sum(0.5 * (P[1:] + P[:-1]) * np.diff(x)))
    return ViscoelasticImpact(
        mass=mass,
        velocity=velocity,
        x_max=x_max,
        P_max=_peak_force(t, P),
        t_x_max=t_x_max,
        t_contact=float(t_contact),
        v_out=float(v[-1]),
        restitution=float(-v[-1] / velocity),
        energy_lost=float(energy_lost),
        work=work,
        energy_balance_error=abs(work - energy_lost) / kinetic,
        time_step=h,
        history={"t": t, "x": x, "v": v, "P": P, "a": a},
    )


def limit_impacts(
    mass: float, velocity: float, law: Law, prony: PronySeries
) -> tuple[ImpactResult | ProfileImpactResult, ImpactResult | ProfileImpactResult]:
    """The exact elastic impacts of the two limits: glassy (tau -> inf, modulus E*_0) and
    relaxed (tau -> 0, modulus g_inf E*_0); both rebound with e = 1."""
    relaxed = contact_law(law.indenter, law.modulus * prony.g_inf)
    return elastic_impact(mass, velocity, law), elastic_impact(mass, velocity, relaxed)
