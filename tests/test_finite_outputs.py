"""The finite-strain impact writes what the linear one writes (issue 28: --out, --history and
--figure-format were refused with --model, and its result was a type of its own)."""

import csv
import json

import numpy as np
import pytest

import shtaerman as sh
from shtaerman.cli import main
from shtaerman.fem.mesh import MeshSettings

COARSE = MeshSettings(size=0.15, domain=1e3, growth=0.35, axis_size=1e-3, axis_growth=0.25)
ARGV = ["dynamic", "--model", "neo-hookean", "--density2", "0", "--velocity", "1"]
ARGV += ["--time-steps", "50", "--json"]


@pytest.fixture
def coarse(monkeypatch):
    import shtaerman.fem.finite_dynamic as finite_dynamic

    monkeypatch.setattr(finite_dynamic, "IMPACT_MESH", COARSE)


def test_out_history_and_figures_of_the_finite_impact(coarse, tmp_path, capsys):
    out, history = tmp_path / "run", tmp_path / "h.csv"
    argv = [*ARGV, "--out", str(out), "--history", str(history), "--figure-format", "svg"]
    assert main(argv) == 0
    printed = json.loads(capsys.readouterr().out)
    written = json.loads((out / "dynamic.json").read_text())
    assert written == printed and written["model"] == "neo-hookean"
    with history.open() as stream:
        rows = list(csv.DictReader(stream))
    # a rubber records no contact radius: the columns the help promises of every body, no
    # a or p0 (the linear body's alone; test_adversary_found.py checks the help's words)
    assert [name.split(" ")[0] for name in rows[0]] == ["t", "x", "v", "P"], list(rows[0])
    force = np.array([float(row["P [N]"]) for row in rows])
    # the same run's history: P_max is its peak located between steps, above the sampled
    # maximum by less than P ~ x^(5/3) drops over half a step of a near half-sine approach
    # (50 steps per t_y): (5/3) (1 - cos(pi / 100)) = 8.2e-4
    p_max = printed["dynamic"]["P_max"]
    assert 0 <= p_max - force.max() < 8.2e-4 * p_max
    assert (out / "history.csv").read_text() == history.read_text()
    energies = (out / "energies.csv").read_text().splitlines()
    assert len(energies) == len(rows) + 1  # one row per step under the header
    assert "<svg" in (out / "dynamic_history.svg").read_text()
    from PIL import Image

    picture = np.asarray(Image.open(out / "dynamic_history.png").convert("L"))
    assert (picture < 200).mean() > 0.02  # axes, two curves and their labels drawn
    # one figure set for every body: the rubber's force-depth loop and energy account too,
    # drawn by the linear impact's functions (the finite route drew x(t), P(t) alone)
    for stem in ("force_depth_loop", "energy_history"):
        assert "<svg" in (out / f"{stem}.svg").read_text()


def test_one_result_type_for_every_body(coarse):
    indenter, body = sh.PowerLawIndenter(5.0, 1.5), sh.Material(7.5e6, 0.5, density=0.0)
    result = sh.dynamic(
        indenter, body, mass=0.7, velocity=1.0, model="yeoh", time_steps=50, estimate=False
    )
    assert isinstance(result, sh.DynamicResult)
    assert result.to_dict()["rubber"]["model"] == "yeoh"
    assert result.to_dict()["radiation_estimate"] is None  # the linear half-space's estimate


def test_the_energy_check_binds_the_finite_impact_too(coarse, monkeypatch, capsys):
    """The linear impact exits 1 when its energy balance is off by more than 1e-2 of M v0^2/2;
    the finite-strain impact exited 0 whatever its balance (one guard, two routes)."""
    import dataclasses

    import shtaerman.cli.dynamic as command

    run = command.dynamic

    def unbalanced(problem, **numerics):
        result = run(problem, **numerics)
        return dataclasses.replace(result, dynamic={**result.dynamic, "energy_balance_error": 0.05})

    monkeypatch.setattr(command, "dynamic", unbalanced)
    assert main(ARGV) == 1
    assert "energy balance error 5.0e-02 of M v0^2/2 exceeds 0.01" in capsys.readouterr().err


def test_the_field_file_flags_the_rubber_model_it_holds(tmp_path):
    """The finite field VTU, now written by the linear body's field_mesh, flagged every rubber
    "model_neo-hookean"; a Mooney-Rivlin curve's file names Mooney-Rivlin."""
    from shtaerman.fem.contact.finite import run_finite_indentation
    from shtaerman.fem.rubber import rubber_model
    from shtaerman.output.finite import write_finite_field

    material = sh.Material(7.5e6, 0.5)
    model = rubber_model("mooney-rivlin", 0.3)
    curve = run_finite_indentation(sh.PowerLawIndenter(5.0, 1.5), material, [1e-4], COARSE, model)
    path = write_finite_field(curve, curve.steps[-1], material, tmp_path / "field.vtu")
    text = path.read_text()
    assert 'Name="model_mooney-rivlin [1]"' in text and "neo-hookean" not in text
    assert 'Name="von_mises [Pa]"' in text and 'Name="displacement [m]"' in text


def test_the_finite_study_impact_figure_names_the_study_s_rubber_and_profile(tmp_path):
    """The finite study's impact legend said "neo-Hookean" for any rubber and "Shtaerman" for
    any profile; it now labels the variants as the study's tables do (one label function)."""
    from types import SimpleNamespace

    from shtaerman.fem.rubber import rubber_model
    from shtaerman.plots.finite import plot_finite_impact
    from shtaerman.plots.labels import variant_label

    t = np.linspace(0.0, 1e-3, 5)
    history = SimpleNamespace(t=t, x=1e-3 * np.sin(np.pi * t / 1e-3), P=np.sin(np.pi * t / 1e-3))
    study = SimpleNamespace(rubber=rubber_model("mooney-rivlin", 0.3))
    study.indenter = SimpleNamespace(kind="sphere")
    variants = ("linear_exact", "linear_fem", "finite_strain")
    outcome = SimpleNamespace(study=study, histories=dict.fromkeys(variants, history))
    text = plot_finite_impact(outcome, tmp_path / "impact.svg").read_text()
    labels = [variant_label(outcome, variant) for variant in variants]
    assert labels[0] == "Sneddon, linear (sphere profile)"
    assert labels[2] == "Mooney-Rivlin finite strain"
    assert all(label in text for label in labels) and "neo-Hookean" not in text
