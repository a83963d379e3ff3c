"""Where a Prony series comes from: its text in either convention, a CSV file or a shipped rubber.

A series is given either as the Abaqus weights g_i on the instantaneous modulus (the suite's
:class:`.viscoelastic.PronySeries`) or as moduli, E(t) = E_inf + sum_i E_i exp(-t/tau_i). At a
constant Poisson's ratio both describe the same relaxation, exactly:

    E0 = E_inf + sum_i E_i,   g_i = E_i / E0,   g_inf = E_inf / E0,

and G(t)/G0 = E(t)/E0, so the g_i relax the shear modulus as the E_i relax Young's.

Text forms (:func:`prony_from_text`):

- ``g1:tau1,g2:tau2,...`` the weights (tau in s);
- ``Einf;E1:tau1,E2:tau2,...`` the moduli in Pa (the ``;`` marks this form);
- a path ending in ``.csv``: a header ``tau,E`` (moduli in Pa, one row with tau = inf holding
  E_inf) or ``tau,g`` (weights), units in brackets allowed (``tau [s],E [Pa]``), ``#`` comments;
- the name of a shipped rubber (:data:`SHIPPED`), e.g. ``zhermack-elite-double-32``.
"""

from __future__ import annotations

import math
import re
from collections.abc import Sized
from dataclasses import dataclass
from importlib import resources
from pathlib import Path
from typing import TYPE_CHECKING

from ..input_file import csv_rows, read_input_csv
from ..validation import InputError, plain_float
from ..vocabulary import MAX_PRONY_TERMS

if TYPE_CHECKING:
    from .viscoelastic import PronySeries

__all__ = [
    "PRONY_FORM",
    "SHIPPED",
    "ShippedRubber",
    "prony_from_csv",
    "prony_from_moduli",
    "prony_from_text",
    "prony_input",
    "prony_with_modulus",
    "shipped_rubber",
]

_DATA = "shtaerman.data.prony"
SHIPPED = tuple(
    sorted(
        entry.name.removesuffix(".csv")
        for entry in resources.files(_DATA).iterdir()
        if entry.name.endswith(".csv")
    )
)
"""The names of the shipped rubbers' series (``src/shtaerman/data/prony/<name>.csv``)."""
_COLUMN = re.compile(r"^\s*(\w+)\s*(\[[^\]]*\])?\s*$")
_KEY = re.compile(r"^#\s*(nu|density)\s*=\s*(\S+)\s*$")


@dataclass(frozen=True)
class ShippedRubber:
    """A shipped rubber: its series and the elastic constants that go with it (SI units).

    Attributes
    ----------
    name : str
        The name that loads it (``--prony NAME``).
    series : PronySeries
        The weights g_i = E_i / E0 and times tau_i in s.
    youngs_modulus : float
        The instantaneous modulus E0 = E_inf + sum E_i in Pa (the suite's E2).
    poisson_ratio : float
        nu, taken constant in time.
    density : float
        kg/m^3.
    provenance : str
        The file's comment lines: where the values come from and what was not verified.
    """

    name: str
    series: PronySeries
    youngs_modulus: float
    poisson_ratio: float
    density: float
    provenance: str


def prony_from_moduli(
    relaxed: float, moduli: tuple[float, ...], times: tuple[float, ...]
) -> tuple[PronySeries, float]:
    """The weights g_i = E_i / E0 of E(t) = E_inf + sum E_i exp(-t/tau_i), and E0 in Pa.

    ``relaxed`` is E_inf > 0 and ``moduli`` the E_i >= 0, in Pa (any one unit: only the ratios
    enter g_i); ``times`` the tau_i in s.
    """
    from .viscoelastic import PronySeries  # here, not at load: PRONY_FORM serves the parsers

    if not (math.isfinite(relaxed) and relaxed > 0.0):
        raise InputError(f"prony: E_inf must be a finite number > 0 Pa, got {relaxed!r}", "prony")
    for i, modulus in enumerate(moduli, start=1):
        if not (math.isfinite(modulus) and modulus >= 0.0):
            raise InputError(f"prony: E{i} must be a finite number >= 0 Pa, got {modulus}", "prony")
    instantaneous = math.fsum((relaxed, *moduli))
    return PronySeries(tuple(m / instantaneous for m in moduli), tuple(times)), instantaneous


def _number(text: str, where: str) -> float:
    try:
        return plain_float(text)
    except ValueError:
        raise InputError(f"prony: {where} must be a number, got {text!r}", "prony") from None


def _moduli_text(text: str) -> tuple[PronySeries, float]:
    from .viscoelastic import PronyFormError

    relaxed, _, terms = text.partition(";")
    pairs = [term.split(":") for term in terms.split(",")]
    if any(len(pair) != 2 for pair in pairs):
        raise PronyFormError(
            f"prony must be written g1:tau1,g2:tau2,... or, in moduli, Einf;E1:tau1,E2:tau2,... "
            f"(Pa, s), got {text!r}",
            text,
        )
    moduli = tuple(_number(m, f"E{i}") for i, (m, _) in enumerate(pairs, start=1))
    times = tuple(_number(t, f"tau{i}") for i, (_, t) in enumerate(pairs, start=1))
    return prony_from_moduli(_number(relaxed, "E_inf"), moduli, times)


def _header(cells: list[str], where: str, line: int) -> str:
    names = []
    for cell in cells:
        match = _COLUMN.match(cell)
        names.append(match[1] if match else cell.strip())
    if names not in (["tau", "E"], ["tau", "g"]):  # case kept: G would be a shear modulus
        raise InputError(
            f"prony: {where}: line {line}: the header must be 'tau [s],E [Pa]' or "
            f"'tau [s],g [1]', got {','.join(cells).strip()!r}",
            "prony",
        )
    return names[1].lower()


def _rows(text: str, where: str) -> tuple[str, list[tuple[int, float, float]]]:
    """The value column's name ('e' or 'g') and the rows (line number, tau, value): the header
    checked first (then a row of other than its 2 cells is refused by
    :func:`~shtaerman.input_file.csv_rows`), then at most :data:`MAX_PRONY_TERMS` + 2 rows
    parsed (the terms, an E column's tau = inf row and one to tell too many; a million rows
    took 10 CPU s)."""
    header, lines = csv_rows(text, f"prony: {where}", "prony", limit=1)
    if not header:
        raise InputError(f"prony: {where} holds no header and no rows", "prony")
    column = _header(header[0], where, lines[0])
    name = "E" if column == "e" else "g"
    body, lines = csv_rows(text, f"prony: {where}", "prony", limit=MAX_PRONY_TERMS + 3)
    return column, [
        (
            k,
            _number(tau, f"{where}: line {k}, column tau"),
            _number(value, f"{where}: line {k}, column {name}"),
        )
        for k, (tau, value) in zip(lines[1:], body[1:], strict=True)
    ]


def _series_from_rows(column: str, rows: list[tuple[int, float, float]], where: str) -> tuple:
    from .viscoelastic import PronySeries

    relaxed = [value for _, tau, value in rows if tau == math.inf]
    terms = [(k, tau, value) for k, tau, value in rows if tau != math.inf]
    for k, tau, _ in terms:
        if not (tau > 0.0 and math.isfinite(tau)):
            raise InputError(
                f"prony: {where}: line {k}, column tau: must be > 0 s, got {tau}", "prony"
            )
    if column == "g" and relaxed:
        raise InputError(f"prony: {where}: a g column takes no tau = inf row", "prony")
    if column == "e" and len(relaxed) != 1:
        raise InputError(
            f"prony: {where}: an E column needs exactly one row with tau = inf (E_inf), got "
            f"{len(relaxed)}",
            "prony",
        )
    if not terms:  # an empty series would run the elastic body unsaid
        raise InputError(f"prony: {where}: holds no term (a row tau,value with tau < inf)", "prony")
    if len(terms) > MAX_PRONY_TERMS:  # after each row read is checked: a row's fault named first
        raise InputError(f"prony: {where}: more than {MAX_PRONY_TERMS} terms", "prony")
    times = tuple(tau for _, tau, _ in terms)
    values = tuple(value for _, _, value in terms)
    name, unit, valid = (
        ("g", "lie in [0, 1)", lambda g: 0.0 <= g < 1.0)
        if column == "g"
        else ("E", "be a finite number >= 0 Pa", lambda e: 0.0 <= e < math.inf)
    )
    for k, _, value in terms:  # named by its line, as a tau is
        if not valid(value):
            raise InputError(
                f"prony: {where}: line {k}, column {name}: must {unit}, got {value}", "prony"
            )
    if column == "g":
        if not math.fsum(values) < 1.0:  # the series' own refusal names no file
            raise InputError(
                f"prony: {where}: column g must sum to less than 1 (relaxed modulus > 0), got "
                f"sum g_i = {math.fsum(values)!r} over lines {terms[0][0]} to {terms[-1][0]}",
                "prony",
            )
        return PronySeries(values, times), None
    return prony_from_moduli(relaxed[0], values, times)


def prony_from_csv(path: str | Path) -> tuple[PronySeries, float | None]:
    """The series of a CSV file (see the module) and E0 in Pa (None for a g column)."""
    path = Path(path)
    text = read_input_csv(path, "prony", "prony")
    return _series_from_rows(*_rows(text, path.name), path.name)


def shipped_rubber(name: str) -> ShippedRubber:
    """The shipped rubber ``name`` (one of :data:`SHIPPED`)."""
    if name not in SHIPPED:
        raise InputError(f"prony: unknown rubber {name!r}. Pick one of {list(SHIPPED)}", "prony")
    text = resources.files(_DATA).joinpath(f"{name}.csv").read_text(encoding="utf-8")
    series, instantaneous = _series_from_rows(*_rows(text, name), name)
    comments = [line for line in text.splitlines() if line.startswith("#")]
    keys = {m[1]: float(m[2]) for m in map(_KEY.match, comments) if m}
    provenance = "\n".join(c.lstrip("# ") for c in comments if not _KEY.match(c))
    return ShippedRubber(name, series, instantaneous, keys["nu"], keys["density"], provenance)


def prony_with_modulus(text: str) -> tuple[PronySeries, float | None]:
    """The series ``text`` in any of the module's forms (see there), and its instantaneous
    modulus E0 in Pa where the form gives one (moduli, a CSV of E, a shipped rubber)."""
    from .viscoelastic import PronySeries

    text = str(text).strip()
    if text in SHIPPED:
        rubber = shipped_rubber(text)
        return rubber.series, rubber.youngs_modulus
    if text.lower().endswith(".csv"):
        return prony_from_csv(text)
    if ";" in text:
        return _moduli_text(text)
    if re.fullmatch(r"[A-Za-z][\w.-]*", text):
        raise InputError(f"prony: unknown rubber {text!r}. Pick one of {list(SHIPPED)}", "prony")
    return PronySeries.parse(text), None


def prony_from_text(text: str) -> PronySeries:
    """The series ``text`` in any of the module's forms (see there)."""
    return prony_with_modulus(text)[0]


PRONY_FORM = (
    f"write g1:tau1,g2:tau2,... with each g_i >= 0, sum g_i < 1, tau_i > 0 s, at most "
    f"{MAX_PRONY_TERMS} terms; or Einf;E1:tau1,... in Pa; or a .csv file; or a shipped rubber "
    f"{', '.join(SHIPPED)}"
)
"""The valid Prony input, in words."""
_FORM = PRONY_FORM.removeprefix("write ")


def prony_input(
    value: object, name: str = "prony", youngs_modulus: float | None = None
) -> PronySeries | None:
    """``value`` as a Prony series: None (elastic), a :class:`PronySeries` or its text
    (:func:`shtaerman.theory.prony_sources.prony_from_text`: ``g1:tau1,...``, ``Einf;E1:tau1,...``,
    a CSV file or a shipped rubber's name); InputError naming ``name`` and the valid form.
    With the body's ``youngs_modulus`` E2 (Pa), a text that carries E0 (moduli, a CSV of E, a
    shipped rubber) is refused unless E2 is E0 to :data:`E0_TOLERANCE`."""
    from .viscoelastic import PronyFormError, PronySeries

    if value is None:
        return None
    if isinstance(value, str):
        _check_terms(value, name)  # before parsing a million terms
    carried = None
    try:
        if isinstance(value, PronySeries):
            series = value
        elif isinstance(value, str):
            series, carried = prony_with_modulus(value)
        else:
            raise InputError(f"prony must be a PronySeries or its text, got {value!r}")
    except PronyFormError as error:  # the forms said once, whole
        raise InputError(f"{name}: must be written {_FORM}; got {error.got!r}", name) from None
    except InputError as error:
        reason = str(error).removeprefix("prony: ").removeprefix("prony ")
        raise InputError(f"{name}: {reason} ({PRONY_FORM})", name) from None
    _check_terms(series.weights, name)
    _check_carried(carried, youngs_modulus, name)
    return series


E0_TOLERANCE = 1e-3
"""Relative difference of E2 from a series' E0 accepted: E2 written to four figures (the
shipped rubber's 2.912e6 is its E0 exactly)."""


def _check_carried(carried: float | None, youngs_modulus: float | None, name: str) -> None:
    """Refuse a series' instantaneous modulus ``carried`` (Pa) that the body's E2
    ``youngs_modulus`` (Pa) is not: the weights g_i = E_i / E0 would relax an E2 the moduli
    never gave (``Einf;E1:tau1`` 1e6;2e6:1e-3 on the default 7.5e6 Pa ran 2.5 times stiffer)."""
    if carried is None or youngs_modulus is None:
        return
    if abs(youngs_modulus - carried) <= E0_TOLERANCE * carried:
        return
    raise InputError(
        f"{name}: its instantaneous modulus E0 = E_inf + sum E_i is {carried:.6g} Pa, but E2 "
        f"is {youngs_modulus:.6g} Pa: give E2=... {carried:.6g} Pa with it, or the series as "
        "weights g1:tau1,... (which relax the E2 given)",
        name,
    )


def _check_terms(terms: str | Sized, name: str) -> None:
    """Refuse an empty term of a series' text (the first named) and more than
    :data:`MAX_PRONY_TERMS` terms, of its text or of a series' weights, before any parsing
    (the terms of g1:tau1,... and of Einf;E1:tau1,... after the ';' are split at its commas; a
    file's name is not counted)."""
    if isinstance(terms, str):
        if terms.strip().lower().endswith(".csv"):
            return
        terms = terms.partition(";")[2] if ";" in terms else terms
        terms = terms.split(",")
        empty = next((i for i, term in enumerate(terms, 1) if not term.strip()), None)
        if empty is not None and len(terms) > 1:  # one empty text: the form's own refusal
            raise InputError(
                f"{name}: must be written {_FORM}; term {empty} is empty (a doubled, leading or "
                "trailing comma)",
                name,
            )
    if len(terms) > MAX_PRONY_TERMS:
        raise InputError(f"{name}: {len(terms)} terms is too many ({PRONY_FORM})", name)
