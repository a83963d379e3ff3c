"""The bonded (no-slip) indenter's exact incremental law (docs/theory.md, "Friction at the
indenter").

Under a monotone load each depth increment of a no-slip contact is a rigid flat punch of the
current radius a bonded to the half-space, whose stiffness Mossakovskii (1954) found:
dP/dd = 2 E* a chi(nu), chi(nu) = (1 - nu) ln(3 - 4 nu) / (1 - 2 nu) (ln 3 = 1.0986 at nu = 0,
1.0286 at 0.3, 1 at 0.5; Borodich and Keer 2004: independent of the punch's shape). For the
self-similar z = A r^n (Spence 1968) the force is then P = 2 E* chi a d n / (n + 1): the ratio
P (n + 1) / (2 E* a d n) equals chi at every depth (1, Shtaerman's, for the frictionless
indenter). Neither P(d) nor a(d) of the bonded indenter has a closed form; this identity does.
"""

from __future__ import annotations

import math

import numpy as np
from numpy.typing import ArrayLike

__all__ = ["bonded_punch_factor", "no_slip_ratio"]


def bonded_punch_factor(poisson_ratio: float) -> float:
    """Mossakovskii's chi(nu) = (1 - nu) ln(3 - 4 nu) / (1 - 2 nu): the bonded flat punch's
    force over the frictionless one (dimensionless; 1 at nu = 0.5, its limit)."""
    nu = float(poisson_ratio)
    if nu == 0.5:
        return 1.0
    return (1.0 - nu) * math.log(3.0 - 4.0 * nu) / (1.0 - 2.0 * nu)


def no_slip_ratio(
    force: ArrayLike, contact_radius: ArrayLike, depth: ArrayLike, modulus: float, exponent: float
) -> np.ndarray:
    """P (n + 1) / (2 E* a d n) of z = A r^n: :func:`bonded_punch_factor` for a no-slip
    indenter, 1 for a frictionless one (dimensionless).

    Parameters
    ----------
    force, contact_radius, depth : array_like
        P in N, a and d in m, per depth.
    modulus : float
        E* of the half-space in Pa.
    exponent : float
        n of the profile.
    """
    n = float(exponent)
    a, d = np.asarray(contact_radius, dtype=float), np.asarray(depth, dtype=float)
    return np.asarray(force, dtype=float) * (n + 1.0) / (2.0 * modulus * a * d * n)
