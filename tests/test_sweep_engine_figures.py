"""A sweep's figures are drawn on its cluster's workers (issue 32: two workers worth two).

Drawn in the sweep's own process after the last case, a 2-axis contact sweep's 10 heat maps
(1.4 s of CPU) took as long on 2 workers as on 1; each figure is now a task, and this process
writes the files the workers return.
"""

import json
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


def test_figures_are_kept_only_when_drawn_from_the_same_results_and_all_there(tmp_path):
    """What a --resume that computed nothing keeps (figures.kept_figures; the resume itself:
    tests/test_sweeprow57.py): the figures in the folder when the previous results.json is the
    new one but for its timings and the sweep file's path, which no figure shows, and every
    file of every figure is there, else None (drawn again)."""
    cases = [{"status": "ok", "outputs": {"e": 0.9, "t": 1.0}, "seconds": 1.0}]
    spec = {"file": "a.toml", "name": "s", "kind": "impact", "axes": {"velocity": [1.0]}}
    old = {"spec": spec, "kind": {"outputs": {"e": "", "t": "s"}}, "cases": cases,
           "timings": {"wall": 9.0}}  # fmt: skip
    moved = {**old, "spec": {**spec, "file": "b/a.toml"}, "timings": {"wall": 0.01}}
    changed = {**old, "cases": [{**cases[0], "outputs": {"e": 0.8, "t": 1.0}}]}
    for name in ("e.png", "t.png", "e.svg"):
        (tmp_path / name).write_bytes(b"drawn")
    kept = [tmp_path / "e.png", tmp_path / "t.png"]
    text = json.dumps(old)
    assert figures.kept_figures(text, json.dumps(moved), tmp_path) == kept
    assert figures.kept_figures(text, json.dumps(moved), tmp_path, "svg") is None  # no t.svg
    assert figures.kept_figures(text, json.dumps(changed), tmp_path) is None
    assert figures.kept_figures(None, text, tmp_path) is None  # no results.json before
    assert figures.kept_figures("{not json", text, tmp_path) is None
    (tmp_path / "t.png").unlink()
    (tmp_path / "t.png").symlink_to(tmp_path / "e.png")
    assert figures.kept_figures(text, text, tmp_path) is None
