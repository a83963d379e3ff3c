"""The exact quasi-static impact: literal values, the paper's Table 3, identities, the ODE.

Literals for the paper's example (M = 0.7 kg, v0 = 3 m/s, A = 5, n = 3/2, steel 2e11/0.25 on
rubber 7.5e6/0.5) from mpmath at 40 digits, with beta, kappa, E* as in test_analytic_contact.py:

    xc = ((q + 1) * M * v**2 / (2*beta))**(1/(q + 1)); Pc = beta * xc**q
    ac = (xc/(kappa(n)*A))**(1/n); pc = (n + 1)/(2*(n - 1)) * Pc/(mp.pi*ac**2)
    I = mp.quad(lambda s: 1/mp.sqrt(1 - s**(q + 1)), [0, 1]); tc = I*xc/v
"""

import warnings

import numpy as np
import pytest
from scipy.integrate import quad

from shtaerman.theory.contact import PowerLawContact
from shtaerman.theory.impact import QuasiStaticValidityWarning, duration_integral, solve_impact
from shtaerman.theory.impact_ode import integrate_impact
from shtaerman.theory.indenter import PowerLawIndenter
from shtaerman.theory.materials import Material, effective_modulus
from shtaerman.validation import InputError

E_STAR = effective_modulus(Material(2e11, 0.25), Material(7.5e6, 0.5))
MPMATH = {
    "x_c": 0.0085174899120372515388,
    "P_c": 986.2060403651068401,
    "a_c": 0.0096492851665473110986,
    "p_c": 8428834.2071276444576,
    "t_c": 0.004105224219406260521,
}


def paper_impact(exponent=1.5, mass=0.7, velocity=3.0, coefficient=5.0):
    law = PowerLawContact(PowerLawIndenter(coefficient, exponent), E_STAR)
    return solve_impact(mass, velocity, law)


@pytest.mark.parametrize("key", sorted(MPMATH))
def test_maxima_match_mpmath(key):
    # closed forms of a few flops each: 1e-14 leaves room for ~50 ulp of accumulated rounding
    assert getattr(paper_impact(), key) == pytest.approx(MPMATH[key], rel=1e-14)


def test_paper_example_as_printed():
    result = paper_impact()
    # the paper prints x_c = 0.008517 m, a_c = 0.009649 m, t_c = 0.004105 s, t_y = 0.008210 s;
    # half a unit of the last printed digit
    assert result.x_c == pytest.approx(0.008517, abs=5e-7)
    assert result.a_c == pytest.approx(0.009649, abs=5e-7)
    assert result.t_c == pytest.approx(0.004105, abs=5e-7)
    assert result.t_y == pytest.approx(0.008210, abs=5e-7)
    # P_c = 986.2176 N and p_c = 8429081.797 Pa are printed to more digits than the paper's beta
    # supports: it used beta = 2.77632e6, which drops the steel's compliance Q1 = 4.6875e-12/Pa
    # (Q1/Q2 = 4.7e-5); our beta keeps Q1, so the printed P_c is high by 1.2e-5
    assert result.P_c == pytest.approx(986.2176, rel=2e-5)
    assert result.p_c == pytest.approx(8429081.797, rel=4e-5)


def test_duration_integral_literals():
    # the paper's eq. (14): I = 1.445927 (6 decimals); Hertz (q = 3/2): mpmath quad
    # 1.4716375921623523287, and the classical total duration 2 I = 2.9433
    assert duration_integral(5 / 3) == pytest.approx(1.4459274722255659937, rel=1e-15)
    assert duration_integral(1.5) == pytest.approx(1.4716375921623523287, rel=1e-15)
    assert 2 * duration_integral(1.5) == pytest.approx(2.9433, abs=5e-5)


def test_hertz_total_duration():
    result = paper_impact(exponent=2.0, coefficient=50.0)
    assert result.t_y * result.velocity / result.x_c == pytest.approx(2.9432751843247, rel=1e-13)


def test_paper_table3():
    # Table 3, last column: the paper's numerical integration in Maple, 4 decimals. Our exact
    # values agree to 6e-5 (0.91495 against the printed 0.9149 is the largest gap, a rounding
    # of Maple's result); the column from the paper's own 2-digit tables is off by up to 4e-4.
    result = paper_impact()
    times = result.t_c * np.array([0.25, 0.5, 0.75, 1.0, 1.25, 1.5, 1.75])
    printed = [0.3582, 0.6826, 0.9149, 1.0000, 0.9149, 0.6826, 0.3582]
    np.testing.assert_allclose(result.history(times=times).x / result.x_c, printed, atol=6e-5)
    # the v0 t / x_c column: 0.3615, 0.7230, 1.0845, 1.4459, ...
    np.testing.assert_allclose(
        times[:4] * 3 / result.x_c, [0.3615, 0.7230, 1.0845, 1.4459], atol=1e-4
    )


def test_history_identities():
    result = paper_impact()
    history = result.history(1001)
    assert history.t[0] == 0 and history.t[-1] == result.t_y
    assert history.x[0] == 0 and history.x[-1] == 0 and history.x[500] == pytest.approx(result.x_c)
    # restitution mirrors compression exactly
    np.testing.assert_allclose(history.x, history.x[::-1], rtol=0, atol=1e-15 * result.x_c)
    # energy: M v^2 / 2 + beta x^(q+1)/(q+1) = M v0^2 / 2
    q = result.force_exponent
    energy = 0.5 * 0.7 * history.v**2 + result.beta * history.x ** (q + 1) / (q + 1)
    np.testing.assert_allclose(energy, 0.5 * 0.7 * 9.0, rtol=1e-13)
    # P, a, p0 follow the static contact law at every instant
    np.testing.assert_allclose(history.P, result.beta * history.x**q, rtol=1e-15)
    assert history.p0.max() == pytest.approx(result.p_c, rel=1e-14)


def test_impulse_is_twice_momentum():
    result = paper_impact()
    law = result.law

    def force(t):
        return float(law.force(result.history(times=[t]).x[0]))

    impulse = quad(force, 0, result.t_y, epsabs=0, epsrel=1e-12, limit=200)[0]
    # adaptive quadrature of the exact history to 1e-12; the integrand is smooth inside
    assert impulse == pytest.approx(2 * 0.7 * 3.0, rel=1e-10)
    assert result.impulse == pytest.approx(4.2, rel=1e-15)
    # the paper's eq. (16) is Simpson's rule on [0, t_c]: (1 + 4 Sa(t_c/2)^(5/3))/3 P_c t_c. With
    # the exact Sa = 0.682581 it gives 1.038886, 0.14 % above the exact 2 M v0 = 1.037396 P_c t_c;
    # the paper's 1.03788 comes from rounding Sa to 0.682 first
    assert result.impulse_simpson / (result.P_c * result.t_c) == pytest.approx(1.038886, abs=1e-6)
    assert result.impulse / (result.P_c * result.t_c) == pytest.approx(1.5 / 1.44592747, rel=1e-8)


@pytest.mark.parametrize("exponent", [1.0, 1.2, 1.5, 2.0, 3.0])
def test_ode_cross_check(exponent):
    result = paper_impact(exponent=exponent)
    numerical = integrate_impact(result.mass, result.velocity, result.law.force, result.x_c)
    # DOP853 at rtol 1e-12 (measured: 1e-12 agreement); the issue asks for <= 1e-8
    for key in ("x_c", "t_c", "t_y"):
        assert getattr(numerical, key) == pytest.approx(getattr(result, key), rel=1e-8)
    assert numerical.rebound_velocity == pytest.approx(-result.velocity, rel=1e-8)
    exact = result.history(501)
    x, v = numerical.sample(exact.t[:-1])
    np.testing.assert_allclose(x, exact.x[:-1], rtol=0, atol=1e-8 * result.x_c)
    np.testing.assert_allclose(v, exact.v[:-1], rtol=0, atol=1e-8 * result.velocity)


def test_ode_cross_check_below_the_smallest_energy():
    # v0 = 9.12e-249 m/s is impact's own remedy for 1e-300 (P_c just above the smallest normal
    # float, 2.2e-308 N): M v0^2 / 2 underflows to 0 in SI units, which divided by zero (adv59).
    # The scaled ODE agrees to ~3e-10 there (beta x^q passes through subnormal x^q, ~5e-10 of
    # itself); 1e-8 as for ordinary velocities.
    result = paper_impact(velocity=9.12e-249)
    assert 0.5 * result.mass * result.velocity**2 == 0.0
    numerical = integrate_impact(result.mass, result.velocity, result.law.force, result.x_c)
    for key in ("x_c", "t_c", "t_y"):
        assert getattr(numerical, key) == pytest.approx(getattr(result, key), rel=1e-8)


def test_scaling_with_velocity():
    # the paper prints x_c = 0.6037365 v0^(3/4): a misprint for 0.0037365 (which gives its own
    # x_c = 0.008517 m at 3 m/s); its beta = 2.77632e6 drops Q1, hence 2e-5
    slow, fast = paper_impact(velocity=1.0), paper_impact(velocity=4.0)
    assert fast.x_c / slow.x_c == pytest.approx(4**0.75, rel=1e-14)
    assert slow.x_c == pytest.approx(0.0037365, rel=2e-5)


def test_velocity_above_validity_warns():
    with pytest.warns(QuasiStaticValidityWarning, match="5 m/s"):
        paper_impact(velocity=6.0)
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        paper_impact(velocity=5.0)


@pytest.mark.parametrize(
    ("kwargs", "message"),
    [({"mass": 0.0}, "mass must be > 0 kg"), ({"velocity": -1.0}, "velocity must be > 0 m/s")],
)
def test_bad_input(kwargs, message):
    with pytest.raises(InputError, match=message):
        paper_impact(**kwargs)


def test_history_rejects_times_outside_the_impact():
    result = paper_impact()
    with pytest.raises(InputError, match="times"):
        result.history(times=[2 * result.t_y])
    with pytest.raises(InputError, match="points"):
        result.history(points=1)
