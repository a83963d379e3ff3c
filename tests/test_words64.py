"""A scale of the exact impact that is NaN (p_c = P_c / a_c^2 where both left the floats)
was shown as 'p_c = nan', as if the number were a result (session 62's user)."""

import pytest

from shtaerman.cli import main


def test_a_nan_scale_is_said_to_be_a_ratio_of_scales_outside_the_floats(capsys):
    argv = ["--velocity", "1e-95", "--mass", "1e-300", "--shape-coefficient", "1e100"]
    assert main(["dynamic", *argv, "--E2", "1e100", "--density2", "1e-6", "--no-estimate"]) == 2
    said = capsys.readouterr().err
    assert "would give p_c = nan (a ratio of scales that both leave the floats)," in said, said
    # the remedy it names is the velocity at which every scale is a float (theory.impact._passing)
    assert said.count("\n") == 1 and "raise --velocity to at least about 1.12e-08 m/s" in said


@pytest.mark.parametrize(
    "text, named",
    [
        ("tau,g\n1e-3,0.3\n1e-2,nan\n", "line 3, column g: must lie in [0, 1), got nan"),
        ("tau,E\ninf,1e6\n1e-3,-2e6\n", "line 3, column E: must be a finite number >= 0 Pa, got"),
    ],
)
def test_a_bad_value_in_a_prony_file_is_named_by_its_row(tmp_path, capsys, text, named):
    """A g column's NaN read 'prony weight g2 must lie in [0, 1), got nan', an E column's
    negative modulus 'E1 must be a finite number >= 0 Pa', naming neither the file nor its
    row, where a bad tau names both (session 64's users)."""
    path = tmp_path / "gnan.csv"
    path.write_text(text)
    assert main(["dynamic", "--prony", str(path), "--no-estimate"]) == 2
    said = capsys.readouterr().err
    assert f"gnan.csv: {named}" in said, said


def test_a_study_run_that_radiates_nothing_reflects_nothing(monkeypatch):
    """A dynamic study at 0.001 m/s FAILed 'reflected energy v0 = 0.001 m/s: nan' (session 64's
    user): its reflected share is 0/0 of a radiated energy of round-off, which the API and the
    CLI count as none (loader.NEGLIGIBLE_REFLECTION); the study's checks now do too."""
    import math
    from types import SimpleNamespace

    from shtaerman.study.dynamic import runner
    from shtaerman.study.dynamic.loader import DynamicTolerances

    monkeypatch.setattr(runner, "first_order_applies", lambda study: False)
    half_space = SimpleNamespace(thickness=None)  # the half-space: reflected of the radiated
    study = SimpleNamespace(
        tolerances=DynamicTolerances(), finite=False, density=1100.0, geometry=half_space
    )
    quiet = SimpleNamespace(
        energy_balance_error=1e-4, reflected_energy_fraction=math.nan, energy_radiated_fraction=1e-9
    )
    loud = SimpleNamespace(
        energy_balance_error=1e-4, reflected_energy_fraction=0.5, energy_radiated_fraction=0.2
    )
    cases = [SimpleNamespace(velocity=v, result=r) for v, r in ((0.001, quiet), (3.0, loud))]
    checks = {check.name: check.passed for check in runner._checks(study, cases)}
    assert checks["reflected energy v0 = 0.001 m/s"]  # nothing radiated: nothing to reflect
    assert not checks["reflected energy v0 = 3 m/s"]  # a real reflection still fails


@pytest.mark.parametrize("text", ["tau,g\n", "tau,E\ninf,1e6\n"])
def test_a_prony_file_without_terms_is_refused(tmp_path, capsys, text):
    """A header-only file crashed `prony-plot` (min() of an empty sequence) and ran `dynamic`
    as the elastic body, saying nothing (session 64's user); an E file holding only E_inf too."""
    path = tmp_path / "empty.csv"
    path.write_text(text)
    plot = ["prony-plot", str(path), "--out", str(tmp_path / "p.png")]
    for command in (plot, ["dynamic", "--prony", str(path), "--no-estimate"]):
        assert main(command) == 2
        said = capsys.readouterr().err
        assert "empty.csv: holds no term" in said and said.count("\n") == 1, said
