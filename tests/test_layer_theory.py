"""The analytic limits of a power-law indenter on a layer (shtaerman.theory.layer).

Identity tests: each closed form against an independent computation (direct quadrature of the
foundation pressure; shooting on the thin-film equation with scipy's quad and brentq).
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from scipy.integrate import quad, solve_ivp
from scipy.optimize import brentq

from shtaerman.theory.contact import PowerLawContact
from shtaerman.theory.indenter import PowerLawIndenter
from shtaerman.theory.layer import (
    FoundationLayer,
    IncompressibleThinLayer,
    half_space_limit,
    oedometric_stiffness,
    sliding_stiffness,
    thin_layer_limit,
)
from shtaerman.theory.materials import Material
from shtaerman.validation import InputError

RUBBER = Material(7.5e6, 0.3)
INDENTERS = [
    PowerLawIndenter(5.0, 1.5),
    PowerLawIndenter(0.5 / 0.02, 2.0),
    PowerLawIndenter(3.0, 2.7),
]


def test_half_space_limit_is_shtaerman_with_plane_strain_modulus():
    indenter = PowerLawIndenter(5.0, 1.5)
    limit = half_space_limit(indenter, RUBBER)
    assert isinstance(limit, PowerLawContact)
    # E* = E / (1 - nu^2) for a rigid indenter; exact to round-off
    assert limit.modulus == pytest.approx(7.5e6 / 0.91, rel=1e-15)


def test_oedometric_stiffness_formula_and_range():
    # k = 2 mu (1 - nu)/((1 - 2 nu) H) = E (1 - nu)/((1 + nu)(1 - 2 nu) H), the constrained modulus
    k = oedometric_stiffness(RUBBER, 0.01)
    assert k == pytest.approx(7.5e6 * 0.7 / (1.3 * 0.4 * 0.01), rel=1e-14)
    with pytest.raises(InputError, match="nu2"):
        oedometric_stiffness(Material(7.5e6, 0.5), 0.01)
    with pytest.raises(InputError, match="thickness"):
        oedometric_stiffness(RUBBER, 0.0)


@pytest.mark.parametrize("indenter", INDENTERS)
def test_compressible_force_is_the_integral_of_the_foundation_pressure(indenter):
    layer = FoundationLayer(indenter, oedometric_stiffness(RUBBER, 0.002))
    depth = 1.3e-3
    a = float(layer.contact_radius(depth))
    assert indenter.profile(a) == pytest.approx(depth, rel=1e-14)  # A a^n = d
    integral, _ = quad(
        lambda r: 2 * math.pi * r * layer.pressure(r, depth), 0.0, a, epsabs=0, epsrel=1e-13
    )
    # quad of a smooth integrand: 1e-12 relative
    assert float(layer.force(depth)) == pytest.approx(integral, rel=1e-12)
    assert layer.pressure(1.01 * a, depth) == 0.0


def _film_by_shooting(layer: IncompressibleThinLayer, depth: float) -> tuple[float, float]:
    """Contact radius and force of the film equation by quadrature, independent of the closed form.

    r p'(r) = -c Int_0^r s (d - A s^n) ds (regular at the axis); the edge a is the root of
    p'(a) = 0, then p(r) = -Int_r^a p'(s) ds and P = 2 pi Int_0^a p r dr by ODE integration.
    """
    c, profile = layer.film_coefficient, layer.indenter.profile

    def slope(r: float) -> float:
        scale = 1e-14 * depth * r * r  # the flux vanishes at the edge: an absolute tolerance
        flux, _ = quad(lambda s: s * (depth - profile(s)), 0.0, r, epsabs=scale, epsrel=1e-12)
        return -c * flux / r

    a = brentq(
        slope,
        (depth / layer.indenter.shape_coefficient) ** (1 / layer.indenter.exponent),
        10 * (depth / layer.indenter.shape_coefficient) ** (1 / layer.indenter.exponent),
        xtol=1e-16,
        rtol=1e-14,
    )

    def rhs(r, y):  # y = (p, force below r) integrated from the edge inward
        return [slope(r), -2 * math.pi * r * y[0]]

    sol = solve_ivp(rhs, (a, 1e-9 * a), [0.0, 0.0], rtol=1e-11, atol=1e-30, method="DOP853")
    return a, float(sol.y[1, -1])


@pytest.mark.parametrize("indenter", INDENTERS)
def test_incompressible_closed_form_solves_the_film_equation(indenter):
    layer = IncompressibleThinLayer(indenter, 2.5e6, 0.002)
    depth = 0.8e-3
    a, force = _film_by_shooting(layer, depth)
    # brentq to 1e-14 and DOP853 at rtol 1e-11: agreement to 1e-9
    assert float(layer.contact_radius(depth)) == pytest.approx(a, rel=1e-9)
    assert float(layer.force(depth)) == pytest.approx(force, rel=1e-8)
    # zero displaced volume: Int_0^a (d - A r^n) r dr = 0
    volume, _ = quad(
        lambda r: r * (depth - indenter.profile(r)), 0.0, a, epsabs=1e-13 * depth * a**2
    )
    assert abs(volume) < 1e-12 * depth * a**2


@pytest.mark.parametrize("indenter", INDENTERS)
def test_incompressible_pressure_is_consistent(indenter):
    layer = IncompressibleThinLayer(indenter, 2.5e6, 0.002)
    depth = 0.8e-3
    a = float(layer.contact_radius(depth))
    r = np.linspace(0.0, a, 2001)
    p = layer.pressure(r, depth)
    assert p[-1] == 0.0 and np.all(np.diff(p) <= 0.0)
    n, big_a = indenter.exponent, indenter.shape_coefficient
    centre = layer.film_coefficient * big_a * n * a ** (n + 2) / (2 * (n + 2) ** 2)
    assert p[0] == pytest.approx(centre, rel=1e-12)
    integral, _ = quad(
        lambda s: 2 * math.pi * s * layer.pressure(s, depth), 0, a, epsabs=0, epsrel=1e-13
    )
    assert float(layer.force(depth)) == pytest.approx(integral, rel=1e-11)


def test_incompressible_paraboloid_is_the_classic_cubic_law():
    radius, mu, h = 0.02, 2.5e6, 0.001
    layer = IncompressibleThinLayer(PowerLawIndenter.sphere(radius), mu, h)
    depth = np.array([1e-5, 1e-4, 3e-4])
    # P = 2 pi mu R^2 d^3 / H^3 and a^2 = 4 R d (twice the geometric a^2 = 2 R d)
    assert layer.force(depth) == pytest.approx(
        2 * math.pi * mu * radius**2 * depth**3 / h**3, rel=1e-13
    )
    assert layer.contact_radius(depth) ** 2 == pytest.approx(4 * radius * depth, rel=1e-13)


def test_bad_input_names_the_parameter():
    with pytest.raises(InputError, match="thickness"):
        IncompressibleThinLayer(PowerLawIndenter(5.0, 1.5), 1e6, -1.0)
    with pytest.raises(InputError, match="depth"):
        FoundationLayer(PowerLawIndenter(5.0, 1.5), 1e9).force(-1e-3)


def test_sliding_stiffness_is_the_plane_strain_modulus_over_the_thickness():
    # k = E / ((1 - nu^2) H) = E* / H; finite at nu = 0.5 (4 mu / H)
    assert sliding_stiffness(RUBBER, 0.01) == pytest.approx(7.5e6 / (0.91 * 0.01), rel=1e-14)
    incompressible = Material(7.5e6, 0.5)
    assert sliding_stiffness(incompressible, 0.01) == pytest.approx(
        4 * incompressible.shear_modulus / 0.01, rel=1e-14
    )


def test_thin_layer_limit_picks_the_limit_of_the_base():
    indenter, h = PowerLawIndenter(5.0, 1.5), 0.01
    incompressible = Material(7.5e6, 0.5)
    film = thin_layer_limit(indenter, incompressible, h)
    assert isinstance(film, IncompressibleThinLayer)
    oedometric = thin_layer_limit(indenter, RUBBER, h, "bonded")
    assert oedometric.stiffness == oedometric_stiffness(RUBBER, h)
    sliding = thin_layer_limit(indenter, incompressible, h, "lubricated")
    assert sliding.stiffness == sliding_stiffness(incompressible, h)
    with pytest.raises(InputError, match="base: unknown base 'glued'"):
        thin_layer_limit(indenter, RUBBER, h, "glued")
