"""The nested ladder of the finite-strain error estimates (study/ladder.py, study/finite).

The nested levels are one gmsh mesh and its uniform refinements: their vertices nest and their
estimates climb a ratio-2 ladder. The tiny-study comparison runs the shipped paper case on its
coarse [quick] mesh and depths, once on the old ladder of independent gmsh meshes and once on
the nested one (about 40 s of CPU time together).
"""

from __future__ import annotations

import itertools
import json
from dataclasses import replace
from pathlib import Path
from types import SimpleNamespace

import numpy as np
import pytest

from shtaerman.fem.mesh import MeshSettings
from shtaerman.output.text_finite import _estimate_finding
from shtaerman.plots.finite import panel_points
from shtaerman.study.finite.accuracy import EDGE_ORDER, IMPACT_KEYS, estimate_study
from shtaerman.study.finite.runner import (
    LADDER_RATIOS,
    _run_level,
    estimate_ladder,
    ladder,
    ladder_meshes,
)
from shtaerman.study.ladder import (
    NESTED_RATIO,
    NestedMeshSettings,
    nested_factors,
    nested_ladder,
)
from shtaerman.study.richardson import Estimate, richardson
from shtaerman.study.schema import StudyError, load_study
from shtaerman.theory.contact import PowerLawContact
from shtaerman.theory.impact import solve_impact
from shtaerman.theory.materials import RIGID, effective_modulus
from shtaerman.validation import InputError

SHIPPED = Path(__file__).resolve().parents[1] / "fem" / "finite_strain.toml"
NESTED = SHIPPED.parent / "extended" / "finite_strain_nested.toml"
COARSE = MeshSettings(size=1 / 12, growth=0.8, axis_size=1e-3, axis_growth=0.6)


def test_nested_levels_are_nested():
    levels = nested_ladder(COARSE.refined(2.0))
    assert [level.nested for level in levels] == [0, 1, 2]
    meshes = [level.build(1.0) for level in levels]
    for coarse, fine in itertools.pairwise(meshes):
        n = coarse.p.shape[1]
        assert fine.p.shape[1] > 2 * n and fine.t.shape[1] == 4 * coarse.t.shape[1]
        np.testing.assert_array_equal(fine.p[:, :n], coarse.p)  # coarse vertices first, kept
        assert set(fine.boundaries) == set(coarse.boundaries)
        surface = fine.p[:, np.unique(fine.facets[:, fine.boundaries["surface"]])]
        assert np.any((surface[0] == 1.0) & (surface[1] == 0.0))  # the refined radius' vertex
    assert nested_factors(1.0) == [0.5, 1.0, 2.0]
    assert levels[2].estimated_dofs == 16 * levels[0].estimated_dofs


def test_nested_settings_refuse_bad_levels_and_count_refined_dofs():
    with pytest.raises(InputError, match="nested must be an integer in"):
        NestedMeshSettings(nested=-1)
    with pytest.raises(InputError, match="nested must be"):
        NestedMeshSettings(nested=1.5)
    with pytest.raises(InputError, match="nested must be"):
        NestedMeshSettings(nested=True)
    with pytest.raises(InputError, match="max_dofs"):
        nested_ladder(replace(COARSE, max_dofs=2000.0).refined(2.0))
    with pytest.raises(InputError, match="refine"):  # the coarse level: growth 0.8 * 2 > 1
        nested_ladder(COARSE)


def test_richardson_on_a_ratio_two_ladder_recovers_a_known_order():
    h = np.array([1.0, 0.5, 0.25])
    values = 3.0 + 0.2 * h**2 + 0.01 * h**3
    e = richardson(values, NESTED_RATIO)
    assert e.method == "richardson"
    assert e.order == pytest.approx(2.0, abs=0.15)
    true = abs(values[-1] / 3.0 - 1.0)
    assert 0.8 < e.error / true < 1.2


@pytest.fixture(scope="module")
def tiny():
    """The paper case on its [quick] mesh and depths: both ladders' estimates."""
    study = load_study(SHIPPED)[0]
    study = replace(study, mesh=study.quick_mesh, ladder=study.quick_ladder)
    modulus = effective_modulus(RIGID, study.half_space)
    impact = solve_impact(study.mass, study.velocity, PowerLawContact(study.indenter, modulus))
    depths = ladder(study.indenter, modulus, impact.x_c, study.ladder)
    out = {}
    for nested in (False, True):
        factors, meshes = ladder_meshes(study.mesh, nested)
        outcomes = [_run_level(study, depths, mesh, impact, False) for mesh in meshes]
        out[nested] = estimate_ladder(outcomes, factors, nested)
        out[nested, "richardson"] = estimate_study(outcomes, factors, LADDER_RATIOS[nested])
    return out


def test_nested_ladder_falls_back_less_than_the_old_one(tiny):
    old, _ = tiny[False].fallbacks()
    new, total = tiny[True].fallbacks()
    assert tiny[True].refines == (0.5, 1.0, 2.0)
    assert new < tiny[True, "richardson"].fallbacks()[0] < old  # measured 20, 38, 50 of 57
    assert tiny[True].to_dict()["fallbacks"] == {"count": new, "of": total}
    # independent gmsh levels: Richardson alone, as before the nested ladder's rules
    same = [json.dumps(tiny[False, k].to_dict()) for k in ("richardson",)]
    assert json.dumps(tiny[False].to_dict()) == same[0]


DEPTHS = np.array([1e-3, 2e-3, 4e-3])


class _Level:
    """A synthetic ladder level of element size h: forces converging at order 2 whose ratio's
    error changes sign between levels, and an edge radius converging at order between 1 and 2."""

    def __init__(self, h: float):
        self.seconds = self.cpu_seconds = 1.0
        self.finite = SimpleNamespace(curve=SimpleNamespace(mesh_stats={"dofs": int(1e3 / h**2)}))
        self.cancel = 1.0 + 0.1 * h**2 - 0.15 * h**3  # P / P_linear-FEM: -0.05, +6e-3, +4e-3
        self.h = h
        finite = {key: (1.0 + k) * (1.0 + 0.3 * h**2) for k, key in enumerate(IMPACT_KEYS)}
        finite["a_c"] = 0.01 * (1.0 + 0.1 * h + 0.05 * h**2)
        self.impacts = {
            "finite_strain": finite,
            "linear_fem": {key: v / self.cancel for key, v in finite.items()},
        }
        self.impacts["finite_strain"]["x_c"] = 3e-3 * (1.0 + 0.01 * h**2)

    def rows(self) -> list[dict[str, float]]:
        h, out = self.h, []
        for d in DEPTHS:
            force = 1e6 * d**1.5 * (1.0 + 0.3 * h**2)
            edge = 1.0 + 0.1 * h + 0.05 * h**2  # observed order 1.35
            out.append(
                {
                    "depth": d,
                    "depth_to_radius": d / 0.01,
                    "force": force,
                    "force_linear_fem": force / self.cancel,
                    "force_ratio": 1.0 + 0.3 * h**2,
                    "force_ratio_fem": self.cancel,
                    "radius_ratio": edge,
                    "central_to_mean": 2.5 / edge**2,
                    "strain_energy": d**2.5 * (1.0 + 0.2 * h**2),
                }
            )
        return out

    def at_maximum(self) -> dict[str, float]:
        x_c, rows = self.impacts["finite_strain"]["x_c"], self.rows()
        at = {}
        for key in ("force_ratio", "force_ratio_fem", "radius_ratio", "central_to_mean"):
            at[key] = float(np.interp(np.log(x_c), np.log(DEPTHS), [r[key] for r in rows]))
        return at

    def validity(self, departure_shift=0.0) -> list[dict[str, object]]:
        return [{"status": "beyond", "depth_to_radius": 0.4, "depth": 4e-3, "velocity": 1.0}]


def test_nested_rules_propagate_ratios_and_use_the_edge_order():
    levels = [_Level(h) for h in (1.0, 0.5, 0.25)]
    plain = estimate_study(levels, [0.5, 1.0, 2.0], NESTED_RATIO)
    rules = estimate_study(levels, [0.5, 1.0, 2.0], NESTED_RATIO, propagate=True, edge_order=True)
    rows = [level.rows() for level in levels]
    for k, (old, new) in enumerate(zip(plain.steps, rules.steps, strict=True)):
        assert old["force_ratio_fem"].method == old["radius_ratio"].method == "two-level"
        factors = [
            richardson([r[k][key] for r in rows], 2.0) for key in ("force", "force_linear_fem")
        ]
        assert new["force_ratio_fem"].method == "propagated"
        assert new["force_ratio_fem"].error == pytest.approx(factors[0].error + factors[1].error)
        edge = [r[k]["radius_ratio"] for r in rows]  # first order: the correction is d2 / (2 - 1)
        assert (
            new["radius_ratio"].method == "richardson" and new["radius_ratio"].order == EDGE_ORDER
        )
        assert new["radius_ratio"].extrapolated == pytest.approx(2 * edge[2] - edge[1], rel=1e-14)
        assert new["force_ratio"] == old["force_ratio"]  # the rest unchanged
    for key in ("P_c_vs_fem", "force_ratio_fem_at_x_c"):
        assert (
            plain.scalars[key].method == "two-level" and rules.scalars[key].method == "propagated"
        )
    assert (
        rules.scalars["a_c"].order == EDGE_ORDER
        and rules.scalars["a_c_vs_fem"].method == "propagated"
    )
    assert rules.fallbacks()[0] < plain.fallbacks()[0]
    assert rules.fallbacks() == (0, plain.fallbacks()[1])
    finding = _estimate_finding(SimpleNamespace(estimates=rules, rows=levels[-1].rows))
    assert f"0 of {plain.fallbacks()[1]} estimates fell back" in finding
    assert "contact edge's first order" in finding and "sum of their two factors'" in finding


class _Oscillating(_Level):
    """P/(beta x^q) whose error, 0.3 h^2 at every depth, changes sign at the middle depth on the
    middle level (the contact edge at another place between the nodes)."""

    def rows(self) -> list[dict[str, float]]:
        out = super().rows()
        out[1]["force_ratio"] = 1.0 + (-1.0 if self.h == 0.5 else 1.0) * 0.3 * self.h**2
        return out


def test_every_depth_carries_at_least_its_neighbourhoods_envelope():
    levels = [_Oscillating(h) for h in (1.0, 0.5, 0.25)]
    plain = estimate_study(levels, [0.5, 1.0, 2.0], NESTED_RATIO)
    rules = estimate_study(levels, [0.5, 1.0, 2.0], NESTED_RATIO, envelopes=True)
    assert plain.steps[1]["force_ratio"].method == "two-level"  # +0.375 then -0.094
    assert plain.steps[0]["force_ratio"].method == "richardson"  # 0.225 then 0.056
    # largest differences over the depths 0.375 then 0.094 (the middle depth), order 2:
    # every depth (each sees the middle one) carries 0.094 / (2^2 - 1) relative to 1.01875
    for step in rules.steps:
        assert step["force_ratio"].method == "envelope"
        assert step["force_ratio"].error == pytest.approx(0.09375 / 3 / 1.01875, rel=1e-12)
    assert plain.steps[0]["force_ratio"].error < rules.steps[0]["force_ratio"].error
    assert rules.fallbacks()[0] < plain.fallbacks()[0]
    assert rules.scalars["force_ratio_worst"].method == "envelope"


def test_the_independent_ladders_finding_names_the_nested_remedy():
    levels = [_Level(h) for h in (1.0, 2**-0.5, 0.5)]
    plain = estimate_study(levels, [0.5, 2**-0.5, 1.0], LADDER_RATIOS[False])
    finding = _estimate_finding(SimpleNamespace(estimates=plain, rows=levels[-1].rows))
    assert "noise of non-nested meshes" in finding and 'ladder = "nested"' in finding


def _estimate(value: float, error: float) -> Estimate:
    return Estimate(value, value, error, 2.0, "richardson")


def test_unresolved_points_are_drawn_open_without_an_error_bar():
    """A depth whose estimated error exceeds the finite-strain effect is no data."""
    finite = np.array([1.0005, 1.02, 1.05])  # effects against linear 1.0: 5e-4, 2e-2, 5e-2
    relative = [1e-3, 1e-3, 1e-3]  # exceeds the first effect only
    steps = [{"force_ratio": _estimate(v, e)} for v, e in zip(finite, relative, strict=True)]
    outcome = SimpleNamespace(estimates=SimpleNamespace(steps=steps))
    drawn = panel_points(outcome, (finite, np.ones(3), np.ones(3)), "force_ratio")
    assert drawn["unresolved"].tolist() == [True, False, False]
    assert np.isnan(drawn["error"][0])
    np.testing.assert_allclose(drawn["error"][1:], 1e-3 * finite[1:])
    quick = panel_points(SimpleNamespace(estimates=None), (finite, np.ones(3), np.ones(3)), "x")
    assert quick["error"] is None and not quick["unresolved"].any()


def test_sweep_files_sweep_the_rubber_model(tmp_path):
    from shtaerman.sweep import SweepError, load_sweep
    from shtaerman.sweep.kinds import _finite_inputs

    path = tmp_path / "s.toml"
    head = 'name = "f"\nkind = "finite-strain"\n'
    path.write_text(
        f'{head}[parameters]\nmooney_ratio = 0.3\n[axes]\nmodel = ["neo-hookean", "mooney-rivlin"]'
    )
    cases = load_sweep(path).cases()
    rubbers = [_finite_inputs(case.params).rubber for case in cases]
    assert [r.name for r in rubbers] == ["neo-hookean", "mooney-rivlin"]
    assert rubbers[1].mooney_ratio == 0.3
    path.write_text(head + '[axes]\nmodel = ["neo-hookean", "linear"]\n')
    with pytest.raises(SweepError, match="model"):
        load_sweep(path)


def test_depth_range_message_names_the_model_in_use():
    from shtaerman.fem.contact.finite import check_finite_depths

    indenter = load_study(SHIPPED)[0].indenter
    with pytest.raises(InputError, match="beyond the yeoh model's"):
        check_finite_depths(indenter, [1e-4, 0.05], "yeoh")
    with pytest.raises(InputError, match="below the gent model's"):
        check_finite_depths(indenter, [1e-24, 1e-3], "gent")


def test_the_ladder_is_independent_unless_the_study_file_asks_for_nested(tmp_path):
    shipped, nested = load_study(SHIPPED), load_study(NESTED)
    assert {s.mesh_ladder for s in shipped} == {s.mesh_ladder for s in nested} == {"nested"}
    for coarser, finer in zip(shipped, nested, strict=True):  # refine 0.6 and 0.8
        assert coarser.mesh.size == pytest.approx(finer.mesh.size * 0.8 / 0.6, rel=1e-12)
        assert coarser.mesh.axis_size == pytest.approx(finer.mesh.axis_size * 0.8 / 0.6)
    assert {s.name for s in nested}.isdisjoint(s.name for s in shipped)
    path = tmp_path / "mine.toml"
    path.write_text(SHIPPED.read_text().replace('ladder = "nested"', ""))
    default = load_study(path)
    assert {s.mesh_ladder for s in default} == {"independent"}
    factors, meshes = ladder_meshes(default[0].mesh)  # the default: three gmsh meshes
    assert factors == pytest.approx([0.5, 2**-0.5, 1.0]) and meshes[-1] == default[0].mesh
    path = tmp_path / "bad.toml"
    path.write_text(NESTED.read_text().replace('ladder = "nested"', 'ladder = "nest"'))
    with pytest.raises(StudyError, match=r"ladder': expected independent or nested .*, got 'nest'"):
        load_study(path)
    path.write_text(NESTED.read_text().replace('ladder = "nested"', "ladder = 3"))
    with pytest.raises(StudyError, match=r"numerics.ladder': expected independent or nested"):
        load_study(path)
