"""The effects sweep kind: each case is the effect table of ``sh.effects`` reduced to its
dominant effect, its resolution and the full change per quantity, so a sweep maps which
effect dominates. Linear effects only (a pad and friction on a massless body: four ~1 s runs
at mesh 0.2, 50 steps, no estimate)."""

import math

import pytest

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


def test_an_effects_case_is_the_effect_table(tmp_path):
    [case] = _spec(tmp_path).cases()
    outputs = KINDS["effects"].case(case.params).outputs
    assert set(outputs) == set(KINDS["effects"].outputs)
    problem = Problem.impact(
        sh.PowerLawIndenter(5.0, 1.5),
        sh.Material(7.5e6, 0.5, 0.0),
        mass=0.7,
        velocity=3.0,
        thickness=0.02,
        interface="bonded",
        friction=0.5,
    )
    table = sh.effects(problem, mesh_size=0.2, time_steps=50, estimate=False).to_dict()
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
