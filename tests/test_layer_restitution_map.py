"""The restitution map's data: what benchmarks/layer_restitution.py reads from a layer sweep's
cases.csv is what plot_layer_restitution draws."""

from __future__ import annotations

import csv
import importlib.util
import json
from pathlib import Path

import numpy as np
import pytest

import shtaerman.plots.layer as layer_plots

SCRIPT = Path(__file__).resolve().parents[1] / "benchmarks" / "layer_restitution.py"
COLUMNS = [
    "case",
    "base",
    "nu2",
    "H_over_a_c",
    "x_c [m]",
    "P_c [N]",
    "restitution",
    "x_max_dynamic [m]",
    "P_max_dynamic [N]",
    "energy_balance_error",
    "status",
]
ROWS = [  # unsorted H, two lines, one failed case
    [0, "bonded", 0.5, 5.0, 0.008, 1000.0, 0.99, 0.007, 1300.0, 1e-4, "ok"],
    [1, "bonded", 0.5, 0.5, 0.008, 1000.0, 1.0, 0.004, 2700.0, 4e-4, "ok"],
    [2, "lubricated", 0.45, 50.0, 0.008, 1000.0, 0.93, 0.0079, 950.0, 8e-5, "ok"],
    [3, "lubricated", 0.45, 1.0, 0.008, 1000.0, 0.97, 0.006, 1500.0, 2e-4, "ok"],
    [4, "bonded", 0.5, 1.0, 0.008, 1000.0, "", "", "", "", "failed"],
]


@pytest.fixture
def script():
    spec = importlib.util.spec_from_file_location("layer_restitution", SCRIPT)
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def test_plotted_restitution_is_the_csv(tmp_path, script, monkeypatch):
    with (tmp_path / "cases.csv").open("w", newline="", encoding="utf-8") as handle:
        csv.writer(handle).writerows([COLUMNS, *ROWS])
    (tmp_path / "results.json").write_text(json.dumps({"spec": {"parameters": {}}}))
    series = script.restitution_series(tmp_path)
    assert list(series) == [("bonded", 0.5), ("lubricated", 0.45)]
    np.testing.assert_array_equal(series[("bonded", 0.5)]["h"], [0.5, 5.0])
    np.testing.assert_array_equal(series[("bonded", 0.5)]["e"], [1.0, 0.99])
    np.testing.assert_allclose(series[("lubricated", 0.45)]["p"], [1.5, 0.95], rtol=1e-15)
    drawn = {}
    monkeypatch.setattr(
        layer_plots, "save", lambda figure, path, fmt: drawn.setdefault("f", figure)
    )
    layer_plots.plot_layer_restitution(script.figure_series(series), tmp_path / "x.png")
    left, right = drawn["f"].axes
    lines = [line for line in left.get_lines() if line.get_label().startswith(("bonded", "lub"))]
    assert [tuple(line.get_ydata()) for line in lines] == [(1.0, 0.99), (0.97, 0.93)]
    assert [tuple(line.get_xdata()) for line in lines] == [(0.5, 5.0), (1.0, 50.0)]
    peaks = [tuple(line.get_ydata()) for line in right.get_lines() if len(line.get_xdata()) == 2]
    assert (2.7, 1.3) in peaks and (1.5, 0.95) in peaks


def test_a_sweep_without_dynamic_columns_is_named(tmp_path, script):
    with (tmp_path / "cases.csv").open("w", newline="", encoding="utf-8") as handle:
        csv.writer(handle).writerows([[*COLUMNS[:6], "status"], [*ROWS[0][:6], "ok"]])
    (tmp_path / "results.json").write_text(json.dumps({"spec": {"parameters": {}}}))
    with pytest.raises(ValueError, match="no restitution column; run a layer sweep with dynamic"):
        script.restitution_series(tmp_path)
