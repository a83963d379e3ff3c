"""The support matrix walked: every cell of the linear body that the table declares runnable
runs through sh.contact / sh.dynamic on a coarse mesh and gives a finite result; every refused
cell is refused before any work (issue 28, item 3). The rubber cells are walked by
benchmarks/support_matrix.py (a minute or more of Newton iterations)."""

import math

import pytest

import shtaerman as sh
from shtaerman.problem import support_table

PAPER = sh.PowerLawIndenter(shape_coefficient=5.0, exponent=1.5)
PARTS = {
    "half-space": {},
    "layer bonded": {"thickness": 0.03, "base": "bonded"},
    "layer lubricated": {"thickness": 0.03, "base": "lubricated"},
    "frictionless": {},
    "bonded": {"interface": "bonded"},
    "coulomb": {"interface": "bonded", "friction": 0.3},
}


def problem_of(cell) -> sh.Problem:
    """The paper's striker at 1 m/s in the parts of ``cell``."""
    keywords = {**PARTS[cell.geometry], **PARTS[cell.interface]}
    if cell.model == "rubber":
        keywords["model"] = "neo-hookean"
    if cell.relaxing:
        keywords["prony"] = "0.3:2e-3"
    if cell.loading == "curve":
        keywords.update(depths=[1e-3, 2e-3], rate=1.0 if cell.relaxing else None)
        return sh.Problem.curve(PAPER, sh.Material(7.5e6, 0.5), **keywords)
    density = 0.0 if cell.loading == "massless" else 1100.0
    body = sh.Material(7.5e6, 0.5, density)
    return sh.Problem.impact(PAPER, body, mass=0.7, velocity=1.0, **keywords)


def solve(problem: sh.Problem) -> float:
    """The deepest force (N) of the problem's curve, or its impact's peak force."""
    if problem.loading.kind == "curve":
        return float(sh.contact(problem, estimate=False, mesh_size=0.2).force[-1])
    return sh.dynamic(problem, mesh_size=0.2, time_steps=50, estimate=False).P_max


LINEAR = [(cell, verdict) for cell, verdict in support_table() if cell.model == "linear"]


@pytest.fixture
def few_rate_steps(monkeypatch):
    """A viscoelastic curve in 20 time steps, not 200: this test asks that it runs."""
    import functools

    import shtaerman.fem.contact.rate as module

    monkeypatch.setattr(module, "press_at_rate", functools.partial(module.press_at_rate, steps=20))


@pytest.mark.parametrize(("cell", "verdict"), LINEAR, ids=lambda v: str(v))
def test_each_linear_cell_runs_or_is_refused_as_declared(cell, verdict, few_rate_steps):
    if verdict != "runs":
        with pytest.raises(sh.InputError, match=verdict.split(":")[0]):
            problem_of(cell)
        return
    force = solve(problem_of(cell))
    # the paper's striker pressed 2 mm (curve) or striking at 1 m/s (x_c 3.7 mm): a force of
    # the order of beta x^(5/3) = 2.78e6 x^(5/3) N, 90-250 N; a pad of 30 mm stiffens it
    assert math.isfinite(force) and 30.0 < force < 1000.0
