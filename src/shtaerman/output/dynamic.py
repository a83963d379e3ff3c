"""Files and figures of a dynamic study (``verify``): CSV histories, a summary over v0, PNGs.

Into ``root/<study name>/``:

- ``history_v<v0>.csv`` per velocity: t, x, v, P, a, p0 of the dynamic FE impact every time
  step, units in the header (as ``shtaerman dynamic --history``);
- ``summary.csv``: one row per velocity, the dynamic and quasi-static maxima and times, their
  relative differences, restitution, the radiated fraction and its first-order estimate, and
  (a viscoelastic body) the dissipated energy and the split of 1 - e^2 into waves and
  hysteresis;
- figures: x(t), P(t), the force-depth loop and the energy account at the example velocity;
  e, 1 - e^2 and the differences over v0; the wave field (von Mises) at the quasi-static t_c
  and at 1.05 t_y (after separation).

:func:`write_case_figures` draws one impact's (``dynamic --out``): x(t), P(t), the force-depth
loop, the energy account and the wave field at each kept time.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

from ..plots.dynamic import plot_dynamic_histories, plot_dynamic_over_velocity, plot_wave_field
from ..plots.impact_energy import on_pad, plot_energy_history, plot_force_depth_loop
from ..study.dynamic.case import DynamicCase
from ..study.dynamic.runner import SEPARATION_SNAPSHOT, DynamicStudyOutcome
from .files import write_csv

__all__ = ["SUMMARY_HEADER", "write_case_figures", "write_dynamic_study"]

SUMMARY_HEADER = (
    "v0 [m/s]",
    "x_max [m]",
    "x_c [m]",
    "x_c/x_max-1 [1]",
    "P_max [N]",
    "P_c [N]",
    "P_c/P_max-1 [1]",
    "t_x_max [s]",
    "t_c [s]",
    "t_contact [s]",
    "t_y [s]",
    "t_y/t_contact-1 [1]",
    "v_out [m/s]",
    "restitution [1]",
    "energy_radiated_fraction [1]",
    "estimate_energy_fraction [1]",
    "energy_balance_error [1]",
    "reflected_energy_fraction [1]",
    "energy_dissipated_fraction [1]",
    "energy_wave_fraction [1]",
    "energy_hysteresis_fraction [1]",
)
"""Columns of summary.csv, one row per velocity, in the ``name [unit]`` convention; the last
three (the viscoelastic split of 1 - e^2, :attr:`ImpactRun.losses`) are NaN
for an elastic body."""

LOSS_KEYS = ("energy_dissipated_fraction", "energy_wave_fraction", "energy_hysteresis_fraction")


def _summary(outcome: DynamicStudyOutcome) -> dict[str, np.ndarray]:
    """summary.csv's columns (:data:`SUMMARY_HEADER`), one value per velocity."""
    rows = []
    for case in outcome.cases:
        q, d = case.quasi, case.differences()
        values = {
            **{"v0": case.velocity, "x_c": q.x_c, "P_c": q.P_c, "t_c": q.t_c, "t_y": q.t_y},
            **{"x_c/x_max-1": d["x"], "P_c/P_max-1": d["P"], "t_y/t_contact-1": d["t"]},
            "estimate_energy_fraction": case.estimate.energy_fraction,
            **dict.fromkeys(LOSS_KEYS, np.nan),
            **case.result.summary(),  # SUMMARY_KEYS and the losses the body has
        }
        rows.append([values[name.split(" [")[0]] for name in SUMMARY_HEADER])
    table = np.array(rows, dtype=float)
    return {name: table[:, i] for i, name in enumerate(SUMMARY_HEADER)}


def _impact_figures(case: DynamicCase, folder: Path, figure_format: str) -> dict[str, Path]:
    """x(t) and P(t) against the quasi-static impact, the force-depth loop and the energy
    account of one impact, every body's; ``{caption: path}``."""
    v0, fmt = f"{case.velocity:g} m/s", {"figure_format": figure_format}
    body = "pad" if on_pad(case.result) else "half-space"
    return {
        f"Dynamic FE impact against the quasi-static one at {v0}: x(t) and P(t)": (
            plot_dynamic_histories(case, folder / "dynamic_history.png", **fmt)
        ),
        f"Force-depth loop at {v0}: loading and unloading of the dynamic FE impact beside the "
        "quasi-static elastic law (the loop's area is the energy left in the body)": (
            plot_force_depth_loop(case, folder / "force_depth_loop.png", **fmt)
        ),
        f"Energy account at {v0} (fractions of M v0^2 / 2): striker, {body} stored, "
        "absorbed (waves), dissipated (hysteresis), numerical residue": (
            plot_energy_history(case, folder / "energy_history.png", **fmt)
        ),
    }


def _over_velocity_caption(outcome: DynamicStudyOutcome) -> str:
    """The caption of the figure over v0: on a pad, what the pad run measured in place of the
    half-space's first-order estimate."""
    layer = outcome.study.geometry
    if layer.thickness is None:
        loss = "energy left in the half-space (%) over v0 (first-order estimate dashed)"
    else:
        loss = (
            f"energy left in the {1e3 * layer.thickness:.3g} mm pad on its {layer.base} "
            "base (%) over v0, with what the pad run measured: the energy that came back "
            "near the contact after separation and the energy balance error, % of M v0^2 / 2 "
            "on a log scale (the half-space's first-order radiation estimate does not apply "
            "to a pad)"
        )
    return (
        f"Restitution and {loss}; quasi-static / dynamic - 1 of x, P and contact time (%), "
        "open markers where the estimated error is not below the difference"
    )


def write_dynamic_study(
    outcome: DynamicStudyOutcome, folder: Path, root: Path, figure_format: str = "png"
) -> tuple[dict[str, str], dict[str, str]]:
    """The study's CSV files and figures; ``{stem: path}``, ``{caption: path}`` from ``root``
    (``figure_format`` "svg" or "pdf": each chart also in that format beside its PNG)."""
    folder.mkdir()
    written = []
    for case in outcome.cases:
        path = folder / f"history_v{case.velocity:g}.csv"
        write_csv(path, case.result.history_columns())
        written.append(path)
    summary = folder / "summary.csv"
    write_csv(summary, _summary(outcome))
    written.append(summary)
    example = outcome.example
    quasi, result = example.quasi, example.result
    figures = _impact_figures(example, folder, figure_format)
    figures[_over_velocity_caption(outcome)] = plot_dynamic_over_velocity(
        outcome, folder / "dynamic_over_velocity.png", figure_format=figure_format
    )
    v0 = f"{example.velocity:g} m/s"
    late = SEPARATION_SNAPSHOT * quasi.t_y
    after = "after" if late > result.t_contact else "before"
    separation = f"at {SEPARATION_SNAPSHOT:g} t_y ({after} separation)"
    for key, words, stem in (
        (quasi.t_c, "at the quasi-static t_c (maximum compression)", "wave_field_tc"),
        (late, separation, "wave_field_separation"),
    ):
        if key in result.snapshots:  # a rubber keeps no linear wave fields
            figures[f"Wave field (von Mises) at {v0}, {words}"] = plot_wave_field(
                example, key, folder / f"{stem}.png"
            )
    return (
        {path.stem: str(path.relative_to(root)) for path in written},
        {caption: str(path.relative_to(root)) for caption, path in figures.items()},
    )


def write_case_figures(
    case: DynamicCase, folder: Path, figure_format: str = "png"
) -> dict[str, Path]:
    """One impact's figures in ``folder``, a linear body's or a rubber's: ``dynamic_history``
    (x(t), P(t) against the quasi-static impact), ``force_depth_loop``, ``energy_history``
    (with ``figure_format`` "svg" or "pdf" also in that format beside each PNG) and
    ``wave_field_<i>.png`` at each time the run kept (PNG only); ``{caption: path}``."""
    v0, figures = f"{case.velocity:g} m/s", _impact_figures(case, folder, figure_format)
    for index, key in enumerate(sorted(case.result.snapshots)):
        figures[f"Wave field (von Mises) at {v0}, t = {key * 1e3:.3g} ms"] = plot_wave_field(
            case, key, folder / f"wave_field_{index}.png"
        )
    return figures
