"""The nested ladder of the finite-strain error estimates (study/ladder.py, study/finite).

The nested levels are one gmsh mesh and its uniform refinements: their vertices nest and their
estimates climb a ratio-2 ladder. The tiny-study comparison runs the shipped paper case on its
coarse [quick] mesh and depths, once on the old ladder of independent gmsh meshes and once on
the nested one (about 40 s of CPU time together).
"""

from __future__ import annotations

import itertools
from dataclasses import replace
from pathlib import Path
from types import SimpleNamespace

import numpy as np
import pytest

from shtaerman.fem.mesh import MeshSettings
from shtaerman.plots.finite import panel_points
from shtaerman.study.finite.accuracy import estimate_study
from shtaerman.study.finite.runner import LADDER_RATIOS, _run_level, ladder, ladder_meshes
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
        out[nested] = estimate_study(outcomes, factors, LADDER_RATIOS[nested])
    return out


def test_nested_ladder_falls_back_less_than_the_old_one(tiny):
    old, _ = tiny[False].fallbacks()
    new, total = tiny[True].fallbacks()
    assert tiny[True].refines == (0.5, 1.0, 2.0)
    assert new < old  # measured 38 against 50 of 57
    assert tiny[True].to_dict()["fallbacks"] == {"count": new, "of": total}


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
    from shtaerman.fem.finite_contact import check_finite_depths

    indenter = load_study(SHIPPED)[0].indenter
    with pytest.raises(InputError, match="beyond the yeoh model's"):
        check_finite_depths(indenter, [1e-4, 0.05], "yeoh")
    with pytest.raises(InputError, match="below the gent model's"):
        check_finite_depths(indenter, [1e-24, 1e-3], "gent")


def test_the_ladder_is_independent_unless_the_study_file_asks_for_nested(tmp_path):
    shipped, nested = load_study(SHIPPED), load_study(NESTED)
    assert {s.mesh_ladder for s in shipped} == {"independent"}
    assert {s.mesh_ladder for s in nested} == {"nested"}
    assert [s.mesh for s in nested] == [s.mesh for s in shipped]  # same refine = 0.8 mesh
    assert {s.name for s in nested}.isdisjoint(s.name for s in shipped)
    factors, meshes = ladder_meshes(shipped[0].mesh)  # the default: three gmsh meshes
    assert factors == pytest.approx([0.5, 2**-0.5, 1.0]) and meshes[-1] == shipped[0].mesh
    path = tmp_path / "bad.toml"
    path.write_text(NESTED.read_text().replace('ladder = "nested"', 'ladder = "nest"'))
    with pytest.raises(StudyError, match=r"ladder': expected independent or nested, got 'nest'"):
        load_study(path)
    path.write_text(NESTED.read_text().replace('ladder = "nested"', "ladder = 3"))
    with pytest.raises(StudyError, match=r"numerics.ladder': expected independent or nested"):
        load_study(path)
