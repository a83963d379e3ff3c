"""Session 62's loose ends of the impact's input checks: a massless FE impact whose time step
squares below the floats runs without numpy's overflow warnings, a striker whose deceleration
P_c / M leaves the floats is refused naming the velocity that runs, and a table sharper than
a cone is refused by its contact law on the contact curve's route too."""

from __future__ import annotations

import json

import numpy as np
import pytest

import shtaerman as sh
from shtaerman.cli import main
from shtaerman.validation import InputError

COARSE = ["--mesh-size", "0.1", "--time-steps", "60", "--no-estimate", "--json"]
FAST = ["--velocity", "1.34e154", "--mass", "1e-300", "--density2", "0"]


def test_a_massless_impact_whose_time_step_squares_below_the_floats_runs_cleanly(capsys):
    """1e-300 kg at 1.34e154 m/s on the default z = 5 r^1.5, massless body: t_c = 5.74e-154 s,
    so dt^2 ~ 1e-310 is subnormal and 1/(beta dt^2) overflowed, printing ~3,000 numpy
    overflow / invalid-value warnings (the mass terms it scaled were all zero). Now none, and
    x_max is the exact x_c 5.3197 m (shtaerman impact --json) to 1e-3 (the massless FE
    matched it to 1e-4 at the default mesh; this mesh is 4x coarser)."""
    assert main(["dynamic", *FAST, *COARSE]) == 0
    out, err = capsys.readouterr()
    assert "encountered" not in err, err
    x_max = json.loads(out)["dynamic"]["x_max"]
    assert x_max == pytest.approx(5.319704645874504, rel=1e-3)


def test_a_deceleration_beyond_the_floats_is_refused_naming_a_velocity_that_runs(capsys):
    """The same striker on z = 1e-10 r^3: P_c = 1.606e9 N (closed form, shtaerman impact
    --json), so P_c / M = 1.606e309 m/s^2 overflowed the striker's acceleration: a traceback
    (LinAlgError, infs in the contact problem). Refused on the command line and by the API,
    each in its words, naming 1.07e153 m/s, which runs."""
    shape = ["--exponent", "3", "--shape-coefficient", "1e-10"]
    assert main(["dynamic", *FAST, *shape, *COARSE]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "P_c / M = 1.606e+309 m/s^2" in err, err
    assert "lower --velocity to at most about 1.07e+153 m/s" in err, err
    body, striker = sh.Material(7.5e6, 0.5), sh.PowerLawIndenter(1e-10, 3.0)
    with pytest.raises(InputError, match=r"lower velocity=\.\.\. to at most about 1\.07e\+153"):
        sh.dynamic(striker, body, mass=1e-300, velocity=1.34e154, density=0.0)
    assert main(["dynamic", *FAST[2:], "--velocity", "1.07e153", *shape, *COARSE]) == 0
    assert "encountered" not in capsys.readouterr().err


@pytest.mark.filterwarnings("ignore::UserWarning")
def test_a_tip_sharper_than_a_cone_is_refused_by_its_contact_law(tmp_path, capsys):
    """z = 0.2 sqrt(r) every mm to 1 cm: its depth delta(a) falls near a = 1 mm (the PCHIP in
    r^2 below the second row); at 1.0 m/s (a_c below the band) the impact ran and the
    contact curve never asked. Refused by the contact law now, before any work, on both
    routes; a cone z = r tabulated alike (n = 1 exactly) still runs."""
    r = np.linspace(0.0, 0.01, 11)
    sharp, cone = tmp_path / "sharp.csv", tmp_path / "cone.csv"
    for path, z in ((sharp, 0.2 * np.sqrt(r)), (cone, r)):
        rows = "".join(f"{a!r},{b!r}\n" for a, b in zip(r.tolist(), z.tolist(), strict=True))
        path.write_text("r,z\n" + rows)
    for argv in (["impact", "--velocity", "1.0"], ["contact"]):
        assert main([*argv, "--profile", str(sharp)]) == 2
        err = capsys.readouterr().err
        assert err.count("\n") == 1 and "--profile: Sneddon's depth delta(a) falls" in err, err
    law = sh.theory.sneddon.SneddonContact(sh.TabulatedIndenter.from_csv(cone), 1e7)
    assert np.all(np.diff(law.depth(r[1:])) > 0.0)  # a cone's depth rises: pi a / 2 for z = r
    assert main(["impact", "--profile", str(cone), "--velocity", "1.0", "--json"]) == 0
