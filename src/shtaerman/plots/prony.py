"""A Prony series at a glance: E(t), E'(f), E''(f) and tan delta, to catch a typo before a run.

:func:`prony_curves` gives the plotted data (tested as numbers); :func:`prony_figure` draws them:
the relaxation E(t) on the left, the storage and loss moduli over the frequency f = omega/2 pi on
the right with tan delta on a second axis. The ranges span a decade beyond the shortest and
the longest tau_i. Without E0 (weights only) the moduli are the ratios to E0.
"""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np

from ..theory.viscoelastic import PronySeries
from .style import EXACT_COLOUR, FEM_COLOUR, SECOND_COLOUR, chart, save, styled

__all__ = ["POINTS_PER_DECADE", "prony_curves", "prony_figure"]

POINTS_PER_DECADE = 40
"""Samples per decade of t and of f: a term's features span about a decade."""


def prony_curves(series: PronySeries, modulus: float | None = None) -> dict[str, np.ndarray]:
    """The plotted data: ``time`` (s) and ``relaxation`` E(t); ``frequency`` (Hz),
    ``storage`` E', ``loss`` E'' and ``tan_delta``; moduli in Pa, or ratios to E0 when
    ``modulus`` (E0 in Pa) is None."""
    scale = 1.0 if modulus is None else float(modulus)
    low, high = math.log10(min(series.times)) - 1.0, math.log10(max(series.times)) + 1.0
    count = math.ceil((high - low) * POINTS_PER_DECADE) + 1
    time = np.logspace(low, high, count)
    frequency = 1.0 / (2.0 * math.pi * time[::-1])
    ratio = series.dynamic_modulus(2.0 * math.pi * frequency)
    return {
        "time": time,
        "relaxation": scale * series.relaxation(time),
        "frequency": frequency,
        "storage": scale * ratio.real,
        "loss": scale * ratio.imag,
        "tan_delta": ratio.imag / ratio.real,
    }


@styled
def prony_figure(
    series: PronySeries, path: Path | str, modulus: float | None = None, label: str = ""
) -> Path:
    """Draw :func:`prony_curves` to ``path`` (.png, .svg or .pdf); returns the path."""
    data = prony_curves(series, modulus)
    unit = "E / E0" if modulus is None else "MPa"
    factor = 1.0 if modulus is None else 1e-6
    figure, (left, right) = chart(3.6, 1, 2, width=9.0)
    left.semilogx(data["time"], factor * data["relaxation"], color=EXACT_COLOUR)
    left.set(xlabel="t (s)", ylabel=f"E(t) ({unit})")
    for tau in series.times:
        left.axvline(tau, color="#b0b0b0", linewidth=0.6, linestyle=":")
    right.loglog(data["frequency"], factor * data["storage"], color=EXACT_COLOUR, label="E'")
    right.loglog(data["frequency"], factor * data["loss"], color=FEM_COLOUR, label="E''")
    right.set(xlabel="f (Hz)", ylabel=f"E', E'' ({unit})")
    twin = right.twinx()
    twin.semilogx(data["frequency"], data["tan_delta"], color=SECOND_COLOUR, linestyle="--")
    twin.set_ylabel("tan \N{GREEK SMALL LETTER DELTA} (dashed)")
    twin.grid(False)
    right.legend(loc="upper left")
    if label:
        left.set_title(label, fontsize=9)
    return save(figure, path)
