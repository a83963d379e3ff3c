"""Restitution of the quasi-static viscoelastic impact against the Deborah number t_c / tau.

The paper's striker (0.7 kg, 3 m/s, A = 5 m^-1/2, n = 3/2, rigid) on an incompressible rubber
half-space with E2 = 7.5 MPa instantaneous and a one-term Prony series g (default 0.5): Lee-Radok
while the contact grows, Ting while it shrinks (shtaerman.theory.viscoelastic). t_c is the glassy
compression time (the elastic impact at E2). Each row is computed at N and N/2 steps per t_c;
the column 'error' is |e(N) - e(N/2)| / 3, the second-order estimate of the error of e(N);
'lost' is the fraction of the impact energy left in the rubber, 1 - e^2.

Run: python benchmarks/visco_restitution.py [--weight G] [--steps N] [--figure PATH.png]
"""

from __future__ import annotations

import argparse

import numpy as np

from shtaerman.theory.contact import PowerLawContact
from shtaerman.theory.indenter import PowerLawIndenter
from shtaerman.theory.materials import RIGID, Material, effective_modulus
from shtaerman.theory.viscoelastic import PronySeries, limit_impacts, viscoelastic_impact

DEBORAH = np.logspace(-3, 3, 25)


def table(weight: float, steps: int) -> list[dict[str, float]]:
    """One row per Deborah number: e, x_max, P_max, t_contact and the step-halving error of e."""
    modulus = effective_modulus(RIGID, Material(7.5e6, 0.5))
    law = PowerLawContact(PowerLawIndenter(5.0, 1.5), modulus)
    glassy, relaxed = limit_impacts(0.7, 3.0, law, PronySeries((weight,), (1.0,)))
    rows = []
    for deborah in DEBORAH:
        prony = PronySeries((weight,), (glassy.t_c / deborah,))
        coarse = viscoelastic_impact(0.7, 3.0, law, prony, steps=steps // 2)
        fine = viscoelastic_impact(0.7, 3.0, law, prony, steps=steps)
        rows.append(
            {
                "deborah": float(deborah),
                "restitution": fine.restitution,
                "error": abs(fine.restitution - coarse.restitution) / 3.0,
                "x_max/x_c": fine.x_max / glassy.x_c,
                "P_max/P_c": fine.P_max / glassy.P_c,
                "t_contact/t_y": fine.t_contact / glassy.t_y,
                "lost": fine.energy_lost / (0.5 * 0.7 * 3.0**2),
            }
        )
    print(f"glassy: x_c = {glassy.x_c:.6g} m, P_c = {glassy.P_c:.6g} N, t_c = {glassy.t_c:.6g} s")
    print(f"relaxed (E2 g_inf): x_c = {relaxed.x_c:.6g} m, P_c = {relaxed.P_c:.6g} N, "
          f"t_y = {relaxed.t_y:.6g} s")  # fmt: skip
    return rows


def main(argv: list[str] | None = None) -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--weight", type=float, default=0.5, help="g of the one-term series")
    parser.add_argument("--steps", type=int, default=800, help="steps per glassy t_c")
    parser.add_argument("--figure", help="write e(De) to this image file (matplotlib)")
    args = parser.parse_args(argv)
    rows = table(args.weight, args.steps)
    keys = list(rows[0])
    print("  ".join(f"{k:>13}" for k in keys))
    for row in rows:
        print("  ".join(f"{row[k]:13.6g}" for k in keys))
    if args.figure:
        import matplotlib

        matplotlib.use("Agg")
        import matplotlib.pyplot as plt

        fig, ax = plt.subplots(figsize=(5, 3.5))
        ax.semilogx([r["deborah"] for r in rows], [r["restitution"] for r in rows], "o-")
        ax.set_xlabel("Deborah number $t_c/\\tau$")
        ax.set_ylabel("restitution $e$")
        ax.set_title(f"one-term Prony series, g = {args.weight:g}")
        fig.tight_layout()
        fig.savefig(args.figure, dpi=150)
        print(f"figure: {args.figure}")


if __name__ == "__main__":
    main()
