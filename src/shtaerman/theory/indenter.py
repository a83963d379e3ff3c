"""The axisymmetric power-law indenter z = A r^n."""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike
from scipy.special import gammaln

from ..validation import validate_positive

__all__ = ["PowerLawIndenter", "shape_factor"]


def shape_factor(exponent: float) -> float:
    """Sneddon's factor kappa_n = sqrt(pi) Gamma(n/2 + 1) / Gamma(n/2 + 1/2), dimensionless.

    It relates depth and contact radius, x = kappa_n A a^n (Sneddon 1965, eq. 6.7):
    kappa_1 = pi/2 (cone), kappa_2 = 2 (paraboloid), kappa_{3/2} = 1.5 J1 = 1.797210 (the paper).
    """
    n = validate_positive("exponent", exponent)
    return math.sqrt(math.pi) * math.exp(gammaln(n / 2 + 1) - gammaln(n / 2 + 0.5))


@dataclass(frozen=True)
class PowerLawIndenter:
    """A rigid-or-elastic striker whose surface near the first contact point is z = A r^n.

    Parameters
    ----------
    shape_coefficient : float
        A in m^(1-n) (the paper: A = 5 m^-1/2 for n = 3/2; Hertz: A = 1/(2R)).
    exponent : float
        n > 0: n = 1 cone, n = 3/2 the paper's singular point, n = 2 paraboloid (Hertz).
    """

    shape_coefficient: float
    exponent: float

    def __post_init__(self) -> None:
        validate_positive("shape_coefficient", self.shape_coefficient, "m^(1-n)")
        validate_positive("exponent", self.exponent)

    @classmethod
    def sphere(cls, radius: float) -> PowerLawIndenter:
        """The Hertz paraboloid z = r^2 / (2R) of a sphere of radius ``radius`` in m."""
        return cls(1.0 / (2.0 * validate_positive("radius", radius, "m")), 2.0)

    @property
    def kappa(self) -> float:
        """Sneddon's factor kappa_n (see :func:`shape_factor`)."""
        return shape_factor(self.exponent)

    def profile(self, radius: ArrayLike) -> np.ndarray:
        """Height of the striker's surface above its tip, A r^n, in m at radius r in m."""
        return self.shape_coefficient * np.abs(np.asarray(radius, dtype=float)) ** self.exponent
