"""Validity limits declared once (src/shtaerman/guards.py) and applied on every route: the
API, the command line and sweep cases (issue 28: the linear impact ran to x/a = 2.27 without a
word, and a sweep case on a 4 mm pad beyond its thickness reported no warning)."""

import contextlib
import json
import re

import numpy as np
import pytest

import shtaerman as sh
from shtaerman.cli import main
from shtaerman.fem.dynamic_contact import DynamicSettings, check_dynamic_impact
from shtaerman.guards import MAX_DEPTH_RATIO, ValidityWarning, depth_ratio, outside_validity
from shtaerman.study.schema import StudyError, load_study
from shtaerman.sweep.engine import execute_case
from shtaerman.sweep.kinds import dynamic_case, get_kind

BLUNT = sh.PowerLawIndenter(shape_coefficient=8.0, exponent=1.3)  # the striker
RUBBER = sh.Material(3e6, 0.49, 0.0)  # massless: the quasi-static FE impact, seconds
NUMERICS = dict(mesh_size=0.2, time_steps=50, estimate=False)


def test_the_depth_ratio_is_shtaermans():
    """x/a = kappa_n A a^(n-1) (docs/theory.md): at a = 1 mm for z = 5 r^1.5, kappa_1.5 =
    1.797210 (Gamma functions, DESIGN.md), so x/a = 5 * 1.797210 * 1e-3^0.5 = 0.2841660."""
    paper = sh.PowerLawIndenter(5.0, 1.5)
    depth = 1.797210 * 5.0 * 1e-3**1.5
    assert depth_ratio(paper, depth) == pytest.approx(5.0 * 1.797210 * 1e-3**0.5, rel=1e-6)


def test_each_limit_is_named_only_beyond_it():
    paper = sh.PowerLawIndenter(5.0, 1.5)
    # x/a = MAX_DEPTH_RATIO at depth d: x/a ~ x^(1 - 1/n) = x^(1/3) for n = 1.5
    at_limit = 1e-3 * (MAX_DEPTH_RATIO / depth_ratio(paper, 1e-3)) ** 3
    assert outside_validity(paper, 0.99 * at_limit, None, finite=False) == []
    (beyond,) = outside_validity(paper, 1.01 * at_limit, None, finite=False)
    assert beyond.startswith("depth:") and "far outside small strain" in beyond
    (finite,) = outside_validity(paper, 1.01 * at_limit, None, finite=True)
    assert "unverified" in finite
    assert outside_validity(paper, 1e-4, 1e-4, finite=False)[0].startswith("thickness:")
    assert outside_validity(paper, 1e-4, 1.0001e-4, finite=False) == []


def test_the_depth_sentence_names_whose_contact_radius():
    """x/a of another profile is over Sneddon's contact radius (:func:`depth_ratio`): a cone
    tabulated as z = 2 r has x = (pi/2) a cot(alpha) (Sneddon 1965), so x/a = pi at any depth.
    Old code: "(x/a, with Shtaerman's a)" for every profile."""
    radii = np.linspace(0.0, 0.01, 51)
    cone = sh.TabulatedIndenter(radii, 2.0 * radii)
    (sentence,) = outside_validity(cone, 5e-3, None, finite=False)
    assert "is 3.14 contact radii (x/a, with Sneddon's a)" in sentence
    paper = sh.PowerLawIndenter(5.0, 1.5)
    (sentence,) = outside_validity(paper, 0.05, None, finite=False)
    assert "(x/a, with Shtaerman's a)" in sentence


def test_the_linear_impact_far_outside_small_strain_warns():
    """The issue's case (0.12 kg at 1.5 m/s on 3 MPa) reaches x/a near 2.3."""
    with pytest.warns(ValidityWarning, match=r"contact radii .* far outside small strain") as said:
        result = sh.dynamic(BLUNT, RUBBER, mass=0.12, velocity=1.5, **NUMERICS)
    ratio = depth_ratio(BLUNT, result.x_max)
    assert ratio > 2.0 and f"is {ratio:.3g} contact radii" in str(said[0].message)


def test_the_command_line_prints_the_warning(capsys):
    argv = ["dynamic", "--exponent", "1.3", "--shape-coefficient", "8", "--E2", "3e6"]
    argv += ["--nu2", "0.49", "--mass", "0.12", "--velocity", "1.5", "--density2", "0"]
    argv += ["--mesh-size", "0.2", "--time-steps", "50", "--no-estimate", "--json"]
    main(argv)
    assert "far outside small strain" in capsys.readouterr().err


def test_a_sweep_case_through_its_pad_is_a_refused_row_in_the_files_words():
    """Beyond the pad's thickness: the API's refusal in the sweep file's keys (was a warning
    beside the numbers)."""
    params = get_kind("dynamic").defaults()
    params.update(mass=0.7, velocity=3.0, thickness=1.3e-4, density2=1100.0)
    params.update(mesh_size=0.2, time_steps=50, estimate=False)
    record = execute_case(dynamic_case, 0, params)
    assert record["status"] == "refused" and record["outputs"] == {}, record
    assert "through the layer's thickness 0.00013 m" in record["error"], record
    assert "lower velocity to at most " in record["error"], record


def test_a_striker_that_never_separates_is_a_one_line_failure(capsys):
    """--prony 0.999:1e-3 held the striker past the run's end: the text ended in a TypeError
    traceback (None restitution) and the JSON in nulls with a 'reflected energy nan'."""
    argv = ["dynamic", "--prony", "0.999:1e-3", "--no-estimate", "--mesh-size", "0.2"]
    assert main([*argv, "--time-steps", "50"]) == 1
    out, err = capsys.readouterr()
    assert out == "" and err.count("\n") == 1 and "had not separated" in err, err


@pytest.mark.parametrize(
    "argv", [["--mass", "1e-300"], ["--mass", "1e300"], ["--velocity", "1e50"]]
)
def test_a_linear_impact_beyond_any_fe_reach_is_refused_in_one_line(capsys, argv):
    """Mass 1e-300 or 1e300 ended in 'matrix is singular' tracebacks (the mesh's scales left
    the floating-point range); velocity 1e50 printed a validity warning before its refusal."""
    coarse = ["--no-estimate", "--mesh-size", "0.2", "--time-steps", "50"]
    assert main(["dynamic", *argv, *coarse]) == 2
    out, err = capsys.readouterr()
    assert out == "" and err.count("\n") == 1 and "error: --mass, --velocity:" in err, err


def test_a_dynamic_sweep_refuses_the_same_at_load():
    from shtaerman.sweep.kinds import get_kind

    kind = get_kind("dynamic")
    params = {**kind.defaults(), "mass": 1e-300}
    with pytest.raises(sh.InputError, match=r"^mass, velocity: 1e-300 kg at 3 m/s"):
        kind.check(params)


def test_a_reflection_share_of_almost_no_radiation_is_not_a_failure(capsys):
    """v0 = 1e-3 m/s radiates less than its own energy-balance error: its reflected share
    was nan (0/0) and failed the run (exit 1); at 3e-3 m/s a share of 1.1e-2 of a radiation
    of ~1e-3 (1e-5 of M v0^2/2) failed it too."""
    from shtaerman.study.dynamic.loader import dynamic_check_failures

    assert dynamic_check_failures(1e-3, float("nan"), radiated=1e-5) == []
    assert dynamic_check_failures(1e-3, 1.1e-2, radiated=1e-3) == []  # 1.1e-5 of M v0^2/2
    (failure,) = dynamic_check_failures(1e-3, 0.05, radiated=0.1)  # 5e-3 of M v0^2/2
    assert failure.startswith("reflected energy 5.0e-02 of the radiated")
    coarse = ["--no-estimate", "--mesh-size", "0.2", "--time-steps", "50"]
    assert main(["dynamic", "--velocity", "1e-3", *coarse]) == 0
    assert "reflected" not in capsys.readouterr().err


def test_a_finite_strain_study_beyond_the_reach_names_its_impact(tmp_path, capsys):
    """Issue 31, item 9 in a study file: 'depths: ... lower the deepest depth' for a study
    whose depths follow from its velocity."""
    study = tmp_path / "fast.toml"
    assert main(["init-study", str(study), "--kind", "finite-strain"]) == 0
    text = study.read_text()
    study.write_text(text.replace("velocity = 3.0", "velocity = 11.0"))
    capsys.readouterr()
    assert main(["verify", str(study), "--quick", "--out", str(tmp_path / "o")]) == 2
    err = capsys.readouterr().err
    # refused at load (its loader checks the finite-strain reach, session 57), in its keys
    said = "keys 'impact.mass', 'impact.velocity': 0.7 kg at 11 m/s drive the striker to about"
    assert said in err
    assert "lower the deepest depth" not in err


def test_a_dynamic_sweep_builds_each_case_as_a_problem_at_load():
    """A layer_rate on a massless body ran in a sweep; the command line refuses it."""
    from shtaerman.sweep.kinds import get_kind

    kind = get_kind("dynamic")
    params = {**kind.defaults(), "density2": 0.0, "layer_rate": 10.0}
    with pytest.raises(sh.InputError, match=r"^layer_rate: applies to a body with mass only"):
        kind.check(params)
    kind.check({**params, "layer_rate": None})  # the default: the geometry's own (none here)
    with pytest.raises(sh.InputError, match=r"^layer_rate: applies to a body with mass only"):
        kind.check({**params, "layer_rate": 0.0})  # given, as `--density2 0 --layer-rate 0`


@pytest.mark.parametrize("layer", ["thickness = 0.02", "thickness_ratio = 2.0"])
def test_a_dynamic_sweep_refuses_layer_rate_0_on_a_layer(tmp_path, layer):
    """layer_rate = 0 on a layer ran as 10 (the sweep's default was 0, so it could not tell 0
    given from no value); refused at load as `dynamic --thickness 0.02 --layer-rate 0` is."""
    from shtaerman.sweep import SweepError, load_sweep

    path = tmp_path / "s.toml"
    text = f'name = "s"\nkind = "dynamic"\n[parameters]\n{layer}\n'
    text += "[axes]\nlayer_rate = [0.0, 5.0]\n"
    path.write_text(text)
    with pytest.raises(SweepError) as caught:
        load_sweep(path)
    message = str(caught.value)
    assert "case 0 (layer_rate = 0.0)" in message and "\n" not in message
    assert "layer_rate: a layer always has its lateral absorber" in message
    assert "give a rate in (0, 1e4] or leave the default (10 on a layer)" in message
    path.write_text(text.replace("[0.0, 5.0]", "[5.0]"))
    assert load_sweep(path).cases()[0].params["layer_rate"] == 5.0
    path.write_text(text.replace("layer_rate = [0.0, 5.0]", "base = ['bonded']"))
    assert load_sweep(path).cases()[0].params["layer_rate"] is None  # the layer's own, 10


def test_a_sphere_past_its_equator_is_one_check_with_one_message(tmp_path):
    """The depth past a sphere's radius was refused by three checks in three wordings (the
    API's contact, the FE impact's guard, the study loader). Now one check
    (guards.check_equator) says it on every route: the input, the radius and the valid range
    (the deepest depth below the radius)."""
    from shtaerman.study.schema import StudyError, load_study
    from shtaerman.validation import InputError

    sphere, rubber = sh.SphereIndenter(1e-3), sh.Material(7.5e6, 0.5)
    said = (
        "depth 0.002 m, beyond the sphere's radius 0.001 m (its equator, past which the FE "
        "profile is no sphere): the deepest depth must be below the radius; give smaller "
        "depths or a {} above 0.002 m"
    )
    with pytest.raises(InputError) as api:
        sh.contact(sphere, rubber, depths=[5e-4, 2e-3], estimate=False)
    assert str(api.value) == f"depths: {said.format('SphereIndenter(radius=...)')}"
    study = tmp_path / "sphere.toml"
    study.write_text(
        "[indenter]\nsphere_radius = 1e-3\n[half_space]\nE2 = 7.5e6\nnu2 = 0.5\n"
        "[impact]\nmass = 0.7\nvelocity = 3.0\n[contact]\ndepths = [5e-4, 2e-3]\n"
    )
    with pytest.raises(StudyError) as loaded:
        load_study(study)
    said = said.format("[indenter] sphere_radius")  # the study file's key
    assert str(loaded.value) == f"{study}: key 'contact.depths': {said}"
    # the FE impact: 0.7 kg at 3 m/s drive a 5 mm sphere to Sneddon's x_c = 9.88 mm
    head = r"^SphereIndenter\(radius=\.\.\.\): "  # the API's field
    with pytest.raises(InputError, match=head + r".* about 0\.00988 m, beyond the "):
        massless = sh.Material(7.5e6, 0.5, 0.0)
        sh.dynamic(sh.SphereIndenter(5e-3), massless, mass=0.7, velocity=3.0, estimate=False)


@pytest.mark.parametrize("command", ["impact", "contact", "dynamic"])
@pytest.mark.parametrize("E2", ["1e-300", "1e101"])
def test_the_modulus_range_is_every_routes(capsys, command, E2):
    """adv53: 'impact --E2 1e-300' printed x_c = 1e113 m where contact and dynamic refused
    E2 outside [1e-3, 1e100] Pa: the vocabulary's range is every kind's, and the Python
    impact checks it too (problem.check_bodies)."""
    quick = [] if command == "impact" else ["--no-estimate"]  # refused before any run anyway
    assert main([command, "--E2", E2, *quick]) == 2
    out, err = capsys.readouterr()
    assert out == "" and err == f"shtaerman: error: --E2 must lie in [1e-3, 1e100] Pa, got '{E2}'\n"
    with pytest.raises(sh.InputError, match=r"^E2 must lie in \[1e-3, 1e100\] Pa") as refused:
        sh.impact(sh.PowerLawIndenter(5.0, 1.5), sh.Material(float(E2), 0.5), mass=0.7, velocity=3)
    assert refused.value.parameter == "E2"


@pytest.mark.parametrize("E1", ["1e-300", "1e101"])
def test_the_strikers_modulus_range_is_every_routes(capsys, tmp_path, E1):
    """guards55: 'impact --E1=1e-300' printed x_c = 4.7e117 m, a contact study's refusal
    blamed mass and velocity: E1 takes E2's range [1e-3, 1e100] Pa, or inf (rigid), on the
    command line, in the API (problem.check_bodies), a study file and a sweep."""
    said = f"E1 must lie in [1e-3, 1e100] Pa, or inf (rigid), got {E1!r}"
    assert main(["impact", f"--E1={E1}"]) == 2
    out, err = capsys.readouterr()
    assert out == "" and err == f"shtaerman: error: --{said}\n"
    striker, body = sh.Material(float(E1), 0.3), sh.Material(3e6, 0.49, 1000.0)
    for run in (sh.impact, sh.contact, sh.dynamic):  # refused before any work
        keywords = {} if run is sh.contact else dict(mass=0.7, velocity=3.0)
        with pytest.raises(sh.InputError, match=r"^E1 must lie in \[1e-3, 1e100\] Pa") as no:
            run(BLUNT, body, striker=striker, **keywords)
        assert no.value.parameter == "E1"

    study = tmp_path / "soft.toml"
    study.write_text(
        "[indenter]\nshape_coefficient = 5.0\nexponent = 1.5\n[striker]\n"
        f"E1 = {float(E1)!r}\nnu1 = 0.3\n[half_space]\nE2 = 7.5e6\nnu2 = 0.5\n"
        "[impact]\nmass = 0.7\nvelocity = 3.0\n"
    )
    with pytest.raises(StudyError) as loaded:  # was: 'mass, velocity: ... set the depths'
        load_study(study)
    said = said.replace(repr(E1), repr(float(E1)))  # TOML's float
    assert str(loaded.value) == f"{study}: key 'striker.E1': {said}"
    sweep = tmp_path / "soft-sweep.toml"
    sweep.write_text(f'name = "soft"\nkind = "impact"\n[axes]\nE1 = [{float(E1)!r}, 2e11]\n')
    assert main(["sweep", str(sweep), "--out", str(tmp_path / "out")]) == 2
    assert "axes.E1[0] must lie in [1e-3, 1e100] Pa, or inf (rigid)" in capsys.readouterr().err


def test_a_soft_body_under_a_slow_striker_runs(capsys):
    """guard56: 'dynamic --E2 1e-3 --velocity 1e-4' was refused (E2 / contact zone radius
    3.6e-4 Pa/m below 0.1, "the mixed u-p system loses digits"); the digits were lost only by
    the solver's accuracy check, in SI units. v0 / c_s = 0.18 here: the run balances its
    energy (the CLI exits 1 above 1e-2 of M v0^2/2; 1.2e-4 measured on the default mesh)."""
    coarse = ["--mesh-size", "0.1", "--time-steps", "60", "--no-estimate", "--json"]
    assert main(["dynamic", "--E2", "1e-3", "--velocity", "1e-4", *coarse]) == 0
    result = json.loads(capsys.readouterr().out)
    assert abs(result["dynamic"]["energy_balance_error"]) < 1e-2
    assert result["parameters"]["solver_backward_error"] < 1e-12  # 1.3e-14 measured


@pytest.mark.parametrize("geometry", [[], ["--thickness", "10"], ["--prony", "0.3:1e-3"]])
def test_a_striker_too_fast_for_the_waves_is_refused(capsys, geometry):
    """guard56: 'dynamic --E2 1e-3' (3 m/s, 5450 c_s) ran to an energy balance off by 5.85 of
    M v0^2/2: the linear FE impact breaks down once the first-order radiated fraction passes
    ~0.88 (guards.MAX_RADIATED_ESTIMATE 0.8). Refused before any mesh on the command line, in
    the API and in a dynamic sweep's load, naming a velocity that passes."""
    assert main(["dynamic", "--E2", "1e-3", "--no-estimate", *geometry]) == 2
    out, err = capsys.readouterr()
    head = "shtaerman: error: --velocity, --density2: 0.7 kg at 3 m/s is 5.45e+03 of the body's "
    assert out == "" and err.count("\n") == 1 and err.startswith(head), err
    passing = float(re.search(r"or velocity (\S+) m/s would pass", err).group(1))
    soft = sh.Material(1e-3, 0.5, 1100.0)
    striker, settings = sh.PowerLawIndenter(5.0, 1.5), DynamicSettings()
    for velocity in (passing, 1.02 * passing):  # the message's is 1 % below the limit's
        refused = velocity > passing
        with pytest.raises(sh.InputError) if refused else contextlib.nullcontext():
            check_dynamic_impact(striker, soft, 1100.0, 0.7, velocity, settings)
    # in Python's words: sh.Material(density=...) (words57), the CLI's --density2 above
    with pytest.raises(sh.InputError, match=r"^velocity, density: 0\.7 kg at 3 m/s") as no:
        sh.dynamic(sh.PowerLawIndenter(5.0, 1.5), soft, mass=0.7, velocity=3.0, estimate=False)
    assert no.value.parameter == "velocity"
    kind = get_kind("dynamic")
    with pytest.raises(sh.InputError, match=r"^velocity, density2: "):
        kind.check({**kind.defaults(), "E2": 1e-3})


@pytest.mark.filterwarnings("ignore::shtaerman.theory.impact.QuasiStaticValidityWarning")
def test_the_wave_speed_guard_spares_a_massless_body_and_takes_a_spheres_estimate():
    """A massless body (density2 0) has no waves: the quasi-static impact runs at any speed;
    a sphere's estimate is its quadrature's (guard56), and the velocity it names passes
    (user56: from q = 3/2 alone it named 0.0323 m/s, at lambda 0.809, and for a 12 g ball at
    60 m/s 1.82 m/s, at 0.837: the sphere's lambda is checked at the velocity named)."""
    settings = DynamicSettings()
    soft = sh.Material(1e-3, 0.5, 1100.0)
    check_dynamic_impact(sh.PowerLawIndenter(5.0, 1.5), soft, 0.0, 0.7, 3.0, settings)
    rubber, ball = sh.Material(7.5e6, 0.5, 1100.0), sh.SphereIndenter(0.05)
    pad = sh.Material(3e6, 0.49, 1000.0)  # 60 m/s: beyond the quasi-static theory's 5 m/s
    for body, density, mass, velocity in ((rubber, 1e6, 0.7, 3.0), (pad, 1000.0, 0.012, 60.0)):
        with pytest.raises(sh.InputError, match=r"^velocity, density2: ") as no:
            check_dynamic_impact(ball, body, density, mass, velocity, settings)  # 12.1, 6.47
        message = str(no.value)
        slower = float(re.search(r"or velocity (?:about )?(\S+) m/s would", message).group(1))
        check_dynamic_impact(ball, body, density, mass, slower, settings)  # checked: passes
        passing = float(re.search(r"density2 (\S+) kg/m\^3 or", message).group(1))
        check_dynamic_impact(ball, body, passing, mass, velocity, settings)  # sqrt(density)


def test_the_fe_impact_refuses_an_elastic_striker_it_would_ignore():
    """guards55: sh.dynamic(striker=Material(E1, nu1)) ran a rigid striker: x_max 8.269017e-3
    m at E1 = 1e-3 and at 1e6 Pa alike (mesh_size 0.1, 60 steps); the exact impact takes E1."""
    body = sh.Material(7.5e6, 0.5, 1100.0)
    steel = dict(mass=0.7, velocity=3.0, striker=sh.Material(2e11, 0.3))
    with pytest.raises(sh.InputError, match=r"^striker: the FE impact's striker is rigid") as no:
        sh.dynamic(sh.PowerLawIndenter(5.0, 1.5), body, **steel, estimate=False)
    assert no.value.parameter == "striker"
    with pytest.raises(sh.InputError, match=r"^striker: the FE impact's striker is rigid"):
        sh.effects(sh.Problem.impact(sh.PowerLawIndenter(5.0, 1.5), body, **steel))


def test_a_dynamic_study_refuses_its_impacts_checks_at_load(tmp_path):
    """guards55: a dynamic study ran its velocities in order and met the impact's own checks
    at each run's start (after the velocities before it had run), in the API's words: they
    are made at load, naming the file's keys. E2 = 0.1 Pa (c_s = 5.5e-3 m/s): 1e-4 m/s passes
    the wave speed guard, 3 m/s does not (guard56)."""
    study = tmp_path / "soft.toml"
    study.write_text(
        'kind = "dynamic"\n[indenter]\nshape_coefficient = 5.0\nexponent = 1.5\n'
        "[half_space]\nE2 = 0.1\nnu2 = 0.5\ndensity2 = 1100.0\n"
        "[impact]\nmass = 0.7\nvelocity = [1e-4, 3.0]\n"
    )
    with pytest.raises(StudyError) as loaded:
        load_study(study)
    keys = "keys 'impact.velocity', 'half_space.density2'"
    assert str(loaded.value).startswith(f"{study}: {keys}: 0.7 kg at 3 m/s is "), loaded.value


def test_the_exact_impacts_float_range_names_the_options_that_set_it(capsys):
    """adv53: the refusal opened with 'mass 1e-300 kg and velocity 1e-300 m/s give x_c = 0'
    and named no option: it heads the options whose values it names (session 59: the
    velocity and the mass that pass, as the FE impact's reach does; tests/test_left59.py),
    spelled as options on the command line."""
    assert main(["impact", "--mass", "1e-300", "--velocity", "1e-300"]) == 2
    out, err = capsys.readouterr()
    head = "shtaerman: error: --mass, --velocity: the exact impact of"
    assert out == "" and err.count("\n") == 1 and err.startswith(head), err
    assert "would give x_c = 0, outside the floating-point range" in err
    with pytest.raises(sh.InputError) as refused:
        sh.impact(sh.PowerLawIndenter(5.0, 1.5), sh.Material(7.5e6, 0.5), mass=1e-300,
                  velocity=1e-300)  # fmt: skip
    assert str(refused.value).startswith("mass, velocity: ")
    assert refused.value.parameter == "velocity"
