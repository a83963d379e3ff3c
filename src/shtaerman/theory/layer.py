"""Analytic limits of a rigid power-law indenter pressed into an elastic layer on a rigid base.

A striker z = A r^n (n > 1), frictionless, pressed to depth d into a layer of thickness H,
shear modulus mu and Poisson's ratio nu on a rigid base. The limits known in closed form
(derivations in ``docs/theory.md``, section "Layer on a rigid base"):

- thick layer, H >> a: Shtaerman's half-space with E* = E / (1 - nu^2) (:func:`half_space_limit`);
- thin layer bonded to the base, nu not near 1/2: an oedometric foundation
  (:func:`oedometric_stiffness`); on a lubricated base, any nu: a plate-restrained foundation
  (:func:`sliding_stiffness`); either contact is a :class:`FoundationLayer`;
- thin incompressible layer bonded to the base: a squeezed film (:class:`IncompressibleThinLayer`;
  for a paraboloid the classic P = 2 pi mu R^2 d^3 / H^3 of Jaffar, Int. J. Mech. Sci. 31, 1989;
  Chadwick, SIAM J. Appl. Math. 62, 2002).

:func:`thin_layer_limit` picks the limit of a base and a Poisson's ratio.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike

from ..validation import InputError, validate_poisson, validate_positive
from ..vocabulary import BASES
from .contact import PowerLawContact
from .indenter import PowerLawIndenter
from .materials import Material

__all__ = [
    "FoundationLayer",
    "IncompressibleThinLayer",
    "check_base",
    "half_space_limit",
    "oedometric_stiffness",
    "sliding_stiffness",
    "thin_layer_limit",
]


def check_base(base: str) -> str:
    """``base`` if it is one of :data:`BASES`, else :class:`InputError` naming them."""
    if base not in BASES:
        raise InputError(f"base: unknown base {base!r}. Pick one of {list(BASES)}", "base")
    return base


def half_space_limit(indenter: PowerLawIndenter, body: Material) -> PowerLawContact:
    """Shtaerman's solution for a rigid indenter on the half-space of ``body`` (H -> inf)."""
    nu = body.poisson_ratio
    return PowerLawContact(indenter, body.youngs_modulus / (1.0 - nu * nu))


def oedometric_stiffness(body: Material, thickness: float) -> float:
    """Foundation stiffness k = 2 mu (1 - nu) / ((1 - 2 nu) H) in Pa/m of a thin bonded layer.

    Raises
    ------
    shtaerman.validation.InputError
        If nu is not in [0, 0.5) (the incompressible layer has no such stiffness) or H <= 0.
    """
    nu = validate_poisson("nu2", body.poisson_ratio, low=0.0)
    if nu >= 0.5:
        raise InputError(f"nu2 must lie in [0, 0.5) for the oedometric limit, got {nu!r}", "nu2")
    h = validate_positive("thickness", thickness, "m")
    return 2.0 * body.shear_modulus * (1.0 - nu) / ((1.0 - 2.0 * nu) * h)


def _depths(depth: ArrayLike) -> np.ndarray:
    d = np.asarray(depth, dtype=float)
    if not np.all(np.isfinite(d) & (d >= 0.0)):
        raise InputError(f"depth must be finite numbers >= 0 m, got {depth!r}", "depth")
    return d


def sliding_stiffness(body: Material, thickness: float) -> float:
    """Foundation stiffness k = E / ((1 - nu^2) H) in Pa/m of a thin layer on a lubricated base.

    Raises
    ------
    shtaerman.validation.InputError
        If nu is not in [0, 0.5] or H <= 0.
    """
    nu = validate_poisson("nu2", body.poisson_ratio, low=0.0)
    h = validate_positive("thickness", thickness, "m")
    return body.youngs_modulus / ((1.0 - nu * nu) * h)


@dataclass(frozen=True)
class FoundationLayer:
    """A thin layer that acts as a foundation p = k w under a rigid power-law indenter.

    Parameters
    ----------
    indenter : PowerLawIndenter
        z = A r^n, n > 0.
    stiffness : float
        k in Pa/m (:func:`oedometric_stiffness`, :func:`sliding_stiffness`).
    """

    indenter: PowerLawIndenter
    stiffness: float

    def __post_init__(self) -> None:
        validate_positive("stiffness", self.stiffness, "Pa/m")

    def contact_radius(self, depth: ArrayLike) -> np.ndarray:
        """a = (d / A)^(1/n) in m for a depth d in m (the profile meets the depth)."""
        n, big_a = self.indenter.exponent, self.indenter.shape_coefficient
        return (_depths(depth) / big_a) ** (1.0 / n)

    def force(self, depth: ArrayLike) -> np.ndarray:
        """P = pi k d a^2 n / (n + 2) in N for a depth d in m."""
        d, n = _depths(depth), self.indenter.exponent
        return math.pi * self.stiffness * d * self.contact_radius(d) ** 2 * n / (n + 2.0)

    def pressure(self, radius: ArrayLike, depth: float) -> np.ndarray:
        """p(r) = k (d - A r^n) inside the contact, 0 outside, in Pa (compression positive)."""
        r = np.abs(np.asarray(radius, dtype=float))
        gap = float(_depths(depth)) - self.indenter.profile(r)
        return self.stiffness * np.maximum(gap, 0.0)


@dataclass(frozen=True)
class IncompressibleThinLayer:
    """Thin incompressible layer bonded to a rigid base, frictionless top: a squeezed film.

    Parameters
    ----------
    indenter : PowerLawIndenter
        z = A r^n, n > 0.
    shear_modulus : float
        mu in Pa.
    thickness : float
        H in m.
    """

    indenter: PowerLawIndenter
    shear_modulus: float
    thickness: float

    def __post_init__(self) -> None:
        validate_positive("shear_modulus", self.shear_modulus, "Pa")
        validate_positive("thickness", self.thickness, "m")

    @property
    def film_coefficient(self) -> float:
        """c = 3 mu / H^3 in Pa/m^3 of the film equation (1/r)(r p')' = -c (d - A r^n)."""
        return 3.0 * self.shear_modulus / self.thickness**3

    def contact_radius(self, depth: ArrayLike) -> np.ndarray:
        """a = ((n + 2) d / (2 A))^(1/n) in m for a depth d in m (zero volume displaced)."""
        n, big_a = self.indenter.exponent, self.indenter.shape_coefficient
        return ((n + 2.0) * _depths(depth) / (2.0 * big_a)) ** (1.0 / n)

    def force(self, depth: ArrayLike) -> np.ndarray:
        """P = 3 pi mu A n a^(n+4) / (4 H^3 (n+2)(n+4)) in N for a depth d in m."""
        n, big_a = self.indenter.exponent, self.indenter.shape_coefficient
        a = self.contact_radius(depth)
        return math.pi * self.film_coefficient * big_a * n * a ** (n + 4) / (4 * (n + 2) * (n + 4))

    def pressure(self, radius: ArrayLike, depth: float) -> np.ndarray:
        """p(r) = c [d (a^2 - r^2)/4 - A (a^(n+2) - r^(n+2)) / (n+2)^2] for r < a, else 0 (Pa).

        Non-negative, decreasing, with p = p' = 0 at the edge; p(0) = c A n a^(n+2)/(2 (n+2)^2).
        """
        n, big_a = self.indenter.exponent, self.indenter.shape_coefficient
        d = float(_depths(depth))
        a = float(self.contact_radius(d))
        r = np.minimum(np.abs(np.asarray(radius, dtype=float)), a)
        inside = d * (a * a - r * r) / 4.0 - big_a * (a ** (n + 2) - r ** (n + 2)) / (n + 2) ** 2
        return self.film_coefficient * np.maximum(inside, 0.0)


def thin_layer_limit(
    indenter: PowerLawIndenter, body: Material, thickness: float, base: str = "bonded"
) -> FoundationLayer | IncompressibleThinLayer:
    """The H -> 0 limit of a layer of ``body`` on a ``base`` ("bonded" or "lubricated").

    Bonded: the thin film for nu = 0.5, else the oedometric foundation; lubricated: the
    foundation k = E* / H for any nu.

    Raises
    ------
    shtaerman.validation.InputError
        If ``base`` is unknown or a value is out of range.
    """
    if check_base(base) == "lubricated":
        return FoundationLayer(indenter, sliding_stiffness(body, thickness))
    if body.poisson_ratio == 0.5:
        return IncompressibleThinLayer(indenter, body.shear_modulus, thickness)
    return FoundationLayer(indenter, oedometric_stiffness(body, thickness))
