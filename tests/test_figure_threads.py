"""Figures drawn from two threads at once (as a user's thread pool or a threaded dask
scheduler draws them) are the figures drawn alone, and leave no global state behind.

Each thread draws the package's own figures, with mathtext labels ($x/x_c$, $\\eta$) and
plain text, in the opposite order of the other, both released together by a barrier. Before
the style was shared between threads (plots/shared.py), one matplotlib.rc_context per figure
restored, on leaving, the rcParams it found on entering: two figures drawn at once undid each
other's style (the first to finish drew the rest of the other unstyled) and the last left the
package's style set in the caller's rcParams (16 of them); VTK's warning switch was left off
the same way. And a thread draws mathtext with its own fonts only (session 53's shared parser
did not). Cheap: theory only (the exact impact, the Ateb functions, a made-up effect table), no
FE run.
"""

from __future__ import annotations

import sys
import threading
from collections.abc import Callable
from pathlib import Path

import matplotlib as mpl
import numpy as np
import pytest
import pyvista as pv
from PIL import Image
from vtkmodules.vtkCommonCore import vtkObject

from shtaerman.api.effect_table.table import QUANTITIES, EffectTable, Run
from shtaerman.plots import ateb, impact, render
from shtaerman.theory.contact import PowerLawContact
from shtaerman.theory.impact import solve_impact
from shtaerman.theory.indenter import PowerLawIndenter

Draw = Callable[[Path], Path]


def _pixels(path: Path) -> np.ndarray:
    return np.asarray(Image.open(path).convert("RGB"))


def _table() -> EffectTable:
    """An effect table of two effects, every bar with a whisker (no FE run)."""
    runs = [Run("none", "none", None, "-", dict.fromkeys(QUANTITIES, 1.0))]
    for role, label, scale in (("alone", "pad alone", 1.1), ("alone", "waves alone", 0.95)):
        runs.append(Run(label, role, label.split()[0], "-", dict.fromkeys(QUANTITIES, scale)))
    runs.append(Run("full", "full", None, "-", dict.fromkeys(QUANTITIES, 1.04)))
    runs = [Run(**{**vars(run), "errors": dict.fromkeys(QUANTITIES, 0.01)}) for run in runs]
    reference = {"P_c": 1.0, "x_c": 1.0, "t_c": 0.5, "t_y": 1.0}
    problem = dict(mass=0.7, velocity=3.0, model="linear", prony=None, geometry="half-space")
    problem.update(thickness=None, interface="frictionless", friction=None)
    return EffectTable(reference, tuple(runs), (), problem)


def _figures() -> dict[str, Draw]:
    exact = solve_impact(0.7, 3.0, PowerLawContact(PowerLawIndenter(5.0, 1.5), 1e7))
    histories = {"analytic": exact.history()}
    table = _table()
    return {
        "ateb": lambda path: ateb.plot_ateb(path),
        "motion": lambda path: impact.plot_impact_motion(histories, exact, path),
        "effects": lambda path: table.plot(path),
    }


def _disc(path: Path) -> Path:
    """An off-screen picture as every field section makes one (render.picture, save)."""
    with render.picture((1, 2)) as plotter:
        plotter.add_mesh(pv.Disc(inner=0.0, c_res=90), color="black", lighting=False)
        return render.save(plotter, path)


def _at_once(draws: dict[str, Draw], folder: Path, rounds: int) -> list[tuple[str, Path]]:
    """Draw ``draws`` in two threads released together, each in the other's reverse order,
    ``rounds`` times; (name, file) of every drawing. A thread's error is raised here."""
    barrier, errors, made = threading.Barrier(2), [], []

    def work(index: int) -> None:
        order = list(draws) if index == 0 else list(reversed(draws))
        try:
            for turn in range(rounds):
                barrier.wait()
                for name in order:
                    made.append((name, draws[name](folder / f"{name}-{index}-{turn}.png")))
        except BaseException as error:
            errors.append(error)
            barrier.abort()  # the other thread stops waiting for this one

    threads = [threading.Thread(target=work, args=(index,)) for index in (0, 1)]
    for thread in threads:
        thread.start()
    for thread in threads:
        thread.join()
    if errors:
        raise errors[0]
    return made


@pytest.fixture
def fast_switching():
    """Hand the interpreter between the threads every microsecond (5 ms by default), so that
    they interleave inside each figure, not figure by figure."""
    interval = sys.getswitchinterval()
    sys.setswitchinterval(1e-6)
    yield
    sys.setswitchinterval(interval)


def test_matplotlib_figures_drawn_in_two_threads_are_those_drawn_alone(tmp_path, fast_switching):
    draws = _figures()
    alone = {name: _pixels(draw(tmp_path / f"{name}.png")) for name, draw in draws.items()}
    before = dict(mpl.rcParams)
    # per-figure restoring left the style set when the figure entered second left last, and
    # drew the rest of a figure unstyled: 1 round of 3 figures missed it in 1 run of 3 on main
    made = _at_once(draws, tmp_path, rounds=2)
    assert len(made) == 2 * 2 * len(draws)
    # the same Agg rendering of the same figure: equal to the bit, not to a tolerance
    differ = [path.name for name, path in made if not np.array_equal(_pixels(path), alone[name])]
    assert differ == []
    left = {key: (before[key], new) for key, new in mpl.rcParams.items() if before[key] != new}
    assert left == {}  # the caller's rcParams, as they were


def test_pyvista_pictures_drawn_in_two_threads_are_those_drawn_alone(tmp_path, fast_switching):
    alone = _pixels(_disc(tmp_path / "disc.png"))
    warnings_shown = vtkObject.GetGlobalWarningDisplay()
    # per-picture restoring left VTK's warnings off when the thread that entered second left
    # last: about half the rounds, so 4 rounds miss it 1 time in 16
    made = _at_once({"disc": _disc}, tmp_path, rounds=4)
    assert [np.array_equal(_pixels(path), alone) for _, path in made] == [True] * 8
    assert vtkObject.GetGlobalWarningDisplay() == warnings_shown  # as the caller had it


def test_a_thread_draws_mathtext_with_its_own_fonts(monkeypatch, tmp_path):
    """matplotlib keeps each thread's fonts apart (its font cache is keyed by thread): a font
    is stateful (size, transform), so one font drawn by two threads at once draws wrong glyphs
    or fails in FreeType. Session 53's parser shared by every figure (150f2b9, reverted in
    8635f79) drew a label parsed in one thread with that thread's fonts in the next thread to
    draw it (the clean-clone CI failed in FT_Load_Glyph on dask workers). Checked one thread
    after the other, so that it fails every time and not only when the threads collide: each
    mathtext glyph is drawn with the font its thread's cache holds for that file."""
    from matplotlib.backends.backend_agg import RendererAgg
    from matplotlib.font_manager import get_font

    drawn, foreign = [], []
    draw_mathtext = RendererAgg.draw_mathtext

    def recording(self, gc, x, y, s, prop, angle):
        parse = self.mathtext_parser.parse(s, self.dpi, prop, antialiased=gc.get_antialiased())
        drawn.append(s)
        foreign.extend(s for font, *_ in parse.glyphs if font is not get_font(font.fname))
        return draw_mathtext(self, gc, x, y, s, prop, angle)

    monkeypatch.setattr(RendererAgg, "draw_mathtext", recording)
    draw = _figures()["motion"]
    draw(tmp_path / "main.png")
    thread = threading.Thread(target=draw, args=(tmp_path / "thread.png",))
    thread.start()
    thread.join()
    assert (tmp_path / "thread.png").exists()  # it drew
    assert "$x/x_c$" in drawn and "Time $t/t_c$" in drawn  # mathtext, in both threads
    assert foreign == []
