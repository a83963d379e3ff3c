"""Defects found by the adversary's and new user's pass over this session's changes (git log
9a3522f..20df9c7, branch adv29): effects --resume, --force keeping the old folder whole, one
dynamic JSON schema, route-worded refusals. Each test asserts what the contract asks; a defect
not yet fixed is marked xfail(strict=True) with its reason, and its fix removes the mark."""

import os
import subprocess
import sys

import pytest

import shtaerman as sh
import shtaerman.cli as cli
from shtaerman.output import files


class _StoppedError(Exception):
    """A stand-in for an interrupted run's reason (VerifyInterrupted carries kept_in)."""

    kept_in = None


def test_a_forced_run_stopped_keeps_its_part_when_incomplete_pid_exists(tmp_path):
    target = tmp_path / "out"
    with files.staged_folder(target) as first:
        (first / "old.txt").write_text("old", encoding="utf-8")
    clash = files.incomplete_path(target)  # an earlier run of the same PID left it
    clash.mkdir()
    (clash / "theirs.txt").write_text("an earlier run's part", encoding="utf-8")
    with pytest.raises(_StoppedError) as caught:
        with files.staged_folder(target, force=True) as content:
            (content / "finished.json").write_text("{}", encoding="utf-8")
            raise files.KeepStaged(_StoppedError("terminated"))
    assert (target / "old.txt").read_text(encoding="utf-8") == "old"  # the old folder whole
    assert (clash / "theirs.txt").is_file()  # the earlier part untouched
    kept = caught.value.kept_in
    assert kept is not None and (kept / "finished.json").is_file(), kept


def test_dynamic_refuses_a_loading_keyword():
    striker = sh.PowerLawIndenter(shape_coefficient=5.0, exponent=1.5)
    rubber = sh.Material(youngs_modulus=7.5e6, poisson_ratio=0.5, density=1100.0)
    # coarse numerics: when the defect is there, the run is made (about a second of CPU)
    with pytest.raises((TypeError, sh.InputError)) as caught:
        sh.dynamic(
            striker, rubber, mass=0.7, velocity=3.0, loading="curve",
            mesh_size=0.2, time_steps=50, estimate=False,
        )  # fmt: skip
    assert "loading" in str(caught.value)


def test_the_rubber_impacts_option_refusal_speaks_command_line(capsys):
    code = cli.main(["dynamic", "--model", "neo-hookean", "--layer-rate", "5"])  # refused: no run
    err = capsys.readouterr().err
    assert code == 2, err
    assert "--layer-rate" in err and "time_steps" not in err and "mesh_size" not in err, err


def test_the_rubber_curves_prony_refusal_names_density2_on_the_command_line(capsys):
    code = cli.main(["contact", "--model", "neo-hookean", "--prony", "0.3:1e-3"])  # refused
    err = capsys.readouterr().err
    assert code == 2, err
    assert "--density2 0" in err, err


def test_a_massless_dynamic_study_refuses_layer_rate(tmp_path):
    study = tmp_path / "massless.toml"
    study.write_text(
        'kind = "dynamic"\ndescription = "x"\n'
        "[indenter]\nshape_coefficient = 5.0\nexponent = 1.5\n"
        "[impact]\nmass = 0.7\nvelocity = 3.0\n"
        "[half_space]\nE2 = 7.5e6\nnu2 = 0.5\ndensity2 = 0.0\n"
        "[numerics]\nlayer_rate = 5.0\n"
        "[quick]\nmesh_size = 0.2\ntime_steps = 50\nlayer_rate = 5.0\n",
        encoding="utf-8",
    )
    # a subprocess: a refusal exits 2 before any run; with the defect it runs (--quick, seconds)
    done = subprocess.run(
        [sys.executable, "-m", "shtaerman", "verify", "--quick", "--workers", "1",
         "--out", os.fspath(tmp_path / "out"), os.fspath(study)],
        capture_output=True, text=True, check=False,
    )  # fmt: skip
    assert done.returncode == 2, done.stderr
    assert "layer_rate" in done.stderr, done.stderr


def test_effects_of_a_mapping_names_what_is_wrong_with_it():
    with pytest.raises((TypeError, sh.InputError)) as caught:  # refused before any run
        sh.effects({"colour": 3})
    assert "colour" in str(caught.value) or "indenter" in str(caught.value), caught.value


@pytest.mark.parametrize("command", [["effects"], ["verify", "hertz"]])
def test_resume_with_force_is_refused_in_option_words(command, tmp_path, capsys):
    code = cli.main([*command, "--out", str(tmp_path / "out"), "--resume", "--force"])  # no run
    err = capsys.readouterr().err
    assert code == 2, err
    assert "--resume" in err and "--force" in err, err


def test_an_effects_resume_of_other_variants_is_refused_in_its_own_words(tmp_path, capsys):
    out = tmp_path / "out"
    out.mkdir()  # an interrupted table's folder as effects leaves it (verify's progress file)
    (out / "incomplete.json").write_text(
        '{"format": "shtaerman-verify-progress-1", "quick": false, '
        '"requested": ["none", "pad alone"], "studies": {}}',
        encoding="utf-8",
    )
    (out / ".shtaerman-folder.json").write_text(
        '{"format": "shtaerman-folder-1", "files": ["incomplete.json"]}', encoding="utf-8"
    )
    code = cli.main(["effects", "--out", str(out), "--resume"])  # refused before any run
    err = capsys.readouterr().err
    assert code == 2, err
    assert "studies" not in err and "--resume" in err, err


def test_a_forced_sweep_stopped_puts_the_old_sweep_back_when_incomplete_pid_exists(tmp_path):
    from shtaerman.sweep import engine

    out, backup = tmp_path / "sweep", tmp_path / "lock" / "replaced"
    backup.mkdir(parents=True)
    (backup / "results.json").write_text("old", encoding="utf-8")  # the sweep --force replaces
    out.mkdir()
    (out / "new-case.json").write_text("{}", encoding="utf-8")  # one case the new run saved
    clash = files.incomplete_path(out)  # an earlier run of the same PID left it
    clash.mkdir()
    (clash / "theirs.txt").write_text("an earlier run's part", encoding="utf-8")
    with pytest.raises((KeyboardInterrupt, OSError)):  # the stop, or an OSError naming it
        with engine._replaced(out, backup, lambda: True):
            raise KeyboardInterrupt
    assert (out / "results.json").read_text(encoding="utf-8") == "old"  # put back whole
    assert (clash / "theirs.txt").is_file()
