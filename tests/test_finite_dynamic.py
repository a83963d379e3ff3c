"""The finite-strain impact in time (fem/finite_dynamic.py)."""

from __future__ import annotations

import numpy as np
import pytest

from shtaerman.fem.finite_contact import solve_finite_contact
from shtaerman.fem.finite_dynamic import FiniteImpactSettings, run_finite_impact
from shtaerman.fem.hyperelastic import NeoHookean, assemble_hyperelastic
from shtaerman.fem.mesh import MeshSettings
from shtaerman.theory.indenter import PowerLawIndenter
from shtaerman.theory.materials import Material
from shtaerman.validation import InputError

INDENTER = PowerLawIndenter(5.0, 1.5)
RUBBER = Material(7.5e6, 0.5)
MASS = 0.7
COARSE = MeshSettings(size=0.15, domain=1e3, growth=0.35, axis_size=1e-3, axis_growth=0.25)
SETTINGS = FiniteImpactSettings(steps=30, mesh=COARSE)


@pytest.fixture(scope="module")
def massless():
    return run_finite_impact(INDENTER, RUBBER, 0.0, MASS, 3.0, SETTINGS)


def _static_reference(result):
    """x_max, P_max of the impact integrated on the same mesh's static curve (energy root)."""
    refined = result.mesh["refined_radius"]
    system = assemble_hyperelastic(COARSE.build(refined), NeoHookean(7.5e6, 0.5))
    depths = result.x_max * np.linspace(0.97, 1.03, 7)
    curve = solve_finite_contact(system, INDENTER, depths, refined)
    energy = np.array([s.strain_energy for s in curve.steps])
    force = np.array([s.force for s in curve.steps])
    target = 0.5 * MASS * 3.0**2
    # Pi / d^(q+1) and P / d^q are smooth: interpolate them, then solve Pi(x) = E0
    q = 5.0 / 3.0
    pi_fit = np.polyfit(depths, energy / depths ** (q + 1), 4)
    p_fit = np.polyfit(depths, force / depths**q, 4)
    x = result.x_max
    for _ in range(30):
        pi = np.polyval(pi_fit, x) * x ** (q + 1)
        x -= (pi - target) / (np.polyval(p_fit, x) * x**q)
    return x, np.polyval(p_fit, x) * x**q


def test_massless_body_is_the_impact_on_the_static_curve(massless):
    x_ref, p_ref = _static_reference(massless)
    assert massless.x_max == pytest.approx(x_ref, rel=3e-3)
    assert massless.P_max == pytest.approx(p_ref, rel=3e-3)
    # the finite-strain force is below Shtaerman's: the depth beyond the small-strain x_c
    assert massless.x_max > massless.parameters["quasi_static_x_c"]


def test_massless_body_restitution_is_one(massless):
    assert massless.restitution == pytest.approx(1.0, abs=5e-4)
    assert massless.energy_balance_error < 1e-6
    assert massless.t_contact > 0
    summary = massless.summary()
    assert {"x_max", "P_max", "t_contact", "restitution", "energy_radiated_fraction"} <= set(
        summary
    )


@pytest.mark.parametrize("density", [1100.0, -1.0, "x", True])
def test_density_other_than_zero_is_refused(density):
    with pytest.raises(InputError, match="density2"):
        run_finite_impact(INDENTER, RUBBER, density, MASS, 3.0, SETTINGS)


@pytest.mark.parametrize("steps", [5, 10.5, 10**6])
def test_bad_steps_are_refused(steps):
    with pytest.raises(InputError, match="steps"):
        FiniteImpactSettings(steps=steps)
