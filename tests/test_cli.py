"""The command line: its interface contract (names other tools use), in-process via main(argv)."""

import csv
import json
import re
import subprocess
import sys

import pytest

from shtaerman.cli import main

CONTRACT_KEYS = {"beta", "x_c", "P_c", "a_c", "p_c", "t_c", "t_y"}


def run(capsys, *argv):
    code = main(list(argv))
    out, err = capsys.readouterr()
    return code, out, err


def test_impact_json_has_the_contract_keys(capsys):
    code, out, err = run(capsys, "impact", "--json")
    assert code == 0 and err == ""
    result = json.loads(out)
    assert CONTRACT_KEYS <= set(result)
    # the paper's example, exact (mpmath literals in test_impact.py)
    assert result["x_c"] == pytest.approx(0.0085174899120372515388, rel=1e-14)
    assert result["t_y"] == pytest.approx(2 * 0.004105224219406260521, rel=1e-14)


def test_impact_table_has_units(capsys):
    code, out, _ = run(capsys, "impact")
    assert code == 0
    assert "max approach x_c" in out and " m\n" in out and " Pa\n" in out and " N s" in out


def test_impact_check_reports_ode_agreement(capsys):
    code, out, _ = run(capsys, "impact", "--json", "--check")
    check = json.loads(out)["ode_check"]
    assert code == 0 and check["max_history_difference"] < 1e-8


def test_history_csv(tmp_path, capsys):
    path = tmp_path / "history.csv"
    code, out, _ = run(capsys, "impact", "--json", "--history", str(path), "--points", "250")
    t_y = json.loads(out)["t_y"]
    with path.open() as stream:
        rows = list(csv.reader(stream))
    assert code == 0 and rows[0] == ["t [s]", "x [m]", "P [N]", "a [m]", "p0 [Pa]"]
    values = [[float(v) for v in row] for row in rows[1:]]
    assert len(values) == 250
    assert values[0][0] == 0.0 and values[-1][0] == pytest.approx(t_y, rel=1e-15)
    assert values[0][1] == 0.0 and values[-1][1] == 0.0


@pytest.mark.parametrize(
    ("argv", "line"),
    [
        (
            ["--points", "50"],
            "--points: applies with --history only (the rows of the history file); give "
            "--history too",
        ),
        (["--points", "201"], "--points: applies with --history only"),  # the default, given
        (["--force"], "--force: applies with --history only (it lets the run replace it)"),
    ],
)
def test_impact_refuses_history_options_without_history(capsys, argv, line):
    # `impact --points N` (or --force) without --history printed the table and exited 0: the
    # option did nothing, without a word
    code, out, err = run(capsys, "impact", *argv)
    assert code == 2 and out == ""
    assert err.startswith(f"shtaerman: error: {line}") and err.count("\n") == 1


@pytest.mark.parametrize(
    ("argv", "message"),
    [
        (["--mass", "-1"], "mass must be > 0 kg"),
        (["--velocity", "0"], "velocity must be > 0 m/s"),
        (["--shape-coefficient", "abc"], "shape-coefficient must be a number > 0"),
        (["--exponent", "0"], r"--exponent must lie in \[0.25, 20\], got '0'"),
        (["--E1", "-2e11"], r"E1 must lie in \[1e-3, 1e100\] Pa, or inf \(rigid\), got '-2e11'"),
        (["--E2", "nan"], r"E2 must be a number in \[1e-3, 1e100\] Pa"),  # every route's range
        (["--nu1", "-1"], r"nu1 must lie in \(-1, 0.5\]"),
        (["--nu2", "0.51"], r"nu2 must lie in \(-1, 0.5\]"),
        (["--points", "1"], r"points must be an integer in \[2, 1e7\]"),
        (["--points", "1000000000"], r"points must be an integer in \[2, 1e7\]"),
        (["--unknown"], "unrecognized arguments: --unknown$"),
        # adv52: an option another command takes is named as such (was argparse's alone)
        (
            ["--friction", "0.5"],
            r"unrecognized arguments: --friction 0.5 \(--friction is an option of contact, "
            r"dynamic, effects; not of this command\)$",
        ),
    ],
)
def test_bad_input_is_one_line_and_exit_2(capsys, argv, message):
    code, out, err = run(capsys, "impact", *argv)
    assert code == 2 and out == ""
    assert err.count("\n") == 1 and err.startswith("shtaerman: error: ")
    assert re.search(message, err)


@pytest.mark.parametrize(
    ("argv", "line"),
    [
        (["dynamic", "--exponent", "20.5"], "--exponent must lie in (1, 20], got '20.5'"),
        (
            ["dynamic", "--model", "neo-hookean", "--exponent", "21"],
            "--exponent must lie in (1, 20]",
        ),
        (["contact", "--exponent", "1"], "--exponent must lie in (1, 20], got '1'"),
        (["impact", "--exponent", "20.5"], "--exponent must lie in [0.25, 20], got '20.5'"),
    ],
)
def test_exponent_range_is_the_commands_and_names_the_option(capsys, argv, line):
    # `dynamic --exponent 20.5` said "exponent must lie in [0.25, 20]" (the theory's range,
    # without --), which contradicts the FEM's n > 1; each command states its own range
    code, out, err = run(capsys, *argv)
    assert code == 2 and out == ""
    assert err.startswith(f"shtaerman: error: {line}") and err.count("\n") == 1


def test_failed_run_keeps_an_existing_history(tmp_path, capsys):
    path = tmp_path / "history.csv"
    path.write_text("precious\n")
    code, _, _ = run(capsys, "impact", "--mass", "0", "--history", str(path))
    assert code == 2 and path.read_text() == "precious\n"
    assert list(tmp_path.iterdir()) == [path]


def test_fast_impact_warns_on_one_line(capsys):
    code, out, err = run(capsys, "impact", "--velocity", "6", "--json")
    assert code == 0 and json.loads(out)["x_c"] > 0
    assert err.startswith("shtaerman: warning: velocity 6 m/s exceeds 5 m/s")
    assert err.count("\n") == 1


def test_rigid_striker(capsys):
    _, out, _ = run(capsys, "impact", "--json", "--E1", "inf")
    # rigid steel: E* = 4/3 E2 = 1e7 Pa exactly
    assert json.loads(out)["modulus"] == pytest.approx(1e7, rel=1e-15)


def test_tables_json(capsys):
    code, out, _ = run(capsys, "tables", "--json")
    names = [table["name"] for table in json.loads(out)["tables"]]
    assert code == 0
    assert names == ["example", "table1", "table2", "table3", "table4", "table5", "table6"]


def test_console_script_has_no_traceback():
    completed = subprocess.run(
        [sys.executable, "-m", "shtaerman.cli", "impact", "--mass", "x"],
        capture_output=True,
        text=True,
        check=False,
    )
    assert completed.returncode == 2
    assert completed.stderr == "shtaerman: error: --mass must be a number > 0 kg, got 'x'\n"


def test_a_depth_list_is_checked_once_by_the_cli_and_once_by_the_api(capsys):
    """Validate once where input enters: the CLI reads --depths through the vocabulary, the
    public API checks what Python users give it, and the layers below (study, FEM) trust the
    checked array."""
    from shtaerman import validation, vocabulary

    codes = {
        vocabulary.Entry.check.__code__: "entry",
        validation.validate_positive.__code__: "positive",
    }
    calls = []

    def profile(frame, event, arg):
        if event == "call" and frame.f_code in codes:
            named = frame.f_locals.get("name") or getattr(frame.f_locals.get("self"), "name", "")
            if named == "depths":
                calls.append((codes[frame.f_code], frame.f_back.f_code.co_name))

    argv = ["contact", "--depths", "1e-3,2e-3", "--no-estimate", "--mesh-size", "0.05"]
    sys.setprofile(profile)
    try:
        code = main([*argv, "--domain-factor", "1e4", "--json"])
    finally:
        sys.setprofile(None)
    assert code == 0 and len(json.loads(capsys.readouterr().out)["steps"]) == 2
    # once as the option is read, once as the problem's loading is built (sh.Problem)
    assert calls == [("entry", "parse"), ("entry", "_depths")]


@pytest.mark.parametrize("value", ["0", "1000", "2.5", "many"])
def test_verify_workers_is_checked_by_the_vocabulary(capsys, value):
    code, out, err = run(capsys, "verify", "paper", "--workers", value)
    assert code == 2 and out == ""
    assert err == f"shtaerman: error: --workers must be an integer in [1, 256], got '{value}'\n"


def test_a_velocity_just_above_the_limit_is_printed_with_its_digits(capsys):
    """5.0000001 m/s was printed with %g as '5 m/s exceeds 5 m/s'."""
    code, _, err = run(capsys, "impact", "--velocity", "5.0000001")
    assert code == 0 and "velocity 5.0000001 m/s exceeds 5 m/s" in err


@pytest.mark.parametrize(
    ("argv", "message"),
    [
        # a negative list reads as a value, so the range check names it (was 'expected one
        # argument', as argparse took '-1e-3,2e-3' for an option)
        (["contact", "--depths", "-1e-3,2e-3"], "--depths must be > 0 m, got '-1e-3,2e-3'"),
        (["impact", "--history", "-h.csv"], "attach it, --history=-VALUE"),
    ],
)
def test_a_value_starting_with_a_dash_is_explained(capsys, argv, message):
    code, out, err = run(capsys, *argv)
    assert code == 2 and out == "" and err.count("\n") == 1
    assert message in err


class _StoppedError(Exception):
    """Raised in place of a verification run: the test stops before any work."""


def _stop(*args, **kwargs):
    raise _StoppedError


@pytest.mark.parametrize(("quick", "said"), [("", True), ("[quick]\ntime_steps = 60\n", False)])
def test_verify_quick_says_when_a_study_has_no_quick_table(
    tmp_path, capsys, monkeypatch, quick, said
):
    """A dynamic study without [quick] ran --quick on its full mesh in silence (its quick
    settings are its [numerics]); it is now said in one line, before the run."""
    from study_texts import DYNAMIC_STUDY

    monkeypatch.setattr("shtaerman.output.folder.run_verification", _stop)
    path = tmp_path / "dyn.toml"
    path.write_text(DYNAMIC_STUDY + quick)
    with pytest.raises(_StoppedError):
        main(["verify", str(path), "--quick", "--out", str(tmp_path / "out")])
    err = capsys.readouterr().err
    assert ("has no [quick] table: --quick runs it on its full [numerics] mesh" in err) is said
