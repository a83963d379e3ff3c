"""What adv67's trial left (session 67): a sweep's Prony CSV is found from the sweep file's
folder, as its ``profile`` is and as a study's ``prony`` is from the study file's."""

import pytest

from shtaerman.sweep.spec import load_sweep

SWEEP = 'name = "p"\nkind = "contact"\n[parameters]\nrate = 0.1\n{fixed}\n[axes]\n{axes}\n'


@pytest.mark.parametrize(
    ("fixed", "axes", "read"),
    [
        ('prony = "series.csv"', "nu2 = [0.3]", lambda spec: spec.parameters["prony"]),
        ("", 'prony = ["0.5:1e-3", "series.csv"]', lambda spec: spec.axes["prony"][1]),
    ],
)
def test_a_sweep_s_prony_file_is_read_beside_the_sweep_file(
    tmp_path, monkeypatch, fixed, axes, read
):
    """The sweep in ``study/`` names ``series.csv`` beside it; run from another folder, it
    was read from there: "parameters.prony: cannot read 'series.csv': No such file or
    directory" (adv67). Its cases get the file's absolute path, as a ``profile``'s."""
    folder, elsewhere = tmp_path / "study", tmp_path / "elsewhere"
    folder.mkdir()
    elsewhere.mkdir()
    (folder / "series.csv").write_text("tau,g\n1e-3,0.3\n")
    (folder / "p.toml").write_text(SWEEP.format(fixed=fixed, axes=axes))
    monkeypatch.chdir(elsewhere)
    spec = load_sweep("../study/p.toml")
    assert read(spec) == str(folder.resolve() / "series.csv")
    assert spec.refused == {}  # every case's check read the series
