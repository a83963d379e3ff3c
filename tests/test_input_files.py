"""A user's input files and options that once crashed or hung the new commands (new-user pass):
a device or a directory given as a CSV, a force history too short to fit or that never
pushes, a sphere so large the impact's quadrature lost its digits."""

import os

import numpy as np
import pytest
from cli_helpers import error_line

import shtaerman as sh
from shtaerman.cli import main
from shtaerman.fitting.data import measurement
from shtaerman.validation import InputError

RIGID = ("--E1", "inf")


@pytest.fixture
def device(tmp_path):
    """A .csv name linked to /dev/zero: endless, once read until the memory ran out."""
    link = tmp_path / "zero.csv"
    os.symlink("/dev/zero", link)
    return link


@pytest.mark.parametrize(
    ("argv", "option"),
    [
        (("fit", "force-history", "{}", "--E2", "5e6"), "DATA"),
        (("impact", *RIGID, "--profile", "{}"), "--profile"),
        (("dynamic", "--prony", "{}"), "--prony"),
        (("prony-plot", "{}", "--out", "{}.png"), "SERIES"),
    ],
)
@pytest.mark.parametrize("which", ["device", "directory"])
def test_a_file_that_is_no_regular_file_is_refused_naming_the_option(
    capsys, device, tmp_path, argv, option, which
):
    path = device
    if which == "directory":
        path = tmp_path / "folder.csv"
        path.mkdir()
    line = error_line(capsys, *(a.format(path) for a in argv))
    assert line.startswith(option) and "is not a regular file" in line, line


@pytest.mark.parametrize("rows", [1, 2])
def test_a_force_history_of_fewer_than_three_rows_is_refused(rows):
    t = np.arange(rows) * 1e-3
    with pytest.raises(InputError, match=f"at least 3 rows, got {rows}") as error:
        measurement("force-history", {"time": t, "force": t + 1.0})
    assert error.value.parameter == "data"


def test_a_force_history_that_never_pushes_is_refused(capsys, tmp_path):
    path = tmp_path / "neg.csv"
    path.write_text("time [ms],force [N]\n0,-1\n1,-2\n2,-3\n3,-4\n")
    line = error_line(capsys, "fit", "force-history", str(path), "--E2", "5e6")
    assert "column 'force' must rise above 0 N" in line and "-1 N" in line, line


def test_a_sphere_beyond_its_range_is_refused_naming_the_option(capsys):
    line = error_line(capsys, "impact", *RIGID, "--sphere-radius", "1e300")
    assert line.startswith("--sphere-radius") and "1e6" in line, line
    with pytest.raises(InputError, match=r"radius must be in \(0, 1e\+06\] m"):
        sh.SphereIndenter(1e300)


@pytest.mark.parametrize("radius", [1e3, 1e6])
def test_a_huge_sphere_impacts_as_its_paraboloid(radius):
    """A contact ~1e-6 of the radius (the quadrature once lost it in round-off)."""
    rubber = sh.Material(7.5e6, 0.5)
    kwargs = {"mass": 1e-6, "velocity": 1e-3}
    sphere = sh.impact(sh.SphereIndenter(radius), rubber, **kwargs)
    paraboloid = sh.impact(sh.PowerLawIndenter(0.5 / radius, 2.0), rubber, **kwargs)
    # sphere - paraboloid is O(x_c / R) < 1e-12 here; 1e-9 leaves room for the quadrature
    assert sphere.x_c == pytest.approx(paraboloid.x_c, rel=1e-9)
    assert sphere.P_c == pytest.approx(paraboloid.P_c, rel=1e-9)


def test_a_profile_error_shows_plain_numbers(capsys, tmp_path):
    path = tmp_path / "tip.csv"
    path.write_text("r,z\n0,0\n0.001,0.0002\n0.002,0.0001\n0.003,0.0005\n")
    line = error_line(capsys, "impact", *RIGID, "--profile", str(path))
    assert "z = 0.0001 after 0.0002" in line and "np.float64" not in line, line


def test_a_sphere_too_small_for_the_impact_is_named_as_the_sphere(capsys):
    """It once said '--profile: ... beyond the table's last radius' for a sphere."""
    line = error_line(capsys, "impact", *RIGID, "--sphere-radius", "1e-5")
    assert line.startswith("--sphere-radius: ") and "sphere's equator" in line, line
    assert "table" not in line and "--profile" not in line, line


@pytest.mark.parametrize(
    ("option", "value", "expected"),
    [
        ("--time-offset", "nan", "--time-offset must be a number (in s), got 'nan'"),
        ("--baseline", "inf", "--baseline must be a finite number (in N), got 'inf'"),
    ],
)
def test_an_unbounded_option_says_number_once(capsys, tmp_path, option, value, expected):
    """They once said 'must be a number a number s', then 'must be a number s'."""
    path = tmp_path / "drop.csv"
    path.write_text("time [ms],force [N]\n0,0\n1,2\n2,1\n")
    assert error_line(capsys, "fit", "force-history", str(path), option, value) == expected


def test_a_unit_no_column_could_take_is_refused_even_when_the_header_has_units(capsys, tmp_path):
    """--units time=parsec was silently ignored beside a header that names its units."""
    path = tmp_path / "drop.csv"
    path.write_text("time [ms],force [N]\n0,0\n1,2\n2,1\n")
    line = error_line(capsys, "fit", "force-history", str(path), "--units", "time=parsec")
    assert line.startswith("--units: ") and "'parsec' is not a time unit" in line, line


def test_prony_plot_keeps_an_existing_figure_unless_forced(capsys, tmp_path):
    """It once overwrote any file at --out without a word."""
    out = tmp_path / "mine.png"
    out.write_bytes(b"precious")
    line = error_line(capsys, "prony-plot", "0.5:2e-3", "--out", str(out))
    assert line.startswith("--out: ") and "--force" in line, line
    assert out.read_bytes() == b"precious"
    assert main(["prony-plot", "0.5:2e-3", "--out", str(out), "--force"]) == 0
    assert out.read_bytes().startswith(b"\x89PNG")
    assert capsys.readouterr().out.startswith("Prony series, 1 term (tau 0.002 s)")


def test_a_profile_header_with_units_in_m_is_read_and_other_units_refused(capsys, tmp_path):
    """'r [m],z [m]' (the fit's header style) once read as 'column r is missing'."""
    rows = "0,0\n0.001,0.00005\n0.002,0.0002\n0.05,0.125\n"
    plain, metres, millimetres = (tmp_path / f"{n}.csv" for n in ("plain", "m", "mm"))
    plain.write_text("r,z\n" + rows)
    metres.write_text("r [m],z [m]\n" + rows)
    millimetres.write_text("r [mm],z [mm]\n" + rows)
    r, z = sh.TabulatedIndenter.from_csv(metres).radii, sh.TabulatedIndenter.from_csv(plain).radii
    np.testing.assert_array_equal(r, z)  # the same table, read alike
    line = error_line(capsys, "impact", *RIGID, "--profile", str(millimetres))
    assert line.startswith("--profile: ") and "unit [mm] is not m" in line, line


def test_a_profile_of_too_many_rows_is_refused_before_the_quadrature():
    """2e6 rows once asked numpy for 27 GiB (ArrayMemoryError traceback)."""
    from shtaerman.theory.profiles import MAX_PROFILE_ROWS

    r = np.linspace(0.0, 0.05, MAX_PROFILE_ROWS + 1)
    with pytest.raises(InputError, match=f"at most {MAX_PROFILE_ROWS} rows"):
        sh.TabulatedIndenter(r, r**2 / 0.02)
    r = np.linspace(0.0, 0.05, MAX_PROFILE_ROWS)  # the limit itself is taken
    assert sh.TabulatedIndenter(r, r**2 / 0.02).radii.size == MAX_PROFILE_ROWS
