"""Error bars of the dynamic impact: the mesh-and-time-step ladder (coarse settings, ~5 s)."""

import json
import math
from operator import attrgetter
from types import SimpleNamespace

import pytest

from shtaerman.fem.dynamic_contact import DynamicSettings
from shtaerman.study.dynamic.accuracy import DYNAMIC_ESTIMATED, ImpactLadder, RetriedWarning
from shtaerman.study.dynamic.case import run_case
from shtaerman.study.ladder import LADDER_RATIO
from shtaerman.study.richardson import richardson
from shtaerman.theory.indenter import PowerLawIndenter
from shtaerman.theory.materials import Material
from shtaerman.validation import InputError

COARSE = DynamicSettings(steps=160, size=1 / 30, axis_size=1 / 300, growth=0.3, domain=1e3)


def test_refined_settings_shrink_h_and_dt_together():
    finer = COARSE.refined(2.0)
    assert (finer.size, finer.axis_size) == pytest.approx((COARSE.size / 2, COARSE.axis_size / 2))
    assert finer.growth == pytest.approx(COARSE.growth / 2) and finer.steps == 2 * COARSE.steps
    assert (finer.margin, finer.domain) == (COARSE.margin, COARSE.domain)
    with pytest.raises(InputError, match="refine must be > 0"):
        COARSE.refined(0.0)
    with pytest.raises(InputError, match="steps"):
        COARSE.refined(0.25)  # 40 steps per impact cannot resolve it


@pytest.fixture(scope="module")
def ladder():
    return run_case(
        PowerLawIndenter(5.0, 1.5), Material(7.5e6, 0.5), 1100.0, 0.7, 3.0, COARSE, ladder=True
    ).ladder


def test_ladder_levels_and_estimates(ladder):
    assert ladder.refines == pytest.approx((1 / LADDER_RATIO**2, 1 / LADDER_RATIO, 1.0))
    steps = [level.steps for level in ladder.settings]
    assert steps == [80, 113, 160]
    dofs = [result.mesh["dofs"] for result in ladder.results]
    assert dofs[0] < dofs[1] < dofs[2]
    assert set(ladder.estimates) == set(DYNAMIC_ESTIMATED)
    for key, estimate in ladder.estimates.items():
        assert estimate.value == getattr(ladder.finest, key)  # the finest run is the answer
        assert math.isfinite(estimate.error) and estimate.error >= 0
    # the coarse ladder's x_max and restitution are converged well below a per cent
    assert ladder.estimates["x_max"].error < 1e-2
    assert ladder.estimates["restitution"].error < 1e-2
    document = ladder.to_dict()
    assert [level["steps"] for level in document["mesh_ladder"]] == steps


def test_cli_json_carries_the_estimates(capsys):
    from shtaerman.cli import main

    argv = ["dynamic", "--json", "--steps", "100", "--mesh-size", "0.05"]
    assert main(argv) == 0
    report = json.loads(capsys.readouterr().out)
    assert set(report["error_estimate"]) == set(DYNAMIC_ESTIMATED)
    assert [level["steps"] for level in report["mesh_ladder"]] == [50, 71, 100]
    assert report["extrapolated"]["x_max"] == pytest.approx(report["dynamic"]["x_max"], rel=1e-2)
    assert main([*argv, "--no-estimate"]) == 0
    report = json.loads(capsys.readouterr().out)  # one schema: the key is there, null, with why
    assert report["error_estimate"] is None
    assert "no-estimate" in report["not_given"]["error_estimate"]
    assert main(["dynamic", "--steps", "60"]) == 2  # its coarsest level would have 30 steps
    assert "--no-estimate" in capsys.readouterr().err


# --- derived quantities: Richardson on their own values over the levels ------------------------


def fake_ladder(name: str, values: list[float]) -> ImpactLadder:
    """A ladder whose runs hold only the result ``name`` (coarsest first); no FEM."""
    results = tuple(SimpleNamespace(**{name: value}) for value in values)
    return ImpactLadder((0.5, 0.71, 1.0), (), results, {})


def test_derived_estimate_of_the_radiated_fraction_matches_its_propagation():
    # e(h) = 0.93 - 0.004 h^2.4 on h = 1, 1/sqrt 2, 1/2. Richardson directly on 1 - e^2 agrees
    # with the first-order propagation of e's estimate: absolute errors 2 e |de|, to O(de / e)
    # (measured 2.6e-3; 5e-3 asserted); relative, 2 e^2 err_e / (1 - e^2), to O(err of 1 - e^2)
    # (the propagation divides by the finest 1 - e^2, not the extrapolated one; measured 1.4 %)
    e = [0.93 - 0.004 * (1 / LADDER_RATIO**k) ** 2.4 for k in range(3)]
    ladder = fake_ladder("restitution", e)
    restitution = ladder.estimate(lambda r: r.restitution)
    radiated = ladder.estimate(lambda r: 1.0 - r.restitution**2)
    assert restitution.method == radiated.method == "richardson"
    assert radiated.order == pytest.approx(restitution.order, abs=0.01)
    propagated = 2 * e[-1] * restitution.absolute_error
    assert radiated.absolute_error == pytest.approx(propagated, rel=5e-3)
    propagated = 2 * e[-1] ** 2 * restitution.error / (1 - e[-1] ** 2)
    assert radiated.error == pytest.approx(propagated, rel=2 * radiated.error)


def test_derived_estimate_is_exact_for_an_affine_quantity():
    # Richardson commutes with Q -> a Q + b (same order; the correction scales by |a|):
    # the difference t_c / (t_contact / 2) - 1 is affine in 1 / t_contact, an identity to 1e-12
    inverse = [1 / 8.30 + 0.002 * (1 / LADDER_RATIO**k) ** 2.0 for k in range(3)]
    ladder = fake_ladder("t_contact", [1 / v for v in inverse])
    t_c = 4.105
    plain = ladder.estimate(lambda r: 1 / r.t_contact)
    difference = ladder.estimate(lambda r: t_c / (0.5 * r.t_contact) - 1.0)
    assert difference.order == pytest.approx(plain.order, rel=1e-12)
    assert difference.absolute_error == pytest.approx(2 * t_c * plain.absolute_error, rel=1e-9)
    assert difference.extrapolated == pytest.approx(2 * t_c * plain.extrapolated - 1, rel=1e-12)


# --- the estimator against the paper's case refined in the ladder's own direction ---------------
# Measured at 3 m/s (fem/dynamic.toml's settings refined by K with DynamicSettings.refined;
# benchmarks/bench_dynamic_study.py (c)): K = 0.707, 1, 1.414, and the finest run K = 4
# (120k dofs, 800 steps per t_y). P_max and e scatter at every level (the flat top's ripple
# under the peak fit; the mesh at the contact edge): K = 1 and 1.414 agree by chance.
MEASURED = {
    "P_max": ([940.7422851616766, 940.5708988687851, 940.573125384032], 940.6639703382245),
    "restitution": (
        [0.9265733953026803, 0.9265683012573577, 0.9265931604495242],
        0.9265852171477688,
    ),
    "x_max": (
        [0.008270206487842277, 0.008270776780897292, 0.008270934803526149],
        0.008271055526975567,
    ),
}


@pytest.mark.parametrize("key", sorted(MEASURED))
def test_estimate_covers_the_difference_to_the_finest_run(key):
    # effectivity = estimate / |Q(1.414) / Q(4) - 1|: the old estimator (observed order, the
    # last difference as fallback) gave P_max 0.025, e 3.1, x_max 0.50; now 1.9, 3.1, 1.3.
    # Bound: effectivity >= 1/2, as the issue's [1/3, 3] with margin below (the noisy
    # reference can make any estimate look large above).
    levels, finest = MEASURED[key]
    ladder = fake_ladder(key, levels)
    estimate = ladder.estimate(attrgetter(key))
    difference = abs(levels[-1] / finest - 1)
    assert estimate.error >= 0.5 * difference, (estimate, difference)
    assert estimate.error < 10 * difference
    old = richardson(levels, LADDER_RATIO)  # the old estimator: not conservative for P_max
    assert (old.error < 0.05 * difference) == (key == "P_max")


def test_the_linear_body_retries_a_failed_level_as_the_rubber_does(monkeypatch):
    """One ladder for every body (issue 28): a level of the linear impact that fails
    numerically is run again with doubled time steps and enters the ladder with them; before,
    the linear ladder aborted the whole run."""
    import shtaerman.study.dynamic.case as case
    from shtaerman.validation import NumericalFailureError

    run = case.run_impact

    def fail_at_113(*inputs, **options):
        if inputs[5].steps == 113:  # the middle level, once
            raise NumericalFailureError("forced failure at 113 steps")
        return run(*inputs, **options)

    monkeypatch.setattr(case, "run_impact", fail_at_113)
    with pytest.warns(RetriedWarning, match="refine 0.707: 113 steps failed"):
        retried = run_case(
            PowerLawIndenter(5.0, 1.5), Material(7.5e6, 0.5), 1100.0, 0.7, 3.0, COARSE, ladder=True
        ).ladder
    assert [level.steps for level in retried.settings] == [80, 226, 160]
    assert "passed with 226 steps" in retried.failures[1] and not retried.missing
    assert set(retried.estimates) == set(DYNAMIC_ESTIMATED)
