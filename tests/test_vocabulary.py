"""One vocabulary: every input declared once, and every entry point (CLI, API defaults, study
files, sweeps, docs) speaking it with the same names, defaults and ranges."""

import argparse
import dataclasses
import math
import warnings

import pytest

from shtaerman.cli import build_parser
from shtaerman.fem.dynamic_contact import DynamicSettings
from shtaerman.fem.mesh import FINITE_MESH, MeshSettings
from shtaerman.study.schema import find_study, load_study
from shtaerman.sweep import load_sweep
from shtaerman.sweep.kinds import get_kind
from shtaerman.sweep.spec import find_sweep
from shtaerman.validation import InputError
from shtaerman.vocabulary import (
    KIND_NAMES,
    VOCABULARY,
    entry,
    inputs_of,
    parameter_table,
    suggestion,
)

CONTRACT = {"--E1", "--E2", "--nu1", "--nu2", "--density2"}
"""Options of the interface contract spelt as their key (no case change, no hyphen to add)."""
COMMANDS = {"impact": "impact", "contact": "contact", "dynamic": "dynamic", "fit": None}
"""CLI subcommand -> the kind whose defaults and ranges it uses."""


RENAMED = {"estimate": "--no-estimate", "unknowns": "--fit"}
"""The inputs whose option is not their keyword's kebab case: the CLI switches the estimate off,
and sh.fit's unknowns are the contract's ``fit ... --fit NAME,...``."""


def test_names_are_unique_snake_case_and_options_their_kebab_case():
    names = [item.name for item in VOCABULARY]
    assert len(names) == len(set(names))
    for item in VOCABULARY:
        assert item.name == item.name.strip() and " " not in item.name and "-" not in item.name
        if item.cli_option in CONTRACT:
            assert item.cli_option == "--" + item.name
        elif item.name in RENAMED:
            assert item.cli_option == RENAMED[item.name]
        else:
            assert item.cli_option == "--" + item.name.replace("_", "-")
        assert item.meaning and item.label and item.group in ("case", "numerics", "output")
        assert set(item.kinds) <= set(KIND_NAMES)


@pytest.mark.parametrize(
    ("name", "kind", "value", "message"),
    [
        ("nu2", "contact", -0.2, r"nu2 must lie in \[0, 0.5\], got -0.2"),
        ("nu2", "impact", 0.6, r"nu2 must lie in \(-1, 0.5\], got 0.6"),
        ("nu1", None, 3.0, r"nu1 must lie in \(-1, 0.5\], got 3.0"),
        ("exponent", "dynamic", 1.0, r"exponent must lie in \(1, 20\], got 1.0"),
        ("time_steps", "dynamic", 10, r"time_steps must be an integer in \[50, 5000\], got 10"),
        ("time_steps", "dynamic", 60.5, r"time_steps must be an integer"),
        ("depths", "contact", [2e-3, 1e-3], r"depths must be increasing, each > 0"),
        # every kind's range, the exact impact's too (adv53: it took 1e-300 Pa)
        ("E2", "impact", math.inf, r"E2 must be a finite number in \[1e-3, 1e100\] Pa"),
        ("mass", "impact", True, r"mass must be a number > 0 kg, got True"),
        ("solver", "contact", "umfpack", r"solver must be one of auto, superlu, pardiso"),
    ],
)
def test_check_names_the_input_and_its_range(name, kind, value, message):
    with pytest.raises(InputError, match=message) as error:
        entry(name).check(value, kind)
    assert error.value.parameter == name and "\n" not in str(error.value)


def test_check_accepts_what_the_range_allows():
    assert entry("nu2").check(-0.2, "impact") == -0.2  # the theory takes auxetic solids
    assert entry("E1").check(math.inf) == math.inf  # a rigid striker
    assert entry("time_steps").check(200, "dynamic") == 200
    assert entry("depths").check(1e-3) == [1e-3]


def test_an_unknown_name_says_what_it_probably_meant():
    with pytest.raises(InputError, match=r"unknown input 'shape_coeficient' \(did you mean "):
        entry("shape_coeficient")
    assert suggestion("densty2", ["E2", "density2"]) == " (did you mean 'density2'?)"
    assert suggestion("colour", ["E2", "nu2"]) == ""


def test_parameter_table_has_one_row_per_input():
    table = parameter_table(build_parser()).splitlines()
    assert table[0] == "### The case"  # a table per group: the case, the numerics, the output
    assert table.count("| Key, CLI option | Default | Meaning [unit] |") == 3
    assert len([line for line in table if line.startswith("| `")]) == len(VOCABULARY)
    row = next(line for line in table if line.startswith("| `nu2`<br>"))
    assert (
        "`--nu2` (impact, contact, dynamic, effects, fit)" in row
        and "(-1, 0.5]; FEM [0, 0.5]" in row
    )
    row = next(line for line in table if line.startswith("| `time_steps`<br>"))
    assert "`--time-steps` (dynamic, effects)" in row and "formerly `steps`" in row
    assert "| 200; the model's in a dynamic sweep |" in row  # a rubber's own there
    row = next(line for line in table if line.startswith("| `mesh_size`<br>"))
    assert "0.025 (dynamic)" in row and "0.00666667 (contact, layer)" in row
    row = next(line for line in table if line.startswith("| `thickness_ratio`<br>"))
    assert "| `thickness_ratio`<br>study and sweep key only |" in row  # no --thickness-ratio


# --- the defaults: declared once, the same through every entry point ------------------------------


def test_mesh_defaults_are_the_fem_defaults():
    for kind, settings in (("contact", MeshSettings()), ("finite-strain", FINITE_MESH)):
        for name, item in inputs_of(kind).items():
            field = item.settings_field
            if field in MeshSettings.__dataclass_fields__:
                assert item.default_for(kind) == getattr(settings, field), (kind, name)


def test_dynamic_defaults_are_the_settings_defaults():
    settings = DynamicSettings()
    for name, item in inputs_of("dynamic").items():
        field = item.settings_field
        if field in DynamicSettings.__dataclass_fields__:
            assert item.default_for("dynamic") == getattr(settings, field), name


@pytest.mark.parametrize("kind", ["impact", "contact", "finite-strain", "dynamic", "layer"])
def test_sweep_parameters_are_the_vocabulary(kind):
    parameters = get_kind(kind).parameters
    assert list(parameters) == list(inputs_of(kind))
    for name, parameter in parameters.items():
        item = entry(name)
        assert (parameter.default, parameter.unit, parameter.type) == (
            item.sweep_default_for(kind),
            item.unit,
            item.type,
        )


def _subcommand(name: str) -> argparse.ArgumentParser:
    action = next(a for a in build_parser()._actions if isinstance(a, argparse._SubParsersAction))
    return action.choices[name]


def _dynamic_cli_default(*options: str) -> str:
    action = next(
        a for a in _subcommand("dynamic")._actions if set(options) & set(a.option_strings)
    )
    return action.default


def test_dynamic_defaults_agree_through_every_entry_point(tmp_path):
    from shtaerman.api.fem_dynamic import check_dynamic
    from shtaerman.sweep.kinds import _dynamic

    """200 time steps per t_y at mesh size 1/40: the CLI, DynamicSettings(), a study file that
    sets none, the shipped study, a sweep that sets none and the shipped validity sweep."""
    expected = (200, 1 / 40)
    cli = (
        int(float(_dynamic_cli_default("--time-steps", "--steps"))),
        float(_dynamic_cli_default("--mesh-size")),
    )
    assert cli == pytest.approx(expected, rel=1e-5)  # the help prints 6 digits
    settings = DynamicSettings()
    assert (settings.steps, settings.size) == expected
    assert settings.refined(2) == dataclasses.replace(
        settings, steps=400, size=1 / 80, axis_size=settings.axis_size / 2, growth=0.1
    )
    minimal = tmp_path / "mine.toml"
    minimal.write_text(
        'kind = "dynamic"\n[indenter]\nshape_coefficient = 5.0\nexponent = 1.5\n'
        "[half_space]\nE2 = 7.5e6\nnu2 = 0.5\ndensity2 = 1100.0\n[impact]\nmass = 0.7\n"
        "velocity = 3.0\n"
    )
    [study] = load_study(minimal)
    [shipped] = load_study(find_study("dynamic"))
    assert study.settings == shipped.settings == settings
    defaults = get_kind("dynamic").defaults()  # None: the model's, the linear one's here
    assert (defaults["time_steps"], defaults["mesh_size"]) == (None, None)
    problem, numerics = _dynamic(defaults)
    linear = check_dynamic(problem, **numerics)
    assert (linear.steps, linear.size) == expected
    validity = load_sweep(find_sweep("validity"))
    assert (validity.parameters["time_steps"], validity.parameters["mesh_size"]) == expected


# --- the command line against the vocabulary -------------------------------------------------


def _options(command: str):
    """(option, action, entry or None) of every ``--`` option of a subcommand but --help."""
    by_option = {item.cli_option: item for item in VOCABULARY}
    renamed = {
        "--" + old.replace("_", "-"): item
        for item in VOCABULARY
        if command in item.kinds or not item.kinds
        for old in item.old_names
    }
    for action in _subcommand(command)._actions:
        option = next((o for o in action.option_strings if o.startswith("--")), None)
        if option in (None, "--help"):
            continue
        yield option, action, by_option.get(option) or renamed.get(option)


@pytest.mark.parametrize("command", sorted(COMMANDS))
def test_every_cli_option_has_an_entry_with_its_default(command):
    kind = COMMANDS[command]
    wrong = []
    for option, action, item in _options(command):
        if item is None:
            wrong.append(f"{option}: no vocabulary entry")
            continue
        expected = item.default_for(kind)
        if item.type in ("flag", "bool"):  # --json is off; --no-estimate leaves estimate on
            if action.default is not expected:
                wrong.append(f"{option}: default {action.default!r}, vocabulary {expected!r}")
            continue
        if action.default is None:
            continue  # a default derived from other inputs (shown in the help)
        same = (
            action.default == expected
            if isinstance(expected, str)
            else math.isclose(float(action.default), expected, rel_tol=1e-5)
        )
        if not same:
            wrong.append(f"{option}: default {action.default!r}, vocabulary {expected!r}")
    assert wrong == []


@pytest.mark.parametrize("command", sorted(COMMANDS))
def test_every_cli_option_is_named_and_ranged_as_the_vocabulary(command):
    kind = COMMANDS[command]
    wrong = []
    for option, action, item in _options(command):
        if item is None or option != item.cli_option:
            wrong.append(f"{option}: the vocabulary calls it {item and item.cli_option}")
            continue
        text = item.range_text(kind)
        if text and not item.choices and text not in (action.help or ""):
            wrong.append(f"{option}: help {action.help!r} lacks {text!r}")
    assert wrong == []


def test_sweep_and_study_keys_that_were_renamed_warn_once(tmp_path):
    path = tmp_path / "old.toml"
    path.write_text(
        'name = "old"\nkind = "dynamic"\n[parameters]\nsteps = 60\nmesh_size = 0.05\n'
        "[axes]\nvelocity = [3.0]\n"
    )
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        spec = load_sweep(path)
    assert spec.parameters["time_steps"] == 60 and "steps" not in spec.parameters
    [warning] = caught
    assert "'parameters.steps' is deprecated; write 'parameters.time_steps'" in str(warning.message)


@pytest.mark.parametrize(
    ("kind", "table", "line", "expected"),
    [
        ("finite-strain", "contact", "reach = 3.5", "reach must lie in [1, 3], got 3.5"),
        (
            "finite-strain",
            "quick",
            "depth_steps = 2",
            "depth_steps must be an integer in [4, 200], got 2",
        ),
        (
            "dynamic",
            "numerics",
            "time_steps = 10",
            "time_steps must be an integer in [50, 5000], got 10",
        ),
        (
            "dynamic",
            "numerics",
            "layer_rate = -1.0",
            "layer_rate must lie in [0, 1e4], got -1.0",
        ),
        (
            "dynamic",
            "numerics",
            "layer_rate = 1e9",
            "layer_rate must lie in [0, 1e4], got 1000000000.0",
        ),
    ],
)
def test_study_files_check_the_vocabulary_ranges(tmp_path, kind, table, line, expected):
    path = tmp_path / "bad.toml"
    density = "density2 = 1100.0\n" if kind == "dynamic" else ""
    path.write_text(
        f'kind = "{kind}"\n[indenter]\nshape_coefficient = 5.0\nexponent = 1.5\n'
        f"[half_space]\nE2 = 7.5e6\nnu2 = 0.5\n{density}[impact]\nmass = 0.7\nvelocity = 3.0\n"
        f"[{table}]\n{line}\n"
    )
    with pytest.raises(InputError) as error:
        load_study(path)
    key = line.split(" = ")[0]
    assert f"key '{table}.{key}': {expected}" in str(error.value)


def _bad_value(valid) -> float:
    """A number just outside ``valid``."""
    if valid.low is not None:
        return valid.low if valid.low_open else valid.low - abs(valid.low) / 2 - 1
    return valid.high * 2 + 1


@pytest.mark.parametrize("command", sorted(COMMANDS))
def test_every_cli_value_is_checked_by_its_entry(command):
    """Each option outside its range is refused as it is read, in one line naming the option
    and the entry's range for the command's kind."""
    kind = COMMANDS[command]
    checked = 0
    for option, _action, item in _options(command):
        valid = item.range_for(kind)
        if item.type not in ("float", "int", "floats") or valid is None:
            continue
        bad = _bad_value(valid)
        with pytest.raises(InputError) as error:
            build_parser().parse_args([command, option, f"{bad!r}"])
        message = str(error.value)
        assert message.startswith(f"{option} must ") and valid.text() in message, message
        assert error.value.parameter == item.name and "\n" not in message
        checked += 1
    assert checked >= {"impact": 9, "contact": 14, "dynamic": 14, "fit": 9}[command]
