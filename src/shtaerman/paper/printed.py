"""The paper's printed tables, as data, and its piecewise approximations of Sa and Ca.

Ol'shanskii, Spol'nik, Slipchenko, Znaidiuk (2019), doi:10.15587/1729-4061.2019.155854, print
Tables 1-2 (the Ateb-sine and Ateb-cosine of the impact, with approximations in brackets),
Table 3 (x(t)/x_c by two procedures), Tables 4-6 (impact characteristics against A, v0, M) and
the scalars of a worked example.  They are stored once, exactly as printed, in
``shtaerman/paper/paper_tables.json`` (format described in its ``"format"`` field); they are
data to compare against: the exact functions are in :mod:`shtaerman.theory.ateb`.

The approximations, with ``I = B(3/8, 1/2) / (8/3) = 1.4459274722...``:

    Sa(5/3, 1, (4/3) eta) ~ eta                                           0 <= eta <= 0.2
                          ~ 0.1996 + 1.0277 (eta - 0.2) - 0.2064 (eta - 0.2)^2   0.2 < eta < 0.8
                          ~ 1 - 1.2 sin^2[(sqrt(5)/3) (I - eta)]          0.8 <= eta <= I

    Ca(5/3, 1, (4/3) zeta) ~ 1 - 1.2 sin^2[(sqrt(5)/3) zeta]              0 <= zeta <= 0.75
                           ~ 0.1996 + 1.0277 (1.2459 - zeta) - 0.2064 (1.2459 - zeta)^2
                                                                          0.75 < zeta < 1.25
                           ~ I - zeta                                     1.25 <= zeta <= I

The paper prints the last branch of the cosine as ``zeta``; it must be ``I - zeta`` (the mirror
of the sine's first branch, and what reproduces the bracketed values of Table 2).
"""

from __future__ import annotations

import json
import math
from importlib.resources import files
from typing import Any

import numpy as np
from numpy.typing import ArrayLike, NDArray
from scipy.special import beta

from ..validation import InputError

__all__ = [
    "INTEGRAL_I",
    "load_printed",
    "paper_cosine_approximation",
    "paper_sine_approximation",
    "printed_table",
]

INTEGRAL_I: float = float(beta(3.0 / 8.0, 0.5) * 3.0 / 8.0)
"""I = Int_0^1 dxi / sqrt(1 - xi^(8/3)) = B(3/8, 1/2) / (8/3) = 1.4459274722... (paper 1.445927)."""

_OMEGA = math.sqrt(5.0) / 3.0


def load_printed() -> dict[str, Any]:
    """Read the paper's printed tables and scalars from the package data.

    Returns
    -------
    dict
        The parsed ``shtaerman/paper/paper_tables.json``: ``"tables"`` (``"table1"`` ...
        ``"table6"``, each with columns, rows as printed, decimals, corrections, accuracy,
        notes), ``"example"`` (inputs, results, constants with units) and ``"source"``.
        A new dict on every call, so callers may modify it.
    """
    resource = files("shtaerman.paper") / "paper_tables.json"
    return json.loads(resource.read_text(encoding="utf-8"))


def printed_table(name: str, *, corrected: bool = True) -> dict[str, NDArray[np.float64]]:
    """One printed table as arrays in SI units (printed number / column scale).

    Parameters
    ----------
    name : str
        ``"table1"`` ... ``"table6"``.
    corrected : bool, optional
        Apply the table's listed misprint corrections (e.g. the rows printed ``101`` are
        ``10 I``); default True.

    Returns
    -------
    dict of str to numpy.ndarray
        Column key (e.g. ``"eta"``, ``"sine"``, ``"P_c"``) to its values in the column's unit.
    """
    tables = load_printed()["tables"]
    if name not in tables:
        raise InputError(f"Unknown table '{name}'. Pick one of {sorted(tables)}")
    table = tables[name]
    keys = [column["key"] for column in table["columns"]]
    rows = np.array(table["rows"], dtype=float)
    if corrected:
        for fix in table["corrections"]:
            rows[fix["row"], keys.index(fix["column"])] = fix["corrected"]
    scales = np.array([column["scale"] for column in table["columns"]], dtype=float)
    return {key: rows[:, j] / scales[j] for j, key in enumerate(keys)}


def _validate_interval(name: str, value: ArrayLike) -> NDArray[np.float64]:
    try:
        array = np.asarray(value, dtype=float)
    except (TypeError, ValueError):
        raise InputError(f"{name} must be real numbers, got {value!r}") from None
    if not np.all((array >= 0.0) & (array <= INTEGRAL_I)):
        raise InputError(f"{name} must lie in [0, I = {INTEGRAL_I:.10f}]")
    return array


def _quadratic(s: NDArray[np.float64]) -> NDArray[np.float64]:
    return 0.1996 + 1.0277 * s - 0.2064 * s**2


def _crest(s: NDArray[np.float64]) -> NDArray[np.float64]:
    return 1.0 - 1.2 * np.sin(_OMEGA * s) ** 2


def paper_sine_approximation(eta: ArrayLike) -> np.ndarray | float:
    """The paper's piecewise approximation of Sa(5/3, 1, (4/3) eta) (its Table 1, brackets).

    Parameters
    ----------
    eta : array_like
        Dimensionless time of compression ``v0 t / x_c``, in ``[0, I]``.

    Returns
    -------
    numpy.ndarray or float
        The approximation of ``x / x_c``; maximum relative error 0.654 % (paper: "< 1 %").

    Raises
    ------
    InputError
        If any ``eta`` lies outside ``[0, I]`` or is NaN.
    """
    eta = _validate_interval("eta", eta)
    value = np.where(
        eta <= 0.2,
        eta,
        np.where(eta < 0.8, _quadratic(eta - 0.2), _crest(INTEGRAL_I - eta)),
    )
    return value[()]


def paper_cosine_approximation(zeta: ArrayLike) -> np.ndarray | float:
    """The paper's piecewise approximation of Ca(5/3, 1, (4/3) zeta) (its Table 2, brackets).

    The last branch is ``I - zeta`` where the paper misprints ``zeta``.

    Parameters
    ----------
    zeta : array_like
        Dimensionless time of restitution ``v0 (t - t_c) / x_c``, in ``[0, I]``.

    Returns
    -------
    numpy.ndarray or float
        The approximation of ``x / x_c``; maximum relative error 0.645 % (paper: "< 1 %").
        Discontinuous at ``zeta = 0.75`` and ``1.25`` (jumps of 4.0e-3 and 5.4e-4).

    Raises
    ------
    InputError
        If any ``zeta`` lies outside ``[0, I]`` or is NaN.
    """
    zeta = _validate_interval("zeta", zeta)
    value = np.where(
        zeta <= 0.75,
        _crest(zeta),
        np.where(zeta < 1.25, _quadratic(1.2459 - zeta), INTEGRAL_I - zeta),
    )
    return value[()]
