"""Session 61's adversary: a table whose interpolation in r^2 leaves the floats is refused in
one line (a traceback, or a staircase refused as reaching beyond its rows), and the wave-speed
refusal names only remedies that run (a density2 below its range, a velocity whose x_c
underflows)."""

from __future__ import annotations

import re

import numpy as np
import pytest

import shtaerman as sh
from shtaerman.cli import main
from shtaerman.validation import InputError

COARSE = ["--mesh-size", "0.1", "--time-steps", "60", "--no-estimate", "--json"]


def _sphere_rows(radius: float, scale: float = 1.0) -> tuple[np.ndarray, np.ndarray]:
    """A sphere's rows z = R - sqrt(R^2 - r^2) to r = 0.8 R, r and z times ``scale``."""
    r = np.linspace(0.0, 0.8 * radius, 41)
    return scale * r, scale * (radius - np.sqrt(radius**2 - r**2))


@pytest.mark.parametrize("scale", [1e-150, 1e150])
def test_a_table_beyond_the_floats_interpolation_is_refused_in_one_line(scale):
    """A sphere of R = 0.05 m scaled by 1e-150 (PCHIP's weights (d r^2)^2 / dz ~ 1e-457
    underflow: its node slopes came out infinite, a scipy ValueError) or by 1e150 (~1e443
    overflow: node slopes 0, a staircase whose impact was refused as reaching beyond the last
    row, 4e148 m, at 3.15 J) is refused as a table; the remedy's spheres of R 1e-6 and 1e6 m
    interpolate with positive node slopes (strictly rising rows)."""
    with pytest.raises(InputError, match=r"beyond what the floats interpolate in r\^2"):
        sh.TabulatedIndenter(*_sphere_rows(0.05, scale))
    for radius in (1e-6, 1e6):
        table = sh.TabulatedIndenter(*_sphere_rows(radius))
        slopes = table.interpolant(table.radii**2, 1)
        assert np.all(np.isfinite(slopes)) and np.all(slopes[1:-1] > 0.0)


def test_a_power_laws_reach_refuses_an_impact_whose_depth_underflows():
    """1e-300 kg at 2.32e-49 m/s: M v0^2 = 5.4e-398 underflows, x_c = 0, which check_reach
    leaves to the exact impact; the wave refusal took it as within reach and named it."""
    from shtaerman.fem.dynamic_contact import _reaches

    reaches = _reaches(sh.PowerLawIndenter(5.0, 1.5), sh.Material(7.5e6, 0.5))
    assert reaches(1e-300, 2.32e-49) is False
    assert reaches(0.7, 3.0) is True  # the paper's impact, x/a ~ 0.07


@pytest.mark.filterwarnings("ignore::UserWarning", "ignore::RuntimeWarning")
def test_the_wave_refusal_names_no_density_below_its_range(capsys):
    """1e-300 kg at 1.34e154 m/s (the velocity the floats' refusal of 1e308 m/s names)
    radiates 8.2e151 of its energy: the refusal named density2 7.94e-302 kg/m^3 (below the
    range 1e-6, refused in turn) and 2.32e-49 m/s (x_c underflows, refused by the floor).
    It names density2 0, which runs."""
    argv = ["dynamic", "--velocity", "1.34e154", "--mass", "1e-300", *COARSE]
    assert main(argv) == 2
    said = capsys.readouterr().err.splitlines()[-1]
    assert "density2 0 (the quasi-static impact without waves) would pass" in said, said
    named = [float(x) for x in re.findall(r"density2 (\S+) kg/m\^3", said)]
    assert all(density >= 1e-6 for density in named), said
    assert main([*argv, "--density2", "0"]) == 0


@pytest.mark.filterwarnings("ignore::UserWarning")
def test_a_tip_sharper_than_a_cone_is_refused_at_any_velocity(tmp_path, capsys):
    """z = 0.2 sqrt(r) tabulated every mm to 4 cm: below its second row the PCHIP in r^2 makes
    Sneddon's depth delta(a) fall with a for a in ~(0.947, 1.0) mm (its r dz/dr decreases),
    so the striker stops before a_c: at 1.1 m/s (a_c 1.14 mm) t_c was NaN and `dynamic` a
    traceback (a singular matrix). Refused by its contact law, before any work and whatever
    depth the run reaches: at 1.0 m/s too (a_c 0.81 mm, below the band, which the impact's
    time quadrature alone refused only where it sampled it: it ran until session 62); the
    remedy, a cone z = r, runs at 1.1 m/s."""
    r = np.linspace(0.0, 0.04, 41)
    sharp, cone = tmp_path / "sharp.csv", tmp_path / "cone.csv"
    for path, z in ((sharp, 0.2 * np.sqrt(r)), (cone, r)):
        rows = "".join(f"{a!r},{b!r}\n" for a, b in zip(r.tolist(), z.tolist(), strict=True))
        path.write_text("r,z\n" + rows)
    body = sh.Material(7.5e6, 0.5)
    for velocity in (1.1, 1.0):
        with pytest.raises(InputError, match=r"profile: Sneddon's depth delta\(a\) falls"):
            sh.impact(sh.TabulatedIndenter.from_csv(sharp), body, mass=0.7, velocity=velocity)
    assert main(["dynamic", "--profile", str(sharp), "--velocity", "1.1", *COARSE]) == 2
    err = capsys.readouterr().err
    assert "Traceback" not in err and "error: --profile: Sneddon's depth" in err, err
    assert main(["impact", "--profile", str(cone), "--velocity", "1.1", "--json"]) == 0
