"""Exact viscoelastic references: Prony input, Lee-Radok, Ting, and the viscoelastic impact.

The paper's striker (0.7 kg, 3 m/s, A = 5 m^-1/2, n = 3/2, rigid) on rubber with E2 = 7.5 MPa
instantaneous, nu2 = 1/2, so E*_0 = 1e7 Pa. Closed forms used below (psi = g_inf + sum g_i
e^(-t/tau_i), F = x^q):

- x^q rising at a constant rate c: P = beta0 c [g_inf t + sum_i g_i tau_i (1 - e^(-t/tau_i))];
- x = v t: Int_0^t e^(-(t-s)/tau) d(s^q) = t^q 1F1(1; q+1; -t/tau) (Kummer), so
  P = beta0 (v t)^q [g_inf + sum_i g_i 1F1(1; q+1; -t/tau_i)];
- x = v t up to t_m, then v (2 t_m - t): Ting's condition Int_{t1}^t psi(t-s) x'(s) ds = 0 reads
  Psi(t - t1) = 2 Psi(t - t_m), Psi(s) = Int_0^s psi = g_inf s + sum g_i tau_i (1 - e^(-s/tau_i)),
  and P(t) = beta0 (v t1)^q [g_inf + sum_i g_i e^(-(t-t1)/tau_i) 1F1(1; q+1; -t1/tau_i)].
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from scipy.integrate import quad
from scipy.optimize import brentq
from scipy.special import hyp1f1

from shtaerman.theory.contact import PowerLawContact
from shtaerman.theory.impact import solve_impact
from shtaerman.theory.indenter import PowerLawIndenter
from shtaerman.theory.viscoelastic import (
    PronySeries,
    indentation_force,
    limit_impacts,
    viscoelastic_impact,
)
from shtaerman.validation import InputError

LAW = PowerLawContact(PowerLawIndenter(5.0, 1.5), 7.5e6 / 0.75)
Q = LAW.force_exponent
GLASSY, _ = limit_impacts(0.7, 3.0, LAW, PronySeries((0.5,), (1.0,)))
T_C = GLASSY.t_c
TWO_TERMS = PronySeries((0.3, 0.25), (0.4 * T_C, 3.0 * T_C))
PAIRS = (TWO_TERMS.weights, TWO_TERMS.times)


def order(coarse: float, medium: float, fine: float) -> float:
    """Observed order from three results at steps N, 2N, 4N."""
    return math.log2(abs(coarse - medium) / abs(medium - fine))


# --- the Prony series ------------------------------------------------------------------------


@pytest.mark.parametrize(
    ("weights", "times", "words"),
    [
        ((-0.1,), (1.0,), "g1 must lie in [0, 1)"),
        ((0.6, 0.4), (1.0, 2.0), "sum to less than 1"),
        ((0.5,), (0.0,), "tau1 must be a finite number > 0"),
        ((0.5,), (-1.0,), "tau1"),
        ((0.5,), (math.inf,), "tau1"),
        ((0.5, 0.1), (1.0,), "one relaxation time per weight"),
        ((math.nan,), (1.0,), "g1"),
        ((True,), (1.0,), "g1"),
    ],
)
def test_prony_rejects_bad_values(weights, times, words):
    with pytest.raises(InputError, match="prony") as caught:
        PronySeries(weights, times)
    assert words in str(caught.value)
    assert "\n" not in str(caught.value)


@pytest.mark.parametrize("text", ["0.5", "0.5:1:2", "a:1e-3", "0.5:1e-3,", "", ":", "0.5;1e-3"])
def test_prony_parse_rejects_malformed_text(text):
    with pytest.raises(InputError, match="prony"):
        PronySeries.parse(text)


def test_prony_parse_and_relaxation():
    prony = PronySeries.parse("0.3:1e-3, 0.2:0.5")
    assert prony == PronySeries((0.3, 0.2), (1e-3, 0.5))
    assert prony.g_inf == pytest.approx(0.5, abs=1e-15)
    psi = prony.relaxation([0.0, 1e3])
    assert psi[0] == pytest.approx(1.0, abs=1e-15)  # glassy: Abaqus' instantaneous modulus
    assert psi[1] == pytest.approx(0.5, abs=1e-15)  # relaxed: g_inf (e^-2000 underflows to 0)
    with pytest.raises(InputError, match="sum to less than 1"):
        PronySeries.parse("0.5:1,0.5:2")


def test_prony_scaled_multiplies_every_time_and_only_the_times():
    prony = PronySeries((0.3, 0.2), (1e-3, 0.5)).scaled(4.0)
    assert prony == PronySeries((0.3, 0.2), (4e-3, 2.0))
    with pytest.raises(InputError, match="factor"):
        prony.scaled(0.0)


def test_restitution_depends_on_tau_only_through_the_deborah_number():
    """In units of x_c and t_c the impact depends only on g and tau/t_c: half the mass with tau
    scaled by its own t_c gives the same e (same steps per t_c: equal to round-off)."""
    light = solve_impact(0.35, 3.0, LAW)
    heavy = viscoelastic_impact(0.7, 3.0, LAW, one_term(2.0), steps=100)
    prony = PronySeries((0.5,), (light.t_c / 2.0,))
    assert viscoelastic_impact(0.35, 3.0, LAW, prony, steps=100).restitution == pytest.approx(
        heavy.restitution, rel=1e-12
    )


# --- Lee-Radok (loading) ---------------------------------------------------------------------


def test_lee_radok_is_exact_for_a_linear_ramp_of_x_to_the_q():
    """F = x^q linear in time is the interpolation's own class: round-off agreement."""
    rate = 2e-3  # m^q / s
    t = np.linspace(0.0, 4.0 * T_C, 37)
    x = (rate * t) ** (1.0 / Q)
    force, radius = indentation_force(t, x, LAW, TWO_TERMS)
    exact = (
        LAW.beta
        * rate
        * (
            TWO_TERMS.g_inf * t
            + sum(g * tau * -np.expm1(-t / tau) for g, tau in zip(*PAIRS, strict=True))
        )
    )
    np.testing.assert_allclose(force, exact, rtol=1e-12, atol=1e-12 * exact[-1])
    np.testing.assert_allclose(radius, LAW.contact_radius(x), rtol=1e-15)


def lee_radok_constant_velocity(t: np.ndarray, speed: float, prony: PronySeries) -> np.ndarray:
    pairs = zip(prony.weights, prony.times, strict=True)
    terms = sum(g * hyp1f1(1.0, Q + 1.0, -t / tau) for g, tau in pairs)
    return LAW.beta * (speed * t) ** Q * (prony.g_inf + terms)


def test_lee_radok_constant_velocity_converges_at_second_order():
    speed, end = 3.0, 2.0 * T_C
    errors = []
    for points in (41, 81, 161):
        t = np.linspace(0.0, end, points)
        force, _ = indentation_force(t, speed * t, LAW, TWO_TERMS)
        exact = lee_radok_constant_velocity(t, speed, TWO_TERMS)
        errors.append(np.max(np.abs(force - exact)) / exact[-1])
    rates = np.log2(np.array(errors[:-1]) / np.array(errors[1:]))
    assert np.all((rates > 1.9) & (rates < 2.2)), (errors, rates)
    assert errors[-1] < 2e-5  # 160 pieces over 2 t_c


def test_elastic_series_gives_the_elastic_law():
    """g = 0: P = beta x^q while loading, whatever x(t)."""
    t = np.linspace(0.0, T_C, 50)
    x = GLASSY.x_c * np.sin(0.5 * np.pi * t / T_C)
    force, _ = indentation_force(t, x, LAW, PronySeries((0.0,), (T_C,)))
    np.testing.assert_allclose(force, LAW.force(x), rtol=1e-14)


# --- Ting (unloading) ------------------------------------------------------------------------


def ting_triangle(t: np.ndarray, speed: float, peak: float, prony: PronySeries) -> np.ndarray:
    """The semi-closed form of the module docstring, t1 to machine precision by brentq."""

    def integral(s: float) -> float:
        g, tau = np.array(prony.weights), np.array(prony.times)
        return prony.g_inf * s + float(np.sum(g * tau * -np.expm1(-s / tau)))

    force = np.zeros_like(t)
    for i, now in enumerate(t):
        if now <= peak:
            force[i] = lee_radok_constant_velocity(np.array([now]), speed, prony)[0]
            continue
        target = 2.0 * integral(now - peak)
        if integral(now) <= target:
            continue  # the contact is lost: t1 would be < 0
        t1 = now - brentq(lambda s, target=target: integral(s) - target, now - peak, now,
                          xtol=1e-18, rtol=1e-15)  # fmt: skip
        terms = sum(
            g * math.exp(-(now - t1) / tau) * hyp1f1(1.0, Q + 1.0, -t1 / tau)
            for g, tau in zip(prony.weights, prony.times, strict=True)
        )
        force[i] = LAW.beta * (speed * t1) ** Q * (prony.g_inf + terms)
    return force


def triangle(points: int, speed: float, peak: float) -> tuple[np.ndarray, np.ndarray]:
    t = np.linspace(0.0, 2.0 * peak, 2 * points - 1)  # the peak is an instant of the grid
    return t, speed * np.minimum(t, 2.0 * peak - t)


def test_ting_triangle_converges_at_second_order_to_the_semi_closed_form():
    """Second order wherever t1 lies beyond the first pieces (P > 5 % of its maximum). As the
    contact closes, t1 -> 0 falls in the first piece, where the linear interpolant of F ~ t^q
    is off by O(h^q) (q = 5/3): the error there is bounded by 0.3 (h/t_m)^q of P_max."""
    speed, peak = 3.0, T_C
    bulk_errors = []
    for points in (81, 161, 321):
        t, x = triangle(points, speed, peak)
        force, _ = indentation_force(t, x, LAW, TWO_TERMS)
        exact = ting_triangle(t, speed, peak, TWO_TERMS)
        error = np.abs(force - exact) / np.max(exact)
        bulk_errors.append(np.max(error[exact > 0.05 * np.max(exact)]))
        assert np.max(error) < 0.3 * (1.0 / (points - 1)) ** Q
    rates = np.log2(np.array(bulk_errors[:-1]) / np.array(bulk_errors[1:]))
    assert np.all((rates > 1.8) & (rates < 2.3)), (bulk_errors, rates)
    assert bulk_errors[-1] < 3e-6


def test_ting_loses_contact_before_the_depth_returns_to_zero():
    """The surface lags the striker: P falls to 0 while x > 0, at the t where Psi(t) = 2
    Psi(t - t_m); a = 0 from then on."""
    t, x = triangle(401, 3.0, T_C)
    force, radius = indentation_force(t, x, LAW, TWO_TERMS)
    lost = np.flatnonzero(force == 0.0)[1]  # [0] is first touch
    assert x[lost] > 0.0 and np.all(force[lost:] == 0.0) and np.all(radius[lost:] == 0.0)
    exact = ting_triangle(t, 3.0, T_C, TWO_TERMS)
    assert np.flatnonzero(exact[1:] == 0.0)[0] + 1 == lost


def test_ting_depth_follows_the_creep_form():
    """Ting's depth in creep form: x(t) = g1(a(t)) + Int_{t1}^t phi(t - s) dsigma(s), with
    sigma(s) = Int_{t1}^s psi(s - r) x'(r) dr the relaxation history of the current edge
    (sigma(t) = 0) and phi the creep function, psi * dphi = 1. For one term,
    phi(t) = 1/g_inf - (g/g_inf) exp(-g_inf t/tau). Checked with the module's own a(t): the
    triangle is piecewise linear, so the module's t1 is exact and the two sides agree to
    round-off (quad at 1e-12)."""
    g, tau, speed = 0.5, 0.7 * T_C, 3.0
    prony = PronySeries((g,), (tau,))
    t, x = triangle(401, speed, T_C)
    _, radius = indentation_force(t, x, LAW, prony)
    g_inf = prony.g_inf

    def creep(s: float) -> float:
        return 1.0 / g_inf - g / g_inf * math.exp(-g_inf * s / tau)

    def rate(s: float, t1: float) -> float:  # dsigma/ds for the triangle
        kink = 2.0 * prony.relaxation(s - T_C) if s > T_C else 0.0
        return speed * float(prony.relaxation(s - t1) - kink)

    for n in (450, 550, 650):  # t = 1.125, 1.375, 1.625 t_m: unloading
        depth_at_t1 = float(LAW.depth(radius[n]))  # g1(a(t)) = x(t1)
        t1 = depth_at_t1 / speed
        creep_part = quad(lambda s, t1=t1, now=t[n]: creep(now - s) * rate(s, t1), t1, t[n],
                          points=[T_C], epsabs=0, epsrel=1e-12)[0]  # fmt: skip
        assert x[n] == pytest.approx(depth_at_t1 + creep_part, rel=1e-11)


def mdr_spring_bed(t: np.ndarray, x: np.ndarray, prony: PronySeries, springs: int) -> np.ndarray:
    """Independent check: the method of dimensionality reduction's 1-D bed of Prony springs,
    q = E*_0 [g_inf w + sum g_i z_i], each spring in contact only where the free surface would
    penetrate the transformed profile g1(s) = kappa A s^n; P = 2 Int q ds (midpoint rule)."""
    ds = 1.2 * float(LAW.contact_radius(x.max())) / springs
    s = (np.arange(springs) + 0.5) * ds
    profile = LAW.indenter.kappa * LAW.indenter.shape_coefficient * s**LAW.indenter.exponent
    g, tau = np.array(prony.weights)[:, None], np.array(prony.times)[:, None]
    w, z = np.zeros(springs), np.zeros((g.size, springs))
    force = np.zeros_like(t)
    for n in range(1, t.size):
        h = t[n] - t[n - 1]
        decay, ramp = np.exp(-h / tau), -np.expm1(-h / tau) * tau / h
        stiff = prony.g_inf + float(np.sum(g * ramp))
        free = np.sum(g * (ramp * w - decay * z), axis=0) / stiff  # q = 0
        new = np.where(free < x[n] - profile, x[n] - profile, free)
        z = decay * z + ramp * (new - w)
        w = new
        q = LAW.modulus * (prony.g_inf * w + np.sum(g * z, axis=0))
        force[n] = 2.0 * np.sum(q) * ds
    return force


def test_ting_agrees_with_an_independent_spring_bed():
    """The bed knows nothing of t1 or Ting's condition: contact is decided spring by spring.
    It reproduces the semi-closed form to 3.2e-7 of P_max here (its own error: the instant a
    spring leaves contact is rounded to a step, second order; 10000 springs put the midpoint
    rule's share below 1e-8), confirming the condition Int_{t1}^t psi(t-s) x'(s) ds = 0 and the
    force formula. The module differs from both by its O(h^q) near separation (3.8e-6)."""
    t, x = triangle(401, 3.0, T_C)
    force, _ = indentation_force(t, x, LAW, TWO_TERMS)
    bed = mdr_spring_bed(t, x, TWO_TERMS, 10000)
    exact = ting_triangle(t, 3.0, T_C, TWO_TERMS)
    assert np.max(np.abs(bed - exact)) / np.max(exact) < 1e-6
    assert np.max(np.abs(force - bed)) / np.max(exact) < 1e-5


# --- the viscoelastic impact -----------------------------------------------------------------

KINETIC = 0.5 * 0.7 * 3.0**2


def one_term(deborah: float, weight: float = 0.5) -> PronySeries:
    """A one-term series with tau = t_c / De (t_c: the glassy compression time)."""
    return PronySeries((weight,), (T_C / deborah,))


def richardson(coarse: float, fine: float) -> float:
    """Second-order extrapolation from steps N and 2N."""
    return (4.0 * fine - coarse) / 3.0


@pytest.mark.parametrize("limit", ["glassy", "relaxed"])
def test_limits_are_the_exact_elastic_impacts(limit):
    """tau = 1e6 t_c behaves as elastic with E2, tau = 1e-7 t_c as elastic with E2 g_inf.

    Tolerance 1e-6 relative: what is left of the relaxation is O(t_c/tau) and O(tau/t_c), with
    measured coefficients 0.43 and 2.2 in 1 - e (so 4e-7 and 2e-7 here); the extrapolation of
    N = 400 and 800 steps leaves about 1e-7 of discretization (x_max 4e-8, P_max 1.9e-7)."""
    prony = one_term(1e-6) if limit == "glassy" else one_term(1e7)
    glassy, relaxed = limit_impacts(0.7, 3.0, LAW, prony)
    exact = glassy if limit == "glassy" else relaxed
    coarse, fine = (viscoelastic_impact(0.7, 3.0, LAW, prony, steps=n) for n in (400, 800))
    assert abs(fine.restitution - 1.0) < 1e-6
    for key, value in (("x_max", exact.x_c), ("P_max", exact.P_c), ("t_x_max", exact.t_c),
                       ("t_contact", exact.t_y)):  # fmt: skip
        extrapolated = richardson(getattr(coarse, key), getattr(fine, key))
        assert extrapolated == pytest.approx(value, rel=1e-6), key
    assert 0.0 <= fine.energy_lost < 1e-6 * KINETIC


def test_glassy_limit_against_the_same_integrator_without_relaxation():
    """Same steps, g = 0 versus tau = 1e6 t_c: the discretization cancels and the difference is
    the relaxation alone, O(g t_c/tau) = 5e-7."""
    slow = viscoelastic_impact(0.7, 3.0, LAW, one_term(1e-6), steps=200)
    elastic = viscoelastic_impact(0.7, 3.0, LAW, PronySeries((0.0,), (T_C,)), steps=200)
    assert elastic.restitution == pytest.approx(1.0, abs=1e-6)  # its own O(h^2) error
    for key in ("restitution", "x_max", "P_max", "t_contact"):
        assert getattr(slow, key) == pytest.approx(getattr(elastic, key), rel=1e-6), key
    assert slow.restitution < elastic.restitution  # some energy is lost, however little


@pytest.fixture(scope="module")
def refined():
    """The two-term impact at 100, 200 and 400 steps per t_c."""
    return [viscoelastic_impact(0.7, 3.0, LAW, TWO_TERMS, steps=n) for n in (100, 200, 400)]


@pytest.mark.parametrize("key", ["restitution", "x_max", "P_max", "t_contact", "t_x_max"])
def test_impact_converges_at_second_order(refined, key):
    values = [getattr(result, key) for result in refined]
    assert 1.8 < order(*values) < 2.3, values
    assert abs(values[2] - values[1]) < 1e-5 * abs(values[2])  # 400 steps: error ~ 3e-6


def test_impact_force_agrees_with_the_spring_bed_on_its_own_trajectory():
    """End to end: the spring bed, driven by the impact's own x(t), gives the same force (to
    1.1e-5 of P_max, largest in the last steps where the module's error is O(h^q)), and its
    impulse M v0 (1 + e) gives e to 1.4e-6 of the module's."""
    result = viscoelastic_impact(0.7, 3.0, LAW, TWO_TERMS, steps=400)
    history = result.history
    bed = mdr_spring_bed(history["t"], history["x"], TWO_TERMS, 10000)
    assert np.max(np.abs(bed - history["P"])) < 3e-5 * result.P_max
    impulse = np.sum(0.5 * (bed[1:] + bed[:-1])) * result.time_step
    assert impulse / (0.7 * 3.0) - 1.0 == pytest.approx(result.restitution, abs=5e-6)


def test_energy_account_closes_and_the_loss_is_the_lost_kinetic_energy():
    """The trapezoidal rule makes the loop integral of P dx equal to M v0^2 (1 - e^2)/2 up to
    round-off (the bookkeeping check); the loss is positive between the limits."""
    result = viscoelastic_impact(0.7, 3.0, LAW, TWO_TERMS, steps=200)
    lost = KINETIC * (1.0 - result.restitution**2)
    assert result.energy_lost == pytest.approx(lost, rel=1e-12)
    assert result.work == pytest.approx(lost, rel=1e-11)
    assert result.energy_balance_error < 1e-12
    assert 0.1 * KINETIC < result.energy_lost < KINETIC
    history = result.history
    assert np.all(history["P"] >= 0.0)
    impulse = np.sum(0.5 * (history["P"][1:] + history["P"][:-1])) * result.time_step
    assert impulse == pytest.approx(0.7 * 3.0 * (1.0 + result.restitution), rel=1e-12)


def test_viscoelastic_impact_lies_between_its_elastic_limits():
    """beta0 g_inf x^q <= P <= beta0 x^q while loading (g_inf <= psi <= 1 and F grows), so
    x_max lies between the glassy and the relaxed x_c; the force relaxes while x still grows,
    so P peaks before x does; the contact ends while x > 0 (the surface lags behind)."""
    result = viscoelastic_impact(0.7, 3.0, LAW, one_term(2.0), steps=200)
    glassy, relaxed = limit_impacts(0.7, 3.0, LAW, one_term(2.0))
    assert glassy.x_c < result.x_max < relaxed.x_c
    assert relaxed.P_c < result.P_max < glassy.P_c
    history = result.history
    assert history["t"][np.argmax(history["P"])] < result.t_x_max
    assert history["x"][-2] > 0.2 * result.x_max  # last step in contact: far from x = 0
    a = history["a"][:-1]
    peak = int(np.argmax(a))
    assert np.all(np.diff(a[: peak + 1]) >= 0) and np.all(np.diff(a[peak:]) <= 0)


def test_restitution_falls_then_rises_with_the_deborah_number():
    """e = 1 at both ends; as tau falls from inf (De = t_c/tau from 0), e falls to a minimum
    near De = 2-3, then rises back to 1 as tau -> 0. A Maxwell branch dissipates only where its
    dashpot both moves and carries stress: frozen for tau >> t_c (glassy, elastic), relaxed at
    every instant for tau << t_c (stress ~ tau x'); the loss, like g w tau / (1 + (w tau)^2),
    peaks when tau is of the contact's time scale."""
    deborah = [0.01, 0.1, 1.0, 3.0, 10.0, 100.0]
    results = [viscoelastic_impact(0.7, 3.0, LAW, one_term(d), steps=100) for d in deborah]
    e = np.array([r.restitution for r in results])
    assert np.all(e < 1.0) and np.all(np.array([r.energy_lost for r in results]) > 0.0)
    assert np.all(np.diff(e[:4]) < 0) and np.all(np.diff(e[3:]) > 0), e
    assert 0.68 < e[3] < 0.70  # the table of benchmarks/visco_restitution.py: 0.6915 at De 3.16


def test_restitution_depends_on_the_weight_monotonically():
    """More relaxing modulus (larger g), more loss at the same Deborah number."""
    e = [viscoelastic_impact(0.7, 3.0, LAW, one_term(1.0, g), steps=100).restitution
         for g in (0.1, 0.3, 0.6)]  # fmt: skip
    assert e[0] > e[1] > e[2]


@pytest.mark.parametrize(("steps", "words"), [(10, "steps"), (2.5, "steps"), (True, "steps")])
def test_impact_rejects_bad_steps(steps, words):
    with pytest.raises(InputError, match=words):
        viscoelastic_impact(0.7, 3.0, LAW, TWO_TERMS, steps=steps)


@pytest.mark.parametrize(
    ("times", "depth", "words"),
    [
        ([0.0, 1.0, 0.5], [0.0, 1e-3, 0.0], "strictly increasing"),
        ([0.0, 1.0, 2.0], [1e-3, 2e-3, 0.0], "0 at the first instant"),
        ([0.0, 1.0, 2.0, 3.0], [0.0, 2e-3, 1e-3, 1.5e-3], "one maximum"),
        ([0.0, 1.0], [0.0, -1e-3], ">= 0 m"),
        ([0.0, 1.0], [0.0, 0.0], "rise above 0"),
        ([0.0], [0.0], "length >= 2"),
    ],
)
def test_indentation_force_rejects_bad_histories(times, depth, words):
    with pytest.raises(InputError, match=words):
        indentation_force(times, depth, LAW, TWO_TERMS)
