"""Exact frictionless contact of a power-law indenter with an elastic half-space.

Sneddon (1965), Shtaerman (1949) and Galin: a striker z = A r^n pressed to depth x into a
half-space with combined modulus E* (1/E* = Q1 + Q2, Q = (1 - nu^2)/E) makes a circular contact of
radius a with

- depth       x = kappa_n A a^n,
- force       P = (2n/(n+1)) kappa_n E* A a^(n+1),
- force law   P = beta x^q, q = (n+1)/n, beta = (2n/(n+1)) E* (kappa_n A)^(-1/n),
- pressure    p(r) = (n kappa_n E* A / pi) Int_r^a s^(n-1) / sqrt(s^2 - r^2) ds
                   = (n kappa_n E* A / pi) a^(n-1) sqrt(1 - rho^2) 2F1(1, 1 - n/2; 3/2; 1 - rho^2),
  rho = r/a (the closed form follows from s^2 = r^2 + t^2 and Pfaff's transformation),
- centre      p(0)/p_avg = (n+1) / (2(n-1)) for n > 1 (2.5 for n = 3/2, 1.5 for Hertz); the
  central pressure is infinite for n <= 1 (logarithmically for the cone).

For n = 3/2 the paper's own forms are also here: J1 and J2 through the gamma function, its
constants 0.81180 and 0.67650, and its eq. (5) for p(r) with incomplete elliptic integrals.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike
from scipy.special import ellipeinc, ellipkinc, gamma, hyp2f1, rgamma

from ..validation import InputError, validate_positive
from .indenter import PowerLawIndenter

__all__ = [
    "PowerLawContact",
    "paper_J1",
    "paper_J2",
    "paper_beta_constant",
    "paper_pressure_eq5",
    "paper_radius_constant",
]


@dataclass(frozen=True)
class PowerLawContact:
    """Exact contact of :class:`PowerLawIndenter` on a half-space of combined modulus E*.

    Parameters
    ----------
    indenter : PowerLawIndenter
        The striker's profile z = A r^n.
    modulus : float
        Combined modulus E* in Pa (see :func:`shtaerman.theory.materials.effective_modulus`).
    """

    indenter: PowerLawIndenter
    modulus: float

    def __post_init__(self) -> None:
        validate_positive("modulus", self.modulus, "Pa")
        beta = self.beta
        if not (math.isfinite(beta) and beta > 0 and math.isfinite(1.0 / beta)):
            raise InputError(
                f"beta = (2n/(n+1)) E* (kappa A)^(-1/n) = {beta:g} N/m^q is not representable "
                f"for shape_coefficient {self.indenter.shape_coefficient!r} m^(1-n), exponent "
                f"{self.indenter.exponent!r} and modulus {self.modulus!r} Pa; scale the units"
            )

    @property
    def force_exponent(self) -> float:
        """q = (n + 1)/n in P = beta x^q (5/3 for the paper, 3/2 for Hertz)."""
        n = self.indenter.exponent
        return (n + 1.0) / n

    @property
    def beta(self) -> float:
        """beta = (2n/(n+1)) E* (kappa_n A)^(-1/n), in N m^-q."""
        n, kappa = self.indenter.exponent, self.indenter.kappa
        try:
            scale = (kappa * self.indenter.shape_coefficient) ** (-1 / n)
        except OverflowError:  # beyond the floats (A = 1e-300 at n = 0.25): the range check's
            scale = math.inf
        return 2 * n / (n + 1) * self.modulus * scale

    @property
    def central_to_mean_ratio(self) -> float:
        """p(0)/p_avg = (n+1)/(2(n-1)); ``math.inf`` for n <= 1 (the pressure is unbounded)."""
        n = self.indenter.exponent
        return (n + 1.0) / (2.0 * (n - 1.0)) if n > 1.0 else math.inf

    def depth(self, contact_radius: ArrayLike) -> np.ndarray:
        """Depth x = kappa_n A a^n in m for a contact radius a in m."""
        a = np.asarray(contact_radius, dtype=float)
        return self.indenter.kappa * self.indenter.shape_coefficient * a**self.indenter.exponent

    def contact_radius(self, depth: ArrayLike) -> np.ndarray:
        """Contact radius a = (x / (kappa_n A))^(1/n) in m for a depth x in m."""
        x = np.asarray(depth, dtype=float)
        scale = self.indenter.kappa * self.indenter.shape_coefficient
        return (x / scale) ** (1.0 / self.indenter.exponent)

    def force(self, depth: ArrayLike) -> np.ndarray:
        """Force P = beta x^q in N for a depth x in m."""
        return self.beta * np.asarray(depth, dtype=float) ** self.force_exponent

    def mean_pressure(self, depth: ArrayLike) -> np.ndarray:
        """Mean contact pressure P / (pi a^2) in Pa at depth x in m."""
        return self.force(depth) / (math.pi * self.contact_radius(depth) ** 2)

    def central_pressure(self, depth: ArrayLike) -> np.ndarray:
        """Pressure at the centre p(0) in Pa at depth x in m (``inf`` for n <= 1)."""
        return self.central_to_mean_ratio * self.mean_pressure(depth)

    def pressure(self, radius: ArrayLike, depth: float) -> np.ndarray:
        """Contact pressure p(r) in Pa (compression positive) at radius r in m and depth x in m.

        Zero outside the contact; ``inf`` at r = 0 for n <= 1.
        """
        n = self.indenter.exponent
        depth = float(depth)
        if not depth >= 0.0 or not math.isfinite(depth):
            raise InputError(f"depth must be a finite number >= 0 m, got {depth!r}")
        radius = np.asarray(radius, dtype=float)
        if depth == 0.0:
            return np.where(np.isnan(radius), np.nan, 0.0)
        a = float(self.contact_radius(depth))
        rho = np.abs(radius) / a
        inside = rho < 1.0
        z = 1.0 - rho[inside] ** 2
        scale = n * self.indenter.kappa * self.modulus * self.indenter.shape_coefficient / math.pi
        p = np.zeros_like(rho)
        with np.errstate(divide="ignore", invalid="ignore"):
            p[inside] = scale * a ** (n - 1) * np.sqrt(z) * pressure_shape(n, z)
        if n > 1.0:
            p[rho == 0.0] = float(self.central_pressure(depth))
        else:
            p[rho == 0.0] = math.inf
        p[np.isnan(rho)] = np.nan
        return p


def pressure_shape(exponent: float, z: np.ndarray) -> np.ndarray:
    """2F1(1, 1 - n/2; 3/2; z), z = 1 - (r/a)^2 in [0, 1], of p(r) (dimensionless).

    Near the axis (z > 1/2) by its connection to 1 - z (Abramowitz & Stegun 15.3.6), where
    both series converge fast: scipy's direct 2F1 there costs about 18 us a point near z = 1
    (rate-contact pressures evaluate it on every instant's profile) and is within 6e-14 of
    mpmath, this within 1e-14 (n = 0.5 .. 7; tests/test_analytic_contact.py). Direct where
    c - a - b = (n - 1)/2 is within 0.05 of an integer (the connection's Gamma poles)."""
    b, s = 1.0 - exponent / 2.0, (exponent - 1.0) / 2.0
    near = z > 0.5 if abs(s - round(s)) > 0.05 else np.zeros(np.shape(z), dtype=bool)
    out = np.asarray(hyp2f1(1.0, b, 1.5, np.where(near, 0.0, z)), dtype=float)
    w = 1.0 - z[near]
    # Gamma(3/2) Gamma(s) / (Gamma(1/2) Gamma(3/2 - b)) and Gamma(3/2) Gamma(-s) / Gamma(b)
    regular = 0.5 * gamma(s) * rgamma(0.5 + exponent / 2.0)
    singular = 0.5 * math.sqrt(math.pi) * gamma(-s) * rgamma(b)
    out[near] = regular * hyp2f1(1.0, b, 1.0 - s, w) + singular * w**s * hyp2f1(
        0.5, 0.5 + exponent / 2.0, 1.0 + s, w
    )
    return out


def paper_J1() -> float:
    """J1 = Int_0^1 sqrt(xi)/sqrt(1 - xi^2) d xi = 2^(-1/2) Gamma(3/4)^2 / Gamma(3/2) (eq. 2)."""
    return 2**-0.5 * gamma(0.75) ** 2 / gamma(1.5)


def paper_J2() -> float:
    """J2 = Int_0^1 xi^2 sqrt(xi)/sqrt(1 - xi^2) d xi = 2^(3/2) Gamma(7/4)^2 / Gamma(7/2)."""
    return 2**1.5 * gamma(1.75) ** 2 / gamma(3.5)


def paper_beta_constant() -> float:
    """The paper's 0.81180 = 3 J2 (2/(3 J1))^(5/3): beta = 0.81180 / (A^(2/3) (Q1 + Q2))."""
    return 3 * paper_J2() * (2 / (3 * paper_J1())) ** (5 / 3)


def paper_radius_constant() -> float:
    """The paper's 0.67650 = (2/(3 J1))^(2/3): a = 0.67650 (x/A)^(2/3)."""
    return (2 / (3 * paper_J1())) ** (2 / 3)


def paper_pressure_eq5(radius: ArrayLike, contact_radius: float, force: float) -> np.ndarray:
    """Pressure p(r) in Pa for n = 3/2 by the paper's eq. (5).

    p(r) = 2.5 P/(pi a^2) { sqrt(r/(2a)) [F(d, k) - 2 E(d, k)] + sqrt(1 - r^2/a^2) },
    d = arccos sqrt(r/a), with incomplete elliptic integrals of modulus k = 1/sqrt(2) (scipy's
    parameter m = k^2 = 1/2).

    Parameters
    ----------
    radius : array_like
        r in m, 0 <= r <= a.
    contact_radius : float
        a in m.
    force : float
        P in N.
    """
    a = validate_positive("contact_radius", contact_radius, "m")
    rho = np.asarray(radius, dtype=float) / a
    if np.any((rho < 0) | (rho > 1)):
        raise InputError("radius must lie in [0, contact_radius]")
    phi = np.arccos(np.sqrt(rho))
    bracket = ellipkinc(phi, 0.5) - 2 * ellipeinc(phi, 0.5)
    return 2.5 * force / (math.pi * a**2) * (np.sqrt(rho / 2) * bracket + np.sqrt(1 - rho**2))
