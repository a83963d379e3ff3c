"""A ``sweep --force`` killed by SIGKILL: the run after it completes the replacement.

The killed run had moved the old sweep into its staging folder and was writing the new one in
place. The next run on the folder keeps the old sweep beside it as ``NAME.replaced-PID``
(shtaerman.output.files); once a ``--resume`` has completed the new sweep there, that old
folder was left for the user to find and delete. The run that completes the replacement now
removes it, and says so in one line.
"""

import os
import shutil
import sys
from pathlib import Path

import pytest
import sweep_probe  # noqa: F401  (registers the kind "probe")

from shtaerman.cli import main


def _probe(tmp_path, name, xs):
    path = tmp_path / f"{name}.toml"
    path.write_text(f'name = "{name}"\nkind = "probe"\n[axes]\nx = {xs}\n')
    return path


DEAD = int(Path("/proc/sys/kernel/pid_max").read_text()) + 1 if sys.platform == "linux" else 0
"""A process id that no process has."""
linux = pytest.mark.skipif(sys.platform != "linux", reason="reads the largest process id in /proc")


def _old_and_new(tmp_path, where):
    """A complete sweep "old" in tmp_path/out and, in ``where``, one case of 2 of the sweep
    "new" that replaces it (its file returned)."""
    old_sweep, new_sweep = _probe(tmp_path, "old", [1.0]), _probe(tmp_path, "new", [2.0, 3.0])
    assert main(["sweep", str(old_sweep), "--out", str(tmp_path / "out"), "--workers", "1"]) == 0
    assert main(["sweep", str(new_sweep), "--out", str(where), "--workers", "1"]) == 0
    for entry in ("cases.csv", "results.json", "figures", "cases/1.json"):
        shutil.rmtree(where / entry) if (where / entry).is_dir() else (where / entry).unlink()
    return new_sweep


@linux
def test_the_run_that_completes_a_killed_force_removes_the_sweep_it_replaced(tmp_path, capfd):
    out, new = tmp_path / "out", tmp_path / "new"
    new_sweep = _old_and_new(tmp_path, new)
    stage = tmp_path / f".out.partial-{DEAD}"  # what a killed --force run leaves
    stage.mkdir()
    os.rename(out, stage / "replaced")
    os.rename(new, out)
    capfd.readouterr()
    assert main(["sweep", str(new_sweep), "--out", str(out), "--resume"]) == 0
    err = capfd.readouterr().err
    kept = tmp_path / f"out.replaced-{DEAD}"
    assert not kept.exists() and not stage.exists()
    line = f"shtaerman: removed {kept}, the sweep a killed --force run was replacing with {out}"
    assert f"{line}, now complete\n" in err
    assert len((out / "cases.csv").read_text().splitlines()) == 3  # the header, 2 cases


def test_a_resume_that_completes_an_interrupted_force_puts_it_in_place(tmp_path, capfd):
    """An interrupted --force keeps the old sweep in DIR and its own cases in
    DIR.incomplete-PID, which the resume line completes; the user then had to rename it."""
    out = tmp_path / "out"
    kept = tmp_path / f"out.incomplete-{os.getpid()}-2"
    new_sweep = _old_and_new(tmp_path, tmp_path / "new")
    os.rename(tmp_path / "new", kept)
    capfd.readouterr()
    assert main(["sweep", str(new_sweep), "--out", str(kept), "--resume"]) == 0
    printed, err = capfd.readouterr()
    assert err == f"shtaerman: the --force run completed in {kept} now replaces {out}\n"
    assert f"results: {out / 'cases.csv'}" in printed and not kept.exists()
    assert (out / "sweep.toml").read_text() == new_sweep.read_text()
    assert len((out / "cases.csv").read_text().splitlines()) == 3
    assert [path.name for path in tmp_path.iterdir() if path.name.startswith(".")] == []
