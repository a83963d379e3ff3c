"""Off-screen pyvista pictures of the FEM fields on the r-z section under the indenter (PNG).

The r-z section of the half-space (the body is z <= 0, the axis r = 0 on the left) is cut to a
window of a few contact radii around the contact, so the stress field there fills the picture
and not the 1e5-radius domain (a pad thinner than the window: the pad, :func:`body_frame`).
Lengths are shown in a prefixed metre unit (mm for the paper's example) with r and z rulers on
round ticks, fields coloured as :mod:`.fields` describes. The contact zone 0 <= r <= a is a
thick green line on the surface z = 0 (or, with ``deformed=True``, on the deformed surface under
the grey indenter z = f(r) - d). Pictures are made by :func:`shtaerman.plots.render.picture`
(off-screen, VTK warnings silenced).
"""

from __future__ import annotations

import math
from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from pathlib import Path

import numpy as np
import pyvista as pv
from vtkmodules.vtkRenderingCore import vtkBillboardTextActor3D

from ..fem.contact.linear import ContactStep
from ..fem.elasticity import ElasticSolution
from ..study.contact.indentation import IndentationResult
from ..validation import InputError, validate_positive
from .fields import FIELDS, add_coloured, check_field, decimals, isolines, nice_step, shown
from .render import FONT_SIZE, WINDOW_SIZE, picture, save, use_font
from .style import si_prefix

__all__ = [
    "CONTACT_COLOUR",
    "FIELDS",
    "WINDOW_SIZE",
    "Frame",
    "body_frame",
    "contact_step",
    "field_solution",
    "frame",
    "plot_each_field",
    "plot_field",
    "section",
    "segments",
]

CONTACT_COLOUR = "#2ca02c"
"""The contact zone (green: in neither colour map, unlike red for tension)."""
INDENTER_COLOUR = "black"
LEFT_MARGIN = 0.12
"""Fraction of the picture's width left of the section, for the z ruler."""
BAR_GAP = 0.08
"""Fraction of the picture's width between the section and the colour bar."""


def contact_step(result: IndentationResult, step: int) -> ContactStep:
    """``result.steps[step]``, or :class:`InputError` naming the valid indices."""
    try:
        return result.steps[step]
    except IndexError:
        raise InputError(f"step must index one of {len(result.steps)} depths, got {step}") from None


@dataclass(frozen=True)
class Frame:
    """The window shown, in display units: 0 <= r <= width, -depth <= z <= top."""

    scale: float
    """Display units per metre."""
    unit: str
    width: float
    depth: float
    top: float
    step: float
    """Tick spacing."""


def frame(contact_radius: float, extent: float, above: bool = False) -> Frame:
    """A window ``extent`` contact radii wide and 2/3 as deep, its edges on round ticks;
    ``above`` adds one tick above the surface (for the indenter)."""
    scale, unit = si_prefix(extent * contact_radius, "m")
    span = extent * contact_radius * scale
    step = nice_step(span, 6)
    width = step * math.ceil(span / step - 1e-9)
    depth = step * max(1, round(2 * width / (3 * step)))
    return Frame(scale, unit, width, depth, step if above else 0.0, step)


PAD_ASPECT = 2.0
"""Width / thickness of the window of a pad thinner than the usual window (:func:`body_frame`),
unless the contact zone needs more: a thin pad fills the picture's height instead of lying as a
strip along the top of a mostly white frame."""


def body_frame(window: Frame, depth: float, contact_radius: float) -> Frame:
    """``window`` fitted to a body ``depth`` (m) deep where that is shallower than the window
    (a pad on its rigid base): its whole thickness, and max(:data:`PAD_ASPECT` x ``depth``,
    2 ``contact_radius``) wide (m) on round ticks, at most ``window``'s width."""
    if depth * window.scale >= window.depth:
        return window
    span = min(window.width / window.scale, max(PAD_ASPECT * depth, 2 * contact_radius))
    scale, unit = si_prefix(span, "m")
    step = nice_step(span * scale, 6)
    width = step * math.ceil(span * scale / step - 1e-9)
    return Frame(scale, unit, width, depth * scale, window.top / window.scale * scale, step)


def section(solution: ElasticSolution, window: Frame, deformed: bool) -> pv.PolyData:
    """The r-z section as x = r, y = z (display units), cut to the window, fields attached."""
    mesh = solution.system.mesh
    r, z = mesh.p
    if deformed:
        r, z = r + solution.u_r, z + solution.u_z
    points = np.column_stack([r, z, np.zeros_like(r)]) * window.scale
    faces = np.column_stack([np.full(mesh.t.shape[1], 3), mesh.t.T]).ravel()
    cut = pv.PolyData(points, faces=faces)
    for name in FIELDS:
        cut.point_data[name] = np.asarray(getattr(solution, name), dtype=float)
    cut = cut.clip(normal=(1.0, 0.0, 0.0), origin=(window.width, 0.0, 0.0))
    return cut.clip(normal=(0.0, -1.0, 0.0), origin=(0.0, -window.depth, 0.0))


def field_solution(
    result: IndentationResult, names: Sequence[str], step: int, extent: float
) -> ElasticSolution:
    """Check the options before any drawing; the fields at the chosen depth."""
    for name in names:
        check_field(name)
    validate_positive("extent", extent)
    return result.field(step)


def polyline(r: np.ndarray, z: np.ndarray) -> pv.PolyData:
    """A line through the r-z points (m), just in front of the section."""
    return pv.lines_from_points(np.column_stack([r, z, np.full_like(r, 0.01)]))


def segments(lines: Sequence[tuple[Sequence[float], Sequence[float]]]) -> pv.PolyData:
    """Straight segments ((r0, r1), (z0, z1)) as one mesh, just in front of the section.

    One mesh draws as the segments drawn one by one (same colour and width), at a fraction of
    the cost of a mesh per segment.
    """
    r, z = (np.asarray([line[i] for line in lines], dtype=float).ravel() for i in (0, 1))
    ends = np.arange(r.size).reshape(-1, 2)
    cells = np.column_stack([np.full(len(ends), 2), ends]).ravel()
    return pv.PolyData(np.column_stack([r, z, np.full_like(r, 0.01)]), lines=cells)


def _indenter(result: IndentationResult, step: ContactStep, window: Frame) -> np.ndarray:
    """(r, z) in display units of the indenter profile z = f(r) - d, up to the window top."""
    r = np.linspace(0.0, window.width / window.scale, 400)
    z = (np.asarray(result.indenter.profile(r)) - step.depth) * window.scale
    return np.column_stack([r * window.scale, z])[z <= window.top]


def _draw_contact(
    plotter: pv.Plotter,
    result: IndentationResult,
    step: ContactStep,
    window: Frame,
    deformed: bool,
) -> None:
    """Contact zone 0 <= r <= a in green; with ``deformed``, the indenter in grey above it."""
    a = step.contact_radius * window.scale
    if not deformed:
        plotter.add_mesh(
            polyline(np.array([0.0, a]), np.zeros(2)), color=CONTACT_COLOUR, line_width=10
        )
        return
    profile = _indenter(result, step, window)
    body = np.vstack([profile, [[profile[-1, 0], window.top], [0.0, window.top]]])
    outline = np.column_stack([body, np.zeros(len(body))])
    solid = pv.PolyData(outline, faces=np.r_[len(body), np.arange(len(body))]).triangulate()
    plotter.add_mesh(solid, color="#d9d9d9", lighting=False)
    plotter.add_mesh(polyline(*profile.T), color=INDENTER_COLOUR, line_width=3)
    inside = profile[profile[:, 0] <= a]
    plotter.add_mesh(polyline(*inside.T), color=CONTACT_COLOUR, line_width=10)


def _draw_field(plotter: pv.Plotter, cut: pv.PolyData, name: str, bar: float) -> None:
    """The field in flat colours (no lighting: exactly the bar's), isolines and outline."""
    colours = shown(cut, name)
    add_coloured(plotter, cut, colours, bar, lighting=False)
    lines = isolines(cut, colours)
    if lines is not None:
        plotter.add_mesh(lines, color="black", line_width=1.2, opacity=0.45)
    outline = cut.extract_feature_edges(
        boundary_edges=True, feature_edges=False, manifold_edges=False, non_manifold_edges=False
    )
    plotter.add_mesh(outline, color="#4d4d4d", line_width=1.5)  # white near 0 needs an edge


def add_label(
    plotter: pv.Plotter,
    text: str,
    at: tuple[float, float],
    offset: tuple[int, int],
    align: tuple[int, int] = (1, 1),
    angle: float = 0.0,
) -> None:
    """Text of constant pixel size anchored at (r, z), shifted by ``offset`` pixels.

    ``align`` = (horizontal, vertical) justification, 0 left/bottom, 1 centred, 2 right/top.
    """
    actor = vtkBillboardTextActor3D()
    actor.SetInput(text)
    actor.SetPosition(at[0], at[1], 0.0)
    actor.SetDisplayOffset(*offset)
    prop = actor.GetTextProperty()
    use_font(prop)
    prop.SetFontSize(FONT_SIZE)
    prop.SetJustification(align[0])
    prop.SetVerticalJustification(align[1])
    prop.SetOrientation(angle)
    plotter.add_actor(actor, reset_camera=False)


def draw_axes(plotter: pv.Plotter, window: Frame) -> None:
    """r and z rulers on round ticks along the window's bottom and left edges."""
    tick, pad = 0.012 * (window.depth + window.top), FONT_SIZE // 2
    places = decimals(window.step)
    r_ticks = window.step * np.arange(round(window.width / window.step) + 1)
    z_ticks = window.top - window.step * np.arange(
        round((window.depth + window.top) / window.step) + 1
    )
    lines = [([0.0, window.width], [-window.depth] * 2), ([0.0, 0.0], [-window.depth, window.top])]
    lines += [([r, r], [-window.depth, -window.depth - tick]) for r in r_ticks]
    lines += [([0.0, -tick], [z, z]) for z in z_ticks]
    plotter.add_mesh(segments(lines), color="black", line_width=2, reset_camera=False)
    for r in r_ticks:
        add_label(plotter, f"{r:.{places}f}", (r, -window.depth - tick), (0, -pad), (1, 2))
    for z in z_ticks:
        add_label(plotter, f"{z + 0.0:.{places}f}", (-tick, z), (-pad, 0), (2, 1))
    add_label(
        plotter,
        f"r ({window.unit})",
        (0.5 * window.width, -window.depth),
        (0, -2 * FONT_SIZE - pad),
        (1, 2),
    )
    add_label(
        plotter,
        f"z ({window.unit})",
        (0.0, 0.5 * (window.top - window.depth)),
        (-3 * FONT_SIZE, 0),
        (1, 0),
        angle=90.0,
    )


def camera_2d(plotter: pv.Plotter, window: Frame) -> float:
    """Parallel view of the r-z plane, the window at the left; returns its right edge (0..1)."""
    aspect = WINDOW_SIZE[0] / WINDOW_SIZE[1]
    height = window.depth + window.top
    half = 0.5 * max(height / 0.78, window.width / (0.62 * aspect))
    centre = (
        half * aspect * (1.0 - 2 * LEFT_MARGIN),
        0.5 * (window.top - window.depth) - 0.05 * half,
    )
    plotter.enable_parallel_projection()
    plotter.camera.focal_point = (*centre, 0.0)
    plotter.camera.position = (*centre, 10.0 * half)
    plotter.camera.up = (0.0, 1.0, 0.0)
    plotter.camera.parallel_scale = half
    return LEFT_MARGIN + window.width / (2 * half * aspect)


def _window(result: IndentationResult, options: tuple[int, float, bool]) -> Frame:
    """The window of a field picture: ``extent`` contact radii at depth ``step``."""
    step, extent, deformed = options
    return frame(contact_step(result, step).contact_radius, extent, above=deformed)


def _panel(
    plotter: pv.Plotter,
    result: IndentationResult,
    cut: pv.PolyData,
    name: str,
    options: tuple[int, float, bool],
) -> None:
    """One field picture of the section ``cut`` into the plotter's current renderer.

    ``cut`` is left unchanged: the field is drawn from a shallow copy, so one section serves
    every field.
    """
    step, _, deformed = options
    window = _window(result, options)
    right = camera_2d(plotter, window)
    _draw_field(plotter, cut.copy(deep=False), name, right + BAR_GAP)
    _draw_contact(plotter, result, contact_step(result, step), window, deformed)
    draw_axes(plotter, window)


def _shared_section(
    result: IndentationResult, names: Sequence[str], options: tuple[int, float, bool]
) -> pv.PolyData:
    """The options checked, then the one section every field picture of them is drawn on."""
    step, extent, deformed = options
    solution = field_solution(result, names, step, extent)
    return section(solution, _window(result, options), deformed)


def plot_field(
    result: IndentationResult,
    path: Path | str,
    field: str = "von_mises",
    *,
    step: int = -1,
    extent: float = 3.0,
    deformed: bool = False,
) -> Path:
    """Write a PNG of one field on the r-z section under the indenter.

    Parameters
    ----------
    result : IndentationResult
        The FEM indentation run.
    path : path-like
        PNG to write (1600 x 1000 pixels); parent folders are created.
    field : str
        One of :data:`FIELDS`: stresses in Pa (tension positive), displacements in m, shown in
        a prefixed unit named in the colour-bar title.
    step : int
        Index of the depth in ``result.steps``; default the largest.
    extent : float
        Width of the window in contact radii a (rounded up to a whole tick); depth 2/3 of it.
    deformed : bool
        Draw the body in its deformed shape (true scale) under the grey indenter, instead of
        the undeformed section with the contact zone on the plane z = 0.

    Returns
    -------
    pathlib.Path
        ``path``.
    """
    made = plot_each_field(result, {field: path}, step=step, extent=extent, deformed=deformed)
    return made[field]


def plot_each_field(
    result: IndentationResult,
    paths: Mapping[str, Path | str],
    *,
    step: int = -1,
    extent: float = 3.0,
    deformed: bool = False,
) -> dict[str, Path]:
    """Write one PNG per field, as :func:`plot_field` would, from one shared section.

    The section and its fields are cut once for all pictures, and one plotter draws them one
    after another, so the pictures are those of :func:`plot_field` called field by field, at a
    fraction of the cost.

    Parameters
    ----------
    result, step, extent, deformed
        As for :func:`plot_field`.
    paths : mapping of str to path-like
        Field name (one of :data:`FIELDS`) to the PNG to write; returned as field -> Path.
    """
    options = (step, extent, deformed)
    cut = _shared_section(result, list(paths), options)
    made = {}
    with picture() as plotter:
        for name, path in paths.items():
            plotter.clear()
            plotter.suppress_rendering = True  # shown: it renders on every add_mesh
            _panel(plotter, result, cut, name, options)
            plotter.suppress_rendering = False
            made[name] = save(plotter, path)
    return made
