"""Issue 28 item 3: the sharp striker's neo-Hookean pad with inertia (z = 8 r^1.3, 0.12 kg at
1.5 m/s on a 12 mm pad, E2 3 MPa, nu2 0.49, 1000 kg/m^3, frictionless, elastic), which ended
with 'element inverted' after 41 CPU s (mesh 0.2, 50 steps: every level of the error-bar ladder
failed, each again with twice its steps).

Where it fails (benchmarks/FEM_NOTES.md, "The sharp striker's pad with inertia"): at 0.82-0.88
mm of the 5.75 mm approach (x/a 1.38-1.45, beyond the 1.2 to which the finite-strain contact is
validated), in the axis element under the tip (R 0.2-0.5 um, 0.2-0.5 um below the surface),
whose J falls 0.83, 0.064, 0.026 over the last steps: at 50, 100 and 200 steps per t_y (each
failing step cut to 1/16), on the default mesh as on mesh 0.2, and on the static curve of the
same mesh (0.9 mm). No time step cures it: the run now says so at once, naming the squeezed
element, and the ladder does not run it again nor its coarser levels."""

from __future__ import annotations

import pytest

import shtaerman as sh
from shtaerman.fem.contact.finite import SqueezedTipError
from shtaerman.fem.finite_dynamic import FiniteImpactSettings
from shtaerman.fem.impact import run_impact
from shtaerman.fem.mesh import Geometry, MeshSettings
from shtaerman.study.dynamic import case
from shtaerman.validation import InputError, NumericalFailureError

SHARP = sh.PowerLawIndenter(8.0, 1.3)
RUBBER = sh.Material(3e6, 0.49)
PAD = Geometry(thickness=0.012, base="bonded")
COARSE = MeshSettings(size=0.4, domain=1e2, growth=0.8, axis_size=1e-4, axis_growth=0.4)
"""The impact's axis grading (1e-4 of the refined radius) on a coarse field: at 25 steps the
same failure as on mesh 0.2 (there at 0.82 mm, x/a 1.45; here at 1.40 mm, x/a 1.64, the axis
element's J 0.063 at R 1.3 um) in about 2 CPU s."""
LADDER_MESH = MeshSettings(size=0.15, domain=1e3, growth=0.35, axis_size=1e-3, axis_growth=0.25)
"""tests/test_finite_impact_ladder.py's: a massless ladder in a few seconds."""


def test_the_sharp_pad_with_inertia_names_the_squeezed_tip_element():
    """Main said 'other time_steps=... may help' after 4 cuts of the step; none helped."""
    settings = FiniteImpactSettings(steps=25, mesh=COARSE)
    with pytest.raises(SqueezedTipError) as failed:
        run_impact(SHARP, RUBBER, 1000.0, 0.12, 1.5, settings, geometry=PAD)
    message = str(failed.value)
    assert "squeezes the element at R" in message and "beside the indenter's tip" in message
    assert "may help" not in message and "\n" not in message
    assert "velocity=..." in message and "shape_coefficient=..." in message
    # the depth reached: 1.40 mm (x/a 1.64), beyond the validated 1.2, short of x_c's 2.27
    ratio = float(message.split("it had reached x/a = ")[1].split(" ")[0])
    assert 1.2 < ratio < 2.27
    # a numerical failure (CLI exit 1), not bad input (exit 2)
    assert isinstance(failed.value, NumericalFailureError)
    assert not isinstance(failed.value, InputError)


def test_the_ladder_stops_at_the_finest_levels_squeezed_tip(monkeypatch):
    """No retry with twice the steps, no coarser level: one run, its message (main ran six
    runs, 41 CPU s on mesh 0.2, and said the last retry's failure)."""
    runs = []

    def squeezed(*inputs, **keywords):
        runs.append(inputs[5].steps)
        raise SqueezedTipError(f"squeezed at {inputs[5].steps} steps")

    monkeypatch.setattr(case, "run_impact", squeezed)
    problem = sh.Problem.impact(  # the 12 mm pad: on the half-space x/a 2.27 is refused first
        SHARP, sh.Material(3e6, 0.49, 1000.0), mass=0.12, velocity=1.5, model="neo-hookean",
        thickness=0.012,
    )  # fmt: skip
    with pytest.raises(SqueezedTipError, match="squeezed at 50 steps"):
        sh.dynamic(problem, time_steps=50, mesh_size=0.2)
    assert runs == [50]


def test_a_coarser_levels_squeezed_tip_leaves_the_estimate_missing(monkeypatch):
    """A coarser level (its axis element twice as large) that squeezes is not retried
    either; the finest level that passed is reported without an estimate."""
    runs, run = [], case.run_impact

    def coarse_fails(*inputs, **keywords):
        runs.append(inputs[5].steps)
        if inputs[5].steps == 25:
            raise SqueezedTipError("squeezed at 25 steps")
        return run(*inputs, **keywords)

    monkeypatch.setattr(case, "run_impact", coarse_fails)
    monkeypatch.setattr("shtaerman.fem.finite_dynamic.IMPACT_MESH", LADDER_MESH)
    blunt = sh.PowerLawIndenter(5.0, 1.5)  # the paper's striker, massless: a quick run
    with pytest.warns(UserWarning, match="refine 0.5: 25 steps failed .*not retried"):
        result = sh.dynamic(
            blunt, sh.Material(7.5e6, 0.5, 0.0), mass=0.7, velocity=1.0, model="neo-hookean"
        )
    assert runs == [50, 25, 35]  # 25 not run again with 50
    assert result.error_estimate is None and "not retried" in result.estimate_missing
