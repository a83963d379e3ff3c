"""A pad-plus-waves drop test fitted with its FE corrections: FE runs, time, E2 against truth.

A rigid striker (0.2 kg at 2 m/s, A = 5 m^-1/2, n = 3/2) drops on a rubber pad (E2 = 7.5 MPa,
nu2 = 0.45, 1100 kg/m^3) 20 mm thick, bonded to a rigid base. The "measurement" is a finer
FE run (``--truth-refine``, no estimate) sampled at 50 kHz from 1 ms before the touch, on a
0.5 N baseline, with Gaussian noise of 1 % of its peak. The fit knows the striker, the pad
and the density, starts from E2 = 5 MPa and fits E2, the time offset and the baseline, its
FE corrections on a coarse mesh (``--refine``, with its error estimate).

With ``--model neo-hookean`` the pad is a rubber at finite strain, the data and the
corrections are finite-strain FE runs. With ``--prony 0.3:2e-3`` the pad relaxes: the fit
knows tau_i, starts every weight at 0.1 and fits the weights too.

Run: python benchmarks/fit_fe_corrections.py [--seeds N] [--refine R] [--truth-refine R]
     [--model neo-hookean] [--prony G1:TAU1,...] [--write-csv pad.csv]
"""

from __future__ import annotations

import argparse
import time

import numpy as np

import shtaerman as sh

INDENTER = sh.PowerLawIndenter(5.0, 1.5)
E2, NU2, DENSITY, THICKNESS = 7.5e6, 0.45, 1100.0, 0.02
MASS, VELOCITY, OFFSET, BASELINE = 0.2, 2.0, 1e-3, 0.5


def case(e2: float, model: str, prony: str | None) -> sh.Problem:
    """The drop test with the pad and its density, at ``e2``, of body ``model``."""
    body = sh.Material(e2, NU2, density=DENSITY)
    return sh.Problem.impact(INDENTER, body, mass=MASS, velocity=VELOCITY, thickness=THICKNESS,
                             model=model, prony=prony)  # fmt: skip


def measurement(refine: float, seed: int, model: str, prony: str | None) -> dict[str, np.ndarray]:
    """The synthetic record: the FE force history at ``refine`` plus noise."""
    run = sh.dynamic(case(E2, model, prony), refine=refine, estimate=False)
    history = run.history()
    t = np.arange(0.0, 2.5 * run.t_contact + OFFSET, 2e-5)
    force = np.interp(t - OFFSET, history["t"], history["P"], left=0.0, right=0.0)
    noise = np.random.default_rng(seed).standard_normal(t.size) * 0.01 * run.P_max
    return {"time": t, "force": force + BASELINE + noise}


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--seeds", type=int, default=1)
    parser.add_argument("--refine", type=float, default=0.6)
    parser.add_argument("--model", default="linear", help="linear, or a rubber: neo-hookean")
    parser.add_argument("--prony", default=None, help="the true series g1:tau1,... (fitted)")
    parser.add_argument("--truth-refine", type=float, default=1.0)
    parser.add_argument("--write-csv", metavar="FILE", help="write seed 0's record, then stop")
    args = parser.parse_args()
    if args.write_csv:  # the docs' pad.csv: shtaerman fit force-history pad.csv ...
        data = measurement(args.truth_refine, 0, args.model, args.prony)
        table = np.c_[data["time"] * 1e3, data["force"]]
        np.savetxt(args.write_csv, table, delimiter=",", header="time [ms],force [N]", comments="")
        return
    print(f"truth E2 = {E2:.4g} Pa ({args.model}); data: FE at refine {args.truth_refine}, "
          f"1 % noise; fit: FE at refine {args.refine}")  # fmt: skip
    print(" seed  FE runs  time [s]  E2 fitted [Pa]  95 % interval [Pa]        covers  c_P    c_t")
    for seed in range(args.seeds):
        data = measurement(args.truth_refine, seed, args.model, args.prony)
        start_prony = None
        if args.prony:  # the fit knows tau_i and starts every weight at 0.1
            start_prony = ",".join(f"0.1:{t.split(':')[1]}" for t in args.prony.split(","))
        start = time.perf_counter()
        result = sh.fit(
            "force-history", data, case(5e6, args.model, start_prony),
            unknowns="E2,time_offset,baseline" + (",prony" if args.prony else ""),
            refine=args.refine, steps=100,
        )  # fmt: skip
        elapsed = time.perf_counter() - start
        e2 = result.fitted["E2"]
        covers = e2["low"] <= E2 <= e2["high"]
        c = result.corrections[0]
        print(
            f" {seed:4d}  {result.fe_runs:7d}  {elapsed:8.1f}  {e2['value']:14.5g}  "
            f"[{e2['low']:.5g}, {e2['high']:.5g}]  {covers!s:6}  {c['force_scale']:.4f} "
            f"{c['time_scale']:.4f}"
        )
        print(f"       forward error (E_star, Pa): {result.forward_error.get('E_star')}")
        for name, item in result.fitted.items():
            if name.startswith("g"):
                print(f"       {name} {item['value']:.4f} [{item['low']:.4f}, {item['high']:.4f}]")


if __name__ == "__main__":
    main()
