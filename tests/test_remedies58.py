"""Refusals whose remedy passes (session 58, issue 28 item 3/4): the dynamic impact's reach in
the contact curve's words, a contact study's layer naming the velocity that fits it, and the
reach's remedies within the waves' limit (user57)."""

import re
import warnings

import pytest

import shtaerman as sh
from shtaerman.api.fem_dynamic import check_dynamic
from shtaerman.cli import main
from shtaerman.validation import LimitError
from shtaerman.vocabulary import entry

SHALLOW = (
    "--mass, --velocity: 0.7 kg at 1e-300 m/s drive the striker to 3.74e-228 m only, depth / "
    "contact radius 6.7e-76, below the 1e-06 an FE impact resolves (strains of that order): "
    "the exact quasi-static impact (shtaerman impact) is the answer there; raise --velocity "
    "to at least about 4.95e-24 m/s with this striker, mass and body"
)


def _refusal(capsys, *argv):
    """The one line of a refused command (exit 2), without its 'shtaerman: error: '."""
    assert main([str(arg) for arg in argv]) == 2
    out, err = capsys.readouterr()
    last = err.strip().splitlines()[-1]  # a quasi-static validity warning may come first
    assert out == "" and "Traceback" not in err, err
    return last.removeprefix("shtaerman: error: ")


def _problem(mass, velocity, density=None, **physics):
    """The command line's default impact (its striker and body) of ``mass`` kg at
    ``velocity`` m/s."""
    indenter = sh.PowerLawIndenter(entry("shape_coefficient").default, entry("exponent").default)
    rho = entry("density2").default if density is None else density
    body = sh.Material(entry("E2").default, entry("nu2").default, rho)
    return sh.Problem.impact(indenter, body, mass=mass, velocity=velocity, **physics)


@pytest.mark.parametrize(
    "argv",
    [
        ("dynamic",),
        ("dynamic", "--density2", "0"),
        ("effects",),
    ],
)
def test_an_impact_far_too_slow_is_refused_in_the_contact_curves_words(capsys, argv):
    """`dynamic --velocity 1e-300` was refused for the exact impact's P_c = 0, naming
    --shape-coefficient, --E2, --mass, --velocity and no value, where `contact` names the
    velocity that passes: the FE impact now checks its reach first, x_c in logs, by the
    contact's check (guards.check_profile_reach). A rubber model's floor is higher:
    tests/test_floor60.py."""
    said = _refusal(capsys, *argv, "--velocity", "1e-300")
    assert said == SHALLOW, said
    assert _refusal(capsys, "contact", "--velocity", "1e-300") == SHALLOW
    density = 0.0 if "0" in argv else None
    check_dynamic(_problem(0.7, 4.95e-24, density))  # the remedy passes


def test_the_exact_impact_alone_still_refuses_a_force_below_the_floats(capsys):
    """`impact --velocity 1e-300` has x_c = 3.7e-228 m (in logs) but P_c = beta x_c^(5/3)
    below the smallest float: it cannot print its P_c, and keeps its refusal (naming the
    velocity and mass that pass since session 59: tests/test_left59.py)."""
    said = _refusal(capsys, "impact", "--velocity", "1e-300")
    assert said.startswith("--mass, --velocity: "), said
    assert "would give P_c = 0, outside the floating-point range" in said, said


def test_a_reach_remedy_the_waves_refuse_is_not_named(capsys):
    """1e-50 kg at 3 m/s was refused as too shallow, naming 41.4 m/s or 1.9e-48 kg, each
    refused in turn by the wave-speed limit (user57): the reach's remedies are checked
    against it, and the heavier mass that passes both is named."""
    said = _refusal(capsys, "dynamic", "--mass", "1e-50", "--velocity", "3")
    assert said == (
        "--mass, --velocity: 1e-50 kg at 3 m/s drive the striker to 1.73e-21 m only, depth / "
        "contact radius 5.2e-07, below the 1e-06 an FE impact resolves (strains of that "
        "order): the exact quasi-static impact (shtaerman impact) is the answer there; raise "
        "--mass to at least about 4.82e-06 kg with this striker, velocity and body (a faster "
        "striker radiates above 0.7 of its energy as waves, where the FE impact with inertia "
        "breaks down)"
    ), said
    check_dynamic(_problem(4.82e-06, 3.0))  # the remedy passes both limits
    for mass, velocity in ((1e-50, 41.4), (1.9e-48, 3.0)):  # what it named before
        with pytest.raises(LimitError, match="shear wave speed"):
            check_dynamic(_problem(mass, velocity))


def test_a_reach_remedy_far_too_fast_is_the_waves_velocity(capsys):
    """0.7 kg at 1e100 m/s (x/a 6.7e24) named 4.94e8 m/s or 1.7e-183 kg, the impacts of x/a
    100, both refused by the waves' limit: it names the velocity that passes both, and no
    lighter mass (a lighter striker radiates more)."""
    said = _refusal(capsys, "dynamic", "--velocity", "1e100")
    assert said.endswith(
        "beyond the 100 up to which an FE impact is run: lower --velocity to at most about "
        "21.8 m/s with this striker, mass and body"
    ), said
    check_dynamic(_problem(0.7, 21.8))
    with pytest.raises(LimitError, match="shear wave speed"):
        check_dynamic(_problem(0.7, 27.0))  # the bound is the waves' (named 1 % below it)


@pytest.mark.parametrize(
    ("thickness", "ending", "velocity"),
    [
        ("1e-9", "at most 4.41e-11", 4.41e-11),
        ("100", "at least 44.2", 44.2),
    ],
)
def test_a_contact_studys_layer_names_the_velocity_that_fits_it(
    tmp_path, thickness, ending, velocity
):
    """A contact study's layer outside the thickness range was refused naming no velocity,
    where `contact --thickness` names one (fem.mesh.fitting_velocity): the study checks it by
    the same call (study.contact.layer.check_thickness), at both its meshes."""
    from shtaerman.study.schema import StudyError, load_study

    path = tmp_path / "c.toml"
    assert main(["init-study", "--kind", "contact", str(path)]) == 0
    text = re.sub(r"(?m)^# \[layer\] .*$", f"[layer]\nthickness = {thickness}", path.read_text())
    path.write_text(text)
    with pytest.raises(StudyError) as caught:
        load_study(path)
    said = str(caught.value)
    assert said.startswith(f"{path}: key 'layer.thickness': must lie in [0.000261, 26] m at")
    assert said.endswith(f"; or [impact] velocity {ending} m/s on this thickness"), said
    path.write_text(re.sub(r"(?m)^velocity = .*$", f"velocity = {velocity}", text))
    with warnings.catch_warnings():  # 44.2 m/s: beyond the quasi-static theory's 5 m/s
        warnings.simplefilter("ignore")
        load_study(path)  # the remedy loads (`verify --quick` PASSes it: the report)


def test_a_dynamic_study_far_too_slow_names_the_velocity_that_passes(tmp_path):
    """A dynamic study at 1e-300 m/s was refused for its v0^2 = 0 ("give it a value of a
    physical size"): its loader checks the reach first, as the run does."""
    from shtaerman.study.schema import StudyError, load_study

    path = tmp_path / "d.toml"
    assert main(["init-study", "--kind", "dynamic", str(path)]) == 0
    text = path.read_text()
    path.write_text(re.sub(r"(?m)^velocity = .*$", "velocity = 1e-300", text))
    with pytest.raises(StudyError) as caught:
        load_study(path)
    assert str(caught.value) == (
        f"{path}: keys 'impact.mass', 'impact.velocity': 0.7 kg at 1e-300 m/s drive the "
        "striker to 3.74e-228 m only, depth / contact radius 6.7e-76, below the 1e-06 an FE "
        "impact resolves (strains of that order): the exact quasi-static impact (shtaerman "
        "impact) is the answer there; raise [impact] velocity to at least about 4.95e-24 m/s "
        "with this striker, mass and body"
    )
    path.write_text(re.sub(r"(?m)^velocity = .*$", "velocity = 4.95e-24", text))
    load_study(path)  # the remedy loads (`verify --quick` runs it: the report)


def test_verify_prints_an_undefined_check_value_as_nan(tmp_path):
    """A dynamic study at 4.95e-24 m/s (the reach's remedy) radiates no energy: its reflected
    fraction is 0/0, null in results.json, and `verify` printed a TypeError traceback."""
    from shtaerman.cli.verify import verify_text

    checks = [
        {"name": "energy balance", "value": 1e-3, "tolerance": 1e-2, "passed": True},
        {"name": "reflected energy", "value": None, "tolerance": 1e-2, "passed": False},
    ]
    results = {"studies": {"d": {"checks": checks, "passed": False}}}
    lines = verify_text(results, tmp_path).splitlines()
    assert lines[1].split() == ["d", "FAIL", "reflected", "energy:", "nan", "/", "1e-02"]
    assert lines[2].split() == [
        "failed",
        "reflected",
        "energy:",
        "nan",
        ">",
        "tolerance",
        "1.0e-02",
    ]


def test_a_reach_remedy_no_wave_passes_is_named_on_the_massless_body(capsys):
    """1e-300 kg at 1e100 m/s: every velocity or mass the reach names radiates above the
    waves' limit at this density; both are named on the massless body, where each runs."""
    said = _refusal(capsys, "dynamic", "--mass", "1e-300", "--velocity", "1e100")
    assert said.endswith(
        "raise --velocity to at least about 4.14e+126 m/s with this striker, mass and body, "
        "or --mass to at least about 1.71e-247 kg, on the massless body, --density2 0 (at "
        "this density2 either radiates above 0.7 of its energy as waves, where the FE impact "
        "with inertia breaks down)"
    ), said
    check_dynamic(_problem(1e-300, 4.14e126, 0.0))
    check_dynamic(_problem(1.71e-247, 1e100, 0.0))
    with pytest.raises(LimitError, match="shear wave speed"):
        check_dynamic(_problem(1.71e-247, 1e100))  # at the body's density: the waves refuse
