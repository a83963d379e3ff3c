"""Where hysteresis outweighs the waves: a steel ball on the silicone Zhermack Elite Double 32.

The shipped series (``zhermack-elite-double-32``: E0 = 2.912 MPa, E_inf = 1.196 MPa, nu = 0.45,
1134 kg/m^3; as used in G. Albertini's public dynamic-friction input, attributed there to Haque
et al. 2018, the primary source not verified here). A rigid steel ball (7850 kg/m^3, mass
4/3 pi rho R^3) of radius R, its tip the paraboloid z = r^2/(2R) (n = 2), hits the half-space at
v0. Two losses of the impact energy, each alone:

- hysteresis: 1 - e^2 of the exact quasi-static viscoelastic impact (Lee-Radok loading, Ting
  unloading, :func:`shtaerman.theory.viscoelastic.viscoelastic_impact`), with E*(t) = E*0 psi(t)
  at the constant nu of the source (exact for that model); each value at N and N/2 steps per t_c,
  the column 'err' the step-halving estimate |l(N) - l(N/2)| / 3;
- waves: the first-order radiated fraction of the elastic impact at the instantaneous E0
  (:func:`shtaerman.theory.radiation.radiation_estimate`; the FE's 'waves' variant of
  fem/extended/silicone.toml), which grows as v0^(3/5) and is independent of R at fixed v0.

The ratio waves/hysteresis > 1 where the waves outweigh the hysteresis. x/R is the glassy
impact's maximum depth over R: the paraboloid (and the linear theory) is a sphere's to a few
per cent up to about 0.3; beyond, a row is marked '*'.

Run: python benchmarks/silicone_map.py [--steps N]
"""

from __future__ import annotations

import argparse
import itertools
import math

import numpy as np

from shtaerman.theory.contact import PowerLawContact
from shtaerman.theory.impact import solve_impact
from shtaerman.theory.indenter import PowerLawIndenter
from shtaerman.theory.materials import RIGID, Material, effective_modulus
from shtaerman.theory.prony_sources import shipped_rubber
from shtaerman.theory.radiation import radiation_estimate
from shtaerman.theory.viscoelastic import viscoelastic_impact

STEEL = 7850.0  # kg/m^3
RADII = (1e-3, 3e-3, 1e-2, 3e-2)  # m
VELOCITIES = tuple(np.round(np.logspace(-2, 1, 10)[:-1], 4))  # m/s, the theory's range (<= 5)
DEPTH_RANGE = 0.3  # x/R up to which the paraboloid stands for the sphere


def row(radius: float, velocity: float, steps: int) -> dict[str, float]:
    """The two losses of one impact, their ratio and the depth over R."""
    rubber = shipped_rubber("zhermack-elite-double-32")
    body = Material(rubber.youngs_modulus, rubber.poisson_ratio)
    law = PowerLawContact(PowerLawIndenter(0.5 / radius, 2.0), effective_modulus(RIGID, body))
    mass = STEEL * 4.0 / 3.0 * math.pi * radius**3
    fine = viscoelastic_impact(mass, velocity, law, rubber.series, steps=steps)
    coarse = viscoelastic_impact(mass, velocity, law, rubber.series, steps=steps // 2)
    hysteresis = 1.0 - fine.restitution**2
    shear = rubber.youngs_modulus / (2.0 * (1.0 + rubber.poisson_ratio))
    waves = radiation_estimate(
        mass, velocity, law.beta, law.force_exponent, rubber.density, shear, body.poisson_ratio
    ).energy_fraction
    return {
        "R": radius,
        "v0": velocity,
        "t_c": solve_impact(mass, velocity, law).t_c,
        "hysteresis": hysteresis,
        "err": abs(fine.restitution**2 - coarse.restitution**2) / 3.0,
        "waves": waves,
        "ratio": waves / hysteresis,
        "depth": solve_impact(mass, velocity, law).x_c / radius,
    }


def crossing(rows: list[dict[str, float]]) -> float | None:
    """v0 where waves = hysteresis (log-linear interpolation of the ratio), None outside."""
    for a, b in itertools.pairwise(rows):
        if (a["ratio"] - 1.0) * (b["ratio"] - 1.0) <= 0.0:
            la, lb = math.log(a["ratio"]), math.log(b["ratio"])
            share = la / (la - lb)
            return math.exp((1 - share) * math.log(a["v0"]) + share * math.log(b["v0"]))
    return None


def main() -> None:
    """Print the map, one block per ball radius, and the crossing velocities."""
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--steps", type=int, default=400, help="steps per t_c (default 400)")
    steps = parser.parse_args().steps
    print(
        f"{'R mm':>5} {'v0 m/s':>7} {'t_c ms':>7} {'hyst':>8} {'err':>7} {'waves':>8} "
        f"{'w/h':>6} {'x/R':>6}"
    )
    for radius in RADII:
        rows = [row(radius, v, steps) for v in VELOCITIES]
        for r in rows:
            flag = "*" if r["depth"] > DEPTH_RANGE else ""
            print(
                f"{1e3 * r['R']:5.0f} {r['v0']:7.3g} {1e3 * r['t_c']:7.3g} "
                f"{r['hysteresis']:8.4f} {r['err']:7.1e} {r['waves']:8.4f} "
                f"{r['ratio']:6.2f} {r['depth']:6.3f}{flag}"
            )
        v = crossing(rows)
        where = "none in range" if v is None else f"{v:.3g} m/s"
        print(f"      R = {1e3 * radius:g} mm: waves = hysteresis at v0 = {where}\n")


if __name__ == "__main__":
    main()
