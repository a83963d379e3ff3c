"""Off-screen VTK rendering through pyvista: the one place a plotter is made.

Every pyvista picture of the package comes from :func:`picture`, which makes the plotter
off-screen (no display or X server needed), white, :data:`WINDOW_SIZE` pixels, and closes it
whatever happens. pyvista's global ``OFF_SCREEN`` is left alone, so a user's own interactive
plots in the same session keep working.

VTK reports "bad X server connection" when it renders off-screen without a display (harmless:
it falls back to an off-screen context). :func:`quiet_vtk` silences VTK's warnings for the
duration of one picture; it is the only place VTK's global state is touched, and it restores it.
Text uses matplotlib's DejaVu Sans: Greek letters, and the same face as the curve figures.
Edges are smoothed by FXAA, a post-pass over the finished image (:func:`smooth_edges`), not
by pyvista's default multisampling, which is dearer on a software OpenGL (benchmarks/FEM_NOTES.md,
"Figures") and leaves the thin isolines stepped.
"""

from __future__ import annotations

from collections.abc import Iterator
from contextlib import AbstractContextManager, contextmanager
from functools import cache
from pathlib import Path

import pyvista as pv
from matplotlib import font_manager
from vtkmodules.vtkCommonCore import vtkObject
from vtkmodules.vtkRenderingCore import vtkTextProperty

from ..signals import deferred
from ..validation import InputError
from .shared import SharedContext

__all__ = ["FONT_SIZE", "WINDOW_SIZE", "picture", "quiet_vtk", "save", "smooth_edges", "use_font"]

WINDOW_SIZE = (1600, 1000)
"""Pixels of every picture."""
FONT_SIZE = 22


@cache
def _font_file() -> str:
    return font_manager.findfont("DejaVu Sans")


def use_font(prop: vtkTextProperty) -> None:
    """Black DejaVu Sans, no bold, no shadow, on a VTK text property."""
    prop.SetFontFamily(4)  # VTK_FONT_FILE
    prop.SetFontFile(_font_file())
    prop.SetColor(0.0, 0.0, 0.0)
    prop.BoldOff()
    prop.ShadowOff()


@contextmanager
def _silenced() -> Iterator[None]:
    previous = vtkObject.GetGlobalWarningDisplay()
    vtkObject.GlobalWarningDisplayOff()
    try:
        yield
    finally:
        vtkObject.SetGlobalWarningDisplay(previous)


_QUIET = SharedContext(_silenced)


def quiet_vtk() -> AbstractContextManager[None]:
    """Silence VTK warnings (the off-screen "bad X server connection") for one picture,
    restored when the last picture drawn at once, in any thread, is done."""
    return _QUIET()


def smooth_edges(plotter: pv.Plotter) -> None:
    """Anti-alias with FXAA on every renderer of ``plotter``, multisampling off.

    Set directly on VTK: pyvista's ``enable_anti_aliasing("fxaa")`` substitutes SSAA (a
    render at several times the pixels) when VTK is built for EGL/OSMesa, where VTK's FXAA
    pass works as well.
    """
    plotter.render_window.SetMultiSamples(0)
    for renderer in plotter.renderers:
        renderer.SetUseFXAA(True)


@contextmanager
def picture(shape: tuple[int, int] = (1, 1)) -> Iterator[pv.Plotter]:
    """An off-screen plotter on white, edges smoothed (:func:`smooth_edges`), VTK warnings
    silenced, closed whatever happens. It can draw several pictures one after another
    (``plotter.clear()`` between; :func:`save` renders each), cheaper than a plotter each,
    if its ``suppress_rendering`` is set while a picture is built: a shown
    pyvista plotter renders again on every ``add_mesh`` (benchmarks/FEM_NOTES.md, "Figures").

    SIGINT and SIGTERM are held until the picture is done (:func:`~shtaerman.signals.
    deferred`): the first plotter makes VTK import its OpenGL modules, which an interrupt
    must not break off.
    """
    with deferred(), quiet_vtk():
        plotter = pv.Plotter(off_screen=True, window_size=WINDOW_SIZE, shape=shape, border=False)
        try:
            smooth_edges(plotter)
            plotter.set_background("white")
            yield plotter
        finally:
            plotter.close()


def save(plotter: pv.Plotter, path: Path | str) -> Path:
    """Render ``plotter`` into the PNG ``path`` (parent folders created); returns the path.

    PNG only (:class:`InputError` for another suffix): VTK's SVG/PDF export embeds the same
    rendered bitmap and re-sets the text in another font, so it would add nothing.
    """
    path = Path(path)
    if path.suffix.lower() != ".png":
        raise InputError(f"field pictures are PNG only: path must end in .png, got {str(path)!r}")
    path.parent.mkdir(parents=True, exist_ok=True)
    plotter.render()  # a plotter already shown: the new scene (a new one renders below)
    plotter.screenshot(str(path))
    return path
