"""Speed of the exact impact history: 10^6 time points, against one incomplete-beta inversion.

Run: python benchmarks/bench_impact.py. Prints seconds and ratios; asserts nothing about time.
"""

import os
import time

import numpy as np
from scipy.special import betaincinv

from shtaerman.theory.contact import PowerLawContact
from shtaerman.theory.impact import solve_impact
from shtaerman.theory.impact_ode import integrate_impact
from shtaerman.theory.indenter import PowerLawIndenter
from shtaerman.theory.materials import Material, effective_modulus


def best_of(function, repeats=3):
    times = []
    for _ in range(repeats):
        start = time.perf_counter()
        function()
        times.append(time.perf_counter() - start)
    return min(times)


def main() -> None:
    modulus = effective_modulus(Material(2e11, 0.25), Material(7.5e6, 0.5))
    law = PowerLawContact(PowerLawIndenter(5.0, 1.5), modulus)
    result = solve_impact(0.7, 3.0, law)
    points = 10**6
    history = best_of(lambda: result.history(points))
    inversion = best_of(lambda: betaincinv(3 / 8, 0.5, np.linspace(0, 1, points)))
    maxima = best_of(lambda: solve_impact(0.7, 3.0, law), repeats=20)
    ode = best_of(lambda: integrate_impact(0.7, 3.0, law.force, result.x_c))
    print(f"machine: {os.cpu_count()} cores")
    print(f"history, 10^6 points (t, x, v, P, a, p0): {history:.3f} s")
    print(f"one betaincinv over 10^6 points:           {inversion:.3f} s")
    print(f"ratio history / betaincinv:                 {history / inversion:.2f}")
    print(f"maxima (solve_impact):                      {1e6 * maxima:.0f} us")
    print(f"ODE cross-check (DOP853, rtol 1e-12):       {1e3 * ode:.1f} ms")


if __name__ == "__main__":
    main()
