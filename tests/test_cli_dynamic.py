"""``shtaerman dynamic``: the interface contract of DESIGN.md, in-process via main(argv).

Coarse numerical controls (60 steps, size 1/20) keep each run to a few seconds; the physics
is tested in test_fem_dynamic.py.
"""

import contextlib
import csv
import io
import json
import math

import meshio
import pytest

from shtaerman.cli import main
from shtaerman.cli.dynamic import _unsigned_zero

COARSE = ("--time-steps", "100", "--mesh-size", "0.05")  # the ladder adds 50 and 71 steps
QUASI_STATIC_KEYS = {"beta", "x_c", "P_c", "a_c", "p_c", "t_c", "t_y"}
DYNAMIC_KEYS = {
    "x_max",
    "P_max",
    "t_x_max",
    "t_contact",
    "v_out",
    "restitution",
    "energy_radiated_fraction",
    "energy_balance_error",
    "reflected_energy_fraction",
}


def run(capsys, *argv):
    code = main(list(argv))
    out, err = capsys.readouterr()
    return code, out, err


@pytest.fixture(scope="module")
def coarse_json(tmp_path_factory):
    """One coarse run with --json, --history and --out (shared; capsys is per test)."""
    folder = tmp_path_factory.mktemp("dynamic")
    history = folder / "history.csv"
    out = folder / "out"
    stream = io.StringIO()
    with contextlib.redirect_stdout(stream):
        code = main(["dynamic", "--json", "--history", str(history), "--out", str(out), *COARSE])
    return code, json.loads(stream.getvalue()), history, out


def test_json_has_the_contract_keys(coarse_json):
    code, report, _, _ = coarse_json
    assert code == 0
    assert set(report) >= {"quasi_static", "dynamic", "radiation_estimate", "mesh", "timings"}
    assert set(report["quasi_static"]) == QUASI_STATIC_KEYS
    assert set(report["dynamic"]) >= DYNAMIC_KEYS  # the contract's; more keys welcome
    # the paper's example with a rigid striker: x_c of E* = 1e7 Pa (mpmath, 1e-12)
    assert report["quasi_static"]["x_c"] == pytest.approx(0.008517340195359727, rel=1e-12)
    # the paper's case radiates ~14 % (coarse: within a few per cent of the default run)
    assert 0.10 < report["dynamic"]["energy_radiated_fraction"] < 0.18
    assert report["radiation_estimate"]["energy_fraction"] == pytest.approx(0.157, abs=5e-4)
    assert set(report["timings"]) >= {"mesh", "assembly", "factorization", "stepping", "total"}


def test_history_has_units_and_every_step(coarse_json):
    _, report, history, _ = coarse_json
    with history.open() as stream:
        rows = list(csv.reader(stream))
    assert rows[0] == ["t [s]", "x [m]", "v [m/s]", "P [N]", "a [m]", "p0 [Pa]"]
    values = [[float(v) for v in row] for row in rows[1:]]
    assert values[0][:3] == [0.0, 0.0, 3.0]  # first touch at v0
    assert max(row[3] for row in values) == pytest.approx(report["dynamic"]["P_max"], rel=1e-2)


def test_out_folder_has_json_csv_and_fields(coarse_json):
    _, _, _, out = coarse_json
    names = sorted(path.name for path in out.iterdir())
    assert "dynamic.json" in names and "history.csv" in names and "energies.csv" in names
    fields = sorted(out.glob("*.vtu"))
    assert len(fields) == 3
    # the snapshot at t_c (second file) is under load: stresses present, surface pressed down
    mesh = meshio.read(fields[1])
    assert mesh.point_data["von_mises [Pa]"].max() > 0
    assert mesh.point_data["u_z [m]"].min() < 0


def test_text_summary(capsys):
    code, out, err = run(capsys, "dynamic", *COARSE)
    assert code == 0 and err == ""
    assert "restitution e" in out and "energy to waves" in out and "dofs" in out


def test_a_run_that_fails_its_energy_balance_says_so_and_exits_1(capsys, monkeypatch):
    # a striker far lighter than the rubber it touches: the mesh and steps sized from the
    # quasi-static impact cannot resolve it (e > 1, balance error ~5); not a silent success.
    # The wave speed guard refuses it before any mesh (exit 2): lifted to reach the run's check
    monkeypatch.setattr("shtaerman.guards.wave_limit", lambda *_: math.inf)
    code, out, err = run(capsys, "dynamic", "--mass", "1e-30", "--no-estimate", *COARSE)
    assert code == 1 and "restitution e" in out
    assert "warning: energy balance error" in err and err.count("\n") == 1


@pytest.mark.parametrize(
    ("argv", "message"),
    [
        (["--density2", "1e-7"], "density2 must lie in [1e-6, 1e6] or 0 kg/m^3"),
        (["--density2", "nan"], "density2 must be a number"),
        (["--time-steps", "10"], "time-steps must be an integer in [50, 5000], got '10'"),
        (["--time-steps", "1.5"], "time-steps must be an integer"),
        (["--nu2", "-0.2"], "nu2 must lie in [0, 0.5]"),
        (["--mesh-margin", "0.5"], "mesh-margin must lie in (1, 10]"),
        (
            ["--refine", "1e3"],
            "--refine must lie in [0.25, 500] with 200 steps per t_y (it scales the time steps",
        ),
    ],
)
def test_bad_input_is_one_line_and_exit_2(capsys, argv, message):
    code, out, err = run(capsys, "dynamic", *argv)
    assert code == 2 and out == ""
    assert message in err and err.count("\n") == 1


def test_unstable_time_stepping_is_a_failure_not_bad_input(capsys):
    """--time-steps 5000 on a coarse mesh makes the contact stepping unstable (c_s dt / h = 0.063):
    one line saying so, exit 1; it used to say 'increase margin' with exit 2, or finish."""
    code = main(["dynamic", "--no-estimate", "--time-steps", "5000", "--mesh-size", "0.1"])
    err = capsys.readouterr().err.strip().splitlines()
    assert code == 1
    assert len(err) == 1
    assert "time stepping became unstable" in err[0] and "use fewer time steps" in err[0]
    assert "energy balance" in err[0]
    # it names what to change: the options, not only "time steps"
    assert "(--time-steps) or a finer mesh with them (--mesh-size)" in err[0]


def test_steps_is_a_deprecated_alias_of_time_steps(capsys):
    import warnings

    from shtaerman.cli import build_parser
    from shtaerman.vocabulary import DeprecatedKeyWarning

    with pytest.warns(DeprecatedKeyWarning, match="--steps is deprecated; write --time-steps"):
        args = build_parser().parse_args(["dynamic", "--steps", "60"])
    assert args.time_steps == 60
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        assert build_parser().parse_args(["dynamic", "--time-steps", "60"]).time_steps == 60
    # through the command: one warning line, then the range under the option's new name
    code, out, err = run(capsys, "dynamic", "--steps", "10")
    assert code == 2 and out == "" and err.count("\n") == 2
    warning, error = err.splitlines()
    assert warning.startswith("shtaerman: warning: --steps is deprecated; write --time-steps")
    assert error == "shtaerman: error: --time-steps must be an integer in [50, 5000], got '10'"


def test_an_option_and_its_deprecated_alias_together_are_refused(capsys):
    code, out, err = run(capsys, "dynamic", "--time-steps", "60", "--steps", "80")
    assert code == 2 and out == ""
    assert err.strip().splitlines()[-1] == (
        "shtaerman: error: --time-steps and --steps name one input; keep --time-steps"
    )


@pytest.mark.parametrize("value", ["nan", "inf", "1e400"])
def test_time_steps_not_an_integer_is_one_line(capsys, value):
    # int(nan) raised ValueError and int(inf) OverflowError: a traceback, exit 1
    code, out, err = run(capsys, "dynamic", "--time-steps", value)
    assert code == 2 and out == "" and err.count("\n") == 1
    assert f"--time-steps must be an integer in [50, 5000], got '{value}'" in err


def test_force_replaces_an_existing_out_folder(capsys, tmp_path):
    """--out EXISTING --force replaces the folder (the API was once called without force=, so
    the run computed everything and then exited 2 with 'not empty (use --force)')."""
    from shtaerman.output.files import FOLDER_MARKER

    out = tmp_path / "out"
    out.mkdir()
    (out / FOLDER_MARKER).write_text("{}")  # a folder this tool wrote
    (out / "old.txt").write_text("old\n")
    code, _, err = run(capsys, "dynamic", "--no-estimate", "--out", str(out), "--force", *COARSE)
    assert code == 0 and err == ""
    names = {path.name for path in out.iterdir()}
    assert "dynamic.json" in names and "old.txt" not in names


def test_a_history_write_that_fails_leaves_no_partial_file(capsys, tmp_path, monkeypatch):
    """A --history write cut short (a file-size limit, a full disk) leaves no file behind: the
    history is staged beside the target and renamed into place; written in place, the first
    bytes stayed although the message says nothing partial is kept."""
    import errno

    import shtaerman.cli.dynamic as command

    def cut_short(path, columns):
        with open(path, "w") as stream:
            stream.write("t [s],x [m]\n0,0\n")
        raise OSError(errno.EFBIG, "File too large")

    monkeypatch.setattr(command, "write_csv", cut_short)
    history = tmp_path / "h.csv"
    code, _, err = run(capsys, "dynamic", "--no-estimate", "--history", str(history), *COARSE)
    assert code == 1 and "nothing partial is kept" in err
    assert list(tmp_path.iterdir()) == []


def test_a_run_whose_boundary_reflects_the_waves_says_so_and_exits_1(capsys):
    """--layer-rate 1e4, the largest valid, makes the far boundary reflect (0.037 of the radiated
    energy comes back after separation on this mesh; the studies allow 1e-2): the rebound is
    not a half-space's, so the run warns in one line and exits 1 (it exited 0 without a
    word)."""
    code, out, err = run(capsys, "dynamic", "--layer-rate", "1e4", "--no-estimate", *COARSE)
    assert code == 1 and "restitution e" in out
    assert err.count("\n") == 1 and "reflected energy 3.7e-02 of the radiated exceeds 0.01" in err
    assert "energy balance" not in err


def test_a_layer_rate_beyond_its_range_is_refused_naming_it(capsys):
    # 1e300 swamped the energy balance and the message blamed the time steps (exit 1)
    code, out, err = run(capsys, "dynamic", "--layer-rate", "1e300", "--no-estimate", *COARSE)
    assert code == 2 and out == "" and err.count("\n") == 1
    assert "--layer-rate must lie in [0, 1e4], got '1e300'" in err


def test_the_dynamic_checks_name_each_failure():
    from shtaerman.study.dynamic.loader import dynamic_check_failures

    assert dynamic_check_failures(1e-3, 2e-3) == []
    assert len(dynamic_check_failures(0.02, 0.5)) == 2
    assert len(dynamic_check_failures(float("nan"), 0.0)) == 1
    assert "reflected energy" in dynamic_check_failures(0.0, float("nan"))[0]


def test_too_few_time_steps_for_the_estimate_name_time_steps(capsys):
    # it blamed 'refine' (never given) with 'got 0.4999999999999999'
    code, out, err = run(capsys, "dynamic", "--time-steps", "60")
    assert code == 2 and out == "" and err.count("\n") == 1
    assert "error: --time-steps: the error-estimate ladder's coarsest level halves the time" in err
    assert "got 60" in err and "refine must" not in err


def test_a_round_off_loss_prints_without_a_minus_sign():
    # a massless run's 1 - e^2 is -1e-13 (restitution 1 to round-off): the text says 0.000000
    assert f"{_unsigned_zero(-1e-13):.6f}" == "0.000000"
    assert f"{_unsigned_zero(-0.0012344):.6f}" == "-0.001234"  # a real value keeps its sign


@pytest.mark.parametrize(
    ("argv", "message"),
    [
        (("contact", "--force"), "--force: applies with --out only"),
        (("contact", "--figure-format", "svg"), "--figure-format: applies with --out only"),
        (("dynamic", "--force"), "--force: applies with --out or --history only"),
        (("dynamic", "--model", "neo-hookean", "--force"), "--force: applies with --out or"),
        (("dynamic", "--model", "yeoh", "--figure-format", "svg"), "--figure-format: applies"),
        (("dynamic", "--figure-format", "pdf"), "--figure-format: applies with --out only"),
    ],
)
def test_output_options_without_an_output_are_refused_in_one_line(capsys, argv, message):
    # they only act on written outputs: silently ignored before, now exit 2 before any run
    assert main(list(argv)) == 2
    err = capsys.readouterr().err
    assert message in err and err.count("\n") == 1


@pytest.mark.parametrize(("option", "value"), [("--time-steps", "99"), ("--mesh-size", "0.11")])
def test_the_help_states_the_estimates_ranges_that_are_enforced(capsys, option, value):
    """--help gave [50, 5000] steps and (0, 0.2] for the mesh size, while the estimate's ladder
    (steps / 2, mesh x 2 on its coarsest level) refuses 99 steps and 0.11: the help now states
    those bounds, and the bound stated is the bound refused, before any work."""
    with pytest.raises(SystemExit):
        main(["dynamic", "--help"])
    text = " ".join(capsys.readouterr().out.split())
    assert "with it at least 100 (a level needs 50)" in text
    assert "the linear estimate's coarsest level doubles it, so with it at most 0.1;" in text
    assert "12.5 mm in the paper's example" in text  # what --mesh-size sizes, in metres
    assert main(["dynamic", option, value]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and f"error: {option}:" in err, err
    if option == "--time-steps":  # the ladder's advice names the switch once, as an option
        assert err.endswith("; or run without the estimate (--no-estimate)\n"), err


def test_a_history_file_inside_the_out_folder_is_refused_before_the_run(tmp_path, capsys):
    """It was written there unlisted, and every later --out --force onto the folder was refused
    ('holds h.csv, not written by shtaerman'); now one line before any run, exit 2."""
    folder = tmp_path / "r1"
    folder.mkdir()
    code = main(["dynamic", "--out", str(folder), "--history", str(folder / "h.csv")])
    err = capsys.readouterr().err.strip().splitlines()
    assert code == 2 and len(err) == 1
    assert "--history:" in err[0] and "inside the --out folder" in err[0]
    assert list(folder.iterdir()) == []
