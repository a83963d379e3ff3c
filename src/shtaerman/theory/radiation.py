"""First-order estimate of the energy an impact radiates into an elastic half-space as waves.

The contact radius is small against the shear wavelength c_s t_c, so the half-space sees a
vertical point force f(t) on its surface, the force history of the quasi-static impact. The
energy it radiates (body waves and the Rayleigh wave) is

    W = I(nu) / (2 pi rho c_s^3) * Int (df/dt)^2 dt,   c_s = sqrt(G / rho).

Derivation of I(nu): Lamb's (1904) vertical surface displacement under a time-harmonic point
force F e^(i w t) at the origin is u_z(0) = F H(w) with

    H = (k_s / (2 pi G)) Int_0^oo s alpha(s) / R(s) ds,
    R(s) = (2 s^2 - 1)^2 - 4 s^2 alpha(s) beta(s),  alpha = sqrt(s^2 - g^2), beta = sqrt(s^2 - 1),

s = xi / k_s the wavenumber over the shear wavenumber, g = c_s / c_p,
g^2 = (1 - 2 nu) / (2 (1 - nu)). The real part of H diverges (the static 1/r), the imaginary
part is finite: Im H = w I(nu) / (2 pi G c_s) with I the sum of three pieces (radiation
branches alpha = i sqrt(g^2 - s^2), beta = i sqrt(1 - s^2), and the Rayleigh pole s_R, R(s_R) = 0):

    I = Int_0^g s a / ((2 s^2 - 1)^2 + 4 s^2 a b) ds                     (a = sqrt(g^2 - s^2))
      + Int_g^1 4 s^3 alpha^2 b / ((2 s^2 - 1)^4 + 16 s^4 alpha^2 b^2) ds   (b = sqrt(1 - s^2))
      + pi s_R alpha(s_R) / |R'(s_R)|.

The mean power of the harmonic force is w |F| |Im u| / 2, and by Parseval a transient force
radiates W = (1/pi) Int_0^oo w Im H |F(w)|^2 dw, which is the formula above. I(0.25) = 0.93075,
of which the Rayleigh wave carries 67.4 % (Miller and Pursey 1955: 67 / 26 / 7 % Rayleigh / S
/ P); I(0.5) = 0.65612 (Rayleigh 54.6 %).

For the quasi-static impact M x'' = -beta x^p, p = (n + 1)/n, df/dt = p beta x^(p-1) x', and
with x' = v0 sqrt(1 - (x/x_m)^(p+1)) over both halves of the impact

    Int (df/dt)^2 dt = 2 p^2 beta^2 v0 x_m^(2p-1) B((2p-1)/(p+1), 3/2) / (p+1),
    lambda = W / (M v0^2 / 2) = 2 I p^2 beta^2 x_m^(2p-1) B((2p-1)/(p+1), 3/2)
                                / (pi (p+1) rho c_s^3 M v0),

and the restitution e = sqrt(1 - lambda) to first order in lambda (the force history is that of
the lossless impact; trust it to a few per cent below lambda ~ 0.05).
"""

from __future__ import annotations

import math
from dataclasses import asdict, dataclass, replace
from functools import cache
from typing import TYPE_CHECKING

import numpy as np
from scipy.integrate import quad
from scipy.optimize import brentq
from scipy.special import beta as beta_function

from ..validation import InputError, validate_poisson, validate_positive

if TYPE_CHECKING:
    from .contact import PowerLawContact
    from .materials import Material
    from .profile_impact import ProfileImpactResult
    from .sneddon import SneddonContact

__all__ = [
    "RadiationEstimate",
    "impact_radiation",
    "profile_radiation_estimate",
    "radiated_energy",
    "radiation_estimate",
    "radiation_integral",
    "rayleigh_fraction",
    "rayleigh_root",
]


def _squared_speed_ratio(nu: float) -> float:
    """g^2 = (c_s / c_p)^2 = (1 - 2 nu) / (2 (1 - nu))."""
    return (1.0 - 2.0 * nu) / (2.0 * (1.0 - nu))


def _rayleigh(s: float, g2: float) -> float:
    return (2.0 * s * s - 1.0) ** 2 - 4.0 * s * s * math.sqrt(s * s - g2) * math.sqrt(s * s - 1.0)


def rayleigh_root(poisson_ratio: float) -> float:
    """s_R = c_s / c_R, the root > 1 of Rayleigh's function (1.0877 at nu = 0.25, 1.0474 at 0.5).

    Parameters
    ----------
    poisson_ratio : float
        nu in [0, 0.5].

    Returns
    -------
    float
        The shear over the Rayleigh wave speed, dimensionless.
    """
    nu = _validate_nu(poisson_ratio)
    g2 = _squared_speed_ratio(nu)
    return brentq(_rayleigh, 1.0 + 1e-14, 2.0, args=(g2,), xtol=1e-15, rtol=1e-15)


@cache
def _pieces(nu: float) -> tuple[float, float, float]:
    """Compressional-branch, shear-branch and Rayleigh-pole parts of I(nu), once per nu of
    the process (two quadratures and a root: the dynamic study's estimate curve asked for
    them 120 times at one nu)."""
    g2 = _squared_speed_ratio(nu)
    g = math.sqrt(g2)

    def body_p(s: float) -> float:
        a, b = math.sqrt(max(g2 - s * s, 0.0)), math.sqrt(1.0 - s * s)
        return s * a / ((2.0 * s * s - 1.0) ** 2 + 4.0 * s * s * a * b)

    def body_s(s: float) -> float:
        alpha2, b = s * s - g2, math.sqrt(max(1.0 - s * s, 0.0))
        real, imag = (2.0 * s * s - 1.0) ** 2, 4.0 * s * s * math.sqrt(alpha2) * b
        return s * math.sqrt(alpha2) * imag / (real * real + imag * imag)

    tight = {"epsabs": 1e-14, "epsrel": 1e-12, "limit": 200}
    compressional = quad(body_p, 0.0, g, **tight)[0] if g > 0 else 0.0
    shear = quad(body_s, g, 1.0, **tight)[0]
    s_r = rayleigh_root(nu)
    # R'(s) analytically: d/ds [(2s^2-1)^2 - 4 s^2 alpha beta]
    alpha, beta = math.sqrt(s_r**2 - g2), math.sqrt(s_r**2 - 1.0)
    slope = (
        8.0 * s_r * (2.0 * s_r**2 - 1.0)
        - 8.0 * s_r * alpha * beta
        - 4.0 * s_r**2 * (s_r * beta / alpha + s_r * alpha / beta)
    )
    pole = math.pi * s_r * alpha / abs(slope)
    return compressional, shear, pole


def _validate_nu(poisson_ratio: float) -> float:
    nu = validate_poisson("poisson_ratio", poisson_ratio)
    if nu < 0.0:
        raise InputError(f"poisson_ratio must lie in [0, 0.5] here, got {poisson_ratio!r}")
    return nu


def radiation_integral(poisson_ratio: float) -> float:
    """I(nu) of W = I / (2 pi rho c_s^3) Int (df/dt)^2 dt, from Lamb's problem (module notes).

    Parameters
    ----------
    poisson_ratio : float
        nu in [0, 0.5] (0.5 exact: no compressional branch).

    Returns
    -------
    float
        Dimensionless; 0.930753 at nu = 0.25, 0.862223 at 0.3, 0.656117 at 0.5.
    """
    return float(sum(_pieces(_validate_nu(poisson_ratio))))


def rayleigh_fraction(poisson_ratio: float) -> float:
    """Share of the radiated energy carried by the Rayleigh wave (0.674 at nu = 0.25)."""
    pieces = _pieces(_validate_nu(poisson_ratio))
    return pieces[2] / sum(pieces)


def radiated_energy(
    force_rate_squared_integral: float,
    density: float,
    shear_modulus: float,
    poisson_ratio: float,
) -> float:
    """W = I(nu) / (2 pi rho c_s^3) Int (df/dt)^2 dt in J.

    Parameters
    ----------
    force_rate_squared_integral : float
        Int (df/dt)^2 dt in N^2/s.
    density : float
        rho in kg/m^3.
    shear_modulus : float
        G in Pa.
    poisson_ratio : float
        nu in [0, 0.5].
    """
    rho = validate_positive("density", density, "kg/m^3")
    c_s = math.sqrt(validate_positive("shear_modulus", shear_modulus, "Pa") / rho)
    integral = float(force_rate_squared_integral)
    if not math.isfinite(integral) or integral < 0:
        raise InputError(f"force_rate_squared_integral must be >= 0 N^2/s, got {integral!r}")
    return radiation_integral(poisson_ratio) * integral / (2.0 * math.pi * rho * c_s**3)


@dataclass(frozen=True)
class RadiationEstimate:
    """First-order radiation loss of the quasi-static impact M x'' = -beta x^p (SI units).

    Attributes
    ----------
    radiation_integral : float
        I(nu), dimensionless.
    shear_wave_speed : float
        c_s = sqrt(G / rho) in m/s.
    max_depth : float
        x_m in m, the lossless maximum approach.
    force_rate_squared_integral : float
        Int (df/dt)^2 dt over the lossless impact in N^2/s.
    radiated_energy : float
        W in J.
    energy_fraction : float
        lambda = W / (M v0^2 / 2).
    restitution : float
        e = sqrt(1 - lambda) (first order; nan if lambda >= 1).
    """

    radiation_integral: float
    shear_wave_speed: float
    max_depth: float
    force_rate_squared_integral: float
    radiated_energy: float
    energy_fraction: float
    restitution: float

    def to_dict(self) -> dict[str, float]:
        """The fields as a JSON-ready dict (SI units)."""
        return {key: float(value) for key, value in asdict(self).items()}


def radiation_estimate(
    mass: float,
    velocity: float,
    beta: float,
    force_exponent: float,
    density: float,
    shear_modulus: float,
    poisson_ratio: float,
) -> RadiationEstimate:
    """First-order radiated energy of the impact M x'' = -beta x^p into the half-space.

    Parameters
    ----------
    mass : float
        Striker mass M in kg.
    velocity : float
        Impact velocity v0 in m/s.
    beta : float
        Contact stiffness in N m^-p.
    force_exponent : float
        p > 1/2 ((n + 1)/n for z = A r^n).
    density : float
        Half-space density rho in kg/m^3.
    shear_modulus : float
        Half-space G in Pa.
    poisson_ratio : float
        Half-space nu in [0, 0.5].

    Returns
    -------
    RadiationEstimate
    """
    m = validate_positive("mass", mass, "kg")
    v0 = validate_positive("velocity", velocity, "m/s")
    b = validate_positive("beta", beta, "N m^-p")
    p = validate_positive("force_exponent", force_exponent)
    if p <= 0.5:
        raise InputError(f"force_exponent must be > 0.5 (finite df/dt energy), got {p!r}")
    x_m = ((p + 1.0) * m * v0**2 / (2.0 * b)) ** (1.0 / (p + 1.0))
    shape = 2.0 * p**2 * v0 * beta_function((2.0 * p - 1.0) / (p + 1.0), 1.5) / (p + 1.0)
    try:
        rate = shape * b**2 * x_m ** (2.0 * p - 1.0)
    except OverflowError:  # b^2 beyond the floats (a striker of A 1e-300): in logarithms
        rate = math.exp(
            min(math.log(shape) + 2.0 * math.log(b) + (2.0 * p - 1.0) * math.log(x_m), 709.0)
        )
    return _estimate(m, v0, x_m, rate, density, shear_modulus, poisson_ratio)


def profile_radiation_estimate(
    quasi: ProfileImpactResult, density: float, shear_modulus: float, poisson_ratio: float
) -> RadiationEstimate:
    """First-order radiated energy of the quasi-static impact ``quasi`` on a sphere or a
    tabulated profile (:mod:`shtaerman.theory.profile_impact`), whose Int (dP/dt)^2 dt is a
    quadrature (the power law's closed form in :func:`radiation_estimate`); density in
    kg/m^3, shear modulus in Pa."""
    rate = quasi.force_rate_squared_integral
    return _estimate(quasi.mass, quasi.velocity, quasi.x_c, rate, density, shear_modulus,
                     poisson_ratio)  # fmt: skip


def impact_radiation(
    mass: float,
    velocity: float,
    law: PowerLawContact | SneddonContact,
    density: float,
    half_space: Material,
    exact: ProfileImpactResult | None = None,
) -> RadiationEstimate:
    """The first-order radiation estimate of the quasi-static impact of ``mass`` kg at
    ``velocity`` m/s on ``law`` (the power law's closed form; a sphere's or a table's Int
    (dP/dt)^2 dt by quadrature over its exact impact, ``exact`` when already solved) on
    ``half_space`` of ``density`` kg/m^3; a massless half-space (density 0) radiates nothing."""
    from .profile_impact import solve_profile_impact  # here: the power law's needs none
    from .sneddon import SneddonContact

    shear, nu = half_space.shear_modulus, half_space.poisson_ratio
    rho = density if density > 0 else 1.0
    if isinstance(law, SneddonContact):
        exact = solve_profile_impact(mass, velocity, law) if exact is None else exact
        estimate = profile_radiation_estimate(exact, rho, shear, nu)
    else:
        estimate = radiation_estimate(mass, velocity, law.beta, law.force_exponent, rho, shear, nu)
    if density > 0:
        return estimate
    return replace(
        estimate, shear_wave_speed=math.inf, radiated_energy=0.0, energy_fraction=0.0,
        restitution=1.0,
    )  # fmt: skip


def _estimate(
    m: float, v0: float, x_m: float, rate: float, rho: float, g: float, poisson_ratio: float
) -> RadiationEstimate:
    """The estimate of an impact of ``m`` kg at ``v0`` m/s reaching ``x_m`` m with
    Int (dP/dt)^2 dt = ``rate`` N^2/s, on a body of density ``rho``, shear modulus ``g``
    (both checked here, by :func:`radiated_energy`)."""
    energy = radiated_energy(rate, rho, g, poisson_ratio)
    fraction = energy / (0.5 * m * v0**2)
    return RadiationEstimate(
        radiation_integral=radiation_integral(poisson_ratio),
        shear_wave_speed=math.sqrt(float(g) / float(rho)),
        max_depth=x_m,
        force_rate_squared_integral=rate,
        radiated_energy=energy,
        energy_fraction=fraction,
        restitution=float(np.sqrt(1.0 - fraction)) if fraction < 1.0 else math.nan,
    )
