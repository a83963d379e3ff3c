"""Files of an indentation run: VTU fields (ParaView) via meshio and CSV curves."""

from __future__ import annotations

from collections.abc import Mapping
from pathlib import Path
from typing import Any
from xml.sax.saxutils import quoteattr

import meshio
import numpy as np

from ..fem.elasticity import ElasticSolution
from ..study.contact.indentation import IndentationResult
from ..theory.impact import ImpactHistory
from .files import write_csv

__all__ = [
    "FIELD_UNITS",
    "field_mesh",
    "indenter_field_data",
    "near_field",
    "step_field_data",
    "write_histories",
    "write_indentation",
    "write_vtu",
]

FIELD_UNITS = {
    "u_r": "m",
    "u_z": "m",
    "sigma_rr": "Pa",
    "sigma_zz": "Pa",
    "sigma_tt": "Pa",
    "sigma_rz": "Pa",
    "von_mises": "Pa",
    "mean_pressure": "Pa",
}
"""Point data of the VTU files and their units: displacements in m, stresses in Pa (tension
positive). In the files each name carries its unit, ``sigma_zz [Pa]``."""
NEAR_FIELD_RADII = 4.0
"""The near-field VTU keeps the triangles within this many contact radii of the first contact
point (ParaView opens on the contact zone, not on the 1e5-times larger domain)."""


def field_mesh(
    solution: ElasticSolution, field_data: dict[str, float] | None = None
) -> meshio.Mesh:
    """The r-z section (x = r, y = z, m) with the displacement and stress fields at vertices.

    Point data are named ``name [unit]``; ``field_data`` (scalars, e.g. the depth) is stored as
    VTK field data under the same convention.
    """
    mesh = solution.system.mesh
    points = np.column_stack([mesh.p[0], mesh.p[1], np.zeros(mesh.p.shape[1])])
    data = {
        f"{name} [{unit}]": np.asarray(getattr(solution, name), dtype=float)
        for name, unit in FIELD_UNITS.items()
    }
    data["displacement [m]"] = np.column_stack(
        [solution.u_r, solution.u_z, np.zeros_like(solution.u_r)]
    )
    fields = {key: np.atleast_1d(np.asarray(value)) for key, value in (field_data or {}).items()}
    return meshio.Mesh(points, [("triangle", mesh.t.T)], point_data=data, field_data=fields)


def write_vtu(path: Path, mesh: meshio.Mesh) -> None:
    """``meshio.write`` plus the mesh's field data as VTK ``FieldData`` (which meshio 5 reads
    but does not write): ParaView shows them in its Information panel."""
    meshio.write(path, meshio.Mesh(mesh.points, mesh.cells, point_data=mesh.point_data))
    if not mesh.field_data:
        return
    arrays = "".join(
        f'<DataArray type="Float64" Name={quoteattr(name)} NumberOfTuples="{np.size(value)}" '
        f'format="ascii">{" ".join(repr(float(v)) for v in np.ravel(value))}</DataArray>'
        for name, value in mesh.field_data.items()
    )
    text = Path(path).read_text(encoding="utf-8")
    anchor = "<UnstructuredGrid>"
    at = text.index(anchor) + len(anchor)
    Path(path).write_text(f"{text[:at]}<FieldData>{arrays}</FieldData>{text[at:]}", "utf-8")


def near_field(full: meshio.Mesh, radius: float) -> meshio.Mesh:
    """The triangles of ``full`` with every vertex within ``radius`` m of the origin, with their
    point data (vertices renumbered) and the same field data."""
    triangles = full.cells_dict["triangle"]
    inside = np.hypot(full.points[:, 0], full.points[:, 1]) <= radius
    kept = triangles[np.all(inside[triangles], axis=1)]
    used = np.unique(kept)
    renumber = np.full(full.points.shape[0], -1, dtype=np.int64)
    renumber[used] = np.arange(used.size)
    return meshio.Mesh(
        full.points[used],
        [("triangle", renumber[kept])],
        point_data={key: value[used] for key, value in full.point_data.items()},
        field_data=full.field_data,
    )


def indenter_field_data(indenter: object) -> dict[str, float]:
    """The striker's profile as VTK field data (numbers): z = A r^n's A and n, the sphere's
    radius, or a table's last radius."""
    if indenter.kind == "sphere":
        return {"indenter_sphere_radius [m]": indenter.radius}
    if indenter.kind == "tabulated":
        return {"indenter_table_last_radius [m]": indenter.r_max}
    return {
        "indenter_shape_coefficient [m^(1-n)]": indenter.shape_coefficient,
        "indenter_exponent [1]": indenter.exponent,
    }


def step_field_data(step: Any, indenter: object, body: Any, model: str) -> dict[str, float]:
    """The VTK field data of a contact step's fields: its depth, contact radius (where it has
    one) and force (SI), the striker's profile (:func:`indenter_field_data`), the ``body``'s E
    and nu, and its material model as a flag (field data are numbers)."""
    radius = getattr(step, "contact_radius", None)
    return {
        "depth [m]": step.depth,
        **({} if radius is None else {"contact_radius [m]": radius}),
        "force [N]": step.force,
        **indenter_field_data(indenter),
        "youngs_modulus [Pa]": body.youngs_modulus,
        "poisson_ratio [1]": body.poisson_ratio,
        f"model_{model} [1]": 1.0,
    }


def write_histories(histories: Mapping[str, ImpactHistory], folder: Path) -> list[Path]:
    """``history_<variant>.csv`` of each impact history in ``folder`` (t, x, P, a, p0 in SI,
    :meth:`~shtaerman.theory.impact.ImpactHistory.columns`); the paths written."""
    written = []
    for variant, history in histories.items():
        written.append(folder / f"history_{variant}.csv")
        write_csv(written[-1], history.columns())
    return written


def write_indentation(result: IndentationResult, folder: Path) -> list[Path]:
    """Write ``contact_curve.csv``, ``pressure_profiles.csv``, ``field_max_depth.vtu`` and its
    near field ``field_max_depth_near.vtu`` (``NEAR_FIELD_RADII`` contact radii).

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
    near_path = folder / "field_max_depth_near.vtu"
    step = result.steps[-1]
    model = getattr(result, "model", "linear")
    data = step_field_data(step, result.indenter, result.half_space, model)
    full = field_mesh(result.deepest_field, data)
    write_vtu(field_path, full)
    write_vtu(near_path, near_field(full, NEAR_FIELD_RADII * step.contact_radius))
    return [curve_path, profiles_path, field_path, near_path]
