"""Exact power-law contact against literal high-precision values, identities and the paper.

The literals come from this mpmath script (40 digits, direct quadrature where an integral is
defined, nothing shared with the code under test):

    import mpmath as mp
    mp.mp.dps = 40
    def kappa(n): return mp.sqrt(mp.pi) * mp.gamma(n/2 + 1) / mp.gamma(n/2 + mp.mpf(1)/2)
    Q = (1 - mp.mpf('0.25')**2) / mp.mpf('2e11') + (1 - mp.mpf('0.5')**2) / mp.mpf('7.5e6')
    E = 1/Q; A = mp.mpf(5); n = mp.mpf(3)/2; q = (n + 1)/n
    beta = 2*n/(n + 1) * E * (kappa(n)*A)**(-1/n)
    xc = ((q + 1) * mp.mpf('0.7') * 9 / (2*beta))**(1/(q + 1)); a = (xc/(kappa(n)*A))**(1/n)
    r = mp.mpf('0.37') * a
    p = n*kappa(n)*E*A/mp.pi * mp.quad(lambda s: s**(n-1)/mp.sqrt(s**2 - r**2), [r, a])
"""

import math

import numpy as np
import pytest

from shtaerman.theory.contact import (
    PowerLawContact,
    paper_beta_constant,
    paper_J1,
    paper_J2,
    paper_pressure_eq5,
    paper_radius_constant,
    pressure_shape,
)
from shtaerman.theory.indenter import PowerLawIndenter, shape_factor
from shtaerman.theory.materials import RIGID, Material, effective_modulus
from shtaerman.validation import InputError

STEEL = Material(2e11, 0.25)
RUBBER = Material(7.5e6, 0.5)
E_STAR = 9999531.27197162633  # mpmath, above
BETA = 2776184.2013042239788  # mpmath, above
X_C = 0.0085174899120372515388
A_C = 0.0096492851665473110986
P_AT_037A = 5155911.1755011106579  # p(0.37 a) at depth x_c, direct quadrature


def paper_contact(exponent: float = 1.5, coefficient: float = 5.0) -> PowerLawContact:
    return PowerLawContact(
        PowerLawIndenter(coefficient, exponent), effective_modulus(STEEL, RUBBER)
    )


@pytest.mark.parametrize(
    ("exponent", "expected"),
    [
        (1.0, 1.5707963267948966192),
        (1.5, 1.7972103521033883112),
        (2.0, 2.0),
        (1.2, 1.6647011510904334427),
    ],
)
def test_shape_factor_matches_mpmath(exponent, expected):
    # gamma-function ratio in double precision: a few ulp
    assert shape_factor(exponent) == pytest.approx(expected, rel=1e-15)


def test_effective_modulus_steel_on_rubber():
    assert effective_modulus(STEEL, RUBBER) == pytest.approx(E_STAR, rel=1e-15)
    # a rigid striker leaves the half-space alone: E* = E2 / (1 - nu2^2) = 4 E2 / 3
    assert effective_modulus(RIGID, RUBBER) == pytest.approx(1e7, rel=1e-15)
    # ... which is the half-space's plane-strain modulus (RUBBER: 7.5 MPa, nu 0.5), to rounding
    assert RUBBER.plane_strain_modulus == pytest.approx(1e7, rel=1e-15)


def test_beta_matches_mpmath_and_paper_constant():
    contact = paper_contact()
    assert contact.beta == pytest.approx(BETA, rel=1e-14)
    # the paper: beta = 0.81180 / (A^(2/3) (Q1 + Q2)), printed to 5 digits
    assert paper_beta_constant() == pytest.approx(0.81180, abs=5e-6)
    assert contact.beta == pytest.approx(paper_beta_constant() * E_STAR / 5 ** (2 / 3), rel=1e-14)


def test_paper_constants_through_gamma_functions():
    # the paper's printed J1 = 1.198140, J2 = 0.718884, a = 0.67650 (x/A)^(2/3): half a unit of
    # the last printed digit
    assert paper_J1() == pytest.approx(1.198140, abs=5e-7)
    assert paper_J2() == pytest.approx(0.718884, abs=5e-7)
    assert paper_radius_constant() == pytest.approx(0.67650, abs=5e-6)
    # identity kappa_{3/2} = 1.5 J1 and the force prefactor (2n/(n+1)) kappa = 3 J2
    assert shape_factor(1.5) == pytest.approx(1.5 * paper_J1(), rel=1e-15)
    assert 1.2 * shape_factor(1.5) == pytest.approx(3 * paper_J2(), rel=1e-15)


def test_depth_radius_force_round_trip():
    contact = paper_contact()
    assert contact.contact_radius(X_C) == pytest.approx(A_C, rel=1e-14)
    a = np.geomspace(1e-4, 1e-1, 7)
    np.testing.assert_allclose(contact.contact_radius(contact.depth(a)), a, rtol=1e-14)
    # P = (2n/(n+1)) kappa E* A a^(n+1) and P = beta x^q are the same law
    n, kappa = 1.5, shape_factor(1.5)
    direct = 2 * n / (n + 1) * kappa * E_STAR * 5.0 * a ** (n + 1)
    np.testing.assert_allclose(contact.force(contact.depth(a)), direct, rtol=1e-13)


@pytest.mark.parametrize(("exponent", "ratio"), [(1.5, 2.5), (2.0, 1.5), (1.2, 5.5)])
def test_central_to_mean_ratio(exponent, ratio):
    contact = paper_contact(exponent)
    # (n + 1)/(2 (n - 1)) in IEEE arithmetic alone: the same bits on every machine; the 2 ulp
    # from the exact ratio are 1.2's own rounding, times n/(n - 1) = 6
    assert contact.central_to_mean_ratio == pytest.approx(ratio, rel=1e-15)
    x = 1e-3
    assert contact.pressure(0.0, x)[()] == pytest.approx(
        ratio * contact.mean_pressure(x), rel=1e-15
    )


def test_pressure_matches_quadrature_and_eq5():
    contact = paper_contact()
    assert contact.pressure(0.37 * A_C, X_C)[()] == pytest.approx(P_AT_037A, rel=1e-13)
    a = float(contact.contact_radius(X_C))
    r = np.linspace(0, a, 41)
    eq5 = paper_pressure_eq5(r, a, float(contact.force(X_C)))
    # the paper's eq. (5) (elliptic integrals) and our 2F1 closed form: two independent routes
    np.testing.assert_allclose(contact.pressure(r, X_C), eq5, rtol=1e-12, atol=1e-9 * eq5[0])


@pytest.mark.parametrize(
    ("exponent", "rho", "expected"),
    [  # mpmath, 40 digits: Int_rho^1 t^(n-1)/sqrt(t^2 - rho^2) dt / sqrt(1 - rho^2), by quad
        # (rho a power of 2 or a short binary fraction: z = 1 - rho^2 is exact in binary)
        (0.8, 2**-7, 9.9411923519512888252),
        (1.2, 2**-10, 3.932621750513562897),
        (1.5, 2**-14, 1.990639531882219823),
        (1.5, 0.625, 1.1550458526956852465),
        (2.5, 2**-4, 0.6777396789885455926),
        (4.5, 0.3125, 0.33859979636484261521),
    ],
)
def test_pressure_shape_near_the_axis_matches_mpmath(exponent, rho, expected):
    """The connection to 1 - z the pressure takes near the axis (z > 1/2): 3.3e-16 measured
    against mpmath; 1e-13 leaves room for the Gamma functions' rounding on other machines."""
    z = np.array([1.0 - rho**2])
    assert pressure_shape(exponent, z)[0] == pytest.approx(expected, rel=1e-13)


@pytest.mark.parametrize("exponent", [1.2, 1.5, 2.0, 3.0])
def test_pressure_integrates_to_force(exponent):
    contact = paper_contact(exponent, coefficient=2.0)
    depth = 1e-3
    a = float(contact.contact_radius(depth))
    r = np.linspace(0.0, a, 20001)
    p = contact.pressure(r, depth)
    # trapezoid on a sqrt edge singularity: error ~ (h/a)^1.5 = 3e-7
    force = np.trapezoid(2 * np.pi * r * p, r)
    assert force == pytest.approx(float(contact.force(depth)), rel=2e-6)
    assert np.all(p >= 0) and p[-1] == 0.0


def test_hertz_limit():
    radius = 0.01
    contact = PowerLawContact(PowerLawIndenter.sphere(radius), 1e9)
    a = 1e-3
    depth = float(contact.depth(a))
    assert depth == pytest.approx(a**2 / radius, rel=1e-15)
    assert float(contact.force(depth)) == pytest.approx(4 / 3 * 1e9 * a**3 / radius, rel=1e-14)
    p0 = 2 * 1e9 * a / (math.pi * radius)
    r = np.array([0.0, 0.5 * a, 0.9 * a])
    np.testing.assert_allclose(
        contact.pressure(r, depth), p0 * np.sqrt(1 - (r / a) ** 2), rtol=1e-14
    )


def test_cone_has_unbounded_central_pressure():
    cone = paper_contact(1.0)
    assert math.isinf(cone.central_to_mean_ratio)
    assert math.isinf(cone.pressure(0.0, 1e-3)[()])
    # logarithmic: p(r) grows without bound as r -> 0, finite elsewhere
    values = cone.pressure(np.array([1e-2, 1e-4, 1e-6]) * float(cone.contact_radius(1e-3)), 1e-3)
    assert np.all(np.isfinite(values)) and np.all(np.diff(values) > 0)


@pytest.mark.parametrize(
    ("kwargs", "name"),
    [
        ({"shape_coefficient": 0.0, "exponent": 1.5}, "shape_coefficient"),
        ({"shape_coefficient": 5.0, "exponent": -1.0}, "exponent"),
        ({"shape_coefficient": "abc", "exponent": 1.5}, "shape_coefficient"),
    ],
)
def test_bad_indenter_names_the_parameter(kwargs, name):
    with pytest.raises(InputError, match=name):
        PowerLawIndenter(**kwargs)


def test_bad_material_names_the_range():
    with pytest.raises(InputError, match=r"\(-1, 0.5\]"):
        Material(1e9, 0.6)
    with pytest.raises(InputError, match="> 0 Pa"):
        Material(-1.0, 0.3)
