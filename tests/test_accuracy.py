"""The mesh ladder behind every contact number's error estimate, and ``--accuracy``.

Coarse meshes here (a ladder of about 3k/5k/9k dofs, 2-3 s), but for the one run of
``--accuracy 1e-6`` at the default caps (five levels to 214k dofs, about 20 CPU s and 1.9 GB:
the issue's promise itself); the effectivity of the estimates on unseen cases and the
``--accuracy`` timings are measured in benchmarks/bench_accuracy.py and accuracy_1e6.py.
"""

import itertools
import json
import math
import re
from dataclasses import replace
from types import SimpleNamespace

import numpy as np
import pytest

from shtaerman.cli import main
from shtaerman.fem.fit import exponent_sensitivity, fit_power_law
from shtaerman.fem.mesh import Grading, MeshSettings, halfspace_mesh
from shtaerman.output.text_contact import tables
from shtaerman.study.contact.accuracy import (
    LadderLevel,
    accuracy_mesh,
    estimate_errors,
    run_ladder,
    run_to_accuracy,
)
from shtaerman.study.contact.indentation import default_depths, run_indentation
from shtaerman.study.ladder import LADDER_RATIO
from shtaerman.theory.indenter import PowerLawIndenter
from shtaerman.theory.materials import Material
from shtaerman.validation import InputError

COARSE = MeshSettings(size=1 / 60, domain=1e4, growth=0.3, axis_size=1e-5, axis_growth=0.2)
PAPER = (PowerLawIndenter(5.0, 1.5), Material(7.5e6, 0.5))


@pytest.fixture(scope="module")
def ladder():
    return run_ladder(*PAPER, mesh=COARSE)


def test_ladder_refines_the_whole_field_by_sqrt2(ladder):
    refines = [level.refine for level in ladder.levels]
    assert refines == pytest.approx([1 / LADDER_RATIO**2, 1 / LADDER_RATIO, 1.0], rel=1e-12)
    dofs = [level.dofs for level in ladder.levels]
    # h / sqrt(2) everywhere doubles the dofs (observed 1.6x, 1.8x: the coarsest far field is
    # capped by the domain's arc)
    assert all(1.4 < fine / coarse < 2.3 for coarse, fine in itertools.pairwise(dofs))


def test_finest_level_is_the_plain_run(ladder):
    # an identity: the ladder's answer is run_indentation on the refined settings
    depths = default_depths(*PAPER)
    plain = run_indentation(*PAPER, depths, COARSE.refined(1.0))
    assert [s.force for s in ladder.finest.steps] == [s.force for s in plain.steps]


def test_estimates_are_positive_and_finite(ladder):
    estimate = ladder.error_estimate()
    assert set(estimate) == {"force", "beta", "exponent", "contact_radius", "central_pressure"}
    assert all(math.isfinite(v) and v > 0 for v in estimate.values())
    # force and beta carry the far-field truncation, 1.886 and 1.16 a / R, at least
    stats, largest = ladder.finest.mesh_stats, ladder.finest.steps[-1].contact_radius
    assert estimate["force"] >= 1.886 * largest / stats["domain_radius"]
    assert estimate["beta"] >= 1.16 * largest / stats["domain_radius"]
    extrapolated = ladder.to_dict()["extrapolated"]
    finest = ladder.finest.steps
    # the extrapolated worst-depth force lies within its own estimate of some FEM force
    forces = np.array([s.force for s in finest])
    assert np.min(np.abs(forces / extrapolated["force"] - 1)) <= estimate["force"]


def test_the_extrapolated_values_name_their_depth(ladder):
    """Issue 31: contact.json gave ``extrapolated.force`` (15.33 N) beside the force at x_c
    (64.97 N) without saying it belongs to another depth. ``extrapolated_depth`` names it."""
    report = ladder.to_dict()
    depths = report["extrapolated_depth"]
    assert set(depths) == {"force", "contact_radius", "central_pressure"}
    finest = ladder.finest.steps
    for key, depth in depths.items():
        (at,) = [step for step in finest if step.depth == depth]  # one of the run's depths
        details = report["estimate_details"][key]
        assert details["value"] == getattr(at, key)  # an identity: the estimate's own point
        # Richardson moves the value there by its own correction, which is the estimate
        # (a two-level fallback does not move it); the 1e-12 is rounding of the division
        moved = abs(report["extrapolated"][key] / getattr(at, key) - 1)
        assert moved <= report["error_estimate"][key] * (1 + 1e-12)
    label = tables({"impact": {}, "accuracy": report})[-1]["rows"][0][0]
    assert label == f"force at depth {depths['force']:.4e} m (the worst)"


EDGE_LADDER = MeshSettings(size=1 / 80, growth=0.1, domain=1e7)
"""Fine at the surface, slowly graded below it (16k/32k/62k dofs, 3 s of CPU): the contact
edge's error term dominates the force, as on the fine meshes of ``--accuracy 1e-6``."""


def test_the_force_estimate_does_not_understate_where_the_contact_edge_dominates():
    """Issue 32: ``--accuracy 1e-6`` stopped at an estimate of 0.55 of the true error: it
    corrected at order 3 an error whose edge term converges at order 2. Here the old rule gave
    0.51 (force) and 0.54 (beta)."""
    ladder = run_ladder(*PAPER, mesh=EDGE_LADDER)
    # the edge term's order: observed 1.89 (an order-3 or order-4 term would show >= 2.5)
    assert ladder.estimates["force"].observed_order < 2.5
    effectivity = ladder.effectivity()
    # estimate / true error, measured 1.26 (force) and 1.98 (beta): >= 1 is the promise
    assert effectivity["force"] >= 1.0 and effectivity["beta"] >= 1.0


def test_accuracy_target_is_met_or_refused():
    loose = run_to_accuracy(*PAPER, 5e-3, mesh=COARSE, max_time=86400.0)  # not the budget's test
    assert loose.tolerance == 5e-3 and len(loose.levels) == 3
    assert max(loose.error_estimate()[k] for k in ("force", "beta")) <= 5e-3
    # the domain grew so that the truncation (< 1.886 / domain) stays below a tenth of it
    stats = loose.finest.mesh_stats
    assert stats["domain_radius"] / stats["refined_radius"] >= 10 * 1.886 / 5e-3 * (1 - 1e-12)
    with pytest.raises(InputError, match=r"accuracy 1e-06 needs about .* dofs"):
        run_to_accuracy(*PAPER, 1e-6, mesh=COARSE, max_time=86400.0)  # the dofs, not the time
    # the floor is 3.0176e-07, printed rounded up: 3e-07 itself is refused
    with pytest.raises(InputError, match=r"accuracy must be >= 3.1e-07"):  # before any work
        run_to_accuracy(*PAPER, 1e-9, mesh=COARSE)
    with pytest.raises(InputError, match=r"accuracy must lie in \(0, 0.1\]"):
        run_to_accuracy(*PAPER, 0.5, mesh=COARSE)


def test_contact_json_carries_the_estimates(capsys):
    argv = ["contact", "--json", "--mesh-size", "0.0166667", "--domain-factor", "1e4"]
    argv += ["--growth", "0.3", "--depths", "2e-3,4e-3,8e-3"]
    assert main(argv) == 0
    report = json.loads(capsys.readouterr().out)
    assert {"error_estimate", "extrapolated", "mesh_ladder", "effectivity"} <= set(report)
    assert [level["refine"] for level in report["mesh_ladder"]] == pytest.approx(
        [0.5, 1 / math.sqrt(2), 1.0]
    )
    assert report["mesh"]["dofs"] == report["mesh_ladder"][-1]["dofs"]


@pytest.mark.parametrize(
    ("argv", "message"),
    [
        (["--refine", "0"], r"--refine must lie in \(0, 1e6\], got .0."),
        (["--refine", "0.3"], r"refine must be >= 0.5 with these mesh settings .* got 0.3"),
        (["--accuracy", "nan"], r"--accuracy must be a number in \(0, 0.1\], got 'nan'"),
        (["--accuracy", "1e-5", "--max-time", "-1"], "max-time must be > 0 s"),
        # the truncation at the largest domain, 1.886 / (1e7 x 1.25) = 1.5e-7, is left alone
        (["--accuracy", "3e-7"], r"accuracy must be >= 3.1e-07: the clamped far boundary"),
        (["--accuracy", "1e-5", "--refine", "2"], "--refine: --accuracy chooses the refinement"),
    ],
)
def test_bad_accuracy_options(capsys, argv, message):
    assert main(["contact", *argv]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1
    assert re.search(message, err)


def test_the_size_guard_refuses_a_ladder_before_its_first_level(capsys, monkeypatch):
    # --refine 4 puts the finest level at about 445k dofs; the two coarse levels (107k, 213k)
    # used to run first, 16 s and 1.75 GB, before the finest one was refused (QA)
    import shtaerman.study.contact.accuracy as accuracy

    def no_level(*args, **kwargs):
        raise AssertionError("a ladder level ran")

    monkeypatch.setattr(accuracy, "run_ladder", no_level)
    assert main(["contact", "--refine", "4"]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "above --max-dofs 4e+05" in err


# the paper's case at domain 1e7, refine sqrt(2), 2, 2sqrt(2) (60k, 116k, 228k dofs): force / exact
# - 1 at its eight default depths, and beta / exact - 1 (benchmarks/accuracy_1e6.py)
MEASURED_FORCE = (
    (-6.46e-06, 3.10e-08, 5.24e-06, 9.63e-06, 1.37e-05, 1.64e-05, 1.85e-05, 2.12e-05),
    (-7.28e-06, -2.21e-06, -1.87e-06, 4.58e-07, 1.39e-06, 2.55e-06, 3.37e-06, 4.26e-06),
    (-5.11e-06, -3.02e-06, -2.04e-06, -1.22e-06, -4.04e-07, 9.00e-08, 6.29e-07, 9.98e-07),
)
Q = 5 / 3
"""The force's exponent of the paper's case (n = 1.5): the exact forces are 2.8e6 x^Q."""


def _measured_level(errors, mesh_stats=None):
    """A ladder level whose forces err by ``errors`` (relative) at geometric depths (the
    default depths' ratio, 1.265), with their fit (beta's and the exponent's errors follow)."""
    depths = 1.6e-3 * 1.265 ** np.arange(len(errors))
    forces = 2.8e6 * depths**Q * (1 + np.asarray(errors))
    steps = [
        SimpleNamespace(depth=x, force=f, contact_radius=1.0, central_pressure=1.0)
        for x, f in zip(depths, forces, strict=True)
    ]
    mesh_stats = mesh_stats or {"domain_radius": 1.25e7}
    fit = fit_power_law(depths, forces, Q)
    return LadderLevel(1.0, SimpleNamespace(steps=steps, fit=fit, mesh_stats=mesh_stats))


def test_the_force_estimate_sees_the_shallow_depth_behind_the_far_fields_cancellation():
    """On these levels the largest difference is the deep end's (3.3e-6, the far field's order-4
    term) while the shallow end's error, 5.1e-6, hides behind a cancellation of the two terms
    (its last difference 2.2e-6): order 3 on the last difference estimated 1.9e-6 (0.37).
    The edge floor (the first difference shrunk at order 2) bounds it."""
    levels = tuple(map(_measured_level, MEASURED_FORCE))
    estimates = estimate_errors(levels)
    # the true errors of the finest level: 5.11e-6 (force, shallowest depth) and 1.26e-6 (beta,
    # the mean of the depths' errors; the run measured the same)
    assert estimates["force"].error >= 5.11e-6
    assert abs(levels[-1].result.fit.beta_fixed_exponent / 2.8e6 - 1) == pytest.approx(
        1.26e-6, 1e-2
    )
    assert estimates["beta"].error >= 1.26e-6


def test_the_exponent_estimate_bounds_what_the_forces_errors_do_to_the_fit():
    """Issue 32: the exponent's own Richardson estimate understated on ``--accuracy 1e-6``
    (0.18) and here (0.30: 6.2e-7 against 2.07e-6, observed order 3.75). The fit's bound,
    the force's estimate times the slope's sum |w_i| / q (:func:`exponent_sensitivity`),
    covers it (effectivity 2.79)."""
    levels = tuple(map(_measured_level, MEASURED_FORCE))
    estimates = estimate_errors(levels)
    true = abs(levels[-1].result.fit.exponent / Q - 1)
    depths = [step.depth for step in levels[-1].result.steps]
    bound = exponent_sensitivity(depths) * estimates["force"].error  # absolute, on q
    # the bound itself (larger than Richardson's here), to rounding: the relative estimate
    # times the extrapolated exponent; and at least the true error it bounds
    assert estimates["exponent"].absolute_error == pytest.approx(bound, rel=1e-12)
    assert estimates["exponent"].error >= true
    assert estimates["exponent"].method == "propagated"  # the report says what set it
    # and why, with the 6.2e-7 of its own ladder; no correction's order gave the error
    own = "the bound from the force's error exceeds the ladder's own 6.2e-07"
    assert estimates["exponent"].reason == own and math.isnan(estimates["exponent"].order)


def test_the_exponent_estimate_does_not_understate_on_a_coarse_hertz_ladder():
    """A real ladder (3k/5k/9k dofs) with an exact reference, the shipped Hertz case (A = 50,
    n = 2): the exponent's Richardson estimate alone was 0.95 of its true error."""
    ladder = run_ladder(PowerLawIndenter(50.0, 2.0), Material(7.5e6, 0.5), mesh=COARSE)
    # measured 1.25e-4 true, 4.51e-4 estimated (3.62); >= 1 is the promise
    assert ladder.effectivity()["exponent"] >= 1.0


def test_the_graded_field_sizes_the_surface_in_proportion_to_r():
    """Issue 32: ``--accuracy``'s meshes grade the surface across the band of contact radii,
    size * r / band_start, so that every depth's contact edge meets the same relative size."""
    grading = Grading(band_start=0.25, near_growth=0.5, near_depth=0.05, far_growth=0.5)
    mesh = halfspace_mesh(1.0, domain_radius=1e3, smallest_size=0.01, growth=0.2, grading=grading)
    edges = mesh.facets[:, mesh.boundaries["surface"]]
    r = mesh.p[0, edges].mean(axis=0)
    length = np.abs(np.diff(mesh.p[0, edges], axis=0))[0]
    inner, outer = (np.median(length[(r > lo) & (r < hi)]) for lo, hi in ((0.1, 0.2), (0.9, 1.0)))
    # 0.01 below r = 0.25, 0.01 x 0.95 / 0.25 = 0.038 at r = 0.95: a ratio of 3.8 (gmsh's edges
    # follow the field to about 10 %); the plain field keeps 0.01 on the whole refined zone
    assert 3.8 / 1.3 < outer / inner < 3.8 * 1.3
    assert np.median(length[r < 0.2]) == pytest.approx(0.01, rel=0.2)


def test_accuracy_below_1e4_is_met_on_the_graded_family_with_an_honest_estimate():
    """Issue 32: ``--accuracy`` below 1e-4 runs the graded family (ACCURACY_GRADING), whose
    estimate does not understate. 1e-5 here (16k, 30k, 56k dofs; about 6 CPU s); its 1e-6 at
    the default caps (214k dofs, force true 5.3e-7, estimate 5.9e-7, about 20 CPU s and 2 GB)
    is benchmarks/accuracy_1e6.py's, an accuracy study kept out of the suite."""
    result = run_to_accuracy(*PAPER, 1e-5, max_time=1e4)  # no wall-clock limit in a test
    true, estimate = result.finest.errors(), result.error_estimate()
    assert result.levels[-1].dofs <= MeshSettings().max_dofs
    # the promise: the true error within the target (measured 9.5e-7 force, 2.6e-7 beta) and
    # an estimate that does not understate it (measured 2.7e-6 for both: effectivity 2.9, 10.5)
    for key in ("force", "beta"):
        assert true[key] <= estimate[key] <= 1e-5
    # the caps are checked on estimates made before meshing: within 15 % here (measured 2-10 %)
    stats = result.finest.mesh_stats
    mesh = replace(MeshSettings(), domain=stats["domain_radius"] / stats["refined_radius"])
    family = accuracy_mesh(mesh, PAPER[0], default_depths(*PAPER), 1e-5)
    assert family.grading is not None
    for level in result.levels:
        assert family.refined(level.refine).estimated_dofs == pytest.approx(level.dofs, rel=0.15)


# layers against the Hankel-transform reference (LayerReference, 1e-10): force / reference - 1
# at five depths (half-space radius 4 .. 10 mm; E 7.5 MPa, A a^n = 5 mm at a = 10 mm), refine
# 1/2, 1/sqrt(2), 1 on the default layer mesh (benchmarks/bench_accuracy.py --floor)
MEASURED_LAYERS = {
    "n 1.8, nu 0.33, bonded, H/a 3": (
        (2.268e-04, 2.417e-04, 2.538e-04, 2.886e-04, 3.277e-04),
        (3.782e-05, 8.848e-05, 8.689e-05, 1.079e-04, 9.509e-05),
        (-6.542e-06, 2.824e-05, 2.415e-05, 3.411e-05, 3.267e-05),
    ),
    "n 1.5, nu 0.3, bonded, H/a 10": (
        (2.562e-04, 4.357e-04, 5.472e-04, 6.114e-04, 6.358e-04),
        (4.972e-05, 1.000e-04, 1.137e-04, 1.383e-04, 1.505e-04),
        (9.356e-06, 2.757e-05, 3.950e-05, 4.860e-05, 5.207e-05),
    ),
}


@pytest.mark.parametrize("case", MEASURED_LAYERS)
def test_no_edge_floor_where_every_depth_converges_monotonically_at_order_3_or_more(case):
    """Where the ladder observes order >= 3 and no depth's differences change sign, no
    order-2 term shows: the edge floor (which made these estimates 2.6 and 3.4 times the true
    error) is not applied; the estimate stays above the true error."""
    errors = MEASURED_LAYERS[case]
    levels = tuple(_measured_level(e, {"thickness": 0.03}) for e in errors)
    estimate = estimate_errors(levels)["force"]
    true = max(abs(e) for e in errors[-1])
    assert estimate.observed_order >= 3.0  # measured 3.31 and 4.61
    # effectivity measured 1.77 and 1.48 (2.62 and 3.38 with the floor); >= 1 is the promise,
    # below 2 what the order-3 correction times FORCE_SAFETY 1.25 gives without the floor
    assert true <= estimate.error <= 2.0 * true
