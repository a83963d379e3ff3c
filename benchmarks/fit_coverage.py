"""Coverage of the 95 % intervals of ``sh.fit`` over seeds of 1 % noise, per kind of measurement.

The paper's striker (0.7 kg, 3 m/s, A = 5 m^-1/2, n = 3/2, steel 2e11 Pa / 0.25) on a rubber of
E2 = 7.5 MPa, nu2 = 0.5; the synthetic data come from the suite's exact forward models, with
seeded Gaussian noise, and the noise is estimated from the residual (Student's t intervals):

- indentation: 30 depths up to 5 mm, noise 1 % of the largest force -> E2;
- force-history: the elastic drop test sampled at 300 instants over 20 ms, touching at 1 ms on
  a 0.5 N baseline, noise 1 % of P_c -> E2, time offset, baseline;
- rebound: e and t_c at 5 velocities (0.5-4 m/s) of the viscoelastic impact with one Prony
  term g = 0.3, tau = 2 ms, relative noise 1 % -> E2, g1;
- relaxing-history: the viscoelastic drop test of that term (Lee-Radok, Ting) sampled at 300
  instants over 20 ms, noise 1 % of its peak, the relaxation time free (started at 1 ms, g1
  at 0.1) -> E2, g1, tau1.

A stated 95 % interval should cover the truth in 90-99 % of 50 seeds (binomial sd 3 %).

Run: python benchmarks/fit_coverage.py [--seeds N] [--kinds indentation,force-history,...]
"""

from __future__ import annotations

import argparse
import time

import numpy as np

import shtaerman as sh
from shtaerman.theory.contact import PowerLawContact
from shtaerman.theory.impact import solve_impact
from shtaerman.theory.viscoelastic import PronySeries, viscoelastic_impact

INDENTER = sh.PowerLawIndenter(5.0, 1.5)
STEEL = sh.Material(2e11, 0.25)
E2, MASS, VELOCITY = 7.5e6, 0.7, 3.0
E_STAR = 1.0 / (STEEL.compliance + 0.75 / E2)
STEPS = 40
TRUE = {"E2": E2, "time_offset": 1e-3, "baseline": 0.5, "g1": 0.3, "tau1": 2e-3}


def case(prony: str | None = None) -> sh.Problem:
    extra = {"prony": prony} if prony else {}
    return sh.Problem.impact(INDENTER, sh.Material(5e6, 0.5), mass=MASS, velocity=VELOCITY,
                             striker=STEEL, **extra)  # fmt: skip


def indentation(rng: np.random.Generator) -> sh.FitResult:
    depth = np.linspace(2e-4, 5e-3, 30)
    force = PowerLawContact(INDENTER, E_STAR).force(depth)
    force = force + 0.01 * force[-1] * rng.standard_normal(depth.size)
    return sh.fit("indentation", {"depth": depth, "force": force}, case())


def force_history(rng: np.random.Generator) -> sh.FitResult:
    impact = solve_impact(MASS, VELOCITY, PowerLawContact(INDENTER, E_STAR))
    time_ = np.linspace(0.0, 0.02, 300)
    t = time_ - TRUE["time_offset"]
    inside = (t > 0) & (t < impact.t_y)
    force = np.full(t.size, TRUE["baseline"])
    force[inside] += impact.history(times=t[inside]).P
    force += 0.01 * impact.P_c * rng.standard_normal(t.size)
    return sh.fit("force-history", {"time": time_, "force": force}, case(),
                  unknowns="E2,time_offset,baseline")  # fmt: skip


REBOUND: dict[str, np.ndarray] = {}


def rebound(rng: np.random.Generator) -> sh.FitResult:
    velocity = np.array([0.5, 1.0, 2.0, 3.0, 4.0])
    if "e" not in REBOUND:
        law = PowerLawContact(INDENTER, E_STAR)
        prony = PronySeries((TRUE["g1"],), (2e-3,))
        runs = [viscoelastic_impact(MASS, v, law, prony, steps=STEPS) for v in velocity]
        REBOUND["e"] = np.array([r.restitution for r in runs])
        REBOUND["t"] = np.array([r.t_contact for r in runs])
    data = {
        "velocity": velocity,
        "restitution": REBOUND["e"] * (1 + 0.01 * rng.standard_normal(5)),
        "contact_time": REBOUND["t"] * (1 + 0.01 * rng.standard_normal(5)),
    }
    return sh.fit("rebound", data, case("0.1:2e-3"), unknowns="E2,prony", steps=STEPS)


def relaxing_history(rng: np.random.Generator) -> sh.FitResult:
    time_ = np.linspace(0.0, 0.02, 300)
    if "history" not in REBOUND:
        law = PowerLawContact(INDENTER, E_STAR)
        run = viscoelastic_impact(MASS, VELOCITY, law, PronySeries((0.3,), (2e-3,)), steps=STEPS)
        REBOUND["history"] = np.interp(time_, run.history["t"], run.history["P"], right=0.0)
    force = REBOUND["history"]
    force = force + 0.01 * np.max(force) * rng.standard_normal(time_.size)
    return sh.fit("force-history", {"time": time_, "force": force}, case("0.1:1e-3"),
                  unknowns="E2,prony,tau", steps=STEPS)  # fmt: skip


KINDS = {"indentation": indentation, "force-history": force_history, "rebound": rebound,
         "relaxing-history": relaxing_history}  # fmt: skip


def coverage(kind: str, seeds: int) -> dict[str, float]:
    """Fraction of seeds whose interval holds the truth, per fitted name."""
    hits: dict[str, list[bool]] = {}
    for seed in range(seeds):
        result = KINDS[kind](np.random.default_rng(seed))
        for name, item in result.fitted.items():
            inside = item["identifiable"] and item["low"] <= TRUE[name] <= item["high"]
            hits.setdefault(name, []).append(bool(inside))
    return {name: float(np.mean(values)) for name, values in hits.items()}


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--seeds", type=int, default=50)
    parser.add_argument("--kinds", default=",".join(KINDS))
    args = parser.parse_args()
    print(f"{'kind':<15} {'unknown':<12} coverage of the 95 % interval ({args.seeds} seeds)")
    for kind in args.kinds.split(","):
        start = time.perf_counter()
        for name, value in coverage(kind, args.seeds).items():
            print(f"{kind:<15} {name:<12} {100 * value:5.1f} %")
        print(f"{'':<15} ({time.perf_counter() - start:.1f} s)")


if __name__ == "__main__":
    main()
