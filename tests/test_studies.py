"""Studies as data: the shipped TOML files load, and bad files get errors naming file and key."""

import json
import re
import warnings

import pytest
from study_texts import PAPER_CASE

from shtaerman.study.schema import StudyError, find_study, load_study, shipped_studies

PAPER = "\n" + PAPER_CASE


def test_shipped_studies_cover_the_issue():
    names = [study.name for path in shipped_studies() for study in load_study(path)]
    assert names == [
        "compressible",
        "dynamic",
        "finite-strain-nu0.5",
        "finite-strain-nu0.3",
        "hertz",
        "layer",
        "paper",
        "table4-A2",
        "table4-A4",
        "table4-A6",
    ]
    slower = sorted(set(shipped_studies(extended=True)) - set(shipped_studies()))
    extended = [study.name for path in slower for study in load_study(path)]
    assert extended == [
        "corrections",
        "finite-strain-nested-nu0.5",
        "finite-strain-nested-nu0.3",
        "rubber-mooney-rivlin",
        "rubber-yeoh",
        "rubber-volumetric",
        "silicone-waves",
        "silicone-hysteresis",
        "silicone-both",
        "viscoelastic-waves",
        "viscoelastic-hysteresis",
        "viscoelastic-both",
    ]
    assert find_study("rubber_models") == slower[2]  # run by name like the others


def test_paper_study_is_the_paper_example():
    [paper] = [s for path in shipped_studies() if path.stem == "paper" for s in load_study(path)]
    assert (paper.indenter.shape_coefficient, paper.indenter.exponent) == (5.0, 1.5)
    assert (paper.half_space.youngs_modulus, paper.half_space.poisson_ratio) == (7.5e6, 0.5)
    assert (paper.striker.youngs_modulus, paper.striker.poisson_ratio) == (2e11, 0.25)
    assert (paper.mass, paper.velocity, paper.tolerances.impact) == (0.7, 3.0, 2e-3)


def test_minimal_user_study(tmp_path):
    path = tmp_path / "mine.toml"
    path.write_text(PAPER)
    [study] = load_study(path)
    # name from the file, rigid striker and default mesh/tolerances when not given
    assert study.name == "mine" and study.striker.compliance == 0.0 and study.depths is None


@pytest.mark.parametrize(
    ("edit", "message"),
    [
        (
            ("exponent = 1.5", "exponent = -1.5"),
            r"key 'indenter.exponent': exponent must lie in \(1, 20\], got -1.5$",
        ),
        (("mass = 0.7", "mass = 'heavy'"), r"key 'impact.mass': mass must be a number > 0 kg"),
        (("nu2 = 0.5", "nu2 = 0.6"), r"half_space.nu2': nu2 must lie in \[0, 0.5\], got 0.6$"),
        (("[impact]", "[impakt]"), r"key 'impakt': expected one of"),
        (("velocity = 3.0", "velocity = 3.0\ncolour = 1"), r"key 'impact.colour': expected one of"),
        (("[indenter]", "indenter = ["), r"not valid TOML"),
        # valid numbers the FEM refuses: the key from InputError.parameter, as in the
        # dynamic and finite-strain files (the contact file named no key before)
        (
            ("exponent = 1.5", "exponent = 1.0"),
            r"key 'indenter.exponent': exponent must lie in \(1, 20\]",
        ),
        (("E2 = 7.5e6", "E2 = 1e200"), r"'half_space.E2': E2"),
    ],
)
def test_bad_study_names_file_and_key(tmp_path, edit, message):
    path = tmp_path / "bad.toml"
    path.write_text(PAPER.replace(*edit))
    with pytest.raises(StudyError, match=message) as error:
        load_study(path)
    assert str(path) in str(error.value)


def test_bad_depths_and_sweep(tmp_path):
    path = tmp_path / "bad.toml"
    path.write_text(PAPER + "[contact]\ndepths = [2e-3, 1e-3]\n")
    with pytest.raises(StudyError, match=r"contact.depths': expected a list of 2 to 1000"):
        load_study(path)
    # one depth cannot give the FEM-fitted exponent the study's impact needs
    path.write_text(PAPER + "[contact]\ndepths = [1e-3]\n")
    with pytest.raises(StudyError, match=r"contact.depths': expected a list of 2 to 1000"):
        load_study(path)
    path.write_text(PAPER + "[sweep]\ncolour = [1, 2]\n")
    with pytest.raises(StudyError, match=r"sweep.colour': expected one of"):
        load_study(path)


def test_missing_file():
    with pytest.raises(StudyError, match="study file not found"):
        load_study("no/such/study.toml")


@pytest.mark.parametrize(
    ("extra", "message"),
    [
        (
            "[tolerances]\nforce = inf\n",
            r"key 'tolerances.force': expected a relative tolerance in",
        ),
        ("[tolerances]\nimpact = 0\n", r"key 'tolerances.impact': expected a relative tolerance"),
        ("[numerics]\nmesh_margin = 0.5\n", r"key 'numerics.mesh_margin': mesh_margin must lie in"),
        ("[numerics]\ncolour = 1\n", r"key 'numerics.colour': expected one of \['axis_growth'"),
        ("[sweep]\n", r"key 'sweep': expected exactly one of"),
        ("[convergence]\nsizes = [0.1]\n", r"key 'convergence.sizes': expected a list of at"),
    ],
)
def test_every_table_is_checked_at_load(tmp_path, extra, message):
    path = tmp_path / "bad.toml"
    path.write_text(PAPER + extra)
    with pytest.raises(StudyError, match=message):
        load_study(path)


@pytest.mark.parametrize(
    ("edit", "key"),
    [
        (("E2 = 7.5e6", "E2 = inf"), "half_space.E2"),
        (("mass = 0.7", "mass = inf"), "impact.mass"),
        (("velocity = 3.0", "velocity = +inf"), "impact.velocity"),
        (("shape_coefficient = 5.0", "shape_coefficient = inf"), "indenter.shape_coefficient"),
        (("velocity = 3.0", "velocity = 3.0\n[contact]\ndepths = [1e-3, inf]"), "contact.depths"),
        (
            ("velocity = 3.0", "velocity = 3.0\n[numerics]\ndomain_factor = inf"),
            "numerics.domain_factor",
        ),
    ],
)
def test_an_infinite_number_is_refused_at_load_with_its_key(tmp_path, edit, key):
    # TOML spells inf; only the striker may be rigid (E1 = inf or "inf")
    path = tmp_path / "bad.toml"
    path.write_text(PAPER.replace(*edit))
    said = rf"bad.toml: key '{re.escape(key)}': (expected|\w+ must be) a fin"  # a list: expected
    with pytest.raises(StudyError, match=said):
        load_study(path)


def test_a_rigid_striker_may_be_spelled_inf(tmp_path):
    path = tmp_path / "rigid.toml"
    for spelling in ("inf", '"inf"'):
        path.write_text(PAPER + f"[striker]\nE1 = {spelling}\nnu1 = 0.3\n")
        [study] = load_study(path)
        assert study.striker.compliance == 0.0


def test_missing_table_is_named(tmp_path):
    path = tmp_path / "bad.toml"
    path.write_text(PAPER.replace("[impact]\nmass = 0.7\nvelocity = 3.0\n", ""))
    with pytest.raises(StudyError, match=r"key 'impact': expected .*\(required\)"):
        load_study(path)


@pytest.mark.parametrize(
    ("edit", "message"),
    [
        (
            ("exponent = 1.5", "exponent = 1.0"),
            r"'indenter.exponent': exponent must lie in \(1, 20\]",
        ),
        (
            ("nu2 = 0.5", "nu2 = -0.2"),
            r"'half_space.nu2': nu2 must lie in \[0, 0.5\]",
        ),
    ],
)
def test_what_the_fem_cannot_run_is_refused_before_it_starts(tmp_path, edit, message):
    path = tmp_path / "bad.toml"
    path.write_text(PAPER.replace(*edit))
    with pytest.raises(StudyError, match=message):
        load_study(path)


@pytest.mark.parametrize(
    "name", ["../../x", "/tmp/abs", "", ".", "..", "a/b", "a\u0000b", "x" * 300, 'q"uote', "<b>"]
)
def test_study_names_are_plain(tmp_path, name):
    path = tmp_path / "named.toml"
    path.write_text(f"name = {json.dumps(name)}\n{PAPER}")  # a JSON string is a TOML string
    with pytest.raises(StudyError, match=r"key 'name': .*name must be a plain name"):
        load_study(path)


# --- the vocabulary's keys, the old ones for one release, and what an unknown key meant -------

OLD_PAPER = """
[indenter]
shape_coefficient = 5.0
exponent = 1.5
[striker]
youngs_modulus = 2e11
poisson_ratio = 0.25
[half_space]
youngs_modulus = 7.5e6
poisson_ratio = 0.5
[impact]
mass = 0.7
velocity = 3.0
[mesh]
size = 0.01
domain = 1e4
[quick_mesh]
size = 0.02
"""
NEW_PAPER = """
[indenter]
shape_coefficient = 5.0
exponent = 1.5
[striker]
E1 = 2e11
nu1 = 0.25
[half_space]
E2 = 7.5e6
nu2 = 0.5
[impact]
mass = 0.7
velocity = 3.0
[numerics]
mesh_size = 0.01
domain_factor = 1e4
[quick]
mesh_size = 0.02
"""


def _loaded(path, text):
    """The studies of ``text`` and the warnings its loading gave."""
    path.write_text(text)
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        studies = load_study(path)
    return studies, [str(w.message) for w in caught if issubclass(w.category, FutureWarning)]


def test_old_keys_work_for_a_release_with_one_line_each_naming_the_new_key(tmp_path):
    [new], quiet = _loaded(tmp_path / "mine.toml", NEW_PAPER)
    [old], messages = _loaded(tmp_path / "mine.toml", OLD_PAPER)
    assert quiet == [] and old == new
    assert (new.mesh.size, new.mesh.domain, new.quick_mesh.size) == (0.01, 1e4, 0.02)
    for old_key, new_key in [
        ("striker.youngs_modulus", "striker.E1"),
        ("half_space.poisson_ratio", "half_space.nu2"),
        ("mesh", "numerics"),
        ("quick_mesh", "quick"),
        ("numerics.size", "numerics.mesh_size"),
        ("numerics.domain", "numerics.domain_factor"),
    ]:
        assert any(
            f"key '{old_key}' is deprecated; write '{new_key}'" in m and "\n" not in m
            for m in messages
        ), old_key


def test_a_vocabulary_key_at_the_top_goes_to_its_table(tmp_path):
    text = PAPER.replace("E2 = 7.5e6\n", "").replace("[indenter]", "E2 = 4e6\n[indenter]")
    [study], _ = _loaded(tmp_path / "mine.toml", text)
    assert study.half_space.youngs_modulus == 4e6
    twice = PAPER.replace("[indenter]", "E2 = 4e6\n[indenter]")
    with pytest.raises(StudyError, match=r"key 'E2' given twice \(at the top and in \[half_space"):
        _loaded(tmp_path / "mine.toml", twice)


def test_old_and_new_key_together_are_refused(tmp_path):
    with pytest.raises(StudyError, match=r"'half_space.youngs_modulus' and 'half_space.E2' name"):
        _loaded(
            tmp_path / "mine.toml", PAPER.replace("E2 = 7.5e6", "E2 = 7.5e6\nyoungs_modulus = 1")
        )


@pytest.mark.parametrize(
    ("edit", "message"),
    [
        (("mass = 0.7", "mas = 0.7"), r"key 'impact.mas': .*unknown key: did you mean 'mass'\?\)"),
        (("E2 = 7.5e6", "E3 = 7.5e6"), r"key 'half_space.E3': .*key: did you mean 'E2'\?\)"),
        (("mass = 0.7", "mass = 0.7\nexponent = 2"), r"key 'impact.exponent': .*in \[indenter\]"),
        (("[half_space]", "[halfspace]"), r"key 'halfspace': .*key: did you mean 'half_space'\?\)"),
        # adv53: a [friction] table was asked 'did you mean description?' (a look-alike name);
        # the friction of a contact study is a key of [contact] (of a dynamic one: [impact])
        (
            ("velocity = 3.0", "velocity = 3.0\n[friction]\ncoefficient = 0.5"),
            r"key 'friction': .*\(unknown key: it belongs in \[contact\]\)$",
        ),
        (("velocity = 3.0", "velocity = 3.0\n[numerics]\nmesh_sise = 0.1"), r"'mesh_size'\?"),
        (
            ("velocity = 3.0", "velocity = 3.0\n[corrections]\nvelocities = [1.0]"),
            r"key 'corrections': .*unknown key: \[corrections\] belongs in a study of kind = "
            "'finite-strain'",
        ),
    ],
)
def test_an_unknown_key_says_what_it_probably_meant(tmp_path, edit, message):
    with pytest.raises(StudyError, match=message):
        _loaded(tmp_path / "bad.toml", PAPER.replace(*edit))


@pytest.mark.parametrize("kind", ["dynamic", "effects"])
def test_an_impact_studys_friction_belongs_in_its_impact_table(tmp_path, kind):
    from shtaerman.cli.init_study import write_template

    path = write_template(tmp_path / "bad.toml", kind=kind)
    text = path.read_text() + "[friction]\ncoefficient = 0.5\n"
    with pytest.raises(
        StudyError, match=r"key 'friction': .*\(unknown key: it belongs in \[impact\]\)$"
    ):
        _loaded(path, text)


DYNAMIC = """\
kind = "dynamic"
[indenter]
shape_coefficient = 5.0
exponent = 1.5
[half_space]
E2 = 7.5e6
nu2 = 0.5
density2 = 1100.0
[impact]
mass = 0.7
"""


@pytest.mark.parametrize(
    ("velocity", "velocities", "example", "quick"),
    [
        ("velocity = 2.0", (2.0,), 2.0, (2.0,)),
        ("velocity = [1.0, 2.0, 3.0]", (1.0, 2.0, 3.0), 2.0, (1.0, 2.0)),
        ("velocity = [1.0, 3.0]", (1.0, 3.0), 3.0, (1.0, 3.0)),
        ("velocity = [1.0, 3.0]\nfigure_velocity = 1.0", (1.0, 3.0), 1.0, (1.0, 3.0)),
    ],
)
def test_a_dynamic_study_takes_velocity_as_a_contact_study_does(
    tmp_path, velocity, velocities, example, quick
):
    [study], messages = _loaded(tmp_path / "dyn.toml", DYNAMIC + velocity + "\n")
    assert (study.velocities, study.example, study.quick_velocities) == (velocities, example, quick)
    assert messages == []


def test_old_dynamic_keys_still_load(tmp_path):
    old = DYNAMIC.replace("density2", "density") + "velocities = [1.0, 3.0]\nexample = 3.0\n"
    old += "[numerics]\nsteps = 100\nsize = 0.05\n[quick]\nvelocities = [3.0]\nsteps = 60\n"
    [study], messages = _loaded(tmp_path / "dyn.toml", old)
    assert (study.velocities, study.example, study.quick_velocities) == ((1.0, 3.0), 3.0, (3.0,))
    assert (study.settings.steps, study.settings.size, study.quick_settings.steps) == (
        100,
        0.05,
        60,
    )
    assert "key 'impact.example' is deprecated; write 'impact.figure_velocity'" in "".join(messages)
    assert "key 'numerics.steps' is deprecated; write 'numerics.time_steps'" in "".join(messages)
    assert len(messages) == 7


def test_finite_strain_depth_steps_and_its_old_names(tmp_path):
    base = DYNAMIC.replace('"dynamic"', '"finite-strain"').replace("density2 = 1100.0\n", "")
    base += "velocity = 3.0\n"
    [new], quiet = _loaded(
        tmp_path / "f.toml",
        base + "[contact]\ndepth_steps = 8\n[quick]\ndepth_steps = 4\nmesh_size = 0.05\n",
    )
    old_text = base + "[contact]\nsteps = 8\n[quick]\nsteps = 4\n[quick.mesh]\nsize = 0.05\n"
    [old], messages = _loaded(tmp_path / "f.toml", old_text)
    assert quiet == [] and old == new
    assert (new.ladder.steps, new.quick_ladder.steps, new.quick_mesh.size) == (8, 4, 0.05)
    assert any("'quick.steps' is deprecated; write 'quick.depth_steps'" in m for m in messages)
    assert any("'quick.mesh' is deprecated; write 'quick'" in m for m in messages)


EFFECTS = 'kind = "effects"\n' + PAPER_CASE.replace("nu2 = 0.5", "nu2 = 0.5\ndensity2 = {density}")


@pytest.mark.parametrize(
    ("text", "says"),
    [
        # a contact study took friction = 500 that the Problem (and every other route) refuses
        (
            PAPER + '[contact]\ninterface = "bonded"\nfriction = 500.0\n',
            "key 'contact.friction': friction must lie in [0, 1e2], got 500.0",
        ),
        # an effects study named its density 'half_space.density', a key no file has; its
        # range is the command line's (--density2), checked at decode
        (
            EFFECTS.format(density=1e300),
            "key 'half_space.density2': density2 must lie in [1e-6, 1e6] or 0 kg/m^3",
        ),
    ],
)
def test_a_study_refuses_what_the_problem_refuses_naming_its_key(tmp_path, text, says):
    path = tmp_path / "bad.toml"
    path.write_text(text)
    with pytest.raises(StudyError) as error:
        load_study(path)
    assert says in str(error.value)
