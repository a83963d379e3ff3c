"""Off-screen pyvista picture of a 3D cut-away: the r-z section revolved about the axis (PNG).

The section of :mod:`.sections`, swept through ``angle`` degrees and coloured by one field
(:mod:`.fields`), seen from above into the open sector, with the contact circle r = a in green.
"""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pyvista as pv

from ..study.contact.indentation import IndentationResult
from ..validation import InputError
from .fields import add_coloured, isolines, shown
from .render import picture, save
from .sections import CONTACT_COLOUR, contact_step, field_solution, frame, section

__all__ = ["plot_revolved"]


def _revolve(cut: pv.PolyData, angle: float) -> pv.PolyData:
    """Sweep the r-z section (x = r, y = z) about the z axis by ``angle`` degrees."""
    upright = cut.copy()
    upright.points = np.column_stack([cut.points[:, 0], 0 * cut.points[:, 0], cut.points[:, 1]])
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


def _draw_contact(plotter: pv.Plotter, a: float, angle: float, lift: float) -> None:
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
    result, path, field, step
        As for :func:`.sections.plot_field`; returns ``path``.
    extent : float
        Radius of the cylinder shown in contact radii a (rounded up to a whole tick); its
        depth is 2/3 of it.
    angle : float
        Sweep in degrees, in (0, 360); the rest is left open to show the section.
    """
    if not 0.0 < angle < 360.0:
        raise InputError(f"angle must lie in (0, 360) degrees, got {angle!r}")
    solution = field_solution(result, [field], step, extent)
    contact = contact_step(result, step)
    window = frame(contact.contact_radius, extent)
    cut = section(solution, window, deformed=False)
    colours = shown(cut, field)
    with picture() as plotter:
        shading = {"ambient": 0.45, "diffuse": 0.6, "specular": 0.0}
        add_coloured(plotter, _revolve(cut, angle), colours, 0.84, **shading)
        lift = 2e-3 * window.depth  # lines just off the faces they lie on
        lines = isolines(cut, colours)
        for face, outward in ((0.0, -lift), (angle, lift)) if lines is not None else ():
            moved = _rotated(lines, face, outward)
            plotter.add_mesh(moved, color="black", line_width=1.2, opacity=0.5)
        _draw_contact(plotter, contact.contact_radius * window.scale, angle, lift)
        _camera_3d(plotter, angle)
        return save(plotter, path)
