"""The viscoelastic study's numbers and their error estimates, the sweep's loss columns, and the
bound on how far a Prony series may relax within the impact."""

import pytest
from study_texts import DYNAMIC_STUDY

from shtaerman.theory.contact import PowerLawContact
from shtaerman.theory.indenter import PowerLawIndenter
from shtaerman.theory.materials import RIGID, Material, effective_modulus
from shtaerman.theory.viscoelastic import PronySeries

LOSSES = ("energy_dissipated_fraction", "energy_wave_fraction", "energy_hysteresis_fraction")
LAW = PowerLawContact(PowerLawIndenter(5.0, 1.5), effective_modulus(RIGID, Material(7.5e6, 0.5)))
GLASSY_T_Y = 8.21e-3  # s: the paper's elastic impact at 3 m/s on E2 = 7.5 MPa


@pytest.fixture(scope="module")
def laddered(tmp_path_factory):
    """A massless viscoelastic study at 3 m/s with its 3-level ladder (coarse levels)."""
    from shtaerman.study.run import run_study
    from shtaerman.study.schema import load_study

    path = tmp_path_factory.mktemp("visco") / "visco.toml"
    text = DYNAMIC_STUDY.replace("density2 = 1100.0", 'density2 = 0\nprony = "0.5:2e-3"')
    text = text.replace("velocity = [1.0, 3.0]", "velocity = [3.0]")
    path.write_text(text + "[numerics]\ntime_steps = 100\nmesh_size = 0.09\n")
    [study] = load_study(path)
    return run_study(study, quick=False)


def test_the_split_of_the_loss_carries_estimates(laddered):
    case = laddered.example
    estimates = case.estimates()
    for key in LOSSES:
        assert key in estimates and estimates[key].absolute_error >= 0.0
    hysteresis = estimates["energy_hysteresis_fraction"]
    assert hysteresis.absolute_error < 0.01 * case.result.losses[LOSSES[2]]
    details = case.document()["error_estimate"]
    assert set(LOSSES) <= set(details)


def test_the_findings_quote_the_split_with_its_error(laddered):
    from shtaerman.output.text_dynamic import study_findings

    loss = next(line for line in study_findings(laddered) if "dissipated by the end" in line)
    heat = loss.split("no waves; ")[1]
    assert heat.split(" %")[0].count("±") == 1  # "43.60 ± 0.0x % of M v0^2/2 dissipated"


def test_an_elastic_ladder_has_no_split():
    from shtaerman.fem.dynamic_contact import DynamicSettings
    from shtaerman.study.dynamic.case import run_case

    ladder = run_case(
        PowerLawIndenter(5.0, 1.5), Material(7.5e6, 0.5), 0.0, 0.7, 3.0,
        DynamicSettings(steps=100, size=0.09), ladder=True,
    ).ladder  # fmt: skip
    assert not set(LOSSES) & set(ladder.estimates)


def test_the_sizing_stops_at_the_bound():
    from shtaerman.fem.viscoelastic import MAX_GLASSY_DURATIONS, sizing_impact
    from shtaerman.validation import InputError

    within = sizing_impact(0.7, 3.0, LAW, PronySeries((0.999,), (1e-9,)), GLASSY_T_Y)
    assert 13.0 < within.t_contact / GLASSY_T_Y < MAX_GLASSY_DURATIONS
    with pytest.raises(InputError, match=r"lasts more than 20 glassy impact durations") as error:
        sizing_impact(0.7, 3.0, LAW, PronySeries((0.999999,), (1e-300,)), GLASSY_T_Y)
    assert error.value.parameter == "prony"


def test_an_extreme_series_is_one_line_and_exit_2(capsys):
    from shtaerman.cli import main

    argv = ["dynamic", "--prony", "0.999999:1e-300", "--density2", "0", "--no-estimate"]
    assert main([*argv, "--time-steps", "100"]) == 2
    err = capsys.readouterr().err
    assert err.startswith("shtaerman: error: --prony: the viscoelastic impact lasts more than 20")
    assert "1 - sum g_i >= 0.00034" in err and err.count("\n") == 1


def test_a_dynamic_sweep_with_prony_has_the_loss_columns():
    from shtaerman.sweep.kinds import get_kind

    kind = get_kind("dynamic")
    assert set(LOSSES) <= set(kind.outputs_for({"prony": "0.5:2e-3"}))
    assert not set(LOSSES) & set(kind.outputs_for({"prony": None}))
    params = {**kind.defaults(), "density2": 0.0, "time_steps": 60, "mesh_size": 0.1}
    visco = kind.case({**params, "estimate": False, "prony": "0.5:2e-3"}).outputs
    assert visco["energy_hysteresis_fraction"] == pytest.approx(
        1.0 - visco["restitution"] ** 2, abs=1e-4
    )  # massless: no waves
    assert visco["energy_dissipated_fraction"] > 0.3 and abs(visco["energy_wave_fraction"]) < 1e-4
    elastic = kind.case({**params, "estimate": False}).outputs
    assert not set(LOSSES) & set(elastic)


def test_the_quasi_static_integration_gives_up_at_longest():
    from shtaerman.theory.viscoelastic import viscoelastic_impact
    from shtaerman.validation import InputError, NumericalFailureError

    one_term = PronySeries((0.5,), (2e-3,))
    whole = viscoelastic_impact(0.7, 3.0, LAW, one_term, steps=100)
    capped = viscoelastic_impact(0.7, 3.0, LAW, one_term, steps=100, longest=2 * whole.t_contact)
    assert capped.restitution == whole.restitution  # a bound it does not reach changes nothing
    with pytest.raises(NumericalFailureError, match="no separation"):
        viscoelastic_impact(0.7, 3.0, LAW, one_term, steps=100, longest=0.5 * whole.t_contact)
    with pytest.raises(InputError, match="longest"):
        viscoelastic_impact(0.7, 3.0, LAW, one_term, steps=100, longest=-1.0)
