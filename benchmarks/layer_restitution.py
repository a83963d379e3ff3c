"""The restitution map from a run of ``sweeps/layer-dynamic.toml``: the dynamic FE impact's
restitution and peak force over H / a_c, per base and nu2, and the figure.

    shtaerman sweep sweeps/layer-dynamic.toml --out sweep-layer-dynamic
    python benchmarks/layer_restitution.py sweep-layer-dynamic [docs/layer_restitution.png]

Prints a markdown table (restitution, P_max_dynamic / P_c, x_max_dynamic / x_c and the energy
balance error per case) and, with a figure path, draws restitution and P_max_dynamic / P_c
against H / a_c with the half-space's dynamic restitution at nu2 = 0.5 as the reference line.
"""

from __future__ import annotations

import csv
import json
import sys
from pathlib import Path

import numpy as np

from shtaerman.plots.layer import RestitutionSeries, plot_layer_restitution

NU = "\N{GREEK SMALL LETTER NU}"
HALF_SPACE_RESTITUTION = 0.927
"""The half-space's dynamic FE restitution of the paper's example at nu2 = 0.5 (density 1100,
default dynamic settings; benchmarks/FEM_NOTES.md, "Layer wiring")."""


def restitution_series(folder: Path | str) -> dict[tuple[str, float], dict[str, np.ndarray]]:
    """(base, nu2) -> arrays by increasing H / a_c: h (H / a_c, the case's output column), e
    (restitution), p (P_max_dynamic / P_c), x (x_max_dynamic / x_c), b (energy balance error);
    cases that failed are left out. base and nu2 fixed by the sweep's [parameters]: from
    results.json."""
    folder = Path(folder)
    spec = json.loads((folder / "results.json").read_text(encoding="utf-8"))["spec"]
    fixed = {"base": "bonded", "nu2": 0.5} | spec["parameters"]
    rows = list(csv.DictReader((folder / "cases.csv").open(encoding="utf-8")))
    if rows and "restitution" not in rows[0]:
        raise ValueError(
            f"{folder}: no restitution column; run a layer sweep with dynamic = true "
            "(e.g. sweeps/layer-dynamic.toml)"
        )
    out: dict[tuple[str, float], dict[str, list[float]]] = {}
    for row in rows:
        if row["status"] != "ok":
            continue
        key = (str(row.get("base", fixed["base"])), float(row.get("nu2", fixed["nu2"])))
        line = out.setdefault(key, {k: [] for k in "hepxb"})
        line["h"].append(float(row["H_over_a_c"]))
        line["e"].append(float(row["restitution"]))
        line["p"].append(float(row["P_max_dynamic [N]"]) / float(row["P_c [N]"]))
        line["x"].append(float(row["x_max_dynamic [m]"]) / float(row["x_c [m]"]))
        line["b"].append(float(row["energy_balance_error"]))
    return {
        key: {name: np.array(values)[np.argsort(line["h"])] for name, values in line.items()}
        for key, line in sorted(out.items())
    }


def figure_series(
    series: dict[tuple[str, float], dict[str, np.ndarray]],
) -> dict[str, RestitutionSeries]:
    """The figure's lines: one per base and nu2, labelled."""
    return {
        f"{base}, {NU}2 = {nu2:g}": RestitutionSeries(line["h"], line["e"], line["p"], base)
        for (base, nu2), line in series.items()
    }


def main(folder: str, figure: str | None = None) -> None:
    """Print the table (markdown) and, with ``figure``, write the restitution map."""
    series = restitution_series(folder)
    print("| base | nu2 | H / a_c | e | P_max / P_c | x_max / x_c | energy balance |")
    print("|---|---|---|---|---|---|---|")
    for (base, nu2), line in series.items():
        for h, e, p, x, b in zip(*(line[k] for k in "hepxb"), strict=True):
            print(f"| {base} | {nu2:g} | {h:g} | {e:.4f} | {p:.3f} | {x:.3f} | {b:.1e} |")
    if figure:
        plotted = figure_series(series)
        print(plot_layer_restitution(plotted, figure, half_space=HALF_SPACE_RESTITUTION))


if __name__ == "__main__":
    main(*sys.argv[1:3])
