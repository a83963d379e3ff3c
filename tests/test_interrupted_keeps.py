"""An interrupted run loses nothing already written (the interface contract): an effect
table keeps its finished runs and --resume completes it; a --force run of effects, verify or
sweep leaves the folder it was replacing whole and keeps its own finished part beside it,
as NAME.incomplete-PID, from which the printed command resumes."""

import json
import os
import shutil
import signal
from pathlib import Path

import pytest

import shtaerman.cli as cli
import shtaerman.output.folder

COARSE = ["effects", "--mesh-size", "0.2", "--time-steps", "50", "--no-estimate"]
"""The paper's impact with waves (the default density): 2 FE runs ('none', 'waves alone'),
shared by the 4 variants, about 1 s of CPU each."""


def snapshot(folder: Path) -> dict:
    """Every file below ``folder``: its bytes and modification time."""
    return {
        p.relative_to(folder): (p.stat().st_mtime_ns, p.read_bytes())
        for p in folder.rglob("*")
        if p.is_file()
    }


def _interrupt_second_run(monkeypatch, calls: list) -> None:
    """The first FE run of the table runs; Ctrl-C arrives as the second starts."""
    import shtaerman.api.effect_table.run as effect_run

    real = effect_run._run

    def first_then_interrupt(variant, *args, **kwargs):
        calls.append(variant.label)
        if len(calls) > 1:
            raise KeyboardInterrupt
        return real(variant, *args, **kwargs)

    monkeypatch.setattr(effect_run, "_run", first_then_interrupt)


def _counting_runs(monkeypatch, calls: list) -> None:
    import shtaerman.api.effect_table.run as effect_run

    real = effect_run._run

    def counted(variant, *args, **kwargs):
        calls.append(variant.label)
        return real(variant, *args, **kwargs)

    monkeypatch.setattr(effect_run, "_run", counted)


def _values(folder: Path) -> dict:
    """Each variant's numbers in ``folder``'s effects.json (not its seconds)."""
    table = json.loads((folder / "effects.json").read_text())
    return {run["label"]: (run["values"], run["refused"]) for run in table["runs"]}


def _resume_argv(err: str) -> list[str]:
    """The effects command the interrupted run's line says completes it."""
    (line,) = [line for line in err.splitlines() if "--resume" in line]
    tail = line.split("the same options and ")[1].split()
    return [*COARSE, *tail]


@pytest.fixture(scope="module")
def whole_table(tmp_path_factory) -> Path:
    """The uninterrupted COARSE table's folder, written once for the two tests below (each ran
    it: 2 FE runs, its figures and files); a test that changes it works on a copy."""
    whole = tmp_path_factory.mktemp("effects") / "whole"
    assert cli.main([*COARSE, "--out", str(whole)]) == 0
    return whole


def test_an_interrupted_effects_table_is_resumed_from_its_kept_run(
    monkeypatch, tmp_path, capsys, whole_table
):
    """Interrupted at its second FE run, the table keeps the first in --out (exit 130, a line
    naming the folder and --resume); the resume runs only the missing one and writes the
    same numbers as an uninterrupted table. Old code: exit 130, no folder, nothing kept."""
    out, calls = tmp_path / "o", []
    _interrupt_second_run(monkeypatch, calls)
    assert cli.main([*COARSE, "--out", str(out)]) == 130
    err = capsys.readouterr().err
    assert calls == ["none", "waves alone"]
    assert "1 finished run(s) kept in" in err and "--resume" in err, err
    kept = json.loads((out / "incomplete.json").read_text())["studies"]
    assert list(kept) == ["none"] and kept["none"]["entry"]["values"]["P_max"] > 0
    assert not (out / "effects.json").exists()  # no table from half of its runs

    monkeypatch.undo()
    calls.clear()
    _counting_runs(monkeypatch, calls)
    assert cli.main(_resume_argv(err)) == 0
    assert calls == ["waves alone"]  # the kept run is not run again
    assert not (out / "incomplete.json").exists()
    # the same deterministic FE runs: the resumed table's numbers are the uninterrupted ones
    # to the last bit
    assert _values(out) == _values(whole_table)


def test_an_interrupted_forced_effects_run_leaves_the_old_table_whole(
    monkeypatch, tmp_path, capsys, whole_table
):
    """effects --out o --force interrupted after one run: o is byte for byte the old table;
    the finished run is in o.incomplete-PID, named in the line, and the resume completes it
    there. Old code: the old table kept (nothing of the new run); with the sweep's and
    verify's old rule, the old folder was lost."""
    out = shutil.copytree(whole_table, tmp_path / "o")  # the old table (mtimes kept)
    before = snapshot(out)
    capsys.readouterr()
    calls: list = []
    _interrupt_second_run(monkeypatch, calls)
    assert cli.main([*COARSE, "--out", str(out), "--force"]) == 130
    err = capsys.readouterr().err
    assert snapshot(out) == before
    beside = tmp_path / f"o.incomplete-{os.getpid()}"
    assert str(beside) in err and "unchanged: --force keeps it whole" in err, err
    assert list(json.loads((beside / "incomplete.json").read_text())["studies"]) == ["none"]
    monkeypatch.undo()
    assert cli.main(_resume_argv(err)) == 0
    assert _values(beside) == _values(out)


@pytest.mark.parametrize(("stop", "code"), [(KeyboardInterrupt(), 130), ("terminated", 143)])
def test_an_interrupted_forced_verify_leaves_the_old_folder_whole(
    quick_outcomes, quick_verify, tmp_path, monkeypatch, capsys, stop, code
):
    """verify --force stopped after its first study: the old complete folder is unchanged
    (old code: it was gone, only the new run's one study left in its place); the finished
    study is beside it, and the printed command completes it there."""
    from shtaerman.cli import Terminated
    from shtaerman.study.schema import shipped_studies

    studies = [str(p) for p in shipped_studies() if p.stem in ("paper", "hertz")]
    served: list = []
    stop = Terminated() if stop == "terminated" else stop

    def first_then_stop(study, *, quick=False, progress=None):
        served.append(study.name)  # the session's quick outcome; the second study: stopped
        if len(served) > 1 and stop is not None:
            raise stop
        return quick_outcomes[study.name]

    out = tmp_path / "run"
    shutil.copytree(quick_verify[1], out)
    before = snapshot(out)
    monkeypatch.setattr(shtaerman.output.folder, "run_study", first_then_stop)
    argv = ["verify", "--quick", "--workers", "1", "--out", str(out), "--force", *studies]
    assert cli.main(argv) == code
    err = capsys.readouterr().err
    first, second = served
    assert snapshot(out) == before
    beside = tmp_path / f"run.incomplete-{os.getpid()}"
    assert sorted(p.name for p in beside.iterdir()) == sorted(
        [".shtaerman-folder.json", "incomplete.json", first]
    )
    assert "1 of 2 studies finished and kept in" in err and str(beside) in err, err
    command = err.split("complete them with: ")[1].strip()
    assert f"--out {beside}" in command and command.endswith("--resume")
    served.clear()
    stop = None
    assert cli.main(command.split()[1:]) == 0
    assert served == [second]
    assert (beside / "results.json").is_file() and not (beside / "incomplete.json").exists()


IMPACT = 'name = "grid"\nkind = "impact"\n[parameters]\nmass = 0.7\n[axes]\nvelocity = [1.0, 2.0]\n'


def test_an_interrupted_forced_sweep_leaves_the_old_sweep_whole(tmp_path, capsys, monkeypatch):
    """sweep --force stopped after it saved a case: the old sweep is unchanged (old code: it
    was deleted and the new run's one case kept in its place); the saved case is beside it
    and the printed resume command completes the sweep there."""
    from shtaerman.sweep import engine

    sweep = tmp_path / "sweep.toml"
    sweep.write_text(IMPACT)
    out = tmp_path / "out"
    assert cli.main(["sweep", str(sweep), "--out", str(out), "--workers", "1"]) == 0
    before = snapshot(out)
    real = engine._compute

    def interrupted(spec, out, ready, pending, records, *args):
        real(spec, out, ready, pending[:1], records, *args)  # case 0 saved ...
        raise engine.SweepInterrupted(signal.SIGTERM)  # ... and the run is stopped

    monkeypatch.setattr(engine, "_compute", interrupted)
    code = cli.main(["sweep", str(sweep), "--out", str(out), "--force", "--workers", "1"])
    err = capsys.readouterr().err
    assert code == 128 + signal.SIGTERM
    assert snapshot(out) == before
    beside = tmp_path / f"out.incomplete-{os.getpid()}"
    assert sorted(p.name for p in (beside / "cases").iterdir()) == ["0.json"]
    assert err.count("\n") == 1 and "--force kept the previous sweep" in err, err
    assert "1 of 2 cases of this run saved in" in err, err
    command = err.split("resume with: ")[1].split()
    assert command[-5:] == ["--out", str(beside), "--resume", "--workers", "1"]
    monkeypatch.undo()
    assert cli.main(command[1:]) == 0
    out_text = capsys.readouterr().out
    assert "1 computed on 1 worker, 1 from an earlier run" in out_text, out_text
    # completed, it replaces the old sweep, as the --force run would have (sweep32c)
    assert not beside.exists() and (out / "cases.csv").read_bytes() == before[Path("cases.csv")][1]


def test_the_resume_command_keeps_the_figure_format(tmp_path, capsys, monkeypatch):
    """sweep --figure-format svg stopped after a case: the printed resume command completes
    the sweep with its SVG figures (old code: the command dropped --figure-format, and the
    completed sweep had PNG figures only)."""
    from shtaerman.sweep import engine

    sweep = tmp_path / "sweep.toml"
    sweep.write_text(IMPACT)
    out = tmp_path / "out"
    real = engine._compute

    def interrupted(spec, out, ready, pending, records, *args):
        real(spec, out, ready, pending[:1], records, *args)  # case 0 saved ...
        raise engine.SweepInterrupted(signal.SIGTERM)  # ... and the run is stopped

    monkeypatch.setattr(engine, "_compute", interrupted)
    argv = ["sweep", str(sweep), "--out", str(out), "--workers", "1", "--figure-format", "svg"]
    assert cli.main(argv) == 128 + signal.SIGTERM
    command = capsys.readouterr().err.split("resume with: ")[1].split()
    assert command[-2:] == ["--figure-format", "svg"], command
    monkeypatch.undo()
    assert cli.main(command[1:]) == 0  # its --workers 1 kept
    figures = sorted(p.name for p in (out / "figures").iterdir())
    pngs = [name for name in figures if name.endswith(".png")]
    assert pngs and [n[:-4] + ".svg" for n in pngs] == [n for n in figures if n.endswith(".svg")]
