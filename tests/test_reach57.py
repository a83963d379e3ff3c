"""The reach refusal finished (session 57): a contact curve's depths set by an impact, refused
by one check (guards.check_profile_reach) in the words of each route."""

import ast
from pathlib import Path

SOURCE = Path(__file__).resolve().parents[1] / "src" / "shtaerman"


def test_the_profile_reach_is_a_guard_every_route_imports_from_guards():
    """It lived in study/contact/loader.py while the API, the sweeps and the finite-strain
    loader used it: each now imports it from guards, beside check_reach."""
    from shtaerman import guards

    assert guards.check_profile_reach.__module__ == "shtaerman.guards"
    importers = []
    for path in SOURCE.rglob("*.py"):
        for node in ast.walk(ast.parse(path.read_text(encoding="utf-8"))):
            if isinstance(node, ast.ImportFrom):
                if any(alias.name == "check_profile_reach" for alias in node.names):
                    importers.append((path.relative_to(SOURCE).as_posix(), node.module))
    # the API, a contact sweep, both study loaders, and the FE impact's check before its
    # exact impact (fem.impact.check_impact_reach: the dynamic route's, session 58)
    assert len(importers) == 5, importers
    assert all(module.endswith("guards") for _, module in importers), importers


def _study(tmp_path, shipped, *changes):
    """A shipped study file with ``changes`` ((old line start, new line)) and no [sweep]."""
    text = (SOURCE.parents[1] / "fem" / shipped).read_text().partition("\n[sweep]")[0]
    lines = text.splitlines()
    for start, line in changes:
        lines = [line if old.startswith(start) else old for old in lines]
    study = tmp_path / shipped
    study.write_text("\n".join(lines) + "\n")
    return study


def test_a_finite_strain_study_far_out_of_reach_names_the_finite_strain_limit(tmp_path):
    """A finite-strain study at 1e30 kg (x/a 5.4e3) was refused 'beyond the 100 up to which
    an FE impact is run', the linear FE's reach: its loader passed no finite flag, where the
    API names the finite-strain contact's 1.2 (9957c5f)."""
    import pytest

    from shtaerman.study.schema import StudyError, load_study

    study = _study(tmp_path, "finite_strain.toml", ("mass =", "mass = 1e30"))
    with pytest.raises(StudyError) as caught:
        load_study(study)
    said = str(caught.value)
    assert "beyond the 1.2 up to which the finite-strain contact converges" in said, said
    assert "the 100 " not in said, said


def _refusal(capsys, *argv):
    """The one line of a refused command (exit 2), without its 'shtaerman: error: '."""
    from shtaerman.cli import main

    assert main([str(arg) for arg in argv]) == 2
    out, err = capsys.readouterr()
    assert out == "" and err.count("\n") == 1, err
    return err.removeprefix("shtaerman: error: ").rstrip("\n")


def test_depths_are_offered_instead_of_the_impact_in_each_routes_words(capsys, tmp_path):
    """'..., or --mass, or give --depths' was read as 'as well', and `--velocity 1e30 --depths
    ...` is then refused 'give either --depths or --mass and --velocity': the remedy says
    'instead'. A finite-strain study file has no depths (its impact sets them), nor a layer
    sweep case: they are offered none."""
    import pytest

    from shtaerman.study.schema import StudyError, load_study
    from shtaerman.sweep.spec import SweepError, parse_sweep

    said = _refusal(capsys, "contact", "--mass", "1e30", "--no-estimate")
    instead = ", or, instead of --mass and --velocity, give --depths"
    assert said.endswith(" kg" + instead), said
    contact = _study(tmp_path, "hertz.toml", ("mass =", "mass = 1e30"))
    with pytest.raises(StudyError) as caught:
        load_study(contact)
    instead = "or, instead of [impact] mass and [impact] velocity, give [contact] depths"
    assert str(caught.value).endswith(instead), caught.value
    finite = _study(tmp_path, "finite_strain.toml", ("mass =", "mass = 1e30"))
    with pytest.raises(StudyError) as caught:
        load_study(finite)
    # its velocity remedy, 3 m/s slowed 1e14 times, is left out (guards.REMEDY_SPAN, reach62)
    mass = "lower [impact] mass to at most about 6.33 kg with this striker, velocity and body"
    assert str(caught.value).endswith(mass), caught.value
    assert "depths" not in str(caught.value).rpartition("beyond")[2], caught.value
    layer = """name = "l"\nkind = "layer"\n[parameters]\nthickness_ratio = 1.0\n[axes]\n"""
    with pytest.raises(SweepError) as caught:
        parse_sweep(layer + "mass = [1e30]\n")
    assert str(caught.value).endswith(" kg"), caught.value  # 'or mass to at most about ...'
    assert "depths" not in str(caught.value), caught.value


def test_the_reach_refusal_says_its_depths_in_metres(capsys):
    """'to about 1.73e+12 mm' and then '4.13e-07 m/s': one unit, SI metres, as the options and
    the rest of the refusals (the equator's, the low side's) are."""
    said = _refusal(capsys, "contact", "--mass", "1e30", "--no-estimate")
    assert "drive the striker to about 1.73e+09 m, depth / contact radius 5.19e+03" in said, said
    assert " mm" not in said, said


def test_a_too_slow_striker_is_told_the_velocity_and_mass_that_pass(capsys):
    """`contact --velocity 1e-300` blamed four options (the exact impact's P_c underflows, 'give
    these a value of a physical size'), and below x/a 1e-6 the refusal said 'raise mass=... or
    velocity=...' with no value: it names the velocity that passes (and the mass, where it is a
    float), each rounded up, and each passes when tried."""
    import re

    import pytest

    from shtaerman.guards import check_profile_reach
    from shtaerman.theory.indenter import PowerLawIndenter
    from shtaerman.validation import InputError

    paper, modulus = PowerLawIndenter(5.0, 1.5), 7.5e6 / (1 - 0.5**2)  # the CLI's E*
    said = _refusal(capsys, "contact", "--velocity", "1e-300", "--no-estimate")
    assert said.startswith("--mass, --velocity: 0.7 kg at 1e-300 m/s drive the striker"), said
    assert "--E2" not in said and "--shape-coefficient" not in said, said
    velocity = float(re.search(r"raise --velocity to at least about (\S+) m/s", said)[1])
    assert "--mass to" not in said, said  # 1e+153 kg x 1e200: no float
    check_profile_reach(paper, modulus, None, (0.7, velocity))  # passes
    with pytest.raises(InputError, match="below the 1e-06"):  # by 1 %: the bound is tight
        check_profile_reach(paper, modulus, None, (0.7, 0.99 * velocity))
    said = _refusal(capsys, "contact", "--velocity", "1e-100", "--no-estimate")
    mass = float(re.search(r"or --mass to at least about (\S+) kg", said)[1])
    check_profile_reach(paper, modulus, None, (mass, 1e-100))


def test_on_a_layer_the_reach_refusal_names_a_velocity_the_layer_takes(capsys):
    """`contact --mass 1e30 --thickness 0.02` named 4.13e-7 m/s (x/a 100 on the half-space),
    which the thickness range then refused (the layer must lie within 0.01 to 1000 refined
    radii: [3.33, 3.32e5] m at those depths). The velocity named now keeps the depths within
    what the 0.02 m layer's mesh resolves: it runs (coarse mesh), 1 % faster is refused."""
    import re

    said = _refusal(capsys, "contact", "--mass", "1e30", "--thickness", "0.02", "--no-estimate")
    assert "mass and body on this 0.02 m layer (the depths its mesh resolves)" in said, said
    velocity = float(re.search(r"lower --velocity to at most about (\S+) m/s", said)[1])
    run = ["contact", "--mass", "1e30", "--thickness", "0.02", "--no-estimate"]
    run += ["--mesh-size", "0.3", "--json"]
    from shtaerman.cli import main

    assert main([*run, "--velocity", str(velocity)]) == 0  # with the strain warnings: x > H
    capsys.readouterr()
    faster = _refusal(capsys, *run, "--velocity", str(1.01 * velocity))
    assert faster.startswith("--thickness: must lie in [0.0201, "), faster
