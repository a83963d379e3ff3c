"""The layer map: how much stiffer than Shtaerman's half-space a layer on a rigid base is,
P / P_Shtaerman - 1 against H / a (log-log), with the 1 % and 5 % bands."""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from ..study.contact.layer import LEVELS
from .style import chart, plain_log, save, styled

__all__ = [
    "LAYER_MAP_CAPTION",
    "MapSeries",
    "RestitutionSeries",
    "plot_layer_map",
    "plot_layer_restitution",
]

LAYER_MAP_CAPTION = (
    "The layer map: P / P_Shtaerman - 1 (log) against the layer thickness H over the "
    "half-space contact radius a (log), for a layer on a rigid base at the same depth; grey "
    "bands: within 1 % and 5 % of the half-space law. Error bars (where wider than the "
    "marker): the estimated error of each FE point."
)
_STYLES = {"bonded": "-", "lubricated": "--"}
_MARKERS = ("o", "s", "^", "D", "v")


@dataclass(frozen=True)
class MapSeries:
    """One line of the map: thicknesses H / a, ratios P / P_Shtaerman and their relative
    errors (``None``: no estimate), and the base (its line style)."""

    thickness_ratio: Sequence[float]
    force_ratio: Sequence[float]
    error: Sequence[float] | None = None
    base: str = "bonded"
    points: bool = True
    """Markers at the values (False: a plain line, e.g. a curve over the depths)."""
    reference: bool = False
    """A thin grey-toned background line (measured elsewhere), not a result of this run."""


@styled
def plot_layer_map(
    series: Mapping[str, MapSeries], path: Path | str, *, figure_format: str = "png"
) -> Path:
    """Write the layer map: one line per labelled series, P / P_Sh - 1 against H / a.

    Parameters
    ----------
    series : mapping of str to MapSeries
        Legend label -> the series (ratios >= 1; a ratio at or below 1 is not drawn).
    path, figure_format
        The PNG and the formats, as every chart (:mod:`.style`).
    """
    figure, axes = chart(4.6)
    for level, shade in sorted(zip(LEVELS, ("#cfcfcf", "#ececec"), strict=True), reverse=True):
        axes.axhspan(1e-6, level, color=shade, zorder=0, lw=0)
        axes.axhline(level, color="#808080", lw=0.8, zorder=1)
        axes.text(
            1.0,
            level,
            f" {100 * level:g} %",
            transform=axes.get_yaxis_transform(),
            va="center",
            ha="left",
            fontsize=8,
            color="#505050",
        )
    for index, (label, line) in enumerate(series.items()):
        h = np.asarray(line.thickness_ratio, dtype=float)
        excess = np.asarray(line.force_ratio, dtype=float) - 1.0
        shown = excess > 0
        marker = _MARKERS[index % len(_MARKERS)] if line.points else ""
        style = {"lw": 0.9, "alpha": 0.45} if line.reference else {"lw": 2.0}
        drawn = axes.loglog(
            h[shown],
            excess[shown],
            ls=_STYLES.get(line.base, "-"),
            marker=marker,
            label=label,
            **style,
        )
        if line.error is not None and line.points:
            error = np.asarray(line.error, dtype=float) * (1.0 + excess)
            axes.errorbar(
                h[shown],
                excess[shown],
                yerr=error[shown],
                fmt="none",
                ecolor=drawn[0].get_color(),
                capsize=2,
            )
    low = min(float(np.min(line.thickness_ratio)) for line in series.values())
    high = max(float(np.max(line.thickness_ratio)) for line in series.values())
    axes.set_xlim(low / 1.3, high * 1.3)
    axes.set_ylim(bottom=max(axes.get_ylim()[0], 1e-4))
    plain_log(axes.xaxis)
    axes.set_xlabel("Layer thickness / half-space contact radius, H / a")
    axes.set_ylabel(r"$P\,/\,P_{\mathrm{Shtaerman}} - 1$ at the same depth")
    axes.legend(loc="lower left", ncols=2, fontsize=7)
    return save(figure, path, figure_format)


@dataclass(frozen=True)
class RestitutionSeries:
    """One line of the restitution map: thicknesses H / a, the dynamic restitutions and peak
    forces over the half-space's quasi-static P_c, and the base (its line style)."""

    thickness_ratio: Sequence[float]
    restitution: Sequence[float]
    peak_ratio: Sequence[float]
    base: str = "bonded"


@styled
def plot_layer_restitution(
    series: Mapping[str, RestitutionSeries],
    path: Path | str,
    *,
    half_space: float | None = None,
    figure_format: str = "png",
) -> Path:
    """Write the restitution map: restitution and P_max / P_c against H / a, one line each.

    Parameters
    ----------
    series : mapping of str to RestitutionSeries
        Legend label -> the series.
    path, figure_format
        The PNG and the formats, as every chart (:mod:`.style`).
    half_space : float, optional
        The half-space's dynamic restitution, drawn as a grey reference line.
    """
    figure, (left, right) = chart(3.6, 1, 2)
    if half_space is not None:
        left.axhline(half_space, color="#808080", lw=1.0, zorder=1)
        left.text(
            0.02,
            half_space,
            f"half-space {half_space:.3f}",
            va="bottom",
            fontsize=7,
            color="#505050",
            transform=left.get_yaxis_transform(),
        )
    for index, (label, line) in enumerate(series.items()):
        style = {"ls": _STYLES.get(line.base, "-"), "marker": _MARKERS[index % len(_MARKERS)]}
        h = np.asarray(line.thickness_ratio, dtype=float)
        drawn = left.semilogx(h, np.asarray(line.restitution, dtype=float), label=label, **style)
        right.loglog(
            h, np.asarray(line.peak_ratio, dtype=float), color=drawn[0].get_color(), **style
        )
    right.axhline(1.0, color="#808080", lw=1.0, zorder=1)
    for axes in (left, right):
        plain_log(axes.xaxis)
        axes.set_xlabel("H / a")
    plain_log(right.yaxis)
    left.set_ylabel("Restitution e (dynamic FE)")
    right.set_ylabel(r"$P_{\max}\,/\,P_c$ (dynamic FE)")
    left.legend(loc="center left", fontsize=7)
    return save(figure, path, figure_format)
