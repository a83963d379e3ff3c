"""A sweep's figures are drawn on its cluster's workers (issue 32: two workers worth two).

Drawn in the sweep's own process after the last case, a 2-axis contact sweep's 10 heat maps
(1.4 s of CPU) took as long on 2 workers as on 1; each figure is now a task, and this process
writes the files the workers return.
"""

import os
import sys

import pytest

from shtaerman.sweep import figures, parse_sweep, run_sweep

CURVES = 'name = "drawn"\nkind = "impact"\n[axes]\nvelocity = [1.0, 2.0, 3.0]\n'
"""Three analytic impact cases (a millisecond each): a curve per output."""


@pytest.mark.skipif(sys.platform != "linux", reason="the workers inherit the patch by fork")
def test_the_figures_are_drawn_by_both_workers_as_this_process_draws_them(tmp_path, monkeypatch):
    drawers = tmp_path / "drawers"
    drawers.mkdir()
    curve = figures._curve

    def recorded(results, name, *args):
        (drawers / f"{os.getpid()}-{name}").touch()
        return curve(results, name, *args)

    monkeypatch.setattr(figures, "_curve", recorded)
    out = tmp_path / "out"
    outcome = run_sweep(parse_sweep(CURVES, "drawn.toml"), out, workers=2, progress=False)
    assert outcome.exit_code == 0 and len(outcome.figures) > 1
    pids = {int(path.name.split("-")[0]) for path in drawers.iterdir()}
    # the outputs' figures are tasks given to whichever of the 2 idle workers is free: each
    # gets some (a worker holds at most 2 queued tasks), none is drawn here
    assert len(pids) == 2 and os.getpid() not in pids
    monkeypatch.undo()
    here = figures.sweep_figures(out / "results.json", tmp_path / "here")
    assert [path.name for path in here] == [path.name for path in outcome.figures]
    for path in here:  # the same figure, byte for byte (the Agg canvas is deterministic)
        assert path.read_bytes() == (out / "figures" / path.name).read_bytes()


@pytest.mark.skipif(sys.platform != "linux", reason="the workers inherit the patch by fork")
def test_a_figure_that_fails_on_a_worker_is_one_warning_and_the_results_are_written(
    tmp_path, monkeypatch
):
    def broken(*args):
        raise ValueError("no ink")

    monkeypatch.setattr(figures, "_curve", broken)
    out = tmp_path / "out"
    with pytest.warns(UserWarning, match="^figures not drawn: ValueError: no ink$"):
        outcome = run_sweep(parse_sweep(CURVES, "drawn.toml"), out, workers=1, progress=False)
    assert outcome.exit_code == 0 and outcome.figures == ()
    assert (out / "results.json").is_file() and not list(out.glob("figures/*"))


def test_a_resume_that_computes_nothing_keeps_the_figures_drawn_from_the_same_results(tmp_path):
    """A --resume with every case saved drew each figure again (~12 figures, 0.1-0.3 s of CPU
    each, for nothing): the figures drawn from the same results are kept, untouched; if one
    is missing, or asked in another format, they are drawn again, as the first run drew them."""
    spec, out = parse_sweep(CURVES, "drawn.toml"), tmp_path / "out"
    first = run_sweep(spec, out, workers=1, progress=False)
    files = sorted((out / "figures").iterdir())
    assert first.exit_code == 0 and len(files) > 1
    saved = {path.name: path.read_bytes() for path in files}
    for path in files:  # a time no drawing now can give: a file written again shows
        os.utime(path, ns=(10**18, 10**18))
    again = run_sweep(spec, out, resume=True, progress=False)
    assert (again.computed, again.figures) == (0, first.figures)
    assert [path.stat().st_mtime_ns for path in files] == [10**18] * len(files)
    files[0].unlink()
    assert run_sweep(spec, out, resume=True, progress=False).figures == first.figures
    assert {path.name: path.read_bytes() for path in files} == saved  # deterministic Agg
    assert files[1].stat().st_mtime_ns != 10**18  # all drawn again
    vector = run_sweep(spec, out, resume=True, progress=False, figure_format="svg")
    assert vector.figures == first.figures and len(list(out.glob("figures/*.svg"))) == len(files)
