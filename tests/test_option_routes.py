"""Each option limit is declared once (shtaerman.problem.OPTION_SUPPORT, the Body) and every
route refuses it in the same words: the table itself, the API, the command line, a study file.
Each route is checked before any work (no mesh is built: these run in milliseconds)."""

from pathlib import Path

import pytest
from study_texts import DYNAMIC_STUDY as DYNAMIC
from study_texts import FINITE_STUDY as FINITE

import shtaerman as sh
from shtaerman.cli import main
from shtaerman.problem import check_options, worded
from shtaerman.study.schema import StudyError, load_study
from shtaerman.sweep.spec import SweepError, parse_sweep

PAPER = sh.PowerLawIndenter(shape_coefficient=5.0, exponent=1.5)
RUBBER = sh.Material(7.5e6, 0.5)
RUBBER_CURVE = sh.Problem.curve(PAPER, RUBBER, model="neo-hookean")
LINEAR_CURVE = sh.Problem.curve(PAPER, RUBBER)
RUBBER_IMPACT = sh.Problem.impact(
    PAPER, sh.Material(7.5e6, 0.5, 1100.0), mass=0.7, velocity=3.0, model="neo-hookean"
)


def _table(problem: sh.Problem, given: dict) -> str:
    with pytest.raises(sh.InputError) as refused:
        check_options(problem, given)
    return str(refused.value)


def _api(**keywords) -> str:
    with pytest.raises(sh.InputError) as refused:
        sh.contact(PAPER, RUBBER, **keywords)
    return str(refused.value)


def _cli(capsys, argv: list[str]) -> str:
    assert main(argv) == 2
    out, err = capsys.readouterr()
    assert out == "" and err.count("\n") == 1, err  # one line, no traceback
    return err.removeprefix("shtaerman: error: ").strip()


def _study(tmp_path: Path, text: str) -> str:
    path = tmp_path / "case.toml"
    path.write_text(text)
    with pytest.raises(StudyError) as refused:
        load_study(path)
    return str(refused.value).removeprefix(f"{path}: ")


@pytest.mark.parametrize(
    ("problem", "given", "keywords", "argv", "words"),
    [
        (
            RUBBER_CURVE,
            {"solver": "pardiso"},
            {"model": "neo-hookean", "solver": "pardiso"},
            ["--model", "neo-hookean", "--solver", "pardiso"],
            "solver: the neo-hookean model uses superlu only, got 'pardiso'",
        ),
        (
            LINEAR_CURVE,
            {"accuracy": 1e-3, "estimate": False},
            {"accuracy": 1e-3, "estimate": False},
            ["--accuracy", "1e-3", "--no-estimate"],
            "accuracy: needs the error estimates, which estimate=False switches off",
        ),
        (
            LINEAR_CURVE,
            {"accuracy": 1e-3, "refine": 2.0},
            {"accuracy": 1e-3, "refine": 2.0},
            ["--accuracy", "1e-3", "--refine", "2"],
            "refine: accuracy=... chooses the refinement itself (its ladder starts at "
            "refine=1), got refine=2; give one of them",
        ),
        (  # the API took max_time without accuracy silently; the command line alone refused
            LINEAR_CURVE,
            {"max_time": 30.0},
            {"max_time": 30.0},
            ["--max-time", "30"],
            "max_time: applies with accuracy=... only: it is the time budget of its "
            "refinement; give accuracy=... too",
        ),
    ],
    ids=[
        "pardiso-with-a-rubber",
        "accuracy-without-estimate",
        "accuracy-with-refine",
        "max-time-without-accuracy",
    ],
)
def test_a_contact_option_limit_is_the_tables_on_every_route(
    capsys, problem, given, keywords, argv, words
):
    name, reason = words.split(": ", 1)
    assert _table(problem, given) == words  # declared in OPTION_SUPPORT, not in the API
    assert _api(**keywords) == words
    cli = reason.replace("estimate=False", "--no-estimate").replace("accuracy=...", "--accuracy")
    cli = cli.replace("refine=", "--refine ")  # the option's value, as typed
    assert _cli(capsys, ["contact", *argv]) == f"--{name.replace('_', '-')}: {cli}"


def test_option_limits_take_the_values_and_combinations_they_allow():
    check_options(LINEAR_CURVE, {"solver": "pardiso", "accuracy": 1e-3, "refine": 1.0})
    check_options(LINEAR_CURVE, {"accuracy": 1e-3, "max_time": 30.0})
    check_options(RUBBER_CURVE, {"solver": "superlu", "refine": 2.0, "estimate": False})
    check_options(RUBBER_IMPACT, {"refine": 2.0, "estimate": False})  # the impact's own refine


@pytest.mark.parametrize(
    ("key", "value"), [("growth", 0.3), ("mesh_margin", 2), ("domain_factor", 1e3)]
)
def test_a_rubber_impacts_numerics_are_refused_alike_by_study_file_cli_and_sweep(
    capsys, tmp_path, key, value
):
    rubber = f'{DYNAMIC}[rubber]\nmodel = "neo-hookean"\n[numerics]\n{key} = {value}\n'
    study = _study(tmp_path, rubber)
    option = f"--{key.replace('_', '-')}"
    cli = _cli(capsys, ["dynamic", "--model", "neo-hookean", option, str(value)])
    sweep = (
        f'name = "rub"\nkind = "dynamic"\n[parameters]\nmodel = "neo-hookean"\n{key} = {value}\n'
    )
    with pytest.raises(SweepError) as refused:  # a sweep case, refused at load
        parse_sweep(sweep + "[axes]\nvelocity = [1.0, 2.0]\n")
    reason = _table(RUBBER_IMPACT, [key]).removeprefix(f"{key}: ")
    # one reason, its inputs spelled per route (problem.worded): keys, options
    assert study == f"key 'numerics.{key}': {worded(reason, 'file')}"
    assert cli == f"{option}: {worded(reason, 'cli')}"
    assert str(refused.value).endswith(f"(velocity = 1.0): {key}: {worded(reason, 'file')}")


@pytest.mark.parametrize("key", ["axis_size", "spectral_radius", "tail", "layer_width"])
def test_a_rubber_impact_refuses_the_study_only_numerics_by_the_table(tmp_path, key):
    """Keys a study file has and the command line has not: the table declares them too."""
    reason = _table(RUBBER_IMPACT, [key]).removeprefix(f"{key}: ")
    study = _study(tmp_path, f'{DYNAMIC}[rubber]\nmodel = "neo-hookean"\n[numerics]\n{key} = 0.3\n')
    assert study == f"key 'numerics.{key}': {worded(reason, 'file')}"


@pytest.mark.parametrize(
    ("key", "keywords"),
    [
        ("mooney_ratio", {"model": "mooney-rivlin", "mooney_ratio": 1.5}),
        ("mooney_ratio", {"model": "neo-hookean", "mooney_ratio": 0.3}),
        ("model", {"model": "foo"}),
        ("gent_limit", {"model": "gent"}),
        ("volumetric", {"model": "yeoh", "volumetric": "cubic"}),
    ],
    ids=["ratio-range", "shape-of-another-model", "unknown-model", "gent-limit", "volumetric"],
)
def test_the_finite_strain_study_checks_its_rubber_as_the_body_does(tmp_path, key, keywords):
    """The finite-strain study, the dynamic study and the API refuse a rubber in one wording:
    the Body's."""
    api = _api(**keywords)
    rubber = "\n".join(f"{name} = {value!r}".replace("'", '"') for name, value in keywords.items())
    finite = _study(tmp_path, f"{FINITE}[rubber]\n{rubber}\n")
    dynamic = _study(tmp_path, f"{DYNAMIC}[rubber]\n{rubber}\n")
    assert finite == dynamic
    assert finite == f"key 'rubber.{key}': {api.removeprefix(f'{key}: ')}"


def test_the_finite_strain_study_refuses_the_linear_model_by_its_key(tmp_path):
    refused = _study(tmp_path, f'{FINITE}[rubber]\nmodel = "linear"\n')
    assert refused.startswith("key 'rubber.model': ") and "neo-hookean" in refused, refused


def test_a_rubber_impacts_axis_size_is_refused_by_the_sweep_in_the_tables_words(tmp_path):
    """The sweep once said "(it takes time_steps and mesh_size)" in words of its own."""
    reason = _table(RUBBER_IMPACT, ["axis_size"]).removeprefix("axis_size: ")
    study = _study(
        tmp_path, f'{DYNAMIC}[rubber]\nmodel = "neo-hookean"\n[numerics]\naxis_size = 0.3\n'
    )
    sweep = (
        'name = "rub"\nkind = "dynamic"\n[parameters]\nmodel = "neo-hookean"\naxis_size = 0.003\n'
    )
    with pytest.raises(SweepError) as refused:
        parse_sweep(sweep + "[axes]\nvelocity = [1.0, 2.0]\n")
    reason = worded(reason, "file")  # the keys of both files
    assert study == f"key 'numerics.axis_size': {reason}"
    assert str(refused.value).endswith(f"(velocity = 1.0): axis_size: {reason}")


@pytest.mark.parametrize(
    ("rubber", "key"),
    [('model = "linear"', "model"), ('model = "gent"', "gent_limit")],
    ids=["linear", "gent-without-its-limit"],
)
def test_a_finite_strain_sweep_refuses_its_rubber_as_the_study_file_does(tmp_path, rubber, key):
    """The sweep built its rubber with words of its own: the linear model was 'unknown'."""
    study = _study(tmp_path, f"{FINITE}[rubber]\n{rubber}\n")
    sweep = (
        f'name = "f"\nkind = "finite-strain"\n[parameters]\n{rubber}\n[axes]\nvelocity = [1.0]\n'
    )
    with pytest.raises(SweepError) as refused:
        parse_sweep(sweep)
    reason = study.removeprefix(f"key 'rubber.{key}': ")
    assert str(refused.value).endswith(f"(velocity = 1.0): {key}: {reason}")


def test_accuracy_without_max_time_keeps_its_60_s_budget(monkeypatch):
    """max_time's default is None (it applies with accuracy only), read as 60 s as before."""
    budgets = []

    def reached(*args, max_time, **keywords):
        budgets.append(max_time)
        raise RuntimeError("reached the ladder")

    monkeypatch.setattr("shtaerman.study.contact.accuracy.run_to_accuracy", reached)
    for keywords, budget in (({}, 60.0), ({"max_time": 5.0}, 5.0)):
        with pytest.raises(RuntimeError, match="reached the ladder"):
            sh.contact(PAPER, RUBBER, accuracy=1e-3, **keywords)
        assert budgets.pop() == budget


def _sweep(kind: str, parameters: str) -> str:
    text = f'name = "s"\nkind = "{kind}"\n[parameters]\n{parameters}\n[axes]\nvelocity = [1.0]\n'
    with pytest.raises(SweepError) as refused:
        parse_sweep(text)
    return str(refused.value).split("(velocity = 1.0): ", 1)[1]


def test_a_refusal_names_the_other_inputs_in_the_words_of_its_route(capsys, tmp_path):
    """One refusal, four routes: each names the input to add as its user spells it (the study
    file and Python once read "give interface 'bonded' too", the command line "--friction: ...
    give interface 'bonded' too")."""
    reason = "applies to a bonded indenter only; give {} too"
    assert _api(friction=0.5) == "friction: " + reason.format("interface='bonded'")
    cli = _cli(capsys, ["dynamic", "--friction", "0.5"])
    assert cli == "--friction: " + reason.format("--interface bonded")
    study = _study(tmp_path, DYNAMIC.replace("[impact]\n", "[impact]\nfriction = 0.5\n"))
    assert study == "key 'impact.friction': " + reason.format('[impact] interface = "bonded"')
    sweep = _sweep("dynamic", "friction = 0.5")
    assert sweep == "friction: " + reason.format('interface = "bonded"')


def test_a_refusals_remedy_names_a_switch_in_the_words_of_its_route(capsys):
    """estimate=False is --no-estimate on the command line (the API's message named both)."""
    assert _api(accuracy=1e-3, estimate=False).endswith("which estimate=False switches off")
    cli = _cli(capsys, ["contact", "--accuracy", "1e-3", "--no-estimate"])
    assert cli == "--accuracy: needs the error estimates, which --no-estimate switches off"


def test_the_pad_reach_of_a_bonded_rubber_impact_names_the_interface_by_route(capsys):
    """Refused before any work: the remedy once read "--interface frictionless" in Python."""
    case = dict(mass=0.12, velocity=1.5, model="neo-hookean", thickness=0.012)
    striker, pad = sh.PowerLawIndenter(8.0, 1.3), sh.Material(3e6, 0.49, 1000.0)
    with pytest.raises(sh.InputError) as refused:
        sh.dynamic(striker, pad, interface="bonded", **case)
    assert str(refused.value).endswith("interface='frictionless' runs beyond it with a warning")
    argv = "--shape-coefficient 8 --exponent 1.3 --E2 3e6 --nu2 0.49 --density2 1000 --mass 0.12"
    argv += " --velocity 1.5 --model neo-hookean --thickness 0.012 --interface bonded"
    cli = _cli(capsys, ["dynamic", *argv.split()])
    assert cli.endswith("; --interface frictionless runs beyond it with a warning"), cli
