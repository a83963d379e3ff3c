"""Coulomb friction at finite strain (fem/contact/finite_stick.py, ``friction``).

Checks on the coarse mesh of tests/test_finite_bonded.py (the same mesh and load ladder for
every pair compared; the limits friction -> 0 and -> large, identities of the solver on any
mesh, on its rough mesh):
- nu2 = 0.5, d/a = 0.3, where the finite-strain bonded force exceeds the frictionless one:
  friction 0 gives the frictionless solver's force (its sliding nodes are the frictionless
  solver's active nodes), friction 1e3 the bonded one (no node slides). In between the force
  is NOT monotone in the coefficient: it exceeds the bonded force at 0.2 (the linear
  friction effect vanishes at nu2 = 0.5; what remains are the vertical component mu f' of the
  friction on the sloped indenter and the radii where nodes that slid stick again);
- small strain (d/a = 0.01, nu2 = 0.3): the force with friction 0.3 equals the linear solver's
  (fem/contact/stick.py) with the same coefficient and load steps, up to the finite-strain
  departure of the bonded pair (6.5e-4 at d/a = 0.01 in tests/test_finite_bonded.py).
"""

from __future__ import annotations

import functools
import json

import numpy as np
import pytest
from test_finite_bonded import COARSE, INDENTER, ROUGH, _depth, _quick, _systems

from shtaerman.cli import main
from shtaerman.cli.contact import finite_contact_text
from shtaerman.fem.contact.finite import solve_finite_contact
from shtaerman.fem.contact.finite_stick import solve_finite_bonded_contact
from shtaerman.fem.contact.linear import solve_contact
from shtaerman.fem.contact.stick import solve_bonded_contact
from shtaerman.fem.mesh import MeshSettings
from shtaerman.validation import InputError

RATIO = 1.44
"""The load steps' depth ratio of every run here (the same for the pairs compared)."""


@functools.cache
def _incompressible(frictions: tuple[float, ...], mesh: MeshSettings = COARSE) -> tuple:
    """Forces (N) at d/a = 0.3, nu2 = 0.5 on ``mesh``: frictionless, then with each friction
    coefficient of ``frictions`` (inf: bonded)."""
    depths = np.array([_depth(0.3)])
    finite, _, refined = _systems(0.5, depths[-1], mesh)
    free = solve_finite_contact(finite, INDENTER, depths, refined).steps[-1].force
    forces = [
        solve_finite_bonded_contact(
            finite, INDENTER, depths, refined, step_ratio=RATIO, friction=mu
        )
        .steps[-1]
        .force
        for mu in frictions
    ]
    return free, *forces


SOME = (0.2, np.inf)
"""The coarse mesh's frictions: a little, and bonded."""


def test_no_friction_is_frictionless_and_large_friction_is_bonded():
    free, _, bonded = _incompressible(SOME)
    assert bonded / free - 1.0 > 1e-3  # the finite-strain bonded effect (measured 1.46e-3)
    # the limits are the solver's identities on any mesh: on the rough one (2.3 CPU s for the
    # four runs; the coarse mesh's 1e-6 and 1e3 took 5.2)
    free, none, tiny, large, bonded = _incompressible((0.0, 1e-6, 1e3, np.inf), ROUGH)
    assert none == free  # friction 0 is solved as the frictionless contact
    # the sliding path's limit: the friction force is O(mu) of the normal one (measured 3.9e-8;
    # 3.8e-8 on the coarse mesh)
    assert tiny == pytest.approx(free, rel=1e-5)
    # no node slides, but the two modified Newtons reuse their factorizations differently,
    # so they agree to the Newton tolerance (corrections <= NEWTON_TOLERANCE, 1e-8 of the
    # depth): measured 2.6e-11 (1.4e-9 on the coarse mesh; bitwise with full Newton)
    assert large == pytest.approx(bonded, rel=1e-8)


def test_a_little_friction_stiffens_the_incompressible_contact():
    """mu = 0.2 raises the force above the frictionless one, as sticking does (the nodes that
    slide keep a share of the bonded effect)."""
    free, some, bonded = _incompressible(SOME)
    # measured against frictionless: +2.23e-3 (friction 0.2), +1.46e-3 (bonded). That a little
    # slip ends above the bonded force on this coarse mesh (two edge nodes slide) is not
    # asserted: on the default mesh the force rises with mu (benchmarks/FEM_NOTES.md)
    assert some / free - 1.0 > 5e-4
    assert bonded / free - 1.0 > 5e-4


def test_small_strain_friction_force_is_the_linear_one():
    depths = np.array([_depth(0.01)])
    finite, linear, refined = _systems(0.3, depths[-1])
    options = {"step_ratio": RATIO, "friction": 0.3}
    force = solve_finite_bonded_contact(finite, INDENTER, depths, refined, **options)
    free = solve_finite_contact(finite, INDENTER, depths, refined).steps[-1].force
    linear_force = solve_bonded_contact(linear, INDENTER.profile, depths, refined, **options)
    linear_free = solve_contact(linear, INDENTER.profile, depths, refined, aligned=False)
    ratio = linear_force.steps[-1].force / linear_free.steps[-1].force
    assert ratio > 1.01  # the linear friction effect at nu2 = 0.3 (measured 1.01366)
    # measured 8.5e-4: the finite-strain departure at d/a = 0.01
    assert force.steps[-1].force / linear_force.steps[-1].force == pytest.approx(1.0, abs=2e-3)
    # measured 1.01332
    assert force.steps[-1].force / free == pytest.approx(ratio, abs=1.5e-3)


def test_cli_shows_the_friction_at_finite_strain(monkeypatch, capsys):
    calls = _quick(monkeypatch)
    argv = ["contact", "--model", "neo-hookean", "--interface", "bonded", "--friction", "0.5"]
    argv += ["--no-estimate", "--E2", "1e6", "--mesh-size", "0.2", "--domain-factor", "100"]
    argv += ["--refine", "0.5", "--depths", f"{_depth(0.05):.6g}", "--json"]
    assert main(argv) == 0
    report = json.loads(capsys.readouterr().out)
    assert calls == [{"friction": 0.5}]
    assert report["mesh"]["friction"] == 0.5 and report["mesh"]["interface"] == "bonded"
    assert "bonded indenter (Coulomb friction 0.5)" in finite_contact_text(report)
    assert report["steps"][-1]["force"] > 0


@pytest.mark.parametrize(
    ("value", "words"),
    [("-0.1", "friction"), ("nan", "friction"), ("inf", "friction"), ("x", "--friction")],
)
def test_bad_friction_is_one_line_and_exit_2(value, words, capsys):
    argv = ["contact", "--model", "neo-hookean", "--interface", "bonded", "--friction", value]
    assert main(argv) == 2
    err = capsys.readouterr().err.strip()
    assert words in err and "\n" not in err


def test_bad_friction_is_an_input_error():
    depths = np.array([_depth(0.05)])
    finite, _, refined = _systems(0.5, depths[-1])
    for bad in (-1.0, float("nan")):
        with pytest.raises(InputError, match="friction"):
            solve_finite_bonded_contact(finite, INDENTER, depths, refined, friction=bad)


def test_the_coulomb_newton_reuses_its_factorization(monkeypatch):
    """The quasi-static Coulomb curve's Newton reuses factorizations (a modified Newton) and
    gives full Newton's force to within the Newton tolerance's effect. On the wiring tests'
    rough mesh (2.2 CPU s; 7.5 on the coarse mesh): the reuse is the solver's, not the mesh's."""
    import shtaerman.fem.contact.finite_stick as finite_stick
    from shtaerman.fem.solver import PatternSolver

    depths = np.array([_depth(0.3)])
    finite, _, refined = _systems(0.5, depths[-1], ROUGH)
    calls = {"factorizations": 0}
    factorized = PatternSolver.factorized

    def counting(self, *args):
        calls["factorizations"] += 1
        return factorized(self, *args)

    def run() -> tuple[float, int]:
        calls["factorizations"] = 0
        options = {"step_ratio": RATIO, "friction": 0.2}
        curve = solve_finite_bonded_contact(finite, INDENTER, depths, refined, **options)
        return curve.steps[-1].force, calls["factorizations"]

    monkeypatch.setattr(PatternSolver, "factorized", counting)
    modified, reused = run()
    monkeypatch.setattr(finite_stick, "_slide_reusable", lambda *args: None)  # full Newton
    full, every = run()
    assert reused < every / 2  # measured 31 against 117 (coarse mesh: 42 against 146)
    # Newton stops at corrections of 1e-8 of the depth; the FE error is ~1e-3 on the coarse
    # mesh, more on this one. measured 2.3e-11 (coarse mesh: 1.3e-11)
    assert modified == pytest.approx(full, rel=1e-7)
