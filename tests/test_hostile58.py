"""user58's hostile measurement files: a force record with its sign flipped (a confident wrong
fit, exit 0), a CSV cell past the csv module's field limit (a ``_csv.Error`` traceback), a
Latin-1 file (a raw codec message), and small words of the Prony option's refusals."""

import numpy as np
import pytest
from cli_helpers import error_line

import shtaerman as sh
from shtaerman.fitting.data import measurement
from shtaerman.validation import InputError

PEAK = 880.0  # N, about the docs' drop test (docs/fit.md)


def pulse(sign: float = 1.0, baseline: float = 0.0, noise: float = 0.01) -> str:
    """A half-sine push of PEAK N over 8 ms in a 20 ms record at 20 kHz, its noise ``noise``
    times PEAK (standard deviation), as the CSV text of a force history (ms, N)."""
    t = np.arange(0.0, 20.0, 0.05)
    push = PEAK * np.sin(np.pi * np.clip((t - 1.0) / 8.0, 0.0, 1.0))
    force = sign * (push + noise * PEAK * np.random.default_rng(58).standard_normal(t.size))
    rows = "".join(f"{a:.6g},{b + baseline:.6g}\n" for a, b in zip(t, force, strict=True))
    return "time [ms],force [N]\n" + rows


def test_a_flipped_force_history_is_refused_by_its_sign(capsys, tmp_path):
    # main fitted it: E2 836642 Pa (true 7.5e6), exit 0 (the max, noise, was > 0)
    path = tmp_path / "negative.csv"
    path.write_text(pulse(sign=-1.0))
    line = error_line(capsys, "fit", "force-history", path, "--E1", "inf", "--E2", "5e6")
    assert line.startswith(f"{path}: line "), line
    assert "column 'force' swings to -" in line and " N but rises only to " in line, line
    assert line.endswith("a push is positive; flip the record's sign"), line
    problem = sh.Problem.impact(
        sh.SphereIndenter(0.01), sh.Material(5e6, 0.5), mass=0.7, velocity=3.0
    )
    with pytest.raises(InputError, match="a push is positive") as error:
        sh.fit("force-history", path, problem)
    assert error.value.parameter == "data"


@pytest.mark.parametrize(
    ("baseline", "noise"),
    [(0.0, 0.2), (-0.3 * PEAK, 0.03), (0.5 * PEAK, 0.03)],
    ids=["noise of 20 % of the peak", "baseline -30 % of the peak", "baseline +50 %"],
)
def test_a_pushed_record_passes_the_sign_rule(baseline, noise):
    # the rule -min > max refuses a true push only at noise ~ 25 % of its peak (4 sigma) or a
    # baseline below -(P - 4 sigma)/2: these, inside, are read
    text = pulse(baseline=baseline, noise=noise)
    t, f = np.loadtxt(text.splitlines()[1:], delimiter=",").T
    data = measurement("force-history", {"time": t * 1e-3, "force": f})
    assert data.rows == t.size


def test_a_flipped_indentation_names_the_sign_not_the_float_range(capsys, tmp_path):
    path = tmp_path / "ih_neg.csv"
    path.write_text("depth [mm],force [N]\n0.5,-3.1\n1,-10\n1.5,-19.7\n2,-31.8\n")
    line = error_line(capsys, "fit", "indentation", path, "--sphere-radius", "0.01")
    assert line == (
        f"{path}: line 5: column 'force' swings to -31.8 N but rises only to -3.1 N: a push "
        "is positive; flip the record's sign"
    )


def big_cell(path):
    path.write_text("time [ms],force [N]\n0,1\n1," + "9" * 200_000 + "\n2,1\n")


def nul_bytes(path):
    path.write_bytes(b"\0" * 1_000_000)


def stray_quote(path):
    path.write_text('"time [ms],force [N]\n' + "0,1\n1,2\n" * 40_000)


@pytest.mark.parametrize(
    ("write", "line_number"), [(big_cell, 3), (nul_bytes, 1), (stray_quote, 1)]
)
def test_a_cell_past_the_field_limit_is_one_line(capsys, tmp_path, write, line_number):
    # main: "_csv.Error: field larger than field limit (131072)", a traceback, exit 1
    path = tmp_path / "d.csv"
    write(path)
    said = (
        f"{path}: line {line_number}: a cell of more than 131072 characters (an unclosed quote, "
        "or not a text CSV)"
    )
    line = error_line(capsys, "fit", "force-history", path, "--E2", "5e6")
    assert line.startswith(said), line
    with pytest.raises(InputError, match=r"a cell of more than 131072 characters"):
        measurement("force-history", path)
    line = error_line(capsys, "impact", "--profile", path)
    assert line.startswith(f"--profile: {str(path)!r}: line {line_number}: a cell of more"), line


def test_a_latin1_file_is_named_by_line_and_column(capsys, tmp_path):
    # main: "cannot read 'l.csv': 'utf-8' codec can't decode byte 0xb5 in position 20: ..."
    path = tmp_path / "l.csv"
    path.write_bytes("time [ms],force [N]\n0,1\n1,2 \xb5N\n2,1\n".encode("latin-1"))
    line = error_line(capsys, "fit", "force-history", path, "--E2", "5e6")
    assert line.endswith(
        f"{str(path)!r}: line 3, column 5: byte 0xb5 is not UTF-8 (a Latin-1 or Windows file?); "
        "save the file as UTF-8 text"
    ), line
    line = error_line(capsys, "dynamic", "--prony", path)
    assert line.startswith(f"--prony: {str(path)!r}: line 3, column 5: byte 0xb5"), line


def test_a_long_header_counts_its_characters_not_their_repr(capsys, tmp_path):
    # main: "(40000000 characters)" for 10,000,000 NUL bytes (the repr's 4 per byte)
    path = tmp_path / "zeros.csv"
    path.write_bytes(b"\0" * 100_000)
    line = error_line(capsys, "dynamic", "--prony", path)
    assert "(100000 characters)" in line and len(line) < 1000, line


def test_a_prony_series_of_the_wrong_form_says_the_form_once(capsys):
    # main: "must be written g1:tau1,g2:tau2,... (tau in s), got '0.3' (write g1:tau1,..."
    line = error_line(capsys, "dynamic", "--prony", "0.3", "--no-estimate")
    assert line.startswith("--prony: must be written g1:tau1,g2:tau2,... with each g_i >= 0")
    assert line.endswith("; got '0.3'") and line.count("g1:tau1") == 1, line


def test_an_indentation_whose_start_is_negative_names_the_sign(capsys, tmp_path):
    # -min <= max passes the sign rule, but the deeper (heavier-weighted) forces pull: the
    # starting E* < 0 was refused by "the floating-point range"
    path = tmp_path / "i.csv"
    path.write_text("depth [m],force [N]\n1e-4,0.72\n2e-4,-0.5\n3e-4,-0.6\n4e-4,-0.7\n")
    line = error_line(capsys, "fit", "indentation", path)
    assert line.startswith(f"{path}: the data give a starting modulus E* = -"), line
    assert line.endswith("a push is positive; check the force's sign"), line


@pytest.mark.parametrize(("unit", "warned"), [("s", True), ("ms", False)])
def test_a_record_far_longer_than_the_contact_is_warned_of(capsys, tmp_path, unit, warned):
    # 20 ms written under 'time [s]': "not identifiable", exit 0 and no hint on main. The
    # model's contact lasts ~9 ms: 19.9 s is ~2200 of it (warned, > SPAN_FACTOR = 100), 20 ms
    # ~2 (not warned)
    from shtaerman.cli import main

    path = tmp_path / "d.csv"
    path.write_text(pulse().replace("time [ms]", f"time [{unit}]"))
    argv = ["fit", "force-history", str(path), "--E1", "inf", "--E2", "5e6"]
    assert main([*argv, "--fit", "E2,time_offset,baseline"]) == 0
    err = capsys.readouterr().err
    said = f"{path}: the record spans 19.9 s, "
    assert (said in err and "check the units in the header" in err) == warned, err
