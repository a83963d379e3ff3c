"""Axisymmetric striker profiles beyond the power law: the exact sphere and a tabulated z(r).

Each profile f(r) (m, f(0) = 0 at the tip, increasing) gives the contact law through
Sneddon's integrals (:mod:`shtaerman.theory.sneddon`), which need its slope f'(r), and the FEM
gap (:meth:`profile`). Like :class:`~shtaerman.theory.indenter.PowerLawIndenter`, each has a
``kind`` and ``parameters`` (the JSON's ``profile`` object) and ``radius_at`` (the radius at
which the profile reaches a height, which sizes the FEM's contact zone).

A tabulated profile is interpolated in s = r^2: z = G(r^2) with G the monotone cubic (PCHIP)
through the points (r_i^2, z_i). So the tip is smooth (f'(0) = 0), a sampled paraboloid is
reproduced exactly (PCHIP reproduces a linear G), and Sneddon's integrals of the piecewise
cubic G are exact Gauss-Legendre sums per piece
(:class:`shtaerman.theory.sneddon.SneddonContact`).
"""

from __future__ import annotations

import math
import sys
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np
from numpy.typing import ArrayLike
from scipy.interpolate import PchipInterpolator

from ..input_file import csv_rows, read_input_csv
from ..validation import InputError, bound_text, plain_float, validate_positive
from ..vocabulary import MAX_PROFILE_ROWS, MAX_SPHERE_RADIUS

__all__ = [
    "MAX_PROFILE_ROWS",
    "MAX_SPHERE_RADIUS",
    "SphereIndenter",
    "TabulatedIndenter",
]


@dataclass(frozen=True)
class SphereIndenter:
    """The exact sphere of radius R: z = R - sqrt(R^2 - r^2) for r <= R.

    Parameters
    ----------
    radius : float
        R in m. Beyond r = R the profile stays at z = R (the equator: no part of the sphere
        is lower there, and no contact reaches it, since the depth diverges as a -> R).
    """

    radius: float

    kind = "sphere"

    def __post_init__(self) -> None:
        radius = validate_positive("radius", self.radius, "m")
        if radius > MAX_SPHERE_RADIUS:
            raise InputError(
                f"radius must be in (0, {MAX_SPHERE_RADIUS:g}] m, got {radius:g} (a larger "
                "sphere is the paraboloid z = r^2 / 2R: exponent 2, shape coefficient 1/(2R))",
                "radius",
            )
        object.__setattr__(self, "radius", radius)

    @property
    def parameters(self) -> dict[str, float]:
        """The JSON's ``profile.parameters``: radius in m."""
        return {"radius": self.radius}

    def profile(self, radius: ArrayLike) -> np.ndarray:
        """Height z(r) of the surface above its tip in m at radius r in m."""
        r = np.minimum(np.abs(np.asarray(radius, dtype=float)), self.radius)
        return r**2 / (self.radius + np.sqrt((self.radius - r) * (self.radius + r)))

    def slope(self, radius: ArrayLike) -> np.ndarray:
        """f'(r) = r / sqrt(R^2 - r^2) at radii r >= 0 in m (0 beyond R, where z stays R)."""
        r = np.asarray(radius, dtype=float)
        inside = r < self.radius
        slope = np.zeros_like(r)
        slope[inside] = r[inside] / np.sqrt((self.radius - r[inside]) * (self.radius + r[inside]))
        return slope

    def curvature(self, radius: ArrayLike) -> np.ndarray:
        """f''(r) = R^2 / (R^2 - r^2)^(3/2) in 1/m at radii r >= 0 in m (0 beyond R)."""
        r = np.asarray(radius, dtype=float)
        inside = r < self.radius
        curvature = np.zeros_like(r)
        squared = (self.radius - r[inside]) * (self.radius + r[inside])
        curvature[inside] = self.radius**2 / squared**1.5
        return curvature

    def radius_at(self, height: ArrayLike) -> np.ndarray:
        """The radius r in m at which z(r) = height (m), sqrt(2 R h - h^2); R beyond h = R."""
        h = np.minimum(np.asarray(height, dtype=float), self.radius)
        return np.sqrt(h * (2.0 * self.radius - h))


def _float(text: str, row: int, column: str, path: Path) -> float:
    try:
        value = plain_float(text)
    except ValueError:
        value = math.nan
    if not math.isfinite(value):
        raise InputError(
            f"profile: {str(path)!r} line {row}, column {column}: expected a finite number in m, "
            f"got {text!r}",
            "profile",
        )
    return value


def _read_rows(path: Path) -> tuple[np.ndarray, np.ndarray, list[int]]:
    """The columns r and z (m) of a profile CSV with a header naming ``r`` and ``z`` (blank
    lines and ``#`` comment lines skipped; a row is named by its line in the file), and the
    line of each row.

    Raises
    ------
    shtaerman.validation.InputError
        One line naming the file and the row or column at fault.
    """
    path = Path(path)
    # the header and one row past the most a table takes: a huge file is refused unparsed
    rows, lines = csv_rows(
        read_input_csv(path, "profile", "profile"),
        f"profile: {str(path)!r}",
        "profile",
        MAX_PROFILE_ROWS + 2,
    )
    header = [_header_name(cell, path) for cell in rows[0]] if rows else []
    missing = [name for name in ("r", "z") if name not in header]
    if missing:
        raise InputError(
            f"profile: {str(path)!r} needs a header row naming the columns r and z (m); "
            f"column {missing[0]} is missing",
            "profile",
        )
    twice = next((name for name in ("r", "z") if header.count(name) > 1), None)
    if twice is not None:  # which one is meant?
        raise InputError(f"profile: {str(path)!r} names column {twice} twice; keep one", "profile")
    columns = {name: header.index(name) for name in ("r", "z")}
    values = []
    for number, row in zip(lines[1:], rows[1:], strict=True):
        for name, index in columns.items():
            if index >= len(row):
                raise InputError(
                    f"profile: {str(path)!r} line {number}, column {name}: missing", "profile"
                )
        values.append([_float(row[columns[n]].strip(), number, n, path) for n in ("r", "z")])
    table = np.array(values, dtype=float).reshape(-1, 2) + 0.0  # -0.0 is the tip 0
    return table[:, 0], table[:, 1], lines[1:]


def _header_name(cell: str, path: Path) -> str:
    """A header cell's column name: ``r``, ``r [m]`` -> ``r``; a unit other than m refused."""
    name, _, unit = cell.strip().lower().partition("[")
    if unit and unit.rstrip("] ").strip() != "m" and name.strip() in ("r", "z"):
        raise InputError(
            f"profile: {str(path)!r} column {name.strip()}: unit [{unit.rstrip('] ').strip()}] "
            "is not m; give r and z in m (header 'r [m],z [m]' or 'r,z')",
            "profile",
        )
    return name.strip()


TIP_ROWS = 3
"""The rows beyond the tip over which a table's tip exponent is measured
(:attr:`TabulatedIndenter.tip_exponent`; all of a 3-row table's 2)."""

_SMALLEST_R, _LARGEST_R = math.sqrt(sys.float_info.min), math.sqrt(sys.float_info.max)
"""The radii whose squares (the interpolation's variable) are normal floats, in m."""


def _check_table(r: np.ndarray, z: np.ndarray, lines: list[int] | None = None) -> None:
    """A profile table starts at the tip (0, 0) and rises: r and z strictly increasing. Row
    k is named by ``lines[k]``, its file line (None: the API's arrays, by index k)."""
    line = (lambda k: f"line {lines[k]}") if lines is not None else (lambda k: f"index {k}")
    if r.size < 3:
        raise InputError(f"profile: needs at least 3 rows (r, z), got {r.size}", "profile")
    if r.size > MAX_PROFILE_ROWS:
        count = f"more than {MAX_PROFILE_ROWS}" if lines is not None else r.size  # a file is
        # read to one row past the most
        raise InputError(
            f"profile: takes at most {MAX_PROFILE_ROWS} rows (r, z), got {count}; resample "
            "the tip more coarsely",
            "profile",
        )
    if r[0] != 0.0 or z[0] != 0.0:
        raise InputError(
            f"profile: {line(0)} (the first) must be the tip r = 0, z = 0, got r = {r[0]:g}, "
            f"z = {z[0]:g}",
            "profile",
        )
    with np.errstate(all="ignore"):
        squares = r * r
    if not (np.isfinite(squares[-1]) and squares[1] >= sys.float_info.min):
        raise InputError(  # the table is interpolated in r^2: its squares must be floats
            f"profile: column r must lie within [{bound_text(_SMALLEST_R, 'low')}, "
            f"{bound_text(_LARGEST_R, 'high')}] m beyond the tip (it is interpolated in "
            f"r^2), got {r[1]:g} to {r[-1]:g}",
            "profile",
        )
    for name, values in (("r", r), ("z", z)):
        step = np.flatnonzero(np.diff(values) <= 0.0)
        if step.size:
            row = line(int(step[0]) + 1)
            raise InputError(
                f"profile: column {name} must increase strictly from row to row; {row} "
                f"has {name} = {values[step[0] + 1]:g} after {values[step[0]]:g}",
                "profile",
            )


def _interpolant(r: np.ndarray, z: np.ndarray) -> PchipInterpolator:
    """The PCHIP of z in r^2 of a checked table (:func:`_check_table`), refused where its
    weights (r^2 steps squared over z steps) leave the floats: a node's slope dz/d(r^2) came
    out infinite (a sphere of R = 5e-152 m tabulated from r = 1e-153 m: a traceback) or 0
    (R = 5e148 m: a staircase, refused as reaching beyond its last row)."""
    with np.errstate(all="ignore"):
        try:
            interpolant = PchipInterpolator(r**2, z, extrapolate=True)
            slopes = interpolant(r**2, 1)
        except ValueError:  # scipy's "dydx must contain only finite values"
            slopes = np.array([math.nan])
    if not (np.all(np.isfinite(slopes)) and np.all(slopes[1:-1] > 0.0)):
        raise InputError(
            f"profile: rows r {r[1]:g} to {r[-1]:g} m, z {z[1]:g} to {z[-1]:g} m are beyond "
            "what the floats interpolate in r^2 (its slopes dz/d(r^2) overflow or vanish); "
            "give a tip of a physical size (a sphere's rows: R from 1e-6 to 1e6 m)",
            "profile",
        )
    return interpolant


@dataclass(frozen=True, eq=False)
class TabulatedIndenter:
    """A measured tip z(r): points (r_i, z_i) in m from the tip r = 0, z = 0, both increasing.

    Parameters
    ----------
    radii, heights : array_like
        r_i and z_i in m. Interpolated by the monotone cubic (PCHIP) in r^2 (see the module);
        beyond the last radius the profile is extended by its last slope (no contact may
        reach it: the entry points refuse a contact radius beyond the table).
    source : str, optional
        Where the points came from (the CSV's path), for the JSON.
    """

    radii: np.ndarray
    heights: np.ndarray
    source: str | None = None
    interpolant: PchipInterpolator = field(init=False, repr=False)

    kind = "tabulated"

    def __post_init__(self) -> None:
        try:
            r = np.asarray(self.radii, dtype=float).ravel() + 0.0  # -0.0 is the tip 0
            z = np.asarray(self.heights, dtype=float).ravel() + 0.0
        except (TypeError, ValueError):  # text, None, ragged lists
            raise InputError("profile: radii and heights must be numbers in m", "profile") from None
        if r.shape != z.shape or not (np.all(np.isfinite(r)) and np.all(np.isfinite(z))):
            raise InputError("profile: radii and heights must be finite, of one length", "profile")
        _check_table(r, z)
        object.__setattr__(self, "radii", r)
        object.__setattr__(self, "heights", z)
        object.__setattr__(self, "interpolant", _interpolant(r, z))

    @classmethod
    def from_csv(cls, path: str | Path) -> TabulatedIndenter:
        """The profile of a CSV file with columns r and z in m (header row; see the class)."""
        r, z, lines = _read_rows(Path(path))
        try:
            _check_table(r, z, lines)  # its rows named by their file lines
            return cls(r, z, str(path))
        except InputError as error:  # the file first, as the rows' own messages name it
            reason = str(error).removeprefix("profile: ")
            raise InputError(f"profile: {str(path)!r}: {reason}", "profile") from None

    @property
    def parameters(self) -> dict[str, object]:
        """The JSON's ``profile.parameters``: the file, the number of points and the last
        radius (m)."""
        return {"file": self.source, "points": int(self.radii.size), "r_max": self.r_max}

    @property
    def tip_exponent(self) -> float:
        """n of z ~ r^n at the tip as the table gives it: the least-squares slope of ln z
        against ln r over its first :data:`TIP_ROWS` rows beyond the tip (3 for the rows of
        z = 50 r^3; 2 for a sphere's rows well inside its radius)."""
        rows = slice(1, TIP_ROWS + 1)
        return float(np.polyfit(np.log(self.radii[rows]), np.log(self.heights[rows]), 1)[0])

    @property
    def r_max(self) -> float:
        """The table's last radius in m: no contact may reach beyond it."""
        return float(self.radii[-1])

    def profile(self, radius: ArrayLike) -> np.ndarray:
        """Height z(r) in m at radius r in m (the last slope beyond the table)."""
        r = np.abs(np.asarray(radius, dtype=float))
        inside = self.interpolant(np.minimum(r, self.r_max) ** 2)
        slope = 2.0 * self.r_max * self.interpolant(self.r_max**2, 1)
        return inside + slope * np.maximum(r - self.r_max, 0.0)

    def slope(self, radius: ArrayLike) -> np.ndarray:
        """f'(r) = 2 r G'(r^2) at radii r >= 0 in m (the last slope beyond the table)."""
        r = np.minimum(np.abs(np.asarray(radius, dtype=float)), self.r_max)
        return 2.0 * r * self.interpolant(r**2, 1)

    def curvature(self, radius: ArrayLike) -> np.ndarray:
        """f''(r) = 2 G'(r^2) + 4 r^2 G''(r^2) in 1/m at radii r >= 0 in m (0 beyond the
        table)."""
        r = np.abs(np.asarray(radius, dtype=float))
        s = np.minimum(r, self.r_max) ** 2
        curvature = 2.0 * self.interpolant(s, 1) + 4.0 * s * self.interpolant(s, 2)
        return np.where(r > self.r_max, 0.0, curvature)

    def radius_at(self, height: ArrayLike) -> np.ndarray:
        """The radius r in m at which z(r) = height (m) (the monotone inverse)."""
        h = np.asarray(height, dtype=float)
        roots = [self._root(float(value)) for value in h.ravel()]
        return np.array(roots, dtype=float).reshape(h.shape)

    def _root(self, height: float) -> float:
        from scipy.optimize import brentq

        if height <= 0.0:
            return 0.0
        top = float(self.heights[-1])
        if height >= top:
            slope = 2.0 * self.r_max * float(self.interpolant(self.r_max**2, 1))
            return self.r_max + (height - top) / slope
        s = brentq(
            lambda s: float(self.interpolant(s)) - height,
            0.0,
            self.r_max**2,
            xtol=1e-300,
            rtol=1e-15,
        )
        return math.sqrt(s)
