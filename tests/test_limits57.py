"""Session 57's limits, finished: each refusal or failure names a value that passes, checked
here by running it (tests/test_adversary57.py's style)."""

from __future__ import annotations

import re
import warnings

import pytest

import shtaerman as sh
from shtaerman.fem.contact.finite import SqueezedTipError
from shtaerman.fem.finite_dynamic import FiniteImpactSettings
from shtaerman.fem.impact import run_impact
from shtaerman.fem.mesh import Geometry, MeshSettings

SHARP = sh.PowerLawIndenter(8.0, 1.3)
RUBBER = sh.Material(3e6, 0.49)
PAD = Geometry(thickness=0.012, base="bonded")
COARSE = MeshSettings(size=0.4, domain=1e2, growth=0.8, axis_size=1e-4, axis_growth=0.4)
"""tests/test_padinertia57.py's coarse field: the squeezed tip at 25 steps in about 2 CPU s."""


def test_the_squeezed_tip_names_the_reach_velocity_which_runs():
    """Main said 'a slower velocity=...' with no value; the reach limit's (x_c at x/a 1.2,
    x/a ~ x^(1 - 1/n), x_c ~ v^(2/(q + 1)): 1.5 * (1.2 / 2.27)^(1.385 / 0.231) = 0.0323 m/s)
    is named, and runs on the same mesh and steps."""
    settings = FiniteImpactSettings(steps=25, mesh=COARSE)
    with pytest.raises(SqueezedTipError) as failed:
        run_impact(SHARP, RUBBER, 1000.0, 0.12, 1.5, settings, geometry=PAD)
    named = str(failed.value).split("velocity=... (at most about ")[1]
    velocity = float(named.split(" m/s")[0])
    assert velocity == 0.0323  # three digits, rounded down
    with warnings.catch_warnings(record=True):
        warnings.simplefilter("always")
        run = run_impact(SHARP, RUBBER, 1000.0, 0.12, velocity, settings, geometry=PAD)
    assert run.restitution > 0  # it ran to separation


def test_a_sphere_impact_far_below_the_panels_round_off_computes():
    """``impact --sphere-radius 1 --mass 1e-200 --velocity 1e-3`` (M v0^2 / 2 = 5e-207 J)
    ended in brentq's "f(a) and f(b) must have different signs": the first guess's panels,
    halved 99 times towards the tip, keep W = 6.5e-166 J of round-off at a = 0. Its a_c =
    2.5e-43 m is Hertz's: the power law z = r^2 / (2 R) within 1e-9 (the sphere departs from
    its parabola by (a/R)^2 ~ 1e-86; the quadrature's round-off on the tip's panels measured
    3e-12 at 1e-250 kg)."""
    rubber = sh.Material(7.5e6, 0.5)
    with warnings.catch_warnings():  # the quasi-static validity warnings of a tiny impact
        warnings.simplefilter("ignore")
        ball = sh.impact(sh.SphereIndenter(1.0), rubber, mass=1e-200, velocity=1e-3)
        parabola = sh.impact(sh.PowerLawIndenter(0.5, 2.0), rubber, mass=1e-200, velocity=1e-3)
    for key in ("x_c", "P_c", "t_y"):
        assert getattr(ball, key) == pytest.approx(getattr(parabola, key), rel=1e-9), key


COARSE_RUN = ("--mesh-size", "0.2", "--time-steps", "50", "--no-estimate")


def _said(capsys, *args):
    from shtaerman.cli import main

    code = main(list(args))
    return code, capsys.readouterr().err


def test_the_wave_speed_velocity_the_reach_refuses_is_said_and_the_mass_named(capsys):
    """``dynamic --mass 1e-40 --velocity 3`` was told velocity 5.96e-06 m/s, which the reach
    then refused (x/a below 1e-6, 'raise velocity to at least 0.000414 m/s'): the refusal says
    so and names the heavier mass that passes (lambda ~ M^(-1/8) for q = 5/3), which runs, as
    the density does."""
    dynamic = ("dynamic", "--mass", "1e-40", "--velocity", "3", *COARSE_RUN)
    code, said = _said(capsys, *dynamic)
    assert code == 2 and said.count("\n") == 1, said
    assert "shallower than an FE impact resolves" in said, said
    assert said.startswith("shtaerman: error: --mass, --density2: "), said
    found = re.search(r"density2 (\S+) kg/m\^3 or mass (\S+) kg at 3 m/s would pass", said)
    assert found, said
    density, mass = found.groups()
    slower = re.search(r"velocity (\S+) m/s, which would pass the waves", said).group(1)
    assert _said(capsys, *dynamic[:4], slower, *COARSE_RUN)[0] == 2  # the reach's refusal
    # each named value runs; exit 1, not 2: at lambda ~ 0.8 on mesh 0.2 the reflected energy
    # is 1.3e-2 of the radiated, above its check's 0.01, as for main's named velocity (0.7 kg
    # at 26.1 m/s, the paper's 300 m/s refused)
    assert _said(capsys, "dynamic", "--mass", mass, "--velocity", "3", *COARSE_RUN)[0] != 2
    assert _said(capsys, *dynamic, "--density2", density)[0] != 2


def test_a_table_s_end_past_an_overshoot_names_the_velocity_and_mass_that_pass():
    """A contact study sizes its depths to 1.01 x_c (DEPTH_OVERSHOOT): an impact whose x_c is
    0.995 of a table's end was refused with 'extend the table' alone; it names the velocity
    and the mass that bring 1.01 x_c within the table, each passing, 1 % faster refused (the
    velocity is rounded down to three digits, 0.137 against 0.1381)."""
    import numpy as np

    from shtaerman.guards import check_profile_reach
    from shtaerman.theory.profile_impact import work_to
    from shtaerman.theory.sneddon import contact_law
    from shtaerman.validation import LimitError

    radii = np.linspace(0.0, 2e-3, 21)
    table, modulus = sh.TabulatedIndenter(radii, 100.0 * radii**2), 1e7
    law = contact_law(table, modulus)
    end = float(law.depth(law.max_contact_radius))
    fast = (2.0 * work_to(law, float(law.contact_radius(0.995 * end))) / 0.7) ** 0.5
    with pytest.raises(LimitError) as caught:
        check_profile_reach(table, modulus, None, (0.7, fast), overshoot=1.01)
    said = str(caught.value)
    found = re.search(
        r"extend the table or lower velocity=\.\.\. to at most (\S+) m/s or mass=\.\.\. to at "
        r"most (\S+) kg",
        said,
    )
    assert found and said.startswith("profile: "), said
    velocity, mass = float(found[1]), float(found[2])
    check_profile_reach(table, modulus, None, (0.7, velocity), overshoot=1.01)
    check_profile_reach(table, modulus, None, (mass, fast), overshoot=1.01)
    with pytest.raises(LimitError, match="beyond the table"):
        check_profile_reach(table, modulus, None, (0.7, 1.01 * velocity), overshoot=1.01)


def test_a_layer_s_thickness_range_names_the_velocity_that_fits_it(capsys):
    """``dynamic --thickness 0.012 --velocity 1e-6``: the thickness range ([7.25e-08,
    0.00724] m for this impact) was the only remedy; the velocity whose contact (refined
    radius ~ v^(2/(2n + 1))) takes the 12 mm layer is named, and runs (coarse); 1 % slower is
    refused (rounded up to three digits)."""
    layer = ("dynamic", "--thickness", "0.012", *COARSE_RUN)
    code, said = _said(capsys, *layer, "--velocity", "1e-6")
    assert code == 2 and said.startswith("shtaerman: error: --thickness: must lie in "), said
    velocity = float(re.search(r"or --velocity at least (\S+) m/s on this thickness", said)[1])
    assert _said(capsys, *layer, "--velocity", str(velocity))[0] == 0
    assert _said(capsys, *layer, "--velocity", f"{0.99 * velocity:.4g}")[0] == 2


@pytest.mark.parametrize(("velocity", "side"), [("1e-9", "at least"), ("1.0", "at most")])
def test_a_contact_curve_s_layer_outside_the_range_names_the_velocity_that_fits(
    capsys, velocity, side
):
    """``contact --thickness 0.012 --velocity 1e-9`` (and a 10 nm layer at 1 m/s) was refused
    by the thickness range 'at these depths' alone; the velocity whose default depths take the
    layer is named too, and runs (coarse); 1 % beyond it is refused (rounded inward)."""
    thickness = "0.012" if side == "at least" else "1e-8"
    layer = ("contact", "--thickness", thickness, "--mesh-size", "0.2", "--no-estimate")
    code, said = _said(capsys, *layer, "--velocity", velocity)
    assert code == 2 and said.startswith("shtaerman: error: --thickness: must lie in "), said
    assert "at these depths" in said, said
    found = re.search(rf"or --velocity {side} (\S+) m/s on this thickness", said)
    assert found, said
    fits = float(found[1])
    assert _said(capsys, *layer, "--velocity", str(fits))[0] == 0
    beyond = 0.99 * fits if side == "at least" else 1.01 * fits
    assert _said(capsys, *layer, "--velocity", f"{beyond:.4g}")[0] == 2


def test_a_cone_gets_no_reach_remedy_and_no_crash():
    """A cone's x/a is the same at every depth, so no mass or velocity moves it: the reach
    check leaves it to the FE's own n > 1 refusal (validate_fem_inputs). The finite-strain
    study loader's reach (finite=True, 1.2) divided by 1 - 1/n = 0 on z = 5 r (CI, session
    57: tests/test_study_finite.py's exponent = 1.0 case, ZeroDivisionError)."""
    from shtaerman.guards import check_reach, reach_velocity

    cone = sh.PowerLawIndenter(5.0, 1.0)  # x/a = 7.85 at every depth, beyond 1.2
    for finite in (True, False):
        assert check_reach(cone, 0.0215, (0.7, 3.0), finite) is None
    assert reach_velocity(cone, 0.0215, 3.0) == ""


def test_a_sphere_whose_equator_takes_no_representable_work_is_refused_in_one_line():
    """user57: `impact --sphere-radius 1e-300 --mass 0.7 --velocity 3` ended in a traceback
    (math domain error): the work to the equator underflows to 0, and its log was taken for
    the remedy. Refused now naming the sphere, with the inputs to lower."""
    head = r"^SphereIndenter\(radius=\.\.\.\): "  # the API's field
    with pytest.raises(sh.InputError, match=head + r".*equator.*lower mass=\.\.\. or"):
        sh.impact(sh.SphereIndenter(1e-300), sh.Material(4e6, 0.49), mass=0.7, velocity=3.0)
