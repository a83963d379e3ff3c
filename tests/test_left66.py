"""What adv66's trial left (session 66, left66): a sweep's resume line keeps its options; a
sweep's Prony file is read at load."""

import shlex
import signal

import pytest

from shtaerman.cli import main
from shtaerman.sweep.spec import SweepError, parse_sweep

GRID = 'name = "g"\nkind = "impact"\n[axes]\nvelocity = [1.0, 2.0]\n'
AXIS = 'prony = ["0.5:1e-3", "no.csv"]'


def test_an_interrupted_sweep_on_one_worker_resumes_on_one_worker(tmp_path, capsys, monkeypatch):
    """The resume line dropped ``--workers 1`` (adv66); the line given completes the sweep."""
    from shtaerman.sweep import engine

    sweep, out = tmp_path / "g.toml", tmp_path / "out"
    sweep.write_text(GRID)
    real = engine._compute

    def interrupted(spec, out, ready, *args):
        ready()
        raise engine.SweepInterrupted(signal.SIGTERM)

    monkeypatch.setattr(engine, "_compute", interrupted)
    argv = ["sweep", str(sweep), "--out", str(out), "--workers", "1"]
    assert main(argv) == 128 + signal.SIGTERM
    said = capsys.readouterr().err
    command = said.rstrip("\n").split("resume with: ")[1]
    assert command == f"shtaerman sweep {sweep} --out {out} --resume --workers 1"
    monkeypatch.setattr(engine, "_compute", real)
    assert main(shlex.split(command)[1:]) == 0
    assert "(2 computed on 1 worker)" in capsys.readouterr().out


@pytest.mark.parametrize(
    ("parameters", "axes", "key"),
    [('prony = "no.csv"', "nu2 = [0.3]", "parameters.prony"), ("", AXIS, "axes.prony[1]")],
)
def test_a_bad_prony_file_is_refused_at_load_naming_its_key_as_a_profile_is(
    tmp_path, monkeypatch, parameters, axes, key
):
    """It was refused by the check of its first case, "case 0 (nu2 = 0.3): prony: cannot
    read ..." (adv66); now by its key, in the words of a profile's ("parameters.profile:
    cannot read '...': No such file or directory"), the path it looked at (adv67: a sweep
    text without a file is read from the working directory)."""
    monkeypatch.chdir(tmp_path)
    text = f'name = "p"\nkind = "contact"\n[parameters]\n{parameters}\n[axes]\n{axes}\n'
    with pytest.raises(SweepError) as error:
        parse_sweep(text)
    looked = str(tmp_path.resolve() / "no.csv")
    said = f"<sweep>: {key}: cannot read {looked!r}: No such file or directory ("
    assert str(error.value).startswith(said)


def test_a_profile_file_s_every_refusal_names_the_file_first(tmp_path):
    """A bad table said "profile: needs at least 3 rows (r, z), got 2 (in 'f.csv')" but a bad
    row "profile: 'f.csv' line 3, column r: missing": the file first in both now."""
    from shtaerman.theory.profiles import TabulatedIndenter
    from shtaerman.validation import InputError

    table = tmp_path / "f.csv"
    table.write_text("r,z\n0,0\n1e-3,1e-4\n")
    with pytest.raises(InputError) as error:
        TabulatedIndenter.from_csv(table)
    assert str(error.value) == f"profile: {str(table)!r}: needs at least 3 rows (r, z), got 2"
