"""Figures of a finished sweep, drawn from its ``results.json`` only.

One PNG (200 dpi) per output, and an SVG or PDF beside it if asked: a curve over the axis for
a 1-axis sweep, a heat map (values written in the cells) for a 2-axis sweep. Failed cases are
gaps (curves) or grey cells (heat maps). Sweeps over 3 or more axes get no figures
(``results.json`` and ``cases.csv`` hold everything). Titles and axes are the quantities'
readable labels (:mod:`shtaerman.plots.labels`); fractions are shown in per cent. The figures
use :class:`matplotlib.figure.Figure` with the Agg canvas: no pyplot state, no display.

A relative difference with levels (the kind's ``levels``, e.g. 1 % and 5 %) and an estimated
error (the output ``error_<name>``) shows value ± error (error bars, or in the cells), and its
heat map draws |value| = level as a contour only between cells whose error resolves the level
(:func:`shtaerman.study.limits.resolved`: below a fifth of it), as the dynamic study states its
limits. A value whose error is not below its own size is unresolved: an open marker on a curve,
a hatched cell without a colour on a heat map.
"""

from __future__ import annotations

import json
import math
import os
import tempfile
from collections.abc import Callable, Iterable
from pathlib import Path
from typing import Any

import matplotlib as mpl
import numpy as np
from matplotlib.colors import ListedColormap
from matplotlib.figure import Figure
from matplotlib.patches import Rectangle

from ..plots.formats import check_figure_format
from ..plots.labels import LABELS, axis_label, describe
from ..plots.labels import scale as shown_scale
from ..plots.style import points, save, si_prefix, unresolved
from ..study.limits import RESOLUTION, resolved

__all__ = ["draw_figures", "figure_files", "kept_figures", "sweep_figures"]


def _numeric(values: list[Any]) -> bool:
    return all(isinstance(v, int | float) and not isinstance(v, bool) for v in values)


def _positions(values: list[Any]) -> tuple[np.ndarray, list[str] | None, bool]:
    """Plot positions of axis values, tick labels for non-numbers, and whether to use log."""
    if _numeric(values):
        x = np.asarray(values, dtype=float)
        log = bool(np.all(x > 0) and x.max() / x.min() >= 20.0)
        return x, None, log
    return np.arange(len(values), dtype=float), [str(v) for v in values], False


def _output_values(cases: list[dict], name: str) -> np.ndarray:
    values = []
    for case in cases:
        value = case.get("outputs", {}).get(name) if case.get("status") == "ok" else None
        values.append(float(value) if isinstance(value, int | float) else math.nan)
    return np.asarray(values, dtype=float)


def _refused(cases: list[dict]) -> np.ndarray:
    """Which cases were refused (beyond a validity limit of the model, not run)."""
    return np.array([case.get("status") == "refused" for case in cases], dtype=bool)


def _categorical(results: dict, name: str, values: np.ndarray) -> tuple[list | None, np.ndarray]:
    """The names of a categorical output that its cases take (an effects sweep's
    ``dominant_<q>``: the effects of the case that dominate somewhere, not the five an effect
    table knows), and ``values`` as positions among them (NaN kept); (None, ``values``): not
    categorical; every name when no case ran)."""
    names = results["kind"].get("categories", {}).get(name)
    taken = sorted({int(value) for value in values[np.isfinite(values)]})
    if names is None or not taken:
        return names, values
    position = {index: place for place, index in enumerate(taken)}
    at = [position[int(value)] if math.isfinite(value) else math.nan for value in values]
    return [names[index] for index in taken], np.asarray(at, dtype=float)


def _errors(results: dict, name: str) -> np.ndarray | None:
    """The estimated absolute errors of a difference with levels, if the sweep has them."""
    key = f"error_{name}"
    if name not in results["kind"].get("levels", {}) or key not in results["kind"]["outputs"]:
        return None
    return _output_values(results["cases"], key)


def _contours(ax: Any, grid: np.ndarray, errors: np.ndarray, levels: list[float]) -> None:
    """|grid| = level for each level, through resolved cells only (needs a 2 x 2 grid)."""
    if min(grid.shape) < 2:
        return
    size = np.abs(grid)
    rows, cols = np.arange(grid.shape[0]), np.arange(grid.shape[1])
    for level, style in zip(levels, (":", "--", "-"), strict=False):
        ok = np.vectorize(lambda e, level=level: math.isfinite(e) and resolved(e, level))(errors)
        masked = np.ma.masked_where(~ok | ~np.isfinite(size), size)
        if masked.count() and masked.min() < level < masked.max():
            drawn = ax.contour(cols, rows, masked, levels=[level], colors="red", linestyles=style)
            ax.clabel(drawn, fmt={level: f"{100 * level:g} %"}, fontsize=8)


PREFIXED = ("m", "s", "N", "Pa")
"""SI units shown with a prefix that puts the values in [1, 1000) (mm, ms, kN, MPa)."""


def _display(name: str, unit: str, values: Any) -> tuple[float, str]:
    """Factor from stored to shown values of ``name`` and their axis label: per cent for a
    fraction, a prefixed SI unit for a length, time, force or stress, else as stored."""
    label = describe(name)
    if label.percent:
        return shown_scale(name), axis_label(name)
    unit = label.unit if name in LABELS else unit
    size = np.abs(np.asarray(values, dtype=float))
    size = size[np.isfinite(size) & (size > 0)]
    if unit not in PREFIXED or not size.size:
        return 1.0, axis_label(name, unit)
    factor, prefixed = si_prefix(float(np.median(size)), unit)
    return factor, f"{label.text} ({prefixed})"


def _value_text(value: float, name: str, factor: float) -> str:
    return f"{factor * value:.3g}" + (" %" if describe(name).percent else "")


def _title(results: dict, name: str) -> str:
    spec = results["spec"]
    return f"{describe(name).text}\n{spec['name']} sweep ({spec['kind']})"


def _curve(results: dict, name: str, unit: str, folder: Path, figure_format: str) -> Path:
    spec = results["spec"]
    [(axis, values)] = spec["axes"].items()
    axis_unit = results["kind"]["parameter_units"].get(axis, "")
    x, ticks, log = _positions(values)
    x_factor, x_label = _display(axis, axis_unit, x if ticks is None else [])
    x = x_factor * x
    names, raw = _categorical(results, name, _output_values(results["cases"], name))
    errors = _errors(results, name)
    factor, y_label = _display(name, unit, raw)
    y, open_ = factor * raw, np.isfinite(raw) & unresolved(raw, errors)
    figure = Figure(figsize=(6.0, 4.0), layout="constrained")
    ax = figure.add_subplot()
    bars = None if errors is None else factor * errors
    line = "-" if names is None else "none"  # no line between categories
    points(ax, x, y, ("C0", "o", line, "_nolegend_"), error=bars, hidden=open_)
    if open_.any():
        ax.lines[-1].set_label("unresolved: estimated error ≥ |value|")
        ax.legend(loc="best", fontsize=8)
    refused = _refused(results["cases"])
    for position in x[~np.isfinite(y) & ~refused]:  # failed
        ax.axvline(position, color="0.6", linestyle=":", linewidth=1.0)
    for number, position in enumerate(x[refused]):
        label = "refused: outside the model's validity" if number == 0 else "_nolegend_"
        ax.axvline(position, color="0.6", linestyle="--", linewidth=1.0, label=label)
    if refused.any():
        ax.legend(loc="best", fontsize=8)
    if log:
        ax.set_xscale("log")
    if ticks is not None:
        ax.set_xticks(x, ticks)
    if names is not None:
        ax.set_yticks(range(len(names)), names)
        ax.set_ylim(-0.5, len(names) - 0.5)
    elif np.all(y[np.isfinite(y)] > 0) and np.isfinite(y).sum() > 1:
        finite = y[np.isfinite(y)]
        if finite.max() / finite.min() >= 100.0:
            ax.set_yscale("log")
    ax.set_xlabel(x_label)
    ax.set_ylabel(y_label)
    ax.set_title(_title(results, name), fontsize=9)
    ax.grid(True, alpha=0.3)
    return save(figure, folder / f"{name}.png", figure_format)


def _heat_map(results: dict, name: str, unit: str, folder: Path, figure_format: str) -> Path:
    spec = results["spec"]
    (row_axis, rows), (col_axis, cols) = spec["axes"].items()
    units = results["kind"]["parameter_units"]
    names, values = _categorical(results, name, _output_values(results["cases"], name))
    grid = values.reshape(len(rows), len(cols))
    errors = _errors(results, name)
    errors = None if errors is None else errors.reshape(grid.shape)
    open_ = np.isfinite(grid) & unresolved(grid, errors)
    figure = Figure(figsize=(1.2 * len(cols) + 3.0, 0.6 * len(rows) + 2.8), layout="constrained")
    ax = figure.add_subplot()
    factor, label = _display(name, unit, grid)
    masked = np.ma.masked_where(~np.isfinite(grid) | open_, factor * grid)
    if names is None:
        cmap = mpl.colormaps["viridis"].with_extremes(bad="0.8")
        image = ax.imshow(masked, cmap=cmap, aspect="auto", origin="lower")
        figure.colorbar(image, ax=ax, label=label)
    else:  # a colour per name, the name in its cells
        cmap = ListedColormap(mpl.colormaps["tab10"].colors[: len(names)], "categories")
        ax.imshow(masked, cmap=cmap.with_extremes(bad="0.8"), aspect="auto", origin="lower",
                  vmin=-0.5, vmax=len(names) - 0.5)  # fmt: skip
    for axis, values, set_ticks, set_label in (
        (col_axis, cols, ax.set_xticks, ax.set_xlabel),
        (row_axis, rows, ax.set_yticks, ax.set_ylabel),
    ):
        scale, text = _display(axis, units.get(axis, ""), values if _numeric(values) else [])
        ticks = [f"{scale * v:g}" if _numeric([v]) else str(v) for v in values]
        set_ticks(range(len(values)), ticks)
        set_label(text)
    refused = _refused(results["cases"]).reshape(grid.shape)
    _cell_texts(ax, masked, (grid, errors, factor), name, names, refused)
    for i, j in zip(*np.nonzero(open_), strict=True):
        ax.add_patch(
            Rectangle((j - 0.5, i - 0.5), 1, 1, facecolor="white", edgecolor="0.55", hatch="///")
        )
    note = _levels_note(results, name, errors)
    ax.set_title(_title(results, name) + note, fontsize=9)
    if errors is not None:
        _contours(ax, grid, errors, results["kind"]["levels"][name])
    return save(figure, folder / f"{name}.png", figure_format)


def _cell_texts(
    ax: Any,
    masked: np.ma.MaskedArray,
    stored: tuple,
    name: str,
    names: list | None = None,
    refused: np.ndarray | None = None,
) -> None:
    """Each cell's value (± its estimated error), or the name it indexes in ``names``,
    "failed", "refused" (where ``refused``: beyond a validity limit, not run), or
    "unresolved" and its error; ``stored`` = (values, errors or None, factor to the shown
    unit)."""
    grid, errors, factor = stored
    finite = masked.compressed()
    middle = 0.5 * (finite.min() + finite.max()) if finite.size else 0.0
    middle = math.inf if names else middle  # names: white on every colour
    hidden = np.ma.getmaskarray(masked)
    for (i, j), value in np.ndenumerate(grid):
        text = "failed" if not math.isfinite(value) else _value_text(value, name, factor)
        if refused is not None and refused[i, j]:
            text = "refused"
        if names and math.isfinite(value):
            text = names[int(value)]
        if errors is not None and math.isfinite(value):
            error = f"± {factor * errors[i, j]:.1g}" + (" %" if factor != 1.0 else "")
            text = f"unresolved\n{error}" if hidden[i, j] else f"{text}\n{error}"
        dark = hidden[i, j] or factor * value > middle
        box = {"facecolor": "white", "edgecolor": "none", "pad": 1} if hidden[i, j] else None
        ax.text(
            j, i, text, ha="center", va="center", fontsize=8,
            color="black" if dark else "white", bbox=box, zorder=3,
        )  # fmt: skip


def _levels_note(results: dict, name: str, errors: np.ndarray | None) -> str:
    """The title's next lines for a difference with levels: what the contours mean."""
    levels = results["kind"].get("levels", {}).get(name)
    if not levels:
        return ""
    words = ", ".join(f"{100 * level:g} %" for level in levels)
    if errors is None:
        return f"\nno error estimates: no {words} contours"
    worst = np.nanmax(errors) if np.isfinite(errors).any() else math.nan
    return (
        f"\n± estimated error (worst {shown_scale(name) * worst:.1g} %); contours |value| = "
        f"{words}\nwhere the error < level / {RESOLUTION:g}; hatched: error ≥ |value|"
    )


def sweep_figures(
    results_file: str | Path,
    folder: str | Path,
    figure_format: str = "png",
    drawn: list[tuple[str, dict[str, bytes]]] | None = None,
) -> list[Path]:
    """Draw one figure per output of the sweep in ``results_file`` into ``folder``.

    Parameters
    ----------
    results_file : path
        A sweep's ``results.json``.
    folder : path
        Created if needed.
    figure_format : {"png", "svg", "pdf"}
        "svg" or "pdf" also writes each figure in that format beside its PNG.
    drawn : list, optional
        The figures already drawn (:func:`draw_figures`), written as they are.

    Returns
    -------
    list of Path
        The PNG files written (none for a sweep over 3 or more axes).
    """
    check_figure_format(figure_format)
    if drawn is None:
        drawn = draw_figures(json.loads(Path(results_file).read_text()), figure_format)
    folder = Path(folder)
    if drawn:
        folder.mkdir(parents=True, exist_ok=True)
    for _, files in drawn:
        for name, data in files.items():
            _write_whole(folder / name, data)
    return [folder / f"{name}.png" for name, _ in drawn]


def _write_whole(path: Path, data: bytes) -> None:
    """``data`` into ``path`` through a temporary file beside it: an interrupted write leaves
    no part of a figure, which :func:`kept_figures` would take for the whole (a killed one a
    hidden file with the figure's suffix, which a sweep folder may hold)."""
    temporary = path.with_name(f".{path.stem}.{os.getpid()}.tmp{path.suffix}")
    try:
        temporary.write_bytes(data)
        os.replace(temporary, path)
    except BaseException:
        temporary.unlink(missing_ok=True)
        raise


def kept_figures(
    previous: str | None, results: str, folder: Path, figure_format: str = "png"
) -> list[Path] | None:
    """The figures already in ``folder`` if they were drawn from the same results: the text of
    the ``previous`` results.json equals the new ``results`` but for what no figure shows
    (:func:`_drawn`), and every file of every figure (:func:`draw_figures`; ``figure_format``
    beside each PNG) is a regular file there. None otherwise: draw them. A ``--resume`` that
    computed nothing keeps its figures instead of drawing them again."""
    try:
        old, new = json.loads(previous or "null"), json.loads(results)
    except ValueError:
        return None
    if not isinstance(old, dict) or _drawn(old) != _drawn(new):
        return None
    names = _figure_names(new)
    suffixes = {"png", figure_format}
    files = [folder / f"{name}.{suffix}" for name in names for suffix in sorted(suffixes)]
    if not all(path.is_file() and not path.is_symlink() for path in files):
        return None
    return [folder / f"{name}.png" for name in names]


def draw_figures(
    results: dict, figure_format: str = "png", mapper: Callable[..., Iterable[Any]] = map
) -> list[tuple[str, dict[str, bytes]]]:
    """(output, files of its figure) per output of a sweep's ``results`` (its results.json,
    read); none over 3 or more axes. ``mapper`` draws them, called as ``map(figure_files,
    ...)`` is: the sweep engine passes one that runs each figure as a task on its cluster."""
    names = _figure_names(results)
    units = [results["kind"]["outputs"][name] for name in names]
    count = len(names)
    drawn = mapper(figure_files, [results] * count, names, units, [figure_format] * count)
    return list(zip(names, drawn, strict=True))


def _drawn(results: dict) -> dict:
    """``results`` but for their ``timings`` and the sweep file's path, which no figure shows
    (the file may move: a resume names its new place)."""
    spec = results.get("spec")
    spec = {**spec, "file": None} if isinstance(spec, dict) else spec
    return {**results, "spec": spec, "timings": None}


def _figure_names(results: dict) -> list[str]:
    """The outputs of a sweep's ``results`` that have a figure (none over 3 or more axes)."""
    if len(results["spec"]["axes"]) not in (1, 2):
        return []
    return [name for name in results["kind"]["outputs"] if _drawable(results["cases"], name)]


def _drawable(cases: list[dict], name: str) -> bool:
    """Whether output ``name`` has a figure: a value in some case, or no case ran (the figure
    marks the failures); an output that no case which ran gave (an effects sweep's
    ``resolved_*`` without estimates) would draw an empty chart whose every case looks failed."""
    ran = any(case.get("status") == "ok" for case in cases)
    return not ran or bool(np.isfinite(_output_values(cases, name)).any())


def figure_files(results: dict, name: str, unit: str, figure_format: str) -> dict[str, bytes]:
    """The files of output ``name``'s figure, {file name: content}, drawn in a temporary
    folder (a worker that draws it need not share the result folder's disk)."""
    draw = _curve if len(results["spec"]["axes"]) == 1 else _heat_map
    with tempfile.TemporaryDirectory(prefix="shtaerman-figure-") as folder:
        draw(results, name, unit, Path(folder), figure_format)
        return {path.name: path.read_bytes() for path in sorted(Path(folder).iterdir())}
