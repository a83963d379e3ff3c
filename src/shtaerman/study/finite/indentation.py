"""The finite-strain (neo-Hookean) indentation test: run it and report it like the linear one.

:func:`shtaerman.fem.contact.finite.run_finite_indentation` does the computing; this module
adds the power-law fit and the JSON of ``shtaerman contact --model neo-hookean``: the linear
report's keys, with ``model``, per-step ``strain_energy`` (J) and ``newton_iterations``, and the
departures from Shtaerman's linear solution in place of errors; :func:`shtaerman.contact` runs it
on the three meshes of :func:`shtaerman.study.contact.accuracy.run_mesh_ladder` for Richardson
error estimates.
"""

from __future__ import annotations

import functools
import warnings
from dataclasses import dataclass, field, replace

from numpy.typing import ArrayLike

from ...fem.contact.finite import (
    FINITE_MESH,
    FiniteContactCurve,
    FiniteContactStep,
    run_finite_indentation,
)
from ...fem.contact.finite_stick import solve_finite_bonded_contact
from ...fem.fit import PowerLawFit, fit_power_law
from ...fem.mesh import HALF_SPACE, Geometry, MeshSettings
from ...fem.rubber import RubberModel
from ...theory.contact import PowerLawContact
from ...theory.indenter import PowerLawIndenter
from ...theory.materials import RIGID, Material, effective_modulus
from ...theory.sneddon import Indenter, SneddonContact, contact_law
from ...validation import caller_stacklevel
from ..contact.accuracy import ORDERS
from ..contact.indentation import (
    CurveResult,
    curve_document,
    default_depths,
    interface_stats,
    worst_against_analytic,
)
from ..dynamic.accuracy import RetriedWarning
from .accuracy import EDGE_ORDER

__all__ = ["CURVE_ORDERS", "FiniteIndentationResult", "run_finite_study"]

CURVE_ORDERS = {**ORDERS, "contact_radius": EDGE_ORDER}
"""The orders of the curve's error estimates (:func:`.contact.accuracy.estimate_errors`):
the linear contact's, but the contact radius at the edge's first order, as the finite-strain
study's (benchmarks/FEM_NOTES.md, "Finite-strain curve per depth")."""


@dataclass(frozen=True)
class FiniteIndentationResult(CurveResult):
    """Finite-strain contact curve of a power-law indenter beside the linear exact solution."""

    indenter: Indenter
    half_space: Material
    exact: PowerLawContact | SneddonContact
    curve: FiniteContactCurve
    fit: PowerLawFit
    rubber: RubberModel = field(default_factory=RubberModel)

    @property
    def steps(self) -> list[FiniteContactStep]:
        """The converged contact at each depth (as :attr:`.IndentationResult.steps`)."""
        return self.curve.steps

    @property
    def mesh_stats(self) -> dict[str, float]:
        """``dofs``, ``nodes``, radii in m ... (as :attr:`.IndentationResult.mesh_stats`)."""
        return self.curve.mesh_stats

    @property
    def timings(self) -> dict[str, float]:
        """Seconds per stage, ``total`` included."""
        return self.curve.timings

    def step_table(self) -> list[dict[str, float]]:
        """Per depth: force, contact radius, central pressure, energy, and the linear values."""
        return [
            {
                "depth": s.depth,
                "force": s.force,
                "contact_radius": s.contact_radius,
                "central_pressure": s.central_pressure,
                "strain_energy": s.strain_energy,
                "force_analytic": s.force_linear,
                "contact_radius_analytic": s.contact_radius_linear,
                "central_pressure_analytic": s.central_pressure_linear,
                "central_to_mean": s.central_pressure / s.mean_pressure,
                "newton_iterations": s.newton_iterations,
            }
            for s in self.curve.steps
        ]

    def departures(self) -> dict[str, float]:
        """Largest |finite / linear - 1| over the depths (not errors: the physics differs)."""
        return worst_against_analytic(self.step_table())

    def to_dict_model(self) -> dict[str, object]:
        """``model``, and the other rubber keys unless it is the default neo-Hookean."""
        return {"model": "neo-hookean"} if self.rubber == RubberModel() else self.rubber.to_dict()

    def to_dict(self) -> dict[str, object]:
        """The JSON of ``shtaerman contact --model neo-hookean --json`` (SI units): ``model``,
        then the other rubber keys (:meth:`RubberModel.to_dict`) unless it is the default;
        a bonded or Coulomb curve's ``load_steps_cut`` (in halves, where they failed)."""
        cuts = self.curve.cuts
        return {
            **self.to_dict_model(),
            **curve_document(self.indenter, self.half_space, self.exact, self.fit, self.depths),
            "steps": self.step_table(),
            "departures_from_linear": self.departures(),
            "mesh": self.curve.mesh_stats,
            **({} if cuts is None else {"load_steps_cut": cuts}),
            "solver": "superlu",
            "timings": self.curve.timings,
        }


def run_finite_study(
    indenter: PowerLawIndenter,
    half_space: Material,
    depths: ArrayLike | None = None,
    mesh: MeshSettings | None = None,
    rubber: RubberModel | None = None,
    friction: float | None = None,
    geometry: Geometry = HALF_SPACE,
) -> FiniteIndentationResult:
    """Press a rigid power-law indenter into a rubber half-space (or the layer of
    ``geometry``); compare with linear.

    Parameters
    ----------
    indenter : PowerLawIndenter
        z = A r^n, n > 1.
    half_space : Material
        E2 (Pa) and nu2 in [0, 0.5], the small-strain constants of the neo-Hookean solid.
    depths : array_like, optional
        Any increasing depths in m (load stepping is internal); default the linear test's
        eight depths up to the paper's impact x_c.
    mesh : MeshSettings, optional
        Default :data:`shtaerman.fem.mesh.FINITE_MESH`.
    rubber : RubberModel, optional
        Default neo-Hookean with the quadratic volumetric energy.
    friction : float, optional
        The indenter's surface (:attr:`shtaerman.problem.Interface.coefficient`): None
        frictionless; else the rubber sticks where it touches, ``math.inf`` for good, mu >= 0
        until Coulomb's limit
        (:func:`shtaerman.fem.contact.finite_stick.solve_finite_bonded_contact`).

    Returns
    -------
    FiniteIndentationResult

    Warns
    -----
    RetriedWarning
        Some load steps of a bonded or Coulomb curve were cut in halves where they failed
        (:func:`shtaerman.fem.contact.finite_stick.solve_finite_bonded_contact`).
    """
    depths = default_depths(indenter, half_space) if depths is None else depths
    rubber = RubberModel() if rubber is None else rubber
    mesh = mesh or FINITE_MESH
    bonded = None
    if friction is not None:
        bonded = functools.partial(solve_finite_bonded_contact, friction=friction)
    curve = run_finite_indentation(indenter, half_space, depths, mesh, rubber, bonded, geometry)
    curve = replace(curve, mesh_stats=curve.mesh_stats | interface_stats(friction))
    if curve.cuts:
        dofs = curve.mesh_stats["dofs"]
        warnings.warn(
            f"retried: {curve.cuts} of the load steps cut in halves where the contact "
            f"failed (mesh of {dofs} dofs; the result is of the steps it passed with)",
            RetriedWarning,
            stacklevel=caller_stacklevel(),
        )
    exact = contact_law(indenter, effective_modulus(RIGID, half_space))
    forces = [s.force for s in curve.steps]
    fit = fit_power_law([s.depth for s in curve.steps], forces, exact.force_exponent)
    return FiniteIndentationResult(indenter, half_space, exact, curve, fit, rubber)
