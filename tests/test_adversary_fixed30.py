"""Defects of the adversary's pass fixed on branch adv30 (issue 28: every combination runs or is
refused in one line, the same guards and words on every route; issue 31: bad input gets one
line naming the option and its range, exit 2). Each test failed on the code before its fix."""

import pytest

import shtaerman.cli as cli
from shtaerman.api.effect_table.table import Run
from shtaerman.study.schema import StudyError, load_study

DYNAMIC_STUDY = (
    'kind = "dynamic"\ndescription = "x"\n'
    "[indenter]\nshape_coefficient = 5.0\nexponent = 1.5\n"
    "[impact]\nmass = 0.7\nvelocity = 3.0\n"
    "[half_space]\nE2 = 7.5e6\nnu2 = 0.5\ndensity2 = 1100.0\n"
)


def _refusal(tmp_path, text):
    """The one-line refusal of a study file holding ``text`` (nothing is run)."""
    study = tmp_path / "study.toml"
    study.write_text(text, encoding="utf-8")
    with pytest.raises(StudyError) as caught:
        load_study(study)
    return str(caught.value)


def test_a_dynamic_study_too_coarse_for_its_ladder_names_its_key_not_estimate_false(tmp_path):
    """Old code: "key 'numerics': time_steps: ...; or run without the estimate
    (estimate=False)", a keyword a study file does not have: its way is [quick]."""
    said = _refusal(tmp_path, DYNAMIC_STUDY + "[numerics]\ntime_steps = 60\n")
    assert "key 'numerics.time_steps'" in said, said
    assert "estimate=" not in said and "[quick]" in said and "\n" not in said, said


def test_a_rubber_dynamic_studys_option_refusal_speaks_the_files_keys(tmp_path):
    """Old code: the rubber's refusal listed Python names, "(it takes mass, velocity, ...)"."""
    text = DYNAMIC_STUDY + '[numerics]\nlayer_rate = 5.0\n[rubber]\nmodel = "neo-hookean"\n'
    said = _refusal(tmp_path, text)
    assert "key 'numerics.layer_rate'" in said, said
    assert "(it takes mass, velocity, density2, time_steps, mesh_size" in said, said  # keys
    assert "=..." not in said and "--" not in said, said


def _interrupted_table(tmp_path, monkeypatch):
    """An effects folder that a stopped table left with one finished run (no run is made:
    the table is a stand-in that finishes one run, then is interrupted); the calls it got."""
    import shtaerman.cli.effects as command

    calls = []

    def stopped(full, *, finished, **options):
        calls.append(options)
        finished(Run("none", "none", None, "-", refused="refused: a stand-in"))
        raise KeyboardInterrupt

    monkeypatch.setattr(command, "effects", stopped)
    out = tmp_path / "out"
    assert cli.main(["effects", "--out", str(out)]) == 130
    assert (out / "incomplete.json").is_file()
    return out, calls


def test_an_effects_resume_with_another_physics_option_is_refused(tmp_path, monkeypatch, capsys):
    """Old code: --resume with another --E2 reran every variant silently (their fingerprints
    differ), or with an option that leaves some variants alone reused those: a table of two
    problems. The kept runs are of the options they were made with: refused in one line."""
    out, calls = _interrupted_table(tmp_path, monkeypatch)
    capsys.readouterr()
    code = cli.main(["effects", "--out", str(out), "--resume", "--E2", "8e6"])
    err = capsys.readouterr().err.strip()
    assert code == 2, err
    assert len(calls) == 1, calls  # nothing run again
    assert "--E2 (7500000.0 there, 8000000.0 now)" in err and "--force" in err, err
    assert "E2=" not in err and "\n" not in err, err
    assert (out / "incomplete.json").is_file()  # the kept run stays for a resume


def test_an_effects_resume_with_the_same_options_reuses_the_kept_run(tmp_path, monkeypatch, capsys):
    """The check above refuses other options only: the same ones reach the table with the
    kept run (the second stand-in call, interrupted again)."""
    out, calls = _interrupted_table(tmp_path, monkeypatch)
    assert cli.main(["effects", "--out", str(out), "--resume"]) == 130, capsys.readouterr().err
    assert len(calls) == 2


def test_the_effects_tables_rows_speak_options_on_the_command_line(monkeypatch, capsys):
    """Old code: the table's notes and reasons on the command line were the API's words
    ("layer_rate not applied", "(estimate=False, --no-estimate)"). A stand-in table (no run)
    with a note, a refusal and a bar switched off, as sh.effects words them."""
    import shtaerman.cli.effects as command
    from shtaerman.api.effect_table.run import NO_ESTIMATE
    from shtaerman.api.effect_table.table import EffectTable

    note = "layer_rate not applied: a massless body (density2=0) has no waves"
    refused = "refused: friction: applies to a bonded indenter only; give interface='bonded' too"
    values = {"P_max": 1.0, "x_max": 1.0, "t_contact": 1.0, "restitution": 1.0}
    runs = (
        Run("none", "none", None, "-", values=values, error_note=NO_ESTIMATE[1], notes=(note,)),
        Run("full", "full", None, "-", refused=refused),
    )
    table = EffectTable({"P_c": 1.0, "x_c": 1.0, "t_c": 0.5, "t_y": 1.0}, runs, ())

    def stand_in(full, *, progress, **options):
        progress(f"effects: run 2/2: full: {refused}")
        return table

    monkeypatch.setattr(command, "effects", stand_in)
    assert cli.main(["effects", "--density2", "0"]) == 0
    said = capsys.readouterr()
    text = said.out + said.err
    assert "--layer-rate not applied" in text and "(--density2 0)" in text, text
    assert "refused: --friction: " in text and "give --interface bonded too" in text, text
    assert "(--no-estimate)" in text, text
    for python in ("layer_rate", "density2=", "estimate=", "interface=", " friction:"):
        assert python not in text, (python, text)
    assert "estimate=False" in NO_ESTIMATE[1] and "--" not in NO_ESTIMATE[1]  # sh.effects'


RUBBER_STUDY = DYNAMIC_STUDY + '[rubber]\nmodel = "neo-hookean"\n'
# the remedy of a rubber with inertia whose step fails (fem/stepper.py), in each route's words
CURE = {"python": "density=0 gives", "cli": "--density2 0 gives", "file": "density2 = 0 gives"}


@pytest.fixture
def failing_rubber_step(monkeypatch):
    """Every time step of a rubber with inertia fails (its Newton), on a coarse mesh: the run
    stops at its first step with fem/stepper.py's numerical failure (a second or so)."""
    import shtaerman.fem.finite_dynamic as finite_dynamic
    import shtaerman.fem.stepper as stepper
    from shtaerman.fem.hyperelastic import NewtonError
    from shtaerman.fem.mesh import MeshSettings

    def fail(*args):
        raise NewtonError("an element inverted (J <= 0)")

    coarse = MeshSettings(size=0.25, domain=1e3, growth=0.5, axis_size=1e-3, axis_growth=0.25)
    monkeypatch.setattr(finite_dynamic, "IMPACT_MESH", coarse)
    monkeypatch.setattr(stepper, "_dynamic_step", fail)


def _spoken_only(text, route):
    """Whether ``text`` names the remedy in ``route``'s words and in no other route's."""
    return CURE[route] in text and all(CURE[o] not in text for o in CURE if o != route)


def test_a_numerical_failure_names_its_remedy_in_the_apis_words(failing_rubber_step):
    """Old code: sh.dynamic's failure said "--density2 0 gives the massless ..."."""
    import shtaerman as sh
    from shtaerman.validation import NumericalFailureError

    striker = sh.PowerLawIndenter(shape_coefficient=5.0, exponent=1.5)
    rubber = sh.Material(youngs_modulus=7.5e6, poisson_ratio=0.5, density=1100.0)
    with pytest.raises(NumericalFailureError) as caught:
        sh.dynamic(striker, rubber, mass=0.7, velocity=3.0, model="neo-hookean", estimate=False)
    assert _spoken_only(str(caught.value), "python"), caught.value


def test_a_numerical_failure_names_its_remedy_in_option_words(failing_rubber_step, capsys):
    """The command line read so before (not a failing test): it still does now that the
    message is written in Python's words (cli.common.in_option_words spells it)."""
    code = cli.main(["dynamic", "--model", "neo-hookean", "--no-estimate"])
    err = capsys.readouterr().err
    assert code == 1 and err.count("\n") == 1, err
    assert _spoken_only(err, "cli"), err


def test_a_numerical_failure_names_its_remedy_in_the_study_files_keys(
    failing_rubber_step, tmp_path
):
    """Old code: a study's failure said "--density2 0" (as the command line, python's once
    the messages were Python's): verify's studies are written in their file's keys."""
    from shtaerman.output.folder import compute_study
    from shtaerman.validation import NumericalFailureError

    study = tmp_path / "rubber.toml"
    study.write_text(RUBBER_STUDY, encoding="utf-8")
    [loaded] = load_study(study)
    with pytest.raises(NumericalFailureError) as caught:
        compute_study(loaded, tmp_path, quick=True)
    said = str(caught.value)
    assert said.startswith(f"{study}: study ") and _spoken_only(said, "file"), said


def test_a_mesh_refusal_names_its_remedy_in_the_apis_words():
    """Old code: sh.contact's refusal said "coarsen it (--mesh-size, ...) raise --max-dofs";
    the command line's reads so still (tests/test_hostile_input.py)."""
    import shtaerman as sh

    with pytest.raises(sh.InputError) as caught:  # refused before any mesh
        sh.contact(sh.PowerLawIndenter(5.0, 1.5), sh.Material(7.5e6, 0.5), mesh_size=1e-6)
    said = str(caught.value)
    assert "(mesh_size=..., growth=..., a lower refine=...)" in said and "--" not in said, said
