"""Isotropic elastic materials and the combined contact modulus E*."""

from __future__ import annotations

import math
from dataclasses import dataclass

from ..validation import validate_poisson, validate_positive

__all__ = ["RIGID", "Material", "effective_modulus"]


@dataclass(frozen=True)
class Material:
    """An isotropic linear-elastic material.

    Parameters
    ----------
    youngs_modulus : float
        Young's modulus E in Pa; ``math.inf`` for a rigid body.
    poisson_ratio : float
        Poisson's ratio nu in (-1, 0.5]; 0.5 is incompressible (the paper's rubber).
    """

    youngs_modulus: float
    poisson_ratio: float

    def __post_init__(self) -> None:
        rigid = not isinstance(self.youngs_modulus, bool) and self.youngs_modulus == math.inf
        if not rigid:
            validate_positive("youngs_modulus", self.youngs_modulus, "Pa (or math.inf: rigid)")
        validate_poisson("poisson_ratio", self.poisson_ratio)

    @property
    def compliance(self) -> float:
        """Contact compliance Q = (1 - nu^2) / E in 1/Pa (0 for a rigid body)."""
        return (1.0 - self.poisson_ratio**2) / self.youngs_modulus

    @property
    def shear_modulus(self) -> float:
        """Shear modulus mu = E / (2 (1 + nu)) in Pa."""
        return self.youngs_modulus / (2.0 * (1.0 + self.poisson_ratio))


RIGID = Material(math.inf, 0.0)
"""A rigid body: Q = 0."""


def effective_modulus(striker: Material, half_space: Material) -> float:
    """Combined modulus E* in Pa, with 1/E* = Q1 + Q2 and Q = (1 - nu^2)/E.

    Parameters
    ----------
    striker, half_space : Material
        The two bodies; either may be :data:`RIGID`, not both.

    Returns
    -------
    float
        E* in Pa.
    """
    total = striker.compliance + half_space.compliance
    if total == 0.0:
        raise ValueError("two rigid bodies have no contact compliance")
    return 1.0 / total
