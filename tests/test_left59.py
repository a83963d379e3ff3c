"""Session 59's leftovers of issue 28, item 4 (the refusals that let a failing run through, or
name a remedy that fails): the wave limit's remedies that run, the same limit on the
finite-strain impact with inertia on every route, a resume of an empty folder refused, the exact
impact beyond the floats naming the velocity and mass that pass, a depth ratio printed apart
from its limit."""

from __future__ import annotations

import contextlib
import io
import json
import re
import warnings

import pytest

import shtaerman as sh
from shtaerman.cli import main


def _error(capsys, *argv) -> str:
    assert main(list(map(str, argv))) == 2
    out, err = capsys.readouterr()
    assert out == "" and err.count("\n") == 1 and "Traceback" not in err, err
    return err


# --- the wave-speed limit names remedies that pass (guards.MAX_RADIATED_ESTIMATE) --------------


def test_the_wave_limits_remedy_runs_and_passes_its_checks(capsys):
    """`dynamic --velocity 300` named --velocity 26.1 (lambda 0.795 < 0.8), whose run was off
    by 2.9 of M v0^2/2 (exit 1): the FE's contact chatters from lambda 0.764 on the default
    mesh (benchmarks/FEM_NOTES.md). The velocity it names now runs on that mesh (the level its
    estimate reports) with both checks passed."""
    said = _error(capsys, "dynamic", "--velocity", "300")
    velocity = re.search(r" or velocity (\S+) m/s would pass", said)[1]
    with contextlib.redirect_stderr(io.StringIO()):  # beyond the theory's 5 m/s: it warns
        code = main(["dynamic", "--velocity", velocity, "--no-estimate", "--json"])
    result = json.loads(capsys.readouterr().out)["dynamic"]
    assert code == 0, result  # exit 1: a check failed
    # passing runs balance to 5e-4 here, failing ones are off by 2 to 4: 1e-2 is the check's
    assert result["energy_balance_error"] < 1e-2
    assert result["reflected_energy_fraction"] < 1e-2  # 0.0068 observed; the check's 1e-2


@pytest.mark.parametrize(
    ("argv", "remedy"),
    [
        (("--velocity", "300"), r"density2 (\S+) kg/m\^3 or"),
        (("--density2", "1e5"), r"density2 (\S+) kg/m\^3 or"),
        (("--mass", "1e-50"), r"raise --mass to at least about (\S+) kg"),
    ],
)
def test_each_remedy_of_the_wave_limit_is_within_it(capsys, argv, remedy):
    """Each remedy lands just below the limit, where the runs measured pass (lambda 0.69-0.70;
    the 1.66e-06 kg that 1e-50 kg named ran at lambda 0.79 with a 13.6 % error bar on P_max,
    the 4.82e-06 kg it names now at 0.693 with 1.3 %)."""
    from shtaerman.guards import MAX_RADIATED_ESTIMATE
    from shtaerman.theory.materials import RIGID, Material, effective_modulus
    from shtaerman.theory.radiation import impact_radiation
    from shtaerman.theory.sneddon import PowerLawIndenter, contact_law

    said = _error(capsys, "dynamic", *argv)
    value = float(re.search(remedy, said)[1])
    mass, velocity, density = 0.7, 3.0, 1100.0
    if "--velocity" in argv:
        velocity = 300.0
    if remedy.startswith("density2"):
        density = value
    elif "--mass" in argv:
        mass = value
    body = Material(7.5e6, 0.5)
    law = contact_law(PowerLawIndenter(5.0, 1.5), effective_modulus(RIGID, body))
    fraction = impact_radiation(mass, velocity, law, density, body).energy_fraction
    assert 0.98 * MAX_RADIATED_ESTIMATE < fraction <= MAX_RADIATED_ESTIMATE <= 0.7, fraction


# --- the finite-strain impact with inertia: the wave-speed limit, on every route ---------------

WAVES = (
    "--mass, --density2: 1e-20 kg at 3 m/s is 0.0629 of the body's shear wave speed c_s = "
    "sqrt(G / density2) = 47.7 m/s and would radiate 47.4 times its energy as waves to first order"
)
"""The head of the refusal of z = 5 r^1.5 on the paper's rubber, 1e-20 kg at 3 m/s (its
remedy: mass 4.82e-06 kg at 3 m/s, or density2 0.237 kg/m^3)."""


def _started(monkeypatch):
    """Make any finite-strain impact that starts fail the test (the refusal comes first)."""
    import shtaerman.fem.finite_dynamic as finite_dynamic

    def started(*args, **kwargs):
        raise AssertionError("the finite-strain impact started")

    monkeypatch.setattr(finite_dynamic, "prepare_finite_impact", started)
    import shtaerman.fem.impact as impact

    monkeypatch.setattr(impact, "prepare_finite_impact", started)


def _rubber(mass: float, velocity: float = 3.0, density: float = 1100.0) -> sh.Problem:
    """The paper's striker on its rubber (neo-Hookean at finite strain), ``mass`` kg."""
    body = sh.Material(7.5e6, 0.5, density)
    indenter = sh.PowerLawIndenter(5.0, 1.5)
    return sh.Problem.impact(indenter, body, mass=mass, velocity=velocity, model="neo-hookean")


def test_a_rubber_impact_too_fast_for_its_waves_is_refused_on_the_command_line(capsys, monkeypatch):
    """`dynamic --model neo-hookean --mass 1e-40 --velocity 3` (lambda 1.5e4) failed
    numerically after about 70 s; the linear body's wave limit refuses it at once, naming a
    mass within the finite-strain reach and the waves' limit. (1e-40 kg, x/a 9.2e-6, is now
    below the finite-strain floor 1e-3: 1e-20 kg, x/a 2.9e-3, is the case since session 60.)"""
    from shtaerman.api.fem_dynamic import check_dynamic

    _started(monkeypatch)
    argv = ["dynamic", "--model", "neo-hookean", "--mass", "1e-20", "--velocity", "3"]
    said = _error(capsys, *argv)
    assert said.startswith(f"shtaerman: error: {WAVES}"), said
    assert "or mass 4.82e-06 kg at 3 m/s would pass" in said, said
    check_dynamic(_rubber(4.82e-6))  # the remedy passes the reach and the waves
    check_dynamic(_rubber(1e-20, density=0.237))


def test_a_rubber_impact_too_fast_for_its_waves_is_refused_by_the_api_a_study_and_a_sweep(
    tmp_path, monkeypatch
):
    """The same refusal by sh.dynamic, a dynamic study's loader and a dynamic sweep's load
    (check_impact_reach, the one check of every route), before any work."""
    import re

    from shtaerman.study.schema import StudyError, load_study
    from shtaerman.sweep.spec import SweepError, parse_sweep

    _started(monkeypatch)
    with pytest.raises(sh.LimitError, match=r"^mass, density: 1e-20 kg at 3 m/s is 0\.0629 "):
        sh.dynamic(_rubber(1e-20))
    path = tmp_path / "d.toml"
    assert main(["init-study", "--kind", "dynamic", str(path)]) == 0
    text = re.sub(r"(?m)^velocity = .*$", "velocity = 3.0", path.read_text())
    text = re.sub(r"(?m)^mass = .*$", "mass = 1e-20", text)
    text = text.replace("# [rubber]", "[rubber]")
    path.write_text(text.replace('# model = "linear"', 'model = "neo-hookean"'))
    with pytest.raises(StudyError, match=r"1e-20 kg at 3 m/s is 0\.0629 of the body's shear"):
        load_study(path)
    sweep = 'name = "r"\nkind = "dynamic"\n[parameters]\nmodel = "neo-hookean"\nvelocity = 3.0\n'
    with pytest.raises(SweepError, match=r"1e-20 kg at 3 m/s is 0\.0629 of the body's shear"):
        parse_sweep(sweep + "[axes]\nmass = [1e-20]\n")


# --- --resume on an empty folder: nothing to complete, on every route (files.check_folder_place)


def test_a_resume_of_an_empty_folder_is_refused_by_sweep_verify_and_effects(
    tmp_path, capsys, monkeypatch
):
    """The sweep ran fresh into an empty --out given with --resume (and verify and effects
    too): an interrupted run keeps what it saved, or nothing, so an empty folder holds no run
    to complete. One check (check_folder_place) says it for the three."""
    import shtaerman.output.folder as folder
    import shtaerman.sweep.engine as engine

    def started(*args, **kwargs):
        raise AssertionError("the run started")

    monkeypatch.setattr(engine, "_client", started)
    monkeypatch.setattr(folder, "run_verification", started)
    out = tmp_path / "empty"
    out.mkdir()
    said = (
        f"shtaerman: error: --resume: the folder '{out}' (--out) is empty, so there is nothing "
        "to complete; drop --resume to start a new run\n"
    )
    assert _error(capsys, "sweep", "nu-grid", "--resume", "--out", out) == said
    assert _error(capsys, "verify", "paper", "--quick", "--resume", "--out", out) == said
    assert _error(capsys, "effects", "--resume", "--out", out) == said
    with pytest.raises(sh.InputError, match=r"^resume: .* is empty, .* drop resume=True to"):
        sh.sweep("nu-grid", out=out, resume=True)
    assert list(out.iterdir()) == []  # nothing made


# --- the exact impact beyond the floats: one remedy, in the reach rule's words ----------------


def test_the_exact_impact_beyond_the_floats_names_the_velocity_and_mass_that_pass(capsys):
    """`impact --velocity 1e-300` (P_c = beta x_c^(5/3) underflows) named --shape-coefficient,
    --E2, --mass, --velocity and "give these a value of a physical size"; it names the
    velocity and the mass that bring every scale of the impact within the floats, as the FE
    impact's reach does, each rounded inward, and each passes when tried."""
    import re

    paper, rubber = sh.PowerLawIndenter(5.0, 1.5), sh.Material(7.5e6, 0.5)
    for argv, mass, velocity, verb in (
        (("--velocity", "1e-300"), 0.7, 1e-300, "raise"),
        (("--mass", "1e-300", "--velocity", "1e-300"), 1e-300, 1e-300, "raise"),
        (("--velocity", "1e300"), 0.7, 1e300, "lower"),
    ):
        assert main(["impact", *argv]) == 2  # 1e300 m/s: the theory's validity warning first
        out, err = capsys.readouterr()
        said = err.splitlines(keepends=True)[-1]
        assert out == "" and "Traceback" not in err, err
        head = f"shtaerman: error: --mass, --velocity: the exact impact of {mass:g} kg at "
        assert said.startswith(head) and " outside the floating-point range " in said, said
        assert "--E2" not in said and "--shape-coefficient" not in said, said
        at = "least" if verb == "raise" else "most"
        found = re.search(
            rf": {verb} --velocity to at {at} about (\S+) m/s with this striker, mass and body, "
            rf"or --mass to at {at} about (\S+) kg\n$",
            said,
        )
        assert found, said
        with warnings.catch_warnings():  # beyond the quasi-static theory's 5 m/s
            warnings.simplefilter("ignore")
            sh.impact(paper, rubber, mass=mass, velocity=float(found[1]))  # each passes
            sh.impact(paper, rubber, mass=float(found[2]), velocity=velocity)
    with pytest.raises(sh.InputError) as refused:
        sh.impact(paper, rubber, mass=0.7, velocity=1e-300)
    assert refused.value.parameter == "velocity"
    assert str(refused.value).startswith("mass, velocity: the exact impact of 0.7 kg at 1e-300")


# --- a ratio just outside the reach prints apart from its limit --------------------------------


def test_a_depth_ratio_just_outside_the_reach_prints_apart_from_its_limit(capsys):
    """x/a 9.96e-07 printed "depth / contact radius 1e-06, below the 1e-06", and 100.005
    "100, beyond the 100": the ratio gets the digits that tell it from the limit."""
    said = _error(capsys, "dynamic", "--mass", "1.84e-48", "--velocity", "3", "--density2", "0")
    assert "depth / contact radius 9.96e-07, below the 1e-06 " in said, said
    said = _error(capsys, "dynamic", "--mass", "1.9e16", "--velocity", "3", "--density2", "0")
    assert "depth / contact radius 100.005, beyond the 100 " in said, said


@pytest.mark.parametrize("coefficient", ["1e-300", "1e-200"])
def test_a_beta_beyond_the_floats_is_refused_in_one_line(capsys, coefficient):
    """adv59: (kappa A)^(-1/n) overflows for A = 1e-300 at n = 0.25 ((1e-300)^-4): Python's
    power raised OverflowError, a traceback (exit 1); beta is inf, which the exact theory's
    range check refuses (exit 2, one line)."""
    argv = ["impact", "--shape-coefficient", coefficient, "--exponent", "0.25"]
    assert main([*argv, "--velocity", "1e-100"]) == 2
    err = capsys.readouterr().err
    assert len(err.strip().splitlines()) == 1 and "Traceback" not in err, err
    assert "beta" in err and "= inf" in err and "not representable" in err
