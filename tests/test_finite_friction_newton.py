"""The Newton of the Coulomb contact at finite strain (fem/contact/finite_stick.py), its cost.

- the sliding nodes' friction is linearized in the multiplier: the eliminated step solves the
  unsymmetric saddle system [[K, -W_A^T], [-G_A, 0]], W_i = (f' - s mu, -(1 + s mu f'));
- :class:`HistoryStepper` solves each time step's load step at the secant's nearby depths:
  a repeated solve starts each contact set's Newton from that set's last solution and ends
  at the same contact (to Newton's tolerance) for a fraction of the cost.
"""

from __future__ import annotations

import numpy as np
import pytest

from shtaerman.fem.contact.finite import (
    NEWTON_TOLERANCE,
    NewtonStepper,
    eliminate_gaps,
    geometric_radius,
)
from shtaerman.fem.contact.finite_stick import HistoryStepper
from shtaerman.fem.hyperelastic import NeoHookean, assemble_hyperelastic
from shtaerman.fem.mesh import MeshSettings
from shtaerman.theory.indenter import PowerLawIndenter

INDENTER = PowerLawIndenter(5.0, 1.5)
E2 = 1.0e6
COARSE = MeshSettings(size=0.1, domain=1e3, growth=0.3, axis_size=1e-4, axis_growth=0.2)
"""The coarse mesh of tests/test_finite_bonded.py."""


def test_the_friction_step_solves_its_unsymmetric_saddle_system():
    system = assemble_hyperelastic(COARSE.build(5e-3), NeoHookean(E2, 0.49))
    stepper = NewtonStepper(system, INDENTER, 5e-3, 1e-8, 5)
    nodes, free = stepper.nodes, stepper.free
    x = np.zeros(system.n_dofs)
    x[nodes.ur] = 1e-6 * nodes.radius  # curved candidates
    rows = np.arange(1, 7)  # node 0 (axis) has no u_r
    drag = np.zeros(nodes.radius.size)
    drag[rows] = 0.5 * np.array([1, -1, 1, 1, -1, 1])  # slip x mu
    _, gap, slope, _ = stepper.geometry(x, 1e-4)
    residual = system.residual(x)[free]
    tangent = system.tangent_data(x)[stepper.take]
    du, dlam = eliminate_gaps(stepper, tangent, residual, rows, slope, gap, drag)

    matrix = stepper.pattern.matrix(tangent)
    position = stepper.position
    pushed = np.zeros((rows.size, free.size))  # W_A: the multipliers' direction
    pushed[np.arange(rows.size), position[nodes.uz[rows]]] = -(1 + drag[rows] * slope[rows])
    pushed[np.arange(rows.size), position[nodes.ur[rows]]] = slope[rows] - drag[rows]
    forces = matrix @ du - pushed.T @ dlam + residual
    scale = abs(matrix) @ abs(du) + abs(pushed.T) @ abs(dlam) + abs(residual)
    # componentwise backward error: round-off over SuperLU's (checked at 1e-8); the
    # frictionless elimination's is 1.6e-15 (tests/test_fem_hyperelastic.py)
    assert np.max(abs(forces) / scale) <= 1e-10
    closing = slope[rows] * du[position[nodes.ur[rows]]] - du[position[nodes.uz[rows]]]
    assert np.allclose(-closing, gap[rows], rtol=0, atol=1e-14 * np.max(abs(gap[rows])))


def test_a_repeated_solve_is_warm_and_ends_at_the_same_contact():
    depth = 5.0 * (0.2 / 5.0) ** 3  # d/a = 0.2 on z = 5 r^1.5
    refined = COARSE.margin * geometric_radius(INDENTER, depth)
    system = assemble_hyperelastic(COARSE.build(refined), NeoHookean(E2, 0.49))
    stepper = HistoryStepper(system, INDENTER, refined, (NEWTON_TOLERANCE, 30), 0.5)
    zero, lam = np.zeros(system.n_dofs), np.zeros(stepper.nodes.radius.size)
    x, force, cold, _ = stepper.solve(depth, zero, lam)
    nearby = depth * (1 + 1e-9)  # the secant's last evaluations differ by ~1e-9
    x_again, force_again, warm, _ = stepper.solve(nearby, zero, lam)  # the same start
    assert stepper.latest[0].slip.any()  # the case slides (else no friction is tested)
    # each contact set's Newton converges in one iteration from its own solution (a change of
    # 1e-9 of the depth moves it by ~1e-9 < the tolerance 1e-8); cold: several each
    assert warm < cold / 2, (warm, cold)
    assert np.max(abs(x_again - x)[: system.n_displacement]) <= 1e-7 * depth
    assert force_again.sum() == pytest.approx(force.sum(), rel=1e-7)


def test_a_bonded_step_failure_beyond_the_validated_depth_names_the_limit():
    """The pad struck by z = 8 r^1.3 (x/a 2.29) fails near separation with friction 0.5 (its
    last ring in contact slides back and folds the surface; 2 min on a coarse mesh, not run
    here): the message names x/a beyond 1.2 and the options, not the time steps."""
    from shtaerman.fem.hyperelastic import NewtonError
    from shtaerman.fem.stepper import _step_failure

    indenter = PowerLawIndenter(8.0, 1.3)
    system = assemble_hyperelastic(COARSE.build(5e-3), NeoHookean(E2, 0.49))
    stepper = HistoryStepper(system, indenter, 5e-3, (NEWTON_TOLERANCE, 30), 0.5)
    folded = NewtonError("the contact surface folded (candidate nodes crossed)")
    deep = _step_failure(stepper, (0.0101, 1.5e-3, 5.2e-3), folded)
    assert "x/a = 2.2" in str(deep) and "beyond" in str(deep)
    # the API's words (problem.worded spells them per route: --interface frictionless)
    assert "interface='frictionless'" in str(deep) and "shape_coefficient=..." in str(deep)
    shallow = _step_failure(stepper, (0.0101, 1.5e-4, 2e-4), folded)
    assert "x/a" not in str(shallow) and "density2=0" in str(shallow)


def test_a_repeated_solve_reuses_the_factorizations_of_its_contact_sets(monkeypatch):
    """The secant's second solve of a time step goes through the same contact sets as the
    first: it reuses their kept factorizations (the last KEPT_SETS sets) and factorizes none."""
    from shtaerman.fem.solver import PatternSolver

    depth = 5.0 * (0.2 / 5.0) ** 3  # d/a = 0.2 on z = 5 r^1.5
    refined = COARSE.margin * geometric_radius(INDENTER, depth)
    system = assemble_hyperelastic(COARSE.build(refined), NeoHookean(E2, 0.49))
    stepper = HistoryStepper(system, INDENTER, refined, (NEWTON_TOLERANCE, 30), 0.5)
    zero, lam = np.zeros(system.n_dofs), np.zeros(stepper.nodes.radius.size)
    calls = {"factorizations": 0}
    factorized = PatternSolver.factorized

    def counting(self, *args):
        calls["factorizations"] += 1
        return factorized(self, *args)

    monkeypatch.setattr(PatternSolver, "factorized", counting)
    stepper.solve(depth, zero, lam)
    assert calls["factorizations"] > 1  # measured 7
    calls["factorizations"] = 0
    stepper.solve(depth * (1 + 1e-9), zero, lam)
    sets = len(stepper.kept_slide)
    assert sets > 1  # the solve went through several contact sets (measured 4)
    assert calls["factorizations"] == 0  # measured none (with one kept set: 4)


def test_a_coulomb_newton_builds_no_matrix_for_its_products(monkeypatch):
    """The stuck nodes' prescribed u_r enter a Newton step's load through K times their shift
    (zero after a contact set's first iteration), the gaps through K times theirs, and the
    multipliers are rows of K du: sums over the few columns or rows concerned
    (:func:`.finite.column_product`, :func:`.finite.row_product`), no sparse K built for
    them. The only matrices built are the factorizations' own (PatternSolver.factorized)."""
    from shtaerman.fem.solver import Pattern, PatternSolver

    depth = 5.0 * (0.2 / 5.0) ** 3  # d/a = 0.2 on z = 5 r^1.5
    refined = COARSE.margin * geometric_radius(INDENTER, depth)
    system = assemble_hyperelastic(COARSE.build(refined), NeoHookean(E2, 0.49))
    stepper = HistoryStepper(system, INDENTER, refined, (NEWTON_TOLERANCE, 30), 0.5)
    built, factorizing, matrix, factorized = [], [], Pattern.matrix, PatternSolver.factorized

    def build(self, data):
        built.append(bool(factorizing))
        return matrix(self, data)

    def factorize(self, data, rhs):
        factorizing.append(1)
        try:
            return factorized(self, data, rhs)
        finally:
            factorizing.pop()

    monkeypatch.setattr(Pattern, "matrix", build)
    monkeypatch.setattr(PatternSolver, "factorized", factorize)
    zero, lam = np.zeros(system.n_dofs), np.zeros(stepper.nodes.radius.size)
    _, _, iterations, _ = stepper.solve(depth, zero, lam)
    assert stepper.latest[0].slip.any()  # the case slides (else the sliding Newton is idle)
    # before: one K per iteration for the gap elimination, plus one per contact set whose
    # stuck nodes move (39 for 27 iterations); now 11, each in one of the 7 factorizations
    assert iterations > 0 and built and all(built), (built, iterations)
