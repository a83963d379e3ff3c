"""Files of an indentation run: VTU fields (ParaView) via meshio and CSV curves."""

from __future__ import annotations

import csv
from pathlib import Path

import meshio
import numpy as np

from .elasticity import ElasticSolution
from .indentation import IndentationResult

__all__ = ["FIELD_NAMES", "field_mesh", "write_indentation"]

FIELD_NAMES = (
    "u_r",
    "u_z",
    "sigma_rr",
    "sigma_zz",
    "sigma_tt",
    "sigma_rz",
    "von_mises",
    "mean_pressure",
)
"""Point data of the VTU files: displacements in m, stresses in Pa (tension positive)."""


def field_mesh(solution: ElasticSolution) -> meshio.Mesh:
    """The r-z section (x = r, y = z, m) with the displacement and stress fields at vertices."""
    mesh = solution.system.mesh
    points = np.column_stack([mesh.p[0], mesh.p[1], np.zeros(mesh.p.shape[1])])
    data = {name: np.asarray(getattr(solution, name), dtype=float) for name in FIELD_NAMES}
    data["displacement"] = np.column_stack(
        [solution.u_r, solution.u_z, np.zeros_like(solution.u_r)]
    )
    return meshio.Mesh(points, [("triangle", mesh.t.T)], point_data=data)


def _write_rows(path: Path, rows: list[dict[str, float]]) -> None:
    with path.open("w", newline="") as stream:
        writer = csv.DictWriter(stream, fieldnames=list(rows[0]))
        writer.writeheader()
        writer.writerows(rows)


def write_indentation(result: IndentationResult, folder: Path) -> list[Path]:
    """Write ``contact_curve.csv``, ``pressure_profiles.csv`` and ``field_max_depth.vtu``.

    Returns the paths written.
    """
    folder = Path(folder)
    curve_path = folder / "contact_curve.csv"
    _write_rows(curve_path, result.step_table())
    profiles_path = folder / "pressure_profiles.csv"
    r = result.curve.compliance.r
    profiles = []
    for step in result.steps:
        exact = result.exact.pressure(r, step.depth)
        profiles += [
            {"depth": step.depth, "r": ri, "pressure": pi, "pressure_analytic": ei, "gap": gi}
            for ri, pi, ei, gi in zip(r, step.pressure, exact, step.gap, strict=True)
        ]
    _write_rows(profiles_path, profiles)
    field_path = folder / "field_max_depth.vtu"
    meshio.write(field_path, field_mesh(result.curve.field_solution(result.steps[-1])))
    return [curve_path, profiles_path, field_path]
