"""One refusal in one wording on every entry point (session 50's adversary): the finite-strain
reach of an impact's depth, said by `contact` and `dynamic`, the API and the file routes."""

import pytest

import shtaerman as sh
from shtaerman.cli import main

RUBBER = ["--model", "neo-hookean"]


def _refusal(capsys, argv):
    assert main(argv) == 2
    out, err = capsys.readouterr()
    assert out == "" and err.count("\n") == 1, err
    return err.removeprefix("shtaerman: error: ").rstrip("\n")


@pytest.mark.parametrize(
    "striker, head",
    [
        # z = 50 r^1.5 at the paper's 0.7 kg, 3 m/s: x/a 4.96; the paper's A = 5 reaches 0.88
        (
            ["--shape-coefficient", "50"],
            "--shape-coefficient, --mass, --velocity: the striker z = 50 r^1.5",
        ),
        # the paper's striker at 30 m/s: x/a 1.57, as its A = 5 would too: the impact's fault
        (["--velocity", "30"], "--mass, --velocity: 0.7 kg at 30 m/s drive the striker"),
    ],
)
def test_the_reach_refusal_is_one_sentence_on_contact_and_dynamic(capsys, striker, head):
    """`contact` named --mass/--velocity ('the depths reach the x_c ...') where `dynamic`
    named --shape-coefficient for the same x_c; now the one rule (guards.check_reach), the
    curve adding its own remedy, its --depths."""
    dynamic = _refusal(capsys, ["dynamic", *RUBBER, *striker])
    contact = _refusal(capsys, ["contact", *RUBBER, *striker, "--no-estimate"])
    assert dynamic.startswith(head), dynamic
    # the lighter mass that reaches x/a 1.2 at 30 m/s radiates above the wave-speed limit, which
    # the impact with inertia keeps to since session 59 and the static curve has not
    lighter = ", or --mass to at most about 0.0816 kg" if "--velocity" in striker else ""
    assert contact == dynamic + lighter + ", or, instead of --mass and --velocity, give --depths"


def test_the_reach_refusal_names_keywords_in_the_api():
    """The API's words: the parameter at fault heads the line (a striker's field as the API
    spells it), the others as name=..."""
    with pytest.raises(
        sh.InputError,
        match=r"^PowerLawIndenter\(shape_coefficient=\.\.\.\), mass, velocity: the striker z = 50",
    ) as caught:
        sh.contact(sh.PowerLawIndenter(50.0, 1.5), sh.Material(7.5e6, 0.5), model="neo-hookean")
    assert caught.value.parameter == "shape_coefficient"
    assert "(shape_coefficient=5)" in str(caught.value) and "give depths=..." in str(caught.value)
    with pytest.raises(sh.InputError, match=r"^mass, velocity: 0.7 kg at 30 m/s") as caught:
        sh.contact(
            sh.PowerLawIndenter(5.0, 1.5),
            sh.Material(7.5e6, 0.5),
            model="neo-hookean",
            velocity=30.0,
        )
    assert "lower velocity=... to at most about 10.2 m/s" in str(caught.value)


def test_an_unreachable_accuracy_names_each_routes_options(capsys):
    """`--accuracy` said '--max-time', '--accuracy' to the API and 'refine' to the command line;
    each route now reads its own spelling. 1e-4 on the coarsest mesh (0.2) needs ~100 s more
    than the 1 s left after its first three levels (estimated error 3.7e-4 at 27k dofs)."""
    coarse = ["--mesh-size", "0.2", "--max-time", "1"]
    said = _refusal(capsys, ["contact", "--accuracy", "1e-4", *coarse])
    assert said.startswith("--accuracy 0.0001 needs about"), said
    assert said.endswith("above what --max-time leaves; raise it or loosen --accuracy"), said
    with pytest.raises(sh.InputError, match=r"max_time=\.\.\. leaves; raise it or loosen accur"):
        sh.contact(
            sh.PowerLawIndenter(5.0, 1.5),
            sh.Material(7.5e6, 0.5),
            accuracy=1e-4,
            mesh_size=0.2,
            max_time=1.0,
        )


@pytest.mark.parametrize(
    "key, table, value, option",
    [
        ("mass", "impact", "-1.0", "-1"),
        ("mass", "impact", "inf", "inf"),
        ("E2", "half_space", "-3.0", "-3"),
        ("velocity", "impact", "0.0", "0"),
    ],
)
def test_a_study_file_refuses_a_number_in_the_command_lines_words(
    tmp_path, capsys, key, table, value, option
):
    """A study file said "expected a number > 0 (kg)" (E2: "> 0") where the command line said
    "--mass must be > 0 kg" (E2: "must lie in [1e-3, 1e100] Pa"): both are the vocabulary's
    Entry.check now, the file naming its key, the command line its option."""
    study = tmp_path / "s.toml"
    assert main(["init-study", str(study)]) == 0
    lines = study.read_text().splitlines()
    study.write_text(
        "\n".join(f"{key} = {value}" if line.startswith(f"{key} =") else line for line in lines)
    )
    capsys.readouterr()
    filed = _refusal(capsys, ["verify", str(study), "--quick", "--out", str(tmp_path / "o")])
    typed = _refusal(capsys, ["contact", f"--{key}", option])
    verdict = typed.split(" must", 1)[1].rsplit(", got ", 1)[0]  # the range and unit
    assert filed == f"{study}: key '{table}.{key}': {key} must{verdict}, got {float(value)!r}"
    assert typed == f"--{key} must{verdict}, got '{option}'"


def test_a_tolerance_named_like_an_input_is_a_tolerance(tmp_path, capsys):
    """tolerances.exponent = 2 was refused as "a number in [0.25, 20]", the striker's n."""
    study = tmp_path / "s.toml"
    assert main(["init-study", str(study)]) == 0
    study.write_text(study.read_text().replace("exponent = 1e-3", "exponent = 2.0"))
    capsys.readouterr()
    said = _refusal(capsys, ["verify", str(study), "--quick", "--out", str(tmp_path / "o")])
    assert said.endswith(
        "key 'tolerances.exponent': expected a relative tolerance in (0, 1], got 2.0"
    )


def test_a_finite_strain_sweep_refuses_prony_for_its_physical_reason(tmp_path, capsys):
    """`prony` was "unknown parameter 'prony' for kind 'finite-strain'"; a Prony curve at
    finite strain is refused by the problem's support table, in the command line's words."""
    sweep = tmp_path / "s.toml"
    sweep.write_text(
        'name = "s"\nkind = "finite-strain"\n[parameters]\nmesh_size = 0.2\n'
        'prony = "0.3:1e-3"\nrate = 0.1\n[axes]\nvelocity = [1.0, 2.0]\n'
    )
    filed = _refusal(capsys, ["sweep", str(sweep), "--out", str(tmp_path / "o")])
    typed = _refusal(capsys, ["contact", *RUBBER, "--prony", "0.3:1e-3", "--rate", "0.1"])
    reason = "a contact curve at finite strain is elastic (the finite-strain contact solver "
    assert filed.startswith(f"{sweep}: parameters.prony: {reason}"), filed
    assert typed.startswith(f"--prony: {reason}"), typed
    # a finite-strain case has no model = "linear" (its kind refuses it): the linear curve,
    # which takes prony, is the contact kind (session 52: the sweep's words offered model)
    assert filed.endswith('or sweep kind = "contact" (linear)'), filed
    assert 'model = "linear"' not in filed and typed.endswith("or take --model linear")
    assert not (tmp_path / "o").exists()  # refused at load, before any case


def test_a_contact_curves_failed_load_step_names_its_options(capsys, monkeypatch):
    """The static curve on a 4 mm Gent pad (session 50's failing impact, as a curve) ended in
    'depth 0.00228344 m (from 0.00228344 m): ... refine the mesh or give more depths': the
    same depth twice (the step, 1/256 of the first, below :g's digits) and no option named.
    A stepper whose Newton always fails stands in for the 11-minute run."""
    import types

    import numpy as np

    from shtaerman.fem.contact import finite
    from shtaerman.fem.hyperelastic import NewtonError

    class Failing:
        system = types.SimpleNamespace(
            material=types.SimpleNamespace(model="gent"),
            state=lambda x: types.SimpleNamespace(J=np.ones(4)),  # nothing squeezed
        )
        nodes = types.SimpleNamespace(radius=np.array([0.0, 1e-3]))

        def solve(self, *args, **kwargs):
            raise NewtonError("Newton did not converge in 30 iterations")

    monkeypatch.setattr(finite, "gent_locks", lambda *args, **kwargs: None)  # not locked
    history = [(0.0022, np.zeros(2), np.zeros(2))]
    with pytest.raises(NewtonError) as caught:
        finite._reach(Failing(), history, 0.0024, max_cuts=8)
    said = str(caught.value)
    # 2e-4 m halved 8 times: 7.8125e-7 m, the step from 0.0022 m that failed last
    assert said.startswith("depth 0.00220078 m (a load step of 7.81e-07 m from 0.0022 m"), said
    assert "mesh_size=..." in said and "depths=..." in said
    from shtaerman.cli import common
    from shtaerman.validation import NumericalFailureError

    with pytest.raises(NumericalFailureError) as caught, common.in_option_words():  # the CLI's
        finite._reach(Failing(), history, 0.0024, max_cuts=8)
    assert "lower the deepest of --depths (a finer --mesh-size or --refine helps" in str(
        caught.value
    )


def test_a_massless_impacts_failed_depth_does_not_ask_for_more_time_steps():
    """`dynamic --model gent --gent-limit 30 --thickness 0.004 --density2 0` (mass 0.7 kg at
    3 m/s, mesh 0.2) failed at 2.32 mm with 40 time steps (session 50) and with 50 (here): a
    massless body follows the static curve, whose own run fails at 2.28 mm (mesh 0.2) and
    2.28 mm (mesh 0.1); the advice said 'more time_steps=...' first. A failing stepper stands
    in for the 9-minute run."""
    import types

    import numpy as np

    from shtaerman.fem.hyperelastic import NewtonError
    from shtaerman.fem.stepper import QuasiStaticBody
    from shtaerman.validation import NumericalFailureError

    def fails(*args):
        raise NewtonError("Newton did not converge in 30 iterations")

    material = types.SimpleNamespace(model="neo-hookean")  # no Gent lock to diagnose
    system = types.SimpleNamespace(n_dofs=4, material=material)
    nodes = types.SimpleNamespace(radius=np.zeros(2))
    stepper = types.SimpleNamespace(system=system, nodes=nodes, solve=fails)
    with pytest.raises(NumericalFailureError) as caught:
        QuasiStaticBody(stepper).at(2.32e-3)
    said = str(caught.value)
    assert said.startswith("the finite-strain contact failed at depth 0.00232 m (Newton"), said
    assert "(more time_steps=... do not move it): a lower velocity=..." in said, said
    assert "a thicker thickness=..." in said


def test_a_rubber_curve_at_a_rate_is_refused_for_its_reason_not_sent_to_prony(capsys):
    """A rate without prony said 'give --prony too', which a rubber's curve then refuses
    ('a contact curve at finite strain is elastic'): the refusal gives that reason at once;
    the linear curve still asks for prony."""
    rubber = _refusal(capsys, ["contact", *RUBBER, "--rate", "0.1"])
    assert rubber.startswith("--rate: applies to a viscoelastic body only"), rubber
    assert "a contact curve at finite strain is elastic" in rubber and "--prony" not in rubber
    linear = _refusal(capsys, ["contact", "--rate", "0.1"])
    assert linear.endswith("give --prony too"), linear
