"""The look shared by every matplotlib figure: colours, rc style, SI prefixes, saving.

Every figure function takes result objects and a path, writes one PNG (200 dpi, no title: the
caption is the reader's; the effect table's figure, which `effects --out` writes without a
report around it, names its case in a title) and returns the path. With
``figure_format="svg"`` or ``"pdf"`` it also writes the same figure as vector graphics beside
the PNG (same stem; text kept as text, so a paper's editor can restyle it); the PNG stays, as
the reports embed it. A path ending in .svg or .pdf writes that format alone. Figures use
:class:`matplotlib.figure.Figure` directly with the Agg canvas and take their style from
:func:`styled` (a :func:`matplotlib.rc_context`): nothing global (pyplot, the backend,
rcParams) is touched.

Colours are fixed across figures: the exact theory is black, the FEM blue (:data:`FEM_COLOUR`),
the paper's printed numbers red and its approximations orange (dashed).
"""

from __future__ import annotations

import math
from collections.abc import Callable
from fractions import Fraction
from functools import wraps
from pathlib import Path
from typing import Any

import matplotlib as mpl
import numpy as np
from matplotlib.axes import Axes
from matplotlib.axis import Axis
from matplotlib.backends.backend_agg import FigureCanvasAgg
from matplotlib.figure import Figure
from matplotlib.image import imsave
from matplotlib.ticker import FuncFormatter, LogLocator, NullFormatter

from ..validation import InputError
from .formats import FIGURE_FORMATS, check_figure_format
from .shared import SharedContext

__all__ = [
    "APPROXIMATION_COLOUR",
    "DEPTH_STYLES",
    "DPI",
    "EXACT_COLOUR",
    "FEM_COLOUR",
    "FIGURE_FORMATS",
    "PAPER_COLOUR",
    "PNG_COMPRESSION",
    "SECOND_COLOUR",
    "STYLE",
    "WIDTH",
    "chart",
    "check_figure_format",
    "fraction",
    "note",
    "percent",
    "plain_log",
    "points",
    "save",
    "sci",
    "si_prefix",
    "styled",
    "unresolved",
]

DPI = 200
PNG_COMPRESSION = 3
"""zlib level of the PNGs (lossless at any level; its cost: benchmarks/FEM_NOTES.md, "Figures")."""
WIDTH = 6.4
"""Figure width in inches (1280 pixels at :data:`DPI`)."""
EXACT_COLOUR = "#000000"
FEM_COLOUR = "#1f77b4"
PAPER_COLOUR = "#d62728"
APPROXIMATION_COLOUR = "#ff7f0e"
SECOND_COLOUR = "#d62728"
"""The second quantity of a two-quantity plot (P/P_c, p(0)/p_c)."""
DEPTH_STYLES = (("#1f77b4", "o"), ("#2ca02c", "s"), ("#9467bd", "^"))
"""(colour, marker) of up to three depths in one plot."""
STYLE = {
    "font.size": 10,
    "axes.labelsize": 10,
    "legend.fontsize": 8.5,
    "xtick.labelsize": 9,
    "ytick.labelsize": 9,
    "xtick.direction": "in",
    "ytick.direction": "in",
    "xtick.top": True,
    "ytick.right": True,
    "axes.grid": True,
    "grid.color": "#d0d0d0",
    "grid.linewidth": 0.5,
    "lines.linewidth": 1.5,
    "lines.markersize": 5,
    "legend.frameon": False,
    "mathtext.fontset": "dejavusans",
    "savefig.dpi": DPI,
    "svg.fonttype": "none",
    "pdf.fonttype": 42,
}
_PREFIXES = {-9: "n", -6: "µ", -3: "m", 0: "", 3: "k", 6: "M", 9: "G"}


def si_prefix(magnitude: float, unit: str) -> tuple[float, str]:
    """Scale factor and prefixed unit that put ``magnitude`` in [1, 1000).

    Parameters
    ----------
    magnitude : float
        A typical value in the SI unit (e.g. 8.5e-3 for 8.5 mm).
    unit : str
        The SI unit, e.g. ``"m"`` or ``"Pa"``.

    Returns
    -------
    scale : float
        Multiply SI values by it to get the prefixed unit.
    prefixed : str
        E.g. ``"mm"`` or ``"MPa"``.
    """
    power = 3 * math.floor(math.log10(magnitude) / 3) if magnitude > 0 else 0
    power = min(max(power, min(_PREFIXES)), max(_PREFIXES))
    return 10.0**-power, f"{_PREFIXES[power]}{unit}"


_STYLED = SharedContext(lambda: mpl.rc_context(STYLE))
""":data:`STYLE` in rcParams while any thread draws; the caller's back after the last."""


def styled(function: Callable[..., Path]) -> Callable[..., Path]:
    """Run a figure function inside :data:`STYLE` (no global state changes once every
    figure drawn at once, in any thread, is done: :data:`_STYLED`)."""

    @wraps(function)
    def wrapper(*args: Any, **kwargs: Any) -> Path:
        with _STYLED():
            return function(*args, **kwargs)

    return wrapper


def chart(height: float, *grid: int, width: float = WIDTH, **options: Any) -> tuple[Figure, Any]:
    """A new figure ``width`` x ``height`` inches (constrained layout) and its axes:
    ``figure.subplots(*grid, **options)``."""
    figure = Figure(figsize=(width, height), layout="constrained")
    return figure, figure.subplots(*grid, **options)


def note(axes: Axes, text: str, x: float = 0.98) -> None:
    """A small grey remark in the lower right corner of ``axes`` (``x``: its right edge, in
    axes fractions)."""
    axes.text(x, 0.02, text, transform=axes.transAxes, ha="right", va="bottom", fontsize=7.5,
              color="0.3")  # fmt: skip


def save(figure: Figure, path: Path | str, figure_format: str = "png") -> Path:
    """Write ``figure`` to ``path`` at :data:`DPI` (parent folders created); returns the path.

    The format is the path's suffix (.png, .svg or .pdf); ``figure_format`` "svg" or "pdf"
    adds that format beside it (same stem), e.g. ``f.png`` and ``f.pdf``.
    """
    path = Path(path)
    check_figure_format(figure_format)
    suffix = path.suffix.lower().lstrip(".")
    if suffix not in FIGURE_FORMATS:
        raise InputError(f"figure path must end in .png, .svg or .pdf, got {str(path)!r}")
    path.parent.mkdir(parents=True, exist_ok=True)
    with _STYLED():
        if suffix == "png":
            _png(figure, path)
        else:
            figure.savefig(path, dpi=DPI, metadata={"Date": None})
        if figure_format not in ("png", suffix):
            twin = path.with_suffix(f".{figure_format}")
            figure.savefig(twin, dpi=DPI, metadata={"Date": None})
    return path


def _png(figure: Figure, path: Path) -> None:
    """``figure`` drawn once on an Agg canvas at :data:`DPI` (its layout engine runs inside the
    draw) and written at :data:`PNG_COMPRESSION`: the bytes ``savefig`` writes, which draws
    twice (the first draw, with drawing disabled, only for the layout). The vector formats keep
    ``savefig``; no creation date in them (the same figure gives the same bytes)."""
    dpi = figure.dpi
    figure.set_dpi(DPI)
    try:
        canvas = FigureCanvasAgg(figure)
        canvas.draw()
        imsave(path, canvas.buffer_rgba(), format="png", origin="upper", dpi=DPI,
               pil_kwargs={"compress_level": PNG_COMPRESSION})  # fmt: skip
    finally:
        figure.set_dpi(dpi)


def plain_log(axis: Axis) -> None:
    """Log axis labelled 1, 2, 5, 10, ... in plain numbers."""
    axis.set_major_locator(LogLocator(base=10.0, subs=(1.0, 2.0, 5.0)))
    axis.set_major_formatter(FuncFormatter(lambda value, _: f"{value:g}"))
    axis.set_minor_formatter(NullFormatter())


def fraction(value: float) -> str:
    """5/3 for 1.6667, 3/2 for 1.5, else the number."""
    exact = Fraction(value).limit_denominator(12)
    if abs(float(exact) - value) > 1e-9 * abs(value):
        return f"{value:.4g}"
    return str(exact)


def sci(value: float, digits: int = 5) -> str:
    """Mathtext scientific notation, e.g. 2.7763\\times10^{6}."""
    exponent = math.floor(math.log10(abs(value)))
    return rf"{value / 10**exponent:.{digits - 1}f}\times10^{{{exponent}}}"


def percent(value: float) -> str:
    """A relative difference in per cent with its sign, e.g. ``+0.012 %``."""
    return f"{100 * value:+.3f} %"


def unresolved(effect: np.ndarray, error: np.ndarray | None) -> np.ndarray:
    """Where an estimated ``error`` is not below the ``effect`` it should resolve (same units;
    NaN errors count as unresolved); all False without errors."""
    effect = np.abs(np.asarray(effect, dtype=float))
    if error is None:
        return np.zeros(effect.shape, dtype=bool)
    with np.errstate(invalid="ignore"):
        return ~(np.asarray(error, dtype=float) < effect)


def points(
    axes: Axes,
    x: np.ndarray,
    y: np.ndarray,
    style: tuple[str, str, str, str],
    *,
    error: np.ndarray | None = None,
    hidden: np.ndarray | None = None,
) -> None:
    """Data points joined by a line, with error bars if given; the ``hidden`` ones (unresolved:
    their error is not below the effect shown) as open markers, not joined to the line.

    ``style`` = (colour, marker, line style, label); the open markers get their own legend
    entry, "<label>, unresolved".
    """
    colour, marker, line, label = style
    x, y = np.asarray(x, dtype=float), np.asarray(y, dtype=float)
    hidden = np.zeros(y.shape, dtype=bool) if hidden is None else np.asarray(hidden, dtype=bool)
    shown = np.where(hidden, np.nan, y)
    axes.plot(x, shown, color=colour, marker=marker, linestyle=line, label=label)
    if error is not None:
        axes.errorbar(x, y, yerr=np.asarray(error, dtype=float), fmt="none", ecolor=colour,
                      capsize=2)  # fmt: skip
    if hidden.any():
        axes.plot(
            x[hidden], y[hidden], color=colour, marker=marker, linestyle="none",
            markerfacecolor="white", label=f"{label}, unresolved",
        )  # fmt: skip
