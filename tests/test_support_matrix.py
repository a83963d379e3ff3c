"""The support matrix walked (issue 28, item 3): every cell that the table declares runnable
runs through sh.contact / sh.dynamic on a coarse mesh and gives a finite result; every refused
cell is refused before any work. The 54 linear cells all run here. Each of the 54 rubber cells
is walked once, the four rubber models taking the cells in turn (:func:`rubber_cells`): the
refused ones are refused, the :data:`QUICK` runnable ones run, and the :data:`SLOW` ones (a
Newton per time or load step; their costs: benchmarks/support_matrix.py's output) are built
here and run by benchmarks/support_matrix.py, which runs every rubber cell with every model."""

import math
import warnings

import pytest

import shtaerman as sh
from shtaerman.problem import Cell, support_table
from shtaerman.study.dynamic.accuracy import RetriedWarning

PAPER = sh.PowerLawIndenter(shape_coefficient=5.0, exponent=1.5)
PARTS = {
    "half-space": {},
    "layer bonded": {"thickness": 0.03, "base": "bonded"},
    "layer lubricated": {"thickness": 0.03, "base": "lubricated"},
    "frictionless": {},
    "bonded": {"interface": "bonded"},
    "coulomb": {"interface": "bonded", "friction": 0.3},
}
RUBBER_MODELS = {  # each with a shape that departs from neo-Hookean
    "neo-hookean": {},
    "mooney-rivlin": {"mooney_ratio": 0.2},
    "yeoh": {"yeoh": (-0.101, 0.0127)},  # Treloar's fit, fem/extended/rubber_models.toml
    "gent": {"gent_limit": 30.0},
}


def problem_of(cell: Cell, model: str = "neo-hookean") -> sh.Problem:
    """The paper's striker at 1 m/s in the parts of ``cell``; a rubber cell of ``model``."""
    keywords = {**PARTS[cell.geometry], **PARTS[cell.interface]}
    if cell.model == "rubber":
        keywords.update(model=model, **RUBBER_MODELS[model])
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


def rubber_cells() -> list[tuple[Cell, str, str]]:
    """Every rubber cell with a model and its verdict: the runnable cells take the four models
    in turn in the table's order, and so do the refused ones."""
    turns = {True: 0, False: 0}
    rows = []
    for cell, verdict in support_table():
        if cell.model == "rubber":
            runs = verdict == "runs"
            rows.append((cell, list(RUBBER_MODELS)[turns[runs] % len(RUBBER_MODELS)], verdict))
            turns[runs] += 1
    return rows


def _cell(relaxing: int, geometry: str, interface: str, loading: str) -> Cell:
    return Cell("rubber", bool(relaxing), geometry, interface, loading)


QUICK = frozenset(
    {  # with their model and cost class (the CPU seconds: the commits that set them)
        _cell(0, "half-space", "frictionless", "curve"),  # neo-Hookean, cheap
        _cell(0, "half-space", "bonded", "massless"),  # neo-Hookean, moderate
        _cell(0, "layer bonded", "frictionless", "curve"),  # Mooney-Rivlin, cheap
        _cell(0, "layer bonded", "frictionless", "massless"),  # Yeoh, moderate
        _cell(0, "layer bonded", "frictionless", "inertia"),  # Gent, moderate
        _cell(0, "layer bonded", "bonded", "massless"),  # Mooney-Rivlin, moderate
        _cell(0, "layer bonded", "coulomb", "massless"),  # neo-Hookean, moderate
    }
)
"""The runnable rubber cells run here: each model, geometry, interface and loading at least
once (Prony in :func:`test_the_mooney_rivlin_pad_with_prony_and_coulomb_runs`). The others
cost more with their model (their Newton per time or load step; the relaxing cells and the
bonded curves the most), all running (one inertial step cut in halves, Mooney-Rivlin with
Prony on the bonded half-space): :data:`SLOW`."""
SLOW = (
    frozenset(
        cell for cell, verdict in support_table() if cell.model == "rubber" and verdict == "runs"
    )
    - QUICK
)
"""The runnable rubber cells that only benchmarks/support_matrix.py runs; here they are built."""
LINEAR = [(cell, verdict) for cell, verdict in support_table() if cell.model == "linear"]
RUBBER = [row for row in rubber_cells() if row[0] not in SLOW]


@pytest.fixture
def few_rate_steps(monkeypatch):
    """A viscoelastic curve in 20 time steps, not 200: this test asks that it runs."""
    import functools

    import shtaerman.fem.contact.rate as module

    monkeypatch.setattr(module, "press_at_rate", functools.partial(module.press_at_rate, steps=20))


def _runs_or_is_refused(problem_of_cell, verdict: str) -> None:
    """The cell's problem is refused with its declared verdict, or runs to a finite force."""
    if verdict != "runs":
        with pytest.raises(sh.InputError, match=verdict.split(":")[0]):
            problem_of_cell()
        return
    force = solve(problem_of_cell())
    # the paper's striker pressed 2 mm (curve) or striking at 1 m/s (x_c 3.7 mm): a force of
    # the order of beta x^(5/3) = 2.78e6 x^(5/3) N, 90-250 N; a pad of 30 mm stiffens it
    assert math.isfinite(force) and 30.0 < force < 1000.0


@pytest.mark.parametrize(("cell", "verdict"), LINEAR, ids=lambda v: str(v))
def test_each_linear_cell_runs_or_is_refused_as_declared(cell, verdict, few_rate_steps):
    _runs_or_is_refused(lambda: problem_of(cell), verdict)


@pytest.mark.parametrize(("cell", "model", "verdict"), RUBBER, ids=lambda v: str(v))
def test_each_rubber_cell_runs_or_is_refused_as_declared(cell, model, verdict):
    _runs_or_is_refused(lambda: problem_of(cell, model), verdict)


@pytest.mark.parametrize(
    ("cell", "model"), [row[:2] for row in rubber_cells() if row[0] in SLOW], ids=lambda v: str(v)
)
def test_each_slow_rubber_cell_is_accepted_with_its_parts(cell, model):
    """Its run is benchmarks/support_matrix.py's: here the problem is built, not refused, with
    the parts of its cell."""
    problem = problem_of(cell, model)
    assert problem.cell == cell and problem.body.model == model


def test_the_mooney_rivlin_pad_with_prony_and_coulomb_runs():
    """The relaxing rubber cell that failed (audit30): Mooney-Rivlin r = 0.2, massless, Prony +
    bonded pad + Coulomb. Near separation the Newton failed at X = 0.5585 mm (50 steps, "did
    not converge"; 0.555 mm at the retry's 100 steps, "an element inverted"). A time step cut
    in halves (993a617) cured it at 50 steps but not at 100 (every cut to dt/16 failed at
    0.64 mm; 200 steps passed): the start extrapolated past the turn of the relaxing surface
    was at fault. The Newton now falls back to the last state
    (:meth:`shtaerman.fem.stepper.QuasiStaticBody._newton`) and no step is cut or retried.
    It stands for the neo-Hookean cell of its parts here."""
    problem = problem_of(_cell(1, "layer bonded", "coulomb", "massless"), "mooney-rivlin")
    with warnings.catch_warnings():
        warnings.simplefilter("error", RetriedWarning)  # no retry, no cut step
        result = sh.dynamic(problem, mesh_size=0.2, time_steps=50, estimate=False)
    assert result.retried is None
    # the pad's peak force: 246.6 N measured; the bound of the matrix (30-1000 N) is enough
    assert math.isfinite(result.P_max) and 30.0 < result.P_max < 1000.0
