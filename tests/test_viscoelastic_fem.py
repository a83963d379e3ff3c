"""The dynamic FE impact without inertia in the body (density 0) and with a Prony series in
shear, against the exact quasi-static references of :mod:`shtaerman.theory`."""

import json
import math

import numpy as np
import pytest

from shtaerman.fem.dynamic_contact import DynamicSettings, run_dynamic_impact
from shtaerman.theory.contact import PowerLawContact
from shtaerman.theory.impact import solve_impact
from shtaerman.theory.indenter import PowerLawIndenter
from shtaerman.theory.materials import RIGID, Material, effective_modulus

INDENTER = PowerLawIndenter(5.0, 1.5)
RUBBER = Material(7.5e6, 0.5)
MASS, VELOCITY = 0.7, 3.0
COARSE = DynamicSettings(steps=100, size=0.05)


@pytest.fixture(scope="module")
def massless():
    return run_dynamic_impact(INDENTER, RUBBER, 0.0, MASS, VELOCITY, COARSE)


def test_massless_body_gives_the_quasi_static_impact(massless):
    """No inertia in the body: the elastic quasi-static impact, to the FE's static error."""
    law = PowerLawContact(INDENTER, effective_modulus(RIGID, RUBBER))
    exact = solve_impact(MASS, VELOCITY, law)
    assert massless.x_max == pytest.approx(exact.x_c, rel=3e-4)
    assert massless.P_max == pytest.approx(exact.P_c, rel=1e-3)
    assert massless.t_contact == pytest.approx(exact.t_y, rel=3e-4)
    assert massless.restitution == pytest.approx(1.0, abs=1e-6)
    assert abs(massless.energy_radiated_fraction) < 1e-6
    assert massless.reflected_energy_fraction == 0.0
    assert math.isinf(massless.parameters["shear_wave_speed"])


def test_massless_energy_account_closes(massless):
    energies, e0 = massless.energies, 0.5 * MASS * VELOCITY**2
    assert np.all(energies["body_kinetic"] == 0.0) and np.all(energies["absorbed"] == 0.0)
    stored = energies["striker_kinetic"] + energies["strain"]
    assert np.max(np.abs(stored - e0)) / e0 < 1e-3
    assert massless.energy_balance_error < 1e-3


def test_cli_and_study_file_take_density_zero(capsys, tmp_path):
    from shtaerman.cli import main
    from shtaerman.study.schema import load_study

    argv = ["dynamic", "--density2", "0", "--no-estimate", "--json", "--time-steps", "50"]
    assert main([*argv, "--mesh-size", "0.1"]) == 0
    report = json.loads(capsys.readouterr().out)
    assert report["radiation_estimate"]["energy_fraction"] == 0.0
    assert report["dynamic"]["restitution"] == pytest.approx(1.0, abs=1e-5)
    assert report["dynamic"]["reflected_energy_fraction"] == 0.0
    path = tmp_path / "massless.toml"
    path.write_text(STUDY.replace("density2 = 1100.0", "density2 = 0"))
    [study] = load_study(path)
    assert study.density == 0.0
    assert main(["dynamic", "--density2", "1e-7"]) == 2
    assert "--density2 must lie in [1e-6, 1e6] or 0 kg/m^3" in capsys.readouterr().err


STUDY = """\
kind = "dynamic"
[indenter]
shape_coefficient = 5.0
exponent = 1.5
[half_space]
E2 = 7.5e6
nu2 = 0.5
density2 = 1100.0
[impact]
mass = 0.7
velocity = [1.0, 3.0]
figure_velocity = 3.0
"""
