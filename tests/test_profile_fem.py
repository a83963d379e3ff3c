"""The FEM contact curve of a sphere and of a tabulated profile (issue 29 item 1): the gap is
the profile's, the reference Sneddon's; other routes refuse the profile in one line."""

import numpy as np
import pytest

import shtaerman as sh
from shtaerman.problem import support_table
from shtaerman.theory.contact import PowerLawContact

RUBBER = sh.Material(7.5e6, 0.5)
RADIUS = 0.01
DEPTHS = [1e-3, 2e-3, 3e-3]  # down to x/R = 0.3, where the sphere is 3 % below Hertz


@pytest.fixture(scope="module")
def curves():
    """The default mesh (no ladder): the sphere, and the paraboloid of the same radius."""
    sphere = sh.contact(sh.SphereIndenter(RADIUS), RUBBER, depths=DEPTHS, estimate=False)
    hertz = sh.PowerLawIndenter.sphere(RADIUS)
    paraboloid = sh.contact(hertz, RUBBER, depths=DEPTHS, estimate=False)
    return sphere, paraboloid


def test_the_fem_sphere_matches_sneddon_as_the_paraboloid_matches_hertz(curves):
    sphere, paraboloid = curves
    # measured at this mesh: sphere 9.09e-5 against Sneddon, paraboloid 9.12e-5 against Hertz
    assert sphere.errors["force"] < 1e-4
    assert sphere.errors["force"] < 1.2 * paraboloid.errors["force"]
    assert sphere.errors["beta"] < 1.2 * paraboloid.errors["beta"]
    assert sphere.errors["central_pressure"] < 1.2 * paraboloid.errors["central_pressure"]
    # and it is the sphere the FEM pressed: 3.0 % below Hertz's paraboloid at x = 0.3 R
    hertz = PowerLawContact(sh.PowerLawIndenter.sphere(RADIUS), 1e7)
    assert sphere.force[-1] / float(hertz.force(DEPTHS[-1])) - 1 == pytest.approx(-0.030, abs=1e-3)
    assert sphere.to_dict()["profile"] == {"kind": "sphere", "parameters": {"radius": RADIUS}}


def test_a_tabulated_paraboloid_is_the_power_law_in_the_fem(curves, tmp_path):
    _, paraboloid = curves
    r = np.linspace(0.0, 0.02, 81)
    path = tmp_path / "tip.csv"
    np.savetxt(path, np.c_[r, r**2 / (2 * RADIUS)], delimiter=",", header="r,z", comments="")
    table = sh.contact(sh.TabulatedIndenter.from_csv(path), RUBBER, depths=DEPTHS, estimate=False)
    # the same gap to round-off, the same mesh up to the round-off of its radius
    np.testing.assert_allclose(table.force, paraboloid.force, rtol=1e-9)
    assert table.beta_analytic == pytest.approx(paraboloid.beta_analytic, rel=1e-12)


def test_a_profile_builds_every_problem_the_power_law_builds():
    """The support matrix holds for every striker: no refusal names the profile."""
    ball = sh.SphereIndenter(RADIUS)
    problem = sh.Problem.impact(
        ball, sh.Material(7.5e6, 0.5, 1100.0), mass=0.7, velocity=3.0, prony="0.3:1e-3"
    )
    assert problem.striker.indenter == ball and problem.body.prony is not None
    reasons = [verdict for _, verdict in support_table() if verdict != "runs"]
    assert not any(reason.startswith(("profile", "sphere_radius")) for reason in reasons)


def test_a_contact_beyond_the_table_is_refused_before_the_fem(monkeypatch):
    import shtaerman.study.contact.indentation as indentation

    def no_fem(*args, **kwargs):
        raise AssertionError("the FEM ran")

    monkeypatch.setattr(indentation, "run_indentation", no_fem)
    r = np.linspace(0.0, 2e-3, 21)  # to r = 2 mm: in contact from x = 0.4 mm (x = a^2/R)
    table = sh.TabulatedIndenter(r, r**2 / (2 * RADIUS))
    # the given depths are named, as a study file and a sweep case name them
    with pytest.raises(sh.InputError, match=r"^depths: depth 0.001 m reaches beyond the table"):
        sh.contact(table, RUBBER, depths=[1e-3], estimate=False)
    with pytest.raises(sh.InputError, match=r"^profile: the striker's energy .* beyond the table"):
        sh.impact(table, RUBBER, mass=0.7, velocity=3.0)


def test_a_tabulated_paraboloid_on_a_layer_is_the_power_law():
    hertz = sh.PowerLawIndenter.sphere(1.0)
    r = np.linspace(0.0, 0.05, 101)
    layer = {"depths": [1e-4, 2e-4], "thickness": 0.005, "estimate": False}
    power_law = sh.contact(hertz, RUBBER, **layer)
    table = sh.contact(sh.TabulatedIndenter(r, hertz.profile(r)), RUBBER, **layer)
    # the same refined zone (the tip's n = 2 bulge) and gap: the same numbers (measured: equal)
    np.testing.assert_allclose(table.force, power_law.force, rtol=1e-12)
    assert table.to_dict()["mesh"]["thickness"] == 0.005


def test_a_profile_at_finite_strain():
    r = np.linspace(0.0, 0.02, 81)
    hertz = sh.PowerLawIndenter.sphere(RADIUS)
    rubber = {"depths": DEPTHS, "model": "neo-hookean", "estimate": False}
    power_law = sh.contact(hertz, RUBBER, **rubber)
    table = sh.contact(sh.TabulatedIndenter(r, hertz.profile(r)), RUBBER, **rubber)
    # the gap, its slope and curvature of a tabulated paraboloid are the power law's to
    # round-off, and so is Newton's answer (measured 3e-14)
    np.testing.assert_allclose(table.force, power_law.force, rtol=1e-11)
    sphere = sh.contact(sh.SphereIndenter(RADIUS), RUBBER, **rubber)
    linear = np.array([step["force_analytic"] for step in sphere.steps])
    hertz_linear = np.array([step["force_analytic"] for step in power_law.steps])
    # finite strain softens both alike at x = 0.1 R: -2.02 % (sphere, against Sneddon) and
    # -1.97 % (paraboloid, against Hertz), measured; the sphere's profile is what differs
    assert sphere.force[0] / linear[0] - 1 == pytest.approx(
        power_law.force[0] / hertz_linear[0] - 1, abs=2e-3
    )
    assert sphere.to_dict()["profile"]["kind"] == "sphere"
