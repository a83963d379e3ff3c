"""Isotropic elastic materials and the combined contact modulus E*."""

from __future__ import annotations

import math
from dataclasses import dataclass
from numbers import Real

from .. import vocabulary
from ..validation import InputError, shown, validate_poisson, validate_positive

__all__ = ["DENSITY_RANGE", "RIGID", "Material", "effective_modulus", "validate_density"]

_DENSITY = vocabulary.entry("density2").valid
DENSITY_RANGE = (_DENSITY.low, _DENSITY.high)
"""Densities in kg/m^3 a material may have besides 0 (massless): the vocabulary's range of
``density2``."""


@dataclass(frozen=True)
class Material:
    """An isotropic linear-elastic material.

    Parameters
    ----------
    youngs_modulus : float
        Young's modulus E in Pa; ``math.inf`` for a rigid body.
    poisson_ratio : float
        Poisson's ratio nu in (-1, 0.5]; 0.5 is incompressible (the paper's rubber).
    density : float, optional
        Mass density rho in kg/m^3, within :data:`DENSITY_RANGE` or 0 (massless: no inertia);
        needed only where inertia counts (the dynamic impact). None: not given.

    Raises
    ------
    shtaerman.validation.InputError
        If a value lies outside its range.
    """

    youngs_modulus: float
    poisson_ratio: float
    density: float | None = None

    def __post_init__(self) -> None:
        young = self.youngs_modulus  # an array's == is an array: no truth value, Real only
        rigid = isinstance(young, Real) and not isinstance(young, bool) and young == math.inf
        if not rigid:
            validate_positive("youngs_modulus", self.youngs_modulus, "Pa (or math.inf: rigid)")
        validate_poisson("poisson_ratio", self.poisson_ratio)
        if self.density is not None:
            object.__setattr__(self, "density", validate_density("density", self.density))

    @property
    def compliance(self) -> float:
        """Contact compliance Q = (1 - nu^2) / E in 1/Pa (0 for a rigid body)."""
        return (1.0 - self.poisson_ratio**2) / self.youngs_modulus

    @property
    def plane_strain_modulus(self) -> float:
        """Plane-strain modulus E / (1 - nu^2) in Pa: a rigid indenter's E* on this body."""
        return self.youngs_modulus / (1.0 - self.poisson_ratio**2)

    @property
    def shear_modulus(self) -> float:
        """Shear modulus mu = E / (2 (1 + nu)) in Pa."""
        return self.youngs_modulus / (2.0 * (1.0 + self.poisson_ratio))


def validate_density(name: str, density: object) -> float:
    """``density`` in kg/m^3 as a float: 0 (massless) or within :data:`DENSITY_RANGE`;
    InputError naming ``name`` otherwise."""
    valid = f"in [{DENSITY_RANGE[0]:g}, {DENSITY_RANGE[1]:g}] kg/m^3 or be 0 (massless)"
    if not isinstance(density, Real) or isinstance(density, bool):
        raise InputError(f"{name} must be a number {valid}, got {shown(density)}", name)
    if density == 0:
        return 0.0
    if not DENSITY_RANGE[0] <= density <= DENSITY_RANGE[1]:  # also a negative, nan or inf
        raise InputError(f"{name} must lie {valid}, got {shown(density)}", name)
    return float(density)


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
