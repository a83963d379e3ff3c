"""A study's linear FE impact computes the energies inside R_a from the contact's end on only.

The dynamic study uses them only there (the reflected energy: what came back after
separation; the loss split into waves and hysteresis, at the last step); the two sparse
products were ~8 % of each time step (benchmarks/FEM_NOTES.md, "Where verify's CPU goes").
A history (`shtaerman dynamic --history`, energies.csv) keeps them at every step. Coarse mesh
and steps: ~2 CPU s for the three runs.
"""

import math

import numpy as np
import pytest

from shtaerman.fem.dynamic_contact import DynamicSettings
from shtaerman.fem.impact import run_impact
from shtaerman.theory.indenter import PowerLawIndenter
from shtaerman.theory.materials import Material
from shtaerman.theory.viscoelastic import PronySeries

COARSE = DynamicSettings(steps=50, size=0.2)
INNER = ("inner", "inner_kinetic")


@pytest.mark.parametrize("prony", [None, PronySeries.parse("0.3:1e-3")])
def test_the_last_step_alone_gives_the_same_run(prony):
    inputs = (PowerLawIndenter(5.0, 1.5), Material(7.5e6, 0.5), 1100.0, 0.7, 3.0, COARSE)
    every = run_impact(*inputs, prony=prony)
    last = run_impact(*inputs, prony=prony, energy_series=False)
    for name in INNER:  # the same products of the same last state: bit for bit
        assert last.energies[name][-1] == every.energies[name][-1]
        during = last.t < last.t_contact  # [0]: first touch, 0
        assert np.isnan(last.energies[name][1:][during[1:]]).all()
        assert np.array_equal(
            last.energies[name][last.t > last.t_contact],
            every.energies[name][every.t > every.t_contact],
        )
        assert np.isfinite(every.energies[name]).all()
    for name in set(every.energies) - set(INNER):
        assert np.array_equal(last.energies[name], every.energies[name]), name
    summary, series = last.to_dict(), every.to_dict()
    for key in ("reflected_energy_fraction", "restitution", "x_max", "P_max"):
        assert summary[key] == series[key] or (math.isnan(summary[key]) and math.isnan(series[key]))
    if prony is not None:  # the loss split reads R_a's energy at the end
        assert summary["energy_wave_fraction"] == series["energy_wave_fraction"]
