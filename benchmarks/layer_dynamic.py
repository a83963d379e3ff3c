"""The dynamic impact of the paper's example on a pad of thickness H on a rigid base.

Run ``python benchmarks/layer_dynamic.py`` (about 5 minutes on 2 idle cores; ``--quick``:
nu = 0.5 only, no refined runs). Prints a markdown table; nothing is asserted. The paper's
striker (0.7 kg at 3 m/s, z = 5 r^1.5, rigid) on rubber (E2 = 7.5 MPa, rho2 = 1100 kg/m^3),
pads of 10, 20 and 50 mm, bonded and lubricated, at the default dynamic settings with the
error-estimate ladder (K/2, K/sqrt 2, K; ``--refine`` and the estimated error of each
quantity), against

- the half-space's dynamic impact (the same settings and ladder),
- the paper's quasi-static impact on the half-space (Shtaerman's law),
- the quasi-static impact on the layer's own static law (the linear static FE on the same
  layer at its default mesh, :func:`shtaerman.api.layer_impact.quasi_static_layer_impact`).

``--refined`` also runs the 20 mm pads at refine 2 (4x the dofs, 2x the steps), the check of
the ladder's estimate.
"""

from __future__ import annotations

import argparse
import os

import numpy as np

import shtaerman as sh
from shtaerman.api.layer_impact import quasi_static_layer_impact
from shtaerman.theory.indenter import PowerLawIndenter
from shtaerman.theory.materials import Material

PAPER = PowerLawIndenter(5.0, 1.5)
PADS = (0.01, 0.02, 0.05)
BASES = ("bonded", "lubricated")
KEYS = ("restitution", "P_max", "x_max", "t_contact")


def dynamic_row(nu: float, thickness: float | None, base: str | None, refine: float = 1.0):
    """The dynamic result's values, their estimated errors and its costs."""
    body = Material(7.5e6, nu, density=1100.0)
    result = sh.dynamic(
        PAPER, body, mass=0.7, velocity=3.0, thickness=thickness, base=base, refine=refine
    )
    details = result.estimate_details or {}
    errors = {key: (details.get(key) or {}).get("absolute_error") for key in KEYS}
    return result, errors


def quasi_static_row(nu: float, thickness: float, base: str) -> dict[str, float]:
    """The quasi-static impact on the layer's static FE law."""
    depths = np.geomspace(2e-4, 9.5e-3, 16)
    body = Material(7.5e6, nu)
    impact, _ = quasi_static_layer_impact(
        PAPER, body, thickness, base, 0.7, 3.0, depths, estimate=False
    )
    return {"P_max": impact.P_c, "x_max": impact.x_c, "t_contact": impact.t_y}


def _cell(value: float, error: float | None, scale: float, digits: int) -> str:
    spread = "" if error is None else f" ± {scale * error:.1e}"
    return f"{scale * value:.{digits}f}{spread}"


def _line(label: str, result, errors, quasi) -> str:
    dyn = result.dynamic
    cells = [
        _cell(dyn["restitution"], errors["restitution"], 1.0, 4),
        _cell(dyn["P_max"], errors["P_max"], 1.0, 0),
        _cell(dyn["x_max"], errors["x_max"], 1e3, 3),
        _cell(dyn["t_contact"], errors["t_contact"], 1e3, 3),
        f"{dyn['energy_balance_error']:.1e}",
        f"{dyn['reflected_energy_fraction']:.1e}",
    ]
    if quasi is None:
        cells += ["", "", ""]
    else:
        cells += [f"{quasi['P_max']:.0f}", f"{1e3 * quasi['x_max']:.3f}"]
        cells += [f"{1e3 * quasi['t_contact']:.3f}"]
    timings, mesh = result.timings, result.mesh
    cells += [f"{mesh['dofs']}", f"{timings['total']:.1f}"]
    return f"| {label} | " + " | ".join(cells) + " |"


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--quick", action="store_true")
    parser.add_argument("--refined", action="store_true")
    args = parser.parse_args()
    print(f"load: {os.getloadavg()[0]:.2f}")
    print(
        "| case | e | P_max (N) | x_max (mm) | t_contact (ms) | balance | reflected | "
        "qs-layer P (N) | qs-layer x (mm) | qs-layer t (ms) | dofs | run s |"
    )
    print("|" + "---|" * 12)
    for nu in (0.5,) if args.quick else (0.5, 0.45):
        result, errors = dynamic_row(nu, None, None)
        quasi = result.quasi_static
        print(
            f"| nu {nu} paper quasi-static | 1 | {quasi['P_c']:.0f} | {1e3 * quasi['x_c']:.3f} "
            f"| {1e3 * quasi['t_y']:.3f} | | | | | | | |"
        )
        print(_line(f"nu {nu} half-space", result, errors, None))
        for thickness in PADS:
            for base in BASES:
                result, errors = dynamic_row(nu, thickness, base)
                quasi = quasi_static_row(nu, thickness, base)
                label = f"nu {nu} H {1e3 * thickness:g} mm {base}"
                print(_line(label, result, errors, quasi), flush=True)
                if args.refined and thickness == 0.02:
                    fine, errors = dynamic_row(nu, thickness, base, refine=2.0)
                    print(_line(label + " refine 2", fine, errors, quasi), flush=True)


if __name__ == "__main__":
    main()
