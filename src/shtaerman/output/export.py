"""Files of an indentation run: VTU fields (ParaView) via meshio and CSV curves."""

from __future__ import annotations

from pathlib import Path

import meshio
import numpy as np

from ..fem.elasticity import ElasticSolution
from ..study.indentation import IndentationResult
from .files import write_csv

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


def write_indentation(result: IndentationResult, folder: Path) -> list[Path]:
    """Write ``contact_curve.csv``, ``pressure_profiles.csv`` and ``field_max_depth.vtu``.

    Returns the paths written.
    """
    folder = Path(folder)
    curve_path = folder / "contact_curve.csv"
    rows = result.step_table()
    write_csv(curve_path, {key: [row[key] for row in rows] for key in rows[0]})
    profiles_path = folder / "pressure_profiles.csv"
    r = result.curve.compliance.r
    steps = result.steps
    write_csv(
        profiles_path,
        {
            "depth": np.repeat([step.depth for step in steps], r.size),
            "r": np.tile(r, len(steps)),
            "pressure": np.concatenate([step.pressure for step in steps]),
            "pressure_analytic": np.concatenate(
                [result.exact.pressure(r, step.depth) for step in steps]
            ),
            "gap": np.concatenate([step.gap for step in steps]),
        },
    )
    field_path = folder / "field_max_depth.vtu"
    meshio.write(field_path, field_mesh(result.deepest_field))
    return [curve_path, profiles_path, field_path]
