"""Off-screen pyvista picture of a 3D cut-away: the r-z section revolved about the axis (PNG).

The section of :mod:`.sections`, swept through :data:`ANGLE` degrees and coloured by von Mises
(:mod:`.fields`), seen from above into the open sector, with the contact circle r = a in green.
"""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pyvista as pv

from ..study.contact.indentation import IndentationResult
from .fields import add_coloured, isolines, shown
from .render import picture, save
from .sections import CONTACT_COLOUR, contact_step, field_solution, frame, section

__all__ = ["plot_revolved"]


ANGLE = 270.0
"""Sweep of the cut-away in degrees; the rest of the turn is left open to show the section."""
EXTENT = 2.5
"""Radius of the cylinder shown, in contact radii."""


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


def plot_revolved(result: IndentationResult, path: Path | str) -> Path:
    """Write a PNG of a 3D cut-away: the r-z section at the largest depth revolved through
    :data:`ANGLE` degrees about the axis, coloured by von Mises; returns ``path``.

    The cylinder shown has a radius of :data:`EXTENT` contact radii (rounded up to a whole
    tick) and 2/3 of it in depth.
    """
    solution = field_solution(result, ["von_mises"], -1, EXTENT)
    contact = contact_step(result, -1)
    window = frame(contact.contact_radius, EXTENT)
    cut = section(solution, window, deformed=False)
    colours = shown(cut, "von_mises")
    with picture() as plotter:
        shading = {"ambient": 0.45, "diffuse": 0.6, "specular": 0.0}
        add_coloured(plotter, _revolve(cut, ANGLE), colours, 0.84, **shading)
        lift = 2e-3 * window.depth  # lines just off the faces they lie on
        lines = isolines(cut, colours)
        for face, outward in ((0.0, -lift), (ANGLE, lift)) if lines is not None else ():
            moved = _rotated(lines, face, outward)
            plotter.add_mesh(moved, color="black", line_width=1.2, opacity=0.5)
        _draw_contact(plotter, contact.contact_radius * window.scale, ANGLE, lift)
        _camera_3d(plotter, ANGLE)
        return save(plotter, path)
