"""A contact study and a sweep on a layer: the [layer] keys, the thickness_ratio spelling
(H / a_c at the half-space impact's x_c) and what a layer does to the force and the impact."""

from __future__ import annotations

import itertools
import math

import numpy as np
import pytest
from study_texts import PAPER_CASE

from shtaerman.cli import main
from shtaerman.study.contact.runner import run_contact_study
from shtaerman.study.schema import StudyError, load_study
from shtaerman.sweep.kinds import get_kind
from shtaerman.sweep.spec import parse_sweep
from shtaerman.theory.contact import PowerLawContact
from shtaerman.theory.impact import solve_impact
from shtaerman.theory.layer import thin_layer_limit
from shtaerman.theory.materials import RIGID, Material, effective_modulus
from shtaerman.validation import InputError

STUDY = """
name = "pad"
[indenter]
shape_coefficient = 5.0
exponent = 1.5
[striker]
E1 = {E1}
nu1 = 0.25
[half_space]
E2 = 7.5e6
nu2 = {nu2}
[impact]
mass = 0.7
velocity = 3.0
[numerics]
mesh_size = 0.025
growth = 0.5
axis_size = 1e-3
axis_growth = 0.3
"""
"""The paper's example on a coarse ladder (finest level about 3k dofs)."""


def _write(tmp_path, extra: str, E1: str = "2e11", nu2: float = 0.5):
    path = tmp_path / "pad.toml"
    path.write_text(STUDY.format(E1=E1, nu2=nu2) + extra, encoding="utf-8")
    return path


def _half_space_a_c(E1: float = 2e11, nu2: float = 0.5) -> float:
    """The paper's half-space contact radius at x_c, computed independently of the loader."""
    from shtaerman.theory.indenter import PowerLawIndenter

    modulus = effective_modulus(Material(E1, 0.25), Material(7.5e6, nu2))
    law = PowerLawContact(PowerLawIndenter(5.0, 1.5), modulus)
    return solve_impact(0.7, 3.0, law).a_c


# --- the loader -----------------------------------------------------------------------------


def test_thickness_in_metres_reaches_the_mesh(tmp_path):
    (study,) = load_study(_write(tmp_path, '[layer]\nthickness = 0.02\nbase = "lubricated"\n'))
    assert study.geometry.thickness == 0.02 and study.geometry.base == "lubricated"
    assert study.layer.thickness_ratio == pytest.approx(0.02 / _half_space_a_c(), rel=1e-12)


def test_thickness_ratio_is_h_over_the_half_space_contact_radius_at_x_c(tmp_path):
    (study,) = load_study(_write(tmp_path, "[layer]\nthickness_ratio = 3.0\n"))
    a_c = _half_space_a_c()
    assert 9e-3 < a_c < 1.1e-2  # the paper's a_c, about 10 mm
    assert study.geometry.thickness == pytest.approx(3.0 * a_c, rel=1e-12)
    assert study.geometry.base == "bonded"  # the default base


def test_a_half_space_study_has_no_layer(tmp_path):
    (study,) = load_study(_write(tmp_path, ""))
    assert study.layer is None and study.geometry.thickness is None


def test_a_layer_that_is_no_table_is_refused_naming_the_table(tmp_path):
    path = tmp_path / "top.toml"
    path.write_text("layer = 5\n" + STUDY.format(E1="2e11", nu2=0.5), "utf-8")
    with pytest.raises(StudyError, match=r"key 'layer': expected a \[layer\] table: .*, got 5$"):
        load_study(path)


def test_a_top_level_thickness_goes_to_the_layer_table(tmp_path):
    path = tmp_path / "top.toml"
    path.write_text("thickness_ratio = 2.0\n" + STUDY.format(E1="2e11", nu2=0.5), "utf-8")
    (study,) = load_study(path)
    assert study.geometry.thickness == pytest.approx(2.0 * _half_space_a_c(), rel=1e-12)


def test_sweeping_the_thickness_ratio_makes_one_study_per_thickness(tmp_path):
    extra = '[layer]\nbase = "lubricated"\n[sweep]\nthickness_ratio = [0.5, 5.0]\n'
    studies = load_study(_write(tmp_path, extra))
    assert [s.name for s in studies] == ["pad-Ha0.5", "pad-Ha5"]
    a_c = _half_space_a_c()
    assert [s.geometry.thickness for s in studies] == pytest.approx([0.5 * a_c, 5.0 * a_c])
    assert {s.geometry.base for s in studies} == {"lubricated"}


@pytest.mark.parametrize(
    ("extra", "message"),
    [
        (
            "[layer]\nthickness_ratio = 0.01\n",
            r"key 'layer\.thickness_ratio': thickness_ratio must lie in \[0\.05, 500\], got 0\.01$",
        ),
        ("[layer]\nthickness = -0.02\n", r"key 'layer\.thickness': thickness must be > 0"),
        ("[layer]\nthickness = 0.0\n", r"key 'layer\.thickness': thickness must be > 0"),
        (
            '[layer]\nthickness = 0.02\nbase = "glued"\n',
            r"key 'layer\.base': expected one of \"bonded\", \"lubricated\", got 'glued'$",
        ),
        ("[layer]\nthickness = 0.02\nthickness_ratio = 2.0\n", r"key 'layer\.thickness_ratio'"),
        ('[layer]\nbase = "bonded"\n', r"key 'layer': expected thickness .* \(required\)$"),
        (
            "[layer]\nthickness = 0.02\n[sweep]\nthickness_ratio = [1.0, 2.0]\n",
            r"key 'sweep\.thickness_ratio': expected the layer's thickness once",
        ),
        (
            "[sweep]\nthickness_ratio = [1.0, 1000.0]\n",
            r"key 'sweep\.thickness_ratio': expected a number in \[0\.05, 500\]",
        ),
        ("[layer]\nthicknes = 0.02\n", r"key 'layer\.thicknes'.*did you mean 'thickness'"),
        (
            "[convergence]\nsizes = [0.02, 0.014]\n[sweep]\nthickness = [0.01, 0.02]\n",
            r"key 'convergence': expected no mesh-convergence study on a layer",
        ),
        ("[layer.thickness]\nvalue = 0.02\n", r"key 'layer\.thickness': expected a number > 0"),
    ],
)
def test_the_loader_refuses_a_bad_layer_in_one_line(tmp_path, extra, message):
    with pytest.raises(StudyError, match=message) as caught:
        load_study(_write(tmp_path, extra))
    assert "\n" not in str(caught.value)


def test_verify_refuses_a_bad_layer_with_exit_code_2(tmp_path, capsys):
    path = _write(tmp_path, "[layer]\nthickness_ratio = -1.0\n")
    assert main(["verify", str(path), "--out", str(tmp_path / "out")]) == 2
    error = capsys.readouterr().err.strip()
    assert "layer.thickness_ratio" in error and "[0.05, 500]" in error
    assert len(error.splitlines()) == 1


@pytest.mark.parametrize("thickness", [1e-6, 30.0])
def test_a_thickness_the_mesh_cannot_take_is_refused_at_load(tmp_path, thickness):
    path = _write(tmp_path, f"[layer]\nthickness = {thickness}\n")
    # the ends are 0.00026064 and 26.064 m, printed rounded inward (26.1 would be refused)
    with pytest.raises(
        StudyError, match=r"pad\.toml: key 'layer\.thickness': must lie in \[0\.000261, 26\] m"
    ):
        load_study(path)
    text = "thickness = [1e-6]"
    with pytest.raises(InputError, match=r"case 0 \(thickness = 1e-06\): thickness: must lie in"):
        parse_sweep(SWEEP.format(parameters="", axes=text))


def test_the_load_time_bounds_are_the_mesh_s(tmp_path):
    from shtaerman.fem.mesh import Geometry
    from shtaerman.study.contact.indentation import run_indentation

    extra = "[contact]\ndepths = [1e-3, 4e-3]\n[layer]\nthickness = 1e-6\n"
    with pytest.raises(StudyError) as at_load:
        load_study(_write(tmp_path, extra))
    (study,) = load_study(_write(tmp_path, extra.replace("1e-6", "0.01")))
    thin = Geometry(1e-6)
    with pytest.raises(InputError) as at_run:  # refused before meshing
        run_indentation(study.indenter, study.half_space, [1e-3, 4e-3], study.mesh, geometry=thin)
    bounds = str(at_run.value).split(" m at ")[0].removeprefix("thickness: must lie in ")
    said = f"key 'layer.thickness': must lie in {bounds} m at this study's depths"
    assert said in str(at_load.value), at_load.value


# --- what a layer does ------------------------------------------------------------------------


@pytest.fixture(scope="module")
def bonded_pair(tmp_path_factory):
    """The coarse paper example on bonded layers of H / a_c = 1 and 10 (nu2 = 0.3)."""
    extra = '[layer]\nbase = "bonded"\n[sweep]\nthickness_ratio = [1.0, 10.0]\n'
    path = _write(tmp_path_factory.mktemp("pair"), extra, nu2=0.3)
    return tuple(run_contact_study(study) for study in load_study(path))


def test_the_force_ratio_grows_as_the_layer_thins_and_the_impact_stiffens(bonded_pair):
    thin, thick = bonded_pair
    # bonded, nu 0.3: about 3.0 at H/a_c = 1 and 1.10 at 10 (FEM_NOTES "Layer"); a layer on a
    # rigid base is stiffer than the half-space, and more so the thinner it is
    assert thin.layer.force_ratio > thick.layer.force_ratio > 1.02
    assert 2.5 < thin.layer.force_ratio < 3.5
    for outcome in (thin, thick):
        layer = outcome.layer
        assert layer.force_ratio_error < 1e-2  # the coarse ladder's own estimate
        assert layer.x_max_ratio < 1.0 < layer.P_max_ratio  # shallower and harder impact
        physical = [check for check in outcome.checks if "estimate" not in check.name]
        assert len(physical) == 3 and all(check.passed for check in physical)
    assert thin.layer.P_max_ratio > thick.layer.P_max_ratio
    # over the depths H / a falls as a grows, and the ratio rises with it
    h, ratio = zip(*thin.layer.curve, strict=True)
    assert all(a > b for a, b in itertools.pairwise(h))
    assert all(a < b for a, b in itertools.pairwise(ratio))


def test_a_thin_lubricated_layer_tends_to_its_foundation_limit(tmp_path):
    # rigid striker: the FE law is not rescaled, so the thin limit compares directly; k = E*/H
    (study,) = load_study(
        _write(tmp_path, '[layer]\nthickness_ratio = 0.1\nbase = "lubricated"\n', E1='"inf"')
    )
    outcome = run_contact_study(study)
    x_c = outcome.impacts["analytic"]["x_c"]
    body = Material(7.5e6, 0.5)
    limit = thin_layer_limit(study.indenter, body, study.layer.thickness, "lubricated")
    fem = outcome.law.force(x_c)
    # the sliding foundation is the limit to 3e-5 at H/a = 0.1 (FEM_NOTES "Layer"); the coarse
    # mesh adds its error, about 1e-3
    assert fem / float(limit.force(x_c)) == pytest.approx(1.0, abs=5e-3)
    assert outcome.layer.force_ratio > 20.0  # against the half-space: far stiffer
    assert effective_modulus(RIGID, body) == pytest.approx(1e7)


# --- the sweep spelling -----------------------------------------------------------------------

SWEEP = """
name = "pads"
kind = "layer"
[parameters]
{parameters}
[axes]
{axes}
"""


def test_the_layer_sweep_resolves_thickness_ratio_to_h():
    spec = parse_sweep(SWEEP.format(parameters="nu2 = 0.3", axes="thickness_ratio = [0.5, 20]"))
    kind = get_kind("layer")
    studies = [kind.check(case.params) for case in spec.cases()]
    a_c = _half_space_a_c(nu2=0.3)
    assert [s.geometry.thickness for s in studies] == pytest.approx([0.5 * a_c, 20 * a_c])
    assert [s.layer.thickness_ratio for s in studies] == [0.5, 20.0]
    assert {s.geometry.base for s in studies} == {"bonded"}


def test_the_layer_sweep_takes_a_thickness_in_metres():
    text = SWEEP.format(parameters="", axes='thickness = [0.01, 0.02]\nbase = ["lubricated"]')
    studies = [get_kind("layer").check(case.params) for case in parse_sweep(text).cases()]
    assert [s.geometry.thickness for s in studies] == [0.01, 0.02]
    assert studies[1].layer.thickness_ratio == pytest.approx(0.02 / _half_space_a_c())
    assert studies[0].geometry.base == "lubricated"


def test_a_layer_sweep_case_is_the_study_of_the_same_file(tmp_path):
    """One path: a case's study is checked and resolved as a study file's (contact_study),
    so the sweep and the file agree on the layer and its mesh."""
    [case] = parse_sweep(
        SWEEP.format(parameters="nu2 = 0.5", axes="thickness_ratio = [2.0]")
    ).cases()
    swept = get_kind("layer").check(case.params)
    path = tmp_path / "pad.toml"
    path.write_text(
        PAPER_CASE + "[striker]\nE1 = 2e11\nnu1 = 0.25\n[layer]\nthickness_ratio = 2.0\n"
    )
    [study] = load_study(path)
    assert swept.layer == study.layer and swept.mesh == study.mesh
    assert swept.layer.thickness == pytest.approx(2.0 * _half_space_a_c(nu2=0.5), rel=1e-15)


@pytest.mark.parametrize(
    ("parameters", "axes", "message"),
    [
        (
            "",
            "thickness_ratio = [0.01]",
            r"axes.thickness_ratio\[0\] must lie in \[0\.05, 500\], got 0\.01$",
        ),
        ("", "thickness = [-1.0]", r"axes.thickness\[0\] must be > 0 m"),
        (
            'base = "glued"',
            "thickness = [0.01]",
            r"parameters.base must be one of \['bonded', 'lubricated'\], got 'glued'$",
        ),
    ],
)
def test_the_layer_sweep_refuses_bad_values_at_load(parameters, axes, message):
    with pytest.raises(InputError, match=message) as caught:
        parse_sweep(SWEEP.format(parameters=parameters, axes=axes))
    assert "\n" not in str(caught.value)


@pytest.mark.parametrize(
    ("axes", "got"),
    [("nu2 = [0.3]", "neither"), ("thickness = [0.01]\nthickness_ratio = [2.0]", "thickness and")],
)
def test_the_layer_sweep_needs_exactly_one_thickness(axes, got):
    with pytest.raises(InputError, match=r"case 0 .*: thickness: give the layer's thickness") as e:
        parse_sweep(SWEEP.format(parameters="", axes=axes))
    assert f"exactly one of them; got {got}" in str(e.value) and "\n" not in str(e.value)


def test_the_shipped_layer_sweeps_span_the_question():
    from shtaerman.sweep.spec import find_sweep, load_sweep

    spec = load_sweep(find_sweep("layer"))
    ratios = spec.axes["thickness_ratio"]
    assert min(ratios) == 0.1 and max(ratios) >= 100.0
    assert spec.axes["nu2"] == [0.3, 0.45, 0.5]
    assert spec.axes["base"] == ["bonded", "lubricated"]
    assert math.isclose(spec.parameters["velocity"], 3.0)


# --- the report -------------------------------------------------------------------------------


def test_a_layer_study_reports_its_departure_as_a_finding_with_the_map(bonded_pair, tmp_path):
    from PIL import Image

    from shtaerman.output import text_contact
    from shtaerman.plots.gallery import study_figures
    from shtaerman.plots.layer import LAYER_MAP_CAPTION

    thin = bonded_pair[0]
    document = text_contact.entry(thin, files={})
    assert document["layer"]["force_ratio"] == thin.layer.force_ratio
    assert document["layer"]["restitution"] is None  # the dynamic impact on a layer: not here
    (finding,) = text_contact.findings("pad", document)
    assert "layer on a bonded rigid base (H / a_c = 1," in finding
    assert f"carries {100 * (thin.layer.force_ratio - 1):.3g} % ±" in finding
    assert text_contact.summary_row("pad", document) is None  # no error against Shtaerman
    impact = text_contact.tables(document)[0]
    assert [row[0] for row in impact["rows"]][::2] == [
        "half-space (Shtaerman, Ateb)",
        "layer: FEM P(x) tabulated, ODE",
    ]
    figures = study_figures(thin, tmp_path)
    image = Image.open(figures[LAYER_MAP_CAPTION]).convert("L")
    assert image.size == (1280, 920)
    assert np.unique(np.asarray(image)).size > 50  # lines, bands and text, not a blank canvas


def test_the_template_s_layer_block_loads_once_uncommented(tmp_path):
    path = tmp_path / "pad.toml"
    assert main(["init-study", str(path)]) == 0
    lines = path.read_text(encoding="utf-8").splitlines()
    start = lines.index(next(line for line in lines if line.startswith("# [layer]")))
    block = [line.removeprefix("# ") for line in lines[start : start + 5]]  # comments stay
    path.write_text("\n".join(lines + block) + "\n", encoding="utf-8")
    (study,) = load_study(path)
    assert study.layer.thickness_ratio == 5.0 and study.geometry.base == "bonded"
    assert study.geometry.thickness == pytest.approx(5.0 * _half_space_a_c(), rel=1e-12)


def test_the_reference_map_is_what_the_layer_study_computes(bonded_pair):
    from shtaerman.study.contact.layer import REFERENCE_MAP, REFERENCE_THICKNESS

    thin, thick = bonded_pair  # H / a_c = 1 and 10, bonded, nu2 = 0.3, coarse mesh
    measured = dict(zip(REFERENCE_THICKNESS, REFERENCE_MAP[("bonded", 0.3)], strict=True))
    # the reference was measured at the default mesh; the coarse ladder (3k dofs) is within
    # its own error estimate of it
    for outcome, h in ((thin, 1.0), (thick, 10.0)):
        error = max(outcome.layer.force_ratio_error, 1e-4)
        assert outcome.layer.force_ratio == pytest.approx(measured[h], rel=2 * error)
