"""The look shared by every matplotlib figure: colours, rc style, SI prefixes, saving.

Every figure function takes result objects and a path, writes one PNG (200 dpi, no title: the
caption is the reader's) and returns the path. Figures use :class:`matplotlib.figure.Figure`
directly with the Agg canvas and take their style from :func:`styled` (a
:func:`matplotlib.rc_context`): nothing global (pyplot, the backend, rcParams) is touched.

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
from matplotlib.axis import Axis
from matplotlib.figure import Figure
from matplotlib.ticker import FuncFormatter, LogLocator, NullFormatter

__all__ = [
    "APPROXIMATION_COLOUR",
    "DEPTH_STYLES",
    "DPI",
    "EXACT_COLOUR",
    "FEM_COLOUR",
    "PAPER_COLOUR",
    "SECOND_COLOUR",
    "STYLE",
    "WIDTH",
    "fraction",
    "percent",
    "plain_log",
    "save",
    "sci",
    "si_prefix",
    "styled",
]

DPI = 200
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


def styled(function: Callable[..., Path]) -> Callable[..., Path]:
    """Run a figure function inside :data:`STYLE` (no global state changes)."""

    @wraps(function)
    def wrapper(*args: Any, **kwargs: Any) -> Path:
        with mpl.rc_context(STYLE):
            return function(*args, **kwargs)

    return wrapper


def save(figure: Figure, path: Path | str) -> Path:
    """Write ``figure`` as a PNG at :data:`DPI` (parent folders created); returns the path."""
    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    figure.savefig(path, dpi=DPI)
    return path


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
