"""Quasi-static impact M x'' = -P(x) on any axisymmetric profile, exact by quadrature.

The power law has its closed form (:mod:`shtaerman.theory.impact`, Ateb functions); any other
profile (:class:`~shtaerman.theory.sneddon.SneddonContact`) is integrated in its contact
radius a, with x = delta(a):

- the work W(a) = Int_0^x P dx. With dP/da = 2 E* a delta'(a), by parts
  W = P delta - E* a delta^2 + E* Int_0^a delta(s)^2 ds (for Hertz 8 E* a^5/(15 R^2));
- the maximum a_c from W(a_c) = M v0^2 / 2, then x_c = delta(a_c), P_c = P(a_c);
- the time t(a) = Int_0^a delta'(s) ds / v(s), v^2 = v0^2 - 2 W / M, whose 1/sqrt singularity
  at a_c is removed by a = a_c (1 - u^2); t_c = t(a_c), and t_y = 2 t_c (restitution
  mirrors compression);
- impulse 2 M v0 and the paper's Simpson estimate (t_c/3) (P_c + 4 P(t_c/2)).

Each integral is Gauss-Legendre on panels between the table's radii (a tabulated profile's
delta is smooth between them; of a dense table, between every k-th, :data:`TABLE_PANELS`),
with a Legendre interpolant on each panel for the integral to any point; the history inverts
t(u) by bisection on that interpolant.
"""

from __future__ import annotations

import math
import sys
from dataclasses import dataclass, field
from functools import cached_property

import numpy as np
from numpy.polynomial import legendre
from numpy.typing import ArrayLike
from scipy.optimize import brentq
from scipy.special import roots_legendre

from ..validation import (
    SQUARABLE_VELOCITY,
    InputError,
    LimitError,
    bound_text,
    validate_positive,
)
from .impact import (
    ImpactHistory,
    ImpactResult,
    check_impact_energy,
    check_velocity,
    history_times,
)
from .sneddon import ROOT_ITERATIONS, SneddonContact

__all__ = [
    "ProfileImpactResult",
    "larger_sphere",
    "lower_impact",
    "lower_inputs",
    "solve_profile_impact",
    "work_to",
]

NODES = roots_legendre(16)[0]
PANELS = 16
"""Equal panels over [0, a_c] (the work) and over u in [0, 1] (the time), joined by a tabulated
profile's radii; on each, 16 Gauss-Legendre nodes carry a degree-15 Legendre interpolant whose
antiderivative gives the integral to any point (round-off for an analytic integrand)."""
TABLE_PANELS = 512
"""Most of a tabulated profile's radii that join the panels: a denser table joins every k-th
radius, so that the quadrature's nodes (at each of which Sneddon's integrals run over the
table's pieces) do not grow with its rows, and the cost stays linear in them, not quadratic.
Between the joined radii the integrands have kinks of the size of the jumps of G'' (the
interpolant's own error; benchmarks/FEM_NOTES.md, "Tabulated profile impact")."""


@dataclass(frozen=True)
class _Cumulative:
    """Int_ends[0]^x f for any x in [ends[0], ends[-1]], from f at the panels' Gauss nodes."""

    ends: np.ndarray
    antiderivative: np.ndarray  # Legendre coefficients per panel, (16 + 1, panels)
    totals: np.ndarray  # the integral up to each panel end

    @classmethod
    def of(cls, ends: np.ndarray, integrand) -> _Cumulative:
        return cls.fit(ends, integrand(cls.nodes(ends)))

    @staticmethod
    def nodes(ends: np.ndarray) -> np.ndarray:
        """The Gauss nodes of the panels between ``ends``, (panels, nodes)."""
        half = 0.5 * np.diff(ends)
        return 0.5 * (ends[:-1] + ends[1:])[:, None] + half[:, None] * NODES

    @classmethod
    def fit(cls, ends: np.ndarray, values: np.ndarray) -> _Cumulative:
        """From f at :meth:`nodes` (``values``, (panels, nodes))."""
        half = 0.5 * np.diff(ends)
        fit = legendre.legfit(NODES, values.T, NODES.size - 1)  # on [-1, 1] per panel
        anti = legendre.legint(fit, lbnd=-1.0) * half  # Int_-1^y, scaled to x
        totals = np.concatenate([[0.0], np.cumsum(legendre.legval(1.0, anti))])
        return cls(ends, anti, totals)

    def __call__(self, x: ArrayLike) -> np.ndarray:
        x = np.asarray(x, dtype=float)
        k = np.clip(np.searchsorted(self.ends, x, side="right") - 1, 0, self.ends.size - 2)
        y = (2.0 * x - self.ends[k] - self.ends[k + 1]) / (self.ends[k + 1] - self.ends[k])
        return self.totals[k] + legendre.legval(y, self.antiderivative[:, k], tensor=False)


def _panels(law: SneddonContact, top: float, to_the_equator: bool = False) -> np.ndarray:
    """Panel ends over [0, top] m: equal panels, plus a tabulated profile's radii below (or
    halving towards the sphere's equator, where delta^2 grows as ln^2)."""
    ends = np.linspace(0.0, top, PANELS + 1)
    if to_the_equator:
        ends = np.union1d(ends, top - (top - ends[-2]) * 0.5 ** np.arange(1, 40))
    elif not law.sphere:
        radii = law.indenter.radii
        radii = radii[radii < top]
        step = -(-radii.size // TABLE_PANELS)  # every radius, or every step-th of a dense table
        ends = np.union1d(ends, radii[::step])
    return ends


def _work(
    law: SneddonContact, a: ArrayLike, below: ArrayLike, delta: np.ndarray | None = None
) -> np.ndarray:
    """W(a) = P delta - E* (a delta^2 - Int_0^a delta^2) in J at contact radii a (m), with
    ``below`` = Int_0^a delta^2 (m^3) (and ``delta`` = delta(a) in m, when known)."""
    a = np.asarray(a, dtype=float)
    delta = law.depth(a) if delta is None else delta
    force = law.force_at_radius(a)
    return force * delta - law.modulus * (a * delta**2 - below)


def _maximum_radius(law: SneddonContact, mass: float, velocity: float) -> float:
    """a_c in m from W(a_c) = M v0^2 / 2: a first guess on equal panels over the whole
    profile, then the exact root on the fine panels up to 1.25 times it (or the whole)."""
    energy = _impact_energy(mass, velocity)
    top = law.max_contact_radius
    top = math.nextafter(top, 0.0) if law.sphere else top
    square = lambda s: law.depth(s) ** 2  # noqa: E731
    ends = _panels(law, top, law.sphere) if law.sphere else np.linspace(0.0, top, PANELS + 1)
    # halving towards the tip too: a contact far smaller than the profile (a huge sphere)
    # is then integrated on panels of its own size, not lost in a big panel's round-off;
    # below 100 halvings' round-off (R = 1 m: W 6.5e-166 J at a = 0; a root within the
    # smallest panel, R = 0.05 m at 1e-100 m/s: ~1e-36 m, not 7e-43), down to the floats'
    guess = top
    for halvings in (100, 1100):
        tip = ends[1] * 0.5 ** np.arange(1, halvings)
        rough = _Cumulative.of(np.union1d(ends, tip), square)
        if not float(_work(law, 0.0, rough(0.0))) < energy:  # 1e-200 kg at 1e-3 m/s, R = 1 m
            continue
        if float(_work(law, top, rough(top))) >= energy:
            guess = _root(law, rough, top, energy, 1e-6)
        if guess > tip[-1]:
            break
    for reach in (min(top, 1.25 * guess), top):
        squares = _Cumulative.of(_panels(law, reach, law.sphere), square)
        if float(_work(law, reach, squares(reach))) >= energy:
            return _root(law, squares, reach, energy, 1e-15)
    _refuse_the_end(law, top, energy, float(_work(law, top, squares(top))), mass, velocity)


def _root(
    law: SneddonContact, squares: _Cumulative, reach: float, energy: float, rtol: float
) -> float:
    """The contact radius a (m) in [0, ``reach``] where W(a) (``squares``: Int_0^a delta^2)
    is ``energy`` J, to ``rtol``."""
    return brentq(
        lambda a: float(_work(law, a, squares(a))) - energy,
        0.0,
        reach,
        xtol=1e-300,
        rtol=rtol,
        maxiter=ROOT_ITERATIONS,
    )


def _impact_energy(mass: float, velocity: float) -> float:
    """M v0^2 / 2 in J (mass kg, velocity m/s). Where it or v0^2 (the history's speed) is
    below the smallest normal float, InputError naming the velocity and (where v0^2 is one)
    the mass that give 4 times it, as the power-law impact's refusal does; beyond the largest,
    the velocity and mass that keep it a float (:func:`.impact.check_impact_energy`)."""
    check_impact_energy(mass, velocity)
    tiny, square = sys.float_info.min, velocity * velocity
    energy = 0.5 * mass * square
    if square >= tiny and energy >= tiny:
        return energy
    log_energy = math.log(8.0 * tiny)  # twice 4 times the smallest
    faster = max(math.exp(0.5 * (log_energy - math.log(mass))), SQUARABLE_VELOCITY)
    said = f"raise velocity=... to at least about {bound_text(faster, 'low')} m/s"
    heavier = log_energy - 2.0 * math.log(velocity)
    if square >= tiny and heavier < math.log(sys.float_info.max):
        said += " with this striker, mass and body, or mass=... to at least about "
        said += f"{bound_text(math.exp(heavier), 'low')} kg"
    raise InputError(
        f"mass, velocity: the exact impact of {mass:g} kg at {velocity:g} m/s would give "
        f"v0^2 = {square:g} m^2/s^2 and M v0^2 / 2 = {energy:g} J; the profile impact needs "
        f"both above the smallest float {tiny:.3g}: {said}",
        "velocity",
    )


def _refuse_the_end(
    law: SneddonContact, top: float, energy: float, most: float, mass: float, velocity: float
) -> None:
    """Refuse the impact (mass kg, velocity m/s) whose energy (J) exceeds ``most`` (J), the
    work that brings the contact to the profile's end ``top`` (m): a sphere's equator, a
    table's last radius, a limit of the model (a sweep case's refused row), naming the
    velocity and the mass that pass (three digits, rounded down)."""
    remedy = "lower mass=... or velocity=..."  # the work to the end underflows (R = 1e-300 m)
    larger = "take a larger sphere"
    if most > 0.0:
        remedy = lower_impact(mass, velocity, math.log(most) - math.log(energy))
        if law.sphere:
            larger = larger_sphere(top, _sphere_share(law, top, energy, most))
    if law.sphere:
        raise LimitError(
            f"sphere_radius: the striker's energy {energy:.6g} J drives the contact to the "
            f"sphere's equator (radius {top:.6g} m); {larger} or {remedy}",
            "sphere_radius",
        )
    raise LimitError(
        f"profile: the striker's energy {energy:.6g} J drives the contact beyond the "
        f"table's last radius {top:.6g} m; extend the table or {remedy}",
        "profile",
    )


def _sphere_share(law: SneddonContact, top: float, energy: float, most: float) -> float:
    """The log share of :func:`larger_sphere` whose sphere R' (from ``top``, the equator of
    ``law``'s, which ``most`` J reach) takes ``energy`` J to its equator: R' raised until its
    own work there is at least ``energy`` (checked as named, three digits). The work to
    a = R less one ulp, where the impact ends, is self-similar in R but for that ulp, whose
    share of R halves across a power of 2: W / (E* R^3) 332 at R = 1e-4 m, 320 at 1e-3 m."""
    from .profiles import SphereIndenter

    log_share = math.log(most) - math.log(energy)
    for _ in range(4):  # one raise suffices: W / R^3 varies by 4 % across the binades
        named = float(bound_text(top * math.exp(-log_share / 3.0), "low"))
        try:
            sphere = SneddonContact(SphereIndenter(named), law.modulus)
        except InputError:  # beyond the radii a sphere takes: named as it is
            break
        reached = work_to(sphere, math.nextafter(named, 0.0))
        if reached >= energy:
            break
        log_share += math.log(reached) - math.log(energy)
    return log_share


def lower_impact(mass: float, velocity: float, log_share: float) -> str:
    """ "lower velocity=... to at most V m/s or mass=... to at most M kg": the impact of
    ``mass`` kg at ``velocity`` m/s whose energy, scaled by e^``log_share`` (< 1), passes a
    limit, either input alone (three digits, rounded down; the mass left out where it
    underflows)."""
    slower, lighter = lower_inputs(mass, velocity, log_share)
    return f"lower velocity=... to at most {slower} m/s" + (
        f" or mass=... to at most {lighter} kg" if lighter else ""
    )


def larger_sphere(radius: float, log_share: float) -> str:
    """ "raise sphere_radius=... to at least R' m": the sphere (R = ``radius`` m) that an
    impact whose energy scaled by e^``log_share`` (< 1) would pass, keeps within the same
    limit (three digits, rounded up). Exact: the quasi-static impact is self-similar in R, the
    work to a depth R' x / R on R' being (R' / R)^3 that to x on R; R' = R e^(-log_share / 3)."""
    least = radius * math.exp(-log_share / 3.0)
    if not math.isfinite(least):
        return "take a larger sphere (sphere_radius=...)"
    return f"raise sphere_radius=... to at least {bound_text(least, 'low')} m"


def lower_inputs(mass: float, velocity: float, log_share: float) -> tuple[str, str]:
    """The velocity (m/s) and the mass (kg) :func:`lower_impact` names, as it shows them."""
    return _down(velocity * math.exp(log_share / 2.0)), _down(mass * math.exp(log_share))


def work_to(law: SneddonContact, radius: float) -> float:
    """The work (J) that presses the profile of ``law`` to the contact radius ``radius`` m:
    the energy M v0^2 / 2 of a quasi-static impact whose a_c it is."""
    squares = _Cumulative.of(_panels(law, radius, law.sphere), lambda s: law.depth(s) ** 2)
    return float(_work(law, radius, squares(radius)))


def _down(value: float) -> str:
    """``value`` > 0 rounded down to three digits: a bound that passes when tried ("" where
    it underflows: 1 kg at 1e154 m/s on a 1 nm sphere, whose mass would be 1e-328 kg)."""
    return bound_text(value, "high") if value > 0.0 else ""


@dataclass(frozen=True)
class ProfileImpactResult:
    """Maxima and durations of a quasi-static impact on a :class:`SneddonContact` profile
    (SI units; the keys of :class:`shtaerman.theory.impact.ImpactResult`). ``beta`` is NaN
    and ``force_exponent`` the tip's 3/2: the force law is no power law."""

    mass: float
    velocity: float
    x_c: float
    P_c: float
    a_c: float
    p_c: float
    law: SneddonContact = field(repr=False, compare=False)
    beta: float = math.nan
    force_exponent: float = 1.5

    @cached_property
    def _u_ends(self) -> np.ndarray:
        """Panel ends in u, a = a_c (1 - u^2): equal, plus the images of the table's radii."""
        ends = np.sqrt(1.0 - _panels(self.law, self.a_c) / self.a_c)
        return np.union1d(np.linspace(0.0, 1.0, PANELS + 1), ends)

    @cached_property
    def _clock(self) -> tuple[_Cumulative, _Cumulative, np.ndarray]:
        """t_c - t(u) (s, the time still to reach a_c) and Int_u^1 delta^2 da (m^3), both on
        the u panels (the second gives W at the first's nodes), and a^2 v da/du delta'(a)
        (m^4/s) at their nodes, the radiation's integrand: Sneddon's integrals (delta, P,
        delta') run once at the nodes for all three, each over the table's pieces."""
        law, a_c, ends = self.law, self.a_c, self._u_ends
        u = _Cumulative.nodes(ends)
        a = a_c * (1.0 - u**2)
        delta = law.depth(a)
        squares = _Cumulative.fit(ends, 2.0 * a_c * u * delta**2)
        speed = self._speed(a, float(squares(1.0)) - squares(u), delta)
        slope = 2.0 * a_c * u * law.depth_slope(a)  # da/du delta'(a) = dx/du
        # dt/du = dx/du / v(a), finite at u = 0 (v ~ u there)
        return _Cumulative.fit(ends, slope / speed), squares, a**2 * speed * slope

    def speed(self, a: ArrayLike) -> np.ndarray:
        """|dx/dt| in m/s at contact radii a in [0, a_c] m."""
        a = np.asarray(a, dtype=float)
        _, squares, _ = self._clock
        below = float(squares(1.0)) - squares(np.sqrt(np.clip(1.0 - a / self.a_c, 0.0, 1.0)))
        return self._speed(a, below)

    def _speed(
        self, a: np.ndarray, below: ArrayLike, delta: np.ndarray | None = None
    ) -> np.ndarray:
        """|dx/dt| in m/s at contact radii a (m) where Int_0^a delta^2 = ``below`` (m^3)
        (and the depth is ``delta`` m, when known)."""
        work = _work(self.law, a, below, delta)
        return np.sqrt(np.clip(self.velocity**2 - 2.0 * work / self.mass, 0.0, None))

    @property
    def t_c(self) -> float:
        """Duration of compression in s."""
        return float(self._clock[0](1.0))

    @property
    def t_y(self) -> float:
        """Duration of the whole impact in s (2 t_c)."""
        return 2.0 * self.t_c

    @property
    def impulse(self) -> float:
        """2 M v0 in N s."""
        return 2.0 * self.mass * self.velocity

    @cached_property
    def force_rate_squared_integral(self) -> float:
        """Int (dP/dt)^2 dt over [0, t_y] in N^2/s, the first-order radiation's integral
        (:mod:`shtaerman.theory.radiation`).

        dP/dt = 2 E* a v (dP/da = 2 E* a delta'(a), da/dt = v / delta'(a)) and dt = delta' da / v,
        so compression and restitution each give 4 E*^2 Int_0^a_c a^2 v delta'(a) da, here on
        the u panels (a = a_c (1 - u^2): v ~ u at a_c, a smooth integrand), from the values the
        clock's quadrature found at their nodes.
        """
        whole = _Cumulative.fit(self._u_ends, self._clock[2])
        return 8.0 * self.law.modulus**2 * float(whole(1.0))

    @property
    def impulse_simpson(self) -> float:
        """The paper's Simpson estimate (t_c/3) (P_c + 4 P(t_c/2)) in N s."""
        middle = float(self.history(times=[0.5 * self.t_c]).P[0])
        return self.t_c / 3.0 * (self.P_c + 4.0 * middle)

    def _u_at(self, left: np.ndarray) -> np.ndarray:
        """u at which the time still to reach a_c is ``left`` (s): bisection on the monotone
        interpolant t_c - t(u) (60 halvings: to round-off)."""
        clock, _, _ = self._clock
        low, high = np.zeros_like(left), np.ones_like(left)
        for _ in range(60):
            middle = 0.5 * (low + high)
            below = clock(middle) < left
            low, high = np.where(below, middle, low), np.where(below, high, middle)
        return 0.5 * (low + high)

    def history(self, points: int = 201, times: ArrayLike | None = None) -> ImpactHistory:
        """The histories t, x, v, P, a, p0 over [0, t_y] (``points`` instants, or ``times``
        in s), each exact to the quadrature's round-off."""
        t = history_times(self.t_y, points, times)
        mirrored = np.minimum(t, self.t_y - t)  # restitution mirrors compression
        a = self.a_c * (1.0 - self._u_at(np.clip(self.t_c - mirrored, 0.0, None)) ** 2)
        a[mirrored <= 0.0] = 0.0  # first touch and separation
        v = np.where(t <= self.t_c, 1.0, -1.0) * self.speed(a)
        with np.errstate(divide="ignore", invalid="ignore"):
            p0 = np.where(a > 0, self.law.central_pressure_at_radius(a), 0.0)
        return ImpactHistory(t, self.law.depth(a), v, self.law.force_at_radius(a), a, p0)

    maxima = ImpactResult.maxima
    """The SI keys of ``shtaerman impact --json``."""


def solve_profile_impact(mass: float, velocity: float, law: SneddonContact) -> ProfileImpactResult:
    """The quasi-static impact of ``mass`` kg at ``velocity`` m/s on the profile of ``law``.

    Raises
    ------
    shtaerman.validation.InputError
        If an input lies outside its range; a LimitError if the contact would outgrow a
        table or reach a sphere's equator.
    """
    mass = validate_positive("mass", mass, "kg")
    velocity = validate_positive("velocity", velocity, "m/s")
    check_velocity(velocity)
    a_c = _maximum_radius(law, mass, velocity)
    result = ProfileImpactResult(
        mass,
        velocity,
        x_c=float(law.depth(a_c)),
        P_c=float(law.force_at_radius(a_c)),
        a_c=a_c,
        p_c=float(law.central_pressure_at_radius(a_c)),
        law=law,
    )
    return result
