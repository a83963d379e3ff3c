"""The figures name an impact's losses by what the case has (issue 28 item 8): a finite-strain
elastic body with Coulomb friction at the striker loses energy to slip, not to hysteresis."""

import math
from types import SimpleNamespace

import numpy as np
import pytest

from shtaerman.fem.impact_run import impact_parameters
from shtaerman.plots.dynamic import _losses
from shtaerman.plots.impact_energy import energy_shares, loss_kinds
from shtaerman.theory.indenter import PowerLawIndenter
from shtaerman.theory.materials import Material

MASS, VELOCITY = 0.7, 3.0
ENERGY0 = 0.5 * MASS * VELOCITY**2


def _run(density: float, friction: float | None, *, linear: bool, prony: bool) -> SimpleNamespace:
    """The fields of an :class:`ImpactRun` the labels read, as the drivers record them: the
    parameters of :func:`impact_parameters`; the finite-strain run one ``dissipated`` energy
    (and its fraction in ``losses``) where the body relaxes or slips, the linear run ``slip``
    apart and its relaxing shear as ``material``."""
    parameters = impact_parameters(
        PowerLawIndenter(5.0, 2.0),
        Material(7.5e6, 0.49),
        (MASS, VELOCITY, density),
        1e-5,
        friction,
    )
    slips = friction is not None and 0.0 < friction < math.inf  # bonded: no slip
    ramp = np.linspace(0.0, 0.1 * ENERGY0, 5)
    energies = {
        "striker_kinetic": 0 * ramp,  # closes the account below
        "body_kinetic": 0 * ramp,
        "strain": 0 * ramp,
        "absorbed": ramp if density > 0 else 0 * ramp,
        "numerical": 0 * ramp,
    }
    losses = {}
    if linear:
        energies |= {
            "dissipated": ramp if prony else 0 * ramp,
            "slip": ramp if slips else 0 * ramp,
        }
    elif prony or slips:
        energies["dissipated"] = ramp
        losses = {"energy_dissipated_fraction": 0.1}
    energies["striker_kinetic"] = ENERGY0 - sum(
        v for k, v in energies.items() if k != "striker_kinetic"
    )
    material = object() if linear and prony else None
    return SimpleNamespace(
        parameters=parameters,
        energies=energies,
        losses=losses,
        material=material,
        relaxes=prony and not linear,  # the finite-strain run's record of its Prony series
        mesh={},
    )


def test_a_finite_elastic_body_with_friction_loses_energy_to_slip():
    """The case of the issue: --model neo-hookean --interface bonded --friction 0.5, no Prony
    series; the figures said "dissipated (hysteresis)" and "waves + hysteresis"."""
    run = _run(1100.0, 0.5, linear=False, prony=False)
    assert loss_kinds(run) == {"waves": True, "hysteresis": False, "slip": True}
    assert _losses(run) == "waves + slip"
    shares = energy_shares(run)
    assert "dissipated (slip)" in shares and "dissipated (hysteresis)" not in shares


@pytest.mark.parametrize(
    ("density", "friction", "linear", "prony", "said", "dissipated"),
    [
        (1100.0, None, False, True, "waves + hysteresis", ["hysteresis"]),  # a Prony series
        (0.0, None, False, True, "hysteresis", ["hysteresis"]),  # massless: no waves
        (0.0, 0.5, False, False, "slip", ["slip"]),
        # the researcher's full case: a relaxing rubber with Coulomb friction, one dissipated
        # energy that is both
        (1100.0, 0.5, False, True, "waves + hysteresis + slip", ["hysteresis + slip"]),
        (0.0, 0.5, False, True, "hysteresis + slip", ["hysteresis + slip"]),
        (1100.0, None, False, False, "waves", []),  # an elastic frictionless rubber
        (0.0, None, False, False, "no loss", []),
        (1100.0, 0.5, True, True, "waves + hysteresis + slip", ["hysteresis", "slip"]),
        (1100.0, 0.5, True, False, "waves + slip", ["slip"]),
        (1100.0, float("inf"), True, False, "waves", []),  # bonded: no slip
    ],
)
def test_each_share_is_named_by_what_the_case_has(
    density, friction, linear, prony, said, dissipated
):
    run = _run(density, friction, linear=linear, prony=prony)
    assert _losses(run) == said
    shares = energy_shares(run)
    assert [k[12:-1] for k in shares if k.startswith("dissipated")] == dissipated
    assert ("absorbed by the layer (waves)" in shares) == (density > 0)
    # the shares close the account: five of size <= 1 summed, round-off a few eps
    assert np.max(np.abs(sum(shares.values()) - 1.0)) < 1e-12


@pytest.mark.parametrize(
    ("density", "friction", "prony", "said"),
    [
        (1100.0, 0.5, False, "as waves and slip ("),  # said 'as waves': the slip left out
        (1100.0, 0.5, True, "as waves, hysteresis and slip ("),
        (0.0, 0.5, True, "as hysteresis and slip (massless body: no waves)"),
        (1100.0, None, True, "as waves and hysteresis ("),
        (0.0, None, False, "(massless body) ("),
    ],
)
def test_a_rubber_studys_text_names_its_losses_as_the_figures_do(density, friction, prony, said):
    from shtaerman.output.text_dynamic import _rubber_loss_words

    run = _run(density, friction, linear=False, prony=prony)
    study = SimpleNamespace(density=density, physics={"model": "neo-hookean"}, prony=prony)
    outcome = SimpleNamespace(study=study, example=SimpleNamespace(result=run))
    assert _rubber_loss_words(outcome).startswith(said)
