"""Exact frictionless contact of any axisymmetric profile with an elastic half-space (Sneddon).

A rigid profile z = f(r) (f(0) = 0, increasing) pressed into a half-space of combined modulus
E* (1/E* = (1 - nu1^2)/E1 + (1 - nu2^2)/E2) makes a contact of radius a with (Sneddon 1965;
with g(x) = x Int_0^x f'(r) / sqrt(x^2 - r^2) dr, the depth at contact radius x)

- depth     delta(a) = g(a) = Int_0^a f'(r) a / sqrt(a^2 - r^2) dr,
- force     P(a) = 2 E* Int_0^a r^2 f'(r) / sqrt(a^2 - r^2) dr = 2 E* Int_0^a (delta(a) - g(x)) dx,
- pressure  p(r) = (E*/pi) Int_r^a g'(x) / sqrt(x^2 - r^2) dx, so dP/da = 2 E* a delta'(a),
- centre    p(0) = (E*/pi) Int_0^a g'(x) / x dx.

For z = A r^n these are :class:`shtaerman.theory.contact.PowerLawContact`'s closed forms. For
the sphere z = R - sqrt(R^2 - r^2), with t = a/R (f'(r) = r / sqrt(R^2 - r^2)):

- delta = a artanh(t) = (a/2) ln((R + a)/(R - a)),
- P = E* [(a^2 + R^2)/2 ln((R + a)/(R - a)) - a R] = E* R^2 sum_{j>=1} 4j/(4j^2 - 1) t^(2j+1)
  (the series for small t, where the closed form cancels; its first term is Hertz's
  4 E* a^3/(3R)),
- g'(x) = artanh(x/R) + (x/R)/(1 - x^2/R^2), p(0) = (E*/pi) [chi_2(t) + artanh(t)], with
  Legendre's chi_2(t) = (Li_2(t) - Li_2(-t))/2 (2 E* a/(pi R), Hertz's, for small t).

For a tabulated profile z = G(r^2) (G piecewise cubic, :mod:`shtaerman.theory.profiles`),
f'(r) dr = G'(s) ds with s = r^2, so with X = a^2

- delta = a I(G'; X), P = 2 E* I(s G'; X), g'(a) = I(G'; X) + 2 sqrt(X) G'(0) + 2 X I(G''; X),

where I(h; X) = Int_0^X h(s) / sqrt(X - s) ds = 2 Int_0^sqrt(X) h(X - w^2) dw is, piece by piece
in w, the integral of a polynomial: Gauss-Legendre with 5 nodes is exact to round-off.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from functools import cached_property, lru_cache

import numpy as np
from numpy.typing import ArrayLike
from scipy.interpolate import PPoly
from scipy.optimize import brentq
from scipy.special import roots_legendre, spence

from ..validation import InputError, LimitError, validate_positive
from .contact import PowerLawContact
from .indenter import PowerLawIndenter
from .profiles import SphereIndenter, TabulatedIndenter

Indenter = PowerLawIndenter | SphereIndenter | TabulatedIndenter
"""A striker's profile: the power law z = A r^n, the exact sphere or a tabulated z(r)."""
INDENTERS = (PowerLawIndenter, SphereIndenter, TabulatedIndenter)

__all__ = [
    "INDENTERS",
    "Indenter",
    "SneddonContact",
    "contact_law",
    "legendre_chi2",
    "profile_inputs",
]

GAUSS_NODES, GAUSS_WEIGHTS = roots_legendre(5)
"""Exact for polynomials of degree <= 9: s G'(s) (cubic in s) is of degree 6 in w."""
PRESSURE_NODES, PRESSURE_WEIGHTS = roots_legendre(48)
"""For p(r) and p(0) of a tabulated profile: smooth integrands, converged to ~1e-12."""
SERIES_BELOW = 0.3
"""t = a/R below which the sphere's force is summed as a series (the closed form cancels)."""
ROOT_ITERATIONS = 2200
"""brentq's iterations for a contact radius from [0, the profile's end]: bisecting, a root
2^-k below the end takes about k of them (1e-60 kg at 1 mm/s on a 1 m sphere, a_c 1e-15 R,
took more than brentq's default 100); 2200 reach any float."""


def legendre_chi2(t: ArrayLike) -> np.ndarray:
    """Legendre's chi_2(t) = (Li_2(t) - Li_2(-t))/2 = Int_0^t artanh(u)/u du, |t| < 1."""
    t = np.asarray(t, dtype=float)
    return 0.5 * (spence(1.0 - t) - spence(1.0 + t))  # Li_2(z) = spence(1 - z)


def _sphere_force_series(t: np.ndarray) -> np.ndarray:
    """sum_{j>=1} 4j/(4j^2 - 1) t^(2j+1) for t < SERIES_BELOW (t^(2j) < 1e-17 at j = 20)."""
    j = np.arange(1, 21)
    return np.sum(4.0 * j / (4.0 * j**2 - 1.0) * t[..., None] ** (2 * j + 1), axis=-1)


CHUNK_VALUES = 2**20
"""Most (point, piece, node) values :func:`_piece_integral` holds at once (8 MB each array):
its memory is bounded whatever the number of points and of the table's rows."""


def _piece_integral(
    indenter: TabulatedIndenter, poly: PPoly, X: ArrayLike, moment: bool = False
) -> np.ndarray:
    """I(h; X) = 2 Int_0^sqrt(X) h(X - w^2) dw for each X, with h the piecewise polynomial
    ``poly`` of s on the table's pieces [s_k, s_k+1] (times s with ``moment``): exact
    Gauss-Legendre per piece in w, each piece's polynomial evaluated by Horner. The X are
    taken in increasing chunks, each over the pieces below its largest X only."""
    X = np.asarray(X, dtype=float).ravel()
    order = np.argsort(X)
    squares = indenter.radii**2
    result = np.empty_like(X)
    start = 0
    while start < X.size:
        pieces = int(np.searchsorted(squares, X[order[-1]])) + 1
        size = max(1, CHUNK_VALUES // (pieces * GAUSS_NODES.size))
        chunk = order[start : start + size]
        result[chunk] = _pieces_below(squares, poly, X[chunk], moment)
        start += size
    return result


def _pieces_below(squares: np.ndarray, poly: PPoly, X: np.ndarray, moment: bool) -> np.ndarray:
    """:func:`_piece_integral` for increasing X, over the pieces below the last X."""
    X = X.reshape(-1, 1, 1)  # (M, 1, 1)
    pieces = int(np.searchsorted(squares, X[-1, 0, 0])) + 1  # those below X
    knots = squares[: pieces + 1]
    coefficients = poly.c[:, : knots.size - 1]
    high = np.sqrt(np.clip(X[..., 0] - knots[:-1], 0.0, None))  # w at s = s_k (M, pieces)
    low = np.sqrt(np.clip(X[..., 0] - knots[1:], 0.0, None))  # w at s = s_k+1
    half = 0.5 * (high - low)
    w = 0.5 * (high + low)[..., None] + half[..., None] * GAUSS_NODES  # (M, pieces, nodes)
    s = np.clip(X - w**2, knots[:-1, None], knots[1:, None])  # stay in the piece
    d = s - knots[:-1, None]
    values = np.zeros_like(d)
    for row in coefficients:  # highest power first
        values = values * d + row[:, None]
    if moment:
        values *= s
    return 2.0 * np.sum(half * (values @ GAUSS_WEIGHTS), axis=-1)


@dataclass(frozen=True)
class SneddonContact:
    """Exact contact of a :class:`SphereIndenter` or :class:`TabulatedIndenter` on a
    half-space of combined modulus E* (see the module for the formulas).

    Parameters
    ----------
    indenter : SphereIndenter or TabulatedIndenter
        The striker's profile.
    modulus : float
        Combined modulus E* in Pa.
    """

    indenter: SphereIndenter | TabulatedIndenter
    modulus: float

    force_exponent = 1.5
    """The smooth tip's small-depth force law P ~ x^(3/2) (the exponent the FEM curve's
    fixed-exponent fit uses); the curve itself is no power law."""
    beta = math.nan
    """No single beta: the force law is no power law (null in the JSON)."""
    central_to_mean_ratio = math.nan
    """Depth dependent (1.5 at small depth, Hertz's); null in the JSON."""

    def __post_init__(self) -> None:
        validate_positive("modulus", self.modulus, "Pa")
        if not isinstance(self.indenter, SphereIndenter | TabulatedIndenter):
            raise InputError("indenter must be a SphereIndenter or a TabulatedIndenter")
        if not self.sphere:
            _check_single_contact(self.indenter)

    @property
    def sphere(self) -> bool:
        return isinstance(self.indenter, SphereIndenter)

    @cached_property
    def _slopes(self) -> tuple:
        """G' and G'' of a tabulated profile (piecewise polynomials in s = r^2)."""
        G = self.indenter.interpolant
        return G.derivative(), G.derivative(2)

    def depth(self, contact_radius: ArrayLike) -> np.ndarray:
        """Depth delta(a) in m at a contact radius a in m."""
        a = np.asarray(contact_radius, dtype=float)
        if self.sphere:
            return a * np.arctanh(a / self.indenter.radius)
        slope, _ = self._slopes
        return a * _piece_integral(self.indenter, slope, a**2).reshape(a.shape)

    def force_at_radius(self, contact_radius: ArrayLike) -> np.ndarray:
        """Force P(a) in N at a contact radius a in m."""
        a = np.asarray(contact_radius, dtype=float)
        if self.sphere:
            R = self.indenter.radius
            t = a / R
            closed = 0.5 * (a**2 + R**2) * 2.0 * np.arctanh(t) - a * R
            with np.errstate(over="ignore", invalid="ignore"):
                series = R**2 * _sphere_force_series(t)
            return self.modulus * np.where(t < SERIES_BELOW, series, closed)
        slope, _ = self._slopes
        moment = _piece_integral(self.indenter, slope, a**2, moment=True)
        return 2.0 * self.modulus * moment.reshape(a.shape)

    def depth_slope(self, contact_radius: ArrayLike) -> np.ndarray:
        """g'(a) = d delta / d a (dimensionless) at a contact radius a in m."""
        a = np.asarray(contact_radius, dtype=float)
        if self.sphere:
            t = a / self.indenter.radius
            return np.arctanh(t) + t / ((1.0 - t) * (1.0 + t))
        return _table_depth_slope(self.indenter, self._slopes, a)

    @property
    def max_contact_radius(self) -> float:
        """The largest contact radius in m: R for the sphere (never reached), the table's
        last radius for a tabulated profile."""
        return self.indenter.radius if self.sphere else self.indenter.r_max

    @cached_property
    def _deepest(self) -> float:
        """The depth in m at which a table's last radius comes into contact."""
        return float(self.depth(self.max_contact_radius))

    def contact_radius(self, depth: ArrayLike) -> np.ndarray:
        """Contact radius a in m at a depth x in m (the inverse of :meth:`depth`).

        Raises
        ------
        shtaerman.validation.LimitError
            If a tabulated profile's contact would reach beyond its last radius.
        """
        x = np.asarray(depth, dtype=float)
        radii = [self._radius(float(value)) for value in x.ravel()]
        return np.array(radii, dtype=float).reshape(x.shape)

    def _radius(self, depth: float) -> float:
        if not depth > 0.0:
            return 0.0
        if self.sphere:
            return brentq(
                self._sphere_gap,
                0.0,
                math.nextafter(self.indenter.radius, 0.0),
                args=(depth,),
                xtol=1e-300,
                rtol=1e-15,
                maxiter=ROOT_ITERATIONS,
            )
        top, deepest = self.max_contact_radius, self._deepest
        if depth > deepest:
            raise LimitError(
                f"profile: depth {depth:.6g} m reaches beyond the table (its last radius "
                f"{top:.6g} m is in contact from depth {deepest:.6g} m); extend the table",
                "profile",
            )
        return brentq(
            lambda a: float(self.depth(a)) - depth,
            *(0.0, top),
            xtol=1e-300,
            rtol=1e-15,
            maxiter=ROOT_ITERATIONS,
        )

    def _sphere_gap(self, contact_radius: float, depth: float) -> float:
        """:meth:`depth` of the sphere minus ``depth``, in m, on floats: the root solve's
        function, 2.3x cheaper than through NumPy (same roots to the bit)."""
        return contact_radius * math.atanh(contact_radius / self.indenter.radius) - depth

    def force(self, depth: ArrayLike) -> np.ndarray:
        """Force P in N at a depth x in m."""
        return self.force_at_radius(self.contact_radius(depth))

    def mean_pressure(self, depth: ArrayLike) -> np.ndarray:
        """Mean contact pressure P / (pi a^2) in Pa at a depth x in m."""
        a = self.contact_radius(depth)
        return self.force_at_radius(a) / (math.pi * a**2)

    def central_pressure(self, depth: ArrayLike) -> np.ndarray:
        """Pressure at the centre p(0) in Pa at a depth x in m."""
        return self.central_pressure_at_radius(self.contact_radius(depth))

    def central_pressure_at_radius(self, contact_radius: ArrayLike) -> np.ndarray:
        """Pressure at the centre p(0) in Pa at a contact radius a in m."""
        a = np.asarray(contact_radius, dtype=float)
        if self.sphere:
            t = a / self.indenter.radius
            return self.modulus / math.pi * (legendre_chi2(t) + np.arctanh(t))
        # Int_0^a g'(x)/x dx on Gauss nodes x = a (1 + node)/2 (smooth: g'(x)/x -> 4 G'(0))
        x = a[..., None] * 0.5 * (1.0 + PRESSURE_NODES)
        inner = self.depth_slope(x) / x
        return self.modulus / math.pi * 0.5 * a * np.sum(inner * PRESSURE_WEIGHTS, axis=-1)

    def pressure(self, radius: ArrayLike, depth: float) -> np.ndarray:
        """Contact pressure p(r) in Pa at radii r in m and a depth x in m (0 outside).

        p(r) = (E*/pi) Int_0^sqrt(a^2 - r^2) g'(x)/x du with x = sqrt(r^2 + u^2) (smooth).
        """
        r = np.abs(np.asarray(radius, dtype=float))
        a = float(self.contact_radius(float(depth)))
        inside = r < a
        span = np.sqrt(np.clip(a**2 - r[inside] ** 2, 0.0, None))[:, None]
        u = span * 0.5 * (1.0 + PRESSURE_NODES)
        x = np.sqrt(r[inside, None] ** 2 + u**2)
        p = np.zeros_like(r)
        integrand = self.depth_slope(x) / x
        p[inside] = self.modulus / math.pi * 0.5 * span[:, 0] * (integrand @ PRESSURE_WEIGHTS)
        return p


def _table_depth_slope(indenter: TabulatedIndenter, slopes: tuple, a: np.ndarray) -> np.ndarray:
    """g'(a) of the table ``indenter`` at contact radii a in m (``slopes``: G', G'')."""
    slope, curvature = slopes
    X = a**2
    first = _piece_integral(indenter, slope, X).reshape(a.shape)
    second = _piece_integral(indenter, curvature, X).reshape(a.shape)
    return first + 2.0 * a * float(slope(0.0)) + 2.0 * X * second


@lru_cache(maxsize=8)  # a run builds the law of one table several times
def _check_single_contact(indenter: TabulatedIndenter) -> None:
    """Refuse a tabulated profile whose depth delta(a) falls with the contact radius anywhere
    on its table (LimitError): a tip sharper than a cone, where one contact region does not
    hold (z = 0.2 sqrt(r) tabulated every mm: t_c NaN at 1.1 m/s, at 1 m/s the impact's time
    quadrature missed the band). delta(a) = Int_0^(pi/2) g(a sin t) / sin t dt rises where
    g = r dz/dr does, checked at 16 radii a row; where g falls, delta'(a) itself at the
    table's radii and midway between them (the falling band straddles a radius)."""
    r, G = indenter.radii, indenter.interpolant
    fine = (r[:-1, None] + np.diff(r)[:, None] * np.linspace(0.0, 1.0, 17)[1:]).ravel()
    if np.all(np.diff(2.0 * fine**2 * G(fine**2, 1)) >= 0.0):
        return
    radii = np.sort(np.concatenate([r[1:], 0.5 * (r[1:] + r[:-1])]))
    falling = radii[_table_depth_slope(indenter, (G.derivative(), G.derivative(2)), radii) < 0.0]
    if falling.size:
        raise LimitError(
            f"profile: Sneddon's depth delta(a) falls with the contact radius near a = "
            f"{float(falling[0]):.3g} m: the table (or its interpolation in r^2 below its "
            "second row) is sharper than a cone there, where one contact region does not "
            "hold; give a tip whose r dz/dr rises with r (a cone z = r or blunter)",
            "profile",
        )


def profile_inputs(indenter: Indenter) -> dict[str, object]:
    """A striker's profile as a document's inputs: the power law's ``shape_coefficient`` and
    ``exponent``; for another profile those None and its ``profile`` (``kind`` and
    ``parameters``, as ``impact --json``)."""
    if isinstance(indenter, PowerLawIndenter):
        return {"shape_coefficient": indenter.shape_coefficient, "exponent": indenter.exponent}
    profile = {"kind": indenter.kind, "parameters": indenter.parameters}
    return {"shape_coefficient": None, "exponent": None, "profile": profile}


def contact_law(indenter: Indenter, modulus: float) -> PowerLawContact | SneddonContact:
    """The exact contact of ``indenter`` on a half-space of combined modulus E* (Pa): the power
    law's closed form, or Sneddon's integrals of any other profile."""
    if isinstance(indenter, PowerLawIndenter):
        return PowerLawContact(indenter, modulus)
    return SneddonContact(indenter, modulus)
