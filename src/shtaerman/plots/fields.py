"""Which FEM fields can be drawn, and how one is coloured: unit, colour map, range, bar, isolines.

Stresses are shown in a prefixed pascal unit (MPa for the paper's example) named in the colour
bar's title, on a colour range with round ticks and isolines at those ticks. Signed fields use a
diverging map cut to their range (white at 0, blue compression, red tension, the same strength
for the same magnitude of either sign); fields that are never negative use :data:`MAGNITUDE`.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
import pyvista as pv
from matplotlib import colormaps
from matplotlib.colors import Colormap, ListedColormap

from ..validation import InputError
from .render import FONT_SIZE, use_font
from .style import si_prefix

__all__ = [
    "DIVERGING",
    "FIELDS",
    "MAGNITUDE",
    "FieldColours",
    "FieldSpec",
    "add_coloured",
    "check_field",
    "decimals",
    "isolines",
    "nice_step",
    "shown",
]

DIVERGING = "RdBu_r"
"""Colour map of signed fields (blue negative: compression, red positive: tension)."""
MAGNITUDE = "plasma"
"""Colour map of fields that are never negative (von Mises)."""
ONE_SIGNED = 0.03
"""Fraction of a field's range below which its minority sign is treated as noise."""

SIGMA = "\N{GREEK SMALL LETTER SIGMA}"
THETA = "\N{GREEK SMALL LETTER THETA}"


@dataclass(frozen=True)
class FieldSpec:
    """How one vertex field of :class:`shtaerman.fem.elasticity.ElasticSolution` is shown."""

    name: str
    symbol: str
    unit: str
    signed: bool = True
    """Drawn with :data:`DIVERGING` (white at 0); else with :data:`MAGNITUDE`."""


FIELDS = {
    "sigma_zz": FieldSpec("Axial stress", f"{SIGMA}zz", "Pa"),
    "sigma_rr": FieldSpec("Radial stress", f"{SIGMA}rr", "Pa"),
    "sigma_tt": FieldSpec("Hoop stress", f"{SIGMA}{THETA}{THETA}", "Pa"),
    "sigma_rz": FieldSpec("Shear stress", f"{SIGMA}rz", "Pa"),
    "von_mises": FieldSpec("Von Mises", f"{SIGMA}v", "Pa", signed=False),
    "mean_pressure": FieldSpec("Mean pressure", "p", "Pa"),
    "u_z": FieldSpec("Displacement", "uz", "m"),
    "u_r": FieldSpec("Displacement", "ur", "m"),
}
"""Fields that can be plotted: name, symbol, SI unit (stresses are tension positive, the mean
pressure compression positive, displacements positive along +r, +z)."""


def check_field(name: str) -> FieldSpec:
    """The spec of field ``name``; :class:`InputError` naming the valid ones if unknown."""
    if name not in FIELDS:
        raise InputError(f"Unknown field '{name}'. Pick one of {sorted(FIELDS)}")
    return FIELDS[name]


def nice_step(span: float, intervals: int = 5) -> float:
    """The smallest of 1, 2, 2.5, 5 x 10^k that cuts ``span`` into at most ``intervals``."""
    raw = span / intervals
    power = 10.0 ** math.floor(math.log10(raw))
    return next(m * power for m in (1.0, 2.0, 2.5, 5.0, 10.0) if m * power >= raw * (1 - 1e-9))


def decimals(step: float) -> int:
    """Decimals needed to print multiples of ``step`` exactly."""
    return next(d for d in range(12) if abs(round(step, d) - step) < 1e-9 * step)


@dataclass(frozen=True)
class FieldColours:
    """Colour range of one field, in display units (``scale`` per SI unit)."""

    scale: float
    title: str
    low: float
    high: float
    step: float
    cmap: str | Colormap

    @property
    def levels(self) -> np.ndarray:
        """Isoline values: the interior colour-bar ticks."""
        count = round((self.high - self.low) / self.step)
        return self.low + self.step * np.arange(1, count)


def _colours(values: np.ndarray, spec: FieldSpec) -> FieldColours:
    """Prefixed unit, colour map and a colour range on round ticks covering ``values`` (SI).

    A sign present only as noise (under ``ONE_SIGNED`` of the range, e.g. the projected
    sigma_zz on the free surface) is cut off at zero, so the range starts at 0.
    """
    low, high = float(values.min()), float(values.max())
    if 0 < high <= ONE_SIGNED * (high - low):
        high = 0.0
    elif 0 > low >= -ONE_SIGNED * (high - low):
        low = 0.0
    step = nice_step(max(high - low, 1e-300), 10)
    low, high = step * math.floor(low / step + 1e-9), step * math.ceil(high / step - 1e-9)
    high = max(high, low + step)
    scale, unit = si_prefix(max(-low, high), spec.unit)
    cmap = _diverging(low, high) if spec.signed else MAGNITUDE
    title = f"{spec.name}\n{spec.symbol} ({unit})"
    return FieldColours(scale, title, low * scale, high * scale, step * scale, cmap)


def _diverging(low: float, high: float) -> Colormap:
    """:data:`DIVERGING` cut to [low, high]: white at 0, blue below, red above, the same
    strength for the same magnitude of either sign (small tension stays pale)."""
    reach = max(-low, high)
    values = np.linspace(low, high, 256)
    return ListedColormap(colormaps[DIVERGING](0.5 + 0.5 * values / reach))


def shown(section: pv.PolyData, name: str) -> FieldColours:
    """Attach the field ``name`` in display units as "shown"; its colour range."""
    colours = _colours(section.point_data[name], FIELDS[name])
    section.point_data["shown"] = section.point_data[name] * colours.scale
    return colours


def _scalar_bar(colours: FieldColours, left: float) -> dict:
    return {
        "title": colours.title,
        "vertical": True,
        "position_x": left,
        "position_y": 0.12,
        "height": 0.72,
        "width": 0.05,
        "n_labels": round((colours.high - colours.low) / colours.step) + 1,
        "fmt": f"%.{decimals(colours.step)}f",
        "color": "black",
        "title_font_size": FONT_SIZE,
        "label_font_size": FONT_SIZE,
    }


def add_coloured(
    plotter: pv.Plotter, mesh: pv.DataSet, colours: FieldColours, bar: float, **shading
) -> None:
    """``mesh`` coloured by "shown", with its colour bar's left edge at ``bar`` (0..1)."""
    plotter.add_mesh(
        mesh,
        scalars="shown",
        cmap=colours.cmap,
        clim=(colours.low, colours.high),
        scalar_bar_args=_scalar_bar(colours, bar),
        **shading,
    )
    actor = plotter.scalar_bars[colours.title]
    for prop in (actor.GetTitleTextProperty(), actor.GetLabelTextProperty()):
        use_font(prop)


def isolines(section: pv.PolyData, colours: FieldColours) -> pv.PolyData | None:
    """Lines of "shown" at the interior colour-bar ticks (None if there are none)."""
    if not colours.levels.size:
        return None
    lines = section.contour(isosurfaces=colours.levels, scalars="shown")
    return lines if lines.n_points else None
