"""A scale of the exact impact that is NaN (p_c = P_c / a_c^2 where both left the floats)
was shown as 'p_c = nan', as if the number were a result (session 62's user)."""

from shtaerman.cli import main


def test_a_nan_scale_is_said_to_be_a_ratio_of_scales_outside_the_floats(capsys):
    argv = ["--velocity", "1e-95", "--mass", "1e-300", "--shape-coefficient", "1e100"]
    assert main(["dynamic", *argv, "--E2", "1e100", "--density2", "1e-6", "--no-estimate"]) == 2
    said = capsys.readouterr().err
    assert "would give p_c = nan (a ratio of scales that both leave the floats)," in said, said
    # the remedy it names is the velocity at which every scale is a float (theory.impact._passing)
    assert said.count("\n") == 1 and "raise --velocity to at least about 1.12e-08 m/s" in said
