"""The finite-strain impact as a sweep kind: a ``dynamic`` case with a rubber ``model`` is the
command line's run (issue 28, item 7), checked at load, its guards and checks in its row.

The runs use the coarse graded mesh of tests/test_finite_dynamic.py, patched in as the
default (a few seconds each); the load checks compute nothing.
"""

from __future__ import annotations

import math

import pytest

import shtaerman as sh
from shtaerman.fem.mesh import MeshSettings
from shtaerman.problem import RUBBER_SHAPES
from shtaerman.sweep.engine import execute_case
from shtaerman.sweep.kinds import KINDS
from shtaerman.sweep.spec import SweepError, parse_sweep

COARSE = MeshSettings(size=0.15, domain=1e3, growth=0.35, axis_size=1e-3, axis_growth=0.25)
SWEEP = """name = "rubber"
kind = "dynamic"
[parameters]
{parameters}
[axes]
{axes}
"""


def _sweep(parameters: str, axes: str = "mass = [0.7]"):
    return parse_sweep(SWEEP.format(parameters=parameters, axes=axes))


@pytest.fixture
def coarse(monkeypatch):
    """The coarse mesh as the finite-strain impact's default (massless and with inertia)."""
    import shtaerman.fem.finite_dynamic as finite_dynamic

    monkeypatch.setattr(finite_dynamic, "IMPACT_MESH", COARSE)


def _row(spec):
    (case,) = spec.cases()
    return execute_case(KINDS["dynamic"].case, case.index, case.params)


def test_a_one_case_sweep_is_the_command_lines_run(coarse):
    spec = _sweep('model = "mooney-rivlin"\nmooney_ratio = 0.2\ndensity2 = 0.0\ntime_steps = 50')
    row = _row(spec)
    assert row["status"] == "ok", row["error"]
    body = sh.Material(7.5e6, 0.5, 0.0)
    problem = sh.Problem.impact(
        sh.PowerLawIndenter(5.0, 1.5),
        body,
        mass=0.7,
        velocity=3.0,
        model="mooney-rivlin",
        mooney_ratio=0.2,
    )
    result = sh.dynamic(problem, time_steps=50)
    out = row["outputs"]
    # the same function on the same inputs: equal to the last bit (deterministic FE run)
    for key in ("x_max", "P_max", "t_x_max", "t_contact", "restitution", "energy_balance_error"):
        assert out[key] == result.dynamic[key], key
    for key in ("x", "P", "t"):
        assert out[f"difference_{key}"] == result.differences[f"{key}_c"], key
    assert out["x_c"] == result.quasi_static["x_c"] and out["dofs"] == result.mesh["dofs"]
    assert math.isnan(out["estimate_energy_fraction"])  # the linear half-space's estimate


def test_a_case_beyond_the_validated_depth_records_the_command_lines_warning(coarse, monkeypatch):
    import shtaerman.guards as guards

    # the validated x/a lowered below the paper's impact on a 20 mm pad (x/a ~ 0.4 there), so
    # that the guard speaks on a run that converges on the coarse mesh; with inertia, as the
    # frictionless pad is the body that runs beyond the reach with a warning (a massless pad
    # follows the static curve and is refused there)
    monkeypatch.setattr(guards, "MAX_DEPTH_RATIO", 0.1)
    spec = _sweep('model = "neo-hookean"\ndensity2 = 1000.0\ntime_steps = 50\nthickness = 0.02')
    row = _row(spec)
    with pytest.warns(guards.ValidityWarning) as caught:
        problem = sh.Problem.impact(
            sh.PowerLawIndenter(5.0, 1.5),
            sh.Material(7.5e6, 0.5, 1000.0),
            mass=0.7,
            velocity=3.0,
            model="neo-hookean",
            thickness=0.02,
        )
        sh.dynamic(problem, time_steps=50)
    expected = sorted({str(w.message) for w in caught})
    assert row["status"] == "ok" and row["warnings"] == expected


def test_a_failed_energy_balance_fails_the_case(coarse, monkeypatch):
    import shtaerman.study.dynamic.loader as loader

    # a limit no run meets: the case is failed with the check's reason, its outputs kept
    strict = loader.DynamicTolerances(energy_balance=0.0)
    monkeypatch.setattr(loader, "DynamicTolerances", lambda: strict)
    row = _row(_sweep('model = "neo-hookean"\ndensity2 = 0.0\ntime_steps = 50'))
    assert row["status"] == "failed" and "energy balance error" in row["error"]
    assert row["outputs"]["x_max"] > 0


@pytest.mark.parametrize(
    ("parameters", "axes", "named"),
    [
        # the researcher's z = 8 r^1.3 at 1.5 m/s reaches x/a = 2.3, beyond the 1.2 where
        # the finite-strain contact converges (issue 28)
        (
            'model = "neo-hookean"\ndensity2 = 0.0\nshape_coefficient = 8.0\nexponent = 1.3\n'
            "E2 = 3e6\nnu2 = 0.49\nmass = 0.12",
            "velocity = [0.1, 1.5]",
            "velocity",
        ),
        (
            'model = "neo-hookean"\ndensity2 = 0.0\nmooney_ratio = 0.2',
            "mass = [0.7]",
            "mooney_ratio",
        ),
        ('model = "neo-hookean"\ndensity2 = 0.0\ngrowth = 0.3', "mass = [0.7]", "growth"),
        ('model = "neo-hookean"\ndensity2 = 0.0\naxis_size = 0.01', "mass = [0.7]", "axis_size"),
        (
            'model = "neo-hookean"\ndensity2 = 0.0\nbase = "lubricated"\nthickness = 0.02',
            "mass = [0.7]",
            "base",
        ),
        ('model = "gent"\ndensity2 = 0.0', "mass = [0.7]", "gent_limit"),
        ('volumetric = "logarithmic"', "mass = [0.7]", "volumetric"),
    ],
)
def test_a_rubber_case_is_refused_at_load(parameters, axes, named):
    with pytest.raises(SweepError) as refused:
        _sweep(parameters, axes)
    message = str(refused.value)
    assert named in message and "\n" not in message


def test_a_rubber_case_takes_refine_and_estimate_as_the_command_line_does():
    """The finite-strain impact has its error ladder: refine and estimate reach sh.dynamic (they
    were refused at load before it had one)."""
    from shtaerman.sweep.kinds import _dynamic

    spec = _sweep(
        'model = "neo-hookean"\ndensity2 = 0.0\nestimate = true\nrefine = 0.8', "mass = [0.7]"
    )
    _, numerics = _dynamic(spec.cases()[0].params)
    assert (numerics["estimate"], numerics["refine"]) == (True, 0.8)


def test_a_shape_option_applies_to_the_cases_of_its_model_when_the_model_is_swept():
    spec = _sweep("density2 = 0.0\nmooney_ratio = 0.2", 'model = ["neo-hookean", "mooney-rivlin"]')
    assert [case.params["model"] for case in spec.cases()] == ["neo-hookean", "mooney-rivlin"]
    assert RUBBER_SHAPES["mooney_ratio"] == "mooney-rivlin"


@pytest.mark.parametrize(
    ("parameters", "axes", "named"),
    [
        # the ladder to 1.1 x_c of z = 8 r^1.3 at 0.1 m/s reaches x/a = 1.5 > 1.2: it ran and
        # failed at run time (beside a case within, it is a refused row since session 57:
        # tests/test_sweeprow57.py; alone, the sweep is refused)
        (
            "shape_coefficient = 8.0\nexponent = 1.3\nE2 = 3e6\nnu2 = 0.49\nmass = 0.12",
            "velocity = [0.1]",
            "velocity",
        ),
        ("depths = [1e-3, 0.05]", "E2 = [7.5e6]", "depths"),  # x/a 1.8 at 5 cm
        ("mooney_ratio = 0.2", "mass = [0.7]", "mooney_ratio"),  # neo-Hookean: was ignored
    ],
)
def test_a_finite_strain_case_is_refused_at_load(parameters, axes, named):
    with pytest.raises(SweepError) as refused:
        parse_sweep(
            SWEEP.replace('"dynamic"', '"finite-strain"').format(parameters=parameters, axes=axes)
        )
    message = str(refused.value)
    assert named in message and "\n" not in message


def test_a_massless_linear_case_with_its_estimate_runs_as_the_command_line():
    """One case function for every body (issue 28): a linear massless case with its ladder
    failed with KeyError 'energy_radiated_fraction' (its own copy of the error outputs read an
    estimate the ladder leaves out: 1 - e^2 is 0 by construction); now its row is
    ``sh.dynamic``'s, that error NaN."""
    p = {**KINDS["dynamic"].defaults(), "density2": 0.0, "estimate": True}
    p.update(mesh_size=0.1, time_steps=100)  # the coarsest the ladder takes
    outputs = KINDS["dynamic"].case(p).outputs
    assert math.isnan(outputs["error_energy_radiated_fraction"])
    # x_max converges on this ladder: an estimate, small and positive (observed 1.3e-4)
    assert 0 < outputs["error_x_max"] < 1e-2
