"""A Gent rubber near its limit is flagged at the same depth on every route (session 51).

Every route tells the run's :class:`shtaerman.guards.LockingWatch` each state it accepts (the
curves' load steps, the impacts' committed time steps); the first whose stretch
(I1bar - 3) / Jm is at :data:`shtaerman.guards.LOCKED` warns once, naming the depth where the
stretch crossed it, linear in the stretch between the last two accepted states. Session 50's
refusal depth was the routes' own (Jm 0.01: 1.02e-4 m on the frictionless curve, 1.37e-3 m
on the bonded one): how far a route goes past 0.999 Jm before a step fails depends on its steps.
"""

from __future__ import annotations

import math
import re
import warnings
from contextlib import nullcontext
from dataclasses import replace

import numpy as np
import pytest

from shtaerman.fem.contact.finite import run_finite_indentation
from shtaerman.fem.contact.finite_stick import solve_finite_bonded_contact
from shtaerman.fem.finite_dynamic import (
    FRICTION_AXIS,
    IMPACT_MARGIN,
    IMPACT_MESH,
    FiniteImpactSettings,
    prepare_finite_impact,
)
from shtaerman.fem.mesh import MeshSettings
from shtaerman.fem.rubber import GentLockError, rubber_model
from shtaerman.guards import LOCKED, LadderWarnings, LockingWatch, ValidityWarning
from shtaerman.theory.indenter import PowerLawIndenter
from shtaerman.theory.materials import Material

PAPER = PowerLawIndenter(5.0, 1.5)
E2 = 7.5e6
SAID = re.compile(
    r"locks from depth (\S+) m on: .* \(interpolated between (\S+) at (\S+) m and (\S+) at "
    r"(\S+) m\)"
)


def _crossings(run) -> list[tuple[float, float, float]]:
    """The locking warnings ``run()`` issued, also where it is then refused as locking
    (:class:`GentLockError`, unchanged): (crossing depth, the bracketing depths) in m."""
    with warnings.catch_warnings(record=True) as said:
        warnings.simplefilter("always")
        try:
            run()
        except GentLockError:
            pass
    found = [SAID.search(str(w.message)) for w in said if issubclass(w.category, ValidityWarning)]
    return [(float(m[1]), float(m[3]), float(m[5])) for m in found if m is not None]


def test_the_watch_warns_once_at_the_interpolated_crossing():
    watch = LockingWatch(0.01)
    watch.accept(1e-4, 0.9)
    with pytest.warns(ValidityWarning, match="gent_limit=0.01") as said:
        watch.accept(2e-4, 0.9995)
        watch.accept(3e-4, 0.9999)  # past it again: no second warning in the run
    assert len(said) == 1
    # linear in the stretch: 1e-4 + 1e-4 (0.999 - 0.9) / (0.9995 - 0.9)
    assert watch.crossed == pytest.approx(1e-4 + 1e-4 * 0.099 / 0.0995, rel=1e-12)
    assert "between 0.900000 at 0.0001 m and 0.999500 at 0.0002 m" in str(said[0].message)
    quiet = LockingWatch(math.inf)  # another rubber: its stretch is 0
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        quiet.accept(1e-3, 0.0)
    assert quiet.crossed is None and LOCKED == 0.999


def test_every_route_names_the_crossing_within_its_steps():
    """Jm 0.01 at 0.7 kg and 0.05 m/s (x_c 0.395 mm: the massless impact's 50 time steps of
    ~10 um bracket the crossing; at 3 m/s its first step already overshoots it and it is
    refused with no state accepted past 0.999), on one mesh (the impact's, sized by the same
    x_c): the curves' depths are 20 to x_c. Measured (mesh 0.3): frictionless curve 1.083e-4
    m, massless impact 1.088e-4 m (refused later, at 1.57e-4 m, where the curve runs on to
    x_c: the refusal stays route-dependent, the warning is not); bonded curve 2.49e-4 m,
    massless bonded impact 2.47e-4 m (the bonded contact holds the surface from flowing in
    under the tip: it locks deeper).

    Bound: the stretch grows with the depth between two accepted states, so the crossing of
    this mesh's rubber lies within each route's bracket; two routes' crossings differ by at
    most the wider bracket (the interpolation's resolution), whatever their steps."""
    rubber = rubber_model("gent", gent_limit=0.01)
    # the bonded impact's axis grading (1e-3) for all four routes; on the frictionless
    # impact's 1e-4 the bonded massless impact refused the lock without warning first
    mesh = replace(IMPACT_MESH, size=0.3, margin=IMPACT_MARGIN, axis_size=FRICTION_AXIS)
    settings = FiniteImpactSettings(50, mesh)
    massless = Material(E2, 0.5, 0.0)

    def impact(friction: float | None):
        def run():
            args = (PAPER, massless, 0.0, 0.7, 0.05, settings, rubber)
            prepare_finite_impact(*args, friction=friction).march()

        return run

    x_c = prepare_finite_impact(PAPER, massless, 0.0, 0.7, 0.05, settings, rubber).scales[0]
    depths = x_c * np.linspace(0.05, 1.0, 20)
    body = Material(E2, 0.5)
    routes = {
        "frictionless curve": lambda: run_finite_indentation(PAPER, body, depths, mesh, rubber),
        "massless impact": impact(None),
        "bonded curve": lambda: run_finite_indentation(
            PAPER, body, depths, mesh, rubber, solve=solve_finite_bonded_contact
        ),
        "bonded massless impact": impact(math.inf),
    }
    found = {}
    for name, run in routes.items():
        [found[name]] = _crossings(run)  # once per run
        crossing, before, after = found[name]
        assert before < crossing <= after, name
    pairs = (("frictionless curve", "massless impact"), ("bonded curve", "bonded massless impact"))
    for pair in pairs:
        (a, a0, a1), (b, b0, b1) = (found[name] for name in pair)
        assert abs(a - b) <= max(a1 - a0, b1 - b0), (pair, found)
    assert found["bonded curve"][0] > 2.0 * found["frictionless curve"][0]  # the bonded locks later


def test_a_rubber_far_from_its_limit_does_not_warn():
    rubber = rubber_model("gent", gent_limit=30.0)
    depths = np.geomspace(1e-3, 8.5e-3, 4)
    mesh = MeshSettings(size=0.3)

    def curve():
        run_finite_indentation(PAPER, Material(E2, 0.5), depths, mesh, rubber)

    assert _crossings(curve) == []


def test_a_curve_to_x_c_past_the_limit_warns_and_runs():
    """adv49's Jm 0.2 at mesh 0.1: the curve reaches the paper's x_c, 8.517 mm, at stretch
    0.99984 Jm (no failed step: no refusal), past LOCKED from about 5.3 mm (session 50: 0.9946
    at 4.3 mm, 0.9991 at 5.32 mm)."""
    import shtaerman as sh

    def run():
        problem = dict(mass=0.7, velocity=3.0, model="gent", gent_limit=0.2)
        result = sh.contact(PAPER, Material(E2, 0.5), **problem, mesh_size=0.1, estimate=False)
        assert result.steps[-1]["depth"] == pytest.approx(8.517e-3, rel=1e-3)

    [(crossing, before, after)] = _crossings(run)
    assert 4e-3 < before < crossing <= after < 7e-3  # the depths that bracket 0.999 above


def test_the_command_line_says_it_once_for_the_reported_level(capsys):
    """With the error estimate the curve runs on three meshes, each crossing at its own depth
    (measured 6.37, 5.65, 5.33 mm at mesh 0.2): the reported (finest) level's warning alone
    is printed, as the impact's ladder does."""
    from shtaerman.cli import main

    code = main(["contact", "--model", "gent", "--gent-limit", "0.2", "--mesh-size", "0.2"])
    err = capsys.readouterr().err
    assert code == 0 and err.count("\n") == 1, err
    head = "shtaerman: warning: the Gent rubber locks from depth "
    assert err.startswith(head) and "of its limit --gent-limit 0.2 there" in err, err
    assert 5e-3 < float(err.removeprefix(head).split()[0]) < 6e-3, err  # the finest: 5.33 mm


def test_a_sweep_case_records_the_warning(monkeypatch):
    import shtaerman.fem.finite_dynamic as finite_dynamic
    from shtaerman.sweep.engine import execute_case
    from shtaerman.sweep.kinds import KINDS
    from shtaerman.sweep.spec import parse_sweep

    coarse = MeshSettings(size=0.15, domain=1e3, growth=0.35, axis_size=1e-3, axis_growth=0.25)
    monkeypatch.setattr(finite_dynamic, "IMPACT_MESH", coarse)  # test_sweep_finite_impact's
    spec = parse_sweep(
        'name = "gent"\nkind = "dynamic"\n[parameters]\nmodel = "gent"\ngent_limit = 0.01\n'
        "density2 = 0.0\ntime_steps = 50\nestimate = false\nmass = 0.7\n[axes]\n"
        "velocity = [0.05]\n"
    )
    (case,) = spec.cases()
    row = execute_case(KINDS["dynamic"].case, case.index, case.params)
    assert row["status"] == "ok", row["error"]
    [said] = [text for text in row["warnings"] if "Gent rubber locks from depth" in text]
    assert "of its limit gent_limit = 0.01 there" in said, said  # in the file's words


def _three_level_ladder(finest_fails: bool) -> None:
    """A ladder whose levels each warn of a lock and of a retried step; the finest raises."""
    with LadderWarnings() as said:
        for level in ("coarse", "middle", "fine"):
            try:
                with said.level():
                    warnings.warn(
                        f"locks at the {level} level's depth", ValidityWarning, stacklevel=1
                    )
                    warnings.warn(f"a step of the {level} level retried", UserWarning, stacklevel=1)
                    if level == "fine":
                        raise ArithmeticError("the finest level fails")
            except ArithmeticError:
                if finest_fails:
                    raise


def test_a_ladder_says_its_reported_levels_validity_warnings_and_every_levels_others():
    """The levels of a mesh ladder cross LOCKED at their own depths: only the reported level
    says its validity warnings (the last that passed; or the one whose error ends the ladder,
    as a Gent lock's refusal, whose warning of the crossing comes first), and every passed
    level its other warnings (a retried step, say), each naming the caller's line."""
    for raised in (False, True):
        with warnings.catch_warnings(record=True) as caught:
            warnings.simplefilter("always")
            with pytest.raises(ArithmeticError) if raised else nullcontext():
                _three_level_ladder(finest_fails=raised)
        assert [(w.category, str(w.message)) for w in caught] == [
            (UserWarning, "a step of the coarse level retried"),
            *([(ValidityWarning, "locks at the middle level's depth")] * (not raised)),
            (UserWarning, "a step of the middle level retried"),
            *([(ValidityWarning, "locks at the fine level's depth")] * raised),
            *([(UserWarning, "a step of the fine level retried")] * raised),
        ]
        assert {w.filename for w in caught} == {__file__}
