"""Figures of one dynamic impact's losses: the force-depth loop and the energy account.

- :func:`force_depth_loop`, :func:`plot_force_depth_loop`: the contact force P against the
  approach x, loading (to x_max) and unloading branches, beside the elastic quasi-static law
  P = beta x^q; the loop's area is the energy the striker left in the body, E0 (1 - e^2);
- :func:`energy_shares`, :func:`plot_energy_history`: the energy account over time as
  fractions of E0 = M v0^2 / 2: the striker's kinetic energy, the body's stored (kinetic +
  strain) energy, the energy absorbed by the layer (waves; left out of a massless body), the
  energy dissipated by a viscoelastic body (hysteresis) and by Coulomb friction at the
  striker's surface (slip), each left out of a body without it, and the numerical residue;
- :func:`loss_kinds`: what the body loses energy to (waves, hysteresis, slip).

Colours as everywhere (:mod:`.style`): the quasi-static theory black, the FEM blue.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

from ..fem.impact_run import ImpactRun
from ..study.dynamic.case import DynamicCase
from .labels import MINUS
from .style import (
    APPROXIMATION_COLOUR,
    EXACT_COLOUR,
    FEM_COLOUR,
    SECOND_COLOUR,
    chart,
    save,
    si_prefix,
    styled,
)

__all__ = [
    "PAD_NOTE",
    "energy_shares",
    "force_depth_loop",
    "loop_work",
    "loss_kinds",
    "on_pad",
    "plot_energy_history",
    "plot_force_depth_loop",
]

ENERGY_STYLES = {
    "striker kinetic": (FEM_COLOUR, "-"),
    "half-space stored (kinetic + strain)": (SECOND_COLOUR, "-"),
    "absorbed by the layer (waves)": ("#2ca02c", "-"),
    "dissipated (hysteresis)": (APPROXIMATION_COLOUR, "-"),
    "dissipated (slip)": ("#9467bd", "-"),
    "dissipated (hysteresis + slip)": ("#8c564b", "-"),
    "numerical residue": ("0.45", ":"),
}
"""Legend label -> (colour, line style) of :func:`plot_energy_history`, in drawing order (on a
half-space; a pad's labels are :data:`PAD_LABELS`, drawn in the same styles)."""
PAD_LABELS = {
    "half-space stored (kinetic + strain)": "pad stored (kinetic + strain)",
    "absorbed by the layer (waves)": "absorbed at the pad's lateral edge (waves)",
}
"""The half-space's labels that name the body, as a pad's energy account names them: the
pad stores the energy, and its lateral absorber (not an absorbing layer around a half-space)
takes the waves that run along it."""


QUASI_STATIC_LAW = r"quasi-static elastic $\beta x^q$"
"""The legend of the quasi-static law: Shtaerman's, of the half-space."""
PAD_NOTE = " (the half-space's, not this pad's)"
"""Added to a half-space curve's legend drawn beside a pad run."""


def on_pad(result: ImpactRun) -> bool:
    """Whether the run was on a pad (a layer on a rigid base), not the half-space."""
    return "thickness" in result.mesh


def force_depth_loop(result: ImpactRun) -> dict[str, np.ndarray]:
    """The loop's branches, m and N: ``x_load``, ``P_load`` from first touch to the largest
    approach, ``x_unload``, ``P_unload`` from there to separation (to the run's end if the
    striker never separates)."""
    peak = int(np.argmax(result.x))
    end = result.t.size
    if np.isfinite(result.t_contact):
        end = int(np.searchsorted(result.t, result.t_contact, side="right"))
    end = max(end, peak + 1)
    return {
        "x_load": result.x[: peak + 1],
        "P_load": result.force[: peak + 1],
        "x_unload": result.x[peak:end],
        "P_unload": result.force[peak:end],
    }


def loop_work(result: ImpactRun) -> float:
    """The net work of the contact force on the body over the run, J: the trapezoidal
    integral of P dx, the loop's area; E0 - M v_out^2 / 2 = E0 (1 - e^2) once separated."""
    return float(np.trapezoid(result.force, result.x))


def loss_kinds(result: ImpactRun) -> dict[str, bool]:
    """What the body of ``result`` loses energy to: ``waves`` (a body with mass),
    ``hysteresis`` (a Prony series) and ``slip`` (Coulomb friction at the striker's surface;
    a bonded striker does not slip).

    The linear body records its relaxing shear (``material``), the finite-strain run whether
    its body ``relaxes``.
    """
    slip = bool(result.parameters.get("friction"))
    hysteresis = result.material is not None or result.relaxes
    return {"waves": result.parameters["density2"] > 0, "hysteresis": hysteresis, "slip": slip}


def energy_shares(result: ImpactRun) -> dict[str, np.ndarray]:
    """The energy account per step as fractions of E0 (dimensionless), keyed by the labels of
    :data:`ENERGY_STYLES` (on a pad, :data:`PAD_LABELS`); they sum to 1 (the residue closes
    it). The waves' share is left out of a massless body, a dissipated share where it is 0
    throughout or not recorded; the finite-strain run's one dissipated energy is named by
    :func:`loss_kinds`."""
    energies, kinds = result.energies, loss_kinds(result)
    energy0 = 0.5 * result.parameters["mass"] * result.parameters["velocity"] ** 2
    shares = {
        "striker kinetic": energies["striker_kinetic"],
        "half-space stored (kinetic + strain)": energies["body_kinetic"] + energies["strain"],
    }
    if kinds["waves"]:
        shares["absorbed by the layer (waves)"] = energies["absorbed"]
    if "slip" in energies:  # the linear body
        dissipated = {"hysteresis": energies["dissipated"], "slip": energies["slip"]}
    else:
        named = " + ".join(kind for kind in ("hysteresis", "slip") if kinds[kind])
        dissipated = {named or "hysteresis": energies.get("dissipated", 0.0)}
    for kind, values in dissipated.items():
        if np.any(values):  # else no such share (or record)
            shares[f"dissipated ({kind})"] = values
    shares["numerical residue"] = energies["numerical"]
    names = PAD_LABELS if on_pad(result) else {}
    return {names.get(k, k): np.asarray(values) / energy0 for k, values in shares.items()}


@styled
def plot_force_depth_loop(
    case: DynamicCase, path: Path | str, *, figure_format: str = "png"
) -> Path:
    """P against x of the dynamic FE impact, loading solid and unloading dashed, beside the
    elastic quasi-static P = beta x^q (PNG, and ``figure_format`` "svg" or "pdf" beside it);
    the title states the loop's area against E0 (1 - e^2)."""
    result, quasi = case.result, case.quasi
    loop = force_depth_loop(result)
    x_scale, x_unit = si_prefix(max(quasi.x_c, result.x_max), "m")
    reach = max(quasi.x_c, result.x_max)
    x = np.linspace(0.0, reach, 301)
    figure, ax = chart(4.4)
    ax.plot(x * x_scale, quasi.beta * x**quasi.force_exponent, color=EXACT_COLOUR,
            label=QUASI_STATIC_LAW + (PAD_NOTE if on_pad(result) else ""))  # fmt: skip
    ax.plot(loop["x_load"] * x_scale, loop["P_load"], color=FEM_COLOUR, label="FEM loading")
    ax.plot(loop["x_unload"] * x_scale, loop["P_unload"], color=SECOND_COLOUR, linestyle="--",
            label="FEM unloading")  # fmt: skip
    ax.fill(
        np.concatenate([loop["x_load"], loop["x_unload"]]) * x_scale,
        np.concatenate([loop["P_load"], loop["P_unload"]]),
        color=FEM_COLOUR,
        alpha=0.12,
        linewidth=0,
    )
    ax.set_xlabel(f"Approach x ({x_unit})")
    ax.set_ylabel("Contact force P (N)")
    ax.set_xlim(left=0.0)
    ax.set_ylim(bottom=0.0)
    ax.legend(loc="upper left")
    energy0 = 0.5 * quasi.mass * quasi.velocity**2
    ax.set_title(
        f"v0 = {case.velocity:g} m/s: loop area / E0 = {_shown(loop_work(result) / energy0)}, "
        f"1 {MINUS} e² = {_shown(result.energy_radiated_fraction)}",
        fontsize=9,
    )
    return save(figure, path, figure_format)


@styled
def plot_energy_history(case: DynamicCase, path: Path | str, *, figure_format: str = "png") -> Path:
    """The energy account of the dynamic FE impact over time, fractions of E0 (PNG, and
    ``figure_format`` "svg" or "pdf" beside it); the dotted line marks separation."""
    result = case.result
    t_scale, t_unit = si_prefix(float(result.t[-1]), "s")
    figure, ax = chart(4.4)
    styles = ENERGY_STYLES | {pad: ENERGY_STYLES[label] for label, pad in PAD_LABELS.items()}
    for label, values in energy_shares(result).items():
        colour, style = styles[label]
        ax.plot(result.t * t_scale, values, color=colour, linestyle=style, label=label)
    if np.isfinite(result.t_contact):
        ax.axvline(result.t_contact * t_scale, color="0.6", linewidth=0.8, linestyle=":")
    ax.axhline(0.0, color=EXACT_COLOUR, linewidth=0.8)
    ax.set_xlabel(f"Time t ({t_unit}); dotted: separation")
    ax.set_ylabel(r"Energy / $E_0 = M v_0^2/2$")
    ax.set_xlim(0.0, float(result.t[-1]) * t_scale)
    ax.legend(loc="upper right")
    reflected = ""
    if on_pad(result):  # what came back into R_a after separation: the edge's reflections
        reflected = (
            f"\ncome back near the contact after separation "
            f"{result.reflected_energy_fraction:.1e} E0"
        )
    ax.set_title(
        f"v0 = {case.velocity:g} m/s: e = {result.restitution:.4f}, energy balance error "
        f"{result.energy_balance_error:.1e}{reflected}",
        fontsize=9,
    )
    return save(figure, path, figure_format)


def _shown(fraction: float) -> str:
    """``fraction`` to 4 decimals, a lossless run's -1e-6 shown as 0.0000, not -0.0000."""
    return f"{round(fraction, 4) + 0.0:.4f}"
