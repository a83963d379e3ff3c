"""Sneddon's contact of any axisymmetric profile (theory/sneddon.py, theory/profiles.py) and
the quasi-static impact on it (theory/profile_impact.py), issue 29 item 1."""

import math
import re

import numpy as np
import pytest
from scipy.integrate import quad

import shtaerman as sh
from shtaerman.theory.contact import PowerLawContact
from shtaerman.theory.impact import solve_impact
from shtaerman.theory.impact_ode import integrate_impact
from shtaerman.theory.profile_impact import solve_profile_impact
from shtaerman.theory.profiles import SphereIndenter, TabulatedIndenter
from shtaerman.theory.sneddon import SneddonContact
from shtaerman.validation import InputError

MODULUS = 1.0e7  # E* in Pa
RADIUS = 0.01  # R in m


def _sneddon_sphere(a: float) -> tuple[float, float]:
    """Sneddon's rigid sphere as the issue prints it: delta and F at contact radius a (m)."""
    log = math.log((RADIUS + a) / (RADIUS - a))
    return a / 2 * log, MODULUS * ((a**2 + RADIUS**2) / 2 * log - a * RADIUS)


@pytest.mark.parametrize("a", [1e-3, 3e-3, 6e-3, 9e-3])
def test_the_sphere_is_sneddons_closed_form_and_his_integrals(a):
    law = SneddonContact(SphereIndenter(RADIUS), MODULUS)
    depth, force = _sneddon_sphere(a)
    slope = lambda r: r / math.sqrt(RADIUS**2 - r**2)  # noqa: E731
    # the brief's integrals, r = a sin(theta): delta = a Int f'(a sin), P = 2 E* a^2 Int sin^2 f'
    integral = quad(lambda th: a * slope(a * math.sin(th)), 0, math.pi / 2, epsrel=1e-14)[0]
    moment = quad(lambda th: a**2 * math.sin(th) ** 2 * slope(a * math.sin(th)), 0, math.pi / 2)[0]
    # closed forms against closed forms and adaptive quadrature: round-off (a few ulp)
    assert float(law.depth(a)) == pytest.approx(depth, rel=1e-14)
    assert float(law.depth(a)) == pytest.approx(integral, rel=1e-13)
    assert float(law.force_at_radius(a)) == pytest.approx(force, rel=1e-13)
    assert float(law.force_at_radius(a)) == pytest.approx(2 * MODULUS * moment, rel=1e-12)
    assert float(law.contact_radius(depth)) == pytest.approx(a, rel=1e-14)


def test_the_sphere_tends_to_hertz_and_is_3_percent_below_it_at_depth_0_3_r():
    law = SneddonContact(SphereIndenter(RADIUS), MODULUS)
    hertz = PowerLawContact(sh.PowerLawIndenter.sphere(RADIUS), MODULUS)
    small = 1e-6 * RADIUS
    # the small-depth series: P/P_Hertz = 1 - delta/(10 R) + ..., so 1e-7 at 1e-6 R
    assert float(law.force(small) / hertz.force(small)) == pytest.approx(1.0, abs=2e-7)
    ratio = float(law.force(0.3 * RADIUS) / hertz.force(0.3 * RADIUS))
    assert ratio == pytest.approx(0.96991, abs=1e-5)  # the "3 % below" (-3.009 %)
    # the central pressure: Hertz's 2 E* a/(pi R) at small depth
    a = float(law.contact_radius(small))
    p0 = float(law.central_pressure(small))
    assert p0 == pytest.approx(2 * MODULUS * a / (math.pi * RADIUS), rel=1e-6)


def test_the_sphere_pressure_integrates_to_its_force():
    law = SneddonContact(SphereIndenter(RADIUS), MODULUS)
    depth = 0.2 * RADIUS
    a = float(law.contact_radius(depth))
    total = quad(lambda r: 2 * math.pi * r * float(law.pressure(r, depth)), 0, a, limit=200)[0]
    # p(r) by 48-point Gauss at each r, integrated adaptively: 1e-9
    assert total == pytest.approx(float(law.force(depth)), rel=1e-9)
    assert float(law.pressure(0.0, depth)) == pytest.approx(float(law.central_pressure(depth)))


def test_a_tabulated_paraboloid_is_the_power_law_n_2_to_round_off():
    hertz = sh.PowerLawIndenter.sphere(RADIUS)
    r = np.linspace(0.0, 0.02, 41)
    law = SneddonContact(TabulatedIndenter(r, hertz.profile(r)), MODULUS)
    exact = PowerLawContact(hertz, MODULUS)
    depths = np.array([1e-5, 1e-3, 5e-3])
    # PCHIP in r^2 reproduces a linear G exactly; the integrals are exact Gauss: round-off
    for name in ("force", "contact_radius", "central_pressure"):
        ratio = getattr(law, name)(depths) / getattr(exact, name)(depths)
        np.testing.assert_allclose(ratio, 1.0, rtol=2e-15 * 10)
    radii = np.linspace(0.0, 0.9, 7) * float(exact.contact_radius(5e-3))
    np.testing.assert_allclose(law.pressure(radii, 5e-3), exact.pressure(radii, 5e-3), rtol=1e-14)


def test_a_sampled_power_law_converges_to_it():
    paper = sh.PowerLawIndenter(5.0, 1.5)
    exact = PowerLawContact(paper, MODULUS)
    errors = []
    for points in (100, 400):
        r = np.linspace(0.0, 0.05, points + 1)
        law = SneddonContact(TabulatedIndenter(r, paper.profile(r)), MODULUS)
        errors.append(abs(float(law.force(4e-3) / exact.force(4e-3)) - 1))
    # the interpolant's error near the r^1.5 tip: 5.2e-6 then 4.7e-8 (about h^3.4)
    assert errors[0] < 1e-5 and errors[1] < errors[0] / 50


def test_the_impact_on_a_tabulated_paraboloid_is_the_ateb_solution():
    hertz = sh.PowerLawIndenter.sphere(RADIUS)
    r = np.linspace(0.0, 0.05, 101)
    law = SneddonContact(TabulatedIndenter(r, hertz.profile(r)), MODULUS)
    quadrature = solve_profile_impact(0.7, 3.0, law)
    ateb = solve_impact(0.7, 3.0, PowerLawContact(hertz, MODULUS))
    for name in ("x_c", "P_c", "a_c", "p_c"):  # one root of W(a_c) = M v0^2/2: round-off
        assert getattr(quadrature, name) == pytest.approx(getattr(ateb, name), rel=1e-14)
    # the time integral's Legendre panels: 6e-12 measured
    assert quadrature.t_c == pytest.approx(ateb.t_c, rel=1e-10)
    assert quadrature.impulse_simpson == pytest.approx(ateb.impulse_simpson, rel=1e-10)
    ours, theirs = quadrature.history(41), ateb.history(41)
    np.testing.assert_allclose(ours.x, theirs.x, rtol=0, atol=1e-10 * ateb.x_c)
    np.testing.assert_allclose(ours.P, theirs.P, rtol=0, atol=1e-10 * ateb.P_c)


def test_the_radiation_integral_reuses_the_clocks_sneddon_integrals():
    """Int (dP/dt)^2 dt (the radiation estimate's) ran Sneddon's integrals (delta, P, and
    delta' of G' and G'') again at the very nodes of the clock (t_c's quadrature): 4 more
    passes over the table's pieces, each O(nodes x rows) (2.1 of the 2000-row z = 5 r^1.5
    table's 4.7 CPU s at a_c = 0.0139 m; 9 passes in all on the old code). It now takes the
    clock's values: 4 passes for both. On a tabulated paraboloid (G linear in r^2: the law
    exact) it is the power law's closed form (:func:`.radiation.radiation_estimate`) to
    round-off: 0 measured before and 2.2e-16 after (one ulp), held to 1e-13."""
    from unittest import mock

    from shtaerman.theory import sneddon
    from shtaerman.theory.radiation import radiation_estimate

    hertz = sh.PowerLawIndenter.sphere(RADIUS)
    r = np.linspace(0.0, 0.05, 101)
    quadrature = solve_profile_impact(
        0.7, 3.0, SneddonContact(TabulatedIndenter(r, hertz.profile(r)), MODULUS)
    )
    spy = mock.patch.object(sneddon, "_piece_integral", wraps=sneddon._piece_integral)
    with spy as passes:
        assert quadrature.t_c > 0.0
        rate = quadrature.force_rate_squared_integral
    assert passes.call_count == 4
    law = PowerLawContact(hertz, MODULUS)
    closed = radiation_estimate(0.7, 3.0, law.beta, law.force_exponent, 1100.0, 2.5e6, 0.5)
    assert rate == pytest.approx(closed.force_rate_squared_integral, rel=1e-13)


def test_the_impact_on_a_sphere_agrees_with_the_ode_and_tends_to_hertz():
    law = SneddonContact(SphereIndenter(RADIUS), MODULUS)
    result = solve_profile_impact(0.7, 3.0, law)
    numerical = integrate_impact(0.7, 3.0, lambda x: law.force(x), result.x_c)
    # solve_ivp at rtol 1e-12 against the quadrature
    assert numerical.x_c == pytest.approx(result.x_c, rel=1e-9)
    assert numerical.t_c == pytest.approx(result.t_c, rel=1e-8)
    big = solve_profile_impact(0.7, 3.0, SneddonContact(SphereIndenter(1.0), MODULUS))
    hertz = solve_impact(0.7, 3.0, PowerLawContact(sh.PowerLawIndenter.sphere(1.0), MODULUS))
    # x_c/R = 3.2e-3: the sphere's force is 1 - x/(10 R) of Hertz's, P_c 1.8e-4 below
    assert big.P_c / hertz.P_c - 1 == pytest.approx(-1.84e-4, rel=0.02)


@pytest.mark.parametrize(
    ("text", "message"),
    [
        ("r,z\n0,0\n1e-3,1e-4\n", "needs at least 3 rows"),
        ("r,h\n0,0\n", "column z is missing"),
        ("r,z\n0,0\n1e-3,abc\n2e-3,1e-3\n", "line 3, column z: expected a finite number"),
        ("r,z\n0,0\n2e-3,1e-4\n1e-3,2e-4\n", "column r must increase strictly"),
        ("r,z\n1e-4,0\n2e-3,1e-4\n3e-3,2e-4\n", "must be the tip r = 0, z = 0"),
    ],
)
def test_a_bad_profile_file_is_refused_in_one_line(tmp_path, text, message):
    path = tmp_path / "tip.csv"
    path.write_text(text)
    with pytest.raises(sh.InputError, match=message) as refused:
        TabulatedIndenter.from_csv(path)
    assert "\n" not in str(refused.value) and refused.value.parameter == "profile"


@pytest.mark.parametrize("radii", [["0", "a", "0.02"], [[0.0], [0.01, 0.02]]])
def test_a_table_of_no_numbers_is_refused_naming_the_profile(radii):
    # text or ragged lists in the radii raised numpy's bare ValueError ('could not convert ...')
    with pytest.raises(InputError, match=r"^profile: radii and heights must be numbers in m$"):
        TabulatedIndenter(radii, [0.0, 0.001, 0.004])


def test_a_profile_impact_prints_its_last_time_rounded_inward():
    """The profile impact's refusal of a time beyond t_y printed t_y to 6 digits rounded to
    nearest (0.00523856 s here, above t_y = 0.005238555924... s), so the printed end was
    itself refused; it prints it rounded inward, as the power law's impact does."""
    result = solve_profile_impact(0.1, 0.5, SneddonContact(SphereIndenter(RADIUS), MODULUS))
    with pytest.raises(InputError, match=r"times must lie within \[0, t_y\]") as refused:
        result.history(times=[2.0 * result.t_y])
    printed = float(re.search(r"\[0, ([0-9.e+-]+)\] s", str(refused.value))[1])
    # the printed end is t_y to 6 digits, at or below it: a time typed as printed is accepted
    assert printed <= result.t_y and printed == pytest.approx(result.t_y, rel=1e-5)
    assert result.history(times=[printed]).t[0] == printed
