"""Quasi-static impact M x'' = -beta x^q, x(0) = 0, x'(0) = v0, solved exactly with Ateb functions.

Hertz's assumptions (the paper, section 4): all kinetic energy goes into the local elastic
deformation, the static contact law holds at every instant. With eta = v0 t / x_c:

- x_c = ((q+1) M v0^2 / (2 beta))^(1/(q+1)),  P_c = beta x_c^q,
- t_c = I x_c / v0 with I = Int_0^1 d xi / sqrt(1 - xi^(q+1)) = B(1/(q+1), 1/2) / (q+1),
  t_y = 2 t_c (restitution mirrors compression),
- x(t) / x_c = Sa(q, 1, (q+1)/2 eta) and x'(t) / v0 = Ca(1, q, (q+1)/2 eta) over the whole impact
  0 <= eta <= 2 I, i.e. the first half-period of the Ateb pair (for q = 5/3 the paper's
  Sa(5/3, 1, 4/3 eta) in compression and Ca(5/3, 1, 4/3 zeta), zeta = eta - I, in restitution),
- impulse Int P dt = 2 M v0 exactly; the paper's Simpson estimate (its eq. 16) is
  (1/3) P_c t_c (1 + 4 Sa(q, 1, (q+1)/4 I)^q).

The contact radius a(t) and central pressure p(0, t) follow from x(t) through the contact law.
"""

from __future__ import annotations

import math
import sys
import warnings
from collections.abc import Callable
from dataclasses import dataclass, field
from typing import Protocol, TypeVar

import numpy as np
from numpy.typing import ArrayLike
from scipy.special import beta as beta_function

from ..validation import InputError, bound_text, caller_stacklevel, validate_positive
from .ateb import ateb_pair, ateb_sine

__all__ = [
    "QUASI_STATIC_VELOCITY_LIMIT",
    "ContactLaw",
    "ImpactHistory",
    "ImpactResult",
    "QuasiStaticValidityWarning",
    "check_impact_energy",
    "duration_integral",
    "history_times",
    "impact_in_floats",
    "log_approach",
    "representable",
    "solve_impact",
]

QUASI_STATIC_VELOCITY_LIMIT = 5.0
"""m/s; the paper (after Kil'chevskii and Nadutyi) bounds the quasi-static theory by 4-5 m/s."""


class QuasiStaticValidityWarning(UserWarning):
    """The impact velocity lies outside the quasi-static theory's stated validity."""


class ContactLaw(Protocol):
    """What the impact needs of a static contact law P = beta x^q (SI units)."""

    @property
    def beta(self) -> float: ...  # N m^-q

    @property
    def force_exponent(self) -> float: ...  # q

    def contact_radius(self, depth: ArrayLike) -> np.ndarray: ...  # m

    def central_pressure(self, depth: ArrayLike) -> np.ndarray: ...  # Pa

    @property
    def central_to_mean_ratio(self) -> float: ...  # p(0)/p_avg; inf: unbounded (n <= 1)


def duration_integral(force_exponent: float) -> float:
    """I = Int_0^1 d xi / sqrt(1 - xi^(q+1)) = B(1/(q+1), 1/2)/(q+1); t_c = I x_c / v0.

    I = 1.445927 for q = 5/3 (the paper's eq. 14) and 1.471638 for Hertz's q = 3/2.
    """
    q = validate_positive("force_exponent", force_exponent)
    return beta_function(1.0 / (q + 1.0), 0.5) / (q + 1.0)


@dataclass(frozen=True)
class ImpactHistory:
    """Time histories of one impact, each an array over the same instants (SI units)."""

    t: np.ndarray
    """Time in s, from first touch."""
    x: np.ndarray
    """Approach of the bodies' centres of mass (indentation depth) in m."""
    v: np.ndarray
    """Approach velocity dx/dt in m/s."""
    P: np.ndarray
    """Contact force in N."""
    a: np.ndarray
    """Contact radius in m."""
    p0: np.ndarray
    """Pressure at the centre of the contact in Pa."""

    def columns(self) -> dict[str, np.ndarray]:
        """The CSV columns t, x, P, a, p0 in that order."""
        return {"t": self.t, "x": self.x, "P": self.P, "a": self.a, "p0": self.p0}


@dataclass(frozen=True)
class ImpactResult:
    """Maxima and durations of a quasi-static impact, and its exact history on demand.

    All quantities in SI units; see the module docstring for the formulas.
    """

    mass: float
    """Striker mass M in kg."""
    velocity: float
    """Approach velocity at first touch v0 in m/s."""
    beta: float
    """Force-law coefficient in N m^-q."""
    force_exponent: float
    """Force-law exponent q."""
    x_c: float
    """Maximum approach in m."""
    P_c: float
    """Maximum force in N."""
    a_c: float
    """Maximum contact radius in m."""
    p_c: float
    """Maximum central pressure in Pa (``inf`` for exponents n <= 1)."""
    t_c: float
    """Duration of compression in s."""
    t_y: float
    """Duration of the whole impact in s."""
    impulse: float
    """Impulse of the contact force over the impact, 2 M v0, in N s."""
    impulse_simpson: float
    """The paper's Simpson estimate of the impulse, its eq. (16), in N s."""
    law: ContactLaw = field(repr=False, compare=False)

    def phase(self, time: ArrayLike) -> np.ndarray:
        """Ateb argument (q+1)/2 v0 t / x_c at times t in s."""
        eta = self.velocity * np.asarray(time, dtype=float) / self.x_c
        return (self.force_exponent + 1.0) / 2.0 * eta

    def history(self, points: int = 201, times: ArrayLike | None = None) -> ImpactHistory:
        """The exact histories over [0, t_y] (``points`` instants, both ends included).

        Parameters
        ----------
        points : int
            Number of equally spaced instants, >= 2; ignored when ``times`` is given.
        times : array_like, optional
            Instants in s, each within [0, t_y].
        """
        t = history_times(self.t_y, points, times)
        if times is None:  # equally spaced over [0, t_y]: restitution mirrors compression
            half = (t.size + 1) // 2
            x_half, v_half = self._state(t[:half])
            rest = slice(t.size - half - 1, None, -1) if t.size > half else slice(0, 0)
            x = np.concatenate([x_half, x_half[rest]])
            v = np.concatenate([v_half, -v_half[rest]])
        else:
            x, v = self._state(t)
        return ImpactHistory(t, x, v, self.beta * x**self.force_exponent, *self._geometry(x))

    def _state(self, t: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """Exact approach x in m and velocity x' in m/s at times t in [0, t_y] s."""
        sine, cosine = ateb_pair(self.force_exponent, 1.0, self.phase(t))
        x = self.x_c * np.clip(sine, 0.0, 1.0)
        x[t >= self.t_y] = 0.0
        return x, self.velocity * cosine

    def _geometry(self, x: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        with np.errstate(divide="ignore", invalid="ignore"):
            a = np.asarray(self.law.contact_radius(x), dtype=float)
            p0 = np.where(x > 0, self.law.central_pressure(x), 0.0)
        return a, p0

    def maxima(self) -> dict[str, float]:
        """The SI keys of ``shtaerman impact --json``."""
        names = ("beta", "x_c", "P_c", "a_c", "p_c", "t_c", "t_y", "impulse", "impulse_simpson")
        return {name: float(getattr(self, name)) for name in names}


def history_times(t_y: float, points: int, times: ArrayLike | None) -> np.ndarray:
    """The instants of an impact's history in s: ``points`` (>= 2) equally spaced over
    [0, t_y], both ends included, or the given ``times``, each within [0, t_y]."""
    if times is not None:
        t = np.atleast_1d(np.asarray(times, dtype=float))
        if np.any((t < 0) | (t > t_y)):
            end = bound_text(float(t_y), "high", 6)
            raise InputError(f"times must lie within [0, t_y] = [0, {end}] s")
        return t
    if int(points) < 2:
        raise InputError(f"points must be >= 2, got {points!r}")
    return np.linspace(0.0, t_y, int(points))


def check_velocity(velocity: float) -> None:
    if velocity > QUASI_STATIC_VELOCITY_LIMIT:
        warnings.warn(
            f"velocity {repr(float(velocity)).removesuffix('.0')} m/s exceeds "
            f"{QUASI_STATIC_VELOCITY_LIMIT:g} m/s, the stated "
            "validity of the quasi-static impact theory; results are outside it",
            QuasiStaticValidityWarning,
            stacklevel=caller_stacklevel(),
        )


def _exp(exponent: float) -> float:
    """exp that overflows to inf instead of raising (from ln of the largest float, 709.78)."""
    try:
        return math.exp(exponent)
    except OverflowError:
        return math.inf


SCALES = ("shape_coefficient", "E2", "mass", "velocity")
"""The inputs that set the exact power-law impact's scales (x_c, P_c, t_c, a_c, p_c)."""


def representable(
    name: str, value: float, mass: float, velocity: float, inputs: tuple[str, ...] = SCALES
) -> float:
    """``value`` if it is a normal float (neither 0, subnormal, nor inf), else InputError
    naming the ``inputs`` that set it (none singled out: any of them may be the one of no
    physical size) at its head (on the command line, their options)."""
    if not (math.isfinite(value) and abs(value) >= sys.float_info.min):
        raise InputError(
            f"{', '.join(inputs)}: the exact impact of {mass:g} kg at {velocity:g} m/s would "
            f"give {_said(name, value)}, outside the floating-point range "
            f"[{sys.float_info.min:.3g}, {sys.float_info.max:.3g}]; give "
            f"{'these' if len(inputs) > 1 else 'it'} a value of a physical size (or rescale "
            "the units)",
            inputs[0],
        )
    return value


def _said(name: str, value: float) -> str:
    """``name = value`` as a refusal shows a scale outside the floats; a NaN is a ratio of
    two scales that both left them (p_c = P_c / a_c^2 at 0 / 0)."""
    if math.isnan(value):
        return f"{name} = nan (a ratio of scales that both leave the floats)"
    return f"{name} = {value:g}"


def check_impact_energy(mass: float, velocity: float) -> None:
    """Refuse an impact (mass kg, velocity m/s) whose v0^2 or M v0^2 / 2 exceeds the largest
    float (the FE impact's energies and the profile impact's clock take them), naming the
    velocity at which both are floats and, where v0^2 is one, the mass (three digits, rounded
    down). ``dynamic --velocity 1e308`` named 4.84e244 m/s, the power law's P_c alone, whose
    v0^2 was refused next with no value."""
    square = velocity * velocity
    energy = 0.5 * mass * square
    if math.isfinite(energy):
        return
    log_top = math.log(sys.float_info.max)
    fastest = math.exp(0.5 * min(log_top, log_top + math.log(2.0 / mass)))
    said = f"lower velocity=... to at most about {bound_text(fastest, 'high')} m/s"
    if math.isfinite(square):
        lightest = math.exp(log_top + math.log(2.0) - math.log(square))
        said += " with this striker, mass and body, or mass=... to at most about "
        said += f"{bound_text(lightest, 'high')} kg"
    raise InputError(
        f"{'mass, ' if math.isfinite(square) else ''}velocity: the impact of {mass:g} kg at "
        f"{velocity:g} m/s would give v0^2 = {square:g} and M v0^2 / 2 = {energy:g}, outside "
        f"the floating-point range [{sys.float_info.min:.3g}, {sys.float_info.max:.3g}]: {said}",
        "velocity",
    )


DECELERATION_LIMIT = sys.float_info.max / 2.0
"""m/s^2; the striker's largest deceleration P_c / M an FE impact takes: half the largest
float (the FE's peak force exceeds P_c by 1e-4 massless, is below it with waves)."""


class _Impact(Protocol):
    """What :func:`impact_in_floats` reads of an exact impact (SI units; a power law's
    :class:`ImpactResult` its force exponent too)."""

    P_c: float


Exact = TypeVar("Exact", bound=_Impact)


def impact_in_floats(mass: float, velocity: float, exact: Callable[[], Exact]) -> Exact:
    """The exact impact ``exact()`` of ``mass`` kg at ``velocity`` m/s once the FE impact's
    floating-point range holds, checked in the order the run meets it: M v0^2 / 2 a float
    (:func:`check_impact_energy`; the exact impact's remedy keeps only its P_c one), the exact
    impact's own scales, v0^2 a normal float and the striker's deceleration P_c / M at most
    :data:`DECELERATION_LIMIT` (InputError naming velocity and the velocity that passes; a
    striker of 1e-300 kg at 1.34e154 m/s on z = 1e-10 r^3 overflowed it: a traceback)."""
    check_impact_energy(mass, velocity)
    quasi = exact()
    representable("v0^2", velocity * velocity, mass, velocity, ("velocity",))
    log_deceleration = math.log(quasi.P_c) - math.log(mass)  # P_c / M may overflow
    log_excess = log_deceleration - math.log(DECELERATION_LIMIT)
    if log_excess > 0.0:  # P_c / M ~ v0^(2q/(q+1)) (q >= 1 where no power law: a profile)
        q = quasi.force_exponent if isinstance(quasi, ImpactResult) else 1.0
        slower = bound_text(velocity * math.exp(-log_excess * (q + 1.0) / (2.0 * q)), "high")
        decade = log_deceleration / math.log(10.0)
        shown = f"{10.0 ** (decade - math.floor(decade)):.3f}e+{math.floor(decade):d}"
        raise InputError(
            f"velocity: the impact of {mass:g} kg at {velocity:g} m/s would decelerate the "
            f"striker by P_c / M = {shown} m/s^2, beyond the "
            f"{DECELERATION_LIMIT:.3g} an FE impact takes (half the largest float): lower "
            f"velocity=... to at most about {slower} m/s with this striker, mass and body",
            "velocity",
        )
    return quasi


def _scales(mass: float, velocity: float, law: ContactLaw) -> dict[str, float]:
    """x_c, P_c, t_c (m, N, s), a_c (m), p_c (Pa) and the impulse (N s) of the exact impact
    of ``mass`` kg at ``velocity`` m/s, each possibly 0, subnormal or inf (x_c in logarithms:
    M v0^2 alone may leave the floats; a_c and p_c left out where x_c does)."""
    beta, q = law.beta, law.force_exponent
    log_x_c = log_approach(mass, velocity, beta, q)
    x_c = _exp(log_x_c)
    found = {
        "x_c": x_c,
        "P_c": _exp(math.log(beta) + q * log_x_c),
        "t_c": duration_integral(q) * _exp(log_x_c - math.log(velocity)),
    }
    if not (math.isfinite(x_c) and x_c >= sys.float_info.min):  # no a_c, p_c of it
        return found
    found["a_c"] = float(law.contact_radius(x_c))
    with np.errstate(all="ignore"):  # a_c^2 may underflow: the check says so
        found["p_c"] = float(law.central_pressure(x_c))
    return {**found, "impulse": 2.0 * mass * velocity}


def _outside(scales: dict[str, float], law: ContactLaw) -> tuple[str, float] | None:
    """The first of ``scales`` (:func:`_scales`) that is no normal float (0, subnormal, inf;
    p_c's inf is exact for n <= 1), as (name, value); None where each is one."""
    unbounded = math.isinf(law.central_to_mean_ratio)
    for name, value in scales.items():
        normal = math.isfinite(value) and abs(value) >= sys.float_info.min
        if not normal and not (unbounded and name == "p_c"):
            return name, value
    return None


def _refuse(name: str, value: float, impact: tuple[float, float], law: ContactLaw) -> None:
    """Raise the refusal of the exact ``impact`` (mass kg, velocity m/s) whose scale ``name``
    is ``value``, outside the floats: naming the velocity and the mass that bring every scale
    within them, as the FE impact's reach does (:func:`shtaerman.guards.check_reach`), else,
    or where the striker or the body is at fault (the command line's default impact on them
    leaves the floats too: z = 1e308 r^1.3 named 8e20 m/s), the inputs that set the scales
    (:func:`representable`)."""
    from ..vocabulary import entry

    mass, velocity = impact
    typical = (entry("mass").default, entry("velocity").default)
    if _outside(_scales(*typical, law), law) is not None:
        representable(name, value, mass, velocity)
    remedies = [
        (*_passing(impact, law, which), parameter, unit)
        for which, parameter, unit in ((1, "velocity", "m/s"), (0, "mass", "kg"))
    ]
    remedies = [remedy for remedy in remedies if remedy[2]]
    if not remedies:
        representable(name, value, mass, velocity)
    (verb, bound, shown, parameter, unit), *others = remedies
    other = "mass" if parameter == "velocity" else "velocity"
    said = f"{verb} {parameter}=... to at {bound} about {shown} {unit} with this striker, {other}"
    for more, bound, shown, parameter, unit in others:  # the verb once where both share it
        said += f" and body, or {'' if more == verb else more + ' '}{parameter}=... to at "
        said += f"{bound} about {shown} {unit}"
    raise InputError(
        f"mass, velocity: the exact impact of {mass:g} kg at {velocity:g} m/s would give "
        f"{_said(name, value)}, outside the floating-point range [{sys.float_info.min:.3g}, "
        f"{sys.float_info.max:.3g}]: {said}{'' if others else ' and body'}",
        remedies[0][3],
    )


def _passing(impact: tuple[float, float], law: ContactLaw, which: int) -> tuple[str, str, str]:
    """("raise" or "lower", "least" or "most", the value, three digits) of the velocity
    (``which`` 1, m/s) or the mass (0, kg) nearest ``impact``'s, the other kept, at which
    every scale of the exact impact is a normal float; ("", "", "") where none is."""

    def fits(log_value: float) -> bool:
        moved = [math.log(impact[0]), math.log(impact[1])]
        moved[which] = log_value
        return _outside(_scales(*map(_exp, moved), law), law) is None

    start = math.log(impact[which])
    far = next(
        (start + sign * 10.0 * step for step in range(1, 150) for sign in (1.0, -1.0)
         if abs(start + sign * 10.0 * step) < 700.0 and fits(start + sign * 10.0 * step)),
        None,
    )  # fmt: skip
    if far is None:
        return "", "", ""
    low, high = start, far  # refused, passing
    for _ in range(80):
        middle = (low + high) / 2.0
        low, high = (low, middle) if fits(middle) else (middle, high)
    up = far > start
    shown = bound_text(math.exp(high), "low" if up else "high")
    if not fits(math.log(float(shown))):
        return "", "", ""
    return ("raise", "least", shown) if up else ("lower", "most", shown)


def log_approach(mass: float, velocity: float, beta: float, q: float) -> float:
    """ln x_c of the impact M x'' = -beta x^q (mass kg, velocity m/s, beta N/m^q, all > 0),
    x_c = ((q + 1) M v0^2 / (2 beta))^(1/(q + 1)) in m, in logarithms: M v0^2 alone under-
    or overflows for extreme but representable inputs."""
    log_x = math.log(q + 1.0) + math.log(mass) + 2.0 * math.log(velocity) - math.log(2.0 * beta)
    return log_x / (q + 1.0)


def solve_impact(mass: float, velocity: float, law: ContactLaw) -> ImpactResult:
    """Maxima and durations of the impact M x'' = -beta x^q, exact (closed form).

    Parameters
    ----------
    mass : float
        Striker mass M in kg (> 0).
    velocity : float
        Approach velocity v0 in m/s (> 0; above 5 m/s a :class:`QuasiStaticValidityWarning`).
    law : ContactLaw
        The static contact law, e.g. :class:`shtaerman.theory.contact.PowerLawContact`.

    Returns
    -------
    ImpactResult
        Call :meth:`ImpactResult.history` for x(t), v(t), P(t), a(t), p(0, t).
    """
    mass = validate_positive("mass", mass, "kg")
    velocity = validate_positive("velocity", velocity, "m/s")
    check_velocity(velocity)
    beta, q = validate_positive("beta", law.beta), law.force_exponent
    scales = _scales(mass, velocity, law)
    outside = _outside(scales, law)
    if outside is not None:
        _refuse(*outside, (mass, velocity), law)
    x_c, P_c, t_c, a_c, p_c, impulse = scales.values()
    half_time = ateb_sine(q, 1.0, (q + 1.0) / 4.0 * duration_integral(q))
    return ImpactResult(
        mass=mass,
        velocity=velocity,
        beta=beta,
        force_exponent=q,
        x_c=x_c,
        P_c=P_c,
        a_c=a_c,
        p_c=p_c,
        t_c=t_c,
        t_y=2.0 * t_c,
        impulse=impulse,
        impulse_simpson=P_c * t_c * (1.0 + 4.0 * float(half_time) ** q) / 3.0,
        law=law,
    )
