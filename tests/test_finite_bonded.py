"""The bonded (no-slip) indenter at finite strain (fem/contact/finite_stick.py).

Checks, on coarse meshes (the same mesh for every pair compared, so that most of the FE error
cancels in the ratios):
- small strain (d/a = 0.01, nu2 = 0.3, where bonded differs from frictionless in linear theory,
  Spence): the finite-strain bonded force equals the linear bonded one (fem/contact/stick.py) up
  to the finite-strain departure, which grows like d/a (the frictionless pair departs by 1.2e-3 at
  d/a = 0.01, 2.4e-3 at 0.02 on this mesh; the bonded pair by 0.6e-3, 1.1e-3), and the bonded /
  frictionless ratio reproduces the linear one to the same order;
- nu2 = 0.5: the linear bonded and frictionless forces coincide (Dundurs beta = 0), the
  finite-strain ones do not: the bonded force is higher, by 2.6e-3 at d/a = 0.3;
- energy: the stuck nodes do not move radially, so the radial reactions do no work and
  int P dd (Simpson over the load steps) is the stored energy, up to the ladder's
  interpolation of the touching radii (9.7e-4 at step ratio 1.2, 3.4e-4 at 1.095);
- the load ladder: halving ln(step ratio) from ln 1.44 changes the force at d/a = 0.3 by
  1.3e-3, then 1.8e-4 (second order).
"""

from __future__ import annotations

import functools
import json
import math

import numpy as np
import pytest
from scipy.integrate import simpson

import shtaerman as sh
import shtaerman.fem.contact.finite_stick as finite_stick
import shtaerman.study.finite.indentation as finite_study
from shtaerman.cli import main
from shtaerman.cli.contact import finite_contact_text
from shtaerman.fem.contact.finite import (
    geometric_radius,
    solve_finite_contact,
)
from shtaerman.fem.contact.finite_stick import solve_finite_bonded_contact
from shtaerman.fem.contact.linear import solve_contact
from shtaerman.fem.contact.stick import solve_bonded_contact
from shtaerman.fem.elasticity import assemble
from shtaerman.fem.hyperelastic import NeoHookean, assemble_hyperelastic
from shtaerman.fem.mesh import MeshSettings
from shtaerman.theory.indenter import PowerLawIndenter
from shtaerman.theory.materials import Material
from shtaerman.validation import InputError

INDENTER = PowerLawIndenter(5.0, 1.5)
E2 = 1.0e6
COARSE = MeshSettings(size=0.1, domain=1e3, growth=0.3, axis_size=1e-4, axis_growth=0.2)
ROUGH = MeshSettings(size=0.2, domain=1e2, growth=0.5, axis_size=1e-3, axis_growth=0.3)
"""The wiring tests' mesh."""
LADDER_RANGE = 89.44 * 27.0
"""Deepest depth / first load step of the nu2 = 0.5 runs: the first requested depth is 1/27
of the deepest (a/9), the first step a/20 of it."""


def _depth(ratio: float) -> float:
    """The depth (m) of depth / contact radius ``ratio`` on z = 5 r^1.5 (d/a = 5 sqrt(a))."""
    return 5.0 * (ratio / 5.0) ** 3


def _systems(nu: float, depth: float, settings: MeshSettings = COARSE):
    refined = settings.margin * geometric_radius(INDENTER, depth)
    mesh = settings.build(refined)
    return assemble_hyperelastic(mesh, NeoHookean(E2, nu)), assemble(mesh, E2, nu), refined


def _linear_pair(system, depths, refined) -> tuple[float, float]:
    free = solve_contact(system, INDENTER.profile, depths, refined, aligned=False)
    stuck = solve_bonded_contact(system, INDENTER.profile, depths, refined)
    return free.steps[-1].force, stuck.steps[-1].force


@pytest.fixture(scope="module")
def small_strain():
    """Forces (N) at d/a = 0.01, nu2 = 0.3: finite free, finite bonded, linear pair."""
    depths = np.array([_depth(0.01)])
    finite, linear, refined = _systems(0.3, depths[-1])
    free = solve_finite_contact(finite, INDENTER, depths, refined).steps[-1].force
    bonded = solve_finite_bonded_contact(finite, INDENTER, depths, refined, step_ratio=1.1)
    return free, bonded.steps[-1].force, *_linear_pair(linear, depths, refined)


def _ladder(ratio: float, every: bool, settings: MeshSettings = COARSE) -> tuple:
    """The nu2 = 0.5 bonded run to d/a = 0.3 from the first load step deepest / LADDER_RANGE,
    reporting every load step from deepest / 27 on (or the deepest only), on ``settings``."""
    deepest = _depth(0.3)
    finite, linear, refined = _systems(0.5, deepest, settings)
    count = int(np.ceil(np.log(LADDER_RANGE) / np.log(ratio) - 1e-9))
    start = deepest / ratio**count
    depths = start * ratio ** np.arange(count + 1)
    depths[-1] = deepest
    depths = depths[depths >= deepest / 27.0] if every else depths[-1:]
    curve = solve_finite_bonded_contact(
        finite, INDENTER, depths, refined, step_ratio=ratio, start=start
    )
    return curve, finite, linear, refined


@functools.cache
def _incompressible(ratio: float):
    """The nu2 = 0.5 bonded run at a step ratio 1.44, 1.2 (every step) or sqrt(1.2), once per
    test process (each test asks only for the runs it needs)."""
    return _ladder(ratio, ratio == 1.2)


def test_small_strain_bonded_force_is_the_linear_one(small_strain):
    free, bonded, linear_free, linear_bonded = small_strain
    assert linear_bonded / linear_free > 1.01  # the linear bonded effect at nu2 = 0.3
    # measured 6.5e-4: the finite-strain departure at d/a = 0.01
    assert bonded / linear_bonded == pytest.approx(1.0, abs=2e-3)
    # measured 1.01564 against 1.01618
    assert bonded / free == pytest.approx(linear_bonded / linear_free, abs=1.5e-3)


def test_incompressible_bonded_departs_from_frictionless_at_finite_strain():
    curve, finite, linear, refined = _incompressible(np.sqrt(1.2))
    depths = np.array([_depth(0.1), _depth(0.2), _depth(0.3)])
    free = solve_finite_contact(finite, INDENTER, depths, refined).steps[-1].force
    linear_free, linear_bonded = _linear_pair(linear, depths, refined)
    assert abs(linear_bonded / linear_free - 1.0) < 5e-4  # Dundurs beta = 0 (measured 2.4e-4)
    assert curve.steps[-1].force / free - 1.0 > 1.5e-3  # measured +2.6e-3: stiffer


def test_work_of_the_force_is_the_stored_energy():
    curve = _incompressible(1.2)[0]
    depth = np.array([s.depth for s in curve.steps])
    force = np.array([s.force for s in curve.steps])
    energy = curve.steps[-1].strain_energy
    assert np.allclose(np.diff(np.log(depth))[:-1], np.log(1.2))  # every load step reported
    slope = np.log(force[1] / force[0]) / np.log(depth[1] / depth[0])
    work = force[0] * depth[0] / (slope + 1.0) + simpson(force * depth, x=np.log(depth))
    assert work / energy == pytest.approx(1.0, abs=2e-3)  # measured 9.7e-4
    assert all(s.strain_energy > 0 for s in curve.steps)


def test_the_load_ladder_converges():
    forces = [_incompressible(ratio)[0].steps[-1].force for ratio in (1.44, 1.2, np.sqrt(1.2))]
    coarse, fine = abs(forces[1] - forces[0]), abs(forces[2] - forces[1])
    assert fine < 0.3 * coarse  # measured 1.3e-3 then 1.8e-4 of the force
    assert fine < 5e-4 * forces[2]


def _quick(monkeypatch) -> list[dict]:
    """Make the bonded solver take load steps of ratio 2 (and record its calls)."""
    calls: list[dict] = []
    original = finite_stick.solve_finite_bonded_contact

    def quick(*args, **kwargs):
        calls.append(kwargs)
        return original(*args, step_ratio=2.0, **kwargs)

    monkeypatch.setattr(finite_study, "solve_finite_bonded_contact", quick)
    return calls


@pytest.mark.parametrize(
    ("model", "shape"),
    [
        ("neo-hookean", {}),
        ("mooney-rivlin", {"mooney_ratio": 0.3}),
        ("yeoh", {"yeoh": "0.1,0.01"}),
        ("gent", {"gent_limit": 20.0}),
    ],
)
def test_every_rubber_model_takes_the_bonded_path(model, shape, monkeypatch):
    calls = _quick(monkeypatch)
    common = {"depths": [_depth(0.05)], "mesh": ROUGH, "estimate": False, **shape}
    bonded = sh.contact(INDENTER, Material(E2, 0.5), interface="bonded", model=model, **common)
    assert len(calls) == 1 and bonded.mesh["interface"] == "bonded"
    step = bonded.steps[-1]
    # a coarse ladder and mesh: within a few % of Shtaerman's force at d/a = 0.05
    assert step["force"] == pytest.approx(step["force_analytic"], rel=0.05)
    assert step["strain_energy"] > 0 and step["contact_radius"] > 0


def test_cli_shows_the_bonded_interface(monkeypatch, capsys):
    _quick(monkeypatch)
    argv = ["contact", "--model", "neo-hookean", "--interface", "bonded", "--no-estimate"]
    argv += ["--E2", "1e6", "--mesh-size", "0.2", "--domain-factor", "100", "--refine", "0.5"]
    argv += ["--depths", f"{_depth(0.05):.6g}"]
    assert main([*argv, "--json"]) == 0
    report = json.loads(capsys.readouterr().out)
    assert "bonded indenter (no slip once in contact)" in finite_contact_text(report)
    assert report["mesh"]["interface"] == "bonded" and report["model"] == "neo-hookean"


@pytest.mark.parametrize(
    ("argv", "words"),
    [
        (["--interface", "bonded", "--model", "neo-hookean", "--friction", "-0.3"], "friction"),
        (["--interface", "glued", "--model", "neo-hookean"], "--interface"),
        (["--model", "yeoh", "--friction", "0.3"], "bonded indenter only"),
    ],
)
def test_bad_bonded_options_are_one_line_and_exit_2(argv, words, capsys):
    assert main(["contact", *argv]) == 2
    err = capsys.readouterr().err.strip()
    assert words in err and "\n" not in err


def test_bad_ladder_is_an_input_error():
    depths = np.array([_depth(0.05)])
    finite, _, refined = _systems(0.5, depths[-1])
    for kwargs, word in (({"step_ratio": 1.0}, "step_ratio"), ({"start": -1.0}, "start")):
        with pytest.raises(InputError, match=word):
            solve_finite_bonded_contact(finite, INDENTER, depths, refined, **kwargs)
    with pytest.raises(InputError, match="friction"):
        sh.contact(
            INDENTER,
            Material(E2, 0.5),
            model="neo-hookean",
            interface="bonded",
            friction=-0.5,
            depths=depths,
            estimate=False,
        )


def test_a_tensile_node_is_released_first_and_alone_when_cautious():
    """The active-set update: all violations at once; when cautious, the most tensile stuck
    node only, or if none the free node deepest below the indenter."""
    from types import SimpleNamespace

    from shtaerman.fem.contact.constraints import worst_only
    from shtaerman.fem.contact.finite_stick import _changes, _Load

    stepper = SimpleNamespace(tolerance=1e-8)
    held = np.array([0.0, 1.0, 2.0, np.nan, np.nan])
    lam = np.array([5.0, -1.0, -2.0, 0.0, 0.0])
    gap = np.array([0.0, 0.0, 0.0, -0.1, -0.3])
    trial = _Load(held, np.zeros(1), np.arange(5.0), gap, lam)

    def changes(cautious: bool) -> tuple[np.ndarray, np.ndarray]:
        found, excess, _ = _changes(stepper, trial, trial, math.inf, (1.0, 1.0))
        assert not (found[2].any() or found[3].any())  # bonded: nothing slides
        return tuple((worst_only(found, excess) if cautious else found)[:2])

    release, enter = changes(cautious=False)
    assert release.tolist() == [False, True, True, False, False]
    assert enter.tolist() == [False, False, False, True, True]
    release, enter = changes(cautious=True)
    assert release.tolist() == [False, False, True, False, False] and not enter.any()
    trial.lam = np.abs(lam)
    release, enter = changes(cautious=True)
    assert not release.any() and enter.tolist() == [False, False, False, False, True]


def test_the_bonded_newton_reuses_its_factorization(monkeypatch):
    """A modified Newton: the load steps share factorizations, and the forces are full
    Newton's to within the Newton tolerance's effect. On the wiring tests' rough mesh (2.2
    CPU s; 7.3 on the coarse mesh of the other nu2 = 0.5 runs): the reuse is the solver's,
    not the mesh's."""
    from shtaerman.fem.solver import PatternSolver

    calls = {"factorizations": 0}
    factorized = PatternSolver.factorized

    def counting(self, *args):
        calls["factorizations"] += 1
        return factorized(self, *args)

    monkeypatch.setattr(PatternSolver, "factorized", counting)
    curve = _ladder(1.44, every=True, settings=ROUGH)[0]
    modified = calls["factorizations"]
    monkeypatch.setattr(finite_stick, "_reusable", lambda *args: None)  # full Newton
    calls["factorizations"] = 0
    full = _ladder(1.44, every=True, settings=ROUGH)[0]
    # full Newton factorizes at every iteration
    assert calls["factorizations"] == sum(step.total_iterations for step in full.steps)
    assert modified < calls["factorizations"] / 3  # measured 10 against 134 (coarse: 13, 186)
    # Newton stops at corrections of 1e-8 of the depth (a reused step: one that shrank 5x):
    # the forces agree far below the FE error (~1e-3 on the coarse mesh, more on this one);
    # measured 1.5e-9 (coarse mesh: 7.9e-10)
    forces = np.array([[a.force, b.force] for a, b in zip(curve.steps, full.steps, strict=True)])
    assert np.allclose(forces[:, 0], forces[:, 1], rtol=1e-7, atol=0.0)


def test_added_stuck_dofs_are_held_by_the_capacitance():
    """The kept factorization (its own dofs prescribed) solves with more dofs prescribed:
    the solution of the matrix with those rows and columns replaced by the identity."""
    from shtaerman.fem.contact.finite_stick import _Kept

    rng = np.random.default_rng(3)
    size, own, more = 12, np.array([2, 7]), np.array([2, 4, 7, 9])
    matrix = rng.normal(size=(size, size))
    matrix = matrix @ matrix.T + size * np.eye(size)  # symmetric positive definite

    def reduced(slaves: np.ndarray) -> np.ndarray:
        out = matrix.copy()
        out[slaves, :], out[:, slaves] = 0.0, 0.0
        out[slaves, slaves] = 1.0
        return out

    kept = _Kept(None, own, np.zeros(1), lambda b: np.linalg.solve(reduced(own), b), size)
    load = rng.normal(size=size)
    load[more] = 0.0
    solve = kept.constrained(more)
    expected = np.linalg.solve(reduced(more), load)
    assert np.allclose(solve(load), expected, rtol=1e-12, atol=1e-14)  # exact up to round-off
    assert kept.constrained(np.array([4, 7])) is None  # dof 2 released: refactorize
