"""Absorbing layer for the truncated half-space: mass-proportional damping growing with distance.

Optional (off by default, see ``DynamicSettings.layer_rate``): the graded mesh extends 10^4
refined radii, far enough that nothing returns during an impact. When used, the layer follows
Semblat, Lenti and Gandomzadeh 2011 ("a simple multi-directional absorbing layer method"):
from the radius R_a outward the body gets a viscous damping force -rho zeta(R) v, either a
sin^2 bump of finite width (the default shape) or

    zeta(R) = zeta_max min(1, (R - R_a) / L)^2,   R = sqrt(r^2 + z^2),

a quadratic ramp over one shear wavelength L = c_s t_y (smooth, so the ramp itself reflects
little), then constant. A wave entering the plateau decays by exp(-zeta_max / (2 c)) per metre.

Mass-proportional damping leaves the stiffness untouched: the static response of the
truncated body is exactly that of the undamped one. But at nu = 0.5 the pressure is
instantaneous (c_p infinite): the quasi-static near field has a velocity ~ dP/dt / (G R) at
every distance, and a layer damps it too, whatever its distance; hence no layer by default.
Lysmer-Kuhlemeyer dashpots carry a normal impedance rho c_p that is infinite at nu = 0.5 (a
rigid normal constraint): only their tangential part absorbs.

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
        zeta_max in 1/s, the plateau (or bump peak) damping rate.
    width : float or None
        W in m: a bump zeta = zeta_max sin^2(pi (R - R_a) / W) on R_a < R < R_a + W, zero
        beyond; None: the ramp-plateau profile.
    lateral : bool
        True: R is the radius r alone (the lateral absorber of a layer on a rigid base, whose
        base reflects); False: R = sqrt(r^2 + z^2).
    """

    start: float
    ramp: float
    rate: float
    width: float | None = None
    lateral: bool = False

    def damping_rate(self, r: np.ndarray, z: np.ndarray) -> np.ndarray:
        """zeta(R) in 1/s at points (r, z) in m."""
        distance = np.abs(r) if self.lateral else np.hypot(r, z)
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
