"""A new user's and an adversary's pass over session 48's features (adv48): study and sweep
files with the new keys, the effect table's --resume, the sweep figures of an effects sweep,
and hostile measurement files for ``shtaerman fit``. Each test states the contract: bad input
is one line naming the key and its valid range (exit code 2), nothing is drawn or estimated
that the data do not hold."""

import math
import os
from dataclasses import asdict
from pathlib import Path

import pytest
from cli_helpers import error_line

from shtaerman.api.effect_table.table import Run
from shtaerman.cli import main
from shtaerman.cli.effects import _stored_run
from shtaerman.output.files import json_safe
from shtaerman.study.schema import StudyError, load_study
from shtaerman.sweep.figures import draw_figures
from shtaerman.validation import InputError


def _template(tmp_path: Path, kind: str, table: str, lines: str) -> Path:
    """``init-study --kind kind``'s template with ``lines`` first in ``[table]`` (a key the
    template sets is replaced)."""
    path = tmp_path / f"{kind}.toml"
    assert main(["init-study", str(path), "--kind", kind]) == 0
    text = path.read_text()
    for line in lines.splitlines():
        key = line.split("=")[0].strip()
        text = "\n".join(row for row in text.splitlines() if not row.startswith(f"{key} "))
    header = next(row for row in text.splitlines() if row.startswith(f"[{table}]"))
    path.write_text(text.replace(f"\n{header}\n", f"\n{header}\n{lines}\n", 1) + "\n")
    return path


def _refusal(path: Path) -> str:
    with pytest.raises(StudyError) as refused:
        load_study(path)
    said = str(refused.value)
    assert "\n" not in said, said
    return said


@pytest.mark.parametrize("value", ["1", '"yes"', "2.5"])
def test_a_study_names_estimate_a_boolean(tmp_path, value):
    # was: "key 'numerics.estimate': expected a number > 0, got 1" for a true/false key
    said = _refusal(_template(tmp_path, "effects", "numerics", f"estimate = {value}"))
    assert "key 'numerics.estimate': expected true or false" in said, said


def test_an_infinite_number_in_a_study_is_refused_with_its_range(tmp_path):
    # was: "expected a finite number, got inf", without the range [0, 1e2] of a friction
    path = _template(tmp_path, "contact", "contact", 'interface = "bonded"\nfriction = inf')
    said = _refusal(path)
    assert "key 'contact.friction': friction must be a finite number in [0, 1e2], got inf" in said
    said = _refusal(_template(tmp_path, "effects", "numerics", "refine = inf"))
    wanted = "key 'numerics.refine': refine must be a finite number in (0, 1e6], got inf"
    assert wanted in said, said


def test_an_effects_study_refuses_numerics_out_of_range_at_load(tmp_path):
    said = _refusal(_template(tmp_path, "effects", "numerics", "time_steps = 1000000000"))
    assert "numerics.time_steps" in said and "[50, 5000]" in said, said


def _entry(**changes) -> dict:
    """A saved effects run as incomplete.json holds it (JSON-safe: NaN as None)."""
    run = Run("none", "none", None, "linear, half-space", values={"P_max": 985.7, "x_max": 8e-3})
    return json_safe(asdict(run)) | changes


def test_a_kept_effects_run_reads_back_as_it_was_saved():
    assert _stored_run(_entry()) == Run(
        "none", "none", None, "linear, half-space", values={"P_max": 985.7, "x_max": 8e-3}
    )
    nan = _stored_run(_entry(values={"P_max": None}))  # json_safe wrote a NaN as null
    assert math.isnan(nan.values["P_max"])


@pytest.mark.parametrize(
    "changes",
    [{"values": {"P_max": "abc"}}, {"values": [1.0]}, {"seconds": "slow"}, {"label": None}],
)
def test_effects_resume_refuses_a_damaged_kept_run_in_one_line(changes):
    # was: TypeError traceback in the table ("unsupported operand type(s) for /: 'str'")
    with pytest.raises(InputError) as refused:
        _stored_run(_entry(**changes))
    said = str(refused.value)
    assert said.startswith("--resume: incomplete.json") and "--force" in said, said


def _effects_results(resolved: list) -> dict:
    """A 1-axis effects sweep's results.json, as the figures read it: every case ran."""
    cases = [
        {"index": i, "status": "ok", "outputs": {"change_P_max": 0.2 + i, "resolved_P_max": r}}
        for i, r in enumerate(resolved)
    ]
    return {
        "spec": {"name": "eff", "kind": "effects", "axes": {"velocity": [1.0, 2.0]}},
        "kind": {
            "outputs": {"change_P_max": "", "resolved_P_max": ""},
            "parameter_units": {"velocity": "m/s"},
            "levels": {},
        },
        "cases": cases,
    }


def test_an_effects_sweep_draws_no_empty_chart_of_an_output_no_case_gave():
    # estimate = false (the sweep's default) leaves every resolved_* null: its chart was
    # empty, a dotted 'failed' line at every case that ran
    drawn = dict(draw_figures(_effects_results([None, None])))
    assert list(drawn) == ["change_P_max"]
    drawn = dict(draw_figures(_effects_results([1.0, None])))  # one value: its chart stays
    assert list(drawn) == ["change_P_max", "resolved_P_max"]


def test_a_fit_of_one_measurement_repeated_asks_for_the_noise(tmp_path, capsys):
    # was: E2 = 2.70147e+06 Pa in [2.70147e+06, 2.70147e+06], noise 6.5e-15 N "estimated
    # from the residual" that the copies make zero
    data = tmp_path / "copies.csv"
    data.write_text("depth [m],force [N]\n0.001,10\n0.001,10\n0.001,10\n")
    said = error_line(capsys, "fit", "indentation", data)
    assert said.startswith("--noise: 3 data value(s), 1 distinct, for 1 unknown(s)"), said
    # repeated depths that measured different forces do tell the noise: the fit runs
    data.write_text("depth [m],force [N]\n0.001,10\n0.001,11\n0.001,9\n")
    assert main(["fit", "indentation", str(data)]) == 0
    assert "noise 1 N (estimated from the residual)" in capsys.readouterr().out


def test_a_forced_output_that_cannot_be_moved_is_refused_before_the_run(tmp_path, monkeypatch):
    # a read-only (or immutable) --out folder under --force: was "[Errno 1] Operation not
    # permitted: 'o' -> 'o/../.o.partial-PID/replaced'", exit code 1
    from shtaerman.output import files

    out = tmp_path / "o"
    with files.staged_folder(out) as stage:
        (stage / "table.csv").write_text("old\n")
    rename = files.os.rename

    def refuse(source, destination):
        if Path(source) == out:
            raise PermissionError(1, "Operation not permitted", str(source))
        return rename(source, destination)

    monkeypatch.setattr(files.os, "rename", refuse)
    with pytest.raises(InputError) as refused:
        with files.staged_folder(out, force=True, option="--out"):
            pytest.fail("the run started on a folder it cannot replace")
    said = str(refused.value)
    assert said.startswith(f"--out: cannot replace '{out}' (Operation not permitted)"), said
    assert (out / "table.csv").read_text() == "old\n"  # the old folder is whole
    assert [path.name for path in tmp_path.iterdir()] == ["o"]  # and no stage is left


def test_a_forced_sweep_onto_a_folder_it_cannot_move_is_refused_before_its_cluster(
    tmp_path, monkeypatch, capsys
):
    # an immutable (chattr +i) sweep folder under --force: the run started, then said
    # "Operation not permitted ...; the finished cases are saved in ...: complete the sweep
    # with --resume", advice that does not apply to a folder nothing can be written in
    import sweep_probe  # noqa: F401  (registers the kind "probe")

    sweep = tmp_path / "p.toml"
    sweep.write_text('name = "p"\nkind = "probe"\n[axes]\nx = [1.0]\n')
    out = tmp_path / "out"
    assert main(["sweep", str(sweep), "--out", str(out), "--workers", "1"]) == 0
    before = sorted(path.name for path in out.iterdir())
    make = os.mkdir

    def immutable(path, *args, **kwargs):
        if Path(path).parent == out:
            raise PermissionError(1, "Operation not permitted", str(path))
        return make(path, *args, **kwargs)

    monkeypatch.setattr(os, "mkdir", immutable)
    capsys.readouterr()
    assert main(["sweep", str(sweep), "--out", str(out), "--force", "--workers", "1"]) == 2
    said = capsys.readouterr().err.strip()
    assert said.endswith(f"--out: cannot write in '{out}' (Operation not permitted)"), said
    assert "\n" not in said  # one line
    assert sorted(path.name for path in out.iterdir()) == before  # the old sweep is whole
