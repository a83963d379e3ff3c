"""Power-law fits P = beta x^q of a computed force-depth curve."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike

from ..validation import InputError

__all__ = ["PowerLawFit", "exponent_sensitivity", "fit_power_law"]


@dataclass(frozen=True)
class PowerLawFit:
    """Least-squares fit of log P = log beta + q log x.

    Attributes
    ----------
    beta : float
        Fitted coefficient in N m^-q (q the fitted exponent).
    exponent : float
        Fitted exponent q.
    beta_fixed_exponent : float
        beta in N m^-q0 with the exponent held at ``fixed_exponent``.
    fixed_exponent : float
        q0, the theory's exponent.
    log_residual : float
        Root-mean-square residual of log P in the free fit (0 for an exact power law).
    """

    beta: float
    exponent: float
    beta_fixed_exponent: float
    fixed_exponent: float
    log_residual: float


def fit_power_law(depths: ArrayLike, forces: ArrayLike, fixed_exponent: float) -> PowerLawFit:
    """Fit P = beta x^q to positive depths x (m) and forces P (N), freely and with q fixed.

    Parameters
    ----------
    depths, forces : array_like
        Positive points. One point determines only the fixed-exponent fit: the free fit's
        ``beta``, ``exponent`` and ``log_residual`` are then NaN (nothing was measured).
    fixed_exponent : float
        The exponent of the theory, (n + 1)/n, for the second fit.
    """
    x, P = np.atleast_1d(depths).astype(float), np.atleast_1d(forces).astype(float)
    if x.size < 1 or np.any(x <= 0) or np.any(P <= 0):
        raise InputError("the fit needs positive depths with positive forces")
    log_x, log_P = np.log(x), np.log(P)
    fixed = np.exp(np.mean(log_P - fixed_exponent * log_x))
    if x.size == 1:
        return PowerLawFit(np.nan, np.nan, float(fixed), float(fixed_exponent), np.nan)
    exponent, log_beta = np.polyfit(log_x, log_P, 1)
    residual = log_P - (log_beta + exponent * log_x)
    return PowerLawFit(
        beta=float(np.exp(log_beta)),
        exponent=float(exponent),
        beta_fixed_exponent=float(fixed),
        fixed_exponent=float(fixed_exponent),
        log_residual=float(np.sqrt(np.mean(residual**2))),
    )


def exponent_sensitivity(depths: ArrayLike) -> float:
    """The most the fitted exponent q of :func:`fit_power_law` moves per relative force error:
    S = sum |w_i|, w_i = (log x_i - m) / sum_j (log x_j - m)^2 the least-squares slope's weights
    (m the mean of the log x_j); forces within a relative error eps move q by at most S eps.

    Parameters
    ----------
    depths : array_like
        The fit's depths in m, positive, at least two distinct.

    Returns
    -------
    float
        S: the bound on |dq| (dimensionless) per unit relative force error.
    """
    log_x = np.log(np.atleast_1d(depths).astype(float))
    centred = log_x - np.mean(log_x)
    return float(np.sum(np.abs(centred)) / np.sum(centred**2))
