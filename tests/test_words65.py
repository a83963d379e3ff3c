"""User-facing words found by session 64's new-user trials (task words65): each message speaks
the words of the route it is read on, names what it is about, and says it once."""

import pytest

from shtaerman.cli.dynamic import ladder_rows
from shtaerman.fitting.data import measurement
from shtaerman.problem import worded
from shtaerman.theory.profiles import TabulatedIndenter
from shtaerman.theory.prony_sources import prony_from_csv
from shtaerman.validation import InputError


def test_the_cli_prints_a_retry_in_options_not_keywords():
    """The text on stdout printed 'time_steps=...' where stderr said '--time-steps'."""
    failure = "the contact did not converge; take more time steps (time_steps=...)"
    report = {
        "retried": f"refine 0.707: 113 steps failed ({failure}); passed with 226 steps",
        "mesh_ladder": [{"dofs": 10, "steps": 80}, {"dofs": None, "steps": 113}],
        "estimate_missing": f"a ladder level failed twice, refine 0.707: {failure}",
    }
    said = "the contact did not converge; take more time steps (--time-steps)"
    assert ladder_rows(report) == [
        f"  retried: refine 0.707: 113 steps failed ({said}); passed with 226 steps",
        f"  no error estimate (ladder 10 dofs/80 steps, failed): a ladder level failed twice, "
        f"refine 0.707: {said}",
    ]


def test_a_prony_files_sum_of_g_names_the_file_and_its_lines(tmp_path):
    """Every other fault of a Prony file named file, line and column; this one said only
    'prony weights must sum to less than 1'. 0.6 + 0.5 is 1.1 exactly in binary (fsum)."""
    path = tmp_path / "f.csv"
    path.write_text("tau [s],g [1]\n# two terms\n1e-3,0.6\n1e-2,0.5\n")
    with pytest.raises(InputError) as raised:
        prony_from_csv(path)
    assert str(raised.value) == (
        "prony: f.csv: column g must sum to less than 1 (relaxed modulus > 0), got "
        "sum g_i = 1.1 over lines 3 to 4"
    )
    assert raised.value.parameter == "prony"


def _message(call, *args) -> str:
    with pytest.raises(InputError) as raised:
        call(*args)
    return str(raised.value)


def test_every_csv_reader_names_a_bad_value_by_its_file_line(tmp_path):
    """Prony and profile files said 'row N', the fit data 'row N' and the CSV layer 'line N'
    for the same thing; each is the file's line, 1-based, comments counted (here line 4, the
    second data row under a comment)."""
    prony, profile, data = (tmp_path / name for name in ("p.csv", "z.csv", "d.csv"))
    prony.write_text("tau,g\n# terms\n1e-3,0.3\n1e-2,x\n")
    profile.write_text("r,z\n# the tip\n0,0\n1e-3,x\n2e-3,2e-3\n")
    data.write_text("depth [m],force [N]\n# run 1\n1e-3,1\n2e-3,x\n")
    assert "p.csv: line 4, column g must be a number" in _message(prony_from_csv, prony)
    assert f"'{profile}' line 4, column z:" in _message(TabulatedIndenter.from_csv, profile)
    assert f"{data}: line 4: column 'force'" in _message(measurement, "indentation", data)


def test_the_apis_profile_arrays_are_named_by_index():
    """Without a file the first point of an API table was called 'row 2'."""
    said = _message(TabulatedIndenter, [1e-3, 2e-3, 3e-3], [0.0, 1e-3, 2e-3])
    assert said.startswith("profile: index 0 (the first) must be the tip r = 0, z = 0")


def test_the_massless_relaxing_pads_refusal_is_short_and_keeps_its_remedies(capsys):
    """The longest pad refusal found (massless, Prony) ran to 846 characters: the bisection
    that finds its remedies and the pad's bound were explained at length. Now the fault, the
    limit and every remedy (velocity, mass, inertia with a frictionless interface) remain;
    the values are those of tests/test_relaxed_reach.py (relax64: 0.0278 m/s, 5.44e-5 kg)."""
    from shtaerman.cli import main

    argv = "dynamic --exponent 1.3 --shape-coefficient 8 --E2 3e6 --nu2 0.49 --mass 0.12"
    argv += " --velocity 1.5 --thickness 0.012 --density2 0 --prony 0.3:1e-3 --model neo-hookean"
    assert main(argv.split()) == 2
    assert capsys.readouterr().err == (
        "shtaerman: error: --mass, --velocity: 0.12 kg at 1.5 m/s drive the striker to about "
        "0.00621 m, depth / contact radius 2.32, beyond the 1.2 up to which the finite-strain "
        "contact converges: lower --velocity to at most about 0.0278 m/s with this striker, "
        "mass and body, or --mass to at most about 5.44e-05 kg; with a Prony series the depth "
        "is the relaxing body's quasi-static one, which the run checks; on a pad, which stops "
        "the striker a little sooner than this depth, a massless body (--density2 0) cannot "
        "pass it; with inertia (--density2) --interface frictionless runs beyond it with a "
        "warning\n"
    )


def test_a_sweep_key_of_another_kind_names_that_kind_not_a_lookalike(tmp_path):
    """'estimate' in a finite-strain sweep suggested 'gent_limit' (difflib's ratio 0.56 above
    its cutoff 0.5); it is the dynamic kind's key. A misspelling keeps its suggestion."""
    from shtaerman.sweep.spec import SweepError, load_sweep

    path = tmp_path / "s.toml"
    text = 'name = "s"\nkind = "finite-strain"\n[parameters]\n{}\n[axes]\nmass = [0.5, 0.7]\n'
    path.write_text(text.format("estimate = false"))
    with pytest.raises(SweepError) as raised:
        load_sweep(path)
    assert "unknown parameter 'estimate' for kind 'finite-strain' (a parameter of kinds " in str(
        raised.value
    )
    assert "'dynamic', 'effects'). Pick one of ['E2'," in str(raised.value)
    path.write_text(text.format("mas = 0.5"))
    with pytest.raises(SweepError, match=r"'mas' for kind 'finite-strain' \(did you mean 'mass'"):
        load_sweep(path)


def test_the_api_names_the_strikers_field_and_its_own_functions():
    """sh.dynamic said 'lower shape_coefficient=...' (no keyword of sh.dynamic: a field of
    PowerLawIndenter) and 'shtaerman impact' (a command) to a Python caller."""
    import shtaerman as sh

    body = sh.Material(3e6, 0.49, density=0.0)
    case = dict(model="neo-hookean", estimate=False)
    with pytest.raises(sh.InputError) as blunt:
        sh.dynamic(sh.PowerLawIndenter(100.0, 1.1), body, mass=0.7, velocity=3.0, **case)
    assert str(blunt.value).endswith(
        "lower PowerLawIndenter(shape_coefficient=...) to at most about 1.15 m^(1-n) with this "
        "mass, velocity and body"
    )
    with pytest.raises(sh.InputError) as shallow:
        sh.dynamic(sh.PowerLawIndenter(5.0, 1.5), body, mass=1e-50, velocity=3.0, **case)
    assert (
        "the linear model is exact there (sh.contact or sh.dynamic without model=...), and so "
        "is the exact quasi-static impact (sh.impact); raise mass=..." in str(shallow.value)
    )


def test_the_command_line_keeps_its_commands_and_options():
    said = "(shtaerman impact) takes any; lower shape_coefficient=... or sphere_radius=0.01"
    assert worded(said, "cli") == (
        "(shtaerman impact) takes any; lower --shape-coefficient or --sphere-radius 0.01"
    )
    assert worded(said, "python") == (
        "(sh.impact) takes any; lower PowerLawIndenter(shape_coefficient=...) or "
        "SphereIndenter(radius=0.01)"
    )
