"""The effects sweep kind: each case is the effect table of ``sh.effects`` reduced to its
dominant effect, its resolution and the full change per quantity, so a sweep maps which
effect dominates. Linear effects only (a pad and friction on a massless body: four ~1 s runs
at mesh 0.2, 50 steps, no estimate)."""

import math

import pytest
from served_runs import served_impacts

import shtaerman as sh
from shtaerman.problem import Problem
from shtaerman.sweep import KINDS, SweepError, load_sweep
from shtaerman.sweep.kinds import EFFECT_NAMES, EFFECT_QUANTITIES

SWEEP = """\
name = "effects"
kind = "effects"
[parameters]
mesh_size = 0.2
time_steps = 50
density2 = 0.0
thickness = 0.02
interface = "bonded"
friction = 0.5
[axes]
velocity = [3.0]
"""


def _spec(tmp_path, text=SWEEP):
    path = tmp_path / "effects.toml"
    path.write_text(text)
    return load_sweep(path)


@pytest.fixture(scope="module", autouse=True)
def served():
    """The module's FE runs by their inputs (tests/served_runs.py): the sweep case and the
    study run the table's four runs with its inputs, and are served them."""
    with pytest.MonkeyPatch.context() as patch:
        served_impacts(patch)
        yield


@pytest.fixture(scope="module")
def table() -> dict:
    """``sh.effects`` of the sweep's case and the study's problem (one table for both tests:
    the case and the study run its four runs with the same inputs, so they give it bit for
    bit; served, a run of other inputs would be computed and differ)."""
    return sh.effects(_problem(), mesh_size=0.2, time_steps=50, estimate=False).to_dict()


def test_an_effects_case_is_the_effect_table(tmp_path, table):
    [case] = _spec(tmp_path).cases()
    outputs = KINDS["effects"].case(case.params).outputs
    assert set(outputs) == set(KINDS["effects"].outputs)
    assert table["effects"] == ["pad", "friction"]
    full = next(run for run in table["runs"] if run["label"] == "full")["changes"]
    for key in EFFECT_QUANTITIES:
        dominant = table["dominant"][key]
        assert EFFECT_NAMES[int(outputs[f"dominant_{key}"])] == dominant["effect"]
        assert outputs[f"change_{key}"] == full[key]["change"]  # the same runs: bit for bit
        assert math.isnan(outputs[f"resolved_{key}"])  # no estimate: no bars, unknown
    # the pad stops the striker short of the half-space's x_c: a change the mesh resolves
    assert outputs["change_x_max"] < -0.01


def test_an_effects_sweep_refuses_a_part_out_of_range_at_load(tmp_path):
    with pytest.raises(SweepError, match="friction"):
        _spec(tmp_path, SWEEP.replace("friction = 0.5", "friction = -1.0"))


STUDY = """\
kind = "effects"
[indenter]
shape_coefficient = 5.0
exponent = 1.5
[half_space]
E2 = 7.5e6
nu2 = 0.5
density2 = 0.0
[impact]
mass = 0.7
velocity = 3.0
interface = "bonded"
friction = 0.5
[layer]
thickness = 0.02
[numerics]
mesh_size = 0.2
time_steps = 50
estimate = false
"""


def test_an_effects_study_writes_the_table_of_sh_effects(tmp_path, table):
    """Old code: ``kind = "effects"`` was no study kind. The study's files are those of
    ``shtaerman effects --out``, their table that of ``sh.effects`` on the same problem."""
    import json

    from shtaerman.output.folder import study_entry
    from shtaerman.study.run import run_study
    from shtaerman.study.schema import load_study

    path = tmp_path / "pad.toml"
    path.write_text(STUDY)
    [study] = load_study(path)
    outcome = run_study(study)
    entry = study_entry(outcome, tmp_path)
    written = json.loads((tmp_path / "pad" / "effects.json").read_text())
    assert written["dominant"] == table["dominant"] == entry["effects"]["dominant"]
    for mine, theirs in zip(written["runs"], table["runs"], strict=True):
        assert mine["changes"] == theirs["changes"], mine["label"]  # the same runs
    assert {"effects.csv", "effects.md"} <= {p.name for p in (tmp_path / "pad").iterdir()}
    from shtaerman.api.effect_table.figure import EFFECTS_CAPTION  # the report shows the figure

    assert entry["figures"] == {EFFECTS_CAPTION: "pad/effects.png"}
    assert entry["findings"][0].startswith("P_max moves most with pad alone")


def _problem():
    return Problem.impact(
        sh.PowerLawIndenter(5.0, 1.5),
        sh.Material(7.5e6, 0.5, 0.0),
        mass=0.7,
        velocity=3.0,
        thickness=0.02,
        interface="bonded",
        friction=0.5,
    )


def _swept(axes: dict, dominant: list[float]) -> dict:
    """A finished effects sweep's results.json over ``axes`` whose cases found ``dominant``
    (indices into EFFECT_NAMES; NaN: a failed case) for P_max."""
    kind = KINDS["effects"]
    cases = [
        {"status": "ok", "outputs": {"dominant_P_max": value}}
        if math.isfinite(value)
        else {"status": "failed", "outputs": {}}
        for value in dominant
    ]
    return {
        "spec": {"name": "map", "kind": "effects", "axes": axes},
        "kind": {
            "outputs": {"dominant_P_max": ""},
            "levels": {},
            "categories": {"dominant_P_max": list(kind.categories["dominant_P_max"])},
            "parameter_units": {name: p.unit for name, p in kind.parameters.items()},
        },
        "cases": cases,
    }


@pytest.mark.parametrize(
    "axes", [{"velocity": [0.5, 1.0, 2.0]}, {"thickness": [0.01, 0.03], "velocity": [1.0, 2.0]}]
)
def test_a_sweeps_dominant_effect_is_drawn_by_name(axes):
    """The dominant effect is an index into EFFECT_NAMES in cases.csv; its figure names it
    (a curve's ticks, a heat map's cells), where it drew the index as a number (3.0, 0.0).
    adv53: the curve's axis listed all five effects, also those absent from the case (finite
    strain, friction): it lists the ones its cases found."""
    from shtaerman.sweep.figures import figure_files

    count = math.prod(len(values) for values in axes.values())
    dominant = [3.0, 0.0, 0.0, math.nan][:count]
    files = figure_files(_swept(axes, dominant), "dominant_P_max", "", "svg")
    svg = files["dominant_P_max.svg"].decode()
    assert "viscoelasticity" in svg and "Dominant single effect on P_max" in svg
    if len(axes) == 2:  # each cell says its effect, a failed one says so; no colour bar
        assert svg.count(">pad<") == 2 and "failed" in svg and "finite strain" not in svg
    else:  # each effect found is a tick, no other, none of the index's numbers is
        shown = [name for name in EFFECT_NAMES if name in svg]
        assert shown == ["pad", "viscoelasticity"] and ">3.0<" not in svg
