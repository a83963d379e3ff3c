"""The viscoelastic dynamic FE impact at the paper's example: cost and the loss split.

The paper's striker (0.7 kg, 3 m/s, A = 5 m^-1/2, n = 3/2, rigid) on the rubber half-space
(E2 = 7.5 MPa instantaneous, nu2 = 0.5) with one Prony term g = 0.5 at tau = t_c / 2 (t_c the
glassy compression time). Three runs at the same settings separate the losses:

- density 1100 kg/m^3, elastic: waves only;
- density 0, Prony: hysteresis only (against the Lee-Radok/Ting reference of
  shtaerman.theory.viscoelastic, and at twice the steps and half the mesh size);
- density 1100, Prony: both.

``--cost`` also times the stepping (CPU seconds per step, least of three interleaved runs) of
the elastic and the viscoelastic body at the same settings, for density 1100 and 0.

Run: python benchmarks/visco_fe.py [--steps N] [--size H] [--cost]
"""

from __future__ import annotations

import argparse
import time

from shtaerman.fem.dynamic_contact import DynamicSettings, prepare_dynamic_impact
from shtaerman.fem.impact import run_impact as run
from shtaerman.fem.stepper import march
from shtaerman.theory.contact import PowerLawContact
from shtaerman.theory.impact import solve_impact
from shtaerman.theory.indenter import PowerLawIndenter
from shtaerman.theory.materials import RIGID, Material, effective_modulus
from shtaerman.theory.viscoelastic import PronySeries, viscoelastic_impact

INDENTER, RUBBER, MASS, VELOCITY = PowerLawIndenter(5.0, 1.5), Material(7.5e6, 0.5), 0.7, 3.0
LAW = PowerLawContact(INDENTER, effective_modulus(RIGID, RUBBER))
T_C = solve_impact(MASS, VELOCITY, LAW).t_c
PRONY = PronySeries((0.5,), (0.5 * T_C,))


def _row(name: str, result) -> None:
    dyn = result.summary()
    split = ""
    if "energy_dissipated_fraction" in dyn:
        split = (
            f"  dissipated {dyn['energy_dissipated_fraction']:.4f}  waves beyond R_a "
            f"{dyn['energy_wave_fraction']:.4f}  hysteresis {dyn['energy_hysteresis_fraction']:.4f}"
        )
    print(
        f"{name:<28} e {result.restitution:.5f}  1-e^2 {1 - result.restitution**2:.4f}  "
        f"x_max {result.x_max:.5e}  P_max {result.P_max:.5e}  t_contact {result.t_contact:.5e}  "
        f"balance {result.energy_balance_error:.1e}{split}"
    )


def losses(settings: DynamicSettings) -> None:
    """The three runs and the quasi-static references."""
    reference = viscoelastic_impact(MASS, VELOCITY, LAW, PRONY, steps=4000)
    print(
        f"t_c = {T_C:.6e} s, tau = {PRONY.times[0]:.6e} s; Lee-Radok/Ting (density 0): e "
        f"{reference.restitution:.5f}  x_max {reference.x_max:.5e}  P_max {reference.P_max:.5e}"
        f"  t_contact {reference.t_contact:.5e}"
    )
    _row("waves (1100, elastic)", run(INDENTER, RUBBER, 1100.0, MASS, VELOCITY, settings))
    _row("hysteresis (0, Prony)", run(INDENTER, RUBBER, 0.0, MASS, VELOCITY, settings, prony=PRONY))
    finer = settings.refined(2.0)
    _row("  refined x2", run(INDENTER, RUBBER, 0.0, MASS, VELOCITY, finer, prony=PRONY))
    _row("both (1100, Prony)", run(INDENTER, RUBBER, 1100.0, MASS, VELOCITY, settings, prony=PRONY))


def cost(settings: DynamicSettings, density: float) -> None:
    """CPU seconds per step of the stepping, elastic and viscoelastic (least of three)."""
    args = (INDENTER, RUBBER, density, MASS, VELOCITY, settings)
    setups = {
        "elastic": prepare_dynamic_impact(*args),
        "Prony": prepare_dynamic_impact(*args, PRONY),
    }
    best = dict.fromkeys(setups, float("inf"))
    for _ in range(3):
        for name, setup in setups.items():
            start = time.process_time()
            history = march(
                setup.problem,
                duration=setup.duration,
                tail_time=setup.tail_time,
                force_exponent=setup.force_exponent,
            )
            best[name] = min(best[name], (time.process_time() - start) / (history.t.size - 1))
    print(
        f"density {density:g}: {setups['elastic'].mesh['dofs']} dofs, ms per step: elastic "
        f"{1e3 * best['elastic']:.2f}, Prony {1e3 * best['Prony']:.2f}, ratio "
        f"{best['Prony'] / best['elastic']:.2f}"
    )


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--steps", type=int, default=200)
    parser.add_argument("--size", type=float, default=1.0 / 40.0)
    parser.add_argument("--cost", action="store_true")
    args = parser.parse_args()
    settings = DynamicSettings(steps=args.steps, size=args.size)
    losses(settings)
    if args.cost:
        for density in (1100.0, 0.0):
            cost(settings, density)


if __name__ == "__main__":
    main()
