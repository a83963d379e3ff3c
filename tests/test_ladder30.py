"""The contact ladder's Coulomb pad (issue 28's case), its failed levels and its advice."""

import json

import pytest
from ladder_helpers import failing_level

import shtaerman as sh
from shtaerman.cli import main

PAD = sh.PowerLawIndenter(8.0, 1.3)
RUBBER = sh.Material(3e6, 0.49)
IMPACT = {"mass": 0.12, "velocity": 1.5, "thickness": 0.012, "interface": "bonded"}


def test_a_node_touching_and_sliding_in_one_step_sticks_where_it_touched():
    """Issue 28's Coulomb pad on its ladder's middle mesh (refine 1/sqrt 2): the edge node
    that touched in a load step, slid and reversed was stuck back where it was before it
    touched, pulled off, touched again, and the stick and slip sets cycled ('did not settle'
    at depth 5.05 mm, on the old code); measured from where it touched, the step settles."""
    result = sh.contact(PAD, RUBBER, **IMPACT, friction=0.5, refine=0.5**0.5, estimate=False)
    # the finer (refine 1) and coarser (1/2) meshes give 85.570 and 85.594 N at the deepest
    # depth: the middle mesh (85.589 N) lies between them, to their spread's rounding
    assert 85.569 < result.force[-1] < 85.595, result.force[-1]


def test_a_load_step_whose_sets_cycle_is_cut_in_smaller_ones(monkeypatch):
    """Every load step's first try reports cycling sets (None) at the 20th step: the step is
    cut in 4 sub-steps, which settle; on the old code the run stopped there ('did not
    settle'). The curve is the uncut one to the load path's own discretisation."""
    from shtaerman.fem.contact import stick

    kwargs = {"friction": 0.5, "refine": 0.5, "estimate": False, **IMPACT}
    uncut = sh.contact(PAD, RUBBER, **kwargs)
    real, calls = stick.stick_slip_step, []

    def cycling_once(*args):
        calls.append(args[1].min())
        return None if len(calls) == 20 else real(*args)

    monkeypatch.setattr(stick, "stick_slip_step", cycling_once)
    cut = sh.contact(PAD, RUBBER, **kwargs)
    # one step more than the uncut run's (the failed try) plus the 4 sub-steps
    taken = [sum(s["active_set_iterations"] for s in r.steps) for r in (uncut, cut)]
    assert taken[1] == taken[0] + 4, taken
    # 4 sub-steps of one of ~100 load steps of ratio 1.02: the path-dependent slip moves the
    # deepest force by the load step's own error, far below the ladder's spread (3e-4;
    # measured: 0 on this step)
    assert abs(cut.force[-1] / uncut.force[-1] - 1.0) < 1e-4, cut.force[-1] / uncut.force[-1] - 1


PAD_CLI = ["contact", "--exponent", "1.3", "--shape-coefficient", "8", "--E2", "3e6"]
PAD_CLI += ["--nu2", "0.49", "--mass", "0.12", "--velocity", "1.5", "--thickness", "0.012"]
PAD_CLI += ["--interface", "bonded", "--friction", "0.5", "--json"]
"""Issue 28's Coulomb pad curve on the command line (its ladder: 6807, 12795, 24350 dofs)."""


def test_a_failed_middle_level_leaves_the_finest_with_its_estimate_said_missing(
    monkeypatch, capsys
):
    failing_level(monkeypatch, 2)
    code = main(PAD_CLI)
    out, err = capsys.readouterr()
    assert code == 0, err
    document = json.loads(out)
    assert document["mesh"]["dofs"] == 24350  # the finest level answers
    assert document["error_estimate"] is None and document["estimate_details"] is None
    assert "refine 0.707: depth 0.005 m: the contact's stick" in document["estimate_missing"]
    dofs = [level["dofs"] for level in document["mesh_ladder"]]
    assert dofs == [6807, None, 24350], dofs
    # the JSON is the API's to_dict (its words); the warning names the option too
    assert "(refine=...)" in document["mesh_ladder"][1]["failure"]
    assert "no error estimate" in err and "the finest level that passed (refine 1)" in err
    assert "--refine" in err, err


def test_a_failed_finest_level_reports_the_finest_that_passed(monkeypatch, capsys):
    failing_level(monkeypatch, 3)
    code = main(PAD_CLI[:-1])  # the text report
    out, err = capsys.readouterr()
    assert code == 0, err
    assert "12795 dofs" in out and "no error estimate (ladder 6807, 12795, failed)" in out, out
    assert "(--refine)" in out and "refine=" not in out, out  # in the option's words
    assert "the finest level that passed (refine 0.707)" in err, err


def test_a_ladder_whose_every_level_fails_names_the_option_to_change(monkeypatch, capsys):
    from shtaerman.fem.contact import stick

    monkeypatch.setattr(stick, "stick_slip_step", lambda *args: None)
    assert main(PAD_CLI) == 1
    err = capsys.readouterr().err
    assert err.count("\n") == 1, err
    assert "did not settle, even in load steps 16 times smaller" in err, err
    assert "(--refine)" in err and "(--mesh-size)" in err, err


def test_the_massless_pad_beyond_the_reach_is_refused_on_every_route():
    """The study and sweep routes call prepare_finite_impact without the API's check: the
    massless frictionless pad beyond the reach (x/a 2.27 > 1.2) is refused there too, before
    any mesh (on the old code it was meshed and then failed in Newton at 2.6 mm)."""
    from shtaerman.fem.finite_dynamic import IMPACT_MESH, prepare_finite_impact
    from shtaerman.fem.finite_dynamic import FiniteImpactSettings as Settings
    from shtaerman.fem.mesh import Geometry
    from shtaerman.validation import InputError

    settings, layer = Settings(mesh=IMPACT_MESH), {"geometry": Geometry(0.012)}
    with pytest.raises(InputError, match=r"a massless body \(density2=0\) cannot pass") as error:
        prepare_finite_impact(PAD, RUBBER, 0.0, 0.12, 1.5, settings, **layer)
    assert "mass, velocity" in str(error.value) and "\n" not in str(error.value)
    # with inertia the frictionless pad is not refused here: it runs with a warning
    assert prepare_finite_impact(PAD, RUBBER, 1000.0, 0.12, 1.5, settings, **layer).mesh["dofs"]
