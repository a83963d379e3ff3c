"""Figures of a dynamic study (PNG): histories, quantities over v0 and the wave field.

- :func:`plot_dynamic_histories`: x(t) and P(t) of the dynamic FE impact against the
  quasi-static (Ateb) impact at one velocity, and the quasi-static minus dynamic difference;
- :func:`plot_dynamic_over_velocity`: restitution e and the energy left in the body 1 - e^2
  (on the half-space the first-order estimate as a line; on a pad the energy that came back
  near the contact after separation and the energy balance error, which the pad run
  measured), and the quasi-static
  over dynamic ratios of x, P and the contact time, over the approach velocity;
- :func:`plot_wave_field`: the von Mises stress on the r-z section at one kept time, over a
  window reaching past the shear wave front (off-screen pyvista, :mod:`.render`).

Colours as everywhere (:mod:`.style`): the quasi-static theory black, the FEM blue, the
estimate orange dashed.
"""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
from matplotlib.axes import Axes

from ..fem.impact_run import ImpactRun
from ..study.dynamic.case import DynamicCase
from ..study.dynamic.runner import DynamicStudyOutcome
from .fields import MAGNITUDE, SIGMA, FieldColours, add_coloured, isolines
from .impact_energy import PAD_NOTE, loss_kinds, on_pad
from .labels import MINUS, axis_label
from .render import picture
from .render import save as save_picture
from .sections import (
    BAR_GAP,
    CONTACT_COLOUR,
    add_label,
    body_frame,
    camera_2d,
    draw_axes,
    frame,
    polyline,
    section,
)
from .style import (
    APPROXIMATION_COLOUR,
    EXACT_COLOUR,
    FEM_COLOUR,
    SECOND_COLOUR,
    chart,
    note,
    points,
    save,
    si_prefix,
    styled,
    unresolved,
)

__all__ = ["plot_dynamic_histories", "plot_dynamic_over_velocity", "plot_wave_field"]

DECADES = 4
"""The wave field is coloured by log10 of the von Mises stress over this many decades below
its largest value in the window: the waves (kPa) are 2-4 decades below the contact's stress
concentration (MPa) and would be invisible on a linear scale."""


def _losses(result: ImpactRun) -> str:
    """What the run loses energy to (:func:`.impact_energy.loss_kinds`), "waves + hysteresis +
    slip" or a part of it, "no loss" for none."""
    kinds = loss_kinds(result)
    return " + ".join(kind for kind, has in kinds.items() if has) or "no loss"


@styled
def plot_dynamic_histories(
    case: DynamicCase, path: Path | str, *, figure_format: str = "png"
) -> Path:
    """x(t) and P(t), dynamic FE against quasi-static, at the case's velocity (PNG, and
    ``figure_format`` "svg" or "pdf" beside it)."""
    result, quasi = case.result, case.quasi
    history = quasi.history(401, times=np.linspace(0.0, quasi.t_y, 401))
    end = max(quasi.t_y, result.t_contact if math.isfinite(result.t_contact) else 0.0)
    shown = result.t <= 1.05 * end
    t_scale, t_unit = si_prefix(quasi.t_y, "s")
    x_scale, x_unit = si_prefix(quasi.x_c, "m")
    figure, axes = chart(5.6, 2, 1, sharex=True)
    rows = (
        (axes[0], history.x * x_scale, result.x * x_scale, f"Approach x ({x_unit})"),
        (axes[1], history.P, result.force, "Contact force P (N)"),
    )
    exact = "Ateb" if math.isfinite(quasi.beta) else "Sneddon"  # a sphere's, a table's: no beta
    quasi_label = f"quasi-static ({exact})" + (PAD_NOTE if on_pad(result) else "")
    for ax, quasi_values, dynamic_values, label in rows:
        ax.plot(history.t * t_scale, quasi_values, color=EXACT_COLOUR, label=quasi_label)
        ax.plot(
            result.t[shown] * t_scale,
            dynamic_values[shown],
            color=FEM_COLOUR,
            linestyle="--",
            label=f"dynamic FEM ({_losses(result)})",
        )
        ax.set_ylabel(label)
        ax.set_ylim(bottom=min(0.0, float(np.min(dynamic_values[shown]))))
    for ax in axes:
        ax.axvline(quasi.t_c * t_scale, color="0.6", linewidth=0.8, linestyle=":")
    axes[0].legend(loc="lower left" if on_pad(result) else "upper right")  # a pad: longer
    axes[1].set_xlabel(f"Time t ({t_unit}); dotted: quasi-static t_c")
    axes[1].set_xlim(0.0, 1.05 * end * t_scale)
    loss = 100 * result.energy_radiated_fraction
    x_diff, p_diff = (f"{100 * d:+.2f}".replace("-", MINUS) for d in (
        quasi.x_c / result.x_max - 1, quasi.P_c / result.P_max - 1))  # fmt: skip
    axes[0].set_title(
        f"v0 = {case.velocity:g} m/s: e = {result.restitution:.4f}, energy left in the "
        f"{'pad' if on_pad(result) else 'half-space'} 1 {MINUS} e² = {loss:.2f} %\n"
        f"x_c/x_max {MINUS} 1 = {x_diff} %, P_c/P_max {MINUS} 1 = {p_diff} %",
        fontsize=9,
    )
    return save(figure, path, figure_format)


def _restitution(ax_e: Axes, ax_loss: Axes, outcome: DynamicStudyOutcome) -> None:
    """e and 1 - e^2 (%) of the dynamic FEM over v0, the first-order estimate dashed (on a
    pad: what the pad run measured instead, :func:`_pad_account`)."""
    v = np.array(outcome.velocities)
    results = [case.result for case in outcome.cases]
    pad = outcome.study.geometry.thickness is not None
    ax_e.plot(v, [r.restitution for r in results], "o", color=FEM_COLOUR, label="dynamic FEM")
    loss = [100 * r.energy_radiated_fraction for r in results]
    ax_loss.plot(v, loss, "o", color=FEM_COLOUR, label="dynamic FEM $1-e^2$")
    if pad:
        _pad_account(ax_loss, v, results)
    else:
        curve = outcome.estimate_curve()
        ax_e.plot(curve["velocity"], curve["restitution"], "--", color=APPROXIMATION_COLOUR,
                  label=r"estimate $\sqrt{1-\lambda}$")  # fmt: skip
        ax_loss.plot(curve["velocity"], 100 * np.asarray(curve["energy_fraction"]), "--",
                     color=APPROXIMATION_COLOUR, label=r"first-order $\lambda$")  # fmt: skip
        ax_loss.set_ylim(bottom=0.0)
    ax_e.axhline(1.0, color=EXACT_COLOUR, linewidth=1.0, label="quasi-static")
    ax_e.set_ylabel(axis_label("restitution"))
    ax_e.legend(loc="lower left")
    loss_label = axis_label("energy_radiated_fraction")
    ax_loss.set_ylabel(loss_label.replace("the body", "the pad") if pad else loss_label)
    if pad:  # three series over decades: two decades of headroom hold the legend
        top = max(loss) if max(loss) > 0 else 1.0
        ax_loss.set_ylim(top=top * 10**2.5)
        ax_loss.legend(loc="upper center", fontsize=7.5)
    else:
        ax_loss.legend(loc="upper left")


def _pad_account(ax: Axes, v: np.ndarray, results: list[ImpactRun]) -> None:
    """What a pad run measured, % of M v0^2/2 on a log scale: the energy that came back near
    the contact after separation and the energy balance error (the half-space's
    first-order radiation estimate does not apply to a pad: not drawn, said in a note)."""
    for key, colour, marker, label in (
        ("reflected_energy_fraction", SECOND_COLOUR, "s", "come back after separation"),
        ("energy_balance_error", "0.45", "^", "energy balance error"),
    ):
        label = f"{label}, % of $E_0$"
        ax.plot(v, [100 * getattr(r, key) for r in results], marker, color=colour, label=label)
    ax.set_yscale("log")
    note(ax, "a pad: no half-space radiation estimate")


@styled
def plot_dynamic_over_velocity(
    outcome: DynamicStudyOutcome, path: Path | str, *, figure_format: str = "png"
) -> Path:
    """e and 1 - e^2 (%) with the first-order estimate (on a pad: with its measured reflection
    and energy balance), and the quasi-static / dynamic differences (%) over v0 (PNG, and
    ``figure_format`` "svg" or "pdf" beside it).

    With error estimates, a difference carries its error bar, and one whose estimated error
    is not below its own size is unresolved: an open marker, not joined to the curve.
    """
    v = np.array(outcome.velocities)
    figure, ((ax_e, ax_loss), (ax_ratio, ax_time)) = chart(6.4, 2, 2, sharex=True)
    _restitution(ax_e, ax_loss, outcome)
    differences = [case.differences() for case in outcome.cases]
    errors = outcome.difference_errors()
    for ax, key, colour, marker, label in (
        (ax_ratio, "P", SECOND_COLOUR, "o", r"$P_c/P_{max} - 1$"),
        (ax_ratio, "x", FEM_COLOUR, "s", r"$x_c/x_{max} - 1$"),
        (ax_time, "t", FEM_COLOUR, "o", r"$t_y/t_{contact} - 1$"),
    ):
        values = 100 * np.array([d[key] for d in differences])
        error = None if errors is None else 100 * np.array(errors[key])
        hidden = unresolved(values, error)
        points(ax, v, values, (colour, marker, "-", label), error=error, hidden=hidden)
    for ax in (ax_ratio, ax_time):
        ax.axhline(0.0, color=EXACT_COLOUR, linewidth=1.0)
        for level in (1.0, 5.0):
            for sign in (1, -1):
                ax.axhline(sign * level, color="0.6", linewidth=0.7, linestyle=":")
        ax.legend(loc="upper left" if ax is ax_ratio else "lower left", fontsize=7.5)
        ax.set_xlabel(axis_label("velocity"))
    if errors is None:
        note(ax_ratio, "no error estimates (quick run)")
    ax_ratio.set_ylabel("Quasi-static / dynamic $-$ 1 (%)")
    ax_time.set_ylabel("Quasi-static / dynamic $-$ 1 (%)\n(dotted: ±1 %, ±5 %)")
    return save(figure, path, figure_format)


def _wave_colours(values: np.ndarray) -> FieldColours:
    """log10 of the von Mises stress in Pa, :data:`DECADES` decades up to the rounded maximum."""
    top = math.ceil(2.0 * math.log10(max(float(np.max(values)), 1e-12))) / 2.0
    title = f"Von Mises\nlog10 {SIGMA}v (Pa)"
    return FieldColours(1.0, title, top - DECADES, top, 0.5, MAGNITUDE)


MASSLESS_EXTENT = 8.0
"""Window width of a massless body's field picture, in quasi-static contact radii."""


def plot_wave_field(
    case: DynamicCase, time_requested: float, path: Path | str, *, reach: float = 1.2
) -> Path:
    """The von Mises stress on the r-z section at a kept time (PNG, 1600 x 1000 pixels).

    Parameters
    ----------
    case : DynamicCase
        A case run with ``snapshots`` holding ``time_requested``.
    time_requested : float
        The requested (key) time in s; the picture is at the nearest step.
    path : path-like
        PNG to write.
    reach : float
        Window width / the distance c_s t a shear wave travels by then (a massless body, c_s
        infinite: ``MASSLESS_EXTENT`` contact radii); a pad thinner than that window is shown
        whole in depth, :data:`.sections.PAD_ASPECT` thicknesses wide (:func:`.body_frame`).
    """
    actual, solution, _ = case.result.field_solution(time_requested)
    c_s = case.estimate.shear_wave_speed
    a_c = case.quasi.a_c
    extent = reach * c_s * max(actual, case.quasi.t_c) / a_c
    window = frame(a_c, extent if math.isfinite(extent) else MASSLESS_EXTENT)
    body_depth = -float(np.min(solution.system.mesh.p[1]))  # a pad's thickness
    window = body_frame(window, body_depth, float(np.max(case.result.contact_radius)))
    cut = section(solution, window, deformed=False)
    colours = _wave_colours(np.asarray(cut.point_data["von_mises"]))
    floor = 10.0**colours.low
    cut.point_data["shown"] = np.log10(np.maximum(cut.point_data["von_mises"], floor))
    step = int(np.argmin(np.abs(case.result.t - actual)))
    radius = float(case.result.contact_radius[step])
    with picture() as plotter:
        right = camera_2d(plotter, window)
        add_coloured(plotter, cut, colours, right + BAR_GAP, lighting=False)
        lines = isolines(cut, colours)
        if lines is not None:
            plotter.add_mesh(lines, color="black", line_width=1.0, opacity=0.35)
        if radius > 0:
            plotter.add_mesh(
                polyline(np.array([0.0, radius * window.scale]), np.zeros(2)),
                color=CONTACT_COLOUR,
                line_width=12,
            )
        draw_axes(plotter, window)
        front = c_s * actual * window.scale
        if not math.isfinite(front):  # a massless body: no wave front
            front = 0.0
        angle = np.linspace(0.0, -0.5 * np.pi, 90)
        arc_r, arc_z = front * np.cos(angle), front * np.sin(angle)
        inside = (arc_r <= window.width) & (arc_z >= -window.depth)
        arc = bool(front > 0 and inside.sum() > 1)  # the front may lie beyond a pad's window
        if arc:
            plotter.add_mesh(polyline(arc_r[inside], arc_z[inside]), color="white", line_width=2)
        state = (
            f"contact radius {radius * 1e3:.2f} mm"
            if radius > 0
            else f"separated at {case.result.t_contact * 1e3:.2f} ms"
        )
        add_label(
            plotter,
            f"t = {actual * 1e3:.2f} ms, {state}{' (white arc: shear front c_s t)' if arc else ''}",
            (0.0, window.top),
            (0, 20),
            (0, 0),
        )
        plotter.renderer.ResetCameraClippingRange()  # the camera sits far in display units
        return save_picture(plotter, path)
