"""The finite-strain ratio figure: unresolved points off the plotted scale draw nothing, not
even their error bars; unresolved points on it are open markers without a bar (no data)."""

from types import SimpleNamespace

import numpy as np
from matplotlib.figure import Figure

from shtaerman.plots import finite


def outcome(errors):
    """A finite-strain outcome with these relative estimated errors of ``force_ratio``."""
    steps = [{"force_ratio": SimpleNamespace(error=e)} for e in errors]
    study = SimpleNamespace(rubber=SimpleNamespace(name="neo-hookean"))  # the legend's model
    return SimpleNamespace(estimates=SimpleNamespace(steps=steps), study=study)


def bars(axes):
    """The x of every error bar drawn on ``axes``."""
    drawn = []
    for collection in axes.collections:
        for segment in collection.get_segments():
            segment = np.asarray(segment, dtype=float).reshape(-1, 2)
            if len(segment) and np.isfinite(segment).all():  # NaN bars are not drawn
                drawn.append(round(float(segment[0, 0]), 6))
    return drawn


def test_no_error_bar_floats_where_its_point_is_off_scale():
    x = np.array([0.1, 0.2, 0.3, 0.4, 0.5])
    value = np.array([0.80, 0.999, 0.99, 0.98, 0.97])  # the first far below the scale
    linear = np.array([1.0005, 1.0004, 1.0, 1.0, 1.0])
    errors = [0.3, 0.005, 1e-3, 1e-3, 1e-3]  # the first two unresolved: error >= effect
    axes = Figure().subplots()
    finite._panel(axes, outcome(errors), x, (value, linear, np.ones(5)), "force_ratio")
    assert axes.get_ylim()[0] > 0.9  # the off-scale point is left out of the scale ...
    drawn = bars(axes)
    assert 0.1 not in drawn  # ... and draws no bar into the picture
    assert 0.2 not in drawn and 0.3 in drawn  # an unresolved point draws no bar, data does
    open_markers = [line for line in axes.get_lines() if line.get_label().endswith("unresolved")]
    assert any(0.2 in line.get_xdata() for line in open_markers)
    assert any("off scale" in text.get_text() for text in axes.texts)
