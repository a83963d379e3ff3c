"""Contact laws made from FEM results, for the impact model.

The FEM presses a rigid indenter into the half-space (E*_rigid = E2/(1 - nu2^2)). For an
elastic striker the frictionless contact depends on the two materials only through E*
(1/E* = Q1 + Q2): at a given depth the contact radius is unchanged and the force and pressures
scale by E*/E*_rigid. That factor (1 - 4.7e-5 for steel on the paper's rubber) is applied here.

Between the computed depths the curves are interpolated linearly in log-log coordinates (exact
for a power law), and extrapolated with the slope of the nearest interval (toward x = 0 and a
little past the deepest step), with no assumption about the exponent.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike

from .indentation import IndentationResult

__all__ = ["FemContactLaw", "fem_contact_law"]


def _loglog(x: ArrayLike, nodes: np.ndarray, values: np.ndarray) -> np.ndarray:
    """Piecewise power-law interpolation through (nodes, values), end slopes extrapolated."""
    x = np.asarray(x, dtype=float)
    out = np.zeros_like(x)
    positive = x > 0
    log_x, log_nodes, log_values = np.log(x[positive]), np.log(nodes), np.log(values)
    slopes = np.diff(log_values) / np.diff(log_nodes)
    index = np.clip(np.searchsorted(log_nodes, log_x) - 1, 0, slopes.size - 1)
    out[positive] = np.exp(log_values[index] + slopes[index] * (log_x - log_nodes[index]))
    return out


@dataclass(frozen=True)
class FemContactLaw:
    """P(x), a(x), p(0, x) from the FEM steps, and the power-law fit P = beta x^q (SI units).

    Satisfies :class:`shtaerman.impact.ContactLaw` (with the fitted beta and q), so the exact
    Ateb solution runs on it; :meth:`force` is the tabulated curve for the numerical impact.
    """

    depths: np.ndarray
    forces: np.ndarray
    radii: np.ndarray
    central_pressures: np.ndarray
    beta: float
    """Fitted coefficient (free exponent), scaled to E*, in N m^-q."""
    force_exponent: float
    """Fitted exponent q."""

    def force(self, depth: ArrayLike) -> np.ndarray:
        """Tabulated force in N at depth x in m (no power-law assumption)."""
        return _loglog(depth, self.depths, self.forces)

    def contact_radius(self, depth: ArrayLike) -> np.ndarray:
        """FEM contact radius in m at depth x in m."""
        return _loglog(depth, self.depths, self.radii)

    def central_pressure(self, depth: ArrayLike) -> np.ndarray:
        """FEM central pressure in Pa at depth x in m."""
        return _loglog(depth, self.depths, self.central_pressures)


def fem_contact_law(result: IndentationResult, modulus: float) -> FemContactLaw:
    """The FEM contact law of ``result`` for a striker-half-space pair of combined modulus E*.

    Parameters
    ----------
    result : IndentationResult
        The FEM contact curve (rigid indenter).
    modulus : float
        E* of the impacting pair in Pa.
    """
    scale = modulus / result.exact.modulus
    steps = result.steps
    return FemContactLaw(
        depths=np.array([step.depth for step in steps]),
        forces=scale * np.array([step.force for step in steps]),
        radii=np.array([step.contact_radius for step in steps]),
        central_pressures=scale * np.array([step.central_pressure for step in steps]),
        beta=scale * result.fit.beta,
        force_exponent=result.fit.exponent,
    )
