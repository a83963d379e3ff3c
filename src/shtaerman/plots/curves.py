"""Contact curves: force against depth, the pressure profile, and mesh convergence.

Each function draws FEM results against Shtaerman's exact solution (see :mod:`.style` for the
colours and the conventions every figure follows).
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from pathlib import Path

import numpy as np
from matplotlib.axes import Axes
from matplotlib.ticker import NullLocator

from ..study.contact.convergence import ConvergenceStudy
from ..study.contact.indentation import IndentationResult
from ..theory.contact import paper_pressure_eq5
from ..theory.viscoelastic import RateContact
from .labels import LABELS, describe
from .style import (
    DEPTH_STYLES,
    EXACT_COLOUR,
    FEM_COLOUR,
    chart,
    fraction,
    percent,
    plain_log,
    save,
    sci,
    si_prefix,
    styled,
)

__all__ = [
    "CONVERGENCE_KEYS",
    "ERROR_LABELS",
    "plot_convergence",
    "plot_force_depth",
    "plot_pressure",
]

ERROR_LABELS = {
    **{
        key: describe(key).text
        for key in ("force", "beta", "contact_radius", "central_pressure", "pressure_profile")
    },
    "exponent": LABELS["exponent_fem"].text,
}
"""Legend text of each relative error of a convergence study (from :mod:`.labels`)."""
CONVERGENCE_KEYS = ("force", "beta", "contact_radius", "central_pressure")
"""Errors drawn by default by :func:`plot_convergence`."""


# --- force against depth -----------------------------------------------------------------------


def _exact_name(result: IndentationResult) -> str:
    """Whose exact solution: Shtaerman's (the power law), Sneddon's (another profile) or Lee
    and Radok's (a viscoelastic body pressed at a rate)."""
    if isinstance(result.exact, RateContact):
        return "Lee-Radok"
    return "Shtaerman" if result.indenter.kind == "power-law" else "Sneddon"


def _fit_note(result: IndentationResult) -> str:
    fit, analytic = result.fit, result.analytic
    q_exact, beta_exact = analytic.exponent, analytic.beta
    q_text = fraction(result.exact.force_exponent)
    power_law = _exact_name(result) == "Shtaerman"  # else: the exact curve fitted alike
    exact_words = f"exact {q_text}" if power_law else "exact curve's fit"
    free = (
        rf"FEM, free fit: $q$ = {fit.exponent:.5f} ({exact_words} = {q_exact:.5f}, "
        f"{percent(fit.exponent / q_exact - 1)})"
        if math.isfinite(fit.exponent)
        else r"FEM, free fit: $q$ fitted only from $\geq$ 2 depths"
    )
    return "\n".join(
        [
            free,
            rf"FEM, $q$ = {q_text}: $\beta$ = ${sci(fit.beta_fixed_exponent)}$ "
            rf"N m$^{{-{q_text}}}$ (exact ${sci(beta_exact)}$, "
            f"{percent(fit.beta_fixed_exponent / beta_exact - 1)})",
        ]
    )


def _fem_label(result: IndentationResult) -> str:
    """ "FEM", or "FEM, neo-Hookean" (the rubber model) for a finite-strain curve."""
    rubber = getattr(result, "rubber", None)
    if rubber is None:
        return "FEM"
    from .labels import model_label

    return f"FEM, {model_label(rubber.name)}"


@styled
def plot_force_depth(
    result: IndentationResult, path: Path | str, *, figure_format: str = "png"
) -> Path:
    """Write the force-depth curve: FEM points against P = beta x^q (log-log); a finite-strain
    curve (:class:`~shtaerman.study.finite.indentation.FiniteIndentationResult`) too.

    The lower panel is the relative difference of each FEM force from the exact one (%);
    the fitted exponent and beta (exponent held at the theory's) are printed against the
    exact values.

    Parameters
    ----------
    result : IndentationResult
        The FEM indentation run (depths in m, forces in N).
    path, figure_format
        The PNG (1280 x 960 pixels) and the formats, as every chart (:mod:`.style`).
    """
    depths = np.array([step.depth for step in result.steps])
    forces = np.array([step.force for step in result.steps])
    x_scale, x_unit = si_prefix(math.sqrt(depths.min() * depths.max()), "m")
    p_scale, p_unit = si_prefix(math.sqrt(forces.min() * forces.max()), "N")
    figure, (top, bottom) = chart(4.8, 2, 1, sharex=True, height_ratios=(3, 1))
    line = np.geomspace(depths.min() / 1.25, depths.max() * 1.25, 200)
    q = fraction(result.exact.force_exponent)
    top.loglog(
        line * x_scale,
        result.exact.force(line) * p_scale,
        color=EXACT_COLOUR,
        label=rf"Shtaerman: $P = \beta x^{{{q}}}$"
        if _exact_name(result) == "Shtaerman"
        else _exact_name(result),
    )
    top.loglog(depths * x_scale, forces * p_scale, "o", color=FEM_COLOUR, label=_fem_label(result))
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
        plain_log(axes.xaxis)
    plain_log(top.yaxis)
    return save(figure, path, figure_format)


# --- pressure profile ---------------------------------------------------------------------------


def _paper_profile(result: IndentationResult) -> bool:
    """Whether the exact pressure is Shtaerman's for n = 3/2, the paper's eq. (5)."""
    return _exact_name(result) == "Shtaerman" and result.indenter.exponent == 1.5


def _exact_profile(result: IndentationResult, depth: float, rho: np.ndarray) -> np.ndarray:
    """p/p_avg at r/a = rho: the paper's eq. (5) for Shtaerman's n = 3/2, else the exact
    solution's own profile."""
    exact, a = result.exact, float(result.exact.contact_radius(depth))
    mean = float(exact.mean_pressure(depth))
    if not _paper_profile(result):
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


@styled
def plot_pressure(
    result: IndentationResult,
    path: Path | str,
    steps: Sequence[int] | None = None,
    *,
    figure_format: str = "png",
) -> Path:
    """Write the contact pressure p(r)/p_avg against r/a: FEM nodal values and the exact curve.

    FEM pressures are normalised by the exact contact radius a and mean pressure P/(pi a^2) at
    the same depth, so differences are errors, not rescalings. For n = 3/2 the exact curve is
    the paper's eq. (5); the central value (n+1)/(2(n-1)) (2.5 for n = 3/2) is marked.

    Parameters
    ----------
    result : IndentationResult
        The FEM indentation run (pressure recovered at the surface nodes, Pa).
    path, figure_format
        The PNG (1280 x 840 pixels) and the formats, as every chart (:mod:`.style`).
    steps : sequence of int, optional
        Indices of ``result.steps`` to show (up to three); default the largest, a middle and
        the smallest depth.
    """
    figure, axes = chart(4.2)
    rho = np.linspace(0.0, 1.3, 521)
    deepest = result.steps[-1].depth
    label = "paper's eq. (5)" if _paper_profile(result) else "exact"
    if _exact_name(result) != "Shtaerman":  # p/p_avg depends on depth: the deepest's
        label = f"exact at x = {deepest * 1e3:.3g} mm"
    profile = _exact_profile(result, deepest, rho)
    axes.plot(rho, profile, color=EXACT_COLOUR, label=f"{_exact_name(result)}, {label}")
    centre = []
    for index, style in zip(_pressure_steps(result, steps), DEPTH_STYLES, strict=False):
        centre.append(_pressure_markers(axes, result, index, style))
    ratio = result.exact.central_to_mean_ratio
    if not math.isfinite(ratio):  # another profile: the deepest depth's
        ratio = float(profile[0])
    axes.axhline(ratio, color="0.4", linestyle=":", linewidth=1.0)
    note = r"$p(0)/p_{avg}$" + f"\nexact {ratio:g}\nFEM {min(centre):.3f} to {max(centre):.3f}"
    axes.text(1.02, 0.97 * ratio, note, ha="left", va="top", fontsize=8.5)
    axes.axvline(1.0, color="0.4", linestyle=":", linewidth=1.0)
    axes.set_xlim(0.0, 1.3)
    axes.set_ylim(0.0, 1.08 * max(ratio, *centre))
    axes.set_xlabel("Radius $r/a$")
    axes.set_ylabel(r"Contact pressure $p/p_{avg}$")
    axes.legend(loc="lower left")
    return save(figure, path, figure_format)


# --- mesh convergence -----------------------------------------------------------------------------


def _order_note(study: ConvergenceStudy, key: str) -> str:
    """ " (order p)" with p the study's fitted order of ``key``, or ""."""
    order = study.orders.get(key, math.nan)
    return f" (order {order:.2f})" if math.isfinite(order) else ""


@styled
def plot_convergence(
    study: ConvergenceStudy,
    path: Path | str,
    keys: Sequence[str] = CONVERGENCE_KEYS,
    *,
    figure_format: str = "png",
) -> Path:
    """Write the relative errors (%) against the element size h (log-log), one line per error.

    Parameters
    ----------
    study : shtaerman.study.contact.convergence.ConvergenceStudy
        Its levels ``{"size": h, "dofs": int, "errors": {"force": .., ...}}`` (h the
        smallest element size / the refined zone's radius; relative errors, dimensionless;
        non-positive ones are not drawn) and fitted orders.
    path, figure_format
        The PNG (1280 x 960 pixels) and the formats, as every chart (:mod:`.style`).
    keys : sequence of str
        The errors to draw (those missing from the levels are skipped). The legend gives each
        one's observed order p, error ~ h^p, fitted over all meshes against the element size
        of the horizontal axis; each mesh's number of unknowns is marked on the top axis.
    """
    rows = study.levels
    figure, axes = chart(4.8)
    size = np.array([row["size"] for row in rows], dtype=float)
    present = [key for key in keys if all(key in row["errors"] for row in rows)]
    for index, key in enumerate(present):
        error = np.array([row["errors"][key] for row in rows], dtype=float)
        shown = np.isfinite(error) & (error > 0)
        axes.loglog(
            size[shown],
            100 * error[shown],
            marker="osD^vP"[index % 6],
            color=f"C{index}",
            label=ERROR_LABELS.get(key, key) + _order_note(study, key),
        )
    dofs = axes.secondary_xaxis("top")
    dofs.set_xticks(size, [f"{row['dofs']:,}" for row in rows], fontsize=7.5)
    dofs.xaxis.set_minor_locator(NullLocator())
    dofs.set_xlabel("Unknowns (degrees of freedom) of each mesh", fontsize=9)
    axes.set_xticks(size, [f"{h:.3g}" for h in size])
    axes.xaxis.set_minor_locator(NullLocator())
    axes.set_xlabel("Element size on the refined zone $h$ / its radius")
    axes.set_ylabel("Relative error (%)")
    plain_log(axes.yaxis)
    figure.legend(
        loc="outside lower center", ncols=2, title=r"observed order $p$: error $\propto h^p$"
    )
    return save(figure, path, figure_format)
