"""Session 53's new-user and adversary pass over main (025e43b): what it found, fixed."""

import math

import pytest

import shtaerman as sh
from shtaerman.cli import main
from shtaerman.validation import InputError

PAD_STRIKER = sh.PowerLawIndenter(shape_coefficient=8.0, exponent=1.3)  # issue 28's A = 8
RUBBER = sh.Material(youngs_modulus=3e6, poisson_ratio=0.49)


def test_an_overflowing_central_pressure_is_refused_not_printed_as_unbounded(capsys):
    """z = 1e308 r^1.3: a_c = 6.2e-174 m, whose square underflows to 0, so p_c = P_c /
    (pi a_c^2) came out inf; the impact printed 'p_c inf' with the note '(n <= 1: the pressure
    at the centre of the contact is unbounded)' for n = 1.3, and --json gave p_c null, where
    z = 1e-300 r^1.3 (p_c = 0) is refused by the floating-point range. inf is exact only for
    n <= 1 (the cone and sharper), which still gives it."""
    with pytest.raises(InputError, match=r"give p_c = inf, outside the floating-point range"):
        sh.impact(sh.PowerLawIndenter(shape_coefficient=1e308, exponent=1.3), RUBBER,
                  mass=0.12, velocity=1.5)  # fmt: skip
    cone = sh.impact(sh.PowerLawIndenter(shape_coefficient=8.0, exponent=1.0), RUBBER,
                     mass=0.12, velocity=1.5)  # fmt: skip
    assert math.isinf(cone.p_c)  # exact: the cone's central pressure is unbounded
    args = ["impact", "--exponent", "1.3", "--shape-coefficient", "1e308", "--mass", "0.12"]
    assert main(args) == 2
    out, err = capsys.readouterr()
    assert out == "" and err.count("\n") == 1 and "p_c = inf" in err, err
    # the striker's shape is the cause here: the line names the options that set the scale,
    # the shape first (adv53 again: it opened with the mass and velocity, naming no option)
    assert err.startswith("shtaerman: error: --shape-coefficient, --E2, --mass, --velocity: ")


def test_a_viscoelastic_curve_without_a_rate_names_the_option_on_the_command_line(capsys):
    """`contact --prony 0.3:1e-3` said '--rate: ... give rate > 0 m/s': the remedy named the
    keyword, not the option; Python keeps its keyword."""
    assert main(["contact", "--prony", "0.3:1e-3", "--no-estimate"]) == 2
    out, err = capsys.readouterr()
    assert out == "" and err.count("\n") == 1, err
    assert err.rstrip().endswith("is pressed at a speed: give --rate > 0 m/s"), err
    with pytest.raises(InputError, match=r"pressed at a speed: give rate=\.\.\. > 0 m/s$"):
        sh.Problem.curve(PAD_STRIKER, RUBBER, depths=[1e-3], prony="0.3:1e-3")


@pytest.mark.parametrize(
    ("edit", "key"),
    [
        ("[numerics]\nmesh_size = 0.5", "numerics.mesh_size"),  # overridden by [quick]'s 0.2
        ("[numerics]\nmesh_size = 0.1\n[quick]\nmesh_size = 0.3", "quick.mesh_size"),
        ("[quick]\ndomain_factor = 0.001", "quick.domain_factor"),
    ],
)
def test_an_effects_study_checks_its_numerics_and_quick_at_load(tmp_path, capsys, edit, key):
    """An effects study's [numerics] and [quick] were checked only when the table ran: under
    `verify --quick`, a [numerics] mesh_size = 0.5 that [quick] overrides was never refused
    (the full `verify` refused it at run, as "study 'x': mesh_size must lie ...", naming no
    key), and a bad [quick] key passed `verify` without --quick. Both are refused at load
    now, naming the file's key, with or without --quick (nothing runs: exit 2 at once)."""
    from shtaerman.study.schema import load_study

    study = tmp_path / "x.toml"
    assert main(["init-study", str(study), "--kind", "effects"]) == 0
    text = study.read_text()
    head = text[: text.index("[numerics]")] if "[numerics]" in text else text
    study.write_text(head + edit + "\n")
    capsys.readouterr()
    with pytest.raises(InputError, match=rf"^{study}: key '{key}': "):
        load_study(study)
    for quick in ([], ["--quick"]):
        assert main(["verify", str(study), *quick, "--out", str(tmp_path / "out")]) == 2
        out, err = capsys.readouterr()
        assert out == "", out
        assert err.count("\n") == 1 and f"key '{key}'" in err, err
        assert not (tmp_path / "out").exists()


def test_sweep_workers_with_a_scheduler_is_refused_with_one_option_head(capsys):
    """`sweep NAME --scheduler ADDRESS --workers 1` said 'workers: --workers sizes the local
    cluster; ...': the keyword's head before the option's (the sweep's command line does not
    pass its refusals through shtaerman.problem.worded)."""
    args = ["sweep", "impact-velocity", "--scheduler", "tcp://nowhere:1", "--workers", "1"]
    assert main(args) == 2
    out, err = capsys.readouterr()
    said = "shtaerman: error: --workers: sizes the local cluster; drop it with --scheduler\n"
    assert out == "" and err == said, err


@pytest.mark.parametrize("given", [None, PAD_STRIKER, "curve"])
def test_sh_effects_of_no_impact_is_refused_by_name(given):
    """`sh.effects(None)` and `sh.effects(indenter)` raised the internal "Problem() argument
    after ** must be a mapping, not NoneType", and `sh.effects(Problem.curve(...))` "mass must
    be a finite number > 0 kg, got None" (a curve has none): `sh.dynamic` names the problem
    in both cases, and so does `sh.effects` now."""
    if given == "curve":
        given = sh.Problem.curve(PAD_STRIKER, RUBBER, depths=[1e-3])
        said = r"^problem: effects\(\) runs an impact \(Problem.impact\), not a curve$"
    else:
        said = rf"^problem must be a Problem .* got {type(given).__name__}$"
    with pytest.raises(InputError, match=said):
        sh.effects(given)


def test_effects_out_says_where_the_table_is(tmp_path, capsys):
    """`effects --out DIR` printed the table and no word of the folder (verify and sweep end
    with a 'results:' line): after an interrupted `--force` run, the printed `--resume`
    completes the table in DIR.incomplete-PID, and nothing said that it lands there, not in
    DIR. One line on stderr names the folder and its files (stdout stays the table or JSON).
    The massless half-space with Prony (one effect: two runs, the coarsest numerics)."""
    out = tmp_path / "t"
    argv = ["effects", "--exponent", "1.3", "--shape-coefficient", "8", "--E2", "3e6"]
    argv += ["--nu2", "0.49", "--mass", "0.12", "--velocity", "1.5", "--density2", "0"]
    argv += ["--prony", "0.3:1e-3", "--mesh-size", "0.2", "--time-steps", "50"]
    assert main([*argv, "--no-estimate", "--json", "--out", str(out)]) == 0
    printed, err = capsys.readouterr()
    assert printed.lstrip().startswith("{") and printed.rstrip().endswith("}")
    said = f"shtaerman: the table is in {out}: effects.csv, effects.json, effects.md, effects.png"
    assert said in err.splitlines(), err


def test_effects_out_stopped_while_writing_keeps_its_runs(tmp_path, capsys, monkeypatch):
    """SIGTERM (or Ctrl-C) after the last run, while `effects --out` wrote its files, said
    'terminated; every output is complete or absent (nothing partial is kept)' and removed
    the folder with every finished run (8 runs of issue 28's pad, 26 s here): the runs were
    kept on disk only until the table was computed. Now they stay, as for a stop between
    runs, and --resume writes the table without running any again."""
    import shtaerman.cli.effects as cli_effects

    out = tmp_path / "t"
    argv = ["effects", "--exponent", "1.3", "--shape-coefficient", "8", "--E2", "3e6"]
    argv += ["--nu2", "0.49", "--mass", "0.12", "--velocity", "1.5", "--density2", "0"]
    argv += ["--prony", "0.3:1e-3", "--mesh-size", "0.2", "--time-steps", "50"]
    argv += ["--no-estimate", "--out", str(out)]

    def stopped(*_args, **_kwargs):
        raise KeyboardInterrupt

    monkeypatch.setattr(cli_effects, "write_table", stopped)
    assert main(argv) == 130
    err = capsys.readouterr().err
    said = next(line for line in err.splitlines() if line.startswith("shtaerman: interrupted"))
    assert "2 finished run(s) kept in" in said and said.endswith(f"--out {out} --resume"), err
    assert sorted(p.name for p in out.iterdir()) == [".shtaerman-folder.json", "incomplete.json"]
    monkeypatch.undo()
    assert main([*argv, "--resume"]) == 0
    err = capsys.readouterr().err
    assert err.count("kept from an earlier run") == 2 and " done in " not in err, err
    assert (out / "effects.json").is_file() and not (out / "incomplete.json").exists()


def test_the_guides_sweep_file_lists_every_sweep_kind():
    """The guide's sweep file comment `kind = "contact"  # contact | impact | dynamic |
    finite-strain | layer` left out `effects`, a registered sweep kind (a new user
    reading it could not know an effects sweep exists)."""
    import re
    from pathlib import Path

    from shtaerman.sweep import KINDS

    guide = (Path(__file__).parents[1] / "docs" / "guide.md").read_text(encoding="utf-8")
    listed = re.search(r'^kind = "contact" +# (.+)$', guide, re.M)[1].split(" | ")
    shipped = [
        name for name, kind in KINDS.items() if kind.case.__module__.startswith("shtaerman.")
    ]
    assert sorted(listed) == sorted(shipped), listed  # not a kind another test registered
