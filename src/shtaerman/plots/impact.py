"""Impact histories: the paper's Figs. 3 and 4, every impact variant against the exact one (PNG).

x(t)/x_c and P(t)/P_c (:func:`plot_impact_motion`), a(t)/a_c and p(0, t)/p_c
(:func:`plot_impact_contact`) against t/t_c, with each variant's difference from the exact
solution below (see :mod:`.style` for the conventions).
"""

from __future__ import annotations

from collections.abc import Iterable, Mapping
from pathlib import Path

import numpy as np
from matplotlib.axes import Axes
from matplotlib.lines import Line2D

from ..theory.impact import ImpactHistory, ImpactResult
from .style import EXACT_COLOUR, FEM_COLOUR, SECOND_COLOUR, chart, save, styled

__all__ = ["VARIANT_LABELS", "VARIANT_STYLES", "plot_impact_contact", "plot_impact_motion"]

VARIANT_STYLES = ("-", "--", ":", "-.")
VARIANT_LABELS = {
    "analytic": r"exact (Ateb, analytic $\beta$)",
    "fem_fitted": r"FEM-fitted $\beta x^q$ (Ateb)",
    "fem_tabulated": r"FEM-tabulated $P(x)$ (ODE)",
}
"""Legend text of the impact variants of :class:`shtaerman.study.contact.runner.StudyOutcome`."""

_MOTION = (("x", "x_c", "$x/x_c$"), ("P", "P_c", "$P/P_c$"))
_CONTACT = (("a", "a_c", "$a/a_c$"), ("p0", "p_c", "$p(0,t)/p_c$"))


def _variant_legend(axes: Axes, labels: Iterable[str]) -> None:
    handles = [
        Line2D([], [], color="0.2", linestyle=style, label=VARIANT_LABELS.get(label, label))
        for label, style in zip(labels, VARIANT_STYLES, strict=False)
    ]
    axes.add_artist(axes.legend(handles=handles, loc="upper right"))


def _draw_history(
    axes: tuple[Axes, Axes],
    runs: tuple[ImpactHistory, ImpactHistory, ImpactResult],
    quantity: tuple[str, str, str],
    style: tuple[str, str],
) -> None:
    """One quantity of one history (top) and its difference from the exact one (bottom).

    ``runs`` = (history, exact history at the same instants, exact result for the scales);
    ``quantity`` = (history attribute, result attribute it is normalised by, label).
    """
    history, exact, reference = runs
    name, scale, _ = quantity
    tau, norm = history.t / reference.t_c, getattr(reference, scale)
    value = getattr(history, name) / norm
    axes[0].plot(tau, value, color=style[0], linestyle=style[1])
    difference = 100 * (value - getattr(exact, name) / norm)
    axes[1].plot(tau, difference, color=style[0], linestyle=style[1])


def _impact_figure(
    histories: Mapping[str, ImpactHistory],
    reference: ImpactResult,
    path: Path | str,
    quantities: tuple[tuple[str, str, str], ...],
    figure_format: str = "png",
) -> Path:
    """Two normalised histories per variant, and their difference from the exact solution."""
    if not 0 < len(histories) <= len(VARIANT_STYLES):
        raise ValueError(f"histories must hold 1 to {len(VARIANT_STYLES)} ImpactHistory objects")
    figure, (top, bottom) = chart(5.0, 2, 1, sharex=True, height_ratios=(3, 1.3))
    colours = (FEM_COLOUR, SECOND_COLOUR)
    for history, style in zip(histories.values(), VARIANT_STYLES, strict=False):
        exact = reference.history(times=np.clip(history.t, 0.0, reference.t_y))
        for quantity, colour in zip(quantities, colours, strict=True):
            _draw_history((top, bottom), (history, exact, reference), quantity, (colour, style))
    _variant_legend(top, histories)
    quantity = [
        Line2D([], [], color=c, label=q[2]) for q, c in zip(quantities, colours, strict=True)
    ]
    top.legend(handles=quantity, loc="upper left")
    top.set_ylim(0.0, 1.32)
    top.set_yticks(np.linspace(0.0, 1.0, 6))
    top.set_ylabel("Normalised value")
    bottom.axhline(0.0, color=EXACT_COLOUR, linewidth=0.8)
    bottom.set_ylabel("Difference from\nexact (% of max)")
    bottom.set_xlabel("Time $t/t_c$")
    end = max(h.t[-1] for h in histories.values()) / reference.t_c
    bottom.set_xlim(0.0, end)
    bottom.set_ylim(_difference_limits(bottom, end))
    _mark_off_scale(bottom, {c: q[2] for q, c in zip(quantities, colours, strict=True)})
    return save(figure, path, figure_format)


def _off_scale(axes: Axes) -> list[tuple[str, float, float]]:
    """(colour, t/t_c, value) of the largest point of each curve beyond the y-limits."""
    low, high = axes.get_ylim()
    found = []
    for line in axes.get_lines():
        tau, value = (np.asarray(data, dtype=float) for data in line.get_data())
        outside = np.isfinite(value) & ((value < low) | (value > high))
        if outside.any():
            worst = int(np.argmax(np.where(outside, np.abs(value), -np.inf)))
            found.append((line.get_color(), float(tau[worst]), float(value[worst])))
    return found


def _mark_off_scale(axes: Axes, labels: Mapping[str, str]) -> None:
    """Say what the difference panel clips: a triangle on its edge at each clipped curve's
    extreme, and a note naming the quantity, its extreme difference and when it occurs."""
    low, high = axes.get_ylim()
    worst: dict[str, tuple[float, float]] = {}
    for colour, tau, value in _off_scale(axes):
        axes.plot(
            tau,
            high if value > 0 else low,
            marker="^" if value > 0 else "v",
            color=colour,
            markersize=7,
            clip_on=False,
            zorder=5,
        )
        if abs(value) > abs(worst.get(colour, (0.0, 0.0))[1]):
            worst[colour] = (tau, value)
    if not worst:
        return
    parts = [
        f"{labels.get(colour, colour)} {value:+.2g} % at $t/t_c$ = {tau:.3f}".replace("-", "\u2212")
        for colour, (tau, value) in worst.items()
    ]
    axes.text(
        0.5,
        0.95,
        "off scale (triangles): " + "; ".join(parts),
        transform=axes.transAxes,
        ha="center",
        va="top",
        fontsize=8,
        bbox={"facecolor": "white", "edgecolor": "none", "alpha": 0.85, "pad": 1.5},
    )


def _difference_limits(axes: Axes, end: float, margin: float = 0.03) -> tuple[float, float]:
    """Symmetric y-limits from the curves away from both ends, where a(t) ~ x^(1/n) and
    p(0, t) ~ x^(1 - 1/n) are so steep that a tiny shift of t_y swamps the comparison."""
    largest = 0.0
    for line in axes.get_lines():
        tau, value = (np.asarray(data, dtype=float) for data in line.get_data())
        inside = (tau > margin * end) & (tau < (1 - margin) * end)
        if inside.any():
            largest = max(largest, float(np.nanmax(np.abs(value[inside]))))
    largest = 1.25 * largest if largest > 0 else 1.0
    return -largest, largest


@styled
def plot_impact_motion(
    histories: Mapping[str, ImpactHistory],
    reference: ImpactResult,
    path: Path | str,
    *,
    figure_format: str = "png",
) -> Path:
    """Write the paper's Fig. 3: x(t)/x_c and P(t)/P_c against t/t_c, variants overlaid.

    Parameters
    ----------
    histories : mapping of str to ImpactHistory
        Label (``"analytic"``, ``"fem_fitted"``, ``"fem_tabulated"`` get descriptive legend
        text, others are shown as given) to history (SI units); up to four, drawn solid,
        dashed, dotted, dash-dotted in that order.
    reference : ImpactResult
        The exact impact: normalises by its x_c (m), P_c (N), t_c (s); the lower panel is each
        history minus this exact solution at the same instants (% of the maximum).
    path, figure_format
        The PNG (1280 x 1000 pixels) and the formats, as every chart (:mod:`.style`).
    """
    return _impact_figure(histories, reference, path, _MOTION, figure_format)


@styled
def plot_impact_contact(
    histories: Mapping[str, ImpactHistory],
    reference: ImpactResult,
    path: Path | str,
    *,
    figure_format: str = "png",
) -> Path:
    """Write the paper's Fig. 4: a(t)/a_c and p(0,t)/p_c against t/t_c, variants overlaid.

    Parameters are those of :func:`plot_impact_motion`; normalised by the exact a_c (m) and
    p_c (Pa).

    The lower panel's scale is set by the differences away from both ends (3 % of the
    duration), where a ~ x^(1/n) and p(0) ~ x^(1-1/n) are infinitely steep; a difference
    beyond it is marked by a triangle on the panel's edge and its extreme written in the panel
    (as in either figure).
    """
    return _impact_figure(histories, reference, path, _CONTACT, figure_format)
