"""A relaxing pad's reach (user62's trial): the finite-strain reach is checked at the relaxed
body's quasi-static depth, which bounds a relaxing pad's depth from above, on the pad as on the
half-space. The researcher's pad (z = 8 r^1.3, 12 mm, Prony 0.3:1e-3, Coulomb 0.5) at the
0.0323 m/s the elastic x_c's refusal named ran to x/a 1.23, past the 1.2 it was named for."""

import pytest

import shtaerman as sh
from shtaerman.guards import MAX_DEPTH_RATIO, depth_ratio
from shtaerman.theory.materials import effective_modulus
from shtaerman.theory.sneddon import contact_law
from shtaerman.theory.viscoelastic import PronySeries, viscoelastic_impact

STRIKER = sh.PowerLawIndenter(shape_coefficient=8.0, exponent=1.3)
RUBBER = sh.Material(3e6, 0.49, 1000.0)


def pad_problem(velocity: float) -> sh.Problem:
    return sh.Problem.impact(
        STRIKER,
        RUBBER,
        mass=0.12,
        velocity=velocity,
        thickness=0.012,
        model="neo-hookean",
        prony="0.3:1e-3",
        interface="bonded",
        friction=0.5,
    )


def relaxed_ratio(velocity: float) -> float:
    """x/a of the quasi-static viscoelastic impact on the half-space (fine: 2,000 steps)."""
    law = contact_law(STRIKER, effective_modulus(sh.RIGID, RUBBER))
    series = PronySeries.parse("0.3:1e-3")
    impact = viscoelastic_impact(0.12, velocity, law, series, steps=2000)
    return depth_ratio(STRIKER, impact.x_max)


def named_remedies(problem: sh.Problem) -> tuple[float, float]:
    """The velocity (m/s) and the mass (kg) the refusal of the API's check of ``problem``
    names."""
    import re

    from shtaerman.api.fem_dynamic import check_dynamic

    with pytest.raises(sh.LimitError) as refused:
        check_dynamic(problem)
    said = str(refused.value)
    velocity = float(re.search(r"velocity=\.\.\. to at most about (\S+) m/s", said)[1])
    return velocity, float(re.search(r"mass=\.\.\. to at most about (\S+) kg", said)[1])


def test_the_relaxed_depth_beyond_the_reach_is_refused_on_the_pad_before_any_work():
    # its relaxed half-space depth is beyond the reach, its elastic x_c within
    assert relaxed_ratio(0.0323) > MAX_DEPTH_RATIO
    # refused at the relaxing body's depth, which its run checks (x/a 1.23)
    match = "with a Prony series the depth is the relaxing body's quasi-static one"
    with pytest.raises(sh.LimitError, match=match):
        sh.dynamic(pad_problem(0.0323), mesh_size=0.2, time_steps=50, estimate=False)


def test_the_remedies_of_a_relaxing_pad_s_refusal_keep_its_relaxed_depth_within_reach():
    # 10 kg at 1.5 m/s on the paper's striker, a 5 cm pad: elastic x/a 1.162, relaxed 1.207.
    # Remedies scaled from the relaxed depth at 1.5 m/s were refused in turn (a slower impact
    # relaxes more: user62b); the fully relaxed body's x_c (1.22) bounds it at every velocity
    from shtaerman.api.fem_dynamic import check_dynamic

    striker = sh.PowerLawIndenter(shape_coefficient=5.0, exponent=1.5)
    body = sh.Material(3e6, 0.49, 0.0)
    keywords = {"thickness": 0.05, "model": "neo-hookean", "prony": "0.3:1e-3"}
    problem = sh.Problem.impact(striker, body, mass=10.0, velocity=1.5, **keywords)
    velocity, mass = named_remedies(problem)
    law = contact_law(striker, effective_modulus(sh.RIGID, body))
    for m, v in ((10.0, velocity), (mass, 1.5)):  # each, taken, within the reach
        impact = viscoelastic_impact(m, v, law, PronySeries.parse("0.3:1e-3"), steps=2000)
        assert depth_ratio(striker, impact.x_max) <= MAX_DEPTH_RATIO
        check_dynamic(sh.Problem.impact(striker, body, mass=m, velocity=v, **keywords))


@pytest.mark.parametrize("route", ["api", "cli"])
def test_the_first_refusal_of_a_relaxing_pad_names_the_remedy_its_run_takes(route, capsys):
    # user62b: the API's and the CLI's first check (the elastic x_c's) named 0.0323 m/s and
    # 5.56e-5 kg, which the run's relaxed check refused in turn (naming a shape coefficient).
    # Both now refuse as the run does: x/a 2.32 of the relaxing body (session 64; the fully
    # relaxed body's 2.34 before), and the velocity at which that depth reaches the reach
    # (relax64: 0.0278 m/s, or 5.44e-5 kg; the fully relaxed body's 0.027 m/s and 3.89e-5 kg
    # before), each of which runs
    import re

    from shtaerman.cli import main

    if route == "api":
        with pytest.raises(sh.LimitError) as refused:
            sh.dynamic(pad_problem(1.5), mesh_size=0.2, time_steps=50, estimate=False)
        said = str(refused.value)
    else:
        command = "dynamic --exponent 1.3 --shape-coefficient 8 --E2 3e6 --nu2 0.49 --mass 0.12"
        command += " --velocity 1.5 --model neo-hookean --density2 1000 --thickness 0.012"
        command += " --prony 0.3:1e-3 --interface bonded --friction 0.5 --no-estimate"
        assert main(command.split()) == 2
        said = capsys.readouterr().err
    assert "depth / contact radius 2.32" in said
    assert "the depth is the relaxing body's quasi-static one, which the run checks" in said
    velocity = float(re.search(r"at most about (\S+) m/s", said)[1])
    assert velocity == pytest.approx(0.0278, rel=5e-3)  # the 3 digits said
    assert relaxed_ratio(velocity) <= MAX_DEPTH_RATIO  # its run's check, finer


def test_a_slowly_relaxing_pad_s_refusal_names_the_velocity_and_mass_at_its_reach():
    # relax64: Prony 0.999:1e3 hardly relaxes within the ~ms impact, yet its refusal named the
    # fully relaxed body's (E* / 1000) 0.00102 m/s and 5.56e-8 kg, 32 and 1000 times too slow
    # and light (0.0323 m/s runs on this pad). The relaxing body's depth, the run's check
    # (relaxed_depth), reaches x/a 1.2 at 0.0323089 m/s and 5.56727e-5 kg: bisection of
    # relaxed_depth in log v (log M) to 1e-7; the elastic x_c's root too (at 0.0323 m/s both
    # give x/a 1.199945: the series hardly relaxes within the contact). Named rounded down.
    keywords = {"thickness": 0.012, "model": "neo-hookean", "prony": "0.999:1e3"}
    keywords.update(interface="bonded", friction=0.5)
    problem = sh.Problem.impact(STRIKER, RUBBER, mass=0.12, velocity=1.5, **keywords)
    velocity, mass = named_remedies(problem)
    assert 0.9 * 0.0323089 <= velocity <= 0.0323089  # the root, three digits rounded down
    assert 0.9 * 5.56727e-5 <= mass <= 5.56727e-5
    from shtaerman.fem.finite_dynamic import relaxed_depth  # the run's check

    law = contact_law(STRIKER, effective_modulus(sh.RIGID, RUBBER))
    series = PronySeries.parse("0.999:1e3")
    for m, v in ((0.12, velocity), (mass, 1.5)):  # each within the run's own check
        assert depth_ratio(STRIKER, relaxed_depth(law, m, v, series)) <= MAX_DEPTH_RATIO
