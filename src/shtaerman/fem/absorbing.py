"""Absorbing layer for the truncated half-space: mass-proportional damping growing with distance.

Waves leaving the contact must not come back. The graded mesh extends far (10^4 refined radii
by default, for the static truncation), so the absorbing device is a layer (Semblat, Lenti and
Gandomzadeh 2011, "a simple multi-directional absorbing layer method"): from the radius R_a
outward the body gets a viscous damping force -rho zeta(R) v with

    zeta(R) = zeta_max min(1, (R - R_a) / L)^2,   R = sqrt(r^2 + z^2),

a quadratic ramp over one shear wavelength L = c_s t_y (smooth, so the ramp itself reflects
little), then constant. A wave entering the plateau decays by exp(-zeta_max / (2 c)) per metre
long before it reaches the coarse elements further out or the clamped far arc.

Mass-proportional damping leaves the stiffness untouched: the static and quasi-static
response of the truncated body is exactly that of the undamped one (the low-density limit is
the static contact), and at nu = 0.5 nothing special is needed. Lysmer-Kuhlemeyer dashpots,
the alternative, carry a normal impedance rho c_p that is infinite at nu = 0.5: the normal
dashpot becomes a rigid constraint (incompressible material transmits pressure instantly, a
normal dashpot cannot absorb what has no finite speed), only the tangential part absorbs.

R_a is placed beyond c_s t_y / 2 (times a safety factor), so no wave reflected at the layer can
return to the contact before the striker separates.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass

import numpy as np

__all__ = ["AbsorbingLayer"]


@dataclass(frozen=True)
class AbsorbingLayer:
    """Damping profile of the absorbing layer (SI units).

    Attributes
    ----------
    start : float
        R_a in m: the damping is zero inside R < R_a.
    ramp : float
        L in m: zeta rises as ((R - R_a)/L)^2 over R_a <= R <= R_a + L.
    rate : float
        zeta_max in 1/s, the plateau damping rate.
    """

    start: float
    ramp: float
    rate: float
    width: float | None = None

    def damping_rate(self, r: np.ndarray, z: np.ndarray) -> np.ndarray:
        """zeta(R) in 1/s at points (r, z) in m."""
        distance = np.hypot(r, z)
        phase = np.clip((distance - self.start) / self.ramp, 0.0, 1.0)
        if self.width is None:
            return self.rate * phase**2
        inside = (distance > self.start) & (distance < self.start + self.width)
        return np.where(
            inside, self.rate * np.sin(np.pi * (distance - self.start) / self.width) ** 2, 0.0
        )

    def weight(self, density: float) -> Callable[[np.ndarray, np.ndarray], np.ndarray]:
        """rho zeta(R) in kg/(m^3 s), the weight of the damping matrix."""
        return lambda r, z: density * self.damping_rate(r, z)
