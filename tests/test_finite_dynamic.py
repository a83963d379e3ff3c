"""The finite-strain impact in time (fem/finite_dynamic.py)."""

from __future__ import annotations

import numpy as np
import pytest

from shtaerman.fem.contact.finite import solve_finite_contact
from shtaerman.fem.dynamic_contact import DynamicSettings
from shtaerman.fem.finite_dynamic import FiniteImpactSettings
from shtaerman.fem.hyperelastic import NeoHookean, assemble_hyperelastic
from shtaerman.fem.impact import run_impact
from shtaerman.fem.mesh import HALF_SPACE, Geometry, MeshSettings
from shtaerman.fem.rubber import RubberModel
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
    return run_impact(INDENTER, RUBBER, 0.0, MASS, 3.0, SETTINGS)


def _static_reference(result, mesh=COARSE, geometry=HALF_SPACE):
    """x_max, P_max of the impact integrated on the same mesh's static curve (energy root)."""
    refined = result.mesh["refined_radius"]
    system = assemble_hyperelastic(mesh.build(refined, geometry), NeoHookean(7.5e6, 0.5))
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


PAD = Geometry(0.02)  # the paper's striker on a 20 mm pad, bonded base


@pytest.fixture(scope="module")
def pad():
    return run_impact(INDENTER, RUBBER, 0.0, MASS, 3.0, SETTINGS, geometry=PAD)


def test_massless_pad_is_the_impact_on_its_own_static_curve(pad, massless):
    x_ref, p_ref = _static_reference(pad, COARSE, PAD)
    assert pad.x_max == pytest.approx(x_ref, rel=3e-3)
    assert pad.P_max == pytest.approx(p_ref, rel=3e-3)
    assert pad.restitution == pytest.approx(1.0, abs=5e-4)
    # a pad on a rigid base is stiffer than the half-space: shallower, harder impact
    assert pad.x_max < 0.9 * massless.x_max and pad.P_max > 1.2 * massless.P_max
    assert (pad.mesh["thickness"], pad.mesh["base"]) == (0.02, "bonded")


def test_a_pad_with_inertia_keeps_its_waves_and_closes_its_energy(pad):
    coarse = MeshSettings(size=0.25, domain=1e3, growth=0.5, axis_size=1e-3, axis_growth=0.25)
    runs = [
        run_impact(
            INDENTER,
            RUBBER,
            1100.0,
            MASS,
            3.0,
            FiniteImpactSettings(steps, coarse),
            geometry=PAD,
        )
        for steps in (30, 60)
    ]
    balance = [abs(run.energy_balance_error) for run in runs]
    # the waves ring in the pad; what the balance misses is the scheme's second-order error in
    # dt (ratio 4 for halved steps; first order would give 2), not a leak
    assert balance[0] / balance[1] > 3.0 and balance[1] < 3e-3
    run = runs[1]
    # the waves stay in a pad 2 a_c thick on a rigid base and return to the striker: the
    # linear dynamic pad's e is 0.99994 at H / a_c = 2 (benchmarks/FEM_NOTES.md, "Layer
    # restitution map"); the half-space's 0.93
    assert run.restitution > 0.999
    assert run.x_max == pytest.approx(pad.x_max, rel=1e-2)  # inertia alone moves it little


def test_massless_body_restitution_is_one(massless):
    assert massless.restitution == pytest.approx(1.0, abs=5e-4)
    assert massless.energy_balance_error < 1e-6
    assert massless.t_contact > 0
    summary = massless.summary()
    assert {"x_max", "P_max", "t_contact", "restitution", "energy_radiated_fraction"} <= set(
        summary
    )


@pytest.mark.parametrize("density", [1e7, -1.0, "x", True])
def test_density_out_of_range_is_refused(density):
    with pytest.raises(InputError, match="density2"):
        run_impact(INDENTER, RUBBER, density, MASS, 3.0, SETTINGS)


def test_one_driver_chooses_the_body_by_the_settings(massless):
    """run_impact (fem/impact.py) runs the finite-strain body for FiniteImpactSettings (the
    Newton iterations it reports; the linear body reports a contact radius history instead)
    and refuses a rubber with the linear body's settings before meshing anything."""
    assert massless.newton_iterations > 0 and massless.contact_radius is None
    with pytest.raises(TypeError, match="a rubber takes FiniteImpactSettings"):
        run_impact(INDENTER, RUBBER, 0.0, MASS, 3.0, DynamicSettings(), RubberModel())


@pytest.mark.parametrize("steps", [5, 10.5, 10**6])
def test_bad_steps_are_refused(steps):
    with pytest.raises(InputError, match="steps"):
        FiniteImpactSettings(steps=steps)


def _run(capsys, *argv):
    from shtaerman.cli import main

    code = main(list(argv))
    captured = capsys.readouterr()
    return code, captured.out, captured.err


@pytest.mark.parametrize(
    ("argv", "message"),
    [
        (("--model", "neo-hookean", "--density2", "1e7"), "density2 must lie in [1e-6, 1e6]"),
        (("--mooney-ratio", "0.3"), "--mooney-ratio: applies to the finite-strain models only"),
        (("--model", "neo-hookean", "--layer-rate", "1"), "--layer-rate: not supported"),
        (
            ("--model", "neo-hookean", "--time-steps", "50", "--refine", "0.7"),
            "--time-steps: the er",
        ),
        (
            ("--model", "neo-hookean", "--time-steps", "200", "--refine", "0.5"),
            "--refine must be >= 0.6",
        ),
        (("--model", "yeoh", "--mooney-ratio", "0.3"), "--mooney-ratio: applies to the mooney"),
        (("--model", "neo-hookean", "--prony", "0.5"), "--prony:"),
        (("--model", "yeoh", "--prony", "0.7:1e-3,0.4:1e-2"), "--prony:"),
        (("--model", "neo-hookean", "--thickness", "0.02", "--base", "lubricated"), "bonded only"),
        (("--model", "neo-hookean", "--velocity", "20"), "at most about 10.2 m/s with this"),
        (("--model", "neo-hookean", "--velocity", "1e300"), "outside the floating-point range"),
        (("--model", "neo-hookean", "--prony", "0.5:2e-3", "--velocity", "20"), "at most about"),
        (("--model", "neo-hookean", "--mass", "1e-300"), "below the 0.001 the finite-strain"),
        (("--model", "neo-hookean", "--base", "bonded"), "--base: applies to a layer only"),
    ],
)
def test_cli_model_refusals_are_one_line_exit_2(capsys, argv, message):
    code, out, err = _run(capsys, "dynamic", *argv)
    assert code == 2 and out == ""
    assert message in err and err.count("\n") == 1


def test_api_dynamic_with_model_runs_the_finite_strain_impact(monkeypatch):
    import shtaerman as sh
    import shtaerman.fem.finite_dynamic as finite_dynamic

    monkeypatch.setattr(finite_dynamic, "IMPACT_MESH", COARSE)
    result = sh.dynamic(
        INDENTER,
        RUBBER,
        mass=MASS,
        velocity=1.0,
        model="mooney-rivlin",
        mooney_ratio=0.0,
        density=0.0,
        time_steps=50,
        estimate=False,  # not about accuracy: one run
    )
    assert result.model == "mooney-rivlin"
    assert result.restitution == pytest.approx(1.0, abs=5e-4)
    report = result.to_dict()
    assert report["dynamic"]["x_max"] == result.x_max > report["quasi_static"]["x_c"]
    assert report["parameters"]["time_steps"] == 50  # what ran, for the record
    assert report["parameters"]["mesh_size"] == COARSE.size
    assert report["differences"]["x_c"] == pytest.approx(
        report["quasi_static"]["x_c"] / result.x_max - 1
    )
    with pytest.raises(TypeError, match="unexpected"):
        sh.dynamic(INDENTER, RUBBER, mass=MASS, velocity=1.0, model="yeoh", colour=1)


def test_a_contact_newton_failure_mid_run_is_a_numerical_failure_not_bad_input():
    from types import SimpleNamespace

    from shtaerman.fem.hyperelastic import NewtonError
    from shtaerman.fem.stepper import QuasiStaticBody
    from shtaerman.validation import NumericalFailureError

    def fails(*_args):
        raise NewtonError("Newton did not converge in 30 iterations")

    system = SimpleNamespace(n_dofs=4, material=SimpleNamespace(model="neo-hookean"))
    stepper = SimpleNamespace(system=system, nodes=SimpleNamespace(radius=np.zeros(2)), solve=fails)
    # a thin pad strained beyond what its mesh resolves (3 mm at 3 m/s fails at 1.9 mm):
    # exit 1 with the depth and what to change, not exit 2 as if an input were out of range
    expected = r"failed at depth 0\.002 m .*finer mesh_size=\.\.\."  # the API's words
    with pytest.raises(NumericalFailureError, match=expected):
        QuasiStaticBody(stepper).at(2e-3)


def test_dynamic_help_states_the_defaults_the_model_runs_with(capsys):
    """The help's linear defaults (200 steps, mesh 0.025) are replaced by --model; it says by
    what, and those are the settings the finite-strain impact resolves to."""
    import re

    from shtaerman.cli import main

    with pytest.raises(SystemExit):
        main(["dynamic", "--help"])
    text = " ".join(capsys.readouterr().out.split())
    steps = re.search(r"with --model the default is (\d+) \((\d+) with --density2 0\)", text)
    size = re.search(r"with --model the default is 1/(\d+)", text)
    with_inertia, massless = FiniteImpactSettings().resolved(1100.0), FiniteImpactSettings()
    assert (int(steps[1]), int(steps[2])) == (with_inertia.steps, massless.resolved(0.0).steps)
    assert 1.0 / int(size[1]) == pytest.approx(massless.resolved(0.0).mesh.size, rel=1e-12)
    assert with_inertia.mesh.size == massless.resolved(0.0).mesh.size


class _NoisyBody:
    """A static contact P = k X^q whose stored energy carries relative noise 1e-12 (the finite
    contact's Newton tolerance leaves noise of that size in Pi)."""

    def __init__(self, k: float, q: float) -> None:
        self.k, self.q = k, q
        self.random = np.random.default_rng(7)

    def at(self, depth: float):
        from shtaerman.fem.stepper import _State

        energy = self.k * depth ** (self.q + 1) / (self.q + 1)
        energy *= 1.0 + 1e-12 * self.random.standard_normal()
        return _State(depth, np.zeros(1), np.zeros(1), self.k * depth**self.q, energy)


def test_a_step_at_the_turning_point_converges_at_the_solves_noise_floor():
    """The default 'dynamic --model neo-hookean --density2 0' failed two steps before x_max
    ("step equation did not converge at depth 0.00866 m"): there the step is 1e-4 of the depth,
    and energy noise of 1e-12 x Pi makes the discrete gradient's residual ~1e-5 N, far above
    the secant tolerance (1e-10 M v0 / dt ~ 1.3e-6 N; of V_n, 5e-8 N, before session 60). The
    state below is that step's."""
    from shtaerman.fem.stepper import _discrete_gradient, _step

    body, k = _NoisyBody(963.56 / 0.0086582 ** (5 / 3), 5 / 3), 1.828e5
    start = body.at(0.0086582)
    new, v = _step(body, start, (0.10693, 0.7, 3.0), (1.642e-4, k), _discrete_gradient)
    # the step's exact solution, to first order: X moves by dt (v - dt P / 2M) ~ 1.6e-5 m;
    # the accepted depth is that within the noise's resolution (1e-12 of the depth ~ 1e-14 m)
    assert new.depth == pytest.approx(
        start.depth + 1.642e-4 * (0.10693 - 1.642e-4 * 963.56 / 1.4), rel=1e-6
    )
    assert abs(2 * (new.depth - start.depth) / 1.642e-4 - 0.10693 - v) < 1e-12


@pytest.mark.parametrize("density", [0.0, 1100.0])
def test_the_march_steps_on_one_blas_thread(monkeypatch, density):
    """Both finite-strain marches step on one BLAS thread, as the linear one (stepper.march),
    whatever the caller's: on two the other thread spun between the small factorizations (the
    relaxing 12 mm pad with Coulomb friction took 35.6 CPU s against 24.5, the same histories
    bit for bit; benchmarks/finite_impact_cost.py)."""
    from threadpoolctl import threadpool_info, threadpool_limits

    from shtaerman.fem import stepper
    from shtaerman.fem.finite_dynamic import prepare_finite_impact

    seen = []

    def record(step, first, exponent):  # the march's loop, stepping nothing
        seen.append(
            {info["num_threads"] for info in threadpool_info() if info["user_api"] == "blas"}
        )
        return np.zeros((1, len(first))), np.nan

    monkeypatch.setattr(stepper, "march_steps", record)
    setup = prepare_finite_impact(INDENTER, RUBBER, density, MASS, 3.0, SETTINGS)
    with threadpool_limits(limits=2, user_api="blas"):
        setup.march()
    assert seen == [{1}]
