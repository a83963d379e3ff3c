"""The half-space's reflected-energy check measures what comes back inside R_a after separation.

It was the body energy inside R_a at the end of the run, of the radiated energy, which counts
energy still on its way out: a blunt striker leaves 1 to 2 % there whatever lambda, which set
the wave-speed limits of n >= 3.5. It now takes the largest rise of that energy above its
running minimum after separation, of the radiated energy (benchmarks/FEM_NOTES.md, "What comes
back on the half-space"). Coarse meshes (size 1/20, 100 steps per t_y): ~3 CPU s a run.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

import shtaerman.guards
from shtaerman.fem.dynamic_contact import DynamicSettings
from shtaerman.fem.impact import run_impact
from shtaerman.study.dynamic.loader import dynamic_check_failures
from shtaerman.theory.indenter import PowerLawIndenter
from shtaerman.theory.materials import Material

COARSE = {"size": 0.05, "steps": 100}
RHO = 0.152839
"""density2 (kg/m^3) at which z = 1e6 r^10, 0.7 kg at 1 m/s on 7.5 MPa, nu2 0.49 radiates an
estimated lambda = 0.1 (RadiatedFraction), above the wave-speed limit: lifted here."""


def _blunt(monkeypatch, energy_series: bool = True, **absorber: float):
    monkeypatch.setattr(shtaerman.guards, "wave_limit", lambda *_, **__: math.inf)
    return run_impact(
        PowerLawIndenter(1e6, 10.0),
        Material(7.5e6, 0.49),
        RHO,
        0.7,
        1.0,
        DynamicSettings(**COARSE, **absorber),
        energy_series=energy_series,
    )


def _failures(run) -> list[str]:
    return dynamic_check_failures(
        run.energy_balance_error,
        run.reflected_energy_fraction,
        radiated=run.energy_radiated_fraction,
    )


def test_energy_still_leaving_a_half_space_is_no_reflection(monkeypatch):
    run = _blunt(monkeypatch)
    e0 = run.energies["striker_kinetic"][0]
    radiated = run.energy_radiated_fraction  # 0.095 observed
    inner = run.energies["inner"][run.t > run.t_contact] / e0
    # main's check: the energy inside R_a at the end, 0.0153 of the radiated, beyond 1e-2
    assert inner[-1] / radiated > 1.2e-2
    # what came back after separation: 4.6e-4 of the radiated observed (2.8e-4 on the
    # default mesh, FEM_NOTES), 30x below the end energy and 20x below the 1e-2 tolerance
    assert run.reflected_energy_fraction < 1e-3
    assert _failures(run) == []


@pytest.fixture(scope="module")
def reflecting():
    """A stiff narrow absorber (damping rate 1000 / t_y over 0.25 c_s t_y, against none on the
    default half-space) reflects at its impedance jump, 0.75 c_s t_y out."""
    with pytest.MonkeyPatch.context() as monkeypatch:
        yield _blunt(monkeypatch, layer_rate=1000.0, layer_width=0.25)


def test_a_reflecting_absorber_fails_the_check(reflecting):
    # what it sent back after separation: 0.0185 of the radiated observed (the energy inside
    # R_a rose by 1e-3 of M v0^2/2 above its running minimum; radiated 0.054)
    assert reflecting.reflected_energy_fraction > 1.5e-2
    (reason,) = _failures(reflecting)
    assert reason.startswith("reflected energy 1.9e-02 of the radiated exceeds 0.01")


def test_a_study_run_measures_the_same_return(reflecting, monkeypatch):
    # a study's run keeps the energies inside R_a from the contact's end on only: the same
    # states, so the same number to the bit
    run = _blunt(monkeypatch, False, layer_rate=1000.0, layer_width=0.25)
    assert run.reflected_energy_fraction == reflecting.reflected_energy_fraction
    inner, during = run.energies["inner"], run.t < run.t_contact
    assert np.isnan(inner[1:][during[1:]]).all()  # row 0 is first touch: 0 everywhere
    assert np.isfinite(inner[run.t > run.t_contact]).all()
