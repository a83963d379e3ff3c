"""The researcher's full case with friction, and its cost against the frictionless run.

Run ``python benchmarks/full_case.py [--exponents 1.2,1.5,2] [--target 0.7]``. Nothing is
asserted.

Measured 2026-11-28 (2 cores, other agents' load 1.4-2.5), n = 1.5, A = 5.31: friction 0.5
x_max 3.296e-3 m (rel. error 3.1e-4), P_max 116.6 N (1.1e-3), t_contact 6.19e-3 s (9.0e-4),
e 0.8199 (2.4e-4), 57 s; frictionless 18 s (ratio 3.1). The researcher's n = 1.3, A = 2 from
the CLI with its error bar: 50.6 s (load 0.6-1.6), frictionless 24.5 s (load 1.6-2.0).
Measured 2026-11-29 in CPU seconds (the API, n = 1.3, A = 2 with its error bar): 42.5 CPU s
(wall 379 s at load 9-13: the "300+ s" seen at load 8 was the wall, not the cost); with the
Coulomb Newton's reused factorizations (fem/contact/finite_stick.py) 28.7 CPU s (wall 245 s at load
9-14; this script, A = 2.011: friction 26.9 CPU s, frictionless 18.6 CPU s, ratio 1.44),
21.4 CPU s with those of the last four contact sets kept. Where it goes (cProfile, 28.7 s):
the finest of the three levels (4960 dofs, 100 time steps) about 2/3; SuperLU factorizations
24 %, back-substitutions 8 %, the viscoelastic kinematics (with the material tangent at every
state) 24 %, the residual 11 %.

For each striker z = A r^n (n in ``--exponents``), 0.12 kg at 1.5 m/s onto a 12 mm neo-Hookean
pad (E2 3 MPa, nu2 0.49, 1000 kg/m^3, Prony 0.3:1e-3) bonded to a rigid base, the indenter
bonded with Coulomb friction 0.5: A is chosen so that the quasi-static x_c / a_c is
``--target`` (the researcher's A = 2 at n = 1.3 gives 0.72; the finite-strain impact is
validated to x / a = 1.2) and x_c stays within half the pad; where no A does, the refusal line
is printed. Each case is built with ``import shtaerman`` only (``sh.Problem.impact``) and run by
``sh.dynamic`` with its error bar (the default), then without friction (the same problem,
frictionless indenter, also with its error bar) right after. Printed: x_max, P_max,
t_contact, e with their estimated relative errors, the CPU seconds of each (user + sys), its
wall time with the load average beside it, and the ratio of the CPU times.
"""

from __future__ import annotations

import argparse
import math
import os
import resource
import time

import shtaerman as sh

MASS, VELOCITY, THICKNESS = 0.12, 1.5, 0.012
BODY = sh.Material(youngs_modulus=3e6, poisson_ratio=0.49, density=1000.0)
PARTS = {"model": "neo-hookean", "thickness": THICKNESS, "prony": "0.3:1e-3"}
KEYS = ("x_max", "P_max", "t_contact", "restitution")


def shape_coefficient(exponent: float, target: float) -> float:
    """A (m^(1-n)) whose quasi-static x_c / a_c is ``target`` (bisection in log A)."""

    def ratio(log_a: float) -> float:
        indenter = sh.PowerLawIndenter(shape_coefficient=math.exp(log_a), exponent=exponent)
        result = sh.impact(indenter, BODY, mass=MASS, velocity=VELOCITY)
        return result.solution.x_c / result.solution.a_c

    low, high = math.log(1e-3), math.log(1e4)
    for _ in range(60):  # x_c / a_c grows with A
        middle = 0.5 * (low + high)
        low, high = (middle, high) if ratio(middle) < target else (low, middle)
    return math.exp(0.5 * (low + high))


def cpu() -> float:
    """CPU seconds (user + sys) of this process, all its threads."""
    usage = resource.getrusage(resource.RUSAGE_SELF)
    return usage.ru_utime + usage.ru_stime


def timed(problem: sh.Problem) -> tuple[sh.DynamicResult, float, str]:
    """The result of ``sh.dynamic(problem)``, its CPU seconds, and its wall time (s) with the
    1-min load before and after (the wall moves with the other agents' load, the CPU less)."""
    load, begun, spent = os.getloadavg()[0], time.perf_counter(), cpu()
    result = sh.dynamic(problem)
    wall = f"wall {time.perf_counter() - begun:.0f} s at load {load:.1f}-{os.getloadavg()[0]:.1f}"
    return result, cpu() - spent, wall


def line(name: str, result: sh.DynamicResult, seconds: float, wall: str) -> str:
    """One row: the four headline results with their estimates, CPU s, wall and load."""
    errors = result.error_estimate or {}
    cells = [
        f"{key} {result.dynamic[key]:.5g} (rel. error {errors.get(key, math.nan):.1e})"
        for key in KEYS
    ]
    return f"  {name:12s} " + ", ".join(cells) + f"; {seconds:.1f} CPU s ({wall})"


def run(exponent: float, target: float) -> None:
    """Print the case at ``exponent``: friction, frictionless and their cost ratio."""
    a = shape_coefficient(exponent, target)
    indenter = sh.PowerLawIndenter(shape_coefficient=a, exponent=exponent)
    quasi = sh.impact(indenter, BODY, mass=MASS, velocity=VELOCITY).solution
    print(
        f"n = {exponent:g}, A = {a:.4g}: quasi-static x_c {quasi.x_c:.4g} m, x_c/a_c "
        f"{quasi.x_c / quasi.a_c:.3g}"
    )
    if quasi.x_c > 0.5 * THICKNESS:
        print(f"  refused: x_c {quasi.x_c:.3g} m beyond half the pad ({THICKNESS / 2:g} m)")
        return
    rows = {}
    for name, interface in (
        ("friction 0.5", {"interface": "bonded", "friction": 0.5}),
        ("frictionless", {}),
    ):
        problem = sh.Problem.impact(
            indenter, BODY, mass=MASS, velocity=VELOCITY, **PARTS, **interface
        )
        try:
            rows[name] = timed(problem)
        except (sh.InputError, RuntimeError) as error:  # a refusal or a numerical failure
            print(f"  {name:12s} refused: {error}")
            continue
        print(line(name, *rows[name]))
    if len(rows) == 2:
        ratio = rows["friction 0.5"][1] / rows["frictionless"][1]
        print(f"  friction / frictionless CPU time: {ratio:.2f}")


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--exponents", default="1.2,1.5,2")
    parser.add_argument("--target", type=float, default=0.7)
    options = parser.parse_args()
    for exponent in map(float, options.exponents.split(",")):
        run(exponent, options.target)


if __name__ == "__main__":
    main()
