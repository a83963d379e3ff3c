"""The time stepping's history against values recorded from the stepper (`march` on the
settings below), so that a change of its arithmetic that is more than round-off shows.

Recorded after the mass redistribution's lost mass was summed from the removed entries (it was
a difference of the body's two total masses, 4.5 % off and dependent on the order in which
scipy sums; it moved these values by up to 3e-5 between scipy 1.11 and 1.17). The values
before the stepper's copies were cut (commit a99cbd7) were the same to round-off.

A coarse run with an absorbing layer and generalized-alpha (rho_inf = 0.9): it takes every
branch of `advance` (the alpha_f load, the damping, the contact correction, separation).

Round-off, not the recording machine, sets the tolerances. Another BLAS or SIMD path rounds each
step's solves differently; the active contact's LCP matrix has condition number 7.0e3 (step 10)
to 8.8e3 (step 40), so its forces carry a relative error up to ~1e4 eps. Propagated through the
march (a relative error of 1e4 eps injected into every solve and every LCP solution of every
step, eight random draws), the recorded values moved at most: X, X', t_c 1.2e-12; P 6.9e-10;
a 9.4e-11; p(0) 5.9e-8 (the axis node's force is a small entry of the LCP solution, its relative
error is cond times the largest force's); the energies 2.4e-11 E0 (E0 = M v0^2/2 = 3.15 J). One
rounding per solve (1 eps) moved them 20 to 1e4 times less, as do OpenBLAS's Haswell,
SandyBridge, Nehalem, SkylakeX and Prescott kernels (OPENBLAS_CORETYPE; at most 9.8e-12 relative,
in the numerical energy at step 120) and numpy 1.26 with scipy 1.11 (at most 6e-12, in p(0) and
the numerical energy). Each tolerance below is that bound times about 10.
"""

import pytest
from threadpoolctl import threadpool_limits

from shtaerman.fem.dynamic_contact import DynamicSettings, prepare_dynamic_impact
from shtaerman.fem.stepper import ImpactState, advance, march
from shtaerman.theory.indenter import PowerLawIndenter
from shtaerman.theory.materials import Material

SETTINGS = DynamicSettings(steps=60, size=0.05, layer_rate=10.0)
RECORDED = {  # step: (X m, X' m/s, P N, p(0) Pa, a m)
    10: (
        0.004011165324003627,
        2.7573029040949013,
        317.37535781679776,
        6251139.523493297,
        0.006093606409787747,
    ),
    40: (
        0.0069907419267545325,
        -1.6983764887842001,
        676.2792591370635,
        7644215.176860601,
        0.008313025587712455,
    ),
    120: (-0.022628826625485432, -2.7841612836666294, 0.0, 0.0, 0.0),
}
ENERGIES = {  # step: (absorbed, numerical, inner, strain) in J
    40: (0.006796077764652043, 0.0023819422161968406, 2.0877216270337646, 2.0019989965672265),
    120: (0.30265571088377524, 0.000722928818325641, 0.004448546677302178, 0.06638738858602197),
}
T_CONTACT = 0.008293407379263295
"""Separation time in s."""
E0 = 0.5 * 0.7 * 3.0**2
"""The striker's kinetic energy M v0^2/2 in J, the size of the terms of every energy."""
STATE_RELATIVE = (1e-11, 1e-11, 1e-8, 1e-6, 1e-9)
"""Relative tolerances of X, X', P, p(0), a: the propagated LCP round-off (module docstring)
times about 10."""
ENERGY_ABSOLUTE = 3e-10 * E0
"""Absolute tolerance of each energy, J. Every energy is a sum or difference of terms of size up
to E0 (the numerical one is E0 minus the others, 1e-3 E0 at step 40 and 2e-4 E0 at step 120), so
its round-off is relative to E0, not to itself: the propagated bound 2.4e-11 E0 times about 10."""


@pytest.fixture(scope="module")
def setup():
    return prepare_dynamic_impact(
        PowerLawIndenter(5.0, 1.5), Material(7.5e6, 0.5), 1100.0, 0.7, 3.0, SETTINGS
    )


@pytest.fixture(scope="module")
def history(setup):
    return march(
        setup.problem,
        duration=setup.duration,
        tail_time=setup.tail_time,
        force_exponent=setup.force_exponent,
    )


def test_history_is_the_recorded_one(history):
    assert history.t.size == 121
    for step, values in RECORDED.items():
        shown = (
            history.x[step],
            history.v[step],
            history.force[step],
            history.central_pressure[step],
            history.contact_radius[step],
        )
        for name, value, recorded, rel in zip(
            "X X' P p0 a".split(), shown, values, STATE_RELATIVE, strict=True
        ):
            # round-off of another BLAS (STATE_RELATIVE); after separation (step 120) P, p(0) and
            # a are exactly 0: no candidate carries a force, whatever the rounding
            assert value == pytest.approx(recorded, rel=rel, abs=0.0), (step, name)
    for step, values in ENERGIES.items():
        shown = tuple(
            history.energies[k][step] for k in ("absorbed", "numerical", "inner", "strain")
        )
        # differences of terms of size E0: an absolute tolerance in E0 (ENERGY_ABSOLUTE)
        assert shown == pytest.approx(values, rel=0.0, abs=ENERGY_ABSOLUTE), step
    # t_c interpolates the force between two steps: the round-off of X (STATE_RELATIVE[0])
    assert history.t_contact == pytest.approx(T_CONTACT, rel=STATE_RELATIVE[0], abs=0.0)


def test_advance_leaves_its_state_alone(setup):
    """The correction is done in place on the solver's fresh vector, never on the state's."""
    with threadpool_limits(limits=1, user_api="blas"):
        state = ImpactState.first_touch(setup.problem)
        for _ in range(12):  # into the contact
            state = advance(setup.problem, state)
        kept = (state.x.copy(), state.v.copy(), state.a.copy(), state.stiffness_x.copy())
        first, second = advance(setup.problem, state), advance(setup.problem, state)
    for before, now in zip(kept, (state.x, state.v, state.a, state.stiffness_x), strict=True):
        assert (before == now).all()
    assert (first.x == second.x).all() and (first.forces == second.forces).all()
    assert first.forces.any()
