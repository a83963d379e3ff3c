"""The Ateb functions of the impact (PNG): for the paper's n = 3/2 against its Tables 1-2 and
approximations, for any other exponent the exact pair alone."""

from __future__ import annotations

from collections.abc import Iterable
from pathlib import Path

import numpy as np
from matplotlib.axes import Axes

from ..paper.printed import paper_cosine_approximation, paper_sine_approximation, printed_table
from ..theory.ateb import ateb_cosine, ateb_sine
from ..theory.impact import duration_integral
from .style import APPROXIMATION_COLOUR, EXACT_COLOUR, PAPER_COLOUR, chart, save, styled

__all__ = ["paper_figures", "plot_ateb"]

PAPER_EXPONENT = 1.5
"""The exponent of the paper's indenter, the only one its tables and approximations are for."""


def _ateb_column(top: Axes, bottom: Axes, kind: str) -> None:
    """One function: exact curve, printed table, approximation; its relative error below."""
    integral = duration_integral(5.0 / 3.0)
    s = np.linspace(0.0, integral, 2001)
    function, paper, name, number = {
        "sine": (ateb_sine, paper_sine_approximation, "eta", "1"),
        "cosine": (ateb_cosine, paper_cosine_approximation, "zeta", "2"),
    }[kind]
    exact, approximation = function(5.0 / 3.0, 1.0, 4.0 / 3.0 * s), paper(s)
    table, symbol = printed_table(f"table{number}"), f"\\{name}"
    label = rf"${kind[0].upper()}a(5/3, 1, 4{symbol}/3)$"
    top.plot(s, exact, color=EXACT_COLOUR, label="exact")
    top.plot(s, approximation, "--", color=APPROXIMATION_COLOUR, label="paper's approximation")
    top.plot(
        table[name],
        table[kind],
        "o",
        color=PAPER_COLOUR,
        markersize=4,
        markerfacecolor="none",
        label=f"paper's Table {number}",
    )
    top.set_ylabel(label)
    top.set_ylim(0.0, 1.05)
    top.legend(loc="lower right" if kind == "sine" else "lower left")
    inside = exact > 1e-9  # the relative error is 0/0 where both vanish
    error = np.full_like(s, np.nan)
    error[inside] = 100 * (approximation[inside] / exact[inside] - 1)
    worst = int(np.nanargmax(np.abs(error)))
    bottom.plot(s, error, color=APPROXIMATION_COLOUR)
    for bound in (-1.0, 1.0):
        bottom.axhline(bound, color="0.4", linestyle=":", linewidth=1.0)
    bottom.plot(s[worst], error[worst], "o", color=APPROXIMATION_COLOUR)
    right = s[worst] > 0.5 * integral
    bottom.annotate(
        f"max {abs(error[worst]):.3f} %",
        (s[worst], error[worst]),
        xytext=(-8 if right else 8, 0),
        textcoords="offset points",
        ha="right" if right else "left",
        va="center",
        fontsize=8.5,
    )
    bottom.text(
        0.99 * integral,
        1.05,
        "paper's claim: 1 %",
        ha="right",
        va="bottom",
        fontsize=8.5,
        color="0.3",
    )
    bottom.set_ylim(-1.5, 1.5)
    bottom.set_xlabel(f"${symbol}$")
    bottom.set_xlim(0.0, integral)


def _exact_column(axes: Axes, kind: str, q: float) -> None:
    """Sa(q, 1, (q+1)/2 eta) (compression) or Ca(q, 1, (q+1)/2 zeta) (restitution) on [0, I]."""
    integral = duration_integral(q)
    s = np.linspace(0.0, integral, 2001)
    function, symbol, name = (
        (ateb_sine, r"\eta", "Sa") if kind == "sine" else (ateb_cosine, r"\zeta", "Ca")
    )
    axes.plot(s, function(q, 1.0, (q + 1.0) / 2.0 * s), color=EXACT_COLOUR, label="exact")
    axes.set_ylabel(f"${name}({q:.4g}, 1, {(q + 1.0) / 2.0:.4g}{symbol})$")
    axes.set_xlabel(f"${symbol}$")
    axes.set_ylim(0.0, 1.05)
    axes.set_xlim(0.0, integral)


@styled
def plot_ateb(
    path: Path | str, exponent: float = PAPER_EXPONENT, *, figure_format: str = "png"
) -> Path:
    """Write the Ateb functions of the impact on an indenter z = A r^n, n = ``exponent``.

    For n = 3/2 (q = 5/3), Sa(5/3, 1, 4 eta/3) and Ca(5/3, 1, 4 zeta/3) against the paper's
    Tables 1-2 as below; for any other n, Sa(q, 1, (q+1)/2 eta) and Ca(q, 1, (q+1)/2 zeta),
    q = (n+1)/n, exact over [0, I] (the paper tabulates no other exponent).

    Top: the exact functions (:mod:`shtaerman.theory.ateb`), the printed table values
    (markers) and the paper's piecewise approximations (dashed), over one compression (eta) and one
    restitution (zeta) interval [0, I], I = 1.445927. Bottom: the approximations' relative
    error in %, its maximum marked, against the paper's claimed 1 % (dotted).

    Parameters
    ----------
    path, figure_format
        The PNG (1480 x 1000 pixels for n = 3/2, 1480 x 600 otherwise) and the formats, as
        every chart (:mod:`.style`).
    exponent : float
        The indenter's exponent n (> 1).
    """
    if exponent != PAPER_EXPONENT:
        q = (exponent + 1.0) / exponent
        figure, panels = chart(3.0, 1, 2, width=7.4)
        for axes, kind in zip(panels, ("sine", "cosine"), strict=True):
            _exact_column(axes, kind, q)
        figure.suptitle(f"n = {exponent:g}, q = (n+1)/n = {q:.4g}")
        return save(figure, path, figure_format)
    figure, axes = chart(5.0, 2, 2, width=7.4, sharex=True, height_ratios=(2.2, 1))
    _ateb_column(axes[0, 0], axes[1, 0], "sine")
    _ateb_column(axes[0, 1], axes[1, 1], "cosine")
    axes[1, 0].set_ylabel("Approximation\nerror (%)")
    return save(figure, path, figure_format)


def paper_figures(
    folder: Path | str, exponents: Iterable[float] = (1.5,), figure_format: str = "png"
) -> dict[str, Path]:
    """The figures that depend on no study, written into ``folder``: the Ateb functions of
    the impact for each indenter exponent of the run (``ateb.png`` for the paper's n = 3/2,
    against its Tables 1-2; ``ateb_n<n>.png`` for any other).

    Parameters
    ----------
    folder, figure_format
        As every figure set of a run (:mod:`.gallery`): returns caption -> PNG path.
    exponents : iterable of float
        The studies' indenter exponents n (repeats ignored).
    """
    made, fmt = {}, {"figure_format": figure_format}
    for exponent in sorted(set(exponents)):
        if exponent == PAPER_EXPONENT:
            caption = (
                "Ateb functions of the impact against the paper's Tables 1-2 and approximations"
            )
            made[caption] = plot_ateb(Path(folder) / "ateb.png", **fmt)
            continue
        q = (exponent + 1.0) / exponent
        caption = (
            f"Ateb functions of the impact for n = {exponent:g} (q = {q:.4g}): x/x_c in "
            "compression, the velocity in restitution"
        )
        made[caption] = plot_ateb(Path(folder) / f"ateb_n{exponent:g}.png", exponent, **fmt)
    return made
