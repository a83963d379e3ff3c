"""The public Python API (``import shtaerman as sh``): the same numbers as the CLI's --json.

The user's own case of the issue that asked for it: z = 12 r^1.8 on rubber of 4 MPa,
nu = 0.49, density 1100 kg/m^3, struck by 0.25 kg at 2 m/s. FEM runs use coarse meshes (a few
seconds each); the physics is tested elsewhere.
"""

import contextlib
import io
import json
import math
import subprocess
import sys

import numpy as np
import pytest

import shtaerman as sh
from shtaerman.cli import main

CASE = ["--exponent", "1.8", "--shape-coefficient", "12", "--E2", "4e6", "--nu2", "0.49"]
IMPACT = ["--mass", "0.25", "--velocity", "2"]
LINEAR_MESH = ["--mesh-size", "0.05", "--domain-factor", "1e4"]
DYNAMIC_COARSE = ["--steps", "100", "--mesh-size", "0.05"]
INDENTER = sh.PowerLawIndenter(shape_coefficient=12.0, exponent=1.8)
RUBBER = sh.Material(youngs_modulus=4e6, poisson_ratio=0.49, density=1100.0)
API_NAMES = {"PowerLawIndenter", "Material", "impact", "contact", "dynamic", "run_study", "sweep"}


def cli_json(*argv):
    """The parsed --json of one in-process CLI run (exit code 0 required)."""
    stream = io.StringIO()
    with contextlib.redirect_stdout(stream):
        code = main([*argv, "--json"])
    assert code == 0
    return json.loads(stream.getvalue())


def without_clock(document):
    """The JSON without wall-clock times (``timings``, ``seconds``): they differ per run."""
    if isinstance(document, dict):
        return {k: without_clock(v) for k, v in document.items() if k not in ("timings", "seconds")}
    if isinstance(document, list):
        return [without_clock(v) for v in document]
    return document


# --- the package -------------------------------------------------------------------------------


def test_import_is_cheap_and_dir_lists_the_api():
    code = (
        "import sys, shtaerman as sh; "
        "heavy = ('numpy', 'scipy', 'gmsh', 'dask', 'skfem'); "
        "print(sorted(m for m in heavy if m in sys.modules)); "
        "print(' '.join(dir(sh)))"
    )
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    loaded, names = out.stdout.splitlines()
    assert loaded == "[]"  # nothing heavy until a name is used
    assert API_NAMES <= set(names.split()) and API_NAMES <= set(sh.__all__)


def test_sweep_is_both_the_function_and_the_package():
    import shtaerman.sweep.engine as engine  # the package's modules still import as usual

    assert callable(sh.sweep) and sh.sweep.engine is engine
    assert "workers" in str(__import__("inspect").signature(sh.sweep))


def test_py_typed_ships_with_the_package():
    from importlib.resources import files

    assert files("shtaerman").joinpath("py.typed").is_file()


# --- impact ------------------------------------------------------------------------------------


def test_impact_matches_the_cli_to_1e_12():
    q = sh.impact(INDENTER, RUBBER, mass=0.25, velocity=2.0)
    cli = cli_json("impact", *CASE, *IMPACT, "--E1", "inf")
    assert set(q.to_dict()) == set(cli)
    assert cli.pop("profile") == q.to_dict()["profile"]  # the striker's profile: its inputs
    for key, value in cli.items():
        assert q.to_dict()[key] == pytest.approx(value, rel=1e-12), key
    # this case's x_c: 4.63 mm (the paper's mass and velocity would give 9.50 mm)
    assert q.x_c == pytest.approx(4.6251665302396e-3, rel=1e-12)
    assert (q.x_c, q.P_c, q.t_c) == (cli["x_c"], cli["P_c"], cli["t_c"])


def test_impact_with_an_elastic_striker_and_the_check():
    steel = sh.Material(2e11, 0.25)
    q = sh.impact(INDENTER, RUBBER, mass=0.25, velocity=2.0, striker=steel, check=True)
    assert q.to_dict() == cli_json("impact", *CASE, *IMPACT, "--check")
    assert q.ode_check["max_history_difference"] < 1e-8


def test_impact_history():
    q = sh.impact(INDENTER, RUBBER, mass=0.25, velocity=2.0)
    history = q.history(11)
    assert history.t[0] == 0.0 and history.t[-1] == pytest.approx(q.t_y, rel=1e-15)
    assert history.x.max() == pytest.approx(q.x_c, rel=1e-12)  # the middle instant is t_c


@pytest.mark.parametrize(
    ("call", "name"),
    [
        (lambda: sh.impact("paper", RUBBER, mass=1, velocity=1), "indenter"),
        (lambda: sh.impact(INDENTER, 4e6, mass=1, velocity=1), "body"),
        (lambda: sh.impact(INDENTER, RUBBER, mass=-1, velocity=1), "mass"),
        (lambda: sh.impact(INDENTER, sh.RIGID, mass=1, velocity=1, striker=sh.RIGID), "body"),
        (lambda: sh.Material(4e6, 0.49, density=-1.0), "density"),
        (lambda: sh.Material(4e6, 0.49, density=1e9), "density"),
        (lambda: sh.Material(math.inf, 3.0), "poisson_ratio"),
    ],
)
def test_bad_input_names_the_parameter(call, name):
    with pytest.raises(sh.InputError) as caught:
        call()
    assert caught.value.parameter == name and "\n" not in str(caught.value)


def test_material_density_is_optional_and_checked_like_density2():
    assert sh.Material(4e6, 0.49).density is None and sh.RIGID.density is None
    assert sh.Material(4e6, 0.49, density=1100).density == 1100.0
    assert sh.Material(4e6, 0.49, density=0).density == 0.0  # massless
    with pytest.raises(sh.InputError, match=r"density must lie in \[1e-06, 1e\+06\] kg/m\^3"):
        sh.Material(4e6, 0.49, density=2e6)


@pytest.mark.parametrize("density", [-3.0, math.inf, "heavy"])
def test_a_density_below_zero_or_no_number_names_the_whole_range(density):
    """adv49: -3 read 'density must be > 0 kg/m^3 (or 0: massless)', hiding the range the
    command line's --density2 names."""
    with pytest.raises(
        sh.InputError, match=r"^density must (lie|be a number) in \[1e-06, 1e\+06\] "
    ):
        sh.Material(4e6, 0.49, density=density)


# --- contact -----------------------------------------------------------------------------------


def test_contact_matches_the_cli_json():
    c = sh.contact(INDENTER, RUBBER, mass=0.25, velocity=2.0, mesh_size=0.05, domain_factor=1e4)
    cli = cli_json("contact", *CASE, *IMPACT, *LINEAR_MESH)
    assert without_clock(c.to_dict()) == without_clock(cli)
    assert list(c.to_dict()) == list(cli)  # the same keys in the same order
    assert c.error_estimate["force"] == cli["error_estimate"]["force"] > 0
    assert np.array_equal(c.force, [step["force"] for step in cli["steps"]])
    assert c.beta_fem == cli["beta_fem"] and c.mesh == cli["mesh"]


def test_contact_default_depths_reach_this_cases_impact(tmp_path):
    # the default depths were those of 0.7 kg at 3 m/s whatever the case (9.50 mm here)
    out = tmp_path / "run"
    argv = ["contact", *CASE, *IMPACT, *LINEAR_MESH, "--no-estimate", "--out", str(out)]
    report = cli_json(*argv)
    x_c = sh.impact(INDENTER, RUBBER, mass=0.25, velocity=2.0).x_c
    assert report["steps"][-1]["depth"] == pytest.approx(x_c, rel=1e-15)
    assert len(report["steps"]) == 8
    assert report["steps"][0]["depth"] == pytest.approx(x_c / 3**1.8, rel=1e-12)
    # --out: the contact curves as figures beside the data
    from matplotlib.image import imread

    for name in ("force_depth.png", "pressure.png"):
        image = imread(out / name)
        assert image.shape[0] > 400 and image[..., :3].std() > 0.05  # drawn, not blank


def test_one_depth_figure_states_that_the_exponent_needs_two(tmp_path):
    from shtaerman.plots.curves import _fit_note

    c = sh.contact(
        INDENTER, RUBBER, depths=[2e-3], estimate=False, mesh_size=0.05, domain_factor=1e4
    )
    assert math.isnan(c.exponent_fem)
    note = _fit_note(c.solution)  # the text of force_depth.png
    assert "nan" not in note and "fitted only from" in note


def test_contact_mass_with_depths_is_refused(capsys):
    with pytest.raises(sh.InputError, match="mass: sets the default depths"):
        sh.contact(INDENTER, RUBBER, mass=0.25, depths=[1e-3])
    assert main(["contact", *CASE, "--mass", "0.25", "--depths", "1e-3"]) == 2
    assert "mass: sets the default depths" in capsys.readouterr().err


def test_neo_hookean_text_with_one_depth_prints_no_nan(capsys):
    argv = ["contact", "--model", "neo-hookean", "--no-estimate", "--depths", "1e-3"]
    assert main([*argv, "--mesh-size", "0.1", "--domain-factor", "1e4"]) == 0
    out = capsys.readouterr().out
    assert "nan" not in out and "exponent: fitted only from >= 2 depths" in out


# --- dynamic -----------------------------------------------------------------------------------


@pytest.fixture(scope="module")
def dynamic_pair():
    d = sh.dynamic(INDENTER, RUBBER, mass=0.25, velocity=2.0, time_steps=100, mesh_size=0.05)
    cli = cli_json("dynamic", *CASE, *IMPACT, "--density2", "1100", *DYNAMIC_COARSE)
    return d, cli


def test_dynamic_matches_the_cli_json(dynamic_pair):
    d, cli = dynamic_pair
    assert without_clock(d.to_dict()) == without_clock(cli)  # None where the CLI has null
    json.dumps(d.to_dict(), allow_nan=False)  # strict JSON: no NaN from estimate_details
    assert list(d.to_dict()) == list(cli)
    assert d.restitution == cli["dynamic"]["restitution"] and d.x_max == cli["dynamic"]["x_max"]
    assert d.quasi_static == cli["quasi_static"]
    assert d.error_estimate["x_max"] > 0 and len(d.mesh_ladder) == 3


def test_dynamic_reports_the_quasi_static_differences(dynamic_pair):
    d, cli = dynamic_pair
    q = d.quasi_static
    assert cli["differences"] == {
        "x_c": q["x_c"] / d.x_max - 1,
        "P_c": q["P_c"] / d.P_max - 1,
        "t_c": q["t_c"] / (d.t_contact / 2) - 1,
    }
    assert set(cli["differences_error"]) == {"x_c", "P_c", "t_c"}
    assert all(0 <= value < 0.05 for value in cli["differences_error"].values())


def test_dynamic_text_prints_the_differences(capsys):
    argv = ["dynamic", *CASE, *IMPACT, *DYNAMIC_COARSE, "--no-estimate"]
    assert main(argv) == 0
    line = next(r for r in capsys.readouterr().out.splitlines() if "quasi-static) / FE" in r)
    assert "x_c" in line and "P_c" in line and "t_c" in line and "%" in line


def test_dynamic_needs_the_density():
    with pytest.raises(sh.InputError, match="density") as caught:
        sh.dynamic(INDENTER, sh.Material(4e6, 0.49), mass=0.25, velocity=2.0)
    assert caught.value.parameter == "density"


# --- the command line's ranges -----------------------------------------------------------------


@pytest.mark.parametrize(
    ("command", "stated"),
    [("impact", "(-1, 0.5]"), ("contact", "[0, 0.5]"), ("dynamic", "[0, 0.5]")],
)
def test_nu2_help_states_the_range_each_command_accepts(capsys, command, stated):
    with pytest.raises(SystemExit):
        main([command, "--help"])
    help_text = " ".join(capsys.readouterr().out.split())
    assert f"half-space Poisson's ratio, {stated}" in help_text
    code = main(
        [command, "--nu2", "-0.2", "--json", "--no-estimate"][: 4 if command == "impact" else 5]
    )
    err = capsys.readouterr().err
    if stated.startswith("("):
        assert code == 0  # a negative ratio is inside (-1, 0.5]
    else:
        assert code == 2 and f"must lie in {stated}" in err


def test_a_rigid_strikers_poisson_ratio_is_still_checked(capsys):
    assert main(["impact", "--E1", "inf", "--nu1", "3"]) == 2
    assert "--nu1 must lie in (-1, 0.5], got '3'" in capsys.readouterr().err


# --- studies and sweeps ------------------------------------------------------------------------


def test_run_study_by_name(tmp_path):
    results = sh.run_study("paper", out=tmp_path / "out", quick=True)
    assert results.passed and list(results.studies) == ["paper"]
    assert (tmp_path / "out" / "results.json").is_file()
    saved = json.loads((tmp_path / "out" / "results.json").read_text())
    assert saved["studies"]["paper"]["passed"] is True
    assert results.outcomes[0].contact.to_dict()["beta_fem"] > 0


def test_sweep_runs_a_file(tmp_path):
    path = tmp_path / "grid.toml"
    path.write_text(
        'name = "grid"\nkind = "impact"\n[parameters]\nmass = 0.25\n[axes]\nvelocity = [1.0, 2.0]\n'
    )
    outcome = sh.sweep(path, workers=1, out=tmp_path / "out")
    assert outcome.succeeded == outcome.total == 2 and outcome.exit_code == 0
    assert (tmp_path / "out" / "cases.csv").is_file()
    again = sh.sweep(sh.sweep.load_sweep(path), out=tmp_path / "out", resume=True)
    assert again.computed == 0 and again.reused == 2


@pytest.mark.parametrize(
    ("call", "message"),
    [
        (
            lambda: sh.contact(INDENTER, RUBBER, mesh=0.01),
            "mesh must be a shtaerman.MeshSettings, got float",
        ),
        (lambda: sh.contact(INDENTER, RUBBER, out=5), "out must be a string, got 5"),
        (lambda: sh.sweep("nu-grid", workers=1.5), "workers must be an integer in [1, 256]"),
    ],
)
def test_wrong_types_are_input_errors_naming_the_keyword(call, message):
    # they were TypeErrors from deep inside: 'replace() should be called on dataclass
    # instances', 'expected str, bytes or os.PathLike object', "'float' object cannot be
    # interpreted as an integer"
    with pytest.raises(sh.InputError) as caught:
        call()
    assert message in str(caught.value)
