"""Dynamic FE impact: the paper's case, the quasi-static limit, the radiation estimate, convergence.

Run: python benchmarks/bench_dynamic.py [--quick]. Prints figures, observed orders and where the
time goes; asserts nothing about time. Sections:

(a) the paper's case (0.7 kg, 3 m/s, A = 5, n = 1.5, rubber 7.5 MPa / 0.5, rho2 = 1100) at the
    default settings, with the timing breakdown and the machine load;
(b) the nearly massless limit (rho2 = 1e-3) against the exact quasi-static impact;
(c) small radiated fractions (lambda ~ 0.04 by the first-order estimate) for n = 1.5 and
    n = 2 (sphere R = 5 cm), nu = 0.3, 0.4, 0.5: measured 1 - e^2 against lambda;
(d) convergence in the time step, (e) in the mesh, (f) in the domain radius;
(g) measured over estimated loss as lambda -> 0: the first-order estimate's own error.

Measured on 2 shared cores (load average 6-10 from other jobs), 2026-11-22:
(a) 13269 dofs, 798 steps: e = 0.926598, 1 - e^2 = 0.1414 (estimate 0.1568), x_max / x_c =
    0.9711, P_max / P_c = 0.9538, balance 2.1e-5, reflected 1.9e-3; 12-20 s wall (factorization
    once 1.0-1.3 s, stepping 10-17 s at 13-21 ms per step), 11 s CPU.
(b) rho2 = 1e-3: x_max -6.4e-5, P_max +3.4e-5, t_contact -5.2e-5, e - 1 = -4.3e-7.
(c) lambda = 0.04: measured / estimate 0.9730-0.9753 for n = 1.5, 2 and nu = 0.3, 0.4, 0.5.
(d) steps 100-800: x_max order 2.1, 1.8; e constant to 1.4e-6, P_max to 4e-5.
(e) size 1/20-1/160: x_max within 1.1e-5, e within 3.6e-5, P_max within 9e-4 (1.2e-4 between
    1/80 and 1/160): below the asymptotic range, no clean order.
(f) domain 1e3-1e5 refined radii: e within 1.0e-6, x_max within 2e-6.
(g) (1 - measured/estimate) / lambda = 0.66-0.69 (n = 1.5, nu = 0.5) and 0.61-0.68 (n = 2,
    nu = 0.3) for lambda = 0.08 .. 0.01: the gap vanishes linearly with lambda, so it is the
    estimate's second-order term, not a FEM error.
"""

import argparse
import itertools
import math
import os
import time
from dataclasses import replace

import numpy as np

from shtaerman.fem.dynamic_contact import DynamicSettings
from shtaerman.fem.impact import run_impact
from shtaerman.theory.contact import PowerLawContact
from shtaerman.theory.impact import solve_impact
from shtaerman.theory.indenter import PowerLawIndenter
from shtaerman.theory.materials import Material
from shtaerman.theory.radiation import radiation_estimate

MASS, VELOCITY, DENSITY = 0.7, 3.0, 1100.0
PAPER = PowerLawIndenter(5.0, 1.5)
SPHERE = PowerLawIndenter(1.0 / (2 * 0.05), 2.0)  # z = r^2 / (2 R), R = 5 cm
E2 = 7.5e6
KEYS = ("x_max", "P_max", "t_contact", "restitution")


def load() -> str:
    return "load average {:.1f} {:.1f} {:.1f}".format(*os.getloadavg())


def estimate(indenter, nu, velocity, density=DENSITY):
    material = Material(E2, nu)
    law = PowerLawContact(indenter, E2 / (1 - nu**2))
    return radiation_estimate(
        MASS, velocity, law.beta, law.force_exponent, density, material.shear_modulus, nu
    )


def exact(indenter, nu, velocity):
    return solve_impact(MASS, velocity, PowerLawContact(indenter, E2 / (1 - nu**2)))


def section_paper(settings):
    print(f"\n(a) paper's case, default settings, {load()}")
    start = time.perf_counter()
    run = run_impact(PAPER, Material(E2, 0.5), DENSITY, MASS, VELOCITY, settings)
    wall = time.perf_counter() - start
    qs = exact(PAPER, 0.5, VELOCITY)
    lam = estimate(PAPER, 0.5, VELOCITY)
    for key, value in run.summary().items():
        print(f"  {key:28s} {value:.6g}")
    print(f"  quasi-static x_c {qs.x_c:.6g} m, P_c {qs.P_c:.6g} N, t_y {qs.t_y:.6g} s")
    print(f"  first-order lambda {lam.energy_fraction:.4f} (beyond its range at 0.157)")
    print(
        f"  mesh {run.mesh['dofs']} dofs ({run.mesh['estimated_dofs']} estimated), "
        f"{run.mesh['contact_candidates']} contact candidates, {len(run.t) - 1} steps"
    )
    timings = run.timings
    steps = len(run.t) - 1
    print(
        "  time: "
        + ", ".join(f"{k} {v:.2f} s" for k, v in timings.items())
        + f" (wall {wall:.2f} s, {1e3 * timings['stepping'] / steps:.2f} ms per step), {load()}"
    )


def section_light(settings):
    print(f"\n(b) nearly massless half-space rho2 = 1e-3 kg/m^3, {load()}")
    run = run_impact(PAPER, Material(E2, 0.5), 1e-3, MASS, VELOCITY, settings)
    qs = exact(PAPER, 0.5, VELOCITY)
    print(f"  x_max/x_c - 1 = {run.x_max / qs.x_c - 1:+.2e}   (acceptance 3e-3)")
    print(f"  P_max/P_c - 1 = {run.P_max / qs.P_c - 1:+.2e}")
    print(f"  t_contact/t_y - 1 = {run.t_contact / qs.t_y - 1:+.2e}")
    print(f"  e - 1 = {run.restitution - 1:+.2e}   (acceptance 5e-3)")
    print(f"  energy balance error {run.energy_balance_error:.2e}")


def velocity_for(indenter, nu, target=0.04):
    """v0 with first-order lambda = target: lambda ~ v0^k, k = 2 (2p - 1)/(p + 1) - 1."""
    p = (indenter.exponent + 1) / indenter.exponent
    k = 2 * (2 * p - 1) / (p + 1) - 1
    reference = estimate(indenter, nu, 1.0).energy_fraction
    return (target / reference) ** (1 / k)


def section_estimate(settings):
    print(f"\n(c) measured 1 - e^2 against the first-order estimate (lambda ~ 0.04), {load()}")
    print("  n    nu    v0 m/s   lambda    1-e^2     ratio   reflected  balance")
    for indenter in (PAPER, SPHERE):
        for nu in (0.3, 0.4, 0.5):
            v0 = velocity_for(indenter, nu)
            lam = estimate(indenter, nu, v0).energy_fraction
            run = run_impact(indenter, Material(E2, nu), DENSITY, MASS, v0, settings)
            measured = run.energy_radiated_fraction
            print(
                f"  {indenter.exponent:<4} {nu:<5} {v0:<8.3f} {lam:.5f}  {measured:.5f}  "
                f"{measured / lam:.4f}  {run.reflected_energy_fraction:.2e}  "
                f"{run.energy_balance_error:.1e}"
            )


def section_first_order(settings):
    print(f"\n(g) measured / estimated loss as lambda -> 0 (first-order check), {load()}")
    print("  n    nu    lambda  v0 m/s    1-e^2      ratio    (1 - ratio) / lambda")
    for indenter, nu in ((PAPER, 0.5), (SPHERE, 0.3)):
        for target in (0.08, 0.04, 0.02, 0.01):
            v0 = velocity_for(indenter, nu, target)
            run = run_impact(indenter, Material(E2, nu), DENSITY, MASS, v0, settings)
            ratio = run.energy_radiated_fraction / target
            print(
                f"  {indenter.exponent:<4} {nu:<5} {target:<7} {v0:<8.4f}  "
                f"{run.energy_radiated_fraction:.6f}  {ratio:.5f}  {(1 - ratio) / target:.3f}"
            )


def orders(values):
    differences = np.abs(np.diff(values))
    return [math.log2(a / b) if b > 0 else math.nan for a, b in itertools.pairwise(differences)]


def convergence(title, settings_list, labels):
    print(f"\n{title}, {load()}")
    table = {key: [] for key in KEYS}
    for settings, label in zip(settings_list, labels, strict=True):
        run = run_impact(PAPER, Material(E2, 0.5), DENSITY, MASS, VELOCITY, settings)
        for key in KEYS:
            table[key].append(getattr(run, key))
        print(
            f"  {label:22s} "
            + "  ".join(f"{key} {getattr(run, key):.7g}" for key in KEYS)
            + f"  ({run.mesh['dofs']} dofs, {run.timings['total']:.1f} s)"
        )
    for key in KEYS:
        print(f"  observed orders {key:12s} " + " ".join(f"{o:.2f}" for o in orders(table[key])))


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--quick", action="store_true", help="coarser ladders")
    parser.add_argument("--only", default="abcdefg", help="sections to run, e.g. 'ab' or 'g'")
    options = parser.parse_args()
    base = DynamicSettings(steps=400, size=1 / 80)  # the benchmark reference: 400 steps at 1/80
    coarse = replace(base, size=1 / 40) if options.quick else base
    print(f"machine: {os.cpu_count()} cores, {load()} (shared: timings are on a loaded machine)")
    sections = {
        "a": lambda: section_paper(base),
        "b": lambda: section_light(base),
        "c": lambda: section_estimate(base),
        "d": lambda: convergence(
            "(d) time step (steps per t_y)",
            [replace(coarse, steps=s) for s in STEPS[options.quick]],
            [f"steps {s}" for s in STEPS[options.quick]],
        ),
        "e": lambda: convergence(
            "(e) mesh (smallest size / refined radius)",
            [replace(base, size=h, axis_size=h / 10) for h in SIZES[options.quick]],
            [f"size 1/{round(1 / h)}" for h in SIZES[options.quick]],
        ),
        "f": lambda: convergence(
            "(f) domain radius / refined radius",
            [replace(coarse, domain=d) for d in (1e3, 1e4, 1e5)],
            [f"domain {d:.0e}" for d in (1e3, 1e4, 1e5)],
        ),
        "g": lambda: section_first_order(base),
    }
    for letter in options.only:
        sections[letter]()


STEPS = {True: (100, 200, 400), False: (100, 200, 400, 800)}
SIZES = {True: (1 / 20, 1 / 40, 1 / 80), False: (1 / 20, 1 / 40, 1 / 80, 1 / 160)}


if __name__ == "__main__":
    main()
