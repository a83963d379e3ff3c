"""The finite-strain impact (massless and with inertia) of a sphere and of a tabulated profile
(issue 29): its scales and its quasi-static reference are the profile's exact impact
(Sneddon's law by quadrature), its gap, slope and curvature the profile's.

Coarse: the mesh of tests/test_finite_dynamic_inertia.py (2.4k dofs) and 20 steps per t_y.
"""

import numpy as np
import pytest

import shtaerman as sh
from shtaerman.fem.finite_dynamic import FiniteImpactSettings
from shtaerman.fem.impact import run_impact
from shtaerman.fem.mesh import MeshSettings

RUBBER = sh.Material(7.5e6, 0.5)
RADIUS = 0.01
COARSE = MeshSettings(size=0.25, domain=1e3, growth=0.5, axis_size=1e-3, axis_growth=0.25)
SETTINGS = FiniteImpactSettings(steps=20, mesh=COARSE)
COMPARED = ("x_max", "P_max", "t_x_max", "t_contact", "restitution")


@pytest.mark.parametrize("density", [0.0, 1100.0])
def test_a_tabulated_paraboloid_is_the_power_law_n_2_at_finite_strain(density):
    r = np.linspace(0.0, 0.05, 201)
    table = sh.TabulatedIndenter(r, r**2 / (2 * RADIUS))
    hertz = sh.PowerLawIndenter.sphere(RADIUS)
    power_law = run_impact(hertz, RUBBER, density, 0.7, 1.0, SETTINGS)
    tabulated = run_impact(table, RUBBER, density, 0.7, 1.0, SETTINGS)
    # the same mesh: the refined radius from the quadrature's x_c differs in the last bit only
    assert tabulated.mesh == pytest.approx(power_law.mesh, rel=1e-15)
    # the gap, its slope and curvature are the power law's to round-off; the time step
    # differs by the quadrature's t_y (3e-12 of the closed form's): measured <= 7e-14
    for key in COMPARED:
        assert getattr(tabulated, key) == pytest.approx(getattr(power_law, key), rel=1e-12), key
    assert tabulated.parameters["shape_coefficient"] is None


def test_finite_strain_softens_the_sphere_as_the_paraboloid():
    """Massless, at 1 m/s: x = 0.34 R, where Sneddon's sphere is 2 % softer than Hertz."""
    departures = {}
    for indenter in (sh.SphereIndenter(RADIUS), sh.PowerLawIndenter.sphere(RADIUS)):
        run = run_impact(indenter, RUBBER, 0.0, 0.7, 1.0, SETTINGS)
        exact = sh.impact(indenter, RUBBER, mass=0.7, velocity=1.0)  # each its own reference
        departures[indenter.kind] = (run.x_max / exact.x_c - 1, run.P_max / exact.P_c - 1)
    sphere, paraboloid = departures["sphere"], departures["power-law"]
    # finite strain: x_max +1.27 % (sphere, against Sneddon) and +1.20 % (paraboloid, against
    # Hertz), P_max -1.66 % and -1.35 %, measured; a profile's own reference leaves the two
    # alike to 0.3 % (against Hertz the sphere's force would be 2 % further off)
    assert sphere[0] == pytest.approx(paraboloid[0], abs=2e-3)
    assert sphere[1] == pytest.approx(paraboloid[1], abs=5e-3)
    assert 0.005 < sphere[0] < 0.02  # the rubber's softening is there


def test_the_problem_takes_a_sphere_at_finite_strain_elastic_or_relaxing():
    ball = sh.SphereIndenter(RADIUS)
    impact = sh.Problem.impact(ball, RUBBER, mass=0.7, velocity=1.0, model="neo-hookean")
    assert impact.cell.model == "rubber" and not impact.cell.relaxing
    relaxing = sh.Problem.impact(
        ball, RUBBER, mass=0.7, velocity=1.0, model="neo-hookean", prony="0.3:1e-3"
    )
    assert relaxing.cell.relaxing and relaxing.striker.indenter == ball
