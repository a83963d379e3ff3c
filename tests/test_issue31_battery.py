"""A hidden battery's variants of issue 31's attacks (other values, files and orders) that found a
defect: each refused in one line naming the option and its valid range, exit code 2."""

import pytest
from cli_helpers import error_line

SEMICOLON_FILES = {
    # European Excel writes ';' between columns (and ',' in decimals)
    "fit": ("depth [m];force [N]\n1e-4;1,0\n2e-4;2,8\n", ["fit", "indentation"]),
    "profile": ("r [m];z [m]\n0;0\n1e-3;1e-6\n", ["contact", "--profile"]),
    "prony": ("tau [s];g [1]\n1e-3;0.5\n", ["dynamic", "--prony"]),
    "prony-plot": ("tau [s];g [1]\n1e-3;0.5\n", ["prony-plot", "--out", "{tmp}/p.png"]),
}


@pytest.mark.parametrize("route", sorted(SEMICOLON_FILES))
def test_a_csv_with_semicolons_names_the_separator(capsys, tmp_path, route):
    # the message was about the header ("header cell 'depth [m];force [N]' is not 'name
    # [unit]'", "unit [m];z [m] is not m", "the header must be 'tau [s],E [Pa]' ...")
    text, argv = SEMICOLON_FILES[route]
    data = tmp_path / "semi.csv"
    data.write_text(text)
    line = error_line(capsys, *(arg.format(tmp=tmp_path) for arg in argv), data)
    assert "column separator ';' found; use ','" in line and "semi.csv" in line
