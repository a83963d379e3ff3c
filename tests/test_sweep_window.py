"""A sweep hands its grid to dask a window at a time (left66).

A map of a 1e5-case grid at once saved no case in 200 s (benchmarks/FEM_NOTES.md, "left66"):
at most :data:`~shtaerman.sweep.engine.PENDING_PER_WORKER` tasks per worker are pending, so the
first cases are saved at once, and the records are those of a grid submitted whole.
"""

from distributed import Client

from shtaerman.sweep import engine, load_sweep, run_sweep

GRID = 'name = "w"\nkind = "impact"\n[axes]\nvelocity = [0.5, 1.0, 1.5, 2.0, 2.5, 3.0, 3.5]\n'


def test_a_grid_larger_than_the_window_keeps_the_window_and_the_rows(tmp_path, monkeypatch):
    (tmp_path / "w.toml").write_text(GRID)
    spec = load_sweep(tmp_path / "w.toml")
    peaks: list[int] = []
    futures: list = []
    real_map = Client.map

    def spied(client, *args, **kwargs):  # pending right after each submission: their peak
        futures.extend(real_map(client, *args, **kwargs))
        peaks.append(sum(not future.done() for future in futures))
        return futures[-len(args[1]) :]

    monkeypatch.setattr(Client, "map", spied)
    monkeypatch.setattr(engine, "PENDING_PER_WORKER", 2)  # 1 worker: a window of 2 of 7 cases
    windowed = run_sweep(spec, tmp_path / "windowed", workers=1, figures=False)
    assert windowed.succeeded == 7 and max(peaks) <= 2 and len(peaks) >= 4  # 7 cases, 2 a time
    futures.clear()
    monkeypatch.setattr(engine, "PENDING_PER_WORKER", 7)  # the whole grid in one map
    whole = run_sweep(spec, tmp_path / "whole", workers=1, figures=False)
    assert whole.succeeded == 7 and len(futures) == 7
    # the same rows in the same order (every output of an impact is deterministic)
    csv = (tmp_path / "windowed" / "cases.csv").read_text()
    assert csv == (tmp_path / "whole" / "cases.csv").read_text()
