"""The FEM indentation test: mesh, assemble, press a power-law indenter, compare with theory.

A rigid indenter z = A r^n is pressed into the half-space (E2, nu2) to a list of depths; each
depth's force, contact radius and central pressure are compared with Shtaerman's exact solution
(:mod:`shtaerman.theory.contact`, with E* = E2/(1 - nu2^2) for the rigid indenter), and the
curve P(x) is fitted by a power law.
"""

from __future__ import annotations

import math
import sys
import time
from dataclasses import dataclass, field
from functools import cached_property
from typing import NamedTuple

import numpy as np
from numpy.typing import ArrayLike

from ...fem.contact.constraints import UnresolvedContactError
from ...fem.contact.linear import ContactCurve, ContactStep, solve_contact
from ...fem.contact.stick import solve_bonded_contact
from ...fem.elasticity import ElasticSolution, ElasticSystem, assemble
from ...fem.fit import PowerLawFit, fit_power_law
from ...fem.mesh import HALF_SPACE, Geometry, MeshSettings
from ...theory.contact import PowerLawContact
from ...theory.impact import solve_impact
from ...theory.indenter import PowerLawIndenter
from ...theory.materials import RIGID, Material, effective_modulus
from ...theory.profile_impact import solve_profile_impact
from ...theory.sneddon import Indenter, SneddonContact, contact_law
from ...theory.viscoelastic import PronySeries, RateContact
from ...validation import InputError
from ...vocabulary import entry

__all__ = [
    "IndentationResult",
    "default_depths",
    "depths_up_to",
    "interface_stats",
    "refined_radius",
    "run_indentation",
]

DEFAULT_STEPS = 8
DEFAULT_RADIUS_SPAN = 3.0
"""The default depths span contact radii a_c/3 .. a_c."""


def depths_up_to(deepest: float, exponent: float) -> np.ndarray:
    """Eight depths (m) up to ``deepest``, geometric, contact radii spanning a factor of 3.

    Radii go as depth^(1/n), so the depths span 3^n for an indenter exponent n.
    """
    span = DEFAULT_RADIUS_SPAN**exponent
    return deepest * np.geomspace(1.0 / span, 1.0, DEFAULT_STEPS)


def default_depths(
    indenter: Indenter,
    half_space: Material,
    mass: float | None = None,
    velocity: float | None = None,
    striker: Material = RIGID,
    overshoot: float = 1.0,
) -> np.ndarray:
    """Eight depths (m) up to ``overshoot`` times the x_c of the impact of ``mass`` (kg) at
    ``velocity`` (m/s) by ``striker`` (defaults: the vocabulary's, the paper's 0.7 kg at
    3 m/s, rigid), radii a/3 .. a at the deepest (another profile than the power law: the
    depths of those radii)."""
    mass = entry("mass").default if mass is None else mass
    velocity = entry("velocity").default if velocity is None else velocity
    law = contact_law(indenter, effective_modulus(striker, half_space))
    if isinstance(law, SneddonContact):
        a_c = solve_profile_impact(mass, velocity, law).a_c
        if overshoot != 1.0:
            a_c = float(law.contact_radius(overshoot * law.depth(a_c)))
        return law.depth(a_c * np.geomspace(1.0 / DEFAULT_RADIUS_SPAN, 1.0, DEFAULT_STEPS))
    x_c = solve_impact(mass, velocity, law).x_c
    return depths_up_to(overshoot * x_c, indenter.exponent)


class CurveResult:
    """What a contact curve result (its ``steps`` and its ``exact`` law) gives at its depths."""

    @property
    def analytic(self) -> AnalyticFit:
        """The power law's exact beta and q; another profile's, or Lee-Radok's, exact forces
        at the curve's depths fitted as the FEM's are (beta at the elastic q held, the
        exponent free: that force law is no power law)."""
        return exact_fit(self.exact, self.depths)

    @property
    def depths(self) -> np.ndarray:
        """The depths in m."""
        return np.array([step.depth for step in self.steps])


@dataclass(frozen=True)
class IndentationResult(CurveResult):
    """FEM contact curve of an indenter against the exact solution (SI units)."""

    indenter: Indenter
    half_space: Material
    exact: PowerLawContact | SneddonContact | RateContact
    curve: ContactCurve
    fit: PowerLawFit
    mesh_stats: dict[str, float]
    timings: dict[str, float] = field(default_factory=dict)

    @property
    def steps(self) -> list[ContactStep]:
        """The contact at each depth."""
        return self.curve.steps

    def field(self, index: int = -1) -> ElasticSolution:
        """Displacements and stresses at step ``index`` (the deepest, computed once, by default).

        Raises
        ------
        shtaerman.validation.InputError
            If there is no such step.
        """
        count = len(self.steps)
        if not -count <= index < count:
            raise InputError(f"step must lie in [{-count}, {count - 1}], got {index!r}")
        return self.deepest_field if index in (-1, count - 1) else self.curve.field_solution(index)

    @cached_property
    def deepest_field(self) -> ElasticSolution:
        """The fields at the largest depth (VTU export and every field picture share them)."""
        return self.curve.field_solution(-1)

    def step_table(self) -> list[dict[str, float]]:
        """Per depth: FEM and exact force, contact radius, central pressure, and ratios."""
        return self._rows

    @cached_property
    def _rows(self) -> list[dict[str, float]]:
        rows = []
        for step in self.steps:
            exact = self._exact(step.depth)
            rows.append(
                {
                    "depth": step.depth,
                    "force": step.force,
                    "contact_radius": step.contact_radius,
                    "central_pressure": step.central_pressure,
                    "strain_energy": self.strain_energy(step),
                    "force_analytic": exact["force"],
                    "contact_radius_analytic": exact["contact_radius"],
                    "central_pressure_analytic": exact["central_pressure"],
                    "central_to_mean": step.central_pressure / step.mean_pressure,
                    "pressure_profile_error": self.pressure_profile_error(step),
                    "active_set_iterations": step.iterations,
                    "force_nodal_sum": step.discrete_force,
                }
            )
        return rows

    def strain_energy(self, step: ContactStep) -> float:
        """Stored energy in J: W = 1/2 u . f = 1/2 sum F_i (d - f(r_i)).

        At a loaded node the surface sits on the indenter, u_z = f(r_i) - d, under the
        downward force F_i; elsewhere F_i = 0.
        """
        r = self.curve.compliance.r
        lift = step.depth - np.asarray(self.indenter.profile(r), dtype=float)
        return float(0.5 * np.sum(step.nodal_forces * lift))

    def _exact(self, depth: float) -> dict[str, float]:
        return {
            "force": float(self.exact.force(depth)),
            "contact_radius": float(self.exact.contact_radius(depth)),
            "central_pressure": float(self.exact.central_pressure(depth)),
        }

    def pressure_profile_error(self, step: ContactStep) -> float:
        """Relative r-weighted L2 error of the nodal pressure, ||p_h - p|| / ||p||."""
        r = self.curve.compliance.r
        exact = self.exact.pressure(r, step.depth)
        weight = np.gradient(r) * r
        return float(
            np.sqrt(np.sum(weight * (step.pressure - exact) ** 2) / np.sum(weight * exact**2))
        )

    def errors(self) -> dict[str, float]:
        """Largest relative errors against the exact solution over all depths."""
        rows = self.step_table()
        return {
            **worst_against_analytic(rows),
            "beta": abs(self.fit.beta_fixed_exponent / self.analytic.beta - 1.0),
            "exponent": abs(self.fit.exponent / self.analytic.exponent - 1.0),
            "pressure_profile": max(row["pressure_profile_error"] for row in rows),
        }

    def to_dict(self) -> dict[str, object]:
        """The JSON of ``shtaerman contact --json`` (its keys are an interface other tools use)."""
        relaxing = {}
        if isinstance(self.exact, RateContact):  # Lee-Radok's *_analytic
            series = self.exact.prony
            terms = zip(series.weights, series.times, strict=True)
            relaxing = {"prony": ",".join(f"{g!r}:{tau!r}" for g, tau in terms)}
            relaxing["rate"] = self.exact.rate
        return {
            "model": "linear",
            **curve_document(self.indenter, self.half_space, self.exact, self.fit, self.depths),
            **relaxing,
            "steps": self.step_table(),
            "errors": self.errors(),
            "mesh": self.mesh_stats,
            "solver": self.curve.backend,
            "timings": self.timings,
        }


STEP_QUANTITIES = ("force", "contact_radius", "central_pressure")
"""Per-depth quantities that step tables give beside their ``*_analytic`` values."""


def worst_against_analytic(rows: list[dict[str, float]]) -> dict[str, float]:
    """Largest |value / analytic - 1| over the rows of a step table, per quantity."""
    return {
        key: max(abs(row[key] / row[f"{key}_analytic"] - 1.0) for row in rows)
        for key in STEP_QUANTITIES
    }


class AnalyticFit(NamedTuple):
    """The exact force law in the form the FEM curve is fitted: beta (N m^-q) with q held at
    ``force_exponent``, and the free exponent."""

    beta: float
    exponent: float


def exact_fit(exact: object, depths: np.ndarray) -> AnalyticFit:
    """The exact beta and exponent of ``exact`` at ``depths`` (m): see
    :attr:`IndentationResult.analytic`."""
    if isinstance(exact, PowerLawContact):
        return AnalyticFit(exact.beta, exact.force_exponent)
    fit = fit_power_law(depths, exact.force(depths), exact.force_exponent)
    exponent = fit.exponent if np.size(depths) > 1 else exact.force_exponent
    return AnalyticFit(fit.beta_fixed_exponent, exponent)


def curve_document(
    indenter: Indenter,
    half_space: Material,
    exact: PowerLawContact | SneddonContact | RateContact,
    fit: PowerLawFit,
    depths: np.ndarray | None = None,
) -> dict[str, object]:
    """The inputs and the fitted force law beside the exact one: the head of the ``contact``
    JSON, shared by the linear and the neo-Hookean model (SI units). For another profile
    than the power law ``shape_coefficient`` and ``exponent`` are None, and the analytic
    beta and exponent are the exact forces at the same ``depths`` fitted as the FEM's."""
    analytic = exact_fit(exact, depths)
    power_law = isinstance(indenter, PowerLawIndenter)
    return {
        "shape_coefficient": indenter.shape_coefficient if power_law else None,
        "exponent": indenter.exponent if power_law else None,
        "profile": {"kind": indenter.kind, "parameters": indenter.parameters},
        "E2": half_space.youngs_modulus,
        "nu2": half_space.poisson_ratio,
        "modulus": exact.modulus,
        "beta_fem": fit.beta_fixed_exponent,
        "beta_analytic": analytic.beta,
        "exponent_fem": fit.exponent,
        "exponent_analytic": analytic.exponent,
        "beta_fem_free_exponent": fit.beta,
        "central_to_mean_analytic": exact.central_to_mean_ratio,
    }


def check_force_range(indenter: Indenter, body: Material, depths: ArrayLike) -> None:
    """Refuse given ``depths`` (m, increasing) whose exact force (Shtaerman's or Sneddon's, on
    the rigid striker pressed into ``body``) leaves the normal floating-point range: the FE
    system's numbers underflow or overflow there; the command line's and the study file's
    check."""
    law = contact_law(indenter, effective_modulus(RIGID, body))
    depths = np.atleast_1d(np.asarray(depths, dtype=float))
    for depth in (depths[0], depths[-1]):
        with np.errstate(all="ignore"):  # an overflow is the refusal's, not a warning
            force = float(law.force(depth))
        if not sys.float_info.min <= force <= sys.float_info.max:
            raise InputError(
                f"depths: {depth:g} m gives a contact force of {force:.3g} N, outside the "
                f"floating-point range [{sys.float_info.min:.3g}, {sys.float_info.max:.3g}] "
                "the FEM computes in; give depths of a physical size",
                "depths",
            )


def refined_radius(
    indenter: Indenter, depths: np.ndarray, mesh: MeshSettings, geometry: Geometry = HALF_SPACE
) -> float:
    """Radius in m of the refined (contact candidate) zone of a curve to ``depths`` (m): the
    margin times the radius where the profile reaches the deepest depth (on the layer of
    ``geometry``, times its bulge, that of the smooth tip n = 2 for another profile than the
    power law)."""
    exponent = indenter.exponent if isinstance(indenter, PowerLawIndenter) else 2.0
    zone = geometry.zone_factor(exponent)  # 1 on the half-space
    return mesh.margin * float(indenter.radius_at(depths[-1])) * zone


def interface_stats(friction: float | None) -> dict[str, object]:
    """The mesh statistics' ``interface`` and ``friction`` of a curve pressed with the
    solvers' ``friction`` (None: none, the frictionless surface; ``math.inf``: bonded)."""
    if friction is None:
        return {}
    return {"interface": "bonded"} | ({} if math.isinf(friction) else {"friction": friction})


def _pressed(
    system: ElasticSystem,
    indenter: Indenter,
    depths: np.ndarray,
    refined: float,
    backend: str,
    aligned: bool,
    prony: PronySeries | None,
    rate: float | None,
    friction: float | None,
) -> ContactCurve:
    """The FEM contact curve of :func:`run_indentation` (its arguments; ``refined``: the
    radius in m of the contact candidates)."""
    if prony is not None:
        from ...fem.contact.rate import press_at_rate

        return press_at_rate(
            system, indenter.profile, depths, refined, prony, rate, backend=backend, aligned=False
        )
    if friction not in (None, 0.0):  # mu = 0 is frictionless
        return solve_bonded_contact(
            system, indenter.profile, depths, refined, backend=backend, friction=friction
        )
    return solve_contact(
        system, indenter.profile, depths, refined, backend=backend, aligned=aligned
    )


def run_indentation(
    indenter: Indenter,
    half_space: Material,
    depths: ArrayLike | None = None,
    mesh: MeshSettings | None = None,
    *,
    backend: str = "auto",
    aligned: bool = True,
    prony: PronySeries | None = None,
    rate: float | None = None,
    friction: float | None = None,
    geometry: Geometry = HALF_SPACE,
) -> IndentationResult:
    """Press a rigid indenter into the FEM half-space (or the layer of ``geometry``) and
    compare with the theory.

    Parameters
    ----------
    indenter : PowerLawIndenter, SphereIndenter or TabulatedIndenter
        Profile z = A r^n, n > 1 (bounded pressure at the centre), compared with Shtaerman;
        or the exact sphere or a tabulated z(r), compared with Sneddon
        (:class:`shtaerman.theory.sneddon.SneddonContact`).
    half_space : Material
        E2 in Pa, nu2 in [0, 0.5].
    depths : array_like, optional
        Depths in m, positive and increasing (the entry points check them); default
        :func:`default_depths`.
    mesh : MeshSettings, optional
    backend : str
        Sparse solver ("auto", "superlu", "pardiso").
    aligned : bool
        Forces of the vertex-aligned contacts (default) or nodal sums, see
        :func:`shtaerman.fem.contact.linear.solve_contact`.
    prony : PronySeries, optional
        A viscoelastic body pressed at ``rate`` m/s
        (:func:`shtaerman.fem.contact.rate.press_at_rate`, frictionless, nodal sums:
        the history breaks the vertex-aligned interpolation), compared with Lee and Radok's
        exact curve (:class:`shtaerman.theory.viscoelastic.RateContact`).
    friction : float, optional
        The indenter's surface (:attr:`shtaerman.problem.Interface.coefficient`): None
        frictionless; ``math.inf`` bonded, the surface sticks where it touches
        (:func:`shtaerman.fem.contact.stick.solve_bonded_contact`, nodal sums); else Coulomb's
        mu >= 0, sliding past it (0: the frictionless solve, whose contact it is).

    Returns
    -------
    IndentationResult
    """
    depths = default_depths(indenter, half_space) if depths is None else depths
    depths = np.atleast_1d(np.asarray(depths, dtype=float))  # checked where they entered
    mesh = MeshSettings() if mesh is None else mesh
    refined = refined_radius(indenter, depths, mesh, geometry)
    start = time.perf_counter()
    skfem_mesh = mesh.build(refined, geometry)
    meshed = time.perf_counter()
    system = assemble(skfem_mesh, half_space.youngs_modulus, half_space.poisson_ratio)
    assembled = time.perf_counter()
    try:
        curve = _pressed(system, indenter, depths, refined, backend, aligned, prony, rate, friction)
    except UnresolvedContactError as error:
        if len(depths) < 2 or error.depth >= depths[-1]:
            raise
        raise InputError(
            f"depths: the smallest, {error.depth:g} m, loads {error.loaded} surface node(s), "
            f"fewer than {error.fewest}, on the mesh that the deepest, {depths[-1]:g} m, sizes "
            f"(refined to r = {refined:.3g} m): raise the smallest depth, lower the deepest, "
            "or refine the mesh (mesh_size=..., refine=...)",
            "depths",
        ) from None
    exact = contact_law(indenter, effective_modulus(RIGID, half_space))
    if prony is not None:
        exact = RateContact(exact, prony, rate, tuple(float(d) for d in depths))
    forces = [step.force for step in curve.steps]
    fit = fit_power_law(depths, forces, exact.force_exponent)
    timings = {
        "mesh": meshed - start,
        "assembly": assembled - meshed,
        **curve.timings,
        "total": time.perf_counter() - start,
    }
    stats = {
        "nodes": int(skfem_mesh.p.shape[1]),
        "elements": int(skfem_mesh.t.shape[1]),
        "dofs": int(system.n_dofs),
        "contact_candidates": int(curve.compliance.r.size),
        "refined_radius": refined,
        "domain_radius": mesh.domain * refined,
        "smallest_size": mesh.size * refined,
    }
    thickness = geometry.thickness
    if thickness is not None:  # a layer: force_analytic stays the half-space's
        stats |= {"thickness": thickness, "base": geometry.base}
        stats["domain_radius"] = mesh.lateral_extent(thickness / refined) * refined
    stats |= interface_stats(friction)  # the *_analytic values stay the frictionless ones
    return IndentationResult(indenter, half_space, exact, curve, fit, stats, timings)
