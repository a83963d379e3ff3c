"""Periodic Ateb functions Sa(m, n, phi) and Ca(n, m, phi), exact to machine precision.

Definition
----------
The periodic Ateb functions of the Ukrainian school (Senik 1969; Sokil 1997; Gritsyk and
Nazarkevych 2007), the inverses of incomplete beta functions that Rosenberg (1963) introduced
for the oscillator ``x'' + x^m = 0``, are the solution ``x = Ca(n, m, phi)``,
``y = Sa(m, n, phi)`` of

    dCa/dphi = -(2 / (1 + n)) Sa^m,    dSa/dphi = (2 / (1 + m)) Ca^n,
    Ca(0) = 1,                          Sa(0) = 0,

with odd real powers ``y^m = sign(y) |y|^m``.  They satisfy

    |Ca|^(n + 1) + |Sa|^(m + 1) = 1,

and are periodic with period ``2 Pi(m, n)``, where the half-period is

    Pi(m, n) = B(1/(m + 1), 1/(n + 1))        (B: Euler's beta function).

For ``m = n = 1`` they are ``cos`` and ``sin`` and ``Pi = pi``.

Evaluation
----------
On the first quarter ``0 <= phi <= Pi/2``, integrating
``dSa/dphi = (2/(1+m)) (1 - Sa^(m+1))^(n/(n+1))`` with ``u = xi^(m+1)`` gives
``2 phi / Pi = I(Sa^(m+1); 1/(m+1), 1/(n+1))``, the regularized incomplete beta function, so

    Sa^(m+1) = betaincinv(1/(m+1), 1/(n+1), 2 phi / Pi),
    Ca^(n+1) = 1 - Sa^(m+1) = betaincinv(1/(n+1), 1/(m+1), 1 - 2 phi / Pi),

the second by ``I(x; a, b) = 1 - I(1 - x; b, a)``, which is the complement computed without
forming ``1 - Sa^(m+1)``: each function is evaluated from the distance of ``phi`` to its own
zero, so neither loses digits where it is small.  The other quarters follow from the symmetries
``Sa(-phi) = -Sa(phi)``, ``Ca(-phi) = Ca(phi)``, ``Sa(Pi - phi) = Sa(phi)``,
``Ca(Pi - phi) = -Ca(phi)``.  Where the function is so small that ``value^(exponent + 1)``
is below ``2^-56``, its Taylor term ``2 d / (1 + exponent)`` (``d``: distance to the zero) is
used instead, exact to rounding there, because ``betaincinv`` clamps at the smallest normal
double.  The only error beyond a few ulps is that of the argument reduction, about
``eps * |phi|`` absolute, as for any trigonometric function whose period is not exact in floating
point.

The paper's functions
---------------------
Ol'shanskii et al. (2019) write the compression of the impact ``M x'' = -beta x^(5/3)`` as
``x / x_c = Sa(5/3, 1, (4/3) eta)`` with ``eta = v0 t / x_c``: with ``m = 5/3``, ``n = 1``,
``dSa/dphi = (3/4) sqrt(1 - Sa^(8/3))``, i.e. ``phi = (4/3) Int_0^Sa dxi / sqrt(1 - xi^(8/3))``.
That is ``ateb_sine(5/3, 1, 4/3 * eta)``; its quarter period is ``(4/3) I`` with
``I = B(3/8, 1/2) / (8/3) = 1.4459274722...``.  The restitution ``x / x_c = Ca(5/3, 1, (4/3)
zeta)``, ``zeta = v0 (t - t_c) / x_c``, is ``ateb_cosine(5/3, 1, 4/3 * zeta)`` (``n = 5/3``,
``m = 1``: ``dCa/dphi = -(3/4) sqrt(1 - Ca^(8/3))``), and it equals
``ateb_sine(5/3, 1, 4/3 * (I - zeta))`` (the general mirror ``Ca(n, m, phi) = Sa(n, m, Pi(n, m)/2
- phi)``): the paper's Table 2 is its Table 1 mirrored about ``eta = I``.  For a general force law
``P = beta x^q`` the compression is ``ateb_sine(q, 1, (q + 1) / 2 * eta)``.

References
----------
Rosenberg R. M., The Ateb(h)-functions and their properties, Quart. Appl. Math. 21 (1963) 37-47.
Senik P. M., Inversion of the incomplete beta function, Ukr. Math. J. 21 (1969) 271-278.
Ol'shanskii V. et al., Eastern-European J. Enterprise Technol. 1/7 (97) (2019),
doi:10.15587/1729-4061.2019.155854.
"""

from __future__ import annotations

import numpy as np
from numpy.typing import ArrayLike, NDArray
from scipy.special import beta, betainc, betaincinv

from ..validation import InputError, validate_positive

__all__ = ["ateb_cosine", "ateb_half_period", "ateb_pair", "ateb_sine", "quarter_period"]

_LINEAR_LIMIT = 2.0**-56
"""Below this value of ``f^(exponent+1)`` the linear Taylor term is exact to rounding."""


def _validate_exponent(name: str, value: float) -> float:
    return validate_positive(f"{name} (Ateb exponent)", value)


def _inputs(phi: ArrayLike, **exponents: float) -> tuple[float, float, NDArray, float]:
    """m, n (validated in the order given), the phase as floats and the quarter period."""
    values = {name: _validate_exponent(name, value) for name, value in exponents.items()}
    array = np.asarray(phi)
    if array.dtype.kind not in "biuf":
        raise InputError(f"phi must be real numbers, got an array of dtype {array.dtype}")
    m, n = values["m"], values["n"]
    return m, n, array.astype(np.float64, copy=False), quarter_period(m, n)


def ateb_half_period(m: float, n: float) -> float:
    """Half-period Pi(m, n) = B(1/(m+1), 1/(n+1)) of Sa(m, n, .) and Ca(n, m, .).

    Parameters
    ----------
    m : float
        Exponent of Sa in ``Ca^(n+1) + Sa^(m+1) = 1``; > 0.
    n : float
        Exponent of Ca; > 0.

    Returns
    -------
    float
        The half-period (dimensionless phase); the full period is twice it.
        ``pi`` for ``m = n = 1``.
    """
    m = _validate_exponent("m", m)
    n = _validate_exponent("n", n)
    return float(beta(1.0 / (m + 1.0), 1.0 / (n + 1.0)))


def quarter_period(m: float, n: float) -> float:
    """Quarter period Pi(m, n)/2: the first zero of Ca(n, m, .) and maximum of Sa(m, n, .).

    Parameters
    ----------
    m, n : float
        The exponents, as in :func:`ateb_half_period`; > 0.

    Returns
    -------
    float
        ``B(1/(m+1), 1/(n+1)) / 2``; ``(4/3) I = 1.92790...`` for the paper's ``m = 5/3, n = 1``.
    """
    return 0.5 * ateb_half_period(m, n)


def _small_root(power: NDArray[np.float64], distance: NDArray[np.float64], own: float):
    """power^(1/(own+1)), or the Taylor term where the power is below ``betaincinv``'s reach."""
    linear = (2.0 / (1.0 + own)) * distance
    return np.where(linear ** (own + 1.0) < _LINEAR_LIMIT, linear, power ** (1.0 / (own + 1.0)))


def _quarter_wave(
    distance: NDArray[np.float64], quarter: float, own: float, other: float
) -> NDArray[np.float64]:
    """|Ateb function| at ``distance`` (0..quarter) from its zero; ``own``: its exponent."""
    power = betaincinv(1.0 / (own + 1.0), 1.0 / (other + 1.0), distance / quarter)
    return _small_root(power, distance, own)


def _reduce(phi: NDArray[np.float64], quarter: float) -> tuple[NDArray[np.float64], ...]:
    """Distances of |phi| to the zeros of Sa and Ca in its quarter, and their signs there."""
    with np.errstate(invalid="ignore"):
        index, rest = np.divmod(np.abs(phi), quarter)
        index = np.mod(index, 4.0)
    odd = (index == 1.0) | (index == 3.0)
    complement = quarter - rest
    sine_distance = np.where(odd, complement, rest)
    cosine_distance = np.where(odd, rest, complement)
    sine_sign = np.where(index < 2.0, 1.0, -1.0)
    cosine_sign = np.where((index == 0.0) | (index == 3.0), 1.0, -1.0)
    return sine_distance, cosine_distance, sine_sign, cosine_sign


def ateb_sine(m: float, n: float, phi: ArrayLike) -> np.ndarray | float:
    """Periodic Ateb-sine Sa(m, n, phi), vectorised over ``phi``.

    Parameters
    ----------
    m : float
        Exponent of Sa itself: ``|Ca|^(n+1) + |Sa|^(m+1) = 1``; > 0.
    n : float
        Exponent of its companion Ca(n, m, .) in ``dSa/dphi = (2/(1+m)) Ca^n``; > 0.
    phi : array_like
        Phase (dimensionless), any real values; NaN and infinities give NaN.

    Returns
    -------
    numpy.ndarray or float
        Sa(m, n, phi), same shape as ``phi`` (a NumPy float for a scalar).  Odd, period
        ``2 Pi(m, n)``, maximum 1 at ``Pi/2``; ``sin(phi)`` for ``m = n = 1``.

    Raises
    ------
    InputError
        If ``m`` or ``n`` is not a finite number > 0, or ``phi`` is not real.

    Examples
    --------
    The paper's compression ``x / x_c = Sa(5/3, 1, (4/3) v0 t / x_c)``:

    >>> round(float(ateb_sine(5 / 3, 1, 4 / 3 * 0.5)), 6)
    0.489372
    """
    m, n, phase, quarter = _inputs(phi, m=m, n=n)
    distance, _, sign, _ = _reduce(phase, quarter)
    value = np.copysign(1.0, phase) * sign * _quarter_wave(distance, quarter, m, n)
    return value[()]


def ateb_cosine(n: float, m: float, phi: ArrayLike) -> np.ndarray | float:
    """Periodic Ateb-cosine Ca(n, m, phi), vectorised over ``phi``.

    Parameters
    ----------
    n : float
        Exponent of Ca itself: ``|Ca|^(n+1) + |Sa|^(m+1) = 1``; > 0.
    m : float
        Exponent of its companion Sa(m, n, .) in ``dCa/dphi = -(2/(1+n)) Sa^m``; > 0.
    phi : array_like
        Phase (dimensionless), any real values; NaN and infinities give NaN.

    Returns
    -------
    numpy.ndarray or float
        Ca(n, m, phi), same shape as ``phi`` (a NumPy float for a scalar).  Even, period
        ``2 Pi(m, n)``, first zero at ``Pi/2``; ``cos(phi)`` for ``m = n = 1``.

    Raises
    ------
    InputError
        If ``m`` or ``n`` is not a finite number > 0, or ``phi`` is not real.

    Examples
    --------
    The paper's restitution ``x / x_c = Ca(5/3, 1, (4/3) v0 (t - t_c) / x_c)``:

    >>> round(float(ateb_cosine(5 / 3, 1, 4 / 3 * 0.5)), 6)
    0.840745
    """
    m, n, phase, quarter = _inputs(phi, n=n, m=m)
    _, distance, _, sign = _reduce(phase, quarter)
    value = sign * _quarter_wave(distance, quarter, n, m)
    return value[()]


def ateb_pair(m: float, n: float, phi: ArrayLike) -> tuple[np.ndarray, np.ndarray]:
    """Sa(m, n, phi) and Ca(n, m, phi) together, at the cost of one inversion per point.

    At each point only the smaller of ``|Sa|^(m+1)`` and ``|Ca|^(n+1)`` is inverted (from the
    distance to its own zero); the other is ``1 -`` it, which is at least 1/2 and so loses no
    digits. Same values as :func:`ateb_sine` and :func:`ateb_cosine` to a few ulps, half the work.

    Parameters
    ----------
    m, n : float
        The exponents, as in :func:`ateb_sine`; > 0.
    phi : array_like
        Phase (dimensionless), any real values.

    Returns
    -------
    tuple of numpy.ndarray
        ``(Sa(m, n, phi), Ca(n, m, phi))``, each shaped like ``phi``.
    """
    m, n, phase, quarter = _inputs(phi, m=m, n=n)
    sine_distance, cosine_distance, sine_sign, cosine_sign = _reduce(phase, quarter)
    a, b = 1.0 / (m + 1.0), 1.0 / (n + 1.0)
    sine_side = sine_distance / quarter <= betainc(a, b, 0.5)
    sine_power = np.empty_like(sine_distance)
    cosine_power = np.empty_like(sine_distance)
    sine_power[sine_side] = betaincinv(a, b, sine_distance[sine_side] / quarter)
    cosine_power[~sine_side] = betaincinv(b, a, cosine_distance[~sine_side] / quarter)
    cosine_power[sine_side] = 1.0 - sine_power[sine_side]
    sine_power[~sine_side] = 1.0 - cosine_power[~sine_side]
    sine = np.copysign(1.0, phase) * sine_sign * _small_root(sine_power, sine_distance, m)
    cosine = cosine_sign * _small_root(cosine_power, cosine_distance, n)
    return sine[()], cosine[()]
