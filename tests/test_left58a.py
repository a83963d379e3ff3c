"""Session 58's leftovers of issue 28 (the same guards and words on every route): the sweep and
verify share one check of the output folder and of a resume, and the public API exports the
error a validity limit raises."""

from __future__ import annotations

import inspect
from pathlib import Path

import pytest

import shtaerman as sh
from shtaerman import validation
from shtaerman.cli import main


def test_the_limit_error_is_public_beside_the_input_error():
    assert "LimitError" in sh.__all__ and "InputError" in sh.__all__
    assert sh.LimitError is validation.LimitError and sh.InputError is validation.InputError
    assert issubclass(sh.LimitError, sh.InputError)


# --- one check of the output folder's place (files.check_folder_place) -------------------------


def _error(capsys, *argv) -> str:
    assert main(list(map(str, argv))) == 2
    out, err = capsys.readouterr()
    assert out == "" and err.count("\n") == 1 and "Traceback" not in err, err
    return err


@pytest.mark.skipif(not Path("/proc/self").is_dir(), reason="needs Linux /proc")
def test_the_sweep_refuses_a_folder_that_takes_no_new_files_as_verify_does(capsys, monkeypatch):
    """/proc is a folder whose file system takes no new entry (mkdir: ENOENT); the sweep said
    "parent '/proc' is not a folder", its own copy of the check reading the error of its lock."""
    import shtaerman.output.folder as folder
    import shtaerman.sweep.engine as engine

    def started(*args, **kwargs):
        raise AssertionError("the run started")

    monkeypatch.setattr(engine, "_client", started)
    monkeypatch.setattr(folder, "run_verification", started)
    said = "shtaerman: error: --out: cannot write in '/proc' (its file system takes no new files)\n"
    assert _error(capsys, "sweep", "nu-grid", "--out", "/proc/x") == said
    assert _error(capsys, "verify", "paper", "--quick", "--out", "/proc/x") == said


def test_the_sweep_has_no_copy_of_the_folder_check():
    import shtaerman.sweep.engine as engine

    source = inspect.getsource(engine)
    assert "missing_folder" not in source and "exists and is not a folder" not in source


# --- --resume on a folder that does not exist: refused by every route, in one line -------------

RESUME = (
    "--resume: the folder '{out}' (--out) does not exist, so there is nothing to complete; drop "
    "--resume to start a new run"
)


def test_a_resume_of_a_missing_folder_is_refused_by_verify_sweep_and_effects(
    tmp_path, capsys, monkeypatch
):
    """It ran everything as a new run (verify, effects, sweep alike), where the user asked to
    complete a folder: a mistyped --out."""
    import shtaerman.output.folder as folder
    import shtaerman.sweep.engine as engine

    def started(*args, **kwargs):
        raise AssertionError("the run started")

    monkeypatch.setattr(engine, "_client", started)
    monkeypatch.setattr(folder, "run_verification", started)
    out = tmp_path / "doesnotexist"
    said = f"shtaerman: error: {RESUME.format(out=out)}\n"
    assert _error(capsys, "verify", "paper", "--quick", "--resume", "--out", out) == said
    assert _error(capsys, "sweep", "nu-grid", "--resume", "--out", out) == said
    assert _error(capsys, "effects", "--resume", "--out", out) == said
    with pytest.raises(sh.InputError, match=r"^resume: .* drop resume=True to") as python:
        sh.sweep("nu-grid", out=out, resume=True)
    assert python.value.parameter == "resume"
    assert list(tmp_path.iterdir()) == []  # nothing made


def test_a_resume_of_an_empty_folder_still_runs(tmp_path, capsys):
    """A folder that exists but holds nothing is a run killed before anything was saved: the
    resume computes everything, as before."""
    import sweep_probe  # noqa: F401  (registers the kind "probe")

    sweep = tmp_path / "p.toml"
    sweep.write_text('name = "p"\nkind = "probe"\n[axes]\nx = [1.0]\n')
    out = tmp_path / "out"
    out.mkdir()
    assert main(["sweep", str(sweep), "--out", str(out), "--resume", "--workers", "1"]) == 0
    assert "1 cases, 1 ok" in capsys.readouterr().out
