"""A pad's figures speak of the pad (issue 28 item 8): they draw what the pad run measured
(its base's reflected energy, the energy balance), not the half-space's first-order radiation
estimate, and name the body "pad" where the half-space's words would mislead.

The figures are checked on their drawn content (legends, titles, plotted series), captured
before saving; the runs are coarse (a pad run here takes about a second).
"""

from __future__ import annotations

import numpy as np
import pytest
from figure_helpers import capture
from study_texts import DYNAMIC_STUDY

from shtaerman.fem.dynamic_contact import DynamicSettings
from shtaerman.fem.mesh import Geometry
from shtaerman.plots import dynamic, impact_energy
from shtaerman.study.dynamic.case import run_case
from shtaerman.study.run import run_study
from shtaerman.study.schema import load_study
from shtaerman.theory.indenter import PowerLawIndenter
from shtaerman.theory.materials import Material

INDENTER = PowerLawIndenter(5.0, 1.5)
RUBBER = Material(7.5e6, 0.5)
PAD = DynamicSettings(steps=60, size=0.2)
HALF_SPACE = DynamicSettings(steps=60, size=0.1)
STUDY = (
    DYNAMIC_STUDY
    + """[layer]
thickness = 0.02
[quick]
time_steps = 60
mesh_size = 0.05
"""
)


def _legend(ax) -> list[str]:
    return [text.get_text() for text in ax.get_legend().get_texts()]


@pytest.fixture(scope="module")
def pad_case():
    return run_case(INDENTER, RUBBER, 1100.0, 0.7, 3.0, PAD, geometry=Geometry(0.02))


@pytest.fixture(scope="module")
def pad_outcome(tmp_path_factory):
    path = tmp_path_factory.mktemp("pad") / "pad.toml"
    path.write_text(STUDY)
    (study,) = load_study(path)
    return run_study(study, quick=True)


def test_over_velocity_draws_the_pads_reflection_not_the_half_space_estimate(
    monkeypatch, pad_outcome
):
    figure = capture(
        monkeypatch,
        dynamic,
        lambda: dynamic.plot_dynamic_over_velocity(pad_outcome, "unused.png"),
    )
    ax_e, ax_loss = figure.axes[:2]
    assert not any("estimate" in label for label in _legend(ax_e))
    labels = _legend(ax_loss)
    assert not any("lambda" in label for label in labels)
    assert "come back after separation, % of $E_0$" in labels
    assert "energy balance error, % of $E_0$" in labels
    assert "pad" in ax_loss.get_ylabel() and "half-space" not in ax_loss.get_ylabel()
    # the series are the pad run's own measurements, in per cent of M v0^2/2
    results = [case.result for case in pad_outcome.cases]
    lines = {line.get_label(): line for line in ax_loss.get_lines()}
    reflected = lines["come back after separation, % of $E_0$"].get_ydata()
    np.testing.assert_array_equal(reflected, [100 * r.reflected_energy_fraction for r in results])
    balance = lines["energy balance error, % of $E_0$"].get_ydata()
    np.testing.assert_array_equal(balance, [100 * r.energy_balance_error for r in results])
    assert ax_loss.get_yscale() == "log"  # 1 - e^2 and the checks lie decades apart
    from shtaerman.output.dynamic import _over_velocity_caption

    caption = _over_velocity_caption(pad_outcome)
    assert "20 mm pad" in caption and "does not apply to a pad" in caption
    assert "first-order estimate dashed" not in caption


def test_case_figures_name_the_pad(monkeypatch, pad_case):
    history = capture(
        monkeypatch, dynamic, lambda: dynamic.plot_dynamic_histories(pad_case, "unused.png")
    )
    assert "energy left in the pad" in history.axes[0].get_title()
    assert "half-space 1" not in history.axes[0].get_title()
    assert "quasi-static (Ateb) (the half-space's, not this pad's)" in _legend(history.axes[0])

    account = capture(
        monkeypatch,
        impact_energy,
        lambda: impact_energy.plot_energy_history(pad_case, "unused.png"),
    )
    labels = _legend(account.axes[0])
    assert "pad stored (kinetic + strain)" in labels
    assert "absorbed at the pad's lateral edge (waves)" in labels
    assert not any("half-space" in label for label in labels)
    reflected = f"{pad_case.result.reflected_energy_fraction:.1e} E0"
    assert "come back near the contact after separation" in account.axes[0].get_title()
    assert reflected in account.axes[0].get_title()

    loop = capture(
        monkeypatch,
        impact_energy,
        lambda: impact_energy.plot_force_depth_loop(pad_case, "unused.png"),
    )
    assert r"quasi-static elastic $\beta x^q$ (the half-space's, not this pad's)" in _legend(
        loop.axes[0]
    )


def test_the_half_space_figures_keep_their_words(monkeypatch):
    case = run_case(INDENTER, RUBBER, 1100.0, 0.7, 3.0, HALF_SPACE)
    history = capture(
        monkeypatch, dynamic, lambda: dynamic.plot_dynamic_histories(case, "unused.png")
    )
    assert "energy left in the half-space" in history.axes[0].get_title()
    assert "quasi-static (Ateb)" in _legend(history.axes[0])
    shares = impact_energy.energy_shares(case.result)
    assert "half-space stored (kinetic + strain)" in shares


def test_the_command_line_text_quotes_no_half_space_estimate_for_a_pad(capsys):
    """dynamic --thickness printed "first-order estimate 0.918234", the half-space's."""
    from shtaerman.cli import main

    coarse = ["--mesh-size", "0.2", "--time-steps", "60", "--no-estimate"]
    main(["dynamic", "--thickness", "0.02", *coarse])
    pad = capsys.readouterr().out
    assert "first-order estimate" not in pad and "does not apply to a pad" in pad
    main(["dynamic", *coarse])
    assert "(first-order estimate of the waves" in capsys.readouterr().out
