"""Figures checked as images: size, not blank, and the features a reader needs.

One coarse paper study (the session's, tests/conftest.py) feeds every figure; the figures of a
run are those its verify run drew. Thresholds were measured on the pictures as accepted by eye
and set with a wide margin: a blank image has pixel standard
deviation 0 and one colour; the figures have std 24-97 (0-255 scale; the field sections are
mostly the near-white middle of a diverging map) and 500-3500 colours.
"""

import os
import subprocess
import sys
from pathlib import Path

import matplotlib as mpl
import numpy as np
import pytest
import pyvista as pv
from matplotlib.figure import Figure
from PIL import Image
from vtkmodules.vtkCommonCore import vtkObject

from shtaerman.plots import curves, gallery, impact, render, sections, style
from shtaerman.study.contact.convergence import ConvergenceStudy
from shtaerman.validation import InputError

MIN_STD = {"matplotlib": 25.0, "pyvista": 12.0}
"""Pixel standard deviation floors; measured minima 37.9 and 24.7 (sigma_rr)."""
MIN_COLOURS = 300
"""Distinct RGB colours; measured minimum 497 (a pale sigma_tt section)."""
RIM_PIXELS = 300
"""Grey pixels along the rim of a black disc on white anti-aliased (measured 810 with FXAA, 701
with 8x multisampling, 0 with neither)."""
TOLERANCE = 16
"""Largest channel difference (0-255) for a pixel to count as a given colour (antialiasing)."""


@pytest.fixture(scope="module")
def outcome(quick_outcome):
    """The session's quick paper study (tests/conftest.py)."""
    return quick_outcome


@pytest.fixture(scope="module")
def folder(tmp_path_factory):
    return tmp_path_factory.mktemp("figures")


@pytest.fixture(scope="module")
def made(quick_verify):
    """The ten figures of the paper study in the session's verify run, and the Ateb figure of
    the hertz study's exponent (n = 2), by file stem.

    The run draws them with gallery.study_figures (the convergence figure too) and
    paper_figures; results.json records each one's caption.
    """
    _, out, results = quick_verify
    figures = dict(results["studies"]["paper"]["figures"])
    assert figures.pop(gallery.CONVERGENCE_CAPTION) == "paper/convergence.png"
    captions = {**figures, **results["figures"]}
    assert all(captions) and len(captions) == 11
    return {Path(path).stem: out / path for path in captions.values()}


def pixels(path: Path) -> np.ndarray:
    """(height, width, 3) integer RGB."""
    return np.asarray(Image.open(path).convert("RGB"), dtype=int)


def packed(image: np.ndarray) -> np.ndarray:
    """One integer per pixel (0xRRGGBB): counting colours on it is 60x faster."""
    return (image[..., 0] << 16) | (image[..., 1] << 8) | image[..., 2]


def assert_picture(path: Path, size: tuple[int, int], kind: str) -> np.ndarray:
    image = pixels(path)
    assert image.shape == (size[1], size[0], 3)
    assert image.std() > MIN_STD[kind]
    assert np.unique(packed(image)).size > MIN_COLOURS
    return image


def colour_mask(image: np.ndarray, colour: str) -> np.ndarray:
    rgb = np.array([int(colour[i : i + 2], 16) for i in (1, 3, 5)])
    return np.abs(image - rgb).max(axis=2) <= TOLERANCE


def assert_colour(image: np.ndarray, colour: str, count: int = 200) -> None:
    assert colour_mask(image, colour).sum() >= count, colour


# --- matplotlib --------------------------------------------------------------------------


def test_force_depth_shows_fem_points_and_exact_line(made):
    image = assert_picture(made["force_depth"], (1280, 960), "matplotlib")
    assert_colour(image, style.FEM_COLOUR, 2000)  # 8 filled markers and the error line
    assert_colour(image, style.EXACT_COLOUR, 2000)


def test_pressure_shows_three_depths_and_exact_curve(made):
    image = assert_picture(made["pressure"], (1280, 840), "matplotlib")
    for colour, _ in style.DEPTH_STYLES:
        assert_colour(image, colour, 300)  # open markers
    assert_colour(image, style.EXACT_COLOUR, 1000)


def test_pressure_selected_step(outcome, folder):
    path = curves.plot_pressure(outcome.contact, folder / "one.png", steps=[-1])
    image = pixels(path)
    assert_colour(image, style.DEPTH_STYLES[0][0], 300)
    assert colour_mask(image, style.DEPTH_STYLES[1][0]).sum() == 0


@pytest.mark.parametrize("stem", ["impact_motion", "impact_contact"])
def test_impact_figures_show_both_quantities(made, stem):
    image = assert_picture(made[stem], (1280, 1000), "matplotlib")
    assert_colour(image, style.FEM_COLOUR, 2000)
    assert_colour(image, style.SECOND_COLOUR, 2000)


def test_impact_needs_a_history(outcome, folder):
    with pytest.raises(ValueError, match="1 to 4"):
        impact.plot_impact_motion({}, outcome.exact, folder / "none.png")


def _drawn_figure(monkeypatch, draw):
    """The matplotlib Figure ``draw`` would save (saving replaced by capturing)."""
    captured = []
    monkeypatch.setattr(impact, "save", lambda figure, path, *_: captured.append(figure) or path)
    draw()
    [figure] = captured
    return figure


def test_impact_contact_says_what_it_clips(outcome, folder, monkeypatch):
    # the FEM-fed impacts end ~1e-4 t_c before the exact t_y, where p(0) ~ x^(1/3) is
    # infinitely steep: their p(0, t) difference leaves the lower panel (measured -6.6 %)
    figure = _drawn_figure(
        monkeypatch,
        lambda: impact.plot_impact_contact(outcome.histories, outcome.exact, folder / "c.png"),
    )
    bottom = figure.axes[1]
    low, high = bottom.get_ylim()
    notes = [text.get_text() for text in bottom.texts]
    assert len(notes) == 1 and notes[0].startswith("off scale (triangles): ")
    assert "$p(0,t)/p_c$ \u2212" in notes[0]
    # a triangle on the panel's edge for each clipped curve
    edges = [line for line in bottom.get_lines() if line.get_marker() in ("^", "v")]
    assert edges and all(line.get_ydata()[0] in (low, high) for line in edges)


def test_impact_figure_without_clipping_has_no_note(outcome, folder, monkeypatch):
    exact = {"analytic": outcome.histories["analytic"]}
    figure = _drawn_figure(
        monkeypatch,
        lambda: impact.plot_impact_motion(exact, outcome.exact, folder / "m.png"),
    )
    assert len(figure.axes[1].texts) == 0


def test_ateb_shows_exact_table_and_approximation(made):
    image = assert_picture(made["ateb"], (1480, 1000), "matplotlib")
    assert_colour(image, style.EXACT_COLOUR, 1000)
    assert_colour(image, style.PAPER_COLOUR, 500)  # open markers of Tables 1-2
    assert_colour(image, style.APPROXIMATION_COLOUR, 2000)


def test_ateb_of_another_exponent_shows_the_exact_pair_alone(made):
    # hertz's n = 2: the paper tabulates only n = 3/2, so no table markers, no approximation
    image = pixels(made["ateb_n2"])  # two black curves: greys only, not MIN_COLOURS colours
    assert image.shape == (600, 1480, 3) and image.std() > 10
    assert_colour(image, style.EXACT_COLOUR, 1000)
    assert colour_mask(image, style.PAPER_COLOUR).sum() == 0
    assert colour_mask(image, style.APPROXIMATION_COLOUR).sum() == 0


def test_convergence_draws_every_error(folder):
    # the format produced by the convergence study: errors ~ h^2, h^2, h, h^1.5
    rows = [
        {
            "size": h,
            "dofs": int(2000 / h**1.2),
            "errors": {
                "force": 3e-2 * h**2,
                "beta": 2e-2 * h**2,
                "contact_radius": 0.5 * h,
                "central_pressure": 0.1 * h**1.5,
            },
        }
        for h in (0.1, 0.05, 0.025)
    ]
    path = curves.plot_convergence(ConvergenceStudy.from_levels(rows), folder / "convergence.png")
    image = assert_picture(path, (1280, 960), "matplotlib")
    for index in range(4):
        assert_colour(image, mpl.colors.to_hex(f"C{index}"), 300)
    single = ConvergenceStudy.from_levels(rows[:1])
    one = curves.plot_convergence(single, folder / "one.png", keys=["force", "missing"])
    assert_colour(pixels(one), mpl.colors.to_hex("C0"), 50)  # a single marker, no order
    with pytest.raises(InputError, match="at least one level"):
        ConvergenceStudy.from_levels([])


def test_figures_leave_matplotlib_state_alone(outcome, folder):
    before = dict(mpl.rcParams)
    curves.plot_pressure(outcome.contact, folder / "state.png")
    assert dict(mpl.rcParams) == before


def zlib_level_class(path: Path) -> int:
    """FLEVEL of the first IDAT's zlib header: 0 for levels 0-1, 1 for 2-5, 2 for 6, 3 for 7-9."""
    data = path.read_bytes()
    start = data.index(b"IDAT") + 4
    return data[start + 1] >> 6


def test_pngs_are_compressed_fast_and_losslessly(outcome, folder):
    path = curves.plot_pressure(outcome.contact, folder / "fast.png")
    assert zlib_level_class(path) == 1  # style.PNG_COMPRESSION = 3; matplotlib's default is 6
    assert style.PNG_COMPRESSION == 3
    with mpl.rc_context(style.STYLE):
        figure = Figure(figsize=(2.0, 1.5))
        figure.add_subplot().plot([0, 1], [1, 0], label=r"$p/p_{avg}$")
        default = folder / "default.png"
        figure.savefig(default, dpi=style.DPI)
        style.save(figure, folder / "level3.png")
    assert zlib_level_class(default) == 2
    assert (pixels(default) == pixels(folder / "level3.png")).all()


def test_png_drawn_once_is_the_savefig_png(folder):
    """save draws a PNG once (savefig draws twice: once for the layout); same bytes, dpi kept."""
    with mpl.rc_context(style.STYLE):
        figure, axes = style.chart(2.0, 1, 2)
        axes[0].plot([0, 1], [1, 0], label=r"$p/p_{avg}$")
        axes[0].legend()
        axes[1].set_xlabel(r"$x/a$ (mm)")
        reference = folder / "savefig.png"
        figure.savefig(reference, dpi=style.DPI, pil_kwargs={"compress_level": 3})
        once = style.save(figure, folder / "once.png")
    assert figure.dpi == mpl.rcParams["figure.dpi"]
    assert once.read_bytes() == reference.read_bytes()
    assert Image.open(once).size == (round(style.WIDTH * style.DPI), 2 * style.DPI)


def test_si_prefix():
    assert style.si_prefix(8.5e-3, "m") == (1e3, "mm")
    assert style.si_prefix(8.4e6, "Pa") == (1e-6, "MPa")
    assert style.si_prefix(986.0, "N") == (1.0, "N")


# --- pyvista -----------------------------------------------------------------------------


def assert_section_filled(image: np.ndarray) -> None:
    """The middle of the r-z section is painted: no pure white (near 0 the map is #f7f7f7)."""
    height, width = image.shape[:2]
    middle = image[int(0.3 * height) : int(0.7 * height), int(0.2 * width) : int(0.55 * width)]
    assert (middle.min(axis=2) < 250).mean() > 0.99


def assert_colour_bar(image: np.ndarray) -> None:
    """A vertical colour gradient right of the section: one column with many colours."""
    right = np.sort(packed(image[:, int(0.7 * image.shape[1]) :]), axis=0)
    colours_per_column = 1 + (np.diff(right, axis=0) != 0).sum(axis=0)
    # measured 143 for a one-signed field (its half of the diverging map, 2 x 2 panel alike),
    # 273 for von Mises; multisampling blended neighbouring bands into more (215, 352)
    assert colours_per_column.max() > 100


def assert_contact_top_left(image: np.ndarray, depth: float = 0.3) -> None:
    """The green contact zone starts at the axis/surface corner: upper left of the picture."""
    rows, columns = np.nonzero(colour_mask(image, sections.CONTACT_COLOUR))
    height, width = image.shape[:2]
    assert rows.size > 500
    assert rows.mean() < depth * height and columns.mean() < 0.4 * width


@pytest.mark.parametrize("field", list(gallery.FIELD_FIGURES))
def test_field_section(made, field):
    image = assert_picture(made[f"field_{field}"], sections.WINDOW_SIZE, "pyvista")
    assert_section_filled(image)
    assert_colour_bar(image)
    assert_contact_top_left(image)


def test_field_deformed_shows_indenter(outcome, folder, monkeypatch):
    monkeypatch.delenv("DISPLAY", raising=False)  # off-screen needs no display
    path = sections.plot_field(outcome.contact, folder / "deformed.png", "u_z", deformed=True)
    image = assert_picture(path, sections.WINDOW_SIZE, "pyvista")
    rows, columns = np.nonzero(colour_mask(image, "#d9d9d9"))
    assert rows.size > 20_000 and columns.mean() < 0.4 * image.shape[1]
    assert_contact_top_left(image, depth=0.5)  # on the deformed surface, pushed down by d


def test_revolved_view(made):
    image = assert_picture(made["field_revolved"], sections.WINDOW_SIZE, "pyvista")
    height, width = image.shape[:2]
    body = image[:, : int(0.8 * width)]
    coloured = body.max(axis=2) - body.min(axis=2) > 40  # not white, not grey
    rows, columns = np.nonzero(coloured)
    # a disc seen from above with a quarter cut out: centred, wider than tall, and filling
    # about 3/4 of its bounding box (measured 0.78; an ellipse alone fills pi/4)
    assert abs(rows.mean() / height - 0.5) < 0.1 and abs(columns.mean() / width - 0.43) < 0.1
    extent = (columns.max() - columns.min(), rows.max() - rows.min())
    assert extent[0] > extent[1] > 0.4 * height
    assert 0.6 < coloured.sum() / (extent[0] * extent[1]) < 0.9
    circle_rows, _ = np.nonzero(colour_mask(image, sections.CONTACT_COLOUR))
    assert circle_rows.size > 200 and circle_rows.mean() < rows.mean()  # the circle on top
    assert_colour_bar(image)


def test_each_field_from_one_section_is_the_field_by_field_picture(outcome, folder):
    """The pictures drawn from the shared section are those drawn one field at a time, to the
    pixel: the section is cut from the same fields and left unchanged by each picture."""
    names = ("sigma_zz", "von_mises")
    shared = sections.plot_each_field(
        outcome.contact, {name: folder / f"shared_{name}.png" for name in names}, extent=2.0
    )
    assert list(shared) == list(names)
    for name in names:
        alone = sections.plot_field(outcome.contact, folder / f"alone_{name}.png", name, extent=2.0)
        assert (pixels(shared[name]) == pixels(alone)).all(), name
    assert not (pixels(shared["sigma_zz"]) == pixels(shared["von_mises"])).all()


def test_each_field_checks_every_name_before_drawing(outcome, folder):
    paths = {"u_z": folder / "first.png", "stress": folder / "second.png"}
    with pytest.raises(InputError, match="Unknown field 'stress'"):
        sections.plot_each_field(outcome.contact, paths)
    assert not paths["u_z"].exists()


def test_axis_segments_are_one_mesh():
    lines = [([0.0, 5.0], [-3.0, -3.0]), ([0.0, 0.0], [-3.0, 1.0]), ([2.5, 2.5], [-3.0, -3.2])]
    mesh = sections.segments(lines)
    assert mesh.n_lines == 3 and mesh.n_points == 6
    expected = [[0.0, -3.0], [5.0, -3.0], [0.0, -3.0], [0.0, 1.0], [2.5, -3.0], [2.5, -3.2]]
    np.testing.assert_array_equal(mesh.points[:, :2], expected)
    assert (mesh.points[:, 2] == 0.01).all()  # in front of the section, as polyline()
    np.testing.assert_array_equal(mesh.lines, [2, 0, 1, 2, 2, 3, 2, 4, 5])


def test_pictures_smooth_edges_without_multisampling(tmp_path):
    """FXAA, not multisampling (several times the render's cost in software OpenGL): a black
    disc on white gets grey pixels along its rim, which no anti-aliasing leaves pure."""
    with render.picture((1, 2)) as plotter:
        assert plotter.render_window.GetMultiSamples() == 0
        assert all(renderer.GetUseFXAA() for renderer in plotter.renderers)
        plotter.add_mesh(pv.Disc(inner=0.0, c_res=90), color="black", lighting=False)
        path = render.save(plotter, tmp_path / "disc.png")
    grey = pixels(path).max(axis=2)
    rim = (grey > 40) & (grey < 215)
    assert (grey < 40).sum() > 50_000 and rim.sum() > RIM_PIXELS


def test_vtk_warnings_restored(outcome, folder):
    before = vtkObject.GetGlobalWarningDisplay()
    with pytest.raises(InputError):
        sections.plot_field(outcome.contact, folder / "quiet.png", "von_mises", extent=-1.0)
    assert vtkObject.GetGlobalWarningDisplay() == before
    sections.plot_field(outcome.contact, folder / "quiet.png", "sigma_tt", step=0, extent=2.0)
    assert vtkObject.GetGlobalWarningDisplay() == before


RENDER = """
import sys
import pyvista as pv
from shtaerman.plots.render import picture, save
with picture() as plotter:
    plotter.add_mesh(pv.Sphere())
    save(plotter, sys.argv[1])
"""


def test_off_screen_rendering_prints_nothing(tmp_path):
    # without a display VTK warns "bad X server connection" (measured with a bare
    # pv.Plotter(off_screen=True)); the package's plotter renders silently
    environment = {k: v for k, v in os.environ.items() if k != "DISPLAY"}
    path = tmp_path / "sphere.png"
    completed = subprocess.run(
        [sys.executable, "-c", RENDER, str(path)],
        env=environment,
        capture_output=True,
        text=True,
        check=False,
        timeout=120,
    )
    assert completed.returncode == 0, completed.stderr
    assert completed.stderr == ""
    assert pixels(path).std() > 10


def test_field_input_errors(outcome, folder):
    with pytest.raises(InputError, match="Unknown field 'stress'"):
        sections.plot_field(outcome.contact, folder / "bad.png", "stress")
    with pytest.raises(InputError, match="step"):
        sections.plot_field(outcome.contact, folder / "bad.png", step=99)
    assert not (folder / "bad.png").exists()
