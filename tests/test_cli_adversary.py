"""Variants of issue 31's attacks (its "hidden battery"): each asserts the outcome the issue
asks for on a route the first fixes did not cover."""

import shtaerman.cli as cli

QUICK = ["--mesh-size", "0.2", "--time-steps", "60", "--no-estimate"]


def test_effects_refuses_a_layer_rate_of_zero_on_a_pad_before_any_run(capsys):
    """Item 15 on 'effects': the full impact of '--thickness 0.02 --layer-rate 0' is what
    'dynamic' refuses; effects ran three variants (20 s), put the refusal in the full row and
    exited 0 ('pad alone' is massless, where the rate does not apply)."""
    code = cli.main(["effects", *QUICK, "--thickness", "0.02", "--layer-rate", "0"])
    err = capsys.readouterr().err
    assert code == 2, err
    assert err.startswith("shtaerman: error: --layer-rate: ") and err.count("\n") == 1, err


def test_an_effects_sweep_refuses_a_layer_rate_of_zero_on_a_pad_at_load(tmp_path, capsys):
    """Item 11 on the effects kind: every case is checked at load. The same case ran on the
    workers and failed both cases (exit 1), after their start."""
    study = tmp_path / "pad.toml"
    study.write_text(
        'name = "pad"\nkind = "effects"\n[parameters]\nmesh_size = 0.2\ntime_steps = 60\n'
        "thickness = 0.02\nlayer_rate = 0.0\n[axes]\nvelocity = [3.0, 2.0]\n"
    )
    code = cli.main(["sweep", str(study), "--workers", "1", "--out", str(tmp_path / "out")])
    err = capsys.readouterr().err
    assert code == 2, err
    assert "layer_rate: a layer always has its lateral absorber" in err and err.count("\n") == 1
    assert not (tmp_path / "out").exists()
