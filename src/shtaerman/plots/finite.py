"""Figures of a finite-strain study: the departure from Shtaerman, the deformed section, the impact.

- :func:`plot_finite_ratios`: P/(beta x^q) and p(0)/p_avg against x/a (linear a), the
  neo-Hookean FEM against the linear FEM on the same mesh and the exact linear values; depths
  where the mesh's error is not below the finite-strain effect are open markers without an
  error bar (unresolved);
- :func:`plot_finite_section`: von Mises stress on the deformed r-z section under the rigid
  indenter (pyvista, off-screen, drawn by :mod:`.sections`) at the computed depth nearest the
  finite-strain x_c;
- :func:`plot_finite_impact`: x(t) and P(t), the paper's linear impact against real rubber.

Only reads results (:class:`shtaerman.study.finite.runner.FiniteStudyOutcome`).
"""

from __future__ import annotations

from pathlib import Path
from types import SimpleNamespace
from typing import TYPE_CHECKING, Any

import numpy as np
from matplotlib.lines import Line2D

from .labels import model_label, variant_label
from .sections import plot_field
from .style import (
    EXACT_COLOUR,
    FEM_COLOUR,
    SECOND_COLOUR,
    chart,
    note,
    points,
    save,
    styled,
    unresolved,
)

if TYPE_CHECKING:
    from ..study.finite.runner import FiniteStudyOutcome

__all__ = [
    "FINITE_COLOUR",
    "nearest_step",
    "panel_points",
    "plot_finite_impact",
    "plot_finite_ratios",
    "plot_finite_section",
]

FINITE_COLOUR = SECOND_COLOUR
"""Finite strain (red); the linear FEM is blue, the exact linear solution black."""
IMPACT_STYLES = {
    "linear_exact": (EXACT_COLOUR, "-"),
    "linear_fem": (FEM_COLOUR, ":"),
    "finite_strain": (FINITE_COLOUR, "--"),
}
"""Impact variant -> (colour, line style); labelled as the tables label it."""


def nearest_step(outcome: FiniteStudyOutcome) -> int:
    """Index of the computed depth nearest the finite-strain x_c (in log depth)."""
    depths = np.array([step.depth for step in outcome.finite.steps])
    x_c = outcome.impacts["finite_strain"]["x_c"]
    return int(np.argmin(np.abs(np.log(depths / x_c))))


def _resolution(
    outcome: FiniteStudyOutcome, finite: np.ndarray, linear: np.ndarray, exact: np.ndarray, key: str
) -> tuple[np.ndarray, np.ndarray | None]:
    """Per depth: whether the finite-strain effect on ``key`` is unresolved, and the
    finite-strain value's estimated absolute error (None without a mesh ladder).

    The effect is |finite / linear FEM - 1| (same mesh: the discretisation error cancels to
    leading order); the mesh's error is the larger of the linear FEM's relative error against
    the exact value and the ladder's estimate of the finite-strain value. Unresolved: the error
    is not below the effect.
    """
    error = np.abs(linear / exact - 1)
    estimated = None
    if outcome.estimates is not None:
        relative = np.array([step[key].error for step in outcome.estimates.steps])
        estimated = relative * np.abs(finite)
        error = np.maximum(error, relative)
    return unresolved(finite / linear - 1, error), estimated


def panel_points(outcome: FiniteStudyOutcome, values: tuple, key: str) -> dict[str, Any]:
    """The points of a :func:`plot_finite_ratios` panel as drawn.

    Parameters
    ----------
    outcome : FiniteStudyOutcome
    values : tuple of array_like
        Per depth: the finite-strain, same-mesh linear FEM and exact linear values of ``key``.
    key : str
        A per-depth estimate key (``force_ratio``, ``central_to_mean``).

    Returns
    -------
    dict
        ``finite``, ``linear``, ``exact`` (arrays), ``unresolved`` (bool per depth: drawn as
        open markers without an error bar), ``error`` (the finite-strain error bar, absolute;
        NaN where none is drawn: unresolved or off the plotted scale; None without a ladder)
        and ``limits`` (the y-limits, or None).
    """
    finite, linear, exact = (np.asarray(v, dtype=float) for v in values)
    hidden, error = _resolution(outcome, finite, linear, exact, key)
    limits = _resolved_limits(np.concatenate([finite, linear, exact]), np.tile(hidden, 3))
    if error is not None:  # an unresolved point is no data: no error bar
        error = np.where(hidden, np.nan, error)
        if limits is not None:  # nor for a point off the plotted scale
            error = np.where((finite < limits[0]) | (finite > limits[1]), np.nan, error)
    return {"finite": finite, "linear": linear, "exact": exact, "unresolved": hidden,
            "error": error, "limits": limits}  # fmt: skip


def _panel(axes: Any, outcome: FiniteStudyOutcome, x: np.ndarray, values: tuple, key: str) -> None:
    """The rubber's and the linear FEM values of ``key`` over ``x``, unresolved ones open."""
    drawn = panel_points(outcome, values, key)
    finite, linear, exact = drawn["finite"], drawn["linear"], drawn["exact"]
    hidden, error, limits = drawn["unresolved"], drawn["error"], drawn["limits"]
    style = (FINITE_COLOUR, "o", "--", f"{model_label(outcome.study.rubber.name)} FEM")
    points(axes, x, finite, style, error=error, hidden=hidden)
    points(axes, x, linear, (FEM_COLOUR, "s", ":", "linear FEM, same mesh"), hidden=hidden)
    handles = [
        line
        for line in axes.get_lines()
        if not line.get_label().startswith("_") and not line.get_label().endswith("unresolved")
    ]
    if hidden.any():
        handles.append(
            Line2D([], [], color="0.3", marker="o", linestyle="none", markerfacecolor="white",
                   label="open, no bar: unresolved (mesh error ≥ finite-strain effect)")
        )  # fmt: skip
    axes.legend(handles=handles, loc="best", fontsize=7.5)
    _scale_to_resolved(axes, np.concatenate([finite, linear, exact]), np.tile(hidden, 3), limits)


def _resolved_limits(values: np.ndarray, hidden: np.ndarray) -> tuple[float, float] | None:
    """y-limits that fit the resolved values and the exact one, padded; None without any."""
    shown = values[~hidden & np.isfinite(values)]
    if not shown.size:
        return None
    low, high = float(shown.min()), float(shown.max())
    pad = 0.08 * max(high - low, 0.02 * abs(high))
    return low - pad, high + pad


def _scale_to_resolved(
    axes: Any, values: np.ndarray, hidden: np.ndarray, limits: tuple[float, float] | None
) -> None:
    """Set the y-limits (:func:`_resolved_limits`); an unresolved point beyond them is left
    out of the picture, with its error bar, and a note says how many."""
    if limits is None:
        return
    low, high = limits
    axes.set_ylim(low, high)
    off = int(np.sum(hidden & ((values < low) | (values > high))))
    if off:
        note(axes, f"{off} unresolved points off scale", 0.99)


@styled
def plot_finite_ratios(
    outcome: FiniteStudyOutcome, path: Path | str, *, figure_format: str = "png"
) -> Path:
    """P/(beta x^q) (top) and p(0)/p_avg (bottom) against x/a; the finite-strain x_c marked
    (PNG, and ``figure_format`` "svg" or "pdf" beside it).

    At a depth where the mesh's error is not below the finite-strain effect (see
    :func:`_resolution`) both FEM points are open markers: unresolved, not data.
    """
    rows = outcome.rows()
    ratio = np.array([row["depth_to_radius"] for row in rows])
    figure, (top, bottom) = chart(5.6, 2, 1, sharex=True)
    top.axhline(1.0, color=EXACT_COLOUR, linewidth=1.0, label="Shtaerman (linear, exact)")
    for level in (0.01, 0.05):
        top.axhspan(1 - level, 1 + level, color="0.5", alpha=0.08, linewidth=0)
    force = [r["force_ratio"] for r in rows]
    linear = [r["force_linear_fem"] / r["force_linear"] for r in rows]
    _panel(top, outcome, ratio, (force, linear, np.ones(len(rows))), "force_ratio")
    top.set_ylabel(r"$P\,/\,\beta x^{q}$")
    exact = outcome.finite.exact.central_to_mean_ratio
    bottom.axhline(exact, color=EXACT_COLOUR, linewidth=1.0, label=f"linear, exact {exact:.2f}")
    centre = [r["central_to_mean"] for r in rows]
    linear = [s.central_pressure * np.pi * s.contact_radius**2 / s.force for s in
              outcome.linear_fem.steps]  # fmt: skip
    _panel(bottom, outcome, ratio, (centre, linear, np.full(len(rows), exact)), "central_to_mean")
    bottom.set_ylabel(r"$p(0)\,/\,p_{avg}$")
    bottom.set_xlabel("Depth / linear contact radius  $x/a$")
    _mark_x_c(outcome, top, bottom)
    bottom.set_xlim(0.0, 1.02 * ratio.max())
    return save(figure, path, figure_format)


def _mark_x_c(outcome: FiniteStudyOutcome, top: Any, bottom: Any) -> None:
    at = outcome.at_maximum()["depth_to_radius"]
    for axes in (top, bottom):
        axes.axvline(at, color="0.4", linewidth=0.8, linestyle="-.")
    top.annotate(
        r"finite-strain $x_c$",
        (at, 1.0),
        xytext=(-4, 6),
        textcoords="offset points",
        ha="right",
        fontsize=8.5,
    )


@styled
def plot_finite_impact(
    outcome: FiniteStudyOutcome, path: Path | str, *, figure_format: str = "png"
) -> Path:
    """x(t) (top) and P(t) (bottom) in mm, N and ms: linear against finite strain, the study's
    rubber model named in the legend (PNG, and ``figure_format`` "svg" or "pdf" beside it)."""
    figure, (top, bottom) = chart(5.2, 2, 1, sharex=True)
    for variant, history in outcome.histories.items():
        colour, line = IMPACT_STYLES[variant]
        label = variant_label(outcome, variant)
        top.plot(history.t * 1e3, history.x * 1e3, line, color=colour, label=label)
        bottom.plot(history.t * 1e3, history.P, line, color=colour, label=label)
    top.set_ylabel("Approach x (mm)")
    bottom.set_ylabel("Force P (N)")
    bottom.set_xlabel("Time t (ms)")
    top.legend(loc="lower center")
    top.set_ylim(bottom=0.0)
    bottom.set_ylim(bottom=0.0)
    bottom.set_xlim(left=0.0)
    return save(figure, path, figure_format)


def plot_finite_section(outcome: FiniteStudyOutcome, path: Path | str) -> Path:
    """Von Mises on the deformed r-z section under the indenter, true scale, 2.5 contact radii
    wide, at the computed depth nearest the finite-strain x_c (PNG, 1600 x 1000)."""
    finite, curve = outcome.finite, outcome.finite.curve

    def fields(step: int) -> SimpleNamespace:  # shaped as :mod:`.sections` reads a result
        system = curve.system
        return SimpleNamespace(system=system, **system.fields(curve.steps[step].solution))

    deformed = SimpleNamespace(indenter=finite.indenter, steps=finite.steps, field=fields)
    step = nearest_step(outcome)
    return plot_field(deformed, path, "von_mises", step=step, extent=2.5, deformed=True)
