"""The axisymmetric power-law indenter z = A r^n."""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike
from scipy.special import gammaln

from ..validation import InputError, validate_positive
from ..vocabulary import MAX_EXPONENT, MIN_EXPONENT

__all__ = ["PowerLawIndenter", "shape_factor", "validate_exponent"]


def validate_exponent(exponent: object, name: str = "exponent") -> float:
    """Return the profile exponent n, or raise unless MIN_EXPONENT <= n <= MAX_EXPONENT.

    Why [0.25, 20]: the force law P = beta x^q has q = (n+1)/n, so n -> 0 (a needle) makes
    q blow up (q = 1001 at n = 1e-3, where beta = (kappa A)^(-1/n) underflows to 0 for any
    A > 1) and n -> inf is a flat punch (q -> 1, a jump in force the power law cannot carry).
    [0.25, 20] keeps q in [1.05, 5] and beta representable for every A in [1e-15, 1e15]
    (|log10(kappa A)| / n <= 60), covering cones (n = 1), the paper's n = 3/2 and Hertz (2).
    """
    n = validate_positive(name, exponent)
    if not MIN_EXPONENT <= n <= MAX_EXPONENT:
        raise InputError(
            f"{name} must lie in [{MIN_EXPONENT:g}, {MAX_EXPONENT:g}] (force law x^((n+1)/n) "
            f"with (n+1)/n in [1.05, 5]), got {exponent!r}"
        )
    return n


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

    kind = "power-law"

    def __post_init__(self) -> None:
        validate_positive("shape_coefficient", self.shape_coefficient, "m^(1-n)")
        validate_exponent(self.exponent)

    @classmethod
    def sphere(cls, radius: float) -> PowerLawIndenter:
        """The Hertz paraboloid z = r^2 / (2R) of a sphere of radius ``radius`` in m."""
        return cls(1.0 / (2.0 * validate_positive("radius", radius, "m")), 2.0)

    @property
    def kappa(self) -> float:
        """Sneddon's factor kappa_n (see :func:`shape_factor`)."""
        return shape_factor(self.exponent)

    @property
    def parameters(self) -> dict[str, float]:
        """The JSON's ``profile.parameters``: shape_coefficient A in m^(1-n) and exponent n."""
        return {"shape_coefficient": self.shape_coefficient, "exponent": self.exponent}

    def profile(self, radius: ArrayLike) -> np.ndarray:
        """Height of the striker's surface above its tip, A r^n, in m at radius r in m."""
        return self.shape_coefficient * np.abs(np.asarray(radius, dtype=float)) ** self.exponent

    def slope(self, radius: ArrayLike) -> np.ndarray:
        """f'(r) = n A r^(n-1) (dimensionless) at radii r >= 0 in m."""
        r = np.asarray(radius, dtype=float)
        return self.exponent * self.shape_coefficient * r ** (self.exponent - 1.0)

    def curvature(self, radius: ArrayLike) -> np.ndarray:
        """f''(r) = n (n-1) A r^(n-2) in 1/m at radii r >= 0 in m (0 on the axis, where the
        finite-strain contact never uses it)."""
        r = np.asarray(radius, dtype=float)
        n, A = self.exponent, self.shape_coefficient
        curvature = np.zeros_like(r)
        inside = r > 0
        curvature[inside] = n * (n - 1.0) * A * r[inside] ** (n - 2.0)
        return curvature

    def radius_at(self, height: ArrayLike) -> np.ndarray:
        """The radius (h/A)^(1/n) in m at which the profile reaches a height h in m."""
        h = np.asarray(height, dtype=float)
        return (h / self.shape_coefficient) ** (1.0 / self.exponent)
