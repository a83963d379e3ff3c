"""Dynamic FE impact (:mod:`shtaerman.fem.dynamic_contact`) and the radiation estimate.

Coarse meshes (size 1/40 of the refined radius, ~12k dofs) and 200 steps per impact keep the
file fast; the default settings are exercised in benchmarks/bench_dynamic.py. The exact
quasi-static impact (:func:`shtaerman.impact.solve_impact`) is the reference of the
low-density limit; the comparison lives here, not in ``fem`` (layering rule).
"""

import json
import math

import numpy as np
import pytest
from threadpoolctl import threadpool_limits

from shtaerman.fem.dynamic_contact import (
    MAX_DOFS,
    RUN_DURATIONS,
    DynamicSettings,
    estimate_dofs,
    prepare_dynamic_impact,
)
from shtaerman.fem.impact import run_impact
from shtaerman.fem.stepper import ContactEdgeReachedError, ImpactState, advance
from shtaerman.theory.contact import PowerLawContact
from shtaerman.theory.impact import solve_impact
from shtaerman.theory.indenter import PowerLawIndenter
from shtaerman.theory.materials import Material, effective_modulus
from shtaerman.theory.radiation import (
    radiation_estimate,
    radiation_integral,
    rayleigh_fraction,
    rayleigh_root,
)
from shtaerman.validation import InputError, NumericalFailureError

RUBBER = Material(7.5e6, 0.5)
PAPER = PowerLawIndenter(5.0, 1.5)
COARSE = DynamicSettings(steps=200, size=1.0 / 40.0)
RIGID_STAR = RUBBER.youngs_modulus / (1.0 - RUBBER.poisson_ratio**2)


def quasi_static(indenter=PAPER, half_space=RUBBER, mass=0.7, velocity=3.0):
    modulus = effective_modulus(Material(math.inf, 0.0), half_space)
    return solve_impact(mass, velocity, PowerLawContact(indenter, modulus))


@pytest.fixture(scope="module")
def rubber_run():
    """The paper's case, rho2 = 1100 kg/m^3, coarse; with two field snapshots."""
    return run_impact(PAPER, RUBBER, 1100.0, 0.7, 3.0, COARSE, snapshot_times=(2e-3, 4e-3))


@pytest.fixture(scope="module")
def light_run():
    """rho2 = 1e-3 kg/m^3: lambda ~ rho^(1/2) ~ 1.5e-4, the quasi-static limit."""
    return run_impact(PAPER, RUBBER, 1e-3, 0.7, 3.0, COARSE)


# --- radiation estimate (pure theory) -------------------------------------------------------

# I(nu) of DESIGN.md, given to 3 decimals: tolerance 5e-4 (half a unit of the last digit)
DESIGN_I = {0.25: 0.931, 0.3: 0.862, 0.4: 0.743, 0.45: 0.694, 0.5: 0.656}


@pytest.mark.parametrize(("nu", "expected"), sorted(DESIGN_I.items()))
def test_radiation_integral_matches_design_table(nu, expected):
    assert radiation_integral(nu) == pytest.approx(expected, abs=5e-4)


def test_rayleigh_share_and_speed():
    # Miller & Pursey (1955): 67.4 % Rayleigh at nu = 0.25; DESIGN.md "about 55 %" at 0.5.
    # c_R / c_s = 0.91940 at nu = 0.25 (root of Rayleigh's cubic, 5 digits): 1e-5
    assert rayleigh_fraction(0.25) == pytest.approx(0.674, abs=5e-4)
    assert rayleigh_fraction(0.5) == pytest.approx(0.55, abs=5e-3)
    assert 1.0 / rayleigh_root(0.25) == pytest.approx(0.91940, abs=1e-5)
    # nu = 0.5: c_R / c_s = 0.95531 (root of s^6 - 8 s^4 + 24 s^2 - 16 = 0 in c_R/c_s)
    assert 1.0 / rayleigh_root(0.5) == pytest.approx(0.95531, abs=1e-5)


# DESIGN.md: lambda = 0.041 / 0.069 / 0.116 / 0.157 / 0.195 / 0.230 (3 decimals): 5e-4
DESIGN_LAMBDA = {0.5: 0.041, 1.0: 0.069, 2.0: 0.116, 3.0: 0.157, 4.0: 0.195, 5.0: 0.230}


@pytest.mark.parametrize(("velocity", "expected"), sorted(DESIGN_LAMBDA.items()))
def test_lambda_of_the_paper_example(velocity, expected):
    law = PowerLawContact(PAPER, RIGID_STAR)
    estimate = radiation_estimate(0.7, velocity, law.beta, 5.0 / 3.0, 1100.0, 2.5e6, 0.5)
    assert estimate.energy_fraction == pytest.approx(expected, abs=5e-4)
    # e = sqrt(1 - lambda) exactly by definition: round-off only
    assert estimate.restitution == pytest.approx(math.sqrt(1 - estimate.energy_fraction), rel=1e-14)


def test_force_rate_integral_matches_quadrature():
    """Int (df/dt)^2 dt in closed form against the exact quasi-static history."""
    impact = quasi_static()
    history = impact.history(points=20001)
    rate = np.gradient(history.P, history.t)
    numeric = np.trapezoid(rate**2, history.t)
    law = PowerLawContact(PAPER, RIGID_STAR)
    estimate = radiation_estimate(0.7, 3.0, law.beta, 5.0 / 3.0, 1100.0, 2.5e6, 0.5)
    # 20001 samples, dP/dt ~ t^(2/3) at the ends: the finite differences err ~1e-4
    assert estimate.force_rate_squared_integral == pytest.approx(numeric, rel=1e-3)


@pytest.mark.parametrize("bad", [0.0, -1.0, math.nan, "x"])
def test_radiation_rejects_bad_density(bad):
    with pytest.raises(InputError, match="density"):
        radiation_estimate(0.7, 3.0, 1e6, 5.0 / 3.0, bad, 2.5e6, 0.5)


# --- nearly massless limit: the exact quasi-static impact -------------------------------------


def test_light_half_space_reproduces_quasi_static_impact(light_run):
    exact = quasi_static()
    # coarse static FEM error in beta ~3e-4 -> x, P ~1e-4 (observed 8e-5, 1.1e-4, Newmark);
    # the acceptance tolerance 3e-3 is used as is
    assert light_run.x_max == pytest.approx(exact.x_c, rel=3e-3)
    assert light_run.P_max == pytest.approx(exact.P_c, rel=3e-3)
    # separation from P^(1/q) extrapolation, O(dt^2): observed 1.6e-5
    assert light_run.t_contact == pytest.approx(exact.t_y, rel=3e-3)
    # radiated lambda ~ 1.5e-4 here plus the time-stepping error: observed e - 1 = -2e-7
    assert light_run.restitution == pytest.approx(1.0, abs=5e-3)
    # t_x_max = t_c: the parabolic peak is O(dt^2) accurate, 1 % of a step is 5e-5 t_c
    assert light_run.t_x_max == pytest.approx(exact.t_c, rel=3e-3)
    # the domain reaches as far as the waves travel in the run (c_s 5e4 m/s: 1.2 km), so R_a
    # lies within it and the reflection is measured (nan before): the studies' 1e-2 holds
    assert light_run.reflected_energy_fraction < 1e-2  # observed 2.0e-3


def test_light_history_follows_the_quasi_static_history(light_run):
    exact = quasi_static().history(times=light_run.t[light_run.t <= quasi_static().t_y])
    x = light_run.x[: exact.t.size]
    # pointwise depth error: the same 1e-4 static FEM error, plus O(dt^2); 2e-3 of x_c
    assert np.max(np.abs(x - exact.x)) < 2e-3 * quasi_static().x_c


# --- rubber: energy, smoothness, radiation ----------------------------------------------------


def test_stepping_by_hand_reproduces_the_run(rubber_run):
    """The problem object and the stepper are the run: advance() from first touch gives the
    run's first steps exactly, and leaves the state it is given unchanged."""
    setup = prepare_dynamic_impact(PAPER, RUBBER, 1100.0, 0.7, 3.0, COARSE)
    start = ImpactState.first_touch(setup.problem)
    with threadpool_limits(limits=1, user_api="blas"):  # as march() steps
        state = advance(setup.problem, start)
        assert advance(setup.problem, start).striker_v == state.striker_v  # a function
        assert not start.x.any() and start.striker_v == 3.0
        for _ in range(19):
            state = advance(setup.problem, state)
    assert state.step == 20
    # the same arithmetic in the same order, one BLAS thread: equal to the last bit
    assert state.striker_x == rubber_run.x[20]
    assert state.striker_v == rubber_run.v[20]
    assert float(state.forces.sum()) == rubber_run.force[20]


def test_energy_balance_closes(rubber_run):
    e0 = rubber_run.energies["striker_kinetic"][0]
    # acceptance: 1e-2 of the initial kinetic energy; observed 8e-5
    assert rubber_run.energy_balance_error < 1e-2
    # generalized-alpha: the scheme's loss is its contact term plus a tiny algorithmic
    # dissipation at the resolved frequencies (observed 2e-6 E0): 2e-5 E0
    np.testing.assert_allclose(
        rubber_run.energies["numerical"], rubber_run.energies["contact_term"], atol=2e-5 * e0
    )
    # the radiated share equals what the striker lost: E0 (1 - e^2) - (E0 - final striker KE)
    lost = 1.0 - rubber_run.energies["striker_kinetic"][-1] / e0
    assert lost == pytest.approx(rubber_run.energy_radiated_fraction, rel=1e-9)


def test_contact_force_is_smooth(rubber_run):
    """No chatter: P rises then falls, once each, and its second difference stays small."""
    force = rubber_run.force
    loaded = np.flatnonzero(force > 0)
    contact = force[loaded[0] : loaded[-1] + 1]
    assert np.all(contact > 0)  # one contact interval, no loss of contact
    peak = int(np.argmax(contact))
    # monotone rise and fall up to a residue of the damped ripple on the flat top (observed
    # 2.4e-3 P_max); chatter would reverse P by O(P_max): bound 5e-3 P_max
    tolerance = 5e-3 * contact.max()
    assert np.all(np.diff(contact[: peak + 1]) > -tolerance)
    assert np.all(np.diff(contact[peak:]) < tolerance)
    # a smooth P(t) over 200 steps: second differences ~ P_max (pi/200)^2 ~ 2.5e-4 P_max;
    # chatter (or Newmark's undamped period-2 ripple: 16 % here) would make them O(P_max).
    # Observed 1.3e-2 at the first steps (P ~ t^(5/3), nodes entering): bound 3e-2 P_max
    assert np.max(np.abs(np.diff(contact, 2))) < 3e-2 * contact.max()
    # the falling half is smoother still: observed 4e-3
    half = contact[np.argmax(contact) :]
    assert np.max(np.abs(np.diff(half, 2))) < 1e-2 * contact.max()


def test_newmark_ripple_is_what_generalized_alpha_removes():
    """Newmark average acceleration: the exact energy identity, and the ripple it leaves."""
    run = run_impact(
        PAPER,
        RUBBER,
        1100.0,
        0.7,
        3.0,
        DynamicSettings(steps=200, size=1 / 40, spectral_radius=None),
    )
    e0 = run.energies["striker_kinetic"][0]
    # the energy the scheme loses is exactly its trapezoidal contact work: round-off, 1e-9 E0
    np.testing.assert_allclose(
        run.energies["numerical"], run.energies["contact_term"], atol=1e-9 * e0
    )
    half = run.force[np.argmax(run.force) :]
    half = half[half > 0]
    # observed 16 % of P_max (undamped stiff modes): the reason for generalized-alpha
    assert np.max(np.abs(np.diff(half, 2))) > 5e-2 * run.force.max()


def test_radiated_energy_agrees_with_estimate_at_lambda_0_16(rubber_run):
    law = PowerLawContact(PAPER, RIGID_STAR)
    estimate = radiation_estimate(0.7, 3.0, law.beta, 5.0 / 3.0, 1100.0, 2.5e6, 0.5)
    # lambda = 0.157 is beyond the first-order range (< 0.05): the measured 0.134 is
    # 15 % below; the estimate is an upper bound here (the softer dynamic force history
    # radiates less). Assert the 20 % band and the direction
    assert rubber_run.energy_radiated_fraction == pytest.approx(estimate.energy_fraction, rel=0.2)
    assert rubber_run.energy_radiated_fraction < estimate.energy_fraction


def test_small_radiation_matches_first_order_estimate():
    """v0 = 0.5 m/s, lambda = 0.041: the measured loss within 20 % (observed -3 %)."""
    run = run_impact(PAPER, RUBBER, 1100.0, 0.7, 0.5, COARSE)
    law = PowerLawContact(PAPER, RIGID_STAR)
    estimate = radiation_estimate(0.7, 0.5, law.beta, 5.0 / 3.0, 1100.0, 2.5e6, 0.5)
    assert run.energy_radiated_fraction == pytest.approx(estimate.energy_fraction, rel=0.2)
    # reflected energy: acceptance 1 %; observed 0.3 % (mesh-grading reflection + near field)
    assert run.reflected_energy_fraction < 1e-2


def test_slow_impact_domain_holds_the_waves_of_the_whole_run():
    """v0 = 1e-3 m/s: a_c shrinks while t_y grows, so 1e4 refined radii (2.29 m) fell short
    of c_s t_y = 2.90 m and the clamped far arc sent the waves back into the contact (loss
    37 % below the estimate on main; benchmarks/FEM_NOTES.md). The domain now reaches as far
    as a shear wave travels in the longest run, RUN_DURATIONS t_y (c_p is infinite at
    nu = 0.5), and the loss meets the first-order estimate (lambda ~ 4e-3)."""
    run = run_impact(PAPER, RUBBER, 1100.0, 0.7, 1e-3, DynamicSettings(steps=50, size=0.2))
    c_s, t_y = run.parameters["shear_wave_speed"], run.parameters["quasi_static_t_y"]
    assert run.mesh["domain_radius"] == pytest.approx(RUN_DURATIONS * c_s * t_y, rel=1e-12)
    law = PowerLawContact(PAPER, RIGID_STAR)
    estimate = radiation_estimate(0.7, 1e-3, law.beta, 5.0 / 3.0, 1100.0, 2.5e6, 0.5)
    # This coarse mesh in a 10x larger domain (22.9 m) gives +0.014 (+1e-5 at size 1/40,
    # 200 steps): 0.03 is twice the mesh's own deviation; the too small domain gave -0.35
    assert run.energy_radiated_fraction / estimate.energy_fraction - 1.0 == pytest.approx(
        0.0, abs=0.03
    )
    assert run.reflected_energy_fraction < 1e-2  # measured now (nan on main): observed 2.0e-3


def test_outputs_are_json_and_snapshots_have_fields(rubber_run):
    data = json.loads(json.dumps(rubber_run.to_dict()))
    assert set(data["history"]) == {"t", "x", "v", "P", "a", "p0"}
    assert data["mesh"]["dofs"] == rubber_run.system.n_dofs
    assert set(data["timings"]) >= {"mesh", "assembly", "factorization", "stepping", "total"}
    actual, solution, velocity = rubber_run.field_solution(4e-3)
    # nearest step: within half a step of the request
    assert abs(actual - 4e-3) <= 0.5 * rubber_run.parameters["time_step"] * (1 + 1e-9)
    assert np.max(solution.von_mises) > 0
    assert np.min(solution.u_z) < 0  # the surface is pressed down at t = 4 ms (near x_max)
    assert velocity.shape == (rubber_run.system.n_dofs,)
    # the contact radius at the peak is near the quasi-static a_c (dynamic x_max is 3 % lower)
    assert np.max(rubber_run.contact_radius) == pytest.approx(quasi_static().a_c, rel=0.05)


# --- input validation -------------------------------------------------------------------------


@pytest.mark.parametrize("bad", [1e-7, -5.0, math.nan, math.inf])  # 0 is valid: massless
def test_bad_density_is_one_line(bad):
    with pytest.raises(InputError, match="density2") as error:
        run_impact(PAPER, RUBBER, bad, 0.7, 3.0, COARSE)
    assert "\n" not in str(error.value)


def test_too_few_steps_rejected():
    with pytest.raises(InputError, match=r"steps .* \[50"):
        DynamicSettings(steps=20)


def test_runaway_mesh_refused_before_meshing():
    settings = DynamicSettings(size=1e-4)
    assert estimate_dofs(settings) > MAX_DOFS
    with pytest.raises(InputError, match="dofs"):
        run_impact(PAPER, RUBBER, 1100.0, 0.7, 3.0, settings)


def test_contact_outgrowing_refined_zone_is_reported():
    with pytest.raises(InputError, match="refined zone"):
        run_impact(PAPER, RUBBER, 1e-3, 0.7, 3.0, DynamicSettings(steps=60, size=0.05, margin=1.01))


def test_absorbing_layer_books_its_energy_and_perturbs_little():
    """The optional layer (off by default): absorbed energy counted, e nearly unchanged.

    At nu = 0.5 the pressure field is instantaneous (c_p infinite), so a viscous layer at any
    distance damps the quasi-static near field too: measured e shifts by 1.4e-3 (rate 10 t_y^-1,
    3 wavelengths wide) and the energy left inside R_a is 1.0 %
    (0.2 % without it). Hence the default: no layer, a far (125 m) clamped arc.
    """
    settings = DynamicSettings(steps=200, size=1 / 40, layer_rate=10.0)
    run = run_impact(PAPER, RUBBER, 1100.0, 0.7, 3.0, settings)
    e0 = run.energies["striker_kinetic"][0]
    absorbed = run.energies["absorbed"][-1] / e0
    # most of the radiated 14 % reaches the layer within the tail (observed 0.096)
    assert 0.05 < absorbed < run.energy_radiated_fraction
    # the bookkeeping closes with the layer's work included: observed 8e-5, acceptance 1e-2
    assert run.energy_balance_error < 1e-2
    # e against the layer-free coarse run (0.92657): observed shift 1.4e-3; bound 5e-3
    assert run.restitution == pytest.approx(0.92657, abs=5e-3)


def test_a_time_stepping_gone_unstable_stops_as_a_numerical_failure():
    """Newmark with 5000 steps per t_y on a coarse mesh (c_s dt / h = 0.063) gains energy
    without bound; the old run finished 'ok' with e = 1.1e8 and its energy 8e19 times the
    initial. It now stops once the balance is off by ten times the initial energy."""
    settings = DynamicSettings(steps=5000, size=0.1, spectral_radius=None)
    with pytest.raises(NumericalFailureError, match=r"off by .* stepping became unstable"):
        run_impact(PAPER, RUBBER, 1100.0, 0.7, 3.0, settings)


def test_a_refined_zone_too_small_still_asks_for_a_larger_margin():
    """A balanced run whose contact outgrows the refined zone (margin 1.01 of a_c, 100 steps)
    is the input's fault: an InputError that names the margin, not a numerical failure."""
    settings = DynamicSettings(steps=100, size=0.1, margin=1.01)
    with pytest.raises(
        ContactEdgeReachedError,
        match=r"refined zone .*increase the margin \(mesh_margin=\.\.\.\)",  # the API's words
    ):
        run_impact(PAPER, RUBBER, 1100.0, 0.7, 3.0, settings)
