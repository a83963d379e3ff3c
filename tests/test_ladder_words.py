"""The contact ladder's missing-estimate warning in each route's words (polish49): its advice
names the inputs to change as the user gave them, ``--refine`` on the command line, ``refine``
in a study or sweep file, ``refine=...`` in Python."""

from __future__ import annotations

import warnings
from types import SimpleNamespace

import pytest

from shtaerman.cli.common import in_option_words
from shtaerman.fem.mesh import MeshSettings
from shtaerman.problem import worded
from shtaerman.study.contact.accuracy import run_mesh_ladder
from shtaerman.study.dynamic.accuracy import EstimateMissingWarning
from shtaerman.validation import NumericalFailureError

ADVICE = {
    "python": "Another mesh (refine=..., mesh_size=...) may pass",
    "cli": "Another mesh (--refine, --mesh-size) may pass",
    "file": "Another mesh (refine, mesh_size) may pass",
}


def _middle_fails():
    """A solve whose second level (refine 1/sqrt(2)) fails; no mesh is built."""
    calls = []

    def solve(mesh):
        calls.append(mesh)
        if len(calls) == 2:
            raise NumericalFailureError("depth 0.005 m: the load step did not settle")
        return SimpleNamespace(mesh_stats={"dofs": 1}, timings={"total": 0.0})

    return solve


def _said(route):
    """The ladder's warning as ``route`` says it."""
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        if route == "cli":
            with in_option_words():
                run_mesh_ladder(_middle_fails(), MeshSettings(), partial=True)
        else:
            run_mesh_ladder(_middle_fails(), MeshSettings(), partial=True)
    [said] = [w for w in caught if w.category is EstimateMissingWarning]
    text = str(said.message)
    return worded(text, "file") if route == "file" else text


@pytest.mark.parametrize("route", ["python", "cli", "file"])
def test_missing_estimate_advice_is_in_the_routes_words(route):
    text = _said(route)
    assert text.startswith("no error estimate: a ladder level failed, refine 0.707: depth")
    assert text.endswith(ADVICE[route]), text
    if route != "python":  # no API keyword where the user gave options or keys
        assert "mesh_size=" not in text and "refine=" not in text, text
