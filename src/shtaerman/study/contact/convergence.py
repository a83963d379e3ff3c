"""Mesh convergence of the FEM indentation test against Shtaerman's exact solution.

:func:`convergence_study` reruns :func:`.indentation.run_indentation` on meshes whose whole
size field is scaled by t = size / base.size (:func:`refined_settings`: h ~ size everywhere,
dofs ~ t^-2; domain and margin kept, so the far-boundary truncation is a floor; why this is a
uniform refinement: benchmarks/FEM_NOTES.md, "Study error estimates").
:func:`observed_orders` gives the orders p, error ~ h^p, between consecutive levels;
:func:`fitted_order` the least-squares slope over all levels.
"""

from __future__ import annotations

import dataclasses
import math
from collections.abc import Callable, Sequence
from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike

from ...fem.mesh import HALF_SPACE, Geometry, MeshSettings
from ...theory.indenter import PowerLawIndenter
from ...theory.materials import Material
from ...validation import InputError, validate_positive
from .indentation import run_indentation

__all__ = [
    "MEASURES",
    "ConvergenceStudy",
    "convergence_study",
    "fitted_order",
    "observed_orders",
    "refined_settings",
]

MEASURES = ("size", "dofs")
"""Mesh measures h for the orders: ``"size"`` (h ~ size) or ``"dofs"`` (h ~ dofs^-1/2)."""


ORDER_KEYS = ("force", "beta", "exponent", "contact_radius", "central_pressure")
"""Errors whose fitted order a :class:`ConvergenceStudy` reports."""


@dataclass(frozen=True)
class ConvergenceStudy:
    """A mesh-convergence study: its levels and the fitted order of each error.

    Attributes
    ----------
    levels : tuple of dict
        One per mesh, coarse to fine (see :func:`convergence_study` for the keys).
    orders : dict of str to float
        Least-squares order p (error ~ h^p, h ~ size) of each error of :data:`ORDER_KEYS`
        present in every level; nan where undefined, empty for a single level.
    """

    levels: tuple[dict, ...]
    orders: dict[str, float]

    @classmethod
    def from_levels(cls, levels: Sequence[dict]) -> ConvergenceStudy:
        """The study of ``levels`` (dicts with "size", "dofs", "errors"), orders fitted."""
        if not levels:
            raise InputError("a convergence study needs at least one level")
        keys = [k for k in ORDER_KEYS if all(k in level["errors"] for level in levels)]
        orders = {k: fitted_order(levels, k) for k in keys} if len(levels) > 1 else {}
        return cls(tuple(levels), orders)

    def to_dict(self) -> dict[str, object]:
        """Plain data for results.json: levels (size, dofs, errors) and fitted orders."""
        return {
            "levels": [{k: level[k] for k in ("size", "dofs", "errors")} for level in self.levels],
            "fitted_orders": self.orders,
        }


def refined_settings(base: MeshSettings, size: float) -> MeshSettings:
    """``base`` with its whole size field scaled by t = size / base.size.

    Parameters
    ----------
    base : MeshSettings
        The reference mesh (all fields relative to the refined radius, dimensionless).
    size : float
        The new smallest surface element size / refined radius, dimensionless, in (0, 1].

    Returns
    -------
    MeshSettings
        ``size``, ``axis_size``, ``growth`` and ``axis_growth`` multiplied by t; ``margin``
        and ``domain`` unchanged.

    Raises
    ------
    shtaerman.validation.InputError
        If ``size`` is not in (0, 1] or a scaled growth rate would exceed 1 (the mesh allows
        growth in (0, 1]: coarsen ``base`` less).
    """
    size = validate_positive("size", size)
    if size > 1.0:
        raise InputError(f"size must lie in (0, 1] refined radii, got {size!r}")
    try:
        return base.refined(base.size / size)
    except InputError as error:
        raise InputError(f"size {size!r}: {error}") from None


def convergence_study(
    indenter: PowerLawIndenter,
    half_space: Material,
    sizes: Sequence[float],
    *,
    depths: ArrayLike | None = None,
    base: MeshSettings | None = None,
    friction: float | None = None,
    progress: Callable[[str], None] | None = None,
    geometry: Geometry = HALF_SPACE,
) -> ConvergenceStudy:
    """Run the indentation test on meshes refined uniformly, one per element size.

    Parameters
    ----------
    indenter : PowerLawIndenter
        Rigid profile z = A r^n, n > 1 (A in m^(1-n)).
    half_space : Material
        E2 in Pa, nu2 in [0, 0.5].
    sizes : sequence of float
        Smallest surface element size / refined radius (dimensionless) of each level, e.g.
        ``[1/75, 1/106, 1/150, 1/212]``; usually decreasing. Each level is
        :func:`refined_settings` ``(base, size)``: the whole size field (surface, axis grading,
        growth rates) is scaled with ``size``, so h ~ size everywhere and dofs ~ size^-2.
    depths : array_like, optional
        Depths in m, positive and increasing; default
        :func:`.indentation.default_depths` (the same for every level).
    base : MeshSettings, optional
        The mesh being refined (default ``MeshSettings()``); its ``domain`` and ``margin`` are
        used as is at every level.
    friction : float, optional
        The indenter's surface, as for :func:`.indentation.run_indentation`.
    progress : callable, optional
        Called with one line of text (str) after each level, e.g. ``print``.
    geometry : Geometry
        The body's shape (default the half-space).

    Returns
    -------
    ConvergenceStudy
        Its ``levels``: one dict per size, in the given order, with keys ``"size"``
        (float, dimensionless), ``"dofs"`` (int), ``"errors"`` (dict: the largest relative
        errors over the depths of :meth:`.indentation.IndentationResult.errors`,
        dimensionless: force, contact_radius, central_pressure, beta, exponent,
        pressure_profile), ``"timings"`` (dict, seconds: mesh, assembly, factorization,
        contact, total) and ``"settings"`` (dict: the :class:`MeshSettings` fields of the
        level); and the fitted order of each error.

    Raises
    ------
    shtaerman.validation.InputError
        For an empty ``sizes``, a size out of range (see :func:`refined_settings`) or invalid
        indenter, material or depths.
    """
    if len(sizes) == 0:
        raise InputError("sizes must hold at least one element size")
    base = MeshSettings() if base is None else base
    levels = [refined_settings(base, float(size)) for size in sizes]  # validate all up front
    study = []
    for settings in levels:
        physics = {"friction": friction, "geometry": geometry}
        result = run_indentation(indenter, half_space, depths, settings, **physics)
        errors = result.errors()
        row = {
            "size": settings.size,
            "dofs": int(result.mesh_stats["dofs"]),
            "errors": errors,
            "timings": dict(result.timings),
            "settings": dataclasses.asdict(settings),
        }
        study.append(row)
        if progress is not None:
            progress(
                f"size 1/{1.0 / settings.size:.4g}: {row['dofs']} dofs, "
                f"{row['timings']['total']:.2f} s, force error {errors['force']:.2e}, "
                f"beta error {errors['beta']:.2e}"
            )
    return ConvergenceStudy.from_levels(study)


def _measures(study: Sequence[dict], key: str, measure: str) -> tuple[np.ndarray, np.ndarray]:
    """Mesh measure h and error of ``key`` of each level."""
    if measure not in MEASURES:
        raise InputError(f"Unknown measure {measure!r}. Pick one of {list(MEASURES)}")
    if len(study) < 2:
        raise InputError(f"an order needs at least two levels, got {len(study)}")
    if measure == "size":
        h = np.array([float(level["size"]) for level in study])
    else:
        h = np.array([float(level["dofs"]) ** -0.5 for level in study])
    try:
        errors = np.array([float(level["errors"][key]) for level in study])
    except KeyError:
        raise InputError(
            f"Unknown error {key!r}. Pick one of {sorted(study[0]['errors'])}"
        ) from None
    return h, np.abs(errors)


def observed_orders(study: Sequence[dict], key: str, *, measure: str = "size") -> list[float]:
    """Observed orders of convergence between consecutive levels of a study.

    p_k = log(e_k / e_(k+1)) / log(h_k / h_(k+1)), so that e ~ h^p: 2 means the error falls
    4-fold when h halves. The errors are the worst over the depths, so a single level can be
    lucky or unlucky (the contact edge falls near or between nodes); read the trend, or
    :func:`fitted_order`.

    Parameters
    ----------
    study : sequence of dict
        From :func:`convergence_study` (or any dicts with ``"size"``, ``"dofs"`` and an
        ``"errors"`` dict), at least two levels.
    key : str
        Which error, e.g. ``"force"`` or ``"beta"``.
    measure : str
        The mesh measure h: ``"size"`` (default; the smallest element size, proportional to
        the element size everywhere under :func:`refined_settings`) or ``"dofs"``
        (h = dofs^-1/2, the mean element size of a 2-D mesh; equal to ``"size"`` up to the
        mesh generator's rounding when the whole field is scaled).

    Returns
    -------
    list of float
        len(study) - 1 orders (dimensionless); nan where an error is zero or two levels share
        the same h.
    """
    h, errors = _measures(study, key, measure)
    orders = []
    for k in range(h.size - 1):
        ratio_h = h[k] / h[k + 1]
        if errors[k] > 0 and errors[k + 1] > 0 and ratio_h != 1.0:
            orders.append(math.log(errors[k] / errors[k + 1]) / math.log(ratio_h))
        else:
            orders.append(math.nan)
    return orders


def fitted_order(study: Sequence[dict], key: str, *, measure: str = "size") -> float:
    """Least-squares slope p of log(error) against log(h) over all levels (error ~ h^p).

    Parameters
    ----------
    study, key, measure
        As for :func:`observed_orders`.

    Returns
    -------
    float
        The order (dimensionless); nan if an error is zero or all levels share one h.
    """
    h, errors = _measures(study, key, measure)
    if np.any(errors <= 0) or np.ptp(np.log(h)) == 0:
        return math.nan
    slope, _ = np.polyfit(np.log(h), np.log(errors), 1)
    return float(slope)
