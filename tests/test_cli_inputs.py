"""Validate once, where input enters, from one vocabulary: every range, limit and default is
declared in :mod:`shtaerman.vocabulary`, and the command line, study files, sweeps and the
Python API refuse the same inputs before computing, each in its own words."""

import ast
import dataclasses
import importlib.util
import warnings
from pathlib import Path

import numpy as np
import pytest

import shtaerman as sh
from shtaerman.cli import build_parser, main
from shtaerman.fem.contact.linear import validate_fem_inputs
from shtaerman.study.contact.indentation import default_depths
from shtaerman.study.schema import load_study
from shtaerman.sweep import parse_sweep
from shtaerman.sweep import spec as sweep_spec
from shtaerman.sweep.kinds import get_kind
from shtaerman.validation import InputError
from shtaerman.vocabulary import MAX_STUDIES, entry, parameter_table

ROOT = Path(__file__).resolve().parents[1]
PAPER = sh.PowerLawIndenter(5.0, 1.5)
RUBBER = sh.Material(7.5e6, 0.5)
DYNAMIC_STUDY = (
    'kind = "dynamic"\n[indenter]\nshape_coefficient = 5.0\nexponent = 1.5\n'
    "[half_space]\nE2 = 7.5e6\nnu2 = 0.5\ndensity2 = 1100.0\n[impact]\nmass = 0.7\n"
)
CONTACT_STUDY = (
    "[indenter]\nshape_coefficient = 5.0\nexponent = 1.5\n[half_space]\nE2 = 7.5e6\n"
    "nu2 = 0.5\n[impact]\nmass = 0.7\nvelocity = 3.0\n"
)


def error_line(capsys, *argv):
    """The one error line of a refused command (exit code 2, nothing on stdout)."""
    code = main(list(argv))
    out, err = capsys.readouterr()
    assert code == 2 and out == "" and err.count("\n") == 1, (code, out, err)
    return err.removeprefix("shtaerman: error: ").strip()


# --- the FEM's ranges come from the vocabulary -------------------------------------------------


def test_the_fem_shape_coefficient_limit_is_refused_as_the_option_is_read():
    """A > 1e100 was refused only after parsing, in the API's words."""
    with pytest.raises(InputError) as error:
        build_parser().parse_args(["contact", "--shape-coefficient", "1e200"])
    assert str(error.value) == "--shape-coefficient must lie in (0, 1e100] m^(1-n), got '1e200'"
    assert "(0, 1e100]" in parameter_table(build_parser())


@pytest.mark.parametrize(
    ("indenter", "body", "name"),
    [
        (sh.PowerLawIndenter(1e200, 1.5), RUBBER, "shape_coefficient"),
        (sh.PowerLawIndenter(5.0, 1.0), RUBBER, "exponent"),
        (PAPER, sh.Material(1e-4, 0.5), "E2"),
        (PAPER, sh.Material(7.5e6, -0.1), "nu2"),
    ],
)
def test_the_fem_check_is_the_vocabularys(indenter, body, name):
    with pytest.raises(InputError) as error:
        validate_fem_inputs(indenter, body)
    value = {
        "shape_coefficient": indenter.shape_coefficient,
        "exponent": indenter.exponent,
        "E2": body.youngs_modulus,
        "nu2": body.poisson_ratio,
    }[name]
    with pytest.raises(InputError) as expected:
        entry(name).check(value, "contact")
    assert str(error.value) == str(expected.value) and error.value.parameter == name


# --- one place for the defaults and the depths ----------------------------------------------------


def test_default_depths_are_one_function_with_the_vocabularys_impact():
    default = default_depths(PAPER, RUBBER)
    assert np.array_equal(
        default, default_depths(PAPER, RUBBER, entry("mass").default, entry("velocity").default)
    )
    own = default_depths(PAPER, RUBBER, 0.25, 2.0)
    assert own[-1] == pytest.approx(sh.impact(PAPER, RUBBER, mass=0.25, velocity=2.0).x_c, 1e-15)


def test_the_contact_help_states_the_vocabularys_striker(monkeypatch):
    from shtaerman.cli import contact

    assert contact.DERIVED["mass"].startswith(f"{entry('mass').default:g}; ")
    assert contact.DERIVED["velocity"].startswith(f"{entry('velocity').default:g}; ")


def test_estimate_default_is_declared_per_surface():
    """On by default in the CLI and the API, off in a sweep (it doubles a case's cost); the
    parameter page said off for all."""
    item = entry("estimate")
    assert item.default_for("dynamic") is True
    assert get_kind("dynamic").defaults()["estimate"] is False
    row = next(
        line
        for line in parameter_table(build_parser()).splitlines()
        if line.startswith("| `estimate`")
    )
    assert "| true; false in a dynamic sweep |" in row
    spec = importlib.util.spec_from_file_location("docs_hooks", ROOT / "docs" / "hooks.py")
    hooks = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(hooks)
    assert "| `--no-estimate` | off (estimate on) |" in hooks.parameters_page()


# --- the CLI names its options, the API its keywords --------------------------------------------


@pytest.mark.parametrize(
    ("argv", "start"),
    [
        (["--mass", "0.5", "--depths", "1e-3,2e-3"], "--mass: sets the default depths"),
        (["--accuracy", "1e-3", "--no-estimate"], "--accuracy: needs the error estimates"),
        (["--accuracy", "1e-3", "--refine", "2"], "--refine: --accuracy chooses the refinement"),
        (["--accuracy", "1e-3", "--model", "neo-hookean"], "--accuracy: applies to the linear"),
        (["--model", "neo-hookean", "--solver", "pardiso"], "--solver: the neo-hookean model"),
    ],
)
def test_contact_refusals_name_the_options(capsys, argv, start):
    assert error_line(capsys, "contact", *argv).startswith(start)


@pytest.mark.skipif(
    importlib.util.find_spec("pypardiso") is not None, reason="pypardiso is installed"
)
def test_a_missing_pardiso_is_refused_before_meshing_naming_the_option(capsys):
    line = error_line(capsys, "contact", "--solver", "pardiso")
    assert line.startswith("--solver 'pardiso' needs the package pypardiso")
    with pytest.raises(InputError, match=r"^solver 'pardiso' needs") as error:
        sh.contact(PAPER, RUBBER, solver="pardiso", estimate=False)
    assert error.value.parameter == "solver"


@pytest.mark.parametrize("text", ["1e-3,,2e-3", "1e-3,2e-3,", ",1e-3"])
def test_empty_depth_items_are_refused(capsys, text):
    line = error_line(capsys, "contact", "--depths", text)
    assert line == f"--depths must be numbers separated by single commas, got '{text}'"


@pytest.mark.parametrize(
    "call",
    [
        lambda: sh.Material(youngs_modulus="4e6", poisson_ratio=0.49),
        lambda: sh.Material(youngs_modulus=4e6, poisson_ratio="0.49"),
        lambda: sh.PowerLawIndenter(shape_coefficient="12", exponent=1.8),
        lambda: sh.impact(PAPER, RUBBER, mass="0.25", velocity=2.0),
        lambda: sh.contact(PAPER, RUBBER, mass=0.25, velocity="2", estimate=False),
        lambda: sh.contact(PAPER, RUBBER, refine="2", estimate=False),
        lambda: sh.dynamic(PAPER, sh.Material(7.5e6, 0.5, 1100.0), mass=0.7, velocity=b"3"),
    ],
)
def test_the_api_refuses_numeric_strings(call):
    """numpy would take "4e6" through float() in one place and as text in another."""
    with pytest.raises(InputError, match="not a string") as error:
        call()
    assert error.value.parameter in {
        "youngs_modulus",
        "poisson_ratio",
        "shape_coefficient",
        "mass",
        "velocity",
        "refine",
    }


# --- limits declared once, refused at load ------------------------------------------------------


def test_time_steps_are_limited_to_what_the_fem_keeps_stable(tmp_path, capsys):
    """100000 time steps per t_y were accepted and failed at run time (the contact stepping is
    unstable beyond about 5000 at the default mesh)."""
    assert entry("time_steps").range_for("dynamic").high == 5000
    path = tmp_path / "dyn.toml"
    path.write_text(DYNAMIC_STUDY + "velocity = 3.0\n[numerics]\ntime_steps = 100000\n")
    with pytest.raises(
        InputError, match=r"'numerics.time_steps': time_steps must be an integer in \[50, "
    ):
        load_study(path)
    line = error_line(capsys, "dynamic", "--time-steps", "20000")
    assert line == "--time-steps must be an integer in [50, 5000], got '20000'"
    with pytest.raises(InputError, match=r"^time_steps must be an integer in \[50, 5000\]"):
        sh.dynamic(PAPER, sh.Material(7.5e6, 0.5, 1100.0), mass=0.7, velocity=3.0, time_steps=10**5)
    sweep = (
        'name = "s"\nkind = "dynamic"\n[parameters]\ntime_steps = 100000\n[axes]\nmass = [1.0]\n'
    )
    with pytest.raises(InputError, match=r"parameters.time_steps must be an integer in \[50, 5000"):
        parse_sweep(sweep)


def test_neo_hookean_depths_are_limited_as_linear_ones(capsys):
    depths = ",".join(f"{1e-4 * (1 + i / 1000):.8g}" for i in range(9000))
    line = error_line(capsys, "contact", "--model", "neo-hookean", "--depths", depths)
    assert line.startswith("--depths must list at most 1000 values, got 9000")
    with pytest.raises(InputError, match="depths must list at most 1000 values, got 1001"):
        sh.contact(PAPER, RUBBER, model="neo-hookean", depths=np.geomspace(1e-4, 1e-3, 1001))


def test_study_depths_are_limited(tmp_path):
    depths = ", ".join(f"{1e-4 * (1 + i / 1000):.8g}" for i in range(1001))
    path = tmp_path / "many.toml"
    path.write_text(CONTACT_STUDY + f"[contact]\ndepths = [{depths}]\n")
    with pytest.raises(InputError, match=r"'contact.depths': expected a list of 2 to 1000 "):
        load_study(path)


def test_dynamic_study_velocities_are_limited(tmp_path):
    velocities = ", ".join(f"{1 + i / 1e5:.6f}" for i in range(101))
    path = tmp_path / "many.toml"
    path.write_text(DYNAMIC_STUDY + f"velocity = [{velocities}]\n")
    with pytest.raises(InputError, match=r"a list of at most 100 increasing ones") as error:
        load_study(path)
    assert "(101 values)" in str(error.value) and len(str(error.value)) < 400


def test_a_study_sweep_is_limited(tmp_path):
    values = ", ".join(f"{1 + i / 1e4:.5f}" for i in range(MAX_STUDIES + 1))
    path = tmp_path / "many.toml"
    path.write_text(CONTACT_STUDY + f"[sweep]\nmass = [{values}]\n")
    with pytest.raises(InputError, match=rf"expected at most {MAX_STUDIES} values of mass"):
        load_study(path)


def test_a_sweep_axis_is_checked_for_duplicates_in_linear_time(monkeypatch):
    """The duplicate check of an axis compares each value with a set, not with every other
    value: 20,000 distinct values make (almost) no equality comparisons."""
    compared = []

    class Counted(float):
        __hash__ = float.__hash__

        def __eq__(self, other):
            compared.append(1)
            return float.__eq__(self, other)

    convert = sweep_spec._value
    monkeypatch.setattr(sweep_spec, "_value", lambda *args: Counted(convert(*args)))
    values = [1.0 + i / 1e4 for i in range(20_000)]
    axis = sweep_spec._axis("s.toml", get_kind("impact"), "velocity", values)
    assert len(compared) < 100 and axis == values
    with pytest.raises(InputError, match=r"lists 1\.5 twice"):
        sweep_spec._axis("s.toml", get_kind("impact"), "velocity", [1.0, 1.5, 2.0, 1.5])


# --- one declaration of each name -----------------------------------------------------------------


def test_public_names_are_listed_once():
    import shtaerman.api

    tree = ast.parse((ROOT / "src" / "shtaerman" / "api" / "__init__.py").read_text())
    literal = [
        node
        for node in ast.walk(tree)
        if isinstance(node, ast.Assign)
        and any(getattr(t, "id", "") == "__all__" for t in node.targets)
        and isinstance(node.value, ast.List)
    ]
    assert literal == []
    sweep_types = ("SweepOutcome", "SweepSpec")  # exported from shtaerman.sweep, lazily
    assert shtaerman.api.__all__ == [
        n for n in sh.__all__ if n not in ("__version__", *sweep_types)
    ]


@pytest.mark.parametrize("package", ["shtaerman", "shtaerman.api"])
def test_star_import_finds_every_listed_name(package):
    """``from PACKAGE import *`` resolves every name of ``__all__`` (a name listed but not
    defined raised AttributeError after the sweep types joined the public list)."""
    namespace: dict = {}
    exec(f"from {package} import *", namespace)
    listed = importlib.import_module(package).__all__
    assert [name for name in listed if name not in namespace] == []


def test_the_impact_result_reads_the_theorys_solution():
    result = sh.impact(PAPER, RUBBER, mass=0.7, velocity=3.0)
    assert [f.name for f in dataclasses.fields(result)] == ["solution", "ode_check"]
    for key in ("beta", "x_c", "P_c", "a_c", "p_c", "t_c", "t_y", "impulse", "force_exponent"):
        assert getattr(result, key) == getattr(result.solution, key)
    assert result.modulus == result.solution.law.modulus


def test_the_settings_fields_are_named_once():
    from shtaerman.api.fem_contact import MESH_OPTIONS
    from shtaerman.api.fem_dynamic import SETTINGS_OPTIONS
    from shtaerman.vocabulary import fields

    assert fields(MESH_OPTIONS)["mesh_size"] == "size"
    assert fields(SETTINGS_OPTIONS)["time_steps"] == "steps"
    assert not isinstance(MESH_OPTIONS, dict) and not isinstance(SETTINGS_OPTIONS, dict)


def test_a_zero_gap_beyond_the_edge_is_refused_by_the_edge_function():
    from shtaerman.fem.contact.constraints import edge_radius
    from shtaerman.validation import NumericalFailureError

    r = np.linspace(0.0, 1e-2, 41)
    forces = np.where(r < 3e-3, 1.0, 0.0)
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        with pytest.raises(NumericalFailureError, match="zero gap"):
            edge_radius(r, forces, np.zeros_like(r))
