"""A sphere's equator refusal with inertia named remedies the waves then refused (user64b):
0.12 kg at 10 m/s drive a 10 mm sphere on 3 MPa rubber (nu2 0.49, 1000 kg/m^3) to Sneddon's
x_c = 16 mm, and the refusal named 5.7 m/s or 0.039 kg or a larger sphere. 0.039 kg at 10 m/s
radiates an estimated 0.602 of its energy as waves, above a sphere's limit 0.45: a lighter
striker radiates more (lambda ~ M^((q - 2)/(q + 1)), q = 3/2), and a larger sphere radiates as
a lighter striker on this one (lambda and the quasi-static impact are self-similar in R). Now
each remedy the refusal names passes the waves too, in the same words on every route."""

import math
import re

import pytest

import shtaerman as sh
from shtaerman.cli import main
from shtaerman.fem.dynamic_contact import DynamicSettings, RadiatedFraction, check_dynamic_impact
from shtaerman.study.schema import StudyError, load_study
from shtaerman.sweep.spec import SweepError, parse_sweep
from shtaerman.validation import InputError

BALL, RUBBER = sh.SphereIndenter(0.01), sh.Material(3e6, 0.49, 1000.0)
WAVES = re.compile(r"velocity.*radiates an estimated (\S+) of its energy as waves")
pytestmark = pytest.mark.filterwarnings(  # 10 m/s: beyond the theory's 5 m/s, as the user's
    "ignore::shtaerman.theory.impact.QuasiStaticValidityWarning"
)
LEFT = (
    " (a lighter striker or a larger sphere radiates above 0.45 of its energy as waves on "
    "this {}, where the FE impact with inertia breaks down)"
)  # the API's density, density2 elsewhere


def _refusal(density: float, **keywords) -> str:
    body = sh.Material(3e6, 0.49, density)
    with pytest.raises(InputError) as caught:
        sh.dynamic(BALL, body, mass=0.12, velocity=10.0, estimate=False, **keywords)
    assert caught.value.parameter == "sphere_radius"
    return str(caught.value)


def test_the_equator_names_no_mass_nor_larger_sphere_the_waves_refuse():
    said = _refusal(1000.0)
    left = LEFT.format("density")
    assert said.endswith("below the radius; lower velocity=... to at most 5.7 m/s" + left), said
    assert _refusal(1000.0, model="neo-hookean") == said  # the finite-strain route's words
    check_dynamic_impact(BALL, RUBBER, 1000.0, 0.12, 5.7, DynamicSettings())  # passes
    with pytest.raises(InputError) as waves:  # the remedy named before: refused by the waves
        check_dynamic_impact(BALL, RUBBER, 1000.0, 0.039, 10.0, DynamicSettings())
    assert float(WAVES.search(str(waves.value))[1]) == 0.602  # user64b's figure
    # a larger sphere R' radiates as M (R / R')^3 on R: exact, the estimate is self-similar
    big, fraction = (
        RadiatedFraction(sh.SphereIndenter(0.02), RUBBER, 1000.0),
        (RadiatedFraction(BALL, RUBBER, 1000.0)),
    )
    assert math.isclose(big(0.12, 10.0), fraction(0.12 / 8.0, 10.0), rel_tol=1e-12)


def test_the_velocity_is_lowered_where_the_waves_ask_it_and_light_bodies_keep_all():
    """At 3000 kg/m^3 the equator's 5.7 m/s radiates 0.594: the waves' own remedy for it,
    3.22 m/s, is named (and passes). At 100 kg/m^3 every remedy passes: the words are the
    massless body's, as before."""
    said = _refusal(3000.0)
    assert said.endswith("lower velocity=... to at most 3.22 m/s" + LEFT.format("density")), said
    check_dynamic_impact(BALL, RUBBER, 3000.0, 0.12, 3.22, DynamicSettings())
    # R' = R (0.12 / 0.039...)^(1/3) = 14.54 mm, rounded up (theory.profile_impact.larger_sphere)
    everything = (
        "lower velocity=... to at most 5.7 m/s or mass=... to at most 0.039 kg or raise "
        "SphereIndenter(radius=...) to at least 0.0146 m"
    )
    assert _refusal(100.0).endswith(everything)
    assert _refusal(0.0, model="neo-hookean").endswith(everything)
    check_dynamic_impact(sh.SphereIndenter(0.0146), sh.Material(3e6, 0.49), 100.0, 0.12, 10.0,
                         DynamicSettings())  # fmt: skip


def test_the_study_file_sweep_row_and_command_line_say_it_too(tmp_path, capsys):
    said = "lower {} to at most 5.7 m/s" + LEFT.format("density2")
    study = tmp_path / "ball.toml"
    study.write_text(
        'kind = "dynamic"\n[indenter]\nsphere_radius = 0.01\n'
        "[half_space]\nE2 = 3e6\nnu2 = 0.49\ndensity2 = 1000.0\n"
        "[impact]\nmass = 0.12\nvelocity = [10.0]\n"
    )
    with pytest.raises(StudyError) as loaded:
        load_study(study)
    assert str(loaded.value).endswith(said.format("[impact] velocity")), loaded.value
    sweep = (
        'name = "ball"\nkind = "dynamic"\n[parameters]\nsphere_radius = 0.01\nE2 = 3e6\n'
        "nu2 = 0.49\ndensity2 = 1000.0\nmass = 0.12\n[axes]\nvelocity = [10.0]\n"
    )
    with pytest.raises(SweepError) as row:
        parse_sweep(sweep)
    assert str(row.value).endswith(said.format("velocity")), row.value
    flags = "--sphere-radius 0.01 --E2 3e6 --nu2 0.49 --density2 1000 --mass 0.12 --velocity 10"
    assert main(["dynamic", *flags.split(), "--no-estimate"]) == 2
    assert capsys.readouterr().err.endswith(said.format("--velocity") + "\n")
