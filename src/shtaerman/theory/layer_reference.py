"""Reference solution: a rigid power-law indenter on an elastic layer, by the Hankel transform.

A frictionless rigid striker z = A r^n (n > 1) is pressed to depth d into a layer of thickness H,
Young's modulus E and Poisson's ratio nu on a rigid base, bonded (u = 0) or lubricated
(u_z = 0, free to slide). An axisymmetric surface pressure p(r) displaces the surface by

    w(r) = (2 / E*) Int_0^inf p~(xi) K(xi H) J0(xi r) dxi,   E* = E / (1 - nu^2),

p~ the Hankel transform of order 0 of p, with the layer's compliance factor (kappa = 3 - 4 nu)

- bonded base (Lebedev & Ufliand, PMM 22, 1958; Hayes et al., J. Biomech. 5, 1972):
  K(t) = (2 kappa sinh 2t - 4t) / (2 kappa cosh 2t + 1 + kappa^2 + 4t^2);
- lubricated base: K(t) = (cosh 2t - 1) / (sinh 2t + 2t).

K -> 1 as t -> inf (the half-space). As t -> 0: bonded K ~ t (1 - 2 nu) / (2 (1 - nu)^2) (the
oedometric foundation), bonded nu = 1/2 K ~ 2 t^3 / 3 (the thin film), lubricated K ~ t / 2 (the
sliding foundation k = E*/H) -- the limits of :mod:`shtaerman.theory.layer`.

With p~(xi) = Int_0^a phi(s) cos(xi s) ds (Copson), the half-space part of w inverts in closed
form (Abel) and the contact reduces to a Fredholm equation of the second kind on 0 <= t <= a,

    phi(t) - (2/pi) Int_0^a phi(s) Int_0^inf (1 - K(xi H)) cos(xi t) cos(xi s) dxi ds
        = (E*/pi) (d - A (n + 1) c_n t^n),   c_n = Int_0^1 s^(n+1) / sqrt(1 - s^2) ds,

with P = 2 pi Int_0^a phi dt; the pressure vanishes at the edge where phi(a) = 0, which fixes d
for a given a. The kernel is smooth (1 - K decays as t^2 exp(-2t)), so a Nystrom method on
composite Gauss-Legendre panels of width below H converges exponentially
(:func:`layer_contact`); :class:`LayerReference` then finds the contact radius of a depth.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike
from scipy.optimize import brentq
from scipy.special import gamma

from ..validation import InputError, validate_poisson, validate_positive
from .indenter import PowerLawIndenter
from .layer import check_base
from .materials import Material

__all__ = [
    "LayerContact",
    "LayerReference",
    "compliance_factor",
    "layer_contact",
    "thick_layer_coefficient",
]

PANEL_NODES = 16
"""Gauss-Legendre nodes per panel of the contact interval (Nystrom)."""
FREQUENCY_NODES = 12
"""Gauss-Legendre nodes per panel of the transform variable u = xi H."""
MIN_RATIO = 0.01
"""Thinnest layer solved, H / a: the work grows as (a / H)^3 (below it, the thin limits of
:mod:`shtaerman.theory.layer` are within about 1e-5 of the force)."""
FREQUENCY_CUTOFF = 24.0
"""Upper limit of u = xi H: 1 - K(u) < 1e-16 beyond it (it decays as u^2 exp(-2u))."""


def _decay(u: np.ndarray, nu: float, base: str) -> np.ndarray:
    """1 - K(u) for u > 0, in forms free of overflow and cancellation."""
    e = np.exp(-2.0 * u)
    if base == "bonded":
        kappa = 3.0 - 4.0 * nu
        top = 2.0 * kappa * e * e + (1.0 + kappa * kappa + 4.0 * u * u + 4.0 * u) * e
        return top / (kappa * (1.0 + e * e) + (1.0 + kappa * kappa + 4.0 * u * u) * e)
    one_minus_e = -np.expm1(-2.0 * u)
    return 2.0 * e * (one_minus_e + 2.0 * u) / (one_minus_e * (1.0 + e) + 4.0 * u * e)


def compliance_factor(t: ArrayLike, poisson_ratio: float, base: str = "bonded") -> np.ndarray:
    """K(t) of the layer, t = xi H >= 0 (dimensionless; 1 for the half-space, 0 at t = 0).

    Raises
    ------
    shtaerman.validation.InputError
        If ``base`` is unknown, nu is not in [0, 0.5] or a t is negative or not finite.
    """
    nu = validate_poisson("nu2", poisson_ratio, low=0.0)
    check_base(base)
    t = np.asarray(t, dtype=float)
    if not np.all(np.isfinite(t) & (t >= 0.0)):
        raise InputError(f"t must be finite numbers >= 0, got {t!r}", "t")
    return np.where(t > 0.5, 1.0 - _decay(np.maximum(t, 0.5), nu, base), _small(t, nu, base))


def _small(t: np.ndarray, nu: float, base: str) -> np.ndarray:
    """K(t) for 0 <= t <= 1/2 without cancellation (sinh 2t - 2t by its series)."""
    x = 2.0 * np.minimum(t, 0.5)
    excess = sum(x ** (2 * k + 1) / math.factorial(2 * k + 1) for k in range(1, 12))
    if base == "lubricated":
        return 2.0 * np.sinh(x / 2.0) ** 2 / (np.sinh(x) + x)
    kappa = 3.0 - 4.0 * nu
    top = 2.0 * kappa * excess + 2.0 * x * (kappa - 1.0)
    return top / (2.0 * kappa * np.cosh(x) + 1.0 + kappa * kappa + x * x)


def _panels(edges: np.ndarray, nodes: int) -> tuple[np.ndarray, np.ndarray]:
    """Composite Gauss-Legendre nodes and weights on consecutive ``edges``."""
    x, w = np.polynomial.legendre.leggauss(nodes)
    low, high = edges[:-1, None], edges[1:, None]
    return ((low + high + (high - low) * x) / 2).ravel(), ((high - low) / 2 * w).ravel()


def _contact_nodes(h: float, resolution: float) -> tuple[np.ndarray, np.ndarray]:
    """Nodes on 0 <= tau <= 1: panels of width min(2 h, 1/4)/resolution, the first graded."""
    count = math.ceil(resolution / min(2.0 * h, 0.25))
    edges = np.linspace(0.0, 1.0, count + 1)
    graded = edges[1] * np.geomspace(1e-4, 1.0, 9)  # tau^n is not smooth at tau = 0
    return _panels(np.concatenate([[0.0], graded, edges[2:]]), PANEL_NODES)


def _kernel(tau: np.ndarray, h: float, nu: float, base: str, resolution: float) -> np.ndarray:
    """k(tau_i, sigma_j) = (2/(pi h)) Int_0^inf (1 - K(u)) cos(u tau_i/h) cos(u sigma_j/h) du
    for the points ``tau`` (rows) and the nodes ``tau[:-1]`` (columns)."""
    width = min(2.0 * h, 2.0) / resolution
    edges = np.linspace(0.0, FREQUENCY_CUTOFF, math.ceil(FREQUENCY_CUTOFF / width) + 1)
    u, weights = _panels(edges, FREQUENCY_NODES)
    cosines = np.cos(np.outer(tau, u) / h)
    return (cosines * (weights * _decay(u, nu, base))) @ cosines[:-1].T * (2.0 / (math.pi * h))


@dataclass(frozen=True)
class LayerContact:
    """The layer contact at one contact radius a, in units of a, A and E*.

    Attributes
    ----------
    depth : float
        d / (A a^n).
    force : float
        P / (E* A a^(n+1)).
    phi_slope : float
        Largest d(phi)/d(tau) on the nodes over phi(0) (<= 0: the pressure is >= 0).
    """

    depth: float
    force: float
    phi_slope: float


def _shape_constant(n: float) -> float:
    """c_n = Int_0^1 s^(n+1) / sqrt(1 - s^2) ds = (sqrt(pi)/2) Gamma(n/2 + 1)/Gamma(n/2 + 3/2)."""
    return math.sqrt(math.pi) / 2.0 * gamma(n / 2.0 + 1.0) / gamma(n / 2.0 + 1.5)


def layer_contact(
    h: float, exponent: float, poisson_ratio: float, base: str = "bonded", resolution: float = 1.0
) -> LayerContact:
    """Solve the Fredholm equation at H / a = ``h`` (module docstring), dimensionless.

    Parameters
    ----------
    h : float
        H / a, >= :data:`MIN_RATIO`.
    exponent : float
        n > 1 of the profile z = A r^n.
    poisson_ratio : float
        nu in [0, 0.5].
    base : {"bonded", "lubricated"}
    resolution : float
        Divides every quadrature panel width (1 gives about 1e-11 in the force).

    Returns
    -------
    LayerContact
        Depth and force in units of A a^n and E* A a^(n+1).

    Raises
    ------
    shtaerman.validation.InputError
        If a value is out of range (H / a below :data:`MIN_RATIO`).
    """
    nu = validate_poisson("nu2", poisson_ratio, low=0.0)
    h, n = validate_positive("h", h), validate_positive("exponent", exponent)
    resolution = validate_positive("resolution", resolution)
    check_base(base)
    if h < MIN_RATIO:
        raise InputError(
            f"h: H / a must be >= {MIN_RATIO:g} for the layer reference (use the thin limits "
            f"of shtaerman.theory.layer), got {h!r}",
            "h",
        )
    tau, weights = _contact_nodes(h, resolution)
    points = np.concatenate([tau, [1.0]])
    kernel = _kernel(points, h, nu, base, resolution) * weights
    system = np.eye(tau.size) - kernel[:-1]
    phi = np.linalg.solve(system, np.stack([np.ones_like(tau), tau**n], axis=1))
    edge = np.array([1.0, 1.0]) + kernel[-1] @ phi  # Nystrom interpolation at tau = 1
    ratio = edge[1] / edge[0]  # phi(1) = 0: d = A a^n (n + 1) c_n ratio
    c = (n + 1.0) * _shape_constant(n)
    combined = ratio * phi[:, 0] - phi[:, 1]
    slope = np.max(np.diff(combined) / np.diff(tau)) / combined[0]
    return LayerContact(c * ratio, 2.0 * c * (weights @ combined), float(slope))


@dataclass(frozen=True)
class LayerReference:
    """The contact of a rigid z = A r^n on a layer of ``body``, to about 1e-10 in the force.

    Parameters
    ----------
    indenter : PowerLawIndenter
        z = A r^n with n > 1.
    body : Material
        The layer (E in Pa, nu in [0, 0.5]).
    thickness : float
        H in m.
    base : {"bonded", "lubricated"}
    resolution : float
        Divides every quadrature panel width (:func:`layer_contact`).
    """

    indenter: PowerLawIndenter
    body: Material
    thickness: float
    base: str = "bonded"
    resolution: float = 1.0

    def __post_init__(self) -> None:
        validate_positive("thickness", self.thickness, "m")
        validate_poisson("nu2", self.body.poisson_ratio, low=0.0)
        check_base(self.base)
        if self.indenter.exponent <= 1.0:
            raise InputError(
                f"exponent must be > 1 for the layer reference, got {self.indenter.exponent!r}",
                "exponent",
            )

    @property
    def modulus(self) -> float:
        """E* = E / (1 - nu^2) in Pa."""
        nu = self.body.poisson_ratio
        return self.body.youngs_modulus / (1.0 - nu * nu)

    def at_radius(self, contact_radius: float) -> tuple[float, float]:
        """Depth d in m and force P in N of the contact of radius ``contact_radius`` m."""
        a = validate_positive("contact_radius", contact_radius, "m")
        n, big_a = self.indenter.exponent, self.indenter.shape_coefficient
        solution = layer_contact(
            self.thickness / a, n, self.body.poisson_ratio, self.base, self.resolution
        )
        return big_a * a**n * solution.depth, self.modulus * big_a * a ** (n + 1) * solution.force

    def contact_radius(self, depth: float) -> float:
        """Contact radius a in m at a depth d > 0 in m (relative tolerance 1e-12).

        d / (A a^n) lies between 2/(n + 2) (thin incompressible film) and (n + 1) c_n (the
        half-space), which brackets the root.
        """
        d = validate_positive("depth", depth, "m")
        n, big_a = self.indenter.exponent, self.indenter.shape_coefficient
        low = (d / (big_a * 1.01 * (n + 1.0) * _shape_constant(n))) ** (1.0 / n)
        high = min((d / (big_a * 0.9 * 2.0 / (n + 2.0))) ** (1.0 / n), self.thickness / MIN_RATIO)

        def mismatch(log_radius: float) -> float:
            return math.log(self.at_radius(math.exp(log_radius))[0] / d)

        if low >= high or mismatch(math.log(high)) < 0.0:
            raise InputError(
                f"thickness: the layer reference needs H >= {MIN_RATIO:g} contact radii; "
                f"{self.thickness!r} m is thinner at depth {d!r} m (use the thin limits of "
                f"shtaerman.theory.layer)",
                "thickness",
            )
        return math.exp(brentq(mismatch, math.log(low), math.log(high), xtol=1e-12))

    def force(self, depth: float) -> float:
        """Force P in N at a depth d > 0 in m."""
        return self.at_radius(self.contact_radius(depth))[1]


def thick_layer_coefficient(poisson_ratio: float, base: str = "bonded") -> float:
    """C of P / P_Shtaerman - 1 = C a / H + O((a / H)^2) at a fixed depth (dimensionless).

    C = (2/pi) Int_0^inf (1 - K(u)) du: to first order in a / H the layer adds the constant
    kernel (2 / (pi H)) Int (1 - K) to the Fredholm equation, which raises the force at a
    given depth by that factor (0.877 bonded, nu = 0.3; 0.743 lubricated, any nu).
    """
    nu = validate_poisson("nu2", poisson_ratio, low=0.0)
    check_base(base)
    u, weights = _panels(np.linspace(0.0, 2.0 * FREQUENCY_CUTOFF, 49), 2 * FREQUENCY_NODES)
    return float(2.0 / math.pi * (weights @ _decay(u, nu, base)))
