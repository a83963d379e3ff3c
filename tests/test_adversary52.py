"""Session 52's new-user and adversary pass over main (e585a17): what it found, fixed."""

import json
import types

import pytest

import shtaerman as sh
from shtaerman.fem.stepper import _step_failure
from shtaerman.guards import MAX_DEPTH_RATIO, depth_ratio

PAD_STRIKER = sh.PowerLawIndenter(shape_coefficient=8.0, exponent=1.3)  # issue 28's A = 8


@pytest.mark.parametrize("reached", [2.518e-3, 1e-4])
def test_an_inertial_step_failure_offers_the_massless_impact_only_within_its_reach(reached):
    """Issue 28's case on the 12 mm pad (neo-Hookean, density2 1000, mesh-size 0.2) failed at
    t = 1.7 ms, x = 2.518 mm (x/a 1.88) with 'other time steps may help ... density2=0 gives
    the massless finite-strain impact': no option named, and the massless impact refuses
    this striker beyond x/a 1.2 (guards.check_reach), so the remedy sent to a refusal."""
    # an inertial frictionless stepper on a rubber that never locked (no Gent crossing)
    watch = types.SimpleNamespace(crossed=None)
    stepper = types.SimpleNamespace(indenter=PAD_STRIKER, watch=watch)
    said = str(_step_failure(stepper, (1.7e-3, reached, reached), RuntimeError("Newton")))
    assert "time_steps=..." in said, said
    beyond = depth_ratio(PAD_STRIKER, reached) > MAX_DEPTH_RATIO  # x/a 1.88 and 0.89
    assert ("density2=0 gives the massless" in said) is not beyond, said
    if beyond:
        assert "x/a = 1.88, beyond the 1.2 of the massless impact" in said, said
        assert "velocity=..." in said and "shape_coefficient=..." in said, said


def test_a_material_of_an_array_modulus_is_refused_in_one_line():
    """``sh.Material(youngs_modulus=np.array([3e6, 1e6]), ...)`` raised NumPy's 'truth value
    of an array ... is ambiguous' ValueError (the rigid test compared the array with inf);
    poisson_ratio and density as arrays were already refused by name."""
    import numpy as np

    from shtaerman.validation import InputError

    with pytest.raises(InputError, match=r"^youngs_modulus must be a finite number > 0 Pa"):
        sh.Material(youngs_modulus=np.array([3e6, 1e6]), poisson_ratio=0.49)
    assert sh.Material(youngs_modulus=np.float64(np.inf), poisson_ratio=0.3).compliance == 0.0


def test_the_low_side_reach_refusal_is_one_sentence_on_contact_and_dynamic(capsys):
    """z = 5 r^3 at 0.7 kg and 1e-13 m/s: x_c 7.9e-15 m, x/a 9e-10, below the 1e-6 the
    finite-strain models resolve. `dynamic` said guards.check_reach's sentence ('0.7 kg at
    1e-13 m/s drive the striker to 7.89e-15 m only ...'), `contact` its own ('the depths
    reach the x_c of ... and 2.92174e-16 m gives depth / contact radius 1e-10'): the brief's
    known wording item; now the one sentence, the curve adding its remedy, its depths."""
    from shtaerman.cli import main

    striker = ["--model", "neo-hookean", "--exponent", "3", "--velocity", "1e-13"]
    said = []
    for command in (["dynamic", "--density2", "0"], ["contact", "--no-estimate"]):
        assert main([*command, *striker]) == 2
        out, err = capsys.readouterr()
        assert out == "" and err.count("\n") == 1, err  # one line, no traceback
        said.append(err.removeprefix("shtaerman: error: ").rstrip("\n"))
    dynamic, contact = said
    head = "--mass, --velocity: 0.7 kg at 1e-13 m/s drive the striker to 7.89e-15 m only"
    assert dynamic.startswith(head), dynamic
    assert contact.startswith(dynamic), contact  # the curve may add its remedy, its depths


def test_a_force_history_fit_on_a_pad_without_density2_runs_massless_fe_impacts(
    tmp_path, monkeypatch
):
    """`fit force-history DATA --thickness 0.012` (no --density2, whose help says 'unset: no
    waves') stopped at its first FE correction with the Python API's 'density: the dynamic
    impact needs the body's density ... e.g. Material(youngs_modulus, poisson_ratio,
    density=1100.0)', which names no option of `fit`; the FE impact is now the massless one.
    The FE run is replaced by a recorder: what it is given is what is asserted."""
    from shtaerman.api import fem_dynamic
    from shtaerman.cli import main

    class ReachedError(Exception):
        pass

    given = []

    def recorder(problem, **options):
        given.append(problem.body.material.density)
        raise ReachedError

    monkeypatch.setattr(fem_dynamic, "dynamic", recorder)
    data = tmp_path / "fh.csv"
    data.write_text("time [s],force [N]\n0,0\n1e-3,10\n2e-3,0\n")
    striker = ["--exponent", "1.3", "--shape-coefficient", "8", "--mass", "0.12"]
    with pytest.raises(ReachedError):
        main(["fit", "force-history", str(data), *striker, "--velocity", "1.5",
              "--E2", "3e6", "--nu2", "0.49", "--thickness", "0.012"])  # fmt: skip
    assert given == [0.0]  # massless: no waves, as --density2's help says of it unset


def test_a_fits_fe_refine_refusal_offers_no_option_fit_lacks(tmp_path, capsys):
    """`fit indentation DATA --model neo-hookean --refine 0.3` ended '...; or run without the
    estimate (--no-estimate)', an option `fit` does not have (its FE runs always estimate):
    now the refusal ends at the refine it needs (0.6 on the finite-strain contact's mesh)."""
    from shtaerman.cli import main

    data = tmp_path / "ok.csv"
    data.write_text("depth [m],force [N]\n1e-4,0.5\n2e-4,1.5\n3e-4,3\n")
    striker = ["--exponent", "1.3", "--shape-coefficient", "8", "--E2", "3e6", "--nu2", "0.49"]
    argv = ["fit", "indentation", str(data), *striker, "--model", "neo-hookean"]
    assert main([*argv, "--fit", "E2", "--refine", "0.3"]) == 2
    err = capsys.readouterr().err.strip().splitlines()[-1]
    assert err.startswith("shtaerman: error: --refine must be >= 0.6"), err
    assert "estimate" not in err.split("), got")[-1], err  # nothing after the value it got


def test_a_sweeps_existing_folder_is_refused_in_each_routes_words(tmp_path, capsys):
    """Running docs/tutorials/sweep.py twice in one folder stopped on 'out: folder ...
    exists; use --resume to complete it or --force to replace it': options, in Python
    (sh.sweep takes resume=True, force=True). Each route now reads its own spelling; the
    folder is refused before any cluster starts."""
    from shtaerman.cli import main

    spec = tmp_path / "s.toml"
    spec.write_text('name = "s"\nkind = "impact"\n[axes]\nvelocity = [1.0, 2.0]\n')
    from shtaerman.sweep.engine import MARKER_FILE, MARKER_FORMAT

    out = tmp_path / "run"
    out.mkdir()
    (out / "cases").mkdir()  # a sweep's folder, as the first run left it (adv53: a folder
    (out / MARKER_FILE).write_text(json.dumps({"format": MARKER_FORMAT}))  # no sweep wrote
    with pytest.raises(sh.InputError) as caught:  # is refused naming --out, see test_sweep)
        sh.sweep(str(spec), out=str(out), workers=1)
    said = str(caught.value)
    assert said.endswith("use resume=True to complete it or force=True to replace it"), said
    assert main(["sweep", str(spec), "--out", str(out), "--workers", "1"]) == 2
    err = capsys.readouterr().err
    assert err.endswith("use --resume to complete it or --force to replace it\n"), err
    assert err.startswith("shtaerman: error: --out: folder") and err.count("\n") == 1, err


def test_a_study_key_of_any_characters_is_refused_as_an_unknown_key(tmp_path, capsys):
    """A quoted TOML key of non-word characters ('"[half_space]" = 1' under [indenter]) fell
    through to msgspec's own words: "expected Object contains unknown field [half_space],
    got {...}"; now the unknown-key refusal every other key gets."""
    from shtaerman.cli import main

    study = tmp_path / "s.toml"
    study.write_text(
        'kind = "contact"\n[indenter]\nshape_coefficient = 5.0\nexponent = 1.5\n'
        '"[half_space]" = 1\n'
    )
    assert main(["verify", str(study), "--quick", "--out", str(tmp_path / "o")]) == 2
    err = capsys.readouterr().err
    head = f"shtaerman: error: {study}: key 'indenter.[half_space]': expected one of ["
    assert err.startswith(head) and err.endswith("(unknown key)\n"), err
    assert "Object contains" not in err and err.count("\n") == 1, err


def test_a_folder_given_as_a_sweep_file_is_named_a_folder(tmp_path, capsys):
    """``shtaerman sweep /tmp`` said "no file '/tmp'" of a folder that exists."""
    from shtaerman.cli import main

    assert main(["sweep", str(tmp_path)]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and f"{str(tmp_path)!r} is a folder" in err, err
