"""The problem object (src/shtaerman/problem.py): one description of the case, checked once,
whose combinations are declared in one table that every entry point applies."""

import itertools

import numpy as np
import pytest

import shtaerman as sh
from shtaerman.api.fem_dynamic import check_dynamic
from shtaerman.cli import main
from shtaerman.problem import SUPPORT, Cell, check_options, support_table

PAPER = sh.PowerLawIndenter(shape_coefficient=5.0, exponent=1.5)
RUBBER = sh.Material(7.5e6, 0.5, 1100.0)
MASSLESS = sh.Material(7.5e6, 0.5, 0.0)

PARTS = {  # one keyword set per value of each axis of the matrix
    "model": {"linear": {}, "rubber": {"model": "neo-hookean"}},
    "relaxing": {False: {}, True: {"prony": "0.3:1e-3"}},
    "geometry": {
        "half-space": {},
        "layer bonded": {"thickness": 0.012, "base": "bonded"},
        "layer lubricated": {"thickness": 0.012, "base": "lubricated"},
    },
    "interface": {
        "frictionless": {},
        "bonded": {"interface": "bonded"},
        "coulomb": {"interface": "bonded", "friction": 0.5},
    },
}


def _problem(cell: Cell) -> sh.Problem:
    keywords = {}
    for axis in PARTS:
        keywords.update(PARTS[axis][getattr(cell, axis)])
    if cell.loading == "curve":
        rate = {"rate": 0.1} if cell.relaxing else {}  # a viscoelastic curve's pressing speed
        return sh.Problem.curve(PAPER, RUBBER, **keywords, **rate)
    body = MASSLESS if cell.loading == "massless" else RUBBER
    return sh.Problem.impact(PAPER, body, mass=0.7, velocity=3.0, **keywords)


@pytest.mark.parametrize(("cell", "verdict"), support_table(), ids=lambda v: str(v))
def test_every_cell_is_built_or_refused_as_the_table_declares(cell, verdict):
    """Building the problem of each of the 108 cells applies exactly the declared refusal."""
    if verdict == "runs":
        assert _problem(cell).cell == cell
    else:
        with pytest.raises(sh.InputError) as refused:
            _problem(cell)
        assert str(refused.value) == verdict
        assert refused.value.parameter == verdict.split(":")[0]


def test_the_table_refuses_what_no_route_computes_and_nothing_else():
    """The refusals are the combinations the code does not compute today."""
    refused = {cell for cell, verdict in support_table() if verdict != "runs"}
    lubricated_rubber = {c for c in refused if c.model == "rubber" and "lubricated" in c.geometry}
    assert len(lubricated_rubber) == 2 * 3 * 3  # relaxing x interface x loading
    assert all(any(limit.when(cell) for limit in SUPPORT) for cell in refused)
    axes = (("linear", "rubber"), (False, True), ("half-space",), ("frictionless",))
    for model, relaxing, geometry, interface in itertools.product(*axes):
        for loading in ("massless", "inertia"):  # the impact of every body on the half-space
            assert Cell(model, relaxing, geometry, interface, loading) not in refused


def test_a_part_checks_its_own_values_and_names_them():
    with pytest.raises(sh.InputError, match=r"^thickness must be"):
        sh.Geometry(thickness=-1.0)
    with pytest.raises(sh.InputError, match=r"^friction: applies to a bonded indenter only"):
        sh.Interface("frictionless", friction=0.3)
    with pytest.raises(sh.InputError, match=r"^mooney_ratio: applies to the finite-strain"):
        sh.Body(RUBBER, mooney_ratio=0.0)  # 0 is a value, not "not given"
    with pytest.raises(sh.InputError, match=r"^mass: an impact needs the striker's mass"):
        sh.Problem(sh.Striker(PAPER, velocity=3.0), sh.Body(RUBBER))
    with pytest.raises(sh.InputError, match=r"^body must be a Material"):
        sh.Problem.impact(PAPER, "rubber", mass=0.7, velocity=3.0)


def test_options_a_combination_does_not_take_are_refused_by_name():
    rubber = sh.Problem.impact(PAPER, RUBBER, mass=0.7, velocity=3.0, model="neo-hookean")
    for name in ("growth", "layer_rate"):
        with pytest.raises(sh.InputError, match=rf"^{name}: not supported with model"):
            check_options(rubber, [name])
    # the finite impact runs its error-estimate ladder (tests/test_finite_impact_ladder.py)
    taken = ["time_steps", "mesh_size", "refine", "estimate", "out", "history", "figure_format"]
    check_options(rubber, taken)


def _one_line_error(capsys, argv, words):
    assert main(argv) == 2
    out, err = capsys.readouterr()
    assert out == "" and err.count("\n") == 1 and words in err, err
    return err


@pytest.mark.parametrize(
    ("argv", "words"),
    [
        # issue 31, item 7: a truthiness test ran the linear model with --mooney-ratio 0
        (["dynamic", "--mooney-ratio", "0"], "--mooney-ratio: applies to the finite-strain"),
        # item 8: the mismatched rubber option is named, not only the velocity
        (
            ["dynamic", "--model", "neo-hookean", "--mooney-ratio", "0", "--velocity", "11"],
            "--mooney-ratio: applies to the mooney-rivlin model only",
        ),
        # item 10: the mass sets the depth as much as the velocity does
        (
            ["dynamic", "--model", "neo-hookean", "--mass", "1e-300"],
            "--mass, --velocity: 1e-300 kg",
        ),
        # item 15: a pad always has its lateral absorber; 0 ran as 10 without a word
        (["dynamic", "--thickness", "0.02", "--layer-rate", "0"], "--layer-rate: a layer always"),
        # item 16: silently accepted before (now the finite impact writes figures with --out)
        (["dynamic", "--model", "neo-hookean", "--figure-format", "svg"], "--figure-format: appl"),
    ],
)
def test_the_cli_refuses_in_one_line_naming_the_options(capsys, argv, words):
    _one_line_error(capsys, argv, words)


def test_default_depths_beyond_the_finite_reach_name_the_impact_not_the_depths(capsys):
    """Issue 31, item 9: no --depths was given, so the message must not ask to lower them
    (giving them is a remedy: the impact's refusal, words51, ends 'or, instead of --mass and
    --velocity, give --depths')."""
    argv = ["contact", "--model", "neo-hookean", "--velocity", "11"]
    err = _one_line_error(capsys, argv, "--mass, --velocity: 0.7 kg at 11 m/s drive the")
    assert "lower the deepest" not in err
    assert err.rstrip().endswith("or, instead of --mass and --velocity, give --depths")


def test_a_problem_runs_as_its_keywords_do():
    """sh.dynamic(problem) is sh.dynamic(indenter, body, ...) for the same parts (coarse,
    massless: the quasi-static FE impact in a few seconds)."""
    numerics = dict(mesh_size=0.2, time_steps=50, estimate=False)
    keywords = dict(mass=0.7, velocity=1.0, prony="0.3:1e-3")
    by_keywords = sh.dynamic(PAPER, MASSLESS, **keywords, **numerics)
    problem = sh.Problem.impact(PAPER, MASSLESS, **keywords)
    by_problem = sh.dynamic(problem, **numerics)
    assert by_problem.dynamic == by_keywords.dynamic  # the same run: bitwise
    with pytest.raises(TypeError, match="takes numerics only"):
        sh.dynamic(problem, mass=0.7)
    with pytest.raises(sh.InputError, match="presses a contact curve"):
        sh.contact(problem)
    curve = sh.Problem.curve(PAPER, MASSLESS)
    for depths in ([1e-3, 2e-3], np.array([1e-3, 2e-3])):  # an array raised a bare ValueError
        with pytest.raises(TypeError, match=r"takes numerics only; the problem holds \['depths'\]"):
            sh.contact(curve, depths=depths)


@pytest.mark.parametrize(
    ("call", "words"),
    [
        (lambda: sh.Problem.curve(PAPER, RUBBER, depths=1e-3), "^depths must be a sequence"),
        (lambda: sh.contact(PAPER, RUBBER, depths="3", estimate=False), "^depths must be a seq"),
        (lambda: sh.contact(PAPER, RUBBER, depths=[1e-3, "x"]), "^depths must be a number"),
        (lambda: sh.dynamic(sh.Problem.curve(PAPER, RUBBER)), "^problem: dynamic.. runs an"),
        (lambda: sh.dynamic(PAPER, RUBBER, mass=0.7, velocity=3.0, settings="x"), "^settings"),
        (lambda: sh.dynamic(PAPER, RUBBER, mass=0.7, velocity=3.0, force="False"), "^force mu"),
        (lambda: sh.contact(PAPER, RUBBER, estimate="no"), "^estimate must be True or False"),
        (lambda: sh.contact(PAPER, RUBBER, figure_format="svg"), "^figure_format: applies"),
    ],
)
def test_the_api_refuses_wrong_types_in_one_line(call, words):
    """An adversary's calls that ended in TypeError/AssertionError tracebacks, ran a 3 m
    depth from the string "3", or read force="False" as true."""
    with pytest.raises(sh.InputError, match=words):
        call()


def test_a_contact_curve_problem_reports_its_own_impact():
    """sh.contact(problem) reported the impact of its keywords, not of the problem: a curve
    whose default depths reach the x_c of 0.25 kg at 2 m/s said mass 0.7 and velocity 3 (the
    vocabulary's defaults), and a curve to given depths gained a mass and a velocity it does
    not have. The result's impact is the problem's (coarse mesh, one FEM run each)."""
    numerics = dict(estimate=False, mesh_size=0.05, domain_factor=1e3)
    own = sh.contact(sh.Problem.curve(PAPER, RUBBER, mass=0.25, velocity=2.0), **numerics)
    assert (own.mass, own.velocity) == (0.25, 2.0)
    assert own.to_dict()["mass"] == 0.25
    given = sh.contact(sh.Problem.curve(PAPER, RUBBER, depths=[1e-4, 2e-4]), **numerics)
    assert given.mass is None and "mass" not in given.to_dict()


def test_worded_spells_the_inputs_a_refusal_names_for_each_route():
    """One message, three spellings; a value the user typed (quoted) is left as typed."""
    from shtaerman.problem import worded

    said = "friction: give interface='bonded' or thickness=... (estimate=False); got 'force=N'"
    assert worded(said, "python") == said
    assert worded(said, "cli", parameter="friction") == (  # the keyword it declares
        "--friction: give --interface bonded or --thickness (--no-estimate); got 'force=N'"
    )
    keys = {"interface": "impact.interface", "thickness": "layer.thickness"}
    assert worded(said, "file", keys) == (
        'friction: give [impact] interface = "bonded" or [layer] thickness (estimate = false); '
        "got 'force=N'"
    )


def test_only_the_declared_keyword_at_the_head_becomes_an_option():
    """The head of a message is spelled as options only when it names the refusal's declared
    parameter, a keyword of the vocabulary; a numerical failure declares none, so its step
    label stays as written even where it is also a keyword (``fit``), and its advice is still
    spelled. Old code: a special case in cli.common split the failure at its first colon."""
    from shtaerman.problem import worded

    advice = "fit: the curve failed; give mesh_size=... or estimate=False"
    assert worded(advice, "cli") == "fit: the curve failed; give --mesh-size or --no-estimate"
    said = worded("unknowns: unknown name 'E3'", "cli", parameter="unknowns")
    assert said == "--fit: unknown name 'E3'"  # the keyword of sh.fit, the option --fit
    assert worded("level 2: Newton failed", "cli") == "level 2: Newton failed"
    assert worded("mass, velocity: too fast", "cli", parameter="mass") == (
        "--mass, --velocity: too fast"
    )
    # a head the refusal does not declare, or no keyword of the vocabulary, is left alone
    assert worded("mass: too fast", "cli", parameter="velocity") == "mass: too fast"
    assert worded("level: too deep", "cli", parameter="level") == "level: too deep"


def test_in_option_words_tells_a_refusal_from_a_failure():
    """Through cli.common.in_option_words: an InputError's declared keyword becomes its option,
    a NumericalFailureError keeps its step label and gets its advice in options."""
    from shtaerman.cli.common import in_option_words
    from shtaerman.validation import InputError, NumericalFailureError

    with pytest.raises(InputError) as refused, in_option_words():
        raise InputError("unknowns: unknown name 'E3'; pick E2 or nu2", "unknowns")
    assert str(refused.value) == "--fit: unknown name 'E3'; pick E2 or nu2"
    assert refused.value.parameter == "unknowns"
    with pytest.raises(NumericalFailureError) as failed, in_option_words():
        raise NumericalFailureError("fit: the FE curve failed; give E2 and a smaller refine=...")
    assert str(failed.value) == "fit: the FE curve failed; give E2 and a smaller --refine"


def test_a_rubber_impact_refuses_the_linear_bodys_settings():
    """user56: sh.dynamic(model="neo-hookean", settings=sh.DynamicSettings(steps=90000)) ran
    on the finite-strain impact's own 100 steps and mesh, the settings dropped without a word
    (a MeshSettings too); the linear body takes them, and names the public type."""
    rubber = sh.Problem.impact(PAPER, RUBBER, mass=0.7, velocity=3.0, model="neo-hookean")
    with pytest.raises(sh.InputError, match=r"^settings: not supported with model") as no:
        check_dynamic(rubber, settings=sh.DynamicSettings(steps=90000), impact=False)
    assert no.value.parameter == "settings" and "time_steps=..., mesh_size=..." in str(no.value)
    linear = sh.Problem.impact(PAPER, RUBBER, mass=0.7, velocity=3.0)
    assert check_dynamic(linear, settings=sh.DynamicSettings(steps=240), impact=False).steps == 240
    with pytest.raises(sh.InputError, match=r"^settings must be a shtaerman\.DynamicSettings, "):
        check_dynamic(linear, settings=sh.MeshSettings(), impact=False)
