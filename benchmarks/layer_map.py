"""The layer map from a run of ``sweeps/layer.toml``: the thickness above which the half-space
law holds to 1 % and 5 %, with error bars, and the map figure.

    shtaerman sweep sweeps/layer.toml --out sweep-layer
    python benchmarks/layer_map.py sweep-layer [docs/layer_map.png]

For each base and nu2 the departure P / P_Shtaerman - 1 at x_c falls monotonically with
H / a_c. The thickness where it crosses 1 % (5 %) is interpolated linearly in log-log between
the two bracketing sweep points. Its error bar adds

- the interpolation error: the crossing of the quadratic log-log interpolant through the three
  nearest points, against the linear one;
- the FE error: the crossing moved by each point's estimated error (``error_force_ratio``, the
  3-mesh ladder plus the interpolation to x_c), both points pushed the same way.
"""

from __future__ import annotations

import csv
import math
import sys
from pathlib import Path

import numpy as np

from shtaerman.plots.layer import MapSeries, plot_layer_map
from shtaerman.study.contact.layer import LEVELS

NU = "\N{GREEK SMALL LETTER NU}"


def _series(folder: Path) -> dict[tuple[str, float], dict[str, np.ndarray]]:
    """(base, nu2) -> arrays of H / a_c, P / P_Sh, relative error, a_c (m), by increasing H."""
    rows = list(csv.DictReader((folder / "cases.csv").open(encoding="utf-8")))
    out: dict[tuple[str, float], dict[str, list[float]]] = {}
    for row in rows:
        line = out.setdefault(
            (row["base"], float(row["nu2"])), {"h": [], "r": [], "e": [], "a": []}
        )
        line["h"].append(float(row["thickness_ratio"]))
        line["r"].append(float(row["force_ratio"]))
        line["e"].append(float(row["error_force_ratio"]))
        line["a"].append(float(row["a_c [m]"]))
    return {
        key: {name: np.array(values)[np.argsort(line["h"])] for name, values in line.items()}
        for key, line in out.items()
    }


def _crossing(h: np.ndarray, excess: np.ndarray, level: float) -> tuple[float, int]:
    """H / a_c where log(excess) crosses log(level), linear in log-log; the bracket index."""
    i = int(np.flatnonzero((excess[:-1] > level) & (excess[1:] <= level))[0])
    lh, le = np.log(h[i : i + 2]), np.log(excess[i : i + 2])
    return math.exp(lh[0] + (math.log(level) - le[0]) * (lh[1] - lh[0]) / (le[1] - le[0])), i


def _quadratic_crossing(h: np.ndarray, excess: np.ndarray, level: float, i: int) -> float:
    """The crossing of the quadratic log-log interpolant through the three nearest points."""
    j = min(max(i - 1, 0), len(h) - 3) if excess[i] - level > level - excess[i + 1] else i
    j = min(j, len(h) - 3)
    lh, le = np.log(h[j : j + 3]), np.log(excess[j : j + 3])
    roots = np.roots(np.polyfit(lh, le, 2) - np.array([0.0, 0.0, math.log(level)]))
    real = [r.real for r in roots if abs(r.imag) < 1e-12 and lh[0] <= r.real <= lh[-1]]
    return math.exp(min(real, key=lambda r: abs(r - math.log(h[i])))) if real else math.nan


def threshold(line: dict[str, np.ndarray], level: float) -> tuple[float, float, float]:
    """H / a_c above which P / P_Sh - 1 < ``level``, its interpolation and FE errors."""
    h, ratio = line["h"], line["r"]
    excess, error = ratio - 1.0, line["e"] * ratio
    value, i = _crossing(h, excess, level)
    quadratic = _quadratic_crossing(h, excess, level, i)
    shifted = [_crossing(h, excess + sign * error, level)[0] for sign in (-1.0, 1.0)]
    fe = max(abs(s - value) for s in shifted)
    return value, abs(quadratic - value), fe


def main(folder: str, figure: str | None = None) -> None:
    """Print the thresholds (markdown) and, with ``figure``, write the map."""
    series = _series(Path(folder))
    print("| base | nu2 | a_c (mm) | 1 %: H / a_c | 1 %: H (mm) | 5 %: H / a_c | 5 %: H (mm) |")
    print("|---|---|---|---|---|---|---|")
    for (base, nu2), line in series.items():
        a_c = 1e3 * float(line["a"][0])
        cells = []
        for level in LEVELS:
            value, interpolation, fe = threshold(line, level)
            bar = interpolation + fe
            cells += [f"{value:.3g} ± {bar:.2g}", f"{value * a_c:.3g} ± {bar * a_c:.2g}"]
        print(f"| {base} | {nu2:g} | {a_c:.3g} | " + " | ".join(cells) + " |")
    if figure:
        lines = {
            (f"{base}, {NU}2 = {nu2:g}" if base == "bonded" else f"{base}, any {NU}2"): MapSeries(
                line["h"], line["r"], line["e"], base
            )
            for (base, nu2), line in series.items()
            if base == "bonded" or nu2 == 0.5  # lubricated: the same for every nu2 (1e-5)
        }
        print(plot_layer_map(lines, figure))


if __name__ == "__main__":
    main(*sys.argv[1:3])
