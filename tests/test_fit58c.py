"""The fit's data files read consistently (user58): a row of more or fewer cells than the
header, a --units contradicting the header, a fitted time offset's given start, and the
residual and noise of a fit where nothing is identifiable."""

import json

import numpy as np
import pytest
from cli_helpers import error_line

from shtaerman.cli import main

FIT = ["--mass", "0.7", "--velocity", "3"]


def pulse(path, header="time [ms],force [N]", extra=""):
    """A force history (ms, N): a half-sine push of 880 N over 8 ms in a 20 ms record with 1 %
    noise, ``extra`` appended to every data row; the file's path."""
    t = np.arange(0.0, 20.0, 0.05)
    push = 880.0 * np.sin(np.pi * np.clip((t - 1.0) / 8.0, 0.0, 1.0))
    force = push + 8.8 * np.random.default_rng(58).standard_normal(t.size)
    rows = "".join(f"{a:.6g},{b:.6g}{extra}\n" for a, b in zip(t, force, strict=True))
    path.write_text(f"{header}\n{rows}")
    return path


@pytest.mark.parametrize(("row", "cells"), [("0.5,4.7,7,8", 4), ("0.5,4.7,5", 3), ("0.5", 1)])
def test_a_row_of_other_cells_than_the_header_is_refused(capsys, tmp_path, row, cells):
    # main read the first two cells of a longer row (long_row.csv, ragged.csv fitted, exit 0)
    path = pulse(tmp_path / "long_row.csv")
    lines = path.read_text().splitlines()
    lines[11] = row
    path.write_text("\n".join(lines) + "\n")
    line = error_line(capsys, "fit", "force-history", path, *FIT)
    noun = "cell" if cells == 1 else "cells"
    assert line == (
        f"{path}: line 12: {cells} {noun} where the header has 2; give every row the header's "
        "columns"
    )


def test_a_trailing_comma_on_the_rows_only_is_refused_and_a_third_column_read(capsys, tmp_path):
    path = pulse(tmp_path / "trail.csv", extra=",")
    line = error_line(capsys, "fit", "force-history", path, *FIT)
    assert line.startswith(f"{path}: line 2: 3 cells where the header has 2"), line
    # a third column named in the header is read as before (user58's extra_col.csv)
    pulse(tmp_path / "extra.csv", "time [ms],force [N],temp [C]", ",20")
    assert main(["fit", "force-history", str(tmp_path / "extra.csv"), *FIT, "--json"]) == 0
    capsys.readouterr()


def test_a_profile_row_of_three_cells_is_refused(capsys, tmp_path):
    path = tmp_path / "tip.csv"
    path.write_text("r,z\n0,0\n1e-3,5e-5,1\n2e-3,2e-4\n")
    line = error_line(capsys, "impact", "--profile", str(path))
    assert line == f"--profile: '{path}': line 3: 3 cells where the header has 2; give every " + (
        "row the header's columns"
    )


def test_units_contradicting_the_header_are_refused(capsys, tmp_path):
    # main ignored --units time=s on 'time [ms]' without a word
    path = pulse(tmp_path / "h.csv")
    line = error_line(capsys, "fit", "force-history", path, *FIT, "--units", "time=s")
    assert line == (
        f"{path}: line 1: the header gives column 'time' in [ms], --units in s; drop "
        "--units time= (it serves a header cell without a unit) or correct the header"
    )
    # the same unit as the header's is no contradiction
    assert main(["fit", "force-history", str(path), *FIT, "--units", "time=ms", "--json"]) == 0
    capsys.readouterr()


@pytest.mark.parametrize(("option", "words"), [
    ("--time-offset", "--time-offset must lie in [-0.01995, 0.01995] s"),
    ("--baseline", "--baseline must lie in (-"),
])  # fmt: skip
def test_a_fitted_offset_or_baseline_start_far_off_is_refused_alike(capsys, tmp_path, option,
                                                                    words):  # fmt: skip
    # main refused --baseline 1e9 but ignored --time-offset 1e9 when both were fitted
    path = pulse(tmp_path / "h.csv")
    fitted = ["--fit", "E2,time_offset,baseline"]
    line = error_line(capsys, "fit", "force-history", path, *FIT, *fitted, option, "1e9")
    assert line.startswith(words) and line.endswith(", got 1e+09"), line


def test_a_given_start_of_the_time_offset_is_the_fits_start(capsys, tmp_path):
    path = pulse(tmp_path / "h.csv")
    argv = ["fit", "force-history", str(path), *FIT, "--fit", "E2,time_offset", "--json"]
    found = []
    for start in ([], ["--time-offset", "0.5e-3"]):
        assert main([*argv, *start]) == 0
        found.append(json.loads(capsys.readouterr().out))
    assert found[1]["known"]["time_offset"] == 0.5e-3  # the start given is the one used
    # both starts reach the same optimum: to the solver's tolerance, far inside the intervals
    for name in ("E2", "time_offset"):
        assert found[1]["fitted"][name]["value"] == pytest.approx(
            found[0]["fitted"][name]["value"], rel=1e-6
        )


def test_nothing_identifiable_reports_the_noise_of_the_residual_shown(capsys, tmp_path):
    # main: "residual rms 79.77 N; noise 53.35 N (estimated from the residual)", the noise
    # from the search's residual, the rms from the model at the held starts
    path = pulse(tmp_path / "h.csv")
    argv = ["fit", "force-history", str(path), *FIT, "--fit", "E2,mass,velocity"]
    assert main([*argv, "--json"]) == 0
    result = json.loads(capsys.readouterr().out)
    assert not any(item["identifiable"] for item in result["fitted"].values())
    # nothing fitted: all 400 degrees of freedom left, so the noise is the rms (rounding)
    assert result["noise"]["value"] == pytest.approx(result["residual"]["rms"], rel=1e-12)
    assert main(argv) == 0
    last = capsys.readouterr().out.splitlines()[-1]
    assert " at the values above (none fitted); noise " in last, last


def test_a_trailing_comma_on_every_line_names_the_header_line(capsys, tmp_path):
    # main refused it without a line: "header cell '' is not 'name [unit]'"
    path = pulse(tmp_path / "trail.csv", "time [ms],force [N],", ",")
    line = error_line(capsys, "fit", "force-history", path, *FIT)
    assert line == (
        f"{path}: line 1: header cell '' is not 'name [unit]' (a trailing or doubled comma?)"
    )
