"""Found by session 58's adversary (adv58) on the remedies the reach refusal names."""

from __future__ import annotations

from shtaerman.cli import main


def test_an_impact_that_radiates_nothing_prints_no_nan_reflection(capsys):
    # `dynamic --velocity 1e-300` names 4.95e-24 m/s; that run radiates nothing (0/0 reflected:
    # --json says null) and printed "reflected nan of the radiated"
    argv = ["dynamic", "--velocity", "4.95e-24", "--mesh-size", "0.2", "--time-steps", "50"]
    assert main([*argv, "--no-estimate"]) == 0
    out = capsys.readouterr().out
    assert "nan" not in out and "reflected n/a (nothing radiated)" in out, out


def test_verify_resume_on_a_sweeps_folder_says_it_is_a_sweeps(capsys, tmp_path):
    # it said "it was not written by shtaerman" of a folder `shtaerman sweep` wrote
    from shtaerman.output.files import SWEEP_MARKER

    folder = tmp_path / "swept"
    folder.mkdir()
    (folder / SWEEP_MARKER).write_text("{}")
    assert main(["verify", "paper", "--quick", "--resume", "--out", str(folder)]) == 2
    err = capsys.readouterr().err
    assert "it is the result of shtaerman sweep" in err and "not written by" not in err, err
    assert err.count("\n") == 1 and sorted(p.name for p in folder.iterdir()) == [SWEEP_MARKER]
