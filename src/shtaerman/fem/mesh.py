"""Graded gmsh mesh of the axisymmetric elastic half-space, read into scikit-fem.

The geometry is ``meshes/halfspace.geo`` (shipped in the wheel as ``shtaerman/meshes``): the
quarter disc r >= 0, z <= 0, r^2 + z^2 <= R^2 in the r-z plane (mesh x = r, y = z, metres).
The element size is ``smallest_size`` on the surface segment 0 <= r <= ``refined_radius`` and
grows linearly with the distance d from it, h = smallest_size + growth * d, so the element count
grows only with log(R / refined_radius).
"""

from __future__ import annotations

import contextlib
import importlib.resources
from collections.abc import Iterator
from pathlib import Path

import gmsh
import meshio
import numpy as np
from skfem import MeshTri
from skfem.io.meshio import from_meshio

from ..validation import InputError, validate_positive

__all__ = [
    "BOUNDARIES",
    "DEFAULT_DOMAIN_FACTOR",
    "DEFAULT_GROWTH",
    "DEFAULT_SIZE_FACTOR",
    "geometry_path",
    "halfspace_mesh",
]

BOUNDARIES = ("axis", "surface", "far")
"""Named boundaries of the mesh: r = 0, z = 0 and the far arc."""

DEFAULT_DOMAIN_FACTOR = 1.0e5
"""Default domain radius over refined radius. The clamped far boundary stiffens the body by
about 1.5 a/R (Boussinesq centre deflection, load radius a): 1.4e-5 here (bench_fem.py (a))."""

DEFAULT_SIZE_FACTOR = 1.0 / 100.0
"""Default smallest element size over refined radius."""

DEFAULT_GROWTH = 0.15
"""Default growth of the element size per unit distance from the refined zone.

With the three defaults, ~20k dofs (nu = 0.5: mesh 0.1 s, assembly 0.15 s, SuperLU 0.1 s)
and relative errors ~3e-5 (Boussinesq centre, Hertz deflection) and 4e-4 to 8e-4 (flat punch
force, limited by its edge singularity; 1e-4 needs smallest_size ~ refined_radius / 800)."""

DEFAULT_AXIS_GROWTH = 0.05
"""Default growth of the element size per unit distance from the origin (when graded)."""

_PARAMETERS = {
    "refined_radius": "Parameters/1Refined radius (m)",
    "domain_radius": "Parameters/2Domain radius (m)",
    "smallest_size": "Parameters/3Smallest element size (m)",
    "growth": "Parameters/4Growth rate (size per distance)",
    "axis_size": "Parameters/5Element size at the axis (m)",
    "axis_growth": "Parameters/6Growth rate from the axis (size per distance)",
}
_GEOMETRY = "halfspace.geo"


def geometry_path() -> Path:
    """Path of ``halfspace.geo``: the installed package data, else the repository's ``meshes/``.

    Returns
    -------
    pathlib.Path
        An existing file.

    Raises
    ------
    FileNotFoundError
        If neither location holds the file (a wheel built without ``meshes/``).
    """
    packaged = importlib.resources.files("shtaerman") / "meshes" / _GEOMETRY
    if packaged.is_file():
        return Path(str(packaged))
    repository = Path(__file__).resolve().parents[3] / "meshes" / _GEOMETRY
    if not repository.is_file():
        raise FileNotFoundError(f"{_GEOMETRY} is neither in shtaerman/meshes nor at {repository}")
    return repository


def halfspace_mesh(
    refined_radius: float,
    *,
    domain_radius: float | None = None,
    smallest_size: float | None = None,
    growth: float = DEFAULT_GROWTH,
    axis_size: float | None = None,
    axis_growth: float = DEFAULT_AXIS_GROWTH,
) -> MeshTri:
    """Mesh the axisymmetric half-space with gmsh and return it as a scikit-fem mesh.

    Parameters
    ----------
    refined_radius : float
        Radius of the finely meshed surface zone in m (take it a little larger than the
        largest contact radius). The mesh has a vertex at r = refined_radius on the surface.
    domain_radius : float, optional
        Radius R of the truncated domain in m; default ``DEFAULT_DOMAIN_FACTOR *
        refined_radius``. Must exceed ``refined_radius``.
    smallest_size : float, optional
        Element size on the refined zone in m; default ``DEFAULT_SIZE_FACTOR *
        refined_radius``. Must not exceed ``refined_radius``.
    growth : float
        Growth of the element size per unit distance from the refined zone, in (0, 1].
    axis_size : float, optional
        Element size at the origin (the first contact point) in m, <= ``smallest_size``; the
        size grows from it by ``axis_growth`` per unit distance until it reaches the size of
        the refined zone. Default ``smallest_size`` (no extra grading).
    axis_growth : float
        Growth of the element size per unit distance from the origin, in (0, 1].

    Returns
    -------
    skfem.MeshTri
        Linear triangles with x = r >= 0, y = z <= 0 (m), named boundaries ``"axis"``,
        ``"surface"``, ``"far"`` and the subdomain ``"body"``. Reproducible: the same
        parameters give the same mesh (gmsh's Delaunay algorithm).

    Raises
    ------
    shtaerman.validation.InputError
        If a parameter is out of range.

    Notes
    -----
    gmsh is a process-wide singleton: do not call this from several threads at once. If the
    caller already initialized gmsh, the session is left running (meshing happens in a model
    of its own, removed afterwards); otherwise gmsh is finalized on return. No file is written.
    """
    parameters = _mesh_parameters(refined_radius, domain_radius, smallest_size, growth)
    parameters |= _axis_parameters(parameters["smallest_size"], axis_size, axis_growth)
    with _gmsh_session():
        points, triangles, lines = _generate(parameters)
    return _to_skfem(points, triangles, lines)


def _mesh_parameters(
    refined_radius: float,
    domain_radius: float | None,
    smallest_size: float | None,
    growth: float,
) -> dict[str, float]:
    a = validate_positive("refined_radius", refined_radius, "m")
    big = DEFAULT_DOMAIN_FACTOR * a if domain_radius is None else domain_radius
    big = validate_positive("domain_radius", big, "m")
    h0 = DEFAULT_SIZE_FACTOR * a if smallest_size is None else smallest_size
    h0 = validate_positive("smallest_size", h0, "m")
    g = validate_positive("growth", growth)
    if big <= 2.0 * a:
        raise InputError(f"domain_radius must be > 2 * refined_radius = {2 * a!r} m, got {big!r}")
    if h0 > a:
        raise InputError(f"smallest_size must lie in (0, refined_radius = {a!r}] m, got {h0!r}")
    if g > 1.0:
        raise InputError(f"growth must lie in (0, 1], got {growth!r}")
    return {"refined_radius": a, "domain_radius": big, "smallest_size": h0, "growth": g}


def _axis_parameters(
    smallest_size: float, axis_size: float | None, axis_growth: float
) -> dict[str, float]:
    size = smallest_size if axis_size is None else validate_positive("axis_size", axis_size, "m")
    growth = validate_positive("axis_growth", axis_growth)
    if size > smallest_size:
        raise InputError(
            f"axis_size must lie in (0, smallest_size = {smallest_size!r}] m, got {size!r}"
        )
    if growth > 1.0:
        raise InputError(f"axis_growth must lie in (0, 1], got {axis_growth!r}")
    return {"axis_size": size, "axis_growth": growth}


@contextlib.contextmanager
def _gmsh_session() -> Iterator[None]:
    """Run gmsh silently; finalize it only if this call initialized it."""
    owned = not gmsh.isInitialized()
    if owned:
        gmsh.initialize(readConfigFiles=False, interruptible=False)
    terminal = gmsh.option.getNumber("General.Terminal")
    gmsh.option.setNumber("General.Terminal", 0)
    try:
        yield
    finally:
        if owned:
            gmsh.finalize()
        else:
            gmsh.option.setNumber("General.Terminal", terminal)


def _generate(parameters: dict[str, float]) -> tuple[np.ndarray, np.ndarray, dict]:
    """Mesh the .geo in a model of its own; return points, triangles and tagged lines."""
    for key, name in _PARAMETERS.items():
        gmsh.onelab.setNumber(name, [parameters[key]])
    gmsh.model.add("shtaerman_halfspace")
    try:
        gmsh.merge(str(geometry_path()))
        gmsh.model.mesh.generate(2)
        return _read_back()
    finally:
        gmsh.model.remove()
        for name in _PARAMETERS.values():
            gmsh.onelab.clear(name)


def _read_back() -> tuple[np.ndarray, np.ndarray, dict[str, np.ndarray]]:
    tags, coords, _ = gmsh.model.mesh.getNodes()
    index = np.zeros(int(tags.max()) + 1, dtype=np.int64)
    index[tags.astype(np.int64)] = np.arange(tags.size)
    points = coords.reshape(-1, 3)[:, :2]
    _, triangle_nodes = gmsh.model.mesh.getElementsByType(2)
    triangles = index[triangle_nodes.astype(np.int64)].reshape(-1, 3)
    lines = {}
    for dim, tag in gmsh.model.getPhysicalGroups(1):
        name = gmsh.model.getPhysicalName(dim, tag)
        nodes = [
            gmsh.model.mesh.getElementsByType(1, entity)[1]
            for entity in gmsh.model.getEntitiesForPhysicalGroup(dim, tag)
        ]
        lines[name] = index[np.concatenate(nodes).astype(np.int64)].reshape(-1, 2)
    return points, triangles, lines


def _to_skfem(points: np.ndarray, triangles: np.ndarray, lines: dict) -> MeshTri:
    """Build a meshio mesh (one triangle block, one line block, a cell set per group)."""
    used = np.unique(triangles)
    renumber = np.full(points.shape[0], -1, dtype=np.int64)
    renumber[used] = np.arange(used.size)
    names = [name for name in BOUNDARIES if name in lines]
    edges = np.concatenate([lines[name] for name in names])
    ends = np.cumsum([0] + [lines[name].shape[0] for name in names])
    cell_sets = {"body": [np.arange(triangles.shape[0]), None]}
    for name, start, stop in zip(names, ends[:-1], ends[1:], strict=True):
        cell_sets[name] = [None, np.arange(start, stop)]
    blocks = [("triangle", renumber[triangles]), ("line", renumber[edges])]
    mesh = from_meshio(meshio.Mesh(points[used], blocks, cell_sets=cell_sets))
    missing = set(BOUNDARIES) - set(mesh.boundaries or {})
    if missing:
        raise RuntimeError(f"{geometry_path()} lacks physical groups {sorted(missing)}")
    return mesh
