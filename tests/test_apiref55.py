"""Session 55's adversary pass over the API and the study files (main 56e4a9f): what it
found, fixed. Every case is refused before any mesh is built."""

import math

import pytest
from study_texts import DYNAMIC_STUDY, PAPER_CASE

import shtaerman as sh
from shtaerman.cli import main
from shtaerman.study.schema import StudyError, load_study
from shtaerman.validation import InputError

PAD_STRIKER = sh.PowerLawIndenter(shape_coefficient=8.0, exponent=1.3)  # issue 28's A = 8
RUBBER = sh.Material(youngs_modulus=3e6, poisson_ratio=0.49)


@pytest.mark.parametrize("modulus", [1e-3, 2e7])
def test_contact_refuses_an_elastic_striker_beside_given_depths(modulus):
    """`sh.contact(..., depths=..., striker=Material(E1, 0.25))` ran and ignored the striker
    (the same numbers for E1 = 1e-3 and 2e7): its E1 only sets the default depths' impact,
    so it is refused with depths, as mass and velocity are."""
    with pytest.raises(InputError, match=r"^striker: .*give either depths=\.\.\. or striker") as e:
        sh.contact(PAD_STRIKER, RUBBER, depths=[1e-3, 2e-3], estimate=False, mesh_size=1.0,
                   striker=sh.Material(modulus, 0.25))  # fmt: skip
    assert e.value.parameter == "striker" and "\n" not in str(e.value)


def test_a_curve_with_an_elastic_striker_and_default_depths_is_a_problem():
    """Without depths the striker's E1 sets the impact whose x_c the depths reach (a contact
    study passes its [striker] this way): still taken."""
    steel = sh.Material(2e11, 0.3)
    problem = sh.Problem.curve(PAD_STRIKER, RUBBER, mass=0.12, velocity=1.5, striker=steel)
    assert problem.striker.material == steel


@pytest.mark.parametrize(
    ("given", "said"),
    [
        ({"indenter": PAD_STRIKER, "body": RUBBER, "mass": 0.7, "velocity": 3.0,
          "thickness": 0.02}, "unknown keys ['indenter', 'mass', 'thickness', 'velocity']"),
        ({}, "no striker and no body"),
    ],
)  # fmt: skip
def test_effects_of_flat_keywords_names_the_problem(given, said):
    """`sh.effects({'indenter': ..., 'mass': ...})` raised Python's "Problem.__init__() got an
    unexpected keyword argument 'indenter'" and `sh.effects({})` its missing positional
    arguments: one line naming `problem` and the way to build one."""
    with pytest.raises(InputError) as caught:
        sh.effects(given)
    text = str(caught.value)
    assert text.startswith("problem: ") and said in text, text
    assert "sh.Problem.impact(" in text and "\n" not in text, text
    assert caught.value.parameter == "problem"


def test_a_problem_names_its_part_classes_as_exported():
    """ "geometry must be a shtaerman.problem.Geometry": Geometry lives in fem.mesh and is
    exported as sh.Geometry, as every part is."""
    striker = sh.Problem.curve(PAD_STRIKER, RUBBER).striker
    with pytest.raises(InputError, match=r"^geometry must be a shtaerman\.Geometry, got int$"):
        sh.Problem(striker, sh.Body(RUBBER), geometry=3)
    with pytest.raises(InputError, match=r"^body must be a shtaerman\.Body, got Material$"):
        sh.Problem(striker, RUBBER)
    assert sh.Geometry.__name__ == "Geometry" and sh.Body.__name__ == "Body"


CONTACT_LAYER = 'name = "pad"\n' + PAPER_CASE + "[layer]\nthickness = {thickness}\n"


@pytest.mark.parametrize(
    "text",
    [
        CONTACT_LAYER.format(thickness=99.0),
        DYNAMIC_STUDY + "[layer]\nthickness = 99.0\n",
        DYNAMIC_STUDY + "[layer]\nthickness = 1e-9\n",
    ],
    ids=["contact", "dynamic-thick", "dynamic-thin"],
)
def test_a_layer_thickness_out_of_range_names_its_key_at_load(tmp_path, text):
    """`l9.toml: thickness: must lie in [0.000261, 26] m ...` (a contact study) named no key,
    and a dynamic study loaded and failed at its run (`study 'dynamic': thickness: ...`),
    where every other [layer] refusal names `key 'layer.thickness'`."""
    path = tmp_path / "l9.toml"
    path.write_text(text)
    with pytest.raises(StudyError) as caught:
        load_study(path)
    said = str(caught.value)
    assert said.startswith(f"{path}: key 'layer.thickness': must lie in ["), said
    assert "\n" not in said


def _striker_study(tmp_path, spelling: str):
    path = tmp_path / "e1.toml"
    path.write_text('name = "x"\n' + PAPER_CASE + f"[striker]\nE1 = {spelling}\nnu1 = 0.3\n")
    return path


def test_a_quoted_modulus_is_refused_saying_inf_is_the_one_string(tmp_path):
    """`E1 = "inf"` is the spelling the init-study template documents (``or write "inf"``)
    beside TOML's inf; `E1 = "2e11"` was refused as "must be a number ..., or inf (rigid)",
    which read as if "inf" were refused too. It now says a number goes unquoted and "inf"
    is the one string taken."""
    [study] = load_study(_striker_study(tmp_path, '"inf"'))
    assert math.isinf(study.striker.youngs_modulus)
    with pytest.raises(StudyError) as caught:
        load_study(_striker_study(tmp_path, '"2e11"'))
    said = str(caught.value)
    assert "key 'striker.E1': expected a number in [1e-3, 1e100] (Pa), unquoted" in said, said
    assert '"inf" (the one string it takes)' in said and said.endswith("got '2e11'"), said


def test_a_negative_infinite_modulus_is_not_refused_as_not_finite(tmp_path, capsys):
    """-inf read "E1 must be a finite number in [1e-3, 1e100] Pa, or inf (rigid)": the range's
    words, as for E1 = 0, everywhere E1 is checked."""
    said = "E1 must lie in [1e-3, 1e100] Pa, or inf (rigid), got -inf"
    with pytest.raises(StudyError) as caught:
        load_study(_striker_study(tmp_path, "-inf"))
    assert str(caught.value).endswith(f"key 'striker.E1': {said}"), caught.value
    command = ["impact", "--E1=-inf"]
    assert main(command) == 2
    err = capsys.readouterr().err
    assert err == f"shtaerman: error: --{said.replace('-inf', repr('-inf'))}\n", err
    sweep = tmp_path / "s.toml"
    sweep.write_text('name = "soft"\nkind = "impact"\n[axes]\nE1 = [-inf, 2e11]\n')
    assert main(["sweep", str(sweep), "--out", str(tmp_path / "out")]) == 2
    assert f"axes.{said.replace('E1', 'E1[0]')}" in capsys.readouterr().err
