"""The force-depth loop and the energy account of a dynamic impact: the figures' data."""

import csv
import dataclasses
import re
from pathlib import Path

import numpy as np
import pytest
from PIL import Image

from shtaerman.fem.dynamic_contact import DynamicSettings
from shtaerman.output.dynamic import write_case_figures, write_dynamic_study
from shtaerman.output.text_dynamic import study_findings
from shtaerman.plots.impact_energy import energy_shares, force_depth_loop, loop_work
from shtaerman.study.dynamic.case import run_case
from shtaerman.study.run import run_study
from shtaerman.study.schema import StudyError, find_study, load_study
from shtaerman.theory.indenter import PowerLawIndenter
from shtaerman.theory.materials import Material
from shtaerman.theory.viscoelastic import PronySeries

INDENTER = PowerLawIndenter(5.0, 1.5)
RUBBER = Material(7.5e6, 0.5)
MASS, VELOCITY = 0.7, 3.0
CHEAP = DynamicSettings(steps=60, size=0.1)
ONE_TERM = PronySeries((0.5,), (2e-3,))


@pytest.fixture(scope="module")
def both():
    """Waves and hysteresis: the paper's rubber with a density and a one-term series."""
    return run_case(INDENTER, RUBBER, 1100.0, MASS, VELOCITY, CHEAP, prony=ONE_TERM)


@pytest.fixture(scope="module")
def elastic():
    return run_case(INDENTER, RUBBER, 1100.0, MASS, VELOCITY, CHEAP)


def energy0(case):
    return 0.5 * MASS * VELOCITY**2


@pytest.mark.parametrize("name", ["both", "elastic"])
def test_loop_area_is_the_energy_left_in_the_body(name, request):
    case = request.getfixturevalue(name)
    result = case.result
    area = loop_work(result) / energy0(case)
    assert area == pytest.approx(result.energy_radiated_fraction, abs=result.energy_balance_error)
    assert area > 0.0


def test_loop_splits_at_the_largest_approach_and_shows_hysteresis(both):
    result = both.result
    loop = force_depth_loop(result)
    assert loop["x_load"][-1] == loop["x_unload"][0] == pytest.approx(result.x_max, rel=1e-6)
    assert np.all(np.diff(loop["x_load"]) >= 0.0)
    # at the same depth the unloading force lies below the loading one (hysteresis)
    depth = 0.5 * result.x_max
    loading = np.interp(depth, loop["x_load"], loop["P_load"])
    unloading = np.interp(depth, loop["x_unload"][::-1], loop["P_unload"][::-1])
    assert unloading < 0.8 * loading
    # the loop's area holds the dissipated energy and the waves' share of 1 - e^2
    losses = result.losses
    shares = losses["energy_hysteresis_fraction"] + losses["energy_wave_fraction"]
    assert loop_work(result) / energy0(both) == pytest.approx(
        shares, abs=result.energy_balance_error
    )


@pytest.mark.parametrize("name", ["both", "elastic"])
def test_energy_shares_sum_to_the_initial_energy(name, request):
    result = request.getfixturevalue(name).result
    shares = energy_shares(result)
    total = sum(shares.values())
    assert np.max(np.abs(total - 1.0)) < 1e-12
    residue = shares["numerical residue"]
    # the same residue two ways, from up to five shares of size <= 1 summed in another order:
    # round-off up to ~6 eps = 1.3e-15 (measured 4e-17); 1e-15 was below that bound
    assert np.max(np.abs(total - residue - 1.0)) <= result.energy_balance_error + 1e-14
    assert shares["striker kinetic"][0] == pytest.approx(1.0)
    assert shares["striker kinetic"][-1] == pytest.approx(result.restitution**2, rel=1e-6)


def test_dissipated_share_only_where_the_body_dissipates(both, elastic):
    assert "dissipated (hysteresis)" not in energy_shares(elastic.result)
    dissipated = energy_shares(both.result)["dissipated (hysteresis)"]
    assert np.all(np.diff(dissipated) >= 0.0) and dissipated[-1] > 0.05
    assert dissipated[-1] == pytest.approx(
        both.result.losses["energy_dissipated_fraction"], rel=1e-12
    )


def test_case_figures_include_the_loop_and_the_energy_account(both, tmp_path):
    figures = write_case_figures(both, tmp_path, "svg")
    stems = {path.stem for path in figures.values()}
    assert {"force_depth_loop", "energy_history"} <= stems
    for stem in ("force_depth_loop", "energy_history"):
        assert Image.open(tmp_path / f"{stem}.png").format == "PNG"
        assert (tmp_path / f"{stem}.svg").read_text().lstrip().startswith("<?xml")


def test_the_viscoelastic_study_splits_into_its_three_losses():
    waves, hysteresis, both_ = load_study(find_study("viscoelastic"))
    assert [s.name for s in (waves, hysteresis, both_)] == [
        "viscoelastic-waves",
        "viscoelastic-hysteresis",
        "viscoelastic-both",
    ]
    assert (waves.density, waves.prony) == (1100.0, None)
    assert (hysteresis.density, hysteresis.prony) == (0.0, both_.prony)
    assert both_.density == 1100.0 and both_.prony == PronySeries((0.5,), (2.0526e-3,))
    assert waves.velocities == (0.5, 1.0, 2.0, 3.0, 4.0, 5.0) and waves.example == 3.0


@pytest.mark.parametrize(
    ("sweep", "reason"),
    [
        ('loss = ["waves", "heat"]', "expected distinct values of waves, hysteresis, both"),
        ('loss = ["waves", "waves"]', "expected distinct values"),
        ("loss = []", "expected distinct values"),
        ('loss = "waves"', "expected a list of distinct values"),
        ("loss = [1]", "expected a list of distinct values"),
    ],
)
def test_a_bad_loss_sweep_names_its_key(tmp_path, sweep, reason):
    text = find_study("viscoelastic").read_text()
    path = tmp_path / "bad.toml"
    path.write_text(re.sub(r"loss = \[[^\]]*\]", sweep, text))
    with pytest.raises(StudyError, match=r"key 'sweep.loss': " + reason):
        load_study(path)


def test_a_loss_sweep_needs_density_and_prony(tmp_path):
    text = find_study("viscoelastic").read_text().replace('prony = "0.5:2.0526e-3"', "")
    path = tmp_path / "elastic.toml"
    path.write_text(text)
    with pytest.raises(StudyError, match=r"key 'sweep.loss': .*density2 > 0 and a prony"):
        load_study(path)


def test_a_viscoelastic_study_writes_its_loss_split_and_figures(tmp_path):
    [_, _, study] = load_study(find_study("viscoelastic"))
    study = dataclasses.replace(study, quick_velocities=(3.0,), quick_settings=CHEAP)
    outcome = run_study(study, quick=True)
    files, figures = write_dynamic_study(outcome, tmp_path / "viscoelastic-both", tmp_path)
    with (tmp_path / files["summary"]).open() as stream:
        [row] = list(csv.DictReader(stream))
    losses = outcome.example.result.losses
    for key in ("energy_dissipated_fraction", "energy_wave_fraction", "energy_hysteresis_fraction"):
        assert float(row[f"{key} [1]"]) == losses[key]
    assert float(row["energy_hysteresis_fraction [1]"]) > 0.5
    stems = {Path(path).stem for path in figures.values()}
    assert {"force_depth_loop", "energy_history", "dynamic_history"} <= stems
    rebound = study_findings(outcome)[1]
    assert "as waves and hysteresis" in rebound and "elastic waves" not in rebound
    assert f"{100 * losses['energy_wave_fraction']:.2f} %" in rebound


def test_a_massless_study_reports_hysteresis_not_waves():
    [_, study, _] = load_study(find_study("viscoelastic"))
    study = dataclasses.replace(study, quick_velocities=(3.0,), quick_settings=CHEAP)
    rebound = study_findings(run_study(study, quick=True))[1]
    assert "as hysteresis (massless body: no waves" in rebound and "waves (" not in rebound


def test_the_history_figure_names_the_losses_of_the_run(both, elastic):
    from shtaerman.plots.dynamic import _losses

    assert _losses(both.result) == "waves + hysteresis"
    assert _losses(elastic.result) == "waves"


def test_a_lossless_share_is_shown_without_a_minus_sign():
    """A rubber's loop area of -1e-6 E0 (the trapezoid's round-off) printed "-0.0000" in the
    loop's title."""
    from shtaerman.plots.impact_energy import _shown

    assert [_shown(x) for x in (-1e-6, 0.0, 0.28049, -0.5)] == [
        "0.0000",
        "0.0000",
        "0.2805",
        "-0.5000",
    ]
