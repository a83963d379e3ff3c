"""A failing load step of the finite-strain bonded / Coulomb curve is taken in halves
(fem/contact/constraints.py, ``in_halves``), as the impacts cut a failing time step.

The case: z = 5 r^1.5 pressed to d/a = 0.6 into nu2 = 0.49 neo-Hookean rubber on the wiring
tests' rough mesh (3093 dofs), in load steps of ratio 4. On main's code path (no cut) the step
from 1.55 mm to 6.18 mm inverts an element; cut once, it passes. The same curve in load steps of
ratio 2^(1/4) and 2^(1/8) agrees to 2e-5 (the ladder has converged there), so that curve is the
reference.
"""

from __future__ import annotations

import functools
import json
import math

import numpy as np
import pytest

import shtaerman.fem.contact.finite_stick as finite_stick
import shtaerman.study.finite.indentation as finite_study
from shtaerman.cli import main
from shtaerman.fem.contact.finite import run_finite_indentation
from shtaerman.fem.mesh import MeshSettings
from shtaerman.study.dynamic.accuracy import RetriedWarning
from shtaerman.theory.indenter import PowerLawIndenter
from shtaerman.theory.materials import Material
from shtaerman.validation import InputError, NumericalFailureError

INDENTER = PowerLawIndenter(5.0, 1.5)
RUBBER = Material(1.0e6, 0.49)
ROUGH = MeshSettings(size=0.2, domain=1e2, growth=0.5, axis_size=1e-3, axis_growth=0.3)
DEEPEST = 5.0 * (0.6 / 5.0) ** 3
"""d/a = 0.6 on z = 5 r^1.5 (m)."""
LARGE = 4.0
"""The step ratio whose step to DEEPEST inverts an element uncut."""


def _curve(ratio: float, friction: float = 0.5, depths: tuple = (DEEPEST,)):
    solve = functools.partial(
        finite_stick.solve_finite_bonded_contact, friction=friction, step_ratio=ratio
    )
    return run_finite_indentation(INDENTER, RUBBER, list(depths), ROUGH, None, solve)


@functools.cache
def _reference(friction: float) -> float:
    """The force (N) at DEEPEST in load steps of ratio 2^(1/4)."""
    return _curve(2**0.25, friction).steps[-1].force


@pytest.mark.parametrize("friction", [0.5, math.inf])
def test_a_failing_load_step_passes_in_halves(friction, monkeypatch):
    monkeypatch.setattr(finite_stick, "MAX_LOAD_CUTS", 0)  # main's code path: no cut
    with pytest.raises(NumericalFailureError, match="element inverted") as failed:
        _curve(LARGE, friction)
    assert not isinstance(failed.value, InputError)  # a numerical failure, not bad input
    monkeypatch.undo()
    curve = _curve(LARGE, friction)
    assert curve.cuts == 1
    # measured 1.0e-3 (Coulomb) and 2.2e-3 (bonded) below the reference: the error of the
    # ratio-2 ladder, whose step the halves are (its uncut curve is 2.1e-3 below); a half not
    # committed (the held radii of the first half lost) would not be a ladder of ratio 2
    assert curve.steps[-1].force == pytest.approx(_reference(friction), rel=3e-3)


def test_a_run_that_needs_no_cut_is_the_uncut_run_bit_for_bit(monkeypatch):
    depths = (DEEPEST / 8.0, DEEPEST)
    cut = _curve(2.0, depths=depths)
    monkeypatch.setattr(finite_stick, "MAX_LOAD_CUTS", 0)
    uncut = _curve(2.0, depths=depths)
    assert cut.cuts == uncut.cuts == 0
    for one, other in zip(cut.steps, uncut.steps, strict=True):
        assert one.force == other.force and one.total_iterations == other.total_iterations
        assert np.array_equal(one.solution, other.solution)


def test_exhausted_cuts_name_the_options(monkeypatch):
    monkeypatch.setattr(finite_stick, "MAX_LOAD_CUTS", 0)
    with pytest.raises(NumericalFailureError) as failed:
        _curve(LARGE)
    said = str(failed.value)
    assert "depth 0.00618228 m" in said and "from 0.00154557 m" in said  # the failed step
    assert "mesh_size=..." in said and "refine=..." in said and "depths=..." in said


def _cli(monkeypatch, capsys) -> tuple[int, str, str]:
    """``contact`` on the case, its bonded solver in load steps of ratio LARGE."""
    original = finite_stick.solve_finite_bonded_contact
    large = functools.partial(original, step_ratio=LARGE)
    monkeypatch.setattr(finite_study, "solve_finite_bonded_contact", large)
    argv = ["contact", "--model", "neo-hookean", "--interface", "bonded", "--friction", "0.5"]
    argv += ["--E2", "1e6", "--nu2", "0.49", "--exponent", "1.5", "--shape-coefficient", "5"]
    argv += ["--mesh-size", "0.2", "--domain-factor", "100", "--refine", "0.5"]
    argv += ["--no-estimate", "--depths", f"{DEEPEST:.6g}", "--json"]
    code = main(argv)
    out, err = capsys.readouterr()
    return code, out, err


def test_the_cuts_are_in_the_json_and_a_warning(monkeypatch, capsys):
    code, out, err = _cli(monkeypatch, capsys)
    assert code == 0
    assert json.loads(out)["load_steps_cut"] == 1
    assert "warning: retried: 1 of the load steps cut in halves" in err
    with pytest.warns(RetriedWarning, match="1 of the load steps cut in halves"):
        # Coulomb 0.5 at _cli's ratio LARGE
        result = finite_study.run_finite_study(INDENTER, RUBBER, [DEEPEST], ROUGH, friction=0.5)
    assert result.to_dict()["load_steps_cut"] == 1


def test_a_frictionless_curve_writes_no_cuts():
    free = finite_study.run_finite_study(INDENTER, RUBBER, [DEEPEST / 8.0], ROUGH)
    assert free.curve.cuts is None and "load_steps_cut" not in free.to_dict()


def test_exhausted_cuts_exit_1_in_one_line_of_options(monkeypatch, capsys):
    monkeypatch.setattr(finite_stick, "MAX_LOAD_CUTS", 0)
    code, _, err = _cli(monkeypatch, capsys)
    assert code == 1  # a numerical failure (exit 2: bad input)
    err = err.strip()
    assert "\n" not in err and "--mesh-size" in err and "--depths" in err
