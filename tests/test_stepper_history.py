"""The time stepping's history against values recorded from the stepper as it was before its
copies were cut (commit a99cbd7, `march` on the settings below): the arithmetic and its order
are unchanged, so the run is the same to round-off (bitwise on the machine they were recorded).

A coarse run with an absorbing layer and generalized-alpha (rho_inf = 0.9): it takes every
branch of `advance` (the alpha_f load, the damping, the contact correction, separation).
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
        0.0040111664843609385,
        2.757304771173357,
        317.3743242070633,
        6251337.457684493,
        0.006093605649844821,
    ),
    40: (
        0.006990734826801007,
        -1.6983831380884737,
        676.2729003602992,
        7644323.614724552,
        0.008312999821413957,
    ),
    120: (-0.0226288523449863, -2.784162237145233, 0.0, 0.0, 0.0),
}
ENERGIES = {  # step: (absorbed, numerical, inner, strain) in J
    40: (0.00679608906112756, 0.002381800387350189, 2.087715705522017, 2.0019935456313913),
    120: (0.30265486993529134, 0.0007228032447969546, 0.004448459441525727, 0.0663869620928191),
}
T_CONTACT = 0.008293396654348419
"""Separation time in s."""
RELATIVE = 1e-12
"""Round-off of another machine's BLAS and SIMD; the recording machine gives them exactly."""


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
        assert shown == pytest.approx(values, rel=RELATIVE, abs=0.0), step
    for step, values in ENERGIES.items():
        shown = tuple(
            history.energies[k][step] for k in ("absorbed", "numerical", "inner", "strain")
        )
        assert shown == pytest.approx(values, rel=RELATIVE, abs=0.0), step
    assert history.t_contact == pytest.approx(T_CONTACT, rel=RELATIVE, abs=0.0)


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
