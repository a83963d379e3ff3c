"""Graded gmsh mesh of the axisymmetric elastic half-space (or layer), read into scikit-fem.

``meshes/halfspace.geo`` (shipped in the wheel as ``shtaerman/meshes``): the quarter disc
r >= 0, z <= 0, r^2 + z^2 <= R^2 (mesh x = r, y = z, metres), element size ``smallest_size``
on the surface segment 0 <= r <= ``refined_radius`` growing linearly with the distance from
it (graded further by :class:`Grading` for ``contact --accuracy``). ``meshes/layer.geo``: the
layer 0 <= r <= L, -H <= z <= 0 with the same size field, capped (:func:`layer_mesh`)."""

from __future__ import annotations

import contextlib
import importlib.resources
import math
import os
import sys
from collections.abc import Callable, Iterator
from dataclasses import dataclass, fields, replace
from pathlib import Path
from typing import TYPE_CHECKING, Any, ClassVar

import numpy as np

from ..signals import deferred
from ..validation import InputError, LimitError, bound_text, validate_positive
from ..vocabulary import entry

if TYPE_CHECKING:
    from skfem import MeshTri

__all__ = [
    "BOUNDARIES",
    "HALF_SPACE",
    "Geometry",
    "GradedMesh",
    "Grading",
    "MeshSettings",
    "check_thickness_range",
    "fitting_velocity",
    "geometry_path",
    "growth_error",
    "halfspace_mesh",
    "layer_mesh",
    "layer_triangles",
    "resolved_depths",
]

BOUNDARIES = ("axis", "surface", "far")
"""Named boundaries of the mesh: r = 0, z = 0 and the far arc (the clamped far boundary)."""
BASE = "base"
"""The rigid base z = -H of a layer on a lubricated base (u_z = 0, free to slide); a bonded
base is clamped, so it belongs to ``"far"``."""

_PARAMETERS = {
    "refined_radius": "Parameters/1Refined radius (m)",
    "domain_radius": "Parameters/2Domain radius (m)",
    "smallest_size": "Parameters/3Smallest element size (m)",
    "growth": "Parameters/4Growth rate (size per distance)",
    "axis_size": "Parameters/5Element size at the axis (m)",
    "axis_growth": "Parameters/6Growth rate from the axis (size per distance)",
    "band_start": "Parameters/7Start of the graded band (m)",
    "near_growth": "Parameters/8Growth rate near the surface (size per distance)",
    "near_depth": "Parameters/9Depth of the near growth (m)",
    "far_growth": "Parameters/10Growth rate far away (size per distance)",
    "far_start": "Parameters/11Distance where the far growth starts (m)",
}
"""The .geo's parameters; those of :class:`Grading` are set only for a graded mesh (else the
.geo's defaults keep its plain size field)."""
_GEOMETRY = "halfspace.geo"
_SHARED = ("refined_radius", "smallest_size", "growth", "axis_size", "axis_growth")
_LAYER_PARAMETERS = {
    **{key: _PARAMETERS[key] for key in _SHARED},
    "lateral_extent": "Parameters/2Lateral extent (m)",
    "thickness": "Parameters/7Layer thickness (m)",
    "thickness_size": "Parameters/8Element size through the thickness (m)",
    "largest_size": "Parameters/9Largest element size (m)",
}
_LAYER_GEOMETRY = "layer.geo"
_PETSC_OPTIONS = "PETSC_OPTIONS"


def geometry_path(name: str = _GEOMETRY) -> Path:
    """Path of ``halfspace.geo`` (or ``name``): the installed package data, else the
    repository's ``meshes/``.

    Returns
    -------
    pathlib.Path
        An existing file.

    Raises
    ------
    FileNotFoundError
        If neither location holds the file (a wheel built without ``meshes/``).
    """
    packaged = importlib.resources.files("shtaerman") / "meshes" / name
    if packaged.is_file():
        return Path(str(packaged))
    repository = Path(__file__).resolve().parents[3] / "meshes" / name
    if not repository.is_file():
        raise FileNotFoundError(f"{name} is neither in shtaerman/meshes nor at {repository}")
    return repository


def halfspace_mesh(
    refined_radius: float,
    *,
    domain_radius: float | None = None,
    smallest_size: float | None = None,
    growth: float | None = None,
    axis_size: float | None = None,
    axis_growth: float | None = None,
    grading: Grading | None = None,
) -> MeshTri:
    """Mesh the axisymmetric half-space with gmsh and return it as a scikit-fem mesh.

    Parameters
    ----------
    refined_radius : float
        Radius of the finely meshed surface zone in m (take it a little larger than the
        largest contact radius). The mesh has a vertex at r = refined_radius on the surface.
    domain_radius : float, optional
        Radius R of the truncated domain in m; default ``MeshSettings.domain *
        refined_radius``. Must exceed ``refined_radius``.
    smallest_size : float, optional
        Element size on the refined zone in m; default ``MeshSettings.size *
        refined_radius``. Must not exceed ``refined_radius``.
    growth : float
        Growth of the element size per unit distance from the refined zone, in (0, 1].
    axis_size : float, optional
        Element size at the origin (the first contact point) in m, <= ``smallest_size``; the
        size grows from it by ``axis_growth`` per unit distance until it reaches the size of
        the refined zone. Default ``smallest_size`` (no extra grading).
    axis_growth : float
        Growth of the element size per unit distance from the origin, in (0, 1].
    grading : Grading, optional
        The graded size field of ``contact --accuracy`` (lengths in refined radii); default
        none: ``smallest_size`` on the refined zone, one ``growth`` everywhere.

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
    The mesh at unit refined radius is made once per process for given parameters (a scaled
    copy is returned again, :func:`_unit_mesh`).
    """
    parameters = _mesh_parameters(refined_radius, domain_radius, smallest_size, growth)
    parameters |= _axis_parameters(parameters["smallest_size"], axis_size, axis_growth)
    if grading is not None:
        parameters |= grading.parameters(parameters["refined_radius"])
    # mesh at unit refined radius, then scale: gmsh's absolute limits (Geometry.Tolerance 1e-8,
    # Mesh.MeshSizeMax 1e22) would merge the points of tiny contacts and cap the elements of
    # huge domains
    scale = parameters["refined_radius"]
    lengths = ("refined_radius", "domain_radius", "smallest_size", "axis_size", *Grading.LENGTHS)
    unit = {key: value / scale if key in lengths else value for key, value in parameters.items()}
    points, triangles, lines = _unit_mesh(unit)
    return _to_skfem(points * scale, triangles, lines)


def layer_mesh(
    refined_radius: float,
    thickness: float,
    *,
    lateral_extent: float,
    smallest_size: float,
    growth: float,
    axis_size: float,
    axis_growth: float,
    thickness_size: float,
    largest_size: float | None = None,
    bonded: bool = True,
) -> MeshTri:
    """Mesh the axisymmetric layer 0 <= r <= ``lateral_extent``, -``thickness`` <= z <= 0.

    Parameters
    ----------
    refined_radius, smallest_size, growth, axis_size, axis_growth : float
        As for :func:`halfspace_mesh` (m, m, -, m, -), already checked.
    thickness : float
        Layer thickness H in m.
    lateral_extent : float
        Radius L > ``refined_radius`` of the truncated layer in m (clamped edge r = L).
    thickness_size : float
        Element size in m at the refined zone, at most (several elements through the
        thickness at the contact); it grows by ``growth`` per unit distance up to
        ``largest_size`` (m; default ``LARGEST_THICKNESS_SIZE`` times itself).
    bonded : bool
        True: the base z = -H joins the clamped boundary ``"far"``; False: it is the boundary
        :data:`BASE` (the solver then holds only u_z there).

    Returns
    -------
    skfem.MeshTri
        Boundaries ``"axis"``, ``"surface"``, ``"far"`` and, for a lubricated base, ``"base"``.
    """
    parameters = {
        "refined_radius": refined_radius,
        "lateral_extent": lateral_extent,
        "smallest_size": smallest_size,
        "growth": growth,
        "axis_size": axis_size,
        "axis_growth": axis_growth,
        "thickness": thickness,
        "thickness_size": thickness_size,
        "largest_size": largest_size or LARGEST_THICKNESS_SIZE * thickness_size,
    }
    scale = refined_radius
    rates = ("growth", "axis_growth")
    unit = {key: value if key in rates else value / scale for key, value in parameters.items()}
    points, triangles, lines = _unit_mesh(unit, _LAYER_PARAMETERS, _LAYER_GEOMETRY)
    if bonded:
        lines["far"] = np.concatenate([lines["far"], lines.pop(BASE)])
    return _to_skfem(points * scale, triangles, lines)


def _mesh_parameters(
    refined_radius: float,
    domain_radius: float | None,
    smallest_size: float | None,
    growth: float | None,
) -> dict[str, float]:
    a = validate_positive("refined_radius", refined_radius, "m")
    big = DEFAULTS.domain * a if domain_radius is None else domain_radius
    big = validate_positive("domain_radius", big, "m")
    h0 = DEFAULTS.size * a if smallest_size is None else smallest_size
    h0 = validate_positive("smallest_size", h0, "m")
    g = validate_positive("growth", DEFAULTS.growth if growth is None else growth)
    if big <= 2.0 * a:
        raise InputError(f"domain_radius must be > 2 * refined_radius = {2 * a!r} m, got {big!r}")
    if h0 > a:
        raise InputError(f"smallest_size must lie in (0, refined_radius = {a!r}] m, got {h0!r}")
    if g > 1.0:
        raise InputError(f"growth must lie in (0, 1], got {growth!r}")
    return {"refined_radius": a, "domain_radius": big, "smallest_size": h0, "growth": g}


def _axis_parameters(
    smallest_size: float, axis_size: float | None, axis_growth: float | None
) -> dict[str, float]:
    size = smallest_size if axis_size is None else validate_positive("axis_size", axis_size, "m")
    growth = DEFAULTS.axis_growth if axis_growth is None else axis_growth
    growth = validate_positive("axis_growth", growth)
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
    with deferred():
        import gmsh  # here, not at load: the command line's parsers read this module

        owned = not gmsh.isInitialized()
        if owned:
            with _petsc_leaving_signals_alone():
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


@contextlib.contextmanager
def _petsc_leaving_signals_alone() -> Iterator[None]:
    """Keep the PETSc built into gmsh's library off the process's signal dispositions
    (``-no_signal_handler`` in ``PETSC_OPTIONS``, restored on exit): its first initialization
    would reset SIGTERM, SIGPIPE and faulthandler's handlers to SIG_DFL."""
    previous = os.environ.get(_PETSC_OPTIONS)
    os.environ[_PETSC_OPTIONS] = f"{previous or ''} -no_signal_handler".lstrip()
    try:
        yield
    finally:
        if previous is None:
            os.environ.pop(_PETSC_OPTIONS, None)
        else:
            os.environ[_PETSC_OPTIONS] = previous


UNIT_MESHES_KEPT = 32
"""gmsh meshes (at unit refined radius) :func:`_unit_mesh` keeps per process."""
_unit_meshes: dict[tuple, tuple[np.ndarray, np.ndarray, dict[str, np.ndarray]]] = {}


def _unit_mesh(
    parameters: dict[str, float], names: dict[str, str] = _PARAMETERS, geometry: str = _GEOMETRY
) -> tuple[np.ndarray, np.ndarray, dict[str, np.ndarray]]:
    """The .geo meshed by :func:`_generate` in a gmsh session, each parameter set (at unit
    refined radius) once per process; the arrays are read-only, the dict of lines a new one per
    call."""
    key = (geometry, tuple(sorted(parameters.items())))
    if key not in _unit_meshes:
        with _gmsh_session():
            made = _generate(parameters, names, geometry)
        for array in (made[0], made[1], *made[2].values()):
            array.flags.writeable = False
        if len(_unit_meshes) >= UNIT_MESHES_KEPT:
            del _unit_meshes[next(iter(_unit_meshes))]
        _unit_meshes[key] = made
    points, triangles, lines = _unit_meshes[key]
    return points, triangles, dict(lines)


def _generate(
    parameters: dict[str, float], names: dict[str, str] = _PARAMETERS, geometry: str = _GEOMETRY
) -> tuple[np.ndarray, np.ndarray, dict]:
    """Mesh the .geo in a model of its own (``gmsh.open``, which resets the parser's bounding
    box and tolerance, never ``gmsh.merge``); return points, triangles and tagged lines."""
    import gmsh

    for key, name in names.items():
        if key in parameters:
            gmsh.onelab.setNumber(name, [parameters[key]])
    gmsh.model.add("shtaerman_halfspace")
    try:
        gmsh.open(str(geometry_path(geometry)))
        gmsh.model.mesh.generate(2)
        return _read_back()
    finally:
        gmsh.model.remove()
        for name in names.values():
            gmsh.onelab.clear(name)


def _read_back() -> tuple[np.ndarray, np.ndarray, dict[str, np.ndarray]]:
    import gmsh

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
    import meshio
    from skfem.io.meshio import from_meshio

    used = np.unique(triangles)
    renumber = np.full(points.shape[0], -1, dtype=np.int64)
    renumber[used] = np.arange(used.size)
    names = [name for name in (*BOUNDARIES, BASE) if name in lines]
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


DEFAULTS_SIZE = 1.0 / 150.0
"""The default :attr:`MeshSettings.size` (the layer's size cap scales with the size)."""
MIN_DOMAIN = 100.0
MAX_DOMAIN = 1e7
MAX_MARGIN = 10.0
"""Largest refined zone / contact radius (see ``MeshSettings.margin``)."""
MAX_DOFS = 400_000
"""Default refusal limit of the estimated mesh size (``MeshSettings.max_dofs``); the
default mesh has 29k dofs."""
DOFS_PER_ELEMENT = 4.7
"""Taylor-Hood P2-P1 unknowns per triangle of these meshes (28904 / 6138 on the default)."""


def estimate_elements(settings: MeshSettings) -> float:
    """Triangles gmsh will make for ``settings`` (any refined radius: the mesh scales), before
    meshing: a fit of the size field's integral Int dA / h^2, zone by zone, within about 30 % of
    gmsh's count (calibration in benchmarks/FEM_NOTES.md); with a :class:`Grading` its own
    first two terms (:meth:`Grading.elements`); inf where the sizes underflow."""
    s, g = settings.size, settings.growth
    axis, axis_growth = min(settings.axis_size, s), settings.axis_growth
    try:
        if settings.grading is not None:
            field = settings.grading.elements(s, g, settings.domain)
        else:
            field = 3.19 / (g * s) + 3.14 * math.log1p(g * settings.domain / s) / g**2
        return field + 3.67 * math.log(s / axis) / axis_growth**2 + 167.0
    except (ZeroDivisionError, OverflowError):  # sizes or growths so small that their
        return math.inf  # products underflow (growth 1e-300, refine 1e300): no mesh


LAYER_EXTENT = 10.0
"""Lateral extent of a layer mesh beyond its refined zone, in thicknesses (the clamped edge
r = L; its effect on the force is measured in benchmarks/FEM_NOTES.md, "Layer")."""
THICKNESS_ELEMENTS = 5.0
"""Elements through the thickness of a layer at the contact at the default size (scaled with
``size``); the cap also sets the surface size (benchmarks/FEM_NOTES.md, "Layer reference")."""
LARGEST_THICKNESS_SIZE = 2.5
"""Largest element size of a layer / its size through the thickness at the contact."""
MIN_THICKNESS = 0.01
"""Thinnest layer the mesh resolves, in refined radii."""
MAX_THICKNESS = 1000.0
"""Thickest layer meshed, in refined radii: a thicker one is the half-space to below 0.1 %
of the force (benchmarks/FEM_NOTES.md, "Layer"), which the mesh without a thickness is."""
_TRIANGLES_PER_SQUARE = 2.3
"""Triangles of gmsh per area h^2 (an equilateral triangle has area 0.433 h^2)."""


def layer_triangles(
    thickness: float, extent: float, cap: float, settings: Any, axis_growth: float
) -> float:
    """Triangles gmsh makes in a layer of ``thickness`` and lateral ``extent`` (refined radii),
    its element size capped at ``cap`` (refined radii): a quadrature of Int dA / h^2 over the
    rectangle (graded grid), plus the axis grading term of :func:`estimate_elements`.
    ``settings`` gives ``size``, ``growth`` and ``axis_size`` (refined radii)."""
    s, g = settings.size, settings.growth
    x = np.concatenate([np.linspace(0.0, 1.0, 65), 1.0 + np.geomspace(1e-3, extent - 1.0, 200)])
    y = -np.concatenate([[0.0], np.geomspace(1e-4 * thickness, thickness, 120)])
    xm, ym = 0.5 * (x[1:] + x[:-1]), 0.5 * (y[1:] + y[:-1])
    xx, yy = np.meshgrid(xm, ym, indexing="ij")
    distance = np.hypot(np.maximum(xx - 1.0, 0.0), yy)
    size = np.minimum(LARGEST_THICKNESS_SIZE * cap, min(s, cap) + g * distance)
    area = np.outer(np.diff(x), -np.diff(y))
    axis = min(settings.axis_size, s)
    grading = 3.67 * math.log(max(min(s, cap) / axis, 1.0)) / axis_growth**2
    return float(_TRIANGLES_PER_SQUARE * np.sum(area / size**2) + grading + 167.0)


def check_thickness_range(thickness: float, refined: float, where: str) -> None:
    """:class:`~shtaerman.validation.LimitError` unless ``thickness`` (m) lies within
    MIN_THICKNESS to MAX_THICKNESS ``refined`` radii (m), the case's contact scale: a limit of
    the layer model for this case, not of the input alone; ``where`` names the case in the
    message ("at these depths")."""
    low, high = MIN_THICKNESS * refined, MAX_THICKNESS * refined
    if not low <= thickness <= high:
        raise LimitError(
            f"thickness: must lie in [{bound_text(low, 'low')}, "
            f"{bound_text(high, 'high')}] m {where} ({MIN_THICKNESS:g} to "
            f"{MAX_THICKNESS:g} refined radii: thinner is not resolved, thicker is the "
            f"half-space, run without a thickness), got {thickness!r}",
            "thickness",
        )


def resolved_depths(
    layer: Geometry, indenter: Any, *margins: float
) -> tuple[float, float, float] | None:
    """The thickness of ``layer`` and the shallowest and deepest depths of a power-law
    ``indenter`` at which a mesh of each refined radius / geometric contact radius in
    ``margins`` resolves it (all m): its thickness within MIN_THICKNESS .. MAX_THICKNESS
    refined radii; None on the half-space or for another profile (whose reach is not
    refused: :func:`shtaerman.guards.check_profile_reach`)."""
    from ..theory.indenter import PowerLawIndenter

    if layer.thickness is None or not isinstance(indenter, PowerLawIndenter):
        return None
    radius = layer.thickness / layer.zone_factor(indenter.exponent)  # refined radius * margin
    shallowest = indenter.profile(radius / (MAX_THICKNESS * min(margins)))
    deepest = indenter.profile(radius / (MIN_THICKNESS * max(margins)))
    return layer.thickness, float(shallowest), float(deepest)


def fitting_velocity(
    thickness: float, refined: float, velocity: float, exponent: float
) -> tuple[float, str] | None:
    """The velocity (m/s, three digits, rounded inward) that brings :func:`check_thickness_range`
    of ``thickness`` (m) within its range, now refused at the ``refined`` radius (m) of an
    impact at ``velocity`` (m/s) by z = A r^``exponent`` (2 for a smooth tip): the refined
    radius goes as the contact's, (M v0^2)^(1/(2n + 1)); with the end of the refusal that
    names it ("; or velocity=... at most V m/s on this thickness"; None beyond the floats).
    Each route checks it by sizing its impact at V."""
    low = thickness < MIN_THICKNESS * refined  # too thin for this contact: a slower impact
    target = thickness / (MIN_THICKNESS if low else MAX_THICKNESS)
    log_moved = math.log(velocity) + (exponent + 0.5) * math.log(target / refined)
    if not abs(log_moved) < 700.0:  # thickness 1e300: beyond the floats
        return None
    bound = bound_text(math.exp(log_moved), "high" if low else "low")
    return float(
        bound
    ), f"; or velocity=... {'at most' if low else 'at least'} {bound} m/s on this thickness"


@dataclass(frozen=True)
class Grading:
    """The graded size field of ``contact --accuracy``: h = s(r) + g(d) (d the distance from the
    refined surface segment; lengths in refined radii).

    On the surface s(r) = size * max(r, band_start) / band_start; below it the size grows by
    ``near_growth`` up to ``near_depth``, by the mesh's ``growth`` beyond and by ``far_growth``
    beyond ``far_start``. :meth:`MeshSettings.refined` divides both growth rates with the
    others (benchmarks/FEM_NOTES.md, "Accuracy 1e-6")."""

    band_start: float = 1.0
    near_growth: float = 0.25
    near_depth: float = 0.0
    far_growth: float = 0.25
    far_start: float = 1e300

    LENGTHS = ("band_start", "near_depth", "far_start")
    GROWTHS = ("near_growth", "far_growth")

    def __post_init__(self) -> None:
        for name in ("band_start", "near_growth", "far_growth"):
            value = validate_positive(name, getattr(self, name))
            if value > 1.0:
                raise InputError(f"{name} must lie in (0, 1], got {value!r}")
        if not 0.0 <= self.near_depth < math.inf:
            raise InputError(f"near_depth must be >= 0 refined radii, got {self.near_depth!r}")
        validate_positive("far_start", self.far_start)

    def parameters(self, refined_radius: float) -> dict[str, float]:
        """The .geo's parameters (lengths in m for a refined zone of ``refined_radius`` m)."""
        return {
            name: getattr(self, name) * (refined_radius if name in self.LENGTHS else 1.0)
            for name in (*self.LENGTHS, *self.GROWTHS)
        }

    def elements(self, size: float, growth: float, domain: float) -> float:
        """Triangles of the size field but the axis grading (:func:`estimate_elements`): the
        surface strip, the rows below it, the field from ``near_depth`` on and beyond
        ``far_start``; within 10 % of gmsh's count on the meshes of ``--accuracy``."""
        band, near = self.band_start, self.near_growth
        below = size + near * self.near_depth
        far_start = min(self.far_start, domain)
        return (
            3.19 * band * (1.0 - math.log(band)) / (near * size)
            + 3.19 * max(1.0 / growth - 1.0 / near, 0.0) / below
            + 3.14 * math.log1p(growth * far_start / below) / growth**2
            + 3.14
            * math.log1p(self.far_growth * domain / (below + growth * far_start))
            / self.far_growth**2
        )


@dataclass(frozen=True)
class Geometry:
    """The body's shape: a half-space (``thickness`` None), or a layer of ``thickness`` m on a
    rigid ``base`` (``bonded``: u = 0, the default; ``lubricated``: u_z = 0)."""

    thickness: float | None = None
    base: str | None = None

    def __post_init__(self) -> None:
        if self.thickness is None:
            if self.base is not None:
                raise InputError(
                    "base: applies to a layer only; give its thickness=... too", "base"
                )
            return
        base = entry("base").default if self.base is None else self.base
        object.__setattr__(self, "base", entry("base").check(base))
        object.__setattr__(self, "thickness", float(entry("thickness").check(self.thickness)))

    @property
    def name(self) -> str:
        """``half-space``, ``layer bonded`` or ``layer lubricated``."""
        return "half-space" if self.thickness is None else f"layer {self.base}"

    def zone_factor(self, exponent: float) -> float:
        """Contact radius bound / geometric radius (A a^n = d): 1 on the half-space;
        ((n + 2)/2)^(1/n) on a layer, whose thin incompressible limit bulges the contact to
        d = 2 A a^n/(n + 2) (see :mod:`shtaerman.theory.layer`)."""
        return 1.0 if self.thickness is None else ((exponent + 2.0) / 2.0) ** (1.0 / exponent)


HALF_SPACE = Geometry()
"""The half-space: the geometry a run takes by default."""


@dataclass(frozen=True)
class MeshSettings:
    """Mesh controls, relative to the largest geometric contact radius a_g = (d_max/A)^(1/n).

    Attributes
    ----------
    margin : float
        Refined (candidate) zone radius / a_g (> 1 keeps the contact edge inside it).
    size : float
        Smallest element size on the refined zone / its radius.
    domain : float
        Domain radius / refined radius, in [1e2, 1e7]: the clamped far boundary stiffens the
        force at contact radius a by about 1.9 a/R and the fitted beta by 1.2 a/R (R the domain
        radius), about 1.5e-5 and 1e-5 at the default domain 1e5.
    growth : float
        Element size growth per unit distance from the refined zone.
    axis_size : float
        Element size at the first contact point / refined radius (grading toward the axis
        resolves the pressure cusp p(0) - p(r) ~ sqrt(r) of n < 2).
    axis_growth : float
        Element size growth per unit distance from the first contact point: every contact
        edge at radius a sees elements of about ``axis_growth * a``.
    max_dofs : float
        Refuse (InputError, before meshing) a mesh whose estimated number of unknowns exceeds
        this (default :data:`MAX_DOFS`); a guard against runaway work, not a mesh control.

    The body's shape is no mesh control: :meth:`build` takes its :class:`Geometry`.
    """

    margin: float = 1.25
    size: float = DEFAULTS_SIZE
    domain: float = 1.0e5
    growth: float = 0.25
    axis_size: float = 1.0e-6
    axis_growth: float = 0.1
    max_dofs: float = MAX_DOFS
    grading: ClassVar[Grading | None] = None
    """None: ``size`` on the refined zone, ``growth`` everywhere (see :class:`GradedMesh`)."""

    def __post_init__(self) -> None:
        names = ("margin", "size", "domain", "growth", "axis_size", "axis_growth", "max_dofs")
        for name in names:
            object.__setattr__(self, name, validate_positive(name, getattr(self, name)))
        if not 1.0 < self.margin <= MAX_MARGIN:
            raise InputError(
                f"margin must lie in (1, {MAX_MARGIN:g}] (the refined zone / contact radius; "
                f"wider zones leave the contact to a few coarse elements), got {self.margin!r}"
            )
        if not MIN_DOMAIN <= self.domain <= MAX_DOMAIN:
            raise InputError(
                f"domain must lie in [{MIN_DOMAIN:g}, {MAX_DOMAIN:g}] refined radii (the "
                f"clamped far boundary stiffens the contact by about 1/domain; gmsh slows down "
                f"sharply beyond 1e7), got {self.domain!r}"
            )
        for name in ("size", "growth", "axis_size", "axis_growth"):
            if getattr(self, name) > 1.0:
                raise InputError(f"{name} must lie in (0, 1], got {getattr(self, name)!r}")

    def refined(self, factor: float) -> MeshSettings:
        """These settings with the whole size field divided by ``factor`` (> 1 refines).

        The smallest size, the axis size and both growth rates are scaled together, so the
        element size h(x) / refined radius is divided by ``factor`` at every point and the
        number of dofs grows as factor^2 (a uniform refinement in the sense of the size
        field). ``margin`` and ``domain`` are kept: the far-field truncation (about
        1.87 / domain of the force) is not a discretisation error and is not refined.

        Raises
        ------
        shtaerman.validation.InputError
            If ``factor`` is not > 0, or it coarsens a growth rate beyond 1.
        """
        factor = validate_positive("refine", factor)
        scaled = {
            name: getattr(self, name) / factor
            for name in ("size", "axis_size", "growth", "axis_growth")
        }
        graded = () if self.grading is None else Grading.GROWTHS
        growths = {name: getattr(self.grading, name) / factor for name in graded}
        for name, value in (scaled | growths).items():
            if value > 1.0 + 1e-12:  # round-off of refine / sqrt(2)^2 is not a coarsening
                raise InputError(
                    f"refine {factor!r} scales the mesh {name} to {value:.3g} > 1; use "
                    f"refine={factor * value:.3g} or more with these settings",
                    "refine",
                )
        scaled = {name: min(value, 1.0) for name, value in scaled.items()}
        if self.grading is not None:  # its growth rates refined with the others
            growths = {name: min(value, 1.0) for name, value in growths.items()}
            scaled["grading"] = replace(self.grading, **growths)
        return replace(self, **scaled)

    @property
    def estimated_dofs(self) -> int:
        """Unknowns of the FEM system on this mesh, estimated before meshing (within about
        30 %, see :func:`estimate_elements`; the largest float where it is unbounded); a
        layer's own estimate needs the refined radius and is checked when it is built
        (:meth:`layer_dofs`)."""
        return round(min(DOFS_PER_ELEMENT * estimate_elements(self), sys.float_info.max))

    def layer_dofs(self, thickness: float) -> int:
        """Estimated unknowns of the layer mesh of ``thickness`` refined radii."""
        extent, cap = self.lateral_extent(thickness), self.thickness_size(thickness)
        triangles = layer_triangles(thickness, extent, cap, self, self.axis_growth)
        return round(DOFS_PER_ELEMENT * triangles)

    def thickness_size(self, thickness: float) -> float:
        """Largest element size of a layer of ``thickness`` (any unit; same unit back)."""
        return thickness / THICKNESS_ELEMENTS * self.size / DEFAULTS_SIZE

    def lateral_extent(self, thickness: float) -> float:
        """Radius of a layer mesh in refined radii for ``thickness`` refined radii:
        1 + LAYER_EXTENT * thickness, at most ``domain``."""
        return min(1.0 + LAYER_EXTENT * thickness, self.domain)

    def check_size(
        self, refined_radius: float | None = None, geometry: Geometry = HALF_SPACE
    ) -> None:
        """Raise InputError if the estimated mesh exceeds ``max_dofs`` (before any work).

        A layer's estimate needs its ``refined_radius`` in m (:meth:`layer_dofs`; its thickness
        is checked too); without it a layer is checked as the half-space of these settings.
        """
        if geometry.thickness is not None and refined_radius is not None:
            self._check_layer(geometry.thickness, refined_radius)
            return
        if self.estimated_dofs > self.max_dofs:
            also = "; or raise max_dofs=..."
            blamed = growth_error(self, lambda mesh: mesh.estimated_dofs, self.max_dofs, 1.0, also)
            if blamed is not None:
                raise blamed
            raise InputError(
                f"max_dofs: this mesh would have about {self.estimated_dofs:.3g} unknowns "
                f"(size {self.size:.3g}, growth {self.growth:.3g}, domain {self.domain:.3g}, "
                f"axis_size {min(self.axis_size, self.size):.3g}, axis_growth "
                f"{self.axis_growth:.3g}), above max_dofs={self.max_dofs:.3g}; coarsen it "
                "(mesh_size=..., growth=..., a lower refine=...) or, in a contact curve, raise "
                "max_dofs=...",
                "max_dofs",
            )

    def build(self, refined_radius: float, geometry: Geometry = HALF_SPACE) -> MeshTri:
        """The gmsh mesh of ``geometry`` (the half-space, or a layer) for a refined (candidate)
        zone of ``refined_radius`` m.

        Raises InputError before meshing if the estimated size exceeds ``max_dofs``.
        """
        if geometry.thickness is not None:
            return self._build_layer(refined_radius, geometry)
        self.check_size()
        return halfspace_mesh(
            refined_radius,
            domain_radius=self.domain * refined_radius,
            smallest_size=self.size * refined_radius,
            growth=self.growth,
            axis_size=min(self.axis_size, self.size) * refined_radius,
            axis_growth=self.axis_growth,
            grading=self.grading,
        )

    def _check_layer(self, thickness: float, refined_radius: float) -> float:
        """``thickness`` (m) in refined radii, checked against the range the mesh resolves and
        the layer mesh's estimated size against ``max_dofs`` (InputError)."""
        check_thickness_range(thickness, refined_radius, "at these depths")
        ratio = thickness / refined_radius
        dofs = self.layer_dofs(ratio)
        if dofs > self.max_dofs:
            raise InputError(
                f"max_dofs: this layer mesh would have about {dofs:.3g} unknowns, above "
                f"max_dofs={self.max_dofs:.3g}; coarsen it (mesh_size=..., a lower refine=...) "
                "or, in a contact curve, raise max_dofs=...",
                "max_dofs",
            )
        return ratio

    def _build_layer(self, refined_radius: float, layer: Geometry) -> MeshTri:
        """The layer mesh of :meth:`build` (checks the thickness against the refined zone)."""
        thickness = layer.thickness
        assert thickness is not None
        ratio = self._check_layer(thickness, refined_radius)
        return layer_mesh(
            refined_radius,
            thickness,
            lateral_extent=self.lateral_extent(ratio) * refined_radius,
            smallest_size=self.size * refined_radius,
            growth=self.growth,
            axis_size=min(self.axis_size, self.size) * refined_radius,
            axis_growth=self.axis_growth,
            thickness_size=self.thickness_size(thickness),
            bonded=layer.base == "bonded",
        )


@dataclass(frozen=True)
class GradedMesh(MeshSettings):
    """:class:`MeshSettings` with the graded size field of ``contact --accuracy`` (a half-space
    only; a class of its own so that the plain settings, and what is written of them, keep
    their fields)."""

    grading: Grading = Grading()


DEFAULTS = MeshSettings()
"""The default mesh: the one place the mesh defaults live."""
FINITE_MESH = MeshSettings(size=1.0 / 60.0, growth=0.3, axis_size=1e-6, axis_growth=0.15)
"""Default mesh for the finite-strain contact (coarser than the linear default: every Newton
iteration assembles and factorizes; its accuracy is in benchmarks/FEM_NOTES.md)."""


# --- the setting to blame when an estimated mesh exceeds its limit of unknowns --------------
# Growth alone sets the graded far field, about pi ln(g D / s) / g^2 elements (g the growth, s
# the size, D the domain): a growth far below the size's proportion makes the mesh too large at
# any refinement. The static and the dynamic meshes, on every route (the CLI, study files,
# sweeps, the API), then name the growth and the range that fits, not the limit of unknowns.

_SCALED = ("growth", "axis_size", "axis_growth")
"""The settings a refinement divides with the size (besides it)."""
_HALVINGS = 60
"""Bisection steps of ln(growth) between the smallest normal float and 1: the bound to 1e-15."""


def growth_error(
    settings: Any,
    estimate: Callable[[Any], float],
    limit: float,
    coarsest_size: float,
    also: str = "",
) -> InputError | None:
    """An InputError naming ``growth`` and the range that fits, when the growth alone makes the
    mesh of ``settings`` (a dataclass with ``size`` and ``growth``) exceed ``limit`` unknowns;
    None when a uniform coarsening (size and growth scaled together up to ``coarsest_size``,
    as a lower refine does) brings it within, or when no growth in (0, 1] can (another
    setting is at fault).

    ``estimate`` maps settings to their estimated unknowns (non-increasing in the growth);
    ``also`` ends the message with another remedy (``"; or raise max_dofs=..."``); the
    inputs are named in Python's words (:func:`shtaerman.problem.worded` spells them per
    route).
    """

    def fits(**changed: float) -> bool:
        return estimate(replace(settings, **changed)) <= limit

    coarser = coarsest_size / settings.size  # the coarsest uniform coarsening (refine < 1)
    scaled = {f.name for f in fields(settings)} & set(_SCALED)
    coarsest = {name: min(getattr(settings, name) * coarser, 1.0) for name in scaled}
    if fits(**coarsest, size=coarsest_size) or not fits(growth=1.0):
        return None  # the mesh is uniformly too fine, or growth is not alone at fault
    low, high = math.log(sys.float_info.min), 0.0  # ln(growth): too many unknowns, within
    for _ in range(_HALVINGS):
        middle = 0.5 * (low + high)
        low, high = (low, middle) if fits(growth=math.exp(middle)) else (middle, high)
    least = bound_text(math.exp(high), "low")
    return InputError(
        f"growth: must lie in [{least}, 1] for a mesh within {limit:.3g} unknowns at size "
        f"{settings.size:.3g}, got {settings.growth:.3g} (the mesh's, after refine=... divides "
        f"growth=...; about {estimate(settings):.3g} unknowns; a coarser mesh_size=... cannot "
        f"make up for it: raise growth=... or lower refine=...){also}",
        "growth",
    )
