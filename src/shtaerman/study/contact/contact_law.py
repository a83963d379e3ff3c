"""Contact laws made from FEM results, for the impact model.

The FEM presses a rigid indenter; for an elastic striker the force and pressures scale by
E*/E*_rigid at the same contact radius (applied here). Between the computed depths the curves
are interpolated linearly in log-log coordinates and extrapolated with the nearest interval's
slope (benchmarks/FEM_NOTES.md, "Study error estimates").
"""

from __future__ import annotations

import math
from bisect import bisect_left
from dataclasses import dataclass
from functools import cached_property

import numpy as np
from numpy.typing import ArrayLike

from .indentation import IndentationResult

__all__ = ["FemContactLaw", "fem_contact_law"]


@dataclass(frozen=True)
class _LogLog:
    """Piecewise power-law interpolation through (nodes, values), end slopes extrapolated.

    The logarithms and slopes are taken once: the impact ODE and its energy quadrature
    evaluate the law one depth a call, many times an impact.
    """

    log_nodes: np.ndarray
    log_values: np.ndarray
    slopes: np.ndarray

    @classmethod
    def through(cls, nodes: np.ndarray, values: np.ndarray) -> _LogLog:
        """The interpolant of positive values at positive, increasing nodes."""
        log_nodes, log_values = np.log(nodes), np.log(values)
        return cls(log_nodes, log_values, np.diff(log_values) / np.diff(log_nodes))

    def __call__(self, x: ArrayLike) -> np.ndarray:
        """Values at x (nodes' units), 0 where x <= 0; an array of x's shape."""
        x = np.asarray(x, dtype=float)
        if x.ndim == 0:  # the ODE's right-hand side: one depth per call
            depth = float(x)
            return self._at(depth) if depth > 0 else np.zeros_like(x)
        out = np.zeros_like(x)
        positive = x > 0
        log_x = np.log(x[positive])
        index = np.clip(np.searchsorted(self.log_nodes, log_x) - 1, 0, self.slopes.size - 1)
        out[positive] = self._power(log_x, index)
        return out

    @cached_property
    def _floats(self) -> tuple[list[float], list[float], list[float]]:
        """The nodes' logarithms, the values' and the slopes as Python floats."""
        return self.log_nodes.tolist(), self.log_values.tolist(), self.slopes.tolist()

    def _at(self, x: float) -> np.float64:
        """The value at one depth x > 0, in plain floats (4.3 -> 1.3 us a call) with the
        array path's numpy log and exp: the same rounding, bit for bit."""
        log_nodes, log_values, slopes = self._floats
        log_x = float(np.log(x))
        index = min(max(bisect_left(log_nodes, log_x) - 1, 0), len(slopes) - 1)
        return np.exp(log_values[index] + slopes[index] * (log_x - log_nodes[index]))

    def _power(self, log_x: np.ndarray, index: np.ndarray | int) -> np.ndarray:
        return np.exp(self.log_values[index] + self.slopes[index] * (log_x - self.log_nodes[index]))


@dataclass(frozen=True)
class FemContactLaw:
    """P(x), a(x), p(0, x) from the FEM steps, and the power-law fit P = beta x^q (SI units).

    Satisfies :class:`shtaerman.theory.impact.ContactLaw` (with the fitted beta and q), so the exact
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
        return self._force(depth)

    def contact_radius(self, depth: ArrayLike) -> np.ndarray:
        """FEM contact radius in m at depth x in m."""
        return self._radius(depth)

    def central_pressure(self, depth: ArrayLike) -> np.ndarray:
        """FEM central pressure in Pa at depth x in m."""
        return self._pressure(depth)

    @property
    def central_to_mean_ratio(self) -> float:
        """p(0)/p_avg = p(0) pi a^2 / P at the deepest FEM step: finite (the FEM's central
        pressure is a nodal value), depth dependent unlike the power law's."""
        return float(self.central_pressures[-1] * math.pi * self.radii[-1] ** 2 / self.forces[-1])

    @cached_property
    def _force(self) -> _LogLog:
        return _LogLog.through(self.depths, self.forces)

    @cached_property
    def _radius(self) -> _LogLog:
        return _LogLog.through(self.depths, self.radii)

    @cached_property
    def _pressure(self) -> _LogLog:
        return _LogLog.through(self.depths, self.central_pressures)


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
