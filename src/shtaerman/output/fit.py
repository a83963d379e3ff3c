"""The result folder of a fit: fit.json (the ``--json`` object), fit.csv, fit.png."""

from __future__ import annotations

import json
from pathlib import Path
from typing import Any

from ..plots.fit import plot_fit
from .files import json_safe, staged_folder, write_csv

__all__ = ["write_fit"]


def write_fit(
    result: Any, folder: Path, *, force: bool = False, figure_format: str = "png"
) -> Path:
    """Write ``result`` (a FitResult) into ``folder``, complete or not at all: fit.json,
    fit.csv (the abscissa, each observed column and its fit, and a force's residual fit -
    data; SI units) and fit.png (data against fit)."""
    with staged_folder(folder, force=force) as stage:
        text = json.dumps(json_safe(result.to_dict()), indent=2)
        (stage / "fit.json").write_text(text + "\n", encoding="utf-8")
        write_csv(stage / "fit.csv", result.curves)
        plot_fit(result, stage / "fit.png", figure_format=figure_format)
    return folder
