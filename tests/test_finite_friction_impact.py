"""Friction in the finite-strain impact (fem/finite_dynamic.py with
fem/contact/finite_stick.HistoryStepper): a bonded (no slip) or Coulomb indenter strikes a
rubber body.

Each time step is one load step of the bonded or Coulomb contact from the contact committed at
the end of the last step, so the slip history is the impact's own. The striker then steps by
the trapezoidal rule (the contact has no stored energy function of X), as a relaxing body does.
"""

from __future__ import annotations

import json
import math

import numpy as np
import pytest

import shtaerman as sh
import shtaerman.fem.stepper as stepper
from shtaerman.cli import main
from shtaerman.fem.finite_dynamic import FiniteImpactSettings
from shtaerman.fem.impact import run_impact
from shtaerman.fem.mesh import Geometry, MeshSettings
from shtaerman.problem import Problem
from shtaerman.theory.indenter import PowerLawIndenter
from shtaerman.theory.materials import Material
from shtaerman.theory.viscoelastic import PronySeries

INDENTER = PowerLawIndenter(5.0, 1.5)
RUBBER = Material(7.5e6, 0.5)
MASS, VELOCITY = 0.7, 1.0
"""x_c / a_c = 0.43 at 1 m/s: finite strain couples friction to the normal contact (at small
strain and nu = 0.5 it does not: Dundurs' beta = 0)."""
COARSE = MeshSettings(size=0.25, domain=1e3, growth=0.5, axis_size=1e-3, axis_growth=0.25)
SETTINGS = FiniteImpactSettings(steps=30, mesh=COARSE)


def _run(friction, density=0.0, settings=SETTINGS):
    return run_impact(INDENTER, RUBBER, density, MASS, VELOCITY, settings, friction=friction)


@pytest.fixture(scope="module")
def bonded():
    return _run(math.inf)


@pytest.fixture(scope="module")
def frictionless_trapezoidal():
    """The frictionless run stepped by the trapezoidal rule, as the frictional runs are (the
    frictionless body's own discrete gradient differs from it by O(dt^2) ~ 1e-3 here, more
    than the friction's effect)."""
    with pytest.MonkeyPatch.context() as patch:
        patch.setattr(stepper, "_discrete_gradient", stepper._mean_force)
        return _run(None)


def _until_peak(run):
    k = int(np.argmax(run.x))
    return run.x[: k + 1], run.force[: k + 1]


def test_a_large_coefficient_is_the_bonded_indenter(bonded):
    """mu = 1e3 never lets a node slide: the Coulomb route gives the bonded run's history, to
    the Newton tolerance (1e-8 of the depth) that both solve to."""
    coulomb = _run(1e3)
    assert coulomb.t.size == bonded.t.size
    assert np.max(np.abs(coulomb.x - bonded.x)) < 1e-7 * bonded.x_max
    assert np.max(np.abs(coulomb.force - bonded.force)) < 1e-6 * bonded.P_max
    assert coulomb.energies["dissipated"][-1] < 1e-9 * 0.5 * MASS * VELOCITY**2


def test_a_vanishing_coefficient_is_the_frictionless_indenter(bonded, frictionless_trapezoidal):
    """mu = 1e-4: every node slides almost freely; up to x_max the history is the frictionless
    one within 1e-4 x_max, where the bonded indenter moves it by more than 1e-3 x_max."""
    x_free, p_free = _until_peak(frictionless_trapezoidal)
    x_slip, p_slip = _until_peak(_run(1e-4))
    x_bond, _ = _until_peak(bonded)
    n = min(x_free.size, x_slip.size, x_bond.size)
    slip_off = np.max(np.abs(x_slip[:n] - x_free[:n])) / x_free.max()
    bonded_off = np.max(np.abs(x_bond[:n] - x_free[:n])) / x_free.max()
    assert slip_off < 1e-4 < 1e-3 < bonded_off
    assert np.max(np.abs(p_slip[:n] - p_free[:n])) < 1e-3 * p_free.max()


def test_the_bonded_impact_is_stiffer_and_keeps_its_energy(bonded, frictionless_trapezoidal):
    """At finite strain the bonded indenter holds the surface from sliding inwards: a shallower,
    harder impact than the frictionless one. No node slides, so nothing is dissipated and the
    account closes to the trapezoidal rule's own O(dt^2) error (2.5e-3 at 30 steps for the
    frictionless run on the same mesh)."""
    assert bonded.x_max < frictionless_trapezoidal.x_max
    assert bonded.P_max > frictionless_trapezoidal.P_max
    assert bonded.energies["dissipated"][-1] == 0.0
    assert bonded.energy_balance_error < 5e-3
    assert bonded.restitution == pytest.approx(1.0, abs=1e-3)


def test_coulomb_friction_dissipates_and_lies_between(bonded, frictionless_trapezoidal):
    """mu = 0.3: some nodes slide against friction, which takes energy (> 0); its x_max lies
    between the frictionless and the bonded ones."""
    coulomb = _run(0.3)
    assert coulomb.energies["dissipated"][-1] > 0.0
    assert bonded.x_max <= coulomb.x_max <= frictionless_trapezoidal.x_max
    assert coulomb.energy_balance_error < 5e-3


def test_the_problem_with_friction_runs_from_the_api_and_the_cli(capsys):
    """The Problem no longer refuses a bonded or Coulomb rubber impact; the API and the CLI
    give the same numbers, and the result names the interface."""
    problem = Problem.impact(
        INDENTER,
        Material(7.5e6, 0.5, density=0.0),
        mass=MASS,
        velocity=VELOCITY,
        model="neo-hookean",
        interface="bonded",
        friction=0.3,
    )
    # one run a route, no error-estimate ladder (the bar of a frictional rubber impact:
    # test_the_massless_relaxing_pad_with_friction_runs_with_its_error_bar), on the ladder's
    # coarsest mesh (refine 0.5: 2.2k dofs, 3 CPU s a route, not 6.7k and 12 s); its slip
    # work, 2.7e-5 of E0 (2.4e-6 at refine 1), is > 0 on both meshes
    result = sh.dynamic(problem, mesh_size=0.2, time_steps=50, refine=0.5, estimate=False)
    assert result.parameters["interface"] == "bonded"
    assert result.parameters["friction"] == 0.3
    assert result.energy_dissipated_fraction > 0.0
    argv = ["dynamic", "--model", "neo-hookean", "--density2", "0", "--velocity", "1"]
    argv += ["--interface", "bonded", "--friction", "0.3", "--mesh-size", "0.2"]
    argv += ["--time-steps", "50", "--refine", "0.5", "--no-estimate", "--json"]
    assert main(argv) == 0
    report = json.loads(capsys.readouterr().out)
    assert report["dynamic"]["x_max"] == result.dynamic["x_max"]
    assert report["parameters"]["friction"] == 0.3


def test_the_api_checks_the_time_steps_as_the_cli_does():
    """sh.dynamic(model=...) ran 20 time steps where --time-steps refuses below 50."""
    from shtaerman.validation import InputError

    problem = Problem.impact(
        INDENTER, Material(7.5e6, 0.5, density=0.0), mass=MASS, velocity=1.0, model="neo-hookean"
    )
    with pytest.raises(InputError, match=r"time_steps must be an integer in \[50, 5000\]"):
        sh.dynamic(problem, time_steps=20)


@pytest.mark.parametrize("friction", [math.inf, 0.5])
def test_a_frictional_impact_on_a_pad_beyond_the_reach_is_refused_before_any_work(friction):
    """Issue 28: the researcher's full case with z = 8 r^1.3 (pad 12 mm, Prony, Coulomb 0.5,
    inertia) failed at separation after 15 minutes (x/a 2.26, beyond the 1.2 that a frictional
    finite-strain contact converges to). The relaxing half-space's quasi-static depth
    bounds the relaxing pad's (x/a 2.32 here; the elastic x_c's 2.27), so the run is refused at
    once, naming velocity (relax64: 0.0278 m/s, where the relaxing body's depth reaches the
    reach; it runs with inertia) and the frictionless alternative; the same striker without
    friction still runs on the pad (with a warning)."""
    from shtaerman.validation import InputError

    settings = FiniteImpactSettings(mesh=MeshSettings())
    with pytest.raises(InputError, match=r"2\.32.*interface='frictionless'") as refused:
        run_impact(
            PowerLawIndenter(8.0, 1.3), Material(3e6, 0.49), 1000.0, 0.12, 1.5, settings,
            prony=PronySeries.parse("0.3:1e-3"), friction=friction, geometry=Geometry(0.012),
        )  # fmt: skip
    assert refused.value.parameter == "velocity"


@pytest.mark.parametrize("friction", [None, "0.5"])
def test_the_massless_relaxing_pad_with_friction_runs_with_its_error_bar(friction, capsys):
    """Issue 28: the researcher's full case without inertia (z = 2.011 r^1.3 on a 12 mm pad,
    Prony 0.3:1e-3, bonded or Coulomb 0.5) failed near separation ("Newton ... at 0.49 mm" of
    a 3.46 mm approach, also with 8 times the time steps): the surface, still recovering, lets
    the stuck nodes at the axis go at once, and on the static contact's axis grading (1e-6 of
    the refined radius) the damped Newton halved its updates to nothing. On the impact's
    grading (1e-3) every level of the ladder runs, and every headline number has its bar.
    Run at refine 0.7 (mesh size 0.2 / 0.7, 1.9k dofs, 12 CPU s; at refine 1: 3.9k dofs, 22
    CPU s) with 72 steps asked, so the levels keep refine 1's 25, 35, 50 time steps per t_y."""
    argv = ["dynamic", "--exponent", "1.3", "--shape-coefficient", "2.011", "--E2", "3e6"]
    argv += ["--nu2", "0.49", "--mass", "0.12", "--velocity", "1.5", "--density2", "0"]
    argv += ["--model", "neo-hookean", "--thickness", "0.012", "--prony", "0.3:1e-3"]
    argv += ["--interface", "bonded", "--mesh-size", "0.2", "--json"]
    argv += ["--refine", "0.7", "--time-steps", "72"]
    assert main([*argv, *(("--friction", friction) if friction else ())]) == 0
    report = json.loads(capsys.readouterr().out)
    dynamic, errors = report["dynamic"], report["error_estimate"]
    assert {"x_max", "P_max", "t_contact", "restitution"} <= set(errors)
    # measured (Coulomb 0.5) errors 9.2e-4 (x_max) to 1.2e-2 (P_max) of the value on this
    # coarse mesh (1.5e-3 to 6.4e-3 at refine 1): a bar of the mesh and time step, not the 0
    # or nan of a missing level
    assert all(1e-5 < errors[key] < 3e-2 for key in ("x_max", "P_max", "t_contact"))
    # the relaxing pad rebounds slower than the elastic one (e ~ 1): measured 0.821 (refine
    # 0.7 and 1 alike)
    assert 0.75 < dynamic["restitution"] < 0.9


def test_a_fast_impact_is_refused_before_work_in_one_line(capsys):
    """Issue 28: the full case with inertia at 30 m/s (x/a 1.19 on the half-space: inside the
    reach; 0.95 of the shear wave speed, 31.7 m/s) printed "exceeds 5 m/s" six times before
    its error, then once beside a failure at its first step. Since session 59 a rubber with
    inertia is held to the wave-speed limit: refused before any work, in one line naming a
    density2 and a velocity that pass, and no warning before it."""
    argv = ["dynamic", "--exponent", "1.3", "--shape-coefficient", "2.011", "--E2", "3e6"]
    argv += ["--nu2", "0.49", "--mass", "0.12", "--velocity", "30", "--density2", "1000"]
    argv += ["--model", "neo-hookean", "--thickness", "0.012", "--prony", "0.3:1e-3"]
    argv += ["--interface", "bonded", "--friction", "0.5", "--mesh-size", "0.1"]
    assert main(argv) == 2
    err = capsys.readouterr().err
    assert err.count("error:") == 1 and len(err.strip().splitlines()) == 1, err
    assert "shear wave speed" in err and "velocity 9.98 m/s would pass" in err
