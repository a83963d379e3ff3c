"""The figure of a fit: the data against the fitted model, and the residual below."""

from __future__ import annotations

from pathlib import Path
from typing import Any

import numpy as np

from .style import EXACT_COLOUR, FEM_COLOUR, chart, save, styled

__all__ = ["plot_fit"]

LABELS = {
    "depth [m]": ("Depth $x$ (mm)", 1e3),
    "time [s]": ("Time $t$ (ms)", 1e3),
    "velocity [m/s]": ("Drop velocity $v_0$ (m/s)", 1.0),
}
"""Abscissa column -> its axis label and the factor from SI to the shown unit."""
QUANTITIES = {
    "force [N]": "Force $P$ (N)",
    "restitution [1]": "Restitution $e$",
    "contact_time [s]": "Contact time $t_y$ (s)",
    "resilience [1]": "Resilience $e^2$",
}
"""Observed column -> its axis label."""


@styled
def plot_fit(result: Any, path: Path | str, figure_format: str = "png") -> Path:
    """Data (blue dots) against the fitted model (black), one panel per observed quantity,
    and the residual (fit - data) of a force below.

    ``result`` is a :class:`shtaerman.fitting.result.FitResult`; its ``curves`` are fit.csv.
    """
    curves = dict(result.curves)
    axis = next(name for name in LABELS if name in curves)
    label, factor = LABELS[axis]
    x = np.asarray(curves[axis]) * factor
    order = np.argsort(x, kind="stable")
    observed = [name for name in QUANTITIES if name in curves]
    panels = [*observed, *(["residual [N]"] if "residual [N]" in curves else [])]
    ratios = [3.0] * len(observed) + [1.3] * (len(panels) - len(observed))
    figure, axes = chart(5.0, len(panels), 1, sharex=True, height_ratios=ratios)
    axes = np.atleast_1d(axes)
    for ax, name in zip(axes, observed, strict=False):
        fit = curves[name.replace(" [", "_fit [")]
        ax.plot(x, curves[name], "o", color=FEM_COLOUR, markersize=5, label="data")
        style = "-" if result.kind in ("indentation", "force-history") else "x-"
        ax.plot(x[order], fit[order], style, color=EXACT_COLOUR, label="fit")
        ax.set_ylabel(QUANTITIES[name])
        ax.legend(loc="best")
    if "residual [N]" in curves:
        axes[-1].plot(x, curves["residual [N]"], "o", color=FEM_COLOUR, markersize=3)
        axes[-1].axhline(0.0, color=EXACT_COLOUR, linewidth=0.8)
        axes[-1].set_ylabel("Fit - data (N)")
    axes[-1].set_xlabel(label)
    return save(figure, path, figure_format)
