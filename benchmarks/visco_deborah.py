"""Restitution of the dynamic FE impact against the Deborah number t_c / tau, one Prony term.

The paper's striker (0.7 kg, 3 m/s, A = 5 m^-1/2, n = 3/2, rigid) on the rubber half-space
(E2 = 7.5 MPa instantaneous, nu2 = 0.5) with one term g (default 0.5) at tau = t_c / De (t_c the
glassy compression time). Per De: the quasi-static reference (Lee-Radok/Ting), the FE without
inertia (density 0: hysteresis only) and with it (density 1100 kg/m^3: waves and hysteresis),
beside the elastic dynamic run (waves only, the row De = 0).

``--ladder``: every FE run is the finest level of the dynamic study's error-estimate ladder
(:mod:`shtaerman.study.dynamic.accuracy`), and 1 - e^2 and the heat carry ± its estimate. The
two Deborah numbers where the hysteresis-only loss (Ting's exact quasi-static impact, which the
massless FE meets to 3e-5) equals the waves-only loss of the elastic run are then found by
bisection, with the range that the waves-only run's estimate leaves them.

Run: python benchmarks/visco_deborah.py [--weight G] [--steps N] [--size H] [--ladder]
"""

from __future__ import annotations

import argparse

import numpy as np
from scipy.optimize import brentq

from shtaerman.fem.dynamic_contact import DynamicSettings
from shtaerman.fem.impact import run_impact
from shtaerman.study.dynamic.case import run_case
from shtaerman.theory.contact import PowerLawContact
from shtaerman.theory.impact import solve_impact
from shtaerman.theory.indenter import PowerLawIndenter
from shtaerman.theory.materials import RIGID, Material, effective_modulus
from shtaerman.theory.viscoelastic import PronySeries, viscoelastic_impact

INDENTER, RUBBER, MASS, VELOCITY = PowerLawIndenter(5.0, 1.5), Material(7.5e6, 0.5), 0.7, 3.0
LAW = PowerLawContact(INDENTER, effective_modulus(RIGID, RUBBER))
T_C = solve_impact(MASS, VELOCITY, LAW).t_c
DEBORAH = np.logspace(-2, 2, 9)


def _run(density, settings, prony, ladder):
    """(result, {quantity: absolute error}) of one FE run; no errors without the ladder."""
    inputs = (INDENTER, RUBBER, density, MASS, VELOCITY, settings)
    if not ladder:
        return run_impact(*inputs, prony=prony), {}
    levels = run_case(*inputs, ladder=True, prony=prony).ladder
    return levels.finest, {k: e.absolute_error for k, e in levels.estimates.items()}


def _pm(errors, key):
    return f" ± {errors[key]:.1g}" if key in errors else ""


def _ting_loss(deborah, weight):
    prony = PronySeries((weight,), (T_C / deborah,))
    return 1.0 - viscoelastic_impact(MASS, VELOCITY, LAW, prony, steps=2000).restitution ** 2


def _crossovers(weight, waves, error):
    """The Deborah numbers where Ting's hysteresis-only loss equals ``waves`` (± ``error``)."""
    peak = DEBORAH[np.argmax([_ting_loss(d, weight) for d in DEBORAH])]
    for low, high in ((DEBORAH[0], peak), (peak, DEBORAH[-1])):
        found = [
            np.exp(brentq(lambda u, w=w: _ting_loss(np.exp(u), weight) - w, *np.log([low, high])))
            for w in (waves - error, waves, waves + error)
        ]
        print(f"hysteresis-only loss = waves-only loss at t_c/tau = {found[1]:.4g} "
              f"(range {min(found):.4g} .. {max(found):.4g})")  # fmt: skip


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--weight", type=float, default=0.5)
    parser.add_argument("--steps", type=int, default=200)
    parser.add_argument("--size", type=float, default=1.0 / 40.0)
    parser.add_argument("--ladder", action="store_true")
    args = parser.parse_args()
    settings = DynamicSettings(steps=args.steps, size=args.size)
    elastic, errors = _run(1100.0, settings, None, args.ladder)
    waves = elastic.energy_radiated_fraction
    print(f"t_c = {T_C:.6e} s, g = {args.weight}; elastic (waves only): e {elastic.restitution:.5f}"
          f", 1-e^2 {waves:.5f}{_pm(errors, 'energy_radiated_fraction')}")  # fmt: skip
    print("| t_c/tau | e Ting | e FE rho 0 | e FE rho 1100 | 1-e^2 rho 0 | 1-e^2 rho 1100 | heat |")
    print("|---|---|---|---|---|---|---|")
    for deborah in DEBORAH:
        prony = PronySeries((args.weight,), (T_C / deborah,))
        ting = viscoelastic_impact(MASS, VELOCITY, LAW, prony, steps=2000).restitution
        (r0, err0), (r1, err1) = (_run(rho, settings, prony, args.ladder) for rho in (0.0, 1100.0))
        heat = r1.losses["energy_dissipated_fraction"]
        loss = "energy_radiated_fraction"
        print(
            f"| {deborah:.3g} | {ting:.5f} | {r0.restitution:.5f} | {r1.restitution:.5f} | "
            f"{r0.energy_radiated_fraction:.4f}{_pm(err0, loss)} | "
            f"{r1.energy_radiated_fraction:.4f}{_pm(err1, loss)} | "
            f"{heat:.4f}{_pm(err1, 'energy_dissipated_fraction')} |",
            flush=True,
        )
    if args.ladder:
        _crossovers(args.weight, waves, errors["energy_radiated_fraction"])


if __name__ == "__main__":
    main()
