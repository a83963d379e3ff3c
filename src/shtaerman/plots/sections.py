"""Off-screen pyvista pictures of the FEM fields under the indenter (PNG, paper-ready).

The r-z section of the half-space (the body is z <= 0, the axis r = 0 on the left) is cut to a
window of a few contact radii around the contact, so the stress field there fills the picture
and not the 1e5-radius domain. Lengths are shown in a prefixed metre unit (mm for the paper's
example) with r and z rulers on round ticks, stresses in a prefixed pascal unit (MPa) named
in the colour-bar title, with isolines at the bar's ticks. The contact zone 0 <= r <= a is a
thick green line on the surface z = 0 (or, with ``deformed=True``, on the deformed surface under
the grey indenter z = f(r) - d). Text uses matplotlib's DejaVu Sans (Greek letters, the same
face as :mod:`shtaerman.figures`).

VTK renders off-screen (no display needed); its one warning about a missing X server is
silenced in :func:`_quiet_vtk`, the only place VTK's global state is touched (and restored).
"""

from __future__ import annotations

import math
from collections.abc import Iterator, Sequence
from contextlib import contextmanager
from dataclasses import dataclass
from functools import cache
from pathlib import Path
from typing import TYPE_CHECKING

import numpy as np
import pyvista as pv
from matplotlib import colormaps, font_manager
from matplotlib.colors import Colormap, ListedColormap
from vtkmodules.vtkCommonCore import vtkObject
from vtkmodules.vtkRenderingCore import vtkBillboardTextActor3D, vtkTextProperty

from ..fem.contact import ContactStep
from ..fem.elasticity import ElasticSolution
from ..study.indentation import IndentationResult
from ..validation import InputError, validate_positive
from .figures import si_prefix

if TYPE_CHECKING:
    from ..study.run import StudyOutcome

__all__ = [
    "FIELDS",
    "FIELD_FIGURES",
    "plot_field",
    "plot_fields",
    "plot_revolved",
    "study_field_figures",
]

WINDOW_SIZE = (1600, 1000)
"""Pixels of every picture."""
CONTACT_COLOUR = "#2ca02c"
"""The contact zone (green: in neither colour map, unlike red for tension)."""
INDENTER_COLOUR = "black"
FONT_SIZE = 22
LEFT_MARGIN = 0.12
"""Fraction of the picture's width left of the section, for the z ruler."""
BAR_GAP = 0.08
"""Fraction of the picture's width between the section and the colour bar."""
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
    """How one vertex field of :class:`ElasticSolution` is shown."""

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


@cache
def _font_file() -> str:
    """DejaVu Sans (matplotlib's font): Greek letters, and the same face as the curve plots."""
    return font_manager.findfont("DejaVu Sans")


def _use_font(prop: vtkTextProperty) -> None:
    prop.SetFontFamily(4)  # VTK_FONT_FILE
    prop.SetFontFile(_font_file())
    prop.SetColor(0.0, 0.0, 0.0)
    prop.BoldOff()
    prop.ShadowOff()


@contextmanager
def _quiet_vtk() -> Iterator[None]:
    """Silence VTK warnings (the off-screen "bad X server connection") for one picture."""
    previous = vtkObject.GetGlobalWarningDisplay()
    vtkObject.GlobalWarningDisplayOff()
    try:
        yield
    finally:
        vtkObject.SetGlobalWarningDisplay(previous)


def _check_field(name: str) -> FieldSpec:
    if name not in FIELDS:
        raise InputError(f"Unknown field '{name}'. Pick one of {sorted(FIELDS)}")
    return FIELDS[name]


def _step(result: IndentationResult, step: int) -> ContactStep:
    try:
        return result.steps[step]
    except IndexError:
        raise InputError(f"step must index one of {len(result.steps)} depths, got {step}") from None


def _nice_step(span: float, intervals: int = 5) -> float:
    """The smallest of 1, 2, 2.5, 5 x 10^k that cuts ``span`` into at most ``intervals``."""
    raw = span / intervals
    power = 10.0 ** math.floor(math.log10(raw))
    return next(m * power for m in (1.0, 2.0, 2.5, 5.0, 10.0) if m * power >= raw * (1 - 1e-9))


def _decimals(step: float) -> int:
    return next(d for d in range(12) if abs(round(step, d) - step) < 1e-9 * step)


@dataclass(frozen=True)
class _Frame:
    """The window shown, in display units: 0 <= r <= width, -depth <= z <= top."""

    scale: float
    """Display units per metre."""
    unit: str
    width: float
    depth: float
    top: float
    step: float
    """Tick spacing."""


def _frame(contact_radius: float, extent: float, above: bool = False) -> _Frame:
    """A window ``extent`` contact radii wide and 2/3 as deep, its edges on round ticks;
    ``above`` adds one tick above the surface (for the indenter)."""
    scale, unit = si_prefix(extent * contact_radius, "m")
    span = extent * contact_radius * scale
    step = _nice_step(span, 6)
    width = step * math.ceil(span / step - 1e-9)
    depth = step * max(1, round(2 * width / (3 * step)))
    return _Frame(scale, unit, width, depth, step if above else 0.0, step)


@dataclass(frozen=True)
class _Colours:
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


def _colours(values: np.ndarray, spec: FieldSpec) -> _Colours:
    """Prefixed unit, colour map and a colour range on round ticks covering ``values`` (SI).

    A sign present only as noise (under ``ONE_SIGNED`` of the range, e.g. the projected
    sigma_zz on the free surface) is cut off at zero, so the range starts at 0.
    """
    low, high = float(values.min()), float(values.max())
    if 0 < high <= ONE_SIGNED * (high - low):
        high = 0.0
    elif 0 > low >= -ONE_SIGNED * (high - low):
        low = 0.0
    step = _nice_step(max(high - low, 1e-300), 10)
    low, high = step * math.floor(low / step + 1e-9), step * math.ceil(high / step - 1e-9)
    high = max(high, low + step)
    scale, unit = si_prefix(max(-low, high), spec.unit)
    cmap = _diverging(low, high) if spec.signed else MAGNITUDE
    title = f"{spec.name}\n{spec.symbol} ({unit})"
    return _Colours(scale, title, low * scale, high * scale, step * scale, cmap)


def _diverging(low: float, high: float) -> Colormap:
    """:data:`DIVERGING` cut to [low, high]: white at 0, blue below, red above, the same
    strength for the same magnitude of either sign (small tension stays pale)."""
    reach = max(-low, high)
    values = np.linspace(low, high, 256)
    return ListedColormap(colormaps[DIVERGING](0.5 + 0.5 * values / reach))


def _section(solution: ElasticSolution, frame: _Frame, deformed: bool) -> pv.PolyData:
    """The r-z section as x = r, y = z (display units), cut to the frame, fields attached."""
    mesh = solution.system.mesh
    r, z = mesh.p
    if deformed:
        r, z = r + solution.u_r, z + solution.u_z
    points = np.column_stack([r, z, np.zeros_like(r)]) * frame.scale
    faces = np.column_stack([np.full(mesh.t.shape[1], 3), mesh.t.T]).ravel()
    section = pv.PolyData(points, faces=faces)
    for name in FIELDS:
        section.point_data[name] = np.asarray(getattr(solution, name), dtype=float)
    section = section.clip(normal=(1.0, 0.0, 0.0), origin=(frame.width, 0.0, 0.0))
    return section.clip(normal=(0.0, -1.0, 0.0), origin=(0.0, -frame.depth, 0.0))


def _curve(r: np.ndarray, z: np.ndarray) -> pv.PolyData:
    return pv.lines_from_points(np.column_stack([r, z, np.full_like(r, 0.01)]))


def _indenter(result: IndentationResult, step: ContactStep, frame: _Frame) -> np.ndarray:
    """(r, z) in display units of the indenter profile z = f(r) - d, up to the frame top."""
    r = np.linspace(0.0, frame.width / frame.scale, 400)
    z = (np.asarray(result.indenter.profile(r)) - step.depth) * frame.scale
    return np.column_stack([r * frame.scale, z])[z <= frame.top]


def _draw_contact(
    plotter: pv.Plotter,
    result: IndentationResult,
    step: ContactStep,
    frame: _Frame,
    deformed: bool,
) -> None:
    """Contact zone 0 <= r <= a in green; with ``deformed``, the indenter in grey above it."""
    a = step.contact_radius * frame.scale
    if not deformed:
        plotter.add_mesh(
            _curve(np.array([0.0, a]), np.zeros(2)), color=CONTACT_COLOUR, line_width=10
        )
        return
    profile = _indenter(result, step, frame)
    body = np.vstack([profile, [[profile[-1, 0], frame.top], [0.0, frame.top]]])
    outline = np.column_stack([body, np.zeros(len(body))])
    solid = pv.PolyData(outline, faces=np.r_[len(body), np.arange(len(body))]).triangulate()
    plotter.add_mesh(solid, color="#d9d9d9", lighting=False)
    plotter.add_mesh(_curve(*profile.T), color=INDENTER_COLOUR, line_width=3)
    inside = profile[profile[:, 0] <= a]
    plotter.add_mesh(_curve(*inside.T), color=CONTACT_COLOUR, line_width=10)


def _scalar_bar(colours: _Colours, left: float) -> dict:
    return {
        "title": colours.title,
        "vertical": True,
        "position_x": left,
        "position_y": 0.12,
        "height": 0.72,
        "width": 0.05,
        "n_labels": round((colours.high - colours.low) / colours.step) + 1,
        "fmt": f"%.{_decimals(colours.step)}f",
        "color": "black",
        "title_font_size": FONT_SIZE,
        "label_font_size": FONT_SIZE,
    }


def _shown(section: pv.PolyData, name: str) -> _Colours:
    """Attach the field ``name`` in display units as "shown"; its colour range."""
    colours = _colours(section.point_data[name], FIELDS[name])
    section.point_data["shown"] = section.point_data[name] * colours.scale
    return colours


def _add_coloured(
    plotter: pv.Plotter, mesh: pv.DataSet, name: str, colours: _Colours, bar: float, **shading
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
        _use_font(prop)


def _isolines(section: pv.PolyData, colours: _Colours) -> pv.PolyData | None:
    """Lines of "shown" at the interior colour-bar ticks (None if there are none)."""
    if not colours.levels.size:
        return None
    lines = section.contour(isosurfaces=colours.levels, scalars="shown")
    return lines if lines.n_points else None


def _draw_field(plotter: pv.Plotter, section: pv.PolyData, name: str, bar: float) -> None:
    """The field in flat colours (no lighting: exactly the bar's), isolines and outline."""
    colours = _shown(section, name)
    _add_coloured(plotter, section, name, colours, bar, lighting=False)
    lines = _isolines(section, colours)
    if lines is not None:
        plotter.add_mesh(lines, color="black", line_width=1.2, opacity=0.45)
    outline = section.extract_feature_edges(
        boundary_edges=True, feature_edges=False, manifold_edges=False, non_manifold_edges=False
    )
    plotter.add_mesh(outline, color="#4d4d4d", line_width=1.5)  # white near 0 needs an edge


def _label(
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
    _use_font(prop)
    prop.SetFontSize(FONT_SIZE)
    prop.SetJustification(align[0])
    prop.SetVerticalJustification(align[1])
    prop.SetOrientation(angle)
    plotter.add_actor(actor, reset_camera=False)


def _draw_axes(plotter: pv.Plotter, frame: _Frame) -> None:
    """r and z rulers on round ticks along the frame's bottom and left edges."""
    tick, pad = 0.012 * (frame.depth + frame.top), FONT_SIZE // 2
    decimals = _decimals(frame.step)
    r_ticks = frame.step * np.arange(round(frame.width / frame.step) + 1)
    z_ticks = frame.top - frame.step * np.arange(round((frame.depth + frame.top) / frame.step) + 1)
    lines = [([0.0, frame.width], [-frame.depth] * 2), ([0.0, 0.0], [-frame.depth, frame.top])]
    lines += [([r, r], [-frame.depth, -frame.depth - tick]) for r in r_ticks]
    lines += [([0.0, -tick], [z, z]) for z in z_ticks]
    for r, z in lines:
        plotter.add_mesh(
            _curve(np.array(r), np.array(z)), color="black", line_width=2, reset_camera=False
        )
    for r in r_ticks:
        _label(plotter, f"{r:.{decimals}f}", (r, -frame.depth - tick), (0, -pad), (1, 2))
    for z in z_ticks:
        _label(plotter, f"{z + 0.0:.{decimals}f}", (-tick, z), (-pad, 0), (2, 1))
    _label(
        plotter,
        f"r ({frame.unit})",
        (0.5 * frame.width, -frame.depth),
        (0, -2 * FONT_SIZE - pad),
        (1, 2),
    )
    _label(
        plotter,
        f"z ({frame.unit})",
        (0.0, 0.5 * (frame.top - frame.depth)),
        (-3 * FONT_SIZE, 0),
        (1, 0),
        angle=90.0,
    )


def _camera_2d(plotter: pv.Plotter, frame: _Frame) -> float:
    """Parallel view of the r-z plane, the frame at the left; returns its right edge (0..1)."""
    aspect = WINDOW_SIZE[0] / WINDOW_SIZE[1]
    height = frame.depth + frame.top
    half = 0.5 * max(height / 0.78, frame.width / (0.62 * aspect))
    centre = (
        half * aspect * (1.0 - 2 * LEFT_MARGIN),
        0.5 * (frame.top - frame.depth) - 0.05 * half,
    )
    plotter.enable_parallel_projection()
    plotter.camera.focal_point = (*centre, 0.0)
    plotter.camera.position = (*centre, 10.0 * half)
    plotter.camera.up = (0.0, 1.0, 0.0)
    plotter.camera.parallel_scale = half
    return LEFT_MARGIN + frame.width / (2 * half * aspect)


def _panel(
    plotter: pv.Plotter,
    result: IndentationResult,
    solution: ElasticSolution,
    name: str,
    options: tuple[int, float, bool],
) -> None:
    """One field picture into the plotter's current renderer."""
    step, extent, deformed = options
    contact = _step(result, step)
    frame = _frame(contact.contact_radius, extent, above=deformed)
    right = _camera_2d(plotter, frame)
    _draw_field(plotter, _section(solution, frame, deformed), name, right + BAR_GAP)
    _draw_contact(plotter, result, contact, frame, deformed)
    _draw_axes(plotter, frame)


@contextmanager
def _picture(shape: tuple[int, int] = (1, 1)) -> Iterator[pv.Plotter]:
    """An off-screen plotter on white, VTK warnings silenced, closed whatever happens."""
    with _quiet_vtk():
        plotter = pv.Plotter(off_screen=True, window_size=WINDOW_SIZE, shape=shape, border=False)
        try:
            plotter.set_background("white")
            yield plotter
        finally:
            plotter.close()


def _save(plotter: pv.Plotter, path: Path | str) -> Path:
    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    plotter.screenshot(str(path))
    return path


def _solution(
    result: IndentationResult, names: Sequence[str], step: int, extent: float
) -> ElasticSolution:
    """Check the options before any drawing; the fields at the chosen depth."""
    for name in names:
        _check_field(name)
    validate_positive("extent", extent)
    return result.field(step)


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
    solution = _solution(result, [field], step, extent)
    with _picture() as plotter:
        _panel(plotter, result, solution, field, (step, extent, deformed))
        return _save(plotter, path)


def plot_fields(
    result: IndentationResult,
    path: Path | str,
    fields: Sequence[str] = ("sigma_zz", "sigma_rr", "von_mises", "u_z"),
    *,
    step: int = -1,
    extent: float = 3.0,
    deformed: bool = False,
) -> Path:
    """Write a 2 x 2 PNG of four fields, 800 x 500 pixels each, laid out as :func:`plot_field`.

    Parameters
    ----------
    result : IndentationResult
        The FEM indentation run.
    path : path-like
        PNG to write (1600 x 1000 pixels); parent folders are created.
    fields : sequence of str
        Four names of :data:`FIELDS`, row by row.
    step, extent, deformed
        As for :func:`plot_field`.

    Returns
    -------
    pathlib.Path
        ``path``.
    """
    if len(fields) != 4:
        raise InputError(f"fields must name four fields, got {len(fields)}")
    solution = _solution(result, fields, step, extent)
    with _picture((2, 2)) as plotter:
        for index, name in enumerate(fields):
            plotter.subplot(*divmod(index, 2))
            _panel(plotter, result, solution, name, (step, extent, deformed))
        return _save(plotter, path)


def _revolve(section: pv.PolyData, angle: float) -> pv.PolyData:
    """Sweep the r-z section (x = r, y = z) about the z axis by ``angle`` degrees."""
    upright = section.copy()
    upright.points = np.column_stack(
        [section.points[:, 0], 0 * section.points[:, 0], section.points[:, 1]]
    )
    return upright.extrude_rotate(resolution=max(8, round(angle / 3)), angle=angle, capping=True)


def _rotated(curve: pv.PolyData, angle: float, shift: float) -> pv.PolyData:
    """An r-z curve (x = r, y = z) in the meridian plane at ``angle`` degrees, moved ``shift``
    along the plane's normal (toward increasing angle; negative: toward decreasing)."""
    theta = math.radians(angle)
    r, z = curve.points[:, 0], curve.points[:, 1]
    normal = (-math.sin(theta), math.cos(theta))
    x = r * math.cos(theta) + shift * normal[0]
    y = r * math.sin(theta) + shift * normal[1]
    moved = curve.copy()
    moved.points = np.column_stack([x, y, z])
    return moved


def _draw_revolved_contact(plotter: pv.Plotter, a: float, angle: float, lift: float) -> None:
    """The contact circle r = a on the surface and its radius on both cut faces, in green."""
    theta = np.radians(np.linspace(angle, 0.0, 181))
    rim = np.column_stack([a * np.cos(theta), a * np.sin(theta), np.full_like(theta, lift)])
    centre = [[0.0, 0.0, lift]]
    path = np.vstack([centre, rim, centre])
    tube = pv.lines_from_points(path).tube(radius=0.012 * a)
    plotter.add_mesh(tube, color=CONTACT_COLOUR, ambient=0.5)


def _camera_3d(plotter: pv.Plotter, angle: float, elevation: float = 28.0) -> None:
    """Look into the open sector from above, the solid left of the colour bar."""
    azimuth = math.radians(0.5 * (angle + 360.0))
    up = math.radians(elevation)
    direction = np.array(
        [math.cos(azimuth) * math.cos(up), math.sin(azimuth) * math.cos(up), math.sin(up)]
    )
    plotter.camera.focal_point = (0.0, 0.0, 0.0)
    plotter.camera.position = tuple(direction)
    plotter.camera.up = (0.0, 0.0, 1.0)
    plotter.reset_camera()
    plotter.camera.zoom(1.45)
    plotter.camera.SetWindowCenter(0.13, 0.0)


def plot_revolved(
    result: IndentationResult,
    path: Path | str,
    field: str = "von_mises",
    *,
    step: int = -1,
    extent: float = 2.5,
    angle: float = 270.0,
) -> Path:
    """Write a PNG of a 3D cut-away: the r-z section revolved about the axis, coloured by a field.

    Parameters
    ----------
    result : IndentationResult
        The FEM indentation run.
    path : path-like
        PNG to write (1600 x 1000 pixels); parent folders are created.
    field : str
        One of :data:`FIELDS` (stresses in Pa, displacements in m; prefixed unit in the bar).
    step : int
        Index of the depth in ``result.steps``; default the largest.
    extent : float
        Radius of the cylinder shown in contact radii a (rounded up to a whole tick); its
        depth is 2/3 of it.
    angle : float
        Sweep in degrees, in (0, 360); the rest is left open to show the section.

    Returns
    -------
    pathlib.Path
        ``path``.
    """
    if not 0.0 < angle < 360.0:
        raise InputError(f"angle must lie in (0, 360) degrees, got {angle!r}")
    solution = _solution(result, [field], step, extent)
    contact = _step(result, step)
    frame = _frame(contact.contact_radius, extent)
    section = _section(solution, frame, deformed=False)
    colours = _shown(section, field)
    with _picture() as plotter:
        shading = {"ambient": 0.45, "diffuse": 0.6, "specular": 0.0}
        _add_coloured(plotter, _revolve(section, angle), field, colours, 0.84, **shading)
        lift = 2e-3 * frame.depth  # lines just off the faces they lie on
        lines = _isolines(section, colours)
        for face, outward in ((0.0, -lift), (angle, lift)) if lines is not None else ():
            moved = _rotated(lines, face, outward)
            plotter.add_mesh(moved, color="black", line_width=1.2, opacity=0.5)
        _draw_revolved_contact(plotter, contact.contact_radius * frame.scale, angle, lift)
        _camera_3d(plotter, angle)
        return _save(plotter, path)


FIELD_FIGURES = {
    "sigma_zz": f"Axial stress {SIGMA}zz under the indenter (r-z section, largest depth)",
    "sigma_rr": f"Radial stress {SIGMA}rr under the indenter (r-z section, largest depth)",
    "von_mises": "Von Mises stress under the indenter (r-z section, largest depth)",
    "u_z": "Axial displacement uz (r-z section, largest depth)",
}
"""Fields of :func:`study_field_figures` and their captions."""


def study_field_figures(outcome: StudyOutcome, folder: Path | str) -> dict[str, Path]:
    """The field pictures of one study, written into ``folder``.

    One PNG per field of :data:`FIELD_FIGURES` (``field_<name>.png``) and the revolved
    von Mises cut-away (``field_revolved.png``), all at the largest depth.

    Parameters
    ----------
    outcome : shtaerman.verification.StudyOutcome
        The study; its ``contact`` (IndentationResult) is drawn.
    folder : path-like
        Where the PNGs go (created if missing).

    Returns
    -------
    dict of str to pathlib.Path
        Caption to PNG path.
    """
    folder, result = Path(folder), outcome.contact
    made = {
        caption: plot_field(result, folder / f"field_{name}.png", name)
        for name, caption in FIELD_FIGURES.items()
    }
    caption = "Von Mises stress, the r-z section revolved through 270° (contact circle in green)"
    made[caption] = plot_revolved(result, folder / "field_revolved.png")
    return made
