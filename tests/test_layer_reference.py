"""The Hankel-transform reference of a layer on a rigid base, and the FE against it.

The reference (:mod:`shtaerman.theory.layer_reference`) is checked by its own limits: the
compliance factor K(t) against the half-space and the three thin-layer foundations of
:mod:`shtaerman.theory.layer`, the contact against Shtaerman's force at large H and the thin
laws at small H. The full FE table is ``benchmarks/layer_reference.py``.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from shtaerman.fem.mesh import Geometry, MeshSettings
from shtaerman.study.contact.indentation import run_indentation
from shtaerman.theory.indenter import PowerLawIndenter
from shtaerman.theory.layer import half_space_limit, thin_layer_limit
from shtaerman.theory.layer_reference import (
    LayerReference,
    compliance_factor,
    layer_contact,
    thick_layer_coefficient,
)
from shtaerman.theory.materials import Material
from shtaerman.validation import InputError

RADIUS = 0.01
COARSE = 1.0 / 60.0


def _case(n: float, nu: float) -> tuple[PowerLawIndenter, Material, float]:
    indenter = PowerLawIndenter(5e-3 / RADIUS**n, n)
    body = Material(7.5e6, nu)
    return indenter, body, float(half_space_limit(indenter, body).depth(RADIUS))


@pytest.mark.parametrize("base", ["bonded", "lubricated"])
@pytest.mark.parametrize("nu", [0.0, 0.3, 0.45, 0.5])
def test_compliance_factor_tends_to_the_half_space(base, nu):
    k = compliance_factor([10.0, 40.0, 1e6], nu, base)
    assert abs(k[0] - 1.0) < 1e-6 and k[1] == 1.0 and k[2] == 1.0


@pytest.mark.parametrize(
    ("nu", "base", "power", "slope"),
    [
        (0.3, "bonded", 1, 0.4 / (2 * 0.49)),  # oedometric: (1 - 2 nu) / (2 (1 - nu)^2)
        (0.45, "bonded", 1, 0.1 / (2 * 0.3025)),
        (0.5, "bonded", 3, 2.0 / 3.0),  # thin film: w = -(H^3 / 3 mu) lap p
        (0.3, "lubricated", 1, 0.5),  # sliding: k = E* / H
        (0.5, "lubricated", 1, 0.5),
    ],
)
def test_compliance_factor_gives_the_thin_layer_foundations(nu, base, power, slope):
    """w = (2/E*) Int p~ K J0: K ~ c t^m is the foundation of theory.layer (c from its k)."""
    t = np.array([1e-3, 1e-4])
    ratio = compliance_factor(t, nu, base) / t**power
    assert ratio[1] == pytest.approx(slope, rel=1e-6)
    assert abs(ratio[0] / slope - 1.0) > abs(ratio[1] / slope - 1.0)  # approached, not fitted


def test_compliance_factor_foundations_match_theory_layer():
    """The slopes above are the stiffnesses of theory.layer: k = E* / (2 c H)."""
    body = Material(7.5e6, 0.35)
    e_star = body.youngs_modulus / (1 - 0.35**2)
    for base, t in (("bonded", 1e-5), ("lubricated", 1e-5)):
        k = float(compliance_factor(t, 0.35, base)) / t
        limit = thin_layer_limit(PowerLawIndenter(5.0, 1.5), body, 0.002, base)
        assert e_star / (2 * k * 0.002) == pytest.approx(limit.stiffness, rel=1e-4)


def test_reference_converges_with_its_quadrature():
    coarse = layer_contact(0.07, 1.7, 0.4, "bonded", resolution=0.5)
    fine = layer_contact(0.07, 1.7, 0.4, "bonded", resolution=1.5)
    assert coarse.force == pytest.approx(fine.force, rel=1e-9)
    assert coarse.depth == pytest.approx(fine.depth, rel=1e-9)
    assert fine.phi_slope < 1e-12  # phi decreasing: the pressure is >= 0 everywhere


@pytest.mark.parametrize("base", ["bonded", "lubricated"])
def test_thick_layer_is_shtaerman_and_approaches_as_a_over_h(base):
    indenter, body, depth = _case(1.8, 0.35)
    half = float(half_space_limit(indenter, body).force(depth))
    huge = LayerReference(indenter, body, 1e6 * RADIUS, base)
    assert huge.force(depth) == pytest.approx(half, rel=1e-6)
    # the first-order rate C a / H, C = (2/pi) Int (1 - K)
    thick = LayerReference(indenter, body, 1e3 * RADIUS, base)
    excess = (thick.force(depth) / half - 1.0) * thick.thickness / thick.contact_radius(depth)
    assert excess == pytest.approx(thick_layer_coefficient(0.35, base), rel=2e-3)


@pytest.mark.parametrize(("nu", "base"), [(0.3, "bonded"), (0.4, "lubricated")])
def test_thin_layer_is_the_foundation(nu, base):
    indenter, body, depth = _case(1.6, nu)
    ratios = []
    for h_over_a in (0.2, 0.05):
        thickness = h_over_a * RADIUS
        law = float(thin_layer_limit(indenter, body, thickness, base).force(depth))
        ratios.append(LayerReference(indenter, body, thickness, base).force(depth) / law)
    assert abs(ratios[1] - 1.0) < 5e-4
    assert abs(ratios[1] - 1.0) < abs(ratios[0] - 1.0) / 8  # faster than (H/a)^1.5


def test_reference_refuses_bad_input():
    indenter, body, _ = _case(1.5, 0.3)
    with pytest.raises(InputError, match="thickness must be > 0 m"):
        LayerReference(indenter, body, 0.0)
    with pytest.raises(InputError, match="base: unknown base"):
        LayerReference(indenter, body, 0.01, "glued")
    with pytest.raises(InputError, match="exponent must be > 1"):
        LayerReference(PowerLawIndenter(5.0, 1.0), body, 0.01)
    with pytest.raises(InputError, match="depth must be > 0 m"):
        LayerReference(indenter, body, 0.01).force(-1e-3)
    with pytest.raises(InputError, match=r"thickness: the layer reference needs H >= 0\.01"):
        LayerReference(indenter, body, 1e-9).force(1e-3)  # would need ~1e13 quadrature nodes
    with pytest.raises(InputError, match=r"h: H / a must be >= 0\.01"):
        layer_contact(1e-4, 1.5, 0.3)
    with pytest.raises(InputError, match="t must be finite"):
        compliance_factor([math.nan], 0.3)


@pytest.mark.parametrize(
    ("n", "nu", "base", "h_over_a", "tolerance"),
    [
        # coarse mesh (size 1/60): measured -7.7e-5 and -1.3e-5 here; the default mesh is
        # within 5e-5 of the reference on twelve cases (benchmarks/layer_reference.py), and
        # 2e-4 is far below the 0.5 % acceptance while still failing a wrong kernel or base
        (1.65, 0.37, "lubricated", 0.6, 2e-4),
        (1.9, 0.43, "bonded", 4.0, 2e-4),
    ],
)
def test_fe_force_agrees_with_the_reference(n, nu, base, h_over_a, tolerance):
    indenter, body, depth = _case(n, nu)
    thickness = h_over_a * RADIUS
    settings, layer = MeshSettings(size=COARSE), Geometry(thickness, base)
    force = run_indentation(indenter, body, np.array([depth]), settings, geometry=layer)
    force = force.steps[-1].force
    reference = LayerReference(indenter, body, thickness, base).force(depth)
    assert force == pytest.approx(reference, rel=tolerance)
