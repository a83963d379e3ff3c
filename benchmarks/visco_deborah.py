"""Restitution of the dynamic FE impact against the Deborah number t_c / tau, one Prony term.

The paper's striker (0.7 kg, 3 m/s, A = 5 m^-1/2, n = 3/2, rigid) on the rubber half-space
(E2 = 7.5 MPa instantaneous, nu2 = 0.5) with one term g (default 0.5) at tau = t_c / De (t_c the
glassy compression time). Per De: the quasi-static reference (Lee-Radok/Ting), the FE without
inertia (density 0: hysteresis only) and with it (density 1100 kg/m^3: waves and hysteresis),
beside the elastic dynamic run (waves only, the row De = 0).

Run: python benchmarks/visco_deborah.py [--weight G] [--steps N] [--size H]
"""

from __future__ import annotations

import argparse

import numpy as np

from shtaerman.fem.dynamic_contact import DynamicSettings, run_dynamic_impact
from shtaerman.theory.contact import PowerLawContact
from shtaerman.theory.impact import solve_impact
from shtaerman.theory.indenter import PowerLawIndenter
from shtaerman.theory.materials import RIGID, Material, effective_modulus
from shtaerman.theory.viscoelastic import PronySeries, viscoelastic_impact

INDENTER, RUBBER, MASS, VELOCITY = PowerLawIndenter(5.0, 1.5), Material(7.5e6, 0.5), 0.7, 3.0
LAW = PowerLawContact(INDENTER, effective_modulus(RIGID, RUBBER))
T_C = solve_impact(MASS, VELOCITY, LAW).t_c
DEBORAH = np.logspace(-2, 2, 9)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--weight", type=float, default=0.5)
    parser.add_argument("--steps", type=int, default=200)
    parser.add_argument("--size", type=float, default=1.0 / 40.0)
    args = parser.parse_args()
    settings = DynamicSettings(steps=args.steps, size=args.size)
    elastic = run_dynamic_impact(INDENTER, RUBBER, 1100.0, MASS, VELOCITY, settings)
    e_waves = elastic.restitution
    print(f"t_c = {T_C:.6e} s, g = {args.weight}; elastic (waves only): e {e_waves:.5f}")
    print("| t_c/tau | e Ting | e FE rho 0 | e FE rho 1100 | 1-e^2 rho 0 | 1-e^2 rho 1100 | heat |")
    print("|---|---|---|---|---|---|---|")
    for deborah in DEBORAH:
        prony = PronySeries((args.weight,), (T_C / deborah,))
        ting = viscoelastic_impact(MASS, VELOCITY, LAW, prony, steps=2000).restitution
        runs = [
            run_dynamic_impact(INDENTER, RUBBER, rho, MASS, VELOCITY, settings, prony=prony)
            for rho in (0.0, 1100.0)
        ]
        e0, e1 = (run.restitution for run in runs)
        heat = runs[1].viscoelastic["energy_dissipated_fraction"]
        print(
            f"| {deborah:.3g} | {ting:.5f} | {e0:.5f} | {e1:.5f} | {1 - e0**2:.4f} | "
            f"{1 - e1**2:.4f} | {heat:.4f} |",
            flush=True,
        )


if __name__ == "__main__":
    main()
