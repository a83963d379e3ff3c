"""``shtaerman prony-plot``: the plotted data against closed forms, the image as pixels."""

import contextlib
import io
import math

import numpy as np
import pytest
from matplotlib.image import imread

from shtaerman.cli import main
from shtaerman.plots.prony import prony_curves
from shtaerman.theory.prony_sources import shipped_rubber
from shtaerman.theory.viscoelastic import PronySeries

SILICONE = shipped_rubber("zhermack-elite-double-32")


def test_one_term_curves_are_the_maxwell_closed_forms():
    """g = 0.5 at tau = 1 ms: E'' peaks at g/2 at omega tau = 1, tan delta at
    g / (2 sqrt(1 - g)) at omega tau = 1/sqrt(1 - g)."""
    data = prony_curves(PronySeries((0.5,), (1e-3,)))
    peak = np.argmax(data["loss"])
    # 40 samples per decade: the sampled peak is off by at most 1/80 decade, a relative
    # (ln 10/80)^2/2 = 4e-4 below the maximum of the Lorentzian in log omega
    assert data["loss"][peak] == pytest.approx(0.25, rel=5e-4)
    assert 2 * math.pi * data["frequency"][peak] * 1e-3 == pytest.approx(1.0, rel=0.03)
    assert data["tan_delta"].max() == pytest.approx(0.5 / (2 * math.sqrt(0.5)), rel=5e-4)
    assert data["relaxation"][0] == pytest.approx(1.0 - 0.5 * (1 - math.exp(-0.1)), rel=1e-12)


def test_silicone_curves_run_from_glassy_to_relaxed():
    """A decade beyond the extreme taus E(t) and E'(f) sit within the last term's share of
    E0 and E_inf (the first term, g = 0.164 at tau 5e-8 s, has relaxed only 10 % at t = 5e-9)."""
    data = prony_curves(SILICONE.series, SILICONE.youngs_modulus)
    assert data["relaxation"][0] == pytest.approx(2.912e6, rel=0.02)
    assert data["relaxation"][-1] == pytest.approx(1.196e6, rel=0.01)
    assert np.all(np.diff(data["relaxation"]) < 0)
    assert data["storage"][0] == pytest.approx(1.196e6, rel=0.01)
    assert data["storage"][-1] == pytest.approx(2.912e6, rel=0.02)
    assert np.all(np.diff(data["storage"]) > 0)
    assert data["tan_delta"] == pytest.approx(data["loss"] / data["storage"], rel=1e-12)


def test_cli_draws_and_prints_the_silicone(tmp_path, capsys):
    out = tmp_path / "silicone.png"
    assert main(["prony-plot", "zhermack-elite-double-32", "--out", str(out)]) == 0
    text = capsys.readouterr().out
    assert "E0    = 2.912 MPa" in text and "E_inf = 1.196 MPa" in text
    image = imread(out)[..., :3]
    red = (image[..., 0] > 0.7) & (image[..., 1] < 0.3) & (image[..., 2] < 0.3)  # tan delta
    blue = (image[..., 2] > 0.6) & (image[..., 0] < 0.3)  # E''
    black = image.sum(axis=-1) < 0.3  # E(t), E', axes and text
    # each curve covers hundreds of pixels at 200 dpi; a missing curve leaves none
    assert red.sum() > 300 and blue.sum() > 300 and black.sum() > 3000


def test_cli_prints_one_term_and_a_ratio_series_plainly(tmp_path, capsys):
    """It printed 'tau 0.002 to 0.002 s' for one term and 'E0 = 1 E0' without a modulus."""
    assert main(["prony-plot", "0.3:2e-3", "--out", str(tmp_path / "one.png")]) == 0
    lines = capsys.readouterr().out.splitlines()
    assert lines[0] == "Prony series, 1 term (tau 0.002 s)"
    assert lines[1] == "  E0    = 1 (the moduli are ratios to E0; --E0 gives them in MPa)"
    assert lines[2] == "  E_inf = 0.7 E0 (g_inf = 0.7)"


def test_cli_refuses_a_typo_in_one_line(tmp_path):
    err = io.StringIO()
    with contextlib.redirect_stderr(err):
        code = main(["prony-plot", "0.5:1e-3,0.6:1e-2", "--out", str(tmp_path / "x.png")])
    assert code == 2
    lines = err.getvalue().strip().splitlines()
    assert len(lines) == 1 and lines[0].startswith("shtaerman: error: SERIES:")
    assert "sum to less than 1" in lines[0] and not (tmp_path / "x.png").exists()


def test_cli_names_out_for_a_wrong_suffix(tmp_path, capsys):
    assert main(["prony-plot", "0.5:1e-3", "--out", str(tmp_path / "x.txt")]) == 2
    err = capsys.readouterr().err
    assert (
        err.startswith("shtaerman: error: --out: the figure must end in .png")
        and err.count("\n") == 1
    )
