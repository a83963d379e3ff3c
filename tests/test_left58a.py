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


# --- a sweep with a refused row, interrupted and resumed, says what the whole run says ----------

DYNAMIC = """name = "fast"
kind = "dynamic"
[parameters]
time_steps = 60
mesh_size = 0.05
[axes]
velocity = [2.0, 3.0, 50.0]
"""
"""tests/test_sweeprow57.py's coarse dynamic sweep (1-3 s a case): 50 m/s is refused by the
wave-speed limit."""


def test_an_interrupted_sweep_counts_its_refused_row_as_its_resume_does(
    tmp_path, capfd, monkeypatch
):
    """The interruption said "all 3 cases saved" (the refused row's record among them), its
    resume "2 from an earlier run" (a refused row is judged again, never reused). The resumed
    summary counts what the uninterrupted run's does (tests/test_sweeprow57.py: "1 ok, 0
    failed, 1 refused" on two of these cases)."""
    import os
    import signal

    from shtaerman.sweep import figures

    path, out = tmp_path / "fast.toml", tmp_path / "out"
    path.write_text(DYNAMIC)
    draw = figures.sweep_figures

    def signalled(*args, **kwargs):
        os.kill(os.getpid(), signal.SIGTERM)
        return draw(*args, **kwargs)

    monkeypatch.setattr(figures, "sweep_figures", signalled)
    assert main(["sweep", str(path), "--out", str(out), "--workers", "1"]) == 143
    said = capfd.readouterr().err
    assert f"all 2 cases saved in {out} (1 more refused, outside the model's validity), " in said
    monkeypatch.undo()
    assert main(["sweep", str(path), "--out", str(out), "--resume"]) == 0
    resumed = capfd.readouterr().out.splitlines()[0]
    counts = "3 cases, 2 ok, 0 failed, 1 refused (outside the model's validity)"
    assert f"{counts} (nothing to compute, 2 from an earlier run)" in resumed
