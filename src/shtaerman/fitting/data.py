"""A measurement to fit: named columns in SI units, read from a CSV ``name [unit]`` header.

The columns each kind of measurement takes (:data:`KIND_COLUMNS`): an indentation curve
``depth [m]``, ``force [N]``; a drop test's force history ``time [s]``, ``force [N]``; rebound
data ``velocity [m/s]`` with ``restitution [1]`` and/or ``contact_time [s]`` (the whole time in
contact); a rebound resilience (ISO 4662) ``velocity [m/s]``, ``resilience [1]`` (the fraction
of the energy returned, e^2). A unit is taken from the header, else from ``units``, else SI.
Blank lines and lines starting with ``#`` (comments) are skipped. Every problem with the file is
an :class:`InputError` naming the column, or the row by its line number in the file.
"""

from __future__ import annotations

import math
import re
from collections.abc import Mapping
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np
from numpy.typing import ArrayLike

from ..input_file import csv_rows, read_input_csv
from ..validation import InputError, plain_float

__all__ = [
    "KINDS",
    "KIND_COLUMNS",
    "UNITS",
    "Measurement",
    "article",
    "check_history_options",
    "measured_unit",
    "measurement",
    "parse_units",
    "resampled",
]

KIND_COLUMNS: dict[str, tuple[tuple[str, ...], tuple[str, ...]]] = {
    "indentation": (("depth", "force"), ()),
    "force-history": (("time", "force"), ()),
    "rebound": (("velocity",), ("restitution", "contact_time")),
    "resilience": (("velocity", "resilience"), ()),
}
"""Kind -> (columns it needs, columns of which it needs at least one)."""
KINDS = tuple(KIND_COLUMNS)

ALIASES = {"t": "time", "x": "depth", "p": "force", "v0": "velocity"}
"""Other names a column may carry (read in lower case): those of the suite's own ``--history``
CSV (t, x, P) and the usual symbols."""

QUANTITY = {
    "depth": "length",
    "force": "force",
    "time": "time",
    "velocity": "velocity",
    "restitution": "ratio",
    "contact_time": "time",
    "resilience": "ratio",
}
"""Column -> the physical quantity its unit must measure."""
UNITS: dict[str, dict[str, float]] = {
    "length": {"m": 1.0, "mm": 1e-3, "um": 1e-6, "µm": 1e-6, "cm": 1e-2, "nm": 1e-9},
    "force": {"N": 1.0, "kN": 1e3, "mN": 1e-3, "uN": 1e-6, "µN": 1e-6},
    "time": {"s": 1.0, "ms": 1e-3, "us": 1e-6, "µs": 1e-6},
    "velocity": {"m/s": 1.0, "mm/s": 1e-3, "cm/s": 1e-2, "km/h": 1.0 / 3.6},
    "ratio": {"1": 1.0, "": 1.0, "%": 1e-2},
}
"""Quantity -> unit -> its value in SI."""
_HEADER = re.compile(r"^\s*([^\[\]]*?)\s*(?:\[\s*([^\[\]]*?)\s*\])?\s*$")


@dataclass(frozen=True)
class Measurement:
    """The measured columns of one kind, in SI units, and where they came from."""

    kind: str
    """One of :data:`KINDS`."""
    columns: Mapping[str, np.ndarray]
    """Column name -> values in SI units (m, N, s, m/s, 1)."""
    source: str = "data"
    """The file's path or ``data`` for values given in Python."""
    units: Mapping[str, str] = field(default_factory=dict)
    """Column name -> the unit it was written in."""
    lines: tuple[int, ...] | None = None
    """The file's line number of each data row (blank and ``#`` comment lines counted), or
    None for values given in Python (then row k is called index k)."""

    @property
    def rows(self) -> int:
        """Number of data rows."""
        return len(next(iter(self.columns.values())))

    def row(self, index: int) -> str:
        """How an error names data row ``index`` (0-based): ``line 7``, its file line, or
        ``index 0`` for values given in Python."""
        return f"line {self.lines[index]}" if self.lines is not None else f"index {index}"


def parse_units(text: str | None) -> dict[str, str]:
    """``depth=mm,force=kN`` -> {"depth": "mm", "force": "kN"} (the --units option)."""
    if not text:
        return {}
    units = {}
    for item in str(text).split(","):
        name, sep, unit = item.partition("=")
        if not sep or name.strip() not in QUANTITY:
            raise InputError(
                f"units must be written COLUMN=UNIT,... with COLUMN one of "
                f"{', '.join(QUANTITY)}, got {item.strip()!r}",
                "units",
            )
        _factor("units", name.strip(), unit.strip())  # a unit no column could take: now
        units[name.strip()] = unit.strip()
    return units


def _factor(where: str, name: str, unit: str) -> float:
    """The SI value of ``unit`` for column ``name``, or an InputError naming the column."""
    known = UNITS[QUANTITY[name]]
    if unit not in known:
        listed = ", ".join(u for u in known if u)
        raise InputError(
            f"{where}: column {name!r}: unit {unit!r} is not a {QUANTITY[name]} unit; "
            f"use one of {listed}",
            "units" if where == "units" else "data",
        )
    return known[unit]


def _header(where: str, row: list[str], line: int) -> list[tuple[str, str | None]]:
    """(name, unit or None) of each header cell; the header is on line ``line``."""
    cells = []
    for text in row:
        match = _HEADER.match(text)
        if match is None or not match[1]:
            empty = " (a trailing or doubled comma?)" if not text.strip() else ""
            raise InputError(
                f"{where}: line {line}: header cell {text!r} is not 'name [unit]'{empty}", "data"
            )
        cells.append((match[1].strip().lower().replace(" ", "_"), match[2]))
    return cells


def _read_csv(path: Path) -> tuple[list[tuple[str, str | None]], list[list[str]], list[int], int]:
    """The header's (name, unit) cells, the data rows of ``path``, their line numbers (blank
    lines and lines starting with ``#``, comments, skipped) and the header's line number."""
    where = str(path)
    rows, lines = csv_rows(read_input_csv(path, "data", "data"), where, "data")
    if not rows:
        raise InputError(f"{where}: the file is empty (expected a header 'name [unit]')", "data")
    return _header(where, rows[0], lines[0]), rows[1:], lines[1:], lines[0]


def _column(
    where: str, name: str, index: int, rows: list[list[str]], lines: list[int]
) -> np.ndarray:
    """Column ``index`` of the data rows as floats; an InputError names the row by its file
    line number (``lines``)."""
    try:  # at once: a million rows in a second; else row by row, to name the bad one
        values = np.array([row[index] for row in rows], dtype=float)
        if np.all(np.isfinite(values)):
            return values
    except (IndexError, ValueError):
        pass
    values = np.empty(len(rows))
    for number, row in enumerate(rows):
        text = row[index].strip() if index < len(row) else ""
        try:
            values[number], what = plain_float(text), "a finite number"
        except ValueError:
            values[number], what = math.nan, "a number"
        if not math.isfinite(values[number]):
            raise InputError(
                f"{where}: line {lines[number]}: column {name!r} holds {text!r}, not {what}", "data"
            )
    return values


def _from_file(kind: str, path: Path, units: Mapping[str, str]) -> Measurement:
    """The columns of ``kind`` read from the CSV at ``path``."""
    where = str(path)
    header, rows, lines, header_line = _read_csv(path)
    names = [ALIASES.get(name, name) for name, _ in header]
    columns, written = {}, {}
    for name in _wanted(kind, names, where, header):
        index = names.index(name)
        if names.count(name) > 1:  # which one is meant? (depth [m] beside depth [mm])
            again = names.index(name, index + 1)
            raise InputError(
                f"{where}: column {name!r} appears twice (columns {index + 1} and {again + 1} "
                "of the header); keep one",
                "data",
            )
        unit = header[index][1]
        if unit is not None and units.get(name, unit) != unit:  # which one is meant?
            raise InputError(
                f"{where}: line {header_line}: the header gives column {name!r} in [{unit}], "
                f"--units in {units[name]}; drop --units {name}= (it serves a header cell "
                "without a unit) or correct the header",
                "units",
            )
        unit = unit if unit is not None else units.get(name, measured_unit(name))
        written[name] = unit
        columns[name] = _column(where, name, index, rows, lines) * _factor(where, name, unit)
    return Measurement(kind, columns, where, written, tuple(lines))


def article(kind: str) -> str:
    """``kind`` with its indefinite article: "an indentation", "a rebound"."""
    return f"{'an' if kind[0] in 'aeiou' else 'a'} {kind}"


def measured_unit(name: str) -> str:
    """The SI unit of column ``name`` (``1`` for a ratio)."""
    return next(iter(UNITS[QUANTITY[name]]))


def _wanted(kind: str, names: list[str], where: str, header: list) -> list[str]:
    """The columns of ``kind`` present in the header, or an InputError naming the missing."""
    needed, some = KIND_COLUMNS[kind]
    shown = ", ".join(f"{n} [{u}]" if u is not None else n for n, u in header)
    for name in needed:  # ``names``: the header's, with ALIASES read as what they stand for
        if name not in names:
            wanted = ", ".join(f"{n} [{measured_unit(n)}]" for n in needed)
            raise InputError(
                f"{where}: no column {name!r} (the header has {shown}); {article(kind)} needs "
                f"{wanted}",
                "data",
            )
    present = [name for name in some if name in names]
    if some and not present:
        raise InputError(
            f"{where}: no column {' or '.join(repr(n) for n in some)} (the header has {shown})",
            "data",
        )
    return [*needed, *present]


def _check_values(data: Measurement) -> Measurement:
    """Refuse values no measurement of the kind can hold, naming the column and row."""
    if data.rows == 0:
        raise InputError(f"{data.source}: no data rows under the header", "data")
    for name, values in data.columns.items():
        bad = np.flatnonzero(~np.isfinite(values))
        if name in ("depth", "velocity", "contact_time", "restitution", "resilience"):
            bad = np.flatnonzero(~(values > 0) | ~np.isfinite(values))
        if name in ("restitution", "resilience"):
            bad = np.flatnonzero(~((values > 0) & (values <= 1)))
        if bad.size:
            valid = "in (0, 1]" if name in ("restitution", "resilience") else "> 0"
            valid = "finite" if name in ("force", "time") else valid
            raise InputError(
                f"{data.source}: {data.row(bad[0])}: column {name!r} must be {valid}, got "
                f"{values[bad[0]]:g}",
                "data",
            )
    if data.kind == "force-history":
        _check_history(data)
    if "force" in data.columns:
        _check_sign(data)
    if "time" in data.columns and np.any(np.diff(data.columns["time"]) <= 0):
        row = data.row(int(np.flatnonzero(np.diff(data.columns["time"]) <= 0)[0]) + 1)
        raise InputError(f"{data.source}: {row}: column 'time' must increase", "data")
    return data


def _check_history(data: Measurement) -> None:
    """A force history spans a time (at least 3 rows) and rises above zero force."""
    if data.rows < 3:
        raise InputError(
            f"{data.source}: a force-history needs at least 3 rows, got {data.rows}", "data"
        )
    largest = float(np.max(data.columns["force"])) + 0.0  # -0.0 is 0
    if largest <= 0.0:
        raise InputError(
            f"{data.source}: column 'force' must rise above 0 N (the striker's push), its "
            f"largest value is {largest:g} N",
            "data",
        )


def _check_sign(data: Measurement) -> None:
    """A push is positive: refuse a force column that swings further below 0 N than above it.

    The rule: refuse if ``-min(force) > max(force)``. A record of a push peaks at P > 0 while
    its noise (standard deviation s) dips to about -4 s, so a true record is refused only if
    its noise reaches a quarter of its peak (a record no fit can read) or if its baseline
    offset is below -(P - 4 s) / 2 (subtract that offset first); a record whose sign is flipped
    peaks at -P and passes only if its noise reaches it (4 s > P).
    """
    force = data.columns["force"]
    lowest, largest = int(np.argmin(force)), float(np.max(force)) + 0.0  # -0.0 is 0
    if -force[lowest] > largest:
        raise InputError(
            f"{data.source}: {data.row(lowest)}: column 'force' swings to {force[lowest]:.4g} N "
            f"but rises only to {largest:.4g} N: a push is positive; flip the record's sign",
            "data",
        )


def measurement(
    kind: str, data: str | Path | Mapping[str, ArrayLike], units: Mapping[str, str] | None = None
) -> Measurement:
    """The measurement of ``kind`` from a CSV path or a mapping column -> values (SI units).

    Parameters
    ----------
    kind : str
        One of :data:`KINDS`.
    data : str, Path or mapping
        A CSV file with a header ``name [unit]`` (units from the header, else ``units``, else
        SI), or the columns themselves in SI units.
    units : mapping, optional
        Column -> unit for header cells without one (e.g. ``{"depth": "mm"}``).

    Raises
    ------
    InputError
        One line naming the file's column or row that is missing or wrong.
    """
    if kind not in KIND_COLUMNS:
        raise InputError(f"kind must be one of {', '.join(KINDS)}, got {kind!r}", "kind")
    for name in units or {}:
        if name not in QUANTITY:
            raise InputError(
                f"units: unknown column {name!r}; one of {', '.join(QUANTITY)}", "units"
            )
    if isinstance(data, str | Path):
        return _check_values(_from_file(kind, Path(data), units or {}))
    if not isinstance(data, Mapping):
        raise InputError(
            "data: give a CSV file's path or a mapping column -> values, got "
            f"{type(data).__name__}",
            "data",
        )
    if units:  # a mapping's columns are SI: a unit given beside them was silently dropped
        raise InputError(
            "units: applies to a CSV file's header; the columns of a mapping are in SI units "
            "(convert them, or leave units unset)",
            "units",
        )
    names = list(data)
    header = [(name, None) for name in names]
    columns = {name: _numbers(name, data[name]) for name in _wanted(kind, names, "data", header)}
    if len({len(values) for values in columns.values()}) != 1:
        raise InputError("data: the columns must have equal lengths", "data")
    return _check_values(Measurement(kind, columns, "data", {n: measured_unit(n) for n in columns}))


def _numbers(name: str, values: ArrayLike) -> np.ndarray:
    """Column ``name`` of a mapping as floats, or one line naming it: strings and booleans
    (``True`` read as 1) are no measurement, and a table is no column."""
    array = np.atleast_1d(np.asarray(values))
    if array.dtype.kind not in "iuf" or array.ndim != 1:
        raise InputError(
            f"data: column {name!r} must be a one-dimensional array of numbers, got shape "
            f"{array.shape} of {array.dtype}",
            "data",
        )
    return array.astype(float)


def resampled(data: Measurement, points: int) -> Measurement:
    """``data`` linearly interpolated onto ``points`` abscissae uniform over its span: time
    for a force history, depth for an indentation (whose depths must then increase).

    Raises
    ------
    InputError
        For rebound or resilience data (one row per drop, no record to resample) and for an
        indentation whose depths do not increase (a loading and unloading curve).
    """
    axis = {"force-history": "time", "indentation": "depth"}.get(data.kind)
    if axis is None:
        raise InputError(
            f"resample: {data.kind} data hold one row per drop, not a record; leave resample unset",
            "resample",
        )
    x = data.columns[axis]
    steps = np.diff(x)
    if np.any(steps <= 0):
        row = data.row(int(np.flatnonzero(steps <= 0)[0]) + 1)
        raise InputError(
            f"resample: {data.source}: {row}: column {axis!r} must increase to be resampled "
            "(fit the loading part only), or leave it unset",
            "resample",
        )
    uniform = np.linspace(x[0], x[-1], int(points))
    columns = {name: np.interp(uniform, x, values) for name, values in data.columns.items()}
    columns[axis] = uniform
    return Measurement(data.kind, columns, data.source, data.units)


FE_REFINE = 0.6
"""The default refinement of the FE runs that correct a force history (a coarse mesh with its
error estimate: seconds a run)."""


def check_history_options(data: Measurement, time_offset: float | None, baseline: float) -> None:
    """Refuse a force history's time offset outside [first time - span, last time] (None: not
    checked, a fitted one) and a baseline outside (-largest |force|, largest force): no
    touch, or no push, on the record."""
    time, force = data.columns["time"], data.columns["force"]
    first, last = float(time[0]), float(time[-1])
    if time_offset is not None and not first - (last - first) <= time_offset <= last:
        raise InputError(
            f"time_offset must lie in [{first - (last - first):g}, {last:g}] s (the record's "
            f"first time less its span, to its last time), got {time_offset:g}",
            "time_offset",
        )
    size, top = float(np.max(np.abs(force))), float(np.max(force))
    if not -size < baseline < top:
        raise InputError(
            f"baseline must lie in ({-size:g}, {top:g}) N (above minus the largest |force|, "
            f"below the largest force), got {baseline:g}",
            "baseline",
        )
