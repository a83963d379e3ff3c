"""Paper-ready matplotlib figures (PNG) of the contact, the impact and the Ateb functions.

Every function takes result objects and a path, writes one PNG (200 dpi, no title: the caption
is the reader's) and returns the path. The figures use :class:`matplotlib.figure.Figure`
directly with the Agg canvas, and their style through :func:`matplotlib.rc_context`: nothing
global (pyplot, the backend, rcParams) is touched.

Colours are fixed across figures: the exact theory is black, the FEM blue (:data:`FEM_COLOUR`),
the paper's printed numbers red and its approximations orange (dashed).
"""

from __future__ import annotations

import math
from collections.abc import Callable, Iterable, Mapping, Sequence
from fractions import Fraction
from functools import wraps
from pathlib import Path
from typing import TYPE_CHECKING, Any

import matplotlib as mpl
import numpy as np
from matplotlib.axes import Axes
from matplotlib.axis import Axis
from matplotlib.figure import Figure
from matplotlib.lines import Line2D
from matplotlib.ticker import FuncFormatter, LogLocator, NullFormatter

from ..paper.printed import paper_cosine_approximation, paper_sine_approximation, printed_table
from ..study.convergence import ConvergenceStudy
from ..study.indentation import IndentationResult
from ..theory.ateb import ateb_cosine, ateb_sine
from ..theory.contact import paper_pressure_eq5
from ..theory.impact import ImpactHistory, ImpactResult, duration_integral

if TYPE_CHECKING:
    from ..study.run import StudyOutcome

__all__ = [
    "EXACT_COLOUR",
    "FEM_COLOUR",
    "paper_figures",
    "plot_ateb",
    "plot_convergence",
    "plot_force_depth",
    "plot_impact_contact",
    "plot_impact_motion",
    "plot_pressure",
    "si_prefix",
    "study_figures",
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
VARIANT_STYLES = ("-", "--", ":", "-.")
VARIANT_LABELS = {
    "analytic": r"exact (Ateb, analytic $\beta$)",
    "fem_fitted": r"FEM-fitted $\beta x^q$ (Ateb)",
    "fem_tabulated": r"FEM-tabulated $P(x)$ (ODE)",
}
"""Legend text of the impact variants of :class:`shtaerman.verification.StudyOutcome`."""
ERROR_LABELS = {
    "force": "force $P$",
    "beta": r"coefficient $\beta$",
    "contact_radius": "contact radius $a$",
    "central_pressure": "central pressure $p(0)$",
    "exponent": "exponent $q$",
    "pressure_profile": "pressure profile $p(r)$",
}
CONVERGENCE_KEYS = ("force", "beta", "contact_radius", "central_pressure")
"""Errors drawn by default by :func:`plot_convergence`."""
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


def _styled(function: Callable[..., Path]) -> Callable[..., Path]:
    """Run a figure function inside the module's rc style (no global state changes)."""

    @wraps(function)
    def wrapper(*args: Any, **kwargs: Any) -> Path:
        with mpl.rc_context(STYLE):
            return function(*args, **kwargs)

    return wrapper


def _save(figure: Figure, path: Path | str) -> Path:
    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    figure.savefig(path, dpi=DPI)
    return path


def _plain_log(axis: Axis) -> None:
    """Log axis labelled 1, 2, 5, 10, ... in plain numbers."""
    axis.set_major_locator(LogLocator(base=10.0, subs=(1.0, 2.0, 5.0)))
    axis.set_major_formatter(FuncFormatter(lambda value, _: f"{value:g}"))
    axis.set_minor_formatter(NullFormatter())


def _fraction(value: float) -> str:
    """5/3 for 1.6667, 3/2 for 1.5, else the number."""
    exact = Fraction(value).limit_denominator(12)
    if abs(float(exact) - value) > 1e-9 * abs(value):
        return f"{value:.4g}"
    return str(exact)


def _sci(value: float, digits: int = 5) -> str:
    """Mathtext scientific notation, e.g. 2.7763\\times10^{6}."""
    exponent = math.floor(math.log10(abs(value)))
    return rf"{value / 10**exponent:.{digits - 1}f}\times10^{{{exponent}}}"


def _percent(value: float) -> str:
    return f"{100 * value:+.3f} %"


# --- 1. force against depth ------------------------------------------------------------------


def _fit_note(result: IndentationResult) -> str:
    q_exact, fit = result.exact.force_exponent, result.fit
    beta_exact, q_text = result.exact.beta, _fraction(q_exact)
    return "\n".join(
        [
            rf"FEM, free fit: $q$ = {fit.exponent:.5f} (exact {q_text} = {q_exact:.5f}, "
            f"{_percent(fit.exponent / q_exact - 1)})",
            rf"FEM, $q$ = {q_text}: $\beta$ = ${_sci(fit.beta_fixed_exponent)}$ "
            rf"N m$^{{-{q_text}}}$ (exact ${_sci(beta_exact)}$, "
            f"{_percent(fit.beta_fixed_exponent / beta_exact - 1)})",
        ]
    )


@_styled
def plot_force_depth(result: IndentationResult, path: Path | str) -> Path:
    """Write the force-depth curve: FEM points against P = beta x^q (log-log).

    The lower panel is the relative difference of each FEM force from the exact one (%);
    the fitted exponent and beta (exponent held at the theory's) are printed against the
    exact values.

    Parameters
    ----------
    result : IndentationResult
        The FEM indentation run (depths in m, forces in N).
    path : path-like
        PNG to write (1280 x 960 pixels).

    Returns
    -------
    pathlib.Path
        ``path``.
    """
    depths = np.array([step.depth for step in result.steps])
    forces = np.array([step.force for step in result.steps])
    x_scale, x_unit = si_prefix(math.sqrt(depths.min() * depths.max()), "m")
    p_scale, p_unit = si_prefix(math.sqrt(forces.min() * forces.max()), "N")
    figure = Figure(figsize=(WIDTH, 4.8), layout="constrained")
    top, bottom = figure.subplots(2, 1, sharex=True, height_ratios=(3, 1))
    line = np.geomspace(depths.min() / 1.25, depths.max() * 1.25, 200)
    q = _fraction(result.exact.force_exponent)
    top.loglog(
        line * x_scale,
        result.exact.force(line) * p_scale,
        color=EXACT_COLOUR,
        label=rf"Shtaerman: $P = \beta x^{{{q}}}$",
    )
    top.loglog(depths * x_scale, forces * p_scale, "o", color=FEM_COLOUR, label="FEM")
    top.set_ylabel(f"Force $P$ ({p_unit})")
    top.legend(loc="upper left")
    top.text(
        0.98,
        0.04,
        _fit_note(result),
        transform=top.transAxes,
        ha="right",
        va="bottom",
        fontsize=8.5,
    )
    bottom.axhline(0.0, color=EXACT_COLOUR, linewidth=1.0)
    bottom.plot(
        depths * x_scale, 100 * (forces / result.exact.force(depths) - 1), "o-", color=FEM_COLOUR
    )
    bottom.set_xlabel(f"Depth $x$ ({x_unit})")
    bottom.set_ylabel(r"$P_\mathrm{FEM}/P - 1$ (%)")
    for axes in (top, bottom):
        _plain_log(axes.xaxis)
    _plain_log(top.yaxis)
    return _save(figure, path)


# --- 2. pressure profile ---------------------------------------------------------------------


def _exact_profile(result: IndentationResult, depth: float, rho: np.ndarray) -> np.ndarray:
    """p/p_avg at r/a = rho: the paper's eq. (5) for n = 3/2, else the hypergeometric form."""
    exact, a = result.exact, float(result.exact.contact_radius(depth))
    mean = float(exact.mean_pressure(depth))
    if result.indenter.exponent != 1.5:
        return exact.pressure(rho * a, depth) / mean
    inside = rho <= 1.0
    p = np.zeros_like(rho)
    p[inside] = paper_pressure_eq5(rho[inside] * a, a, float(exact.force(depth)))
    return p / mean


def _thinned(rho: np.ndarray, spacing: float) -> np.ndarray:
    """Indices of rho (ascending) at least ``spacing`` apart, the first always kept."""
    keep, last = [], -np.inf
    for index, value in enumerate(rho):
        if value - last >= spacing:
            keep.append(index)
            last = value
    return np.array(keep, dtype=int)


def _pressure_steps(result: IndentationResult, steps: Sequence[int] | None) -> list[int]:
    count = len(result.steps)
    if steps is None:
        steps = [count - 1, count // 2, 0] if count > 2 else list(range(count - 1, -1, -1))
    return list(dict.fromkeys(index % count for index in steps))[: len(DEPTH_STYLES)]


def _pressure_markers(axes: Axes, result: IndentationResult, index: int, style: tuple) -> float:
    """FEM nodal p/p_avg against r/a for one step (exact a, p_avg).

    Returns the FEM's own p(0)/p_avg, from its central pressure, force and contact radius.
    """
    step, r = result.steps[index], result.curve.compliance.r
    a = float(result.exact.contact_radius(step.depth))
    mean = float(result.exact.mean_pressure(step.depth))
    rho = r / a
    shown = _thinned(rho, 0.03)
    shown = shown[rho[shown] <= 1.3]
    scale, unit = si_prefix(step.depth, "m")
    colour, marker = style
    axes.plot(
        rho[shown],
        step.pressure[shown] / mean,
        marker,
        color=colour,
        markersize=4.5,
        markerfacecolor="none",
        label=f"FEM, $x$ = {step.depth * scale:#.3g} {unit}",
    )
    return step.central_pressure / step.mean_pressure


@_styled
def plot_pressure(
    result: IndentationResult, path: Path | str, steps: Sequence[int] | None = None
) -> Path:
    """Write the contact pressure p(r)/p_avg against r/a: FEM nodal values and the exact curve.

    FEM pressures are normalised by the exact contact radius a and mean pressure P/(pi a^2) at
    the same depth, so differences are errors, not rescalings. For n = 3/2 the exact curve is
    the paper's eq. (5); the central value (n+1)/(2(n-1)) (2.5 for n = 3/2) is marked.

    Parameters
    ----------
    result : IndentationResult
        The FEM indentation run (pressure recovered at the surface nodes, Pa).
    path : path-like
        PNG to write (1280 x 840 pixels).
    steps : sequence of int, optional
        Indices of ``result.steps`` to show (up to three); default the largest, a middle and
        the smallest depth.

    Returns
    -------
    pathlib.Path
        ``path``.
    """
    figure = Figure(figsize=(WIDTH, 4.2), layout="constrained")
    axes = figure.subplots()
    rho = np.linspace(0.0, 1.3, 521)
    deepest = result.steps[-1].depth
    label = "paper's eq. (5)" if result.indenter.exponent == 1.5 else "exact"
    axes.plot(
        rho, _exact_profile(result, deepest, rho), color=EXACT_COLOUR, label=f"Shtaerman, {label}"
    )
    centre = []
    for index, style in zip(_pressure_steps(result, steps), DEPTH_STYLES, strict=False):
        centre.append(_pressure_markers(axes, result, index, style))
    ratio = result.exact.central_to_mean_ratio
    axes.axhline(ratio, color="0.4", linestyle=":", linewidth=1.0)
    note = r"$p(0)/p_{avg}$" + f"\nexact {ratio:g}\nFEM {min(centre):.3f} to {max(centre):.3f}"
    axes.text(1.02, 0.97 * ratio, note, ha="left", va="top", fontsize=8.5)
    axes.axvline(1.0, color="0.4", linestyle=":", linewidth=1.0)
    axes.set_xlim(0.0, 1.3)
    axes.set_ylim(0.0, 1.08 * max(ratio, *centre))
    axes.set_xlabel("Radius $r/a$")
    axes.set_ylabel(r"Contact pressure $p/p_{avg}$")
    axes.legend(loc="lower left")
    return _save(figure, path)


# --- 3, 4. impact histories (the paper's Figs. 3 and 4) --------------------------------------

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
) -> Path:
    """Two normalised histories per variant, and their difference from the exact solution."""
    if not 0 < len(histories) <= len(VARIANT_STYLES):
        raise ValueError(f"histories must hold 1 to {len(VARIANT_STYLES)} ImpactHistory objects")
    figure = Figure(figsize=(WIDTH, 5.0), layout="constrained")
    top, bottom = figure.subplots(2, 1, sharex=True, height_ratios=(3, 1.3))
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
    return _save(figure, path)


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


@_styled
def plot_impact_motion(
    histories: Mapping[str, ImpactHistory], reference: ImpactResult, path: Path | str
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
    path : path-like
        PNG to write (1280 x 1000 pixels).

    Returns
    -------
    pathlib.Path
        ``path``.
    """
    return _impact_figure(histories, reference, path, _MOTION)


@_styled
def plot_impact_contact(
    histories: Mapping[str, ImpactHistory], reference: ImpactResult, path: Path | str
) -> Path:
    """Write the paper's Fig. 4: a(t)/a_c and p(0,t)/p_c against t/t_c, variants overlaid.

    Parameters are those of :func:`plot_impact_motion`; normalised by the exact a_c (m) and
    p_c (Pa).

    Returns
    -------
    pathlib.Path
        ``path``.
    """
    return _impact_figure(histories, reference, path, _CONTACT)


# --- 5. Ateb functions against the paper's tables --------------------------------------------


def _ateb_column(top: Axes, bottom: Axes, kind: str) -> None:
    """One function: exact curve, printed table, approximation; its relative error below."""
    integral = duration_integral(5.0 / 3.0)
    s = np.linspace(0.0, integral, 2001)
    if kind == "sine":
        exact = ateb_sine(5.0 / 3.0, 1.0, 4.0 / 3.0 * s)
        approximation, table, name = paper_sine_approximation(s), printed_table("table1"), "eta"
        symbol, label, number = r"\eta", r"$Sa(5/3, 1, 4\eta/3)$", "Table 1"
    else:
        exact = ateb_cosine(5.0 / 3.0, 1.0, 4.0 / 3.0 * s)
        approximation, table, name = paper_cosine_approximation(s), printed_table("table2"), "zeta"
        symbol, label, number = r"\zeta", r"$Ca(5/3, 1, 4\zeta/3)$", "Table 2"
    top.plot(s, exact, color=EXACT_COLOUR, label="exact")
    top.plot(s, approximation, "--", color=APPROXIMATION_COLOUR, label="paper's approximation")
    top.plot(
        table[name],
        table[kind],
        "o",
        color=PAPER_COLOUR,
        markersize=4,
        markerfacecolor="none",
        label=f"paper's {number}",
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


@_styled
def plot_ateb(path: Path | str) -> Path:
    """Write Sa(5/3, 1, 4 eta/3) and Ca(5/3, 1, 4 zeta/3) against the paper's Tables 1-2.

    Top: the exact functions (:mod:`shtaerman.ateb`), the printed table values (markers) and
    the paper's piecewise approximations (dashed), over one compression (eta) and one
    restitution (zeta) interval [0, I], I = 1.445927. Bottom: the approximations' relative
    error in %, its maximum marked, against the paper's claimed 1 % (dotted).

    Parameters
    ----------
    path : path-like
        PNG to write (1480 x 1000 pixels).

    Returns
    -------
    pathlib.Path
        ``path``.
    """
    figure = Figure(figsize=(7.4, 5.0), layout="constrained")
    axes = figure.subplots(2, 2, sharex=True, height_ratios=(2.2, 1))
    _ateb_column(axes[0, 0], axes[1, 0], "sine")
    _ateb_column(axes[0, 1], axes[1, 1], "cosine")
    axes[1, 0].set_ylabel("Approximation\nerror (%)")
    return _save(figure, path)


# --- 6. mesh convergence ---------------------------------------------------------------------


def _order_note(study: ConvergenceStudy, key: str) -> str:
    """ " (order p)" with p the study's fitted order of ``key``, or ""."""
    order = study.orders.get(key, math.nan)
    return f" (order {order:.2f})" if math.isfinite(order) else ""


@_styled
def plot_convergence(
    study: ConvergenceStudy, path: Path | str, keys: Sequence[str] = CONVERGENCE_KEYS
) -> Path:
    """Write the relative errors against the number of unknowns (log-log), one line per error.

    Parameters
    ----------
    study : shtaerman.study.convergence.ConvergenceStudy
        Its levels ``{"size": h/R, "dofs": int, "errors": {"force": .., ...}}`` (relative
        errors, dimensionless; non-positive ones are not drawn) and fitted orders.
    path : path-like
        PNG to write (1280 x 840 pixels).
    keys : sequence of str
        The errors to draw (those missing from the levels are skipped). The legend gives each
        one's observed order p, error ~ h^p, fitted over all meshes against the element size.

    Returns
    -------
    pathlib.Path
        ``path``.
    """
    rows = study.levels
    figure = Figure(figsize=(WIDTH, 4.2), layout="constrained")
    axes = figure.subplots()
    dofs = np.array([row["dofs"] for row in rows], dtype=float)
    present = [key for key in keys if all(key in row["errors"] for row in rows)]
    for index, key in enumerate(present):
        error = np.array([row["errors"][key] for row in rows], dtype=float)
        shown = np.isfinite(error) & (error > 0)
        axes.loglog(
            dofs[shown],
            error[shown],
            marker="osD^vP"[index % 6],
            color=f"C{index}",
            label=ERROR_LABELS.get(key, key) + _order_note(study, key),
        )
    axes.set_xlabel("Unknowns (degrees of freedom)")
    axes.set_ylabel("Relative error")
    axes.legend(loc="best", title=r"observed order $p$: error $\propto h^p$")
    return _save(figure, path)


# --- the figures of a verification run -------------------------------------------------------


def study_figures(outcome: StudyOutcome, folder: Path | str) -> dict[str, Path]:
    """The curve figures of one study, written into ``folder``.

    ``force_depth.png`` and ``pressure.png`` (:func:`plot_force_depth`, :func:`plot_pressure`),
    ``impact_motion.png`` and ``impact_contact.png`` (the paper's Figs. 3 and 4, every impact
    variant of the study against its exact impact).

    Parameters
    ----------
    outcome : shtaerman.verification.StudyOutcome
        The study: its ``contact``, ``histories`` and ``exact`` are drawn.
    folder : path-like
        Where the PNGs go (created if missing).

    Returns
    -------
    dict of str to pathlib.Path
        Caption to PNG path.
    """
    folder = Path(folder)
    contact, histories, exact = outcome.contact, outcome.histories, outcome.exact
    return {
        "Force against depth: FEM and Shtaerman's P = βx^q": plot_force_depth(
            contact, folder / "force_depth.png"
        ),
        "Contact pressure p(r)/p_avg: FEM nodal values and the exact profile": plot_pressure(
            contact, folder / "pressure.png"
        ),
        "Impact: approach x/x_c and force P/P_c against t/t_c (the paper's Fig. 3)": (
            plot_impact_motion(histories, exact, folder / "impact_motion.png")
        ),
        "Impact: contact radius a/a_c and central pressure p(0,t)/p_c (the paper's Fig. 4)": (
            plot_impact_contact(histories, exact, folder / "impact_contact.png")
        ),
    }


def paper_figures(folder: Path | str) -> dict[str, Path]:
    """The figures that depend on no study, written into ``folder``: ``ateb.png``.

    Parameters
    ----------
    folder : path-like
        Where the PNG goes (created if missing).

    Returns
    -------
    dict of str to pathlib.Path
        Caption to PNG path.
    """
    caption = "Ateb functions of the impact against the paper's Tables 1-2 and approximations"
    return {caption: plot_ateb(Path(folder) / "ateb.png")}
