"""Every input of the suite, declared once: name, CLI option, unit, valid range, default, meaning.

The name is the study-file and sweep key and the Python keyword (snake_case); the CLI option is
the kebab-case of the same word (the interface contract keeps ``--E2``, ``--nu2``, ...). Study
files, sweeps, their validation and the documentation's parameter table come from
:data:`VOCABULARY`; defaults that depend on the computation are given per kind (``impact``,
``contact``, ``finite-strain``, ``dynamic``, ``layer``).
"""

from __future__ import annotations

import argparse
import difflib
import itertools
import math
import numbers
import sys
import warnings
from collections.abc import Iterable, Mapping
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from .validation import InputError, bound_text, plain_float, shown, validate_positive

__all__ = [
    "KIND_NAMES",
    "MAX_STUDIES",
    "VOCABULARY",
    "DeprecatedKeyWarning",
    "Entry",
    "Range",
    "checked_positive",
    "deprecated",
    "entry",
    "fields",
    "inputs_of",
    "parameter_table",
    "suggestion",
]

KIND_NAMES = ("impact", "contact", "finite-strain", "dynamic", "layer")
"""The computations an input can belong to (study and sweep kinds)."""
FEM_KINDS = ("contact", "finite-strain", "dynamic", "layer")

MIN_EXPONENT = 0.25
MAX_EXPONENT = 20.0
"""The profile exponent n of z = A r^n that the exact theory takes (a force law x^((n+1)/n)
from nearly linear to a flat punch); the FEM takes (1, MAX_EXPONENT]."""
MAX_SPHERE_RADIUS = 1e6
"""Largest sphere radius in m: beyond it R^2 and the contact's round-off leave no digits of
the sphere's own correction, and the paraboloid (exponent 2, A = 1/(2R)) is the same striker."""
MAX_PROFILE_ROWS = 2000
"""Most rows of a tabulated profile (--profile): Sneddon's integrals at each point run over
all the table's pieces (measured, one impact of 2000 rows: 55 MB and 2.4 s)."""


class DeprecatedKeyWarning(FutureWarning):
    """A key of a study or sweep file that works for one more release under its new name."""


def deprecated(where: str, old: str, new: str) -> None:
    """Warn (one line) that key ``old`` at ``where`` is now called ``new``."""
    warnings.warn(
        f"{where}: key '{old}' is deprecated; write '{new}' (the old key works for one release)",
        DeprecatedKeyWarning,
        stacklevel=3,
    )


@dataclass(frozen=True)
class Range:
    """An interval of valid numbers; ``None`` ends are unbounded; ``zero``: 0 is valid too."""

    low: float | None = 0.0
    high: float | None = None
    low_open: bool = True
    high_open: bool = False
    zero: bool = False

    def text(self) -> str:
        """The range as written in messages and help: ``> 0``, ``(-1, 0.5]``, ``[50, 1e+05]``,
        ``[1e-6, 1e6] or 0``."""
        if self.zero:
            return self._interval() + " or 0"
        return self._interval()

    def _interval(self) -> str:
        if self.high is None:
            return f"{'>' if self.low_open else '>='} {_shown(self.low, 'low')}"
        if self.low is None:
            return f"{'<' if self.high_open else '<='} {_shown(self.high, 'high')}"
        return (
            f"{'(' if self.low_open else '['}{_shown(self.low, 'low')}, "
            f"{_shown(self.high, 'high')}"
            f"{')' if self.high_open else ']'}"
        )

    def contains(self, number: float) -> bool:
        """Whether ``number`` lies in the range."""
        if self.zero and number == 0:
            return True
        if self.low is not None and (number <= self.low if self.low_open else number < self.low):
            return False
        return self.high is None or (number < self.high if self.high_open else number <= self.high)


def _shown(number: float, side: str) -> str:
    """A range end as people write it: 0.5, 200, 1e2, 1e-3; rounded inward of the range
    (:func:`shtaerman.validation.bound_text`) where 6 digits do not write it exactly."""
    if number > 0 and 10.0 ** round(math.log10(number)) == number and not 1e-2 <= number <= 10:
        return f"1e{round(math.log10(number))}"
    if number == int(number) and abs(number) < 1e4:
        return str(int(number))
    mantissa, _, power = bound_text(number, side, 6).partition("e")
    return f"{mantissa}e{int(power)}" if power else mantissa


POSITIVE = Range()
POISSON = Range(-1.0, 0.5)
FRACTION = Range(0.0, 1.0)
MODULUS = Range(1e-3, 1e100, low_open=False)
"""Young's moduli E1 and E2 in Pa: of a physical size, and the FEM's (its scaled
factorization); E1 may also be inf, a rigid striker."""
MAX_STUDIES = 100
"""Most studies one study file expands into (the values of its ``[sweep]``): each is a full
study."""
MAX_VELOCITIES = 100
"""Most approach velocities of a dynamic study: each is a dynamic FE run."""
BASES = ("bonded", "lubricated")
"""Conditions at a layer's rigid base z = -H: bonded u = 0; lubricated u_z = 0, free to slide."""
MAX_PRONY_TERMS = 20
"""Most terms of a Prony series: each adds internal variables at every quadrature point."""
MAX_LAYER_RATE = 1e4
"""Largest absorbing-layer rate zeta_max t_y: far beyond the impact's frequencies the layer is
a wall (it sends back 0.35 of the radiated energy at 1e4), and from about 1e30 its damping
swamps the energy balance (benchmarks/FEM_NOTES.md, "Option checks and printed ranges")."""
MAX_GLASSY_DURATIONS = 20.0
"""Longest quasi-static viscoelastic contact accepted, in glassy impact durations t_y: a run
lasts three contact times, so at most 60 t_y (60 times the steps of the glassy t_y)."""


@dataclass(frozen=True)
class Entry:
    """One input.

    Attributes
    ----------
    name : str
        Study-file and sweep key, Python keyword (unless ``keyword`` says otherwise).
    unit : str
        SI unit ("" for a pure number).
    meaning : str
        One line for help and docs.
    label : str
        Readable name for figures and tables.
    default : object
        The value when none is given (``None``: derived from the other inputs, or unset).
    kinds : tuple of str
        The computations that take it as a study or sweep input.
    valid : Range or None
        Valid numbers (``None``: not a number, or no constraint).
    by_kind : mapping
        Kind -> default where it differs from ``default``.
    valid_by_kind : mapping
        Kind -> a narrower :class:`Range` where a method requires it (the FEM: nu2 >= 0).
    type : {"float", "int", "floats", "bool", "str", "path", "flag"}
        What a value must be.
    choices : tuple of str
        Allowed strings for ``type="str"``.
    option : str
        The CLI option ("" : ``--`` + the name in kebab-case).
    group : {"case", "numerics", "output"}
        What the input sets: the physical case, the numerics, or what is written.
    old_names : tuple of str
        Keys that meant it before (accepted with a deprecation message).
    infinite : bool
        Whether ``inf`` is valid (a rigid striker's E1).
    setting : str
        The settings field it sets (``MeshSettings``, ``DynamicSettings``; "": the name).
    max_items : int or None
        Most values of a list (``type="floats"``, or a dynamic study's velocities): each costs
        a computation.
    sweep_default : mapping
        Kind -> default in a sweep where it differs from the command line's, the API's and
        the study file's (:meth:`default_for`).
    keyword : str
        The Python API's name of it where that differs from ``name`` ("": the name):
        density2 is the body's ``Material(density=...)``.
    """

    name: str
    unit: str
    meaning: str
    label: str
    default: Any = None
    kinds: tuple[str, ...] = ()
    valid: Range | None = POSITIVE
    by_kind: Mapping[str, Any] = field(default_factory=dict)
    valid_by_kind: Mapping[str, Range] = field(default_factory=dict)
    type: str = "float"
    choices: tuple[str, ...] = ()
    option: str = ""
    group: str = "case"
    old_names: tuple[str, ...] = ()
    infinite: bool = False
    setting: str = ""
    max_items: int | None = None
    sweep_default: Mapping[str, Any] = field(default_factory=dict)
    keyword: str = ""

    @property
    def cli_option(self) -> str:
        """The command-line option, e.g. ``--shape-coefficient``."""
        return self.option or "--" + self.name.replace("_", "-")

    def default_for(self, kind: str | None = None) -> Any:
        """The default in computation ``kind`` (the common default if it has none of its own)
        on the command line, in the API and in a study file."""
        return self.by_kind.get(kind, self.default) if kind else self.default

    def sweep_default_for(self, kind: str) -> Any:
        """The default in a sweep of computation ``kind``."""
        return self.sweep_default.get(kind, self.default_for(kind))

    @property
    def settings_field(self) -> str:
        """The settings field it sets: ``mesh_size`` sets ``MeshSettings.size``."""
        return self.setting or self.name

    def range_for(self, kind: str | None = None) -> Range | None:
        """The valid range in computation ``kind``."""
        return self.valid_by_kind.get(kind, self.valid) if kind else self.valid

    def range_text(self, kind: str | None = None) -> str:
        """The valid values in words, as in messages and help (``""``: anything of the type)."""
        if self.choices:
            return "one of " + ", ".join(self.choices)
        valid = self.range_for(kind)
        text = "" if valid is None else valid.text()
        if self.type == "int" and text:
            text = f"an integer {'in ' if text[0] in '([' else ''}{text}"
        if self.type == "floats" and text:
            text = f"increasing, each {text}"
        return f"{text}, or inf (rigid)" if self.infinite else text

    def check(
        self, value: Any, kind: str | None = None, *, called: str = "", given: str = ""
    ) -> Any:
        """``value`` converted to the entry's type, or :class:`InputError` naming the entry and
        its valid values.

        ``called`` names the input in the message (default: its key; the CLI: its option) and
        ``given`` is the value as the user wrote it (default: ``repr(value)``).
        """
        says = _Says(called or self.name, given)
        if self.type == "floats":
            if isinstance(value, str | bytes) or not hasattr(value, "__iter__"):
                value = [value]
            value = list(value)
            if self.max_items is not None and len(value) > self.max_items:
                count = _Says(says.called)  # the count, not the (long) list
                raise count.error(self, f"must list at most {self.max_items} values", len(value))
            numbers = [_number(self, v, kind, says) for v in value]
            if not numbers or any(b <= a for a, b in itertools.pairwise(numbers)):
                raise says.error(self, f"must be {self.range_text(kind)}", value)
            return numbers
        if self.type in ("float", "int"):
            return _number(self, value, kind, says)
        if self.type in ("bool", "flag"):
            if not isinstance(value, bool):
                raise says.error(self, "must be true or false", value)
            return value
        if not isinstance(value, str) or (self.choices and value not in self.choices):
            raise says.error(self, f"must be {self.range_text(kind) or 'a string'}", value)
        return value

    def parse(self, text: str, kind: str | None = None, *, called: str = "") -> Any:
        """Command-line ``text`` converted to the entry's type and checked (:meth:`check`):
        a number, ``inf`` or ``rigid`` where infinity is valid, or comma-separated numbers."""
        if self.type == "floats":
            items = text.split(",")
            if any(not item.strip() for item in items):
                says = _Says(called or self.name, shown(text))
                raise says.error(self, "must be numbers separated by single commas", text)
            value: Any = [_float(item) for item in items]
        elif self.type in ("float", "int"):
            value = _float(text)
            if self.infinite and text.strip().lower() == "rigid":
                value = math.inf
        else:
            value = text
        return self.check(value, kind, called=called, given=shown(text))


def _float(text: str) -> float | str:
    """``text`` as a float, or ``text`` itself when it is no number (the check names it)."""
    try:
        return plain_float(text)
    except ValueError:
        return text


@dataclass(frozen=True)
class _Says:
    """How a message names the input and the value given."""

    called: str
    given: str = ""

    def error(self, item: Entry, verdict: str, value: Any) -> InputError:
        return InputError(f"{self.called} {verdict}, got {self.given or shown(value)}", item.name)


def _number(item: Entry, value: Any, kind: str | None, says: _Says) -> float | int:
    """One number of ``item``, checked against its type and range."""
    expected = item.range_text(kind) or "a number"
    if item.type == "floats":
        expected = item.range_for(kind).text() if item.range_for(kind) else "a number"
    rigid = ", or inf (rigid)" if item.infinite else ""
    expected = expected.removesuffix(rigid)
    unit = (f" {item.unit}" if item.unit else "") + rigid
    is_number = isinstance(value, numbers.Real) and not isinstance(value, bool | np.bool_)
    if is_number and isinstance(value, numbers.Integral) and abs(value) > 2**1023:
        raise says.error(item, f"must lie in {expected}", "an integer beyond any float")
    whole = is_number and math.isfinite(value) and float(value) == int(value)
    if item.type == "int" and not whole:
        raise says.error(item, f"must be {expected}", value)
    where = "in " if expected[0] in "([" else ""
    bounded = "" if expected == "a number" else f" {where}{expected}"  # not "a number a number"
    if not bounded and unit:
        unit = f" (in {unit.lstrip()})"  # not "a number s"
    if not is_number or math.isnan(value):
        raise says.error(item, f"must be a number{bounded}{unit}", value)
    verb = "lie in" if expected[0] in "([" else "be"
    if math.isinf(value) and item.infinite and value < 0:  # not "finite ..., or inf"
        raise says.error(item, f"must {verb} {expected}{unit}", value)
    if math.isinf(value) and not item.infinite:
        raise says.error(item, f"must be a finite number{bounded}{unit}", value)
    valid = item.range_for(kind)
    if not math.isinf(value) and valid is not None and not valid.contains(float(value)):
        raise says.error(item, f"must {verb} {expected}{unit}", value)
    if valid is not None and valid.low == 0 and valid.low_open and value < sys.float_info.min:
        least = bound_text(sys.float_info.min, "low", 4)  # a subnormal has lost its digits
        verdict = f"must {verb} {expected}{unit} and at least {least} (the smallest normal float)"
        raise says.error(item, verdict, value)
    return int(value) if item.type == "int" else float(value) + 0.0  # -0.0 is 0


def _numeric(
    name: str,
    meaning: str,
    label: str,
    default: Any,
    kinds: tuple[str, ...] = FEM_KINDS,
    **options: Any,
) -> Entry:
    """An entry of the numerics (a pure number unless ``unit`` is given)."""
    return Entry(
        name, options.pop("unit", ""), meaning, label, default, kinds, group="numerics", **options
    )


_MESH = {"contact": 1.0 / 150.0, "finite-strain": 1.0 / 60.0, "dynamic": 1.0 / 40.0}

VOCABULARY: tuple[Entry, ...] = (
    # --- the case ---------------------------------------------------------------------------
    Entry(
        "mass",
        "kg",
        "striker mass M",
        "Striker mass M",
        0.7,
        ("impact", "finite-strain", "dynamic", "layer"),
    ),
    Entry(
        "velocity",
        "m/s",
        "approach velocity v0",
        "Approach velocity v0",
        3.0,
        ("impact", "finite-strain", "dynamic", "layer"),
        old_names=("velocities",),
        max_items=MAX_VELOCITIES,
    ),
    Entry(
        "shape_coefficient",
        "m^(1-n)",
        "A in z = A r^n (the FEM: up to 1e100, beyond which the depths underflow)",
        "Shape coefficient A",
        5.0,
        KIND_NAMES,
        valid_by_kind=dict.fromkeys(FEM_KINDS, Range(0.0, 1e100)),
    ),
    Entry(
        "exponent",
        "",
        "n in z = A r^n",
        "Profile exponent n",
        1.5,
        KIND_NAMES,
        valid=Range(MIN_EXPONENT, MAX_EXPONENT, low_open=False),  # the theory's (indenter.py)
        valid_by_kind=dict.fromkeys(FEM_KINDS, Range(1.0, MAX_EXPONENT)),  # and bounded p(0)
    ),
    Entry(
        "sphere_radius",
        "m",
        "radius R of an exact sphere z = R - sqrt(R^2 - r^2), in place of the power law "
        "(--shape-coefficient, --exponent)",
        "Sphere radius R",
        kinds=KIND_NAMES,
        valid=Range(0.0, MAX_SPHERE_RADIUS),
    ),
    Entry(
        "profile",
        "",
        "a tabulated tip z(r): a CSV file whose header names the columns r and z (m), 3 to "
        f"{MAX_PROFILE_ROWS} rows from the tip r = 0, z = 0, both increasing; in place of the "
        "power law",
        "tabulated profile",
        kinds=KIND_NAMES,
        valid=None,
        type="path",
    ),
    Entry(
        "E1",
        "Pa",
        "striker Young's modulus",
        "Striker Young's modulus E1",
        2e11,
        ("impact", "layer"),
        valid=MODULUS,
        infinite=True,
        old_names=("youngs_modulus",),
    ),
    Entry(
        "nu1",
        "",
        "striker Poisson's ratio",
        "Striker Poisson's ratio \N{GREEK SMALL LETTER NU}1",
        0.25,
        ("impact", "layer"),
        valid=POISSON,
        old_names=("poisson_ratio",),
    ),
    Entry(
        "E2",
        "Pa",
        "half-space Young's modulus",
        "Half-space Young's modulus E2",
        7.5e6,
        KIND_NAMES,
        valid=MODULUS,
        old_names=("youngs_modulus",),
    ),
    Entry(
        "nu2",
        "",
        "half-space Poisson's ratio",
        "Half-space Poisson's ratio \N{GREEK SMALL LETTER NU}2",
        0.5,
        KIND_NAMES,
        valid=POISSON,
        valid_by_kind=dict.fromkeys(FEM_KINDS, Range(0.0, 0.5, low_open=False)),
        old_names=("poisson_ratio",),
    ),
    Entry(
        "density2",
        "kg/m^3",
        "half-space density (the paper gives none; 1100 is natural rubber; 0: massless, "
        "the quasi-static impact without waves)",
        "Half-space density \N{GREEK SMALL LETTER RHO}2",
        1100.0,
        ("dynamic", "layer"),
        valid=Range(1e-6, 1e6, low_open=False, zero=True),
        old_names=("density",),
        keyword="density",
    ),
    Entry(
        "prony",
        "",
        "shear relaxation of the half-space, the Prony series g1:tau1,g2:tau2,... (tau_i in s):"
        " G(t) = G0 [1 - sum g_i (1 - exp(-t/tau_i))], E2 and nu2 the instantaneous values; "
        "or the moduli Einf;E1:tau1,... (Pa, g_i = E_i/E0; give E2 = E0 = Einf + sum E_i), a "
        ".csv file (tau,E or tau,g) or a shipped rubber (zhermack-elite-double-32; give its "
        "E2 2.912e6, nu2 0.45, density2 1134 too: no form of the series sets them); check it "
        "with shtaerman prony-plot; "
        f"the bulk elastic; each g_i >= 0, sum g_i < 1, tau_i > 0, at most {MAX_PRONY_TERMS} "
        f"terms, and the quasi-static impact at most {MAX_GLASSY_DURATIONS:g} glassy impact "
        "durations long; with --model the isochoric stress relaxes (Simo's finite-strain "
        "model); unset: elastic",
        "Prony series (g_i:tau_i)",
        None,
        ("contact", "dynamic"),
        valid=None,
        type="str",
    ),
    # --- a fit (shtaerman fit: command line and sh.fit only) ------------------------------
    Entry(
        "unknowns",
        "",
        "the unknowns NAME[,NAME...] to fit: E2, nu2 (nu2 alone needs E2 known), mass, "
        "velocity, time_offset, baseline, prony (the weights g_i of --prony), tau (its relaxation "
        "times tau_i, fitted in log; a tau_i outside the measured time range is reported not "
        "identifiable, its g_i with it); --prony's terms are the starting values; an indentation "
        "with --model: E2 and, for mooney-rivlin, mooney_ratio (from FE curves)",
        "fitted unknowns",
        "E2",
        valid=None,
        type="str",
        option="--fit",
    ),
    Entry(
        "noise",
        "",
        "standard deviation of the data, in the residual's unit (N for a force; relative, "
        "e.g. 0.01, for rebound data); unset: estimated from the residual",
        "noise level",
        None,
        valid=Range(0.0, 1e100),  # squared in the covariance: 1e200 overflowed (traceback)
    ),
    Entry(
        "time_offset",
        "s",
        "the force history's time of first touch on the data's clock, unless fitted (then "
        "its starting value; unset: 0, or read off the data when fitted); from the record's "
        "first time less its span to its last time",
        "time offset",
        None,
        valid=None,
    ),
    Entry(
        "baseline",
        "N",
        "the force history's zero force (the force read before and after contact), unless "
        "fitted (then its starting value); above minus the largest |force| and below the "
        "largest force",
        "force baseline",
        0.0,
        valid=None,
    ),
    Entry(
        "resample",
        "",
        "points to resample the data onto before the fit, uniform in time (a force history) "
        "or in depth (an indentation), by linear interpolation over the record's span: an "
        "irregular or over-dense record then gives each span of time fair weight, and a long "
        "one fits faster; unset: the rows as read",
        "resampled points",
        None,
        valid=Range(3.0, 1e7, low_open=False),
        type="int",
    ),
    Entry(
        "units",
        "",
        "units of the data columns whose header gives none, COLUMN=UNIT,... (e.g. "
        "depth=mm,force=kN); a header 'depth [mm]' gives its own (a different one is refused)",
        "data units",
        None,
        valid=None,
        type="str",
    ),
    Entry(
        "rate",
        "m/s",
        "pressing speed of a contact curve on a viscoelastic body",
        "Pressing speed V",
        None,
        ("contact",),
    ),
    Entry(
        "depths",
        "m",
        "indentation depths",
        "Depth x",
        None,
        ("contact", "finite-strain"),
        type="floats",
        max_items=1000,
    ),
    Entry(
        "model",
        "",
        "material model of the half-space",
        "model",
        "linear",
        ("finite-strain", "dynamic"),
        valid=None,
        type="str",
        choices=("linear", "neo-hookean", "mooney-rivlin", "yeoh", "gent"),
        sweep_default={"finite-strain": "neo-hookean"},
    ),
    # --- rubber models beyond neo-Hookean (all with the small-strain E2, nu2) -----------------
    Entry(
        "mooney_ratio",
        "",
        "Mooney-Rivlin r = C01 / (C10 + C01), C10 + C01 = E2 / (4 (1 + nu2))",
        "Mooney ratio r",
        None,
        ("finite-strain", "dynamic"),
        valid=Range(0.0, 1.0, low_open=False, high_open=True),
    ),
    Entry(
        "yeoh",
        "",
        "Yeoh c2,c3 = C20/C10, C30/C10 (C10 = E2 / (4 (1 + nu2))), |c2| <= 10, c3 in [0, 10]; "
        "a negative c2 needs c2^2 < 3 c3 (dW/dI1 > 0)",
        "Yeoh c2, c3",
        None,
        ("finite-strain", "dynamic"),
        valid=None,
        type="str",
    ),
    Entry(
        "gent_limit",
        "",
        "Gent limit Jm of I1 - 3 (W = -mu/2 Jm ln(1 - (I1 - 3)/Jm))",
        "Gent limit Jm",
        None,
        ("finite-strain", "dynamic"),
    ),
    Entry(
        "volumetric",
        "",
        "volumetric energy of a finite-strain model for nu2 < 0.5: K/2 (J-1)^2 (quadratic) or "
        "K/2 (ln J)^2 (logarithmic)",
        "Volumetric energy",
        None,
        ("finite-strain", "dynamic"),
        valid=None,
        type="str",
        choices=("quadratic", "logarithmic"),
    ),
    # --- a layer on a rigid base (the half-space without thickness) ---------------------------
    Entry(
        "thickness",
        "m",
        "thickness H of a layer on a rigid base (a study's [layer] table too)",
        "Layer thickness H",
        None,
        ("layer", "dynamic", "finite-strain"),
    ),
    Entry(
        "thickness_ratio",
        "",
        "layer thickness H / a_c, the half-space contact radius at the (quasi-static) impact's "
        "x_c (instead of thickness; a study's [layer] table too)",
        "Layer thickness H / a_c",
        None,
        ("layer", "dynamic"),
        valid=Range(0.05, 500.0, low_open=False),
    ),
    Entry(
        "base",
        "",
        "the layer's rigid base: bonded (u = 0) or lubricated (u_z = 0, free to slide)",
        "Layer base",
        "bonded",
        ("layer", "dynamic", "finite-strain"),
        valid=None,
        type="str",
        choices=BASES,
    ),
    Entry(
        "dynamic",
        "",
        "also the dynamic FE impact on the layer (elastic waves, rigid striker, density2): its "
        "restitution, x_max and P_max (about 5 s per case; a contact study's [layer] table too)",
        "Dynamic impact on the layer",
        False,
        ("layer",),
        valid=None,
        type="bool",
    ),
    # --- the indenter's surface ---------------------------------------------------------------
    Entry(
        "interface",
        "",
        "the indenter's surface: frictionless, or bonded (no slip once in contact)",
        "Interface",
        "frictionless",
        ("contact", "finite-strain", "dynamic"),
        valid=None,
        type="str",
        choices=("frictionless", "bonded"),
    ),
    Entry(
        "friction",
        "",
        "Coulomb friction coefficient of a bonded indenter: a point in contact slides where its "
        "shear exceeds friction x its pressure (no slip at all: leave it out)",
        "Friction coefficient",
        None,
        ("contact", "finite-strain", "dynamic"),
        valid=Range(0.0, 100.0, low_open=False),  # rubber on steel: up to ~3; 100 never slides
    ),
    # --- the numerics -----------------------------------------------------------------------
    _numeric(
        "refine",
        "divide the whole mesh size field by K",
        "Mesh refinement factor K",
        1.0,
        valid=Range(0.0, 1e6),  # far past any max_dofs; 1e308 underflowed the mesh size
    ),
    _numeric(
        "mesh_size",
        "smallest element size / refined radius",
        "Smallest element size / refined-zone radius",
        _MESH["contact"],
        by_kind=_MESH,
        valid=FRACTION,
        valid_by_kind={"dynamic": Range(0.0, 0.2)},
        old_names=("size",),
        setting="size",
        sweep_default={"dynamic": None},  # the model's: 1/40 linear, finite strain its own
    ),
    _numeric(
        "mesh_margin",
        "refined radius / largest contact radius",
        "Refined-zone radius / contact radius",
        1.25,
        valid=Range(1.0, 10.0),  # dynamic too: 1e300 made the mesh's radii inf
        by_kind={"dynamic": 1.3},
        old_names=("margin",),
        setting="margin",
    ),
    _numeric(
        "domain_factor",
        "domain radius / refined radius",
        "Domain radius / refined-zone radius",
        1e5,
        valid=Range(1e2, 1e7, low_open=False),
        by_kind={"dynamic": 1e4},
        old_names=("domain",),
        setting="domain",
    ),
    _numeric(
        "growth",
        "element size growth per unit distance from the refined zone",
        "Element size growth from the refined zone",
        0.25,
        valid=FRACTION,
        by_kind={"finite-strain": 0.3, "dynamic": 0.2},
    ),
    _numeric(
        "axis_size",
        "element size at the axis / refined radius",
        "Element size at the first contact point / refined-zone radius",
        1e-6,
        valid=FRACTION,
        by_kind={"dynamic": 1.0 / 800.0},
    ),
    _numeric(
        "axis_growth",
        "element size growth away from the axis",
        "Element size growth from the first contact point",
        0.1,
        ("contact", "finite-strain", "layer"),
        valid=FRACTION,
        by_kind={"finite-strain": 0.15},
    ),
    _numeric(
        "max_dofs",
        "refuse a mesh estimated (before meshing) above this many unknowns",
        "largest mesh (dofs)",
        400_000.0,
        ("contact", "finite-strain", "layer"),
    ),
    _numeric(
        "time_steps",
        "time steps per quasi-static impact duration t_y (more than about 100 / mesh-size leave "
        "the contact stepping unstable: fewer steps or a finer mesh; refine scales them with "
        "the mesh)",
        "Time steps per impact duration t_y",
        200,
        ("dynamic",),
        valid=Range(50.0, 5000.0, low_open=False),
        old_names=("steps",),
        type="int",
        setting="steps",
        sweep_default={"dynamic": None},  # the model's: 200 linear, finite strain its own
    ),
    _numeric(
        "layer_rate",
        "absorbing-layer damping rate x t_y (0: no layer, on the half-space only: a pad always "
        "has one, 10 by default; a faster layer damps the waves so abruptly that it reflects "
        "them, like a wall: more the larger the rate)",
        "Absorbing layer rate",
        0.0,
        ("dynamic",),
        valid=Range(0.0, MAX_LAYER_RATE, low_open=False),
        sweep_default={"dynamic": None},  # the geometry's own: 0 must be told from it
    ),
    _numeric(
        "reach",
        "deepest depth / the linear impact's x_c",
        "Deepest depth / linear x_c",
        1.1,
        ("finite-strain",),
        valid=Range(1.0, 3.0, low_open=False),
    ),
    _numeric(
        "depth_steps",
        "equal depth steps up to the reach",
        "Depth steps",
        12,
        ("finite-strain",),
        valid=Range(4.0, 200.0, low_open=False),
        old_names=("steps",),
        type="int",
    ),
    _numeric(
        "small_ratio",
        "x/a of the first, tiny depth (the small-strain limit)",
        "x/a of the smallest depth",
        0.01,
        ("finite-strain",),
        valid=Range(0.0, 0.2),
    ),
    _numeric(
        "small_steps",
        "geometric depths from the first one to the first equal step",
        "Depth steps up to the first regular depth",
        5,
        ("finite-strain",),
        valid=Range(1.0, 200.0, low_open=False),
        type="int",
    ),
    Entry(
        "solver",
        "",
        "sparse direct solver",
        "Linear solver",
        "auto",
        ("contact",),
        valid=None,
        type="str",
        choices=("auto", "superlu", "pardiso"),
        group="numerics",
    ),
    Entry(
        "estimate",
        "",
        "error estimates by Richardson extrapolation from two coarser runs (K/2 and K/sqrt(2))",
        "Error estimates",
        True,
        ("dynamic",),
        valid=None,
        sweep_default={"dynamic": False},
        type="bool",
        group="numerics",
        option="--no-estimate",
    ),
    Entry(
        "accuracy",
        "",
        "refine until the estimated relative error of force and beta is <= TOL",
        "target accuracy",
        None,
        valid=Range(0.0, 0.1),
        group="numerics",
    ),
    Entry("max_time", "s", "time budget of --accuracy", "time budget", 60.0, group="numerics"),
    # --- what is written (command line only) ---------------------------------------------------
    *(
        Entry(name, unit, meaning, label, default, valid=valid, type=kind, group="output")
        for name, unit, meaning, label, default, valid, kind in (
            ("json", "", "print one JSON object (SI units)", "JSON", False, None, "flag"),
            ("out", "", "write the results to this folder", "folder", None, None, "path"),
            (
                "force",
                "",
                "replace existing outputs (a result folder only if shtaerman wrote it and you "
                "added no file)",
                "replace",
                False,
                None,
                "flag",
            ),
            (
                "resume",
                "",
                "complete the folder an interrupted run left in --out, keeping what it finished",
                "resume",
                False,
                None,
                "flag",
            ),
            ("history", "", "write the time history as CSV", "history", None, None, "path"),
            (
                "points",
                "",
                "rows of --history",
                "history rows",
                201,
                Range(2.0, 1e7, low_open=False),
                "int",
            ),
            ("check", "", "also integrate the ODE numerically", "ODE check", False, None, "flag"),
            (
                "workers",
                "",
                "processes of the local dask cluster, one thread each",
                "workers",
                None,
                Range(1.0, 256.0, low_open=False),
                "int",
            ),
        )
    ),
    Entry(
        "figure_format",
        "",
        "figure files: png, or svg / pdf beside each chart's PNG",
        "figure format",
        "png",
        type="str",
        choices=("png", "svg", "pdf"),
        group="output",
    ),
)
"""Every input, in the order of the documentation's table."""

_BY_NAME = {item.name: item for item in VOCABULARY}


def entry(name: str) -> Entry:
    """The entry called ``name``; :class:`InputError` with the likely one for an unknown name."""
    if name not in _BY_NAME:
        raise InputError(f"unknown input {name!r}{suggestion(name, _BY_NAME)}", name)
    return _BY_NAME[name]


def checked_positive(name: str, value: object) -> float:
    """The API's value of input ``name``, a positive number (``refine``, ``noise``), as a
    float, or :class:`InputError` naming it: a non-number in
    :func:`~shtaerman.validation.validate_positive`'s words ("not a string: got '2'"), a
    number outside the entry's range (refine: (0, 1e6]) in the vocabulary's."""
    return entry(name).check(validate_positive(name, value))


def inputs_of(kind: str) -> dict[str, Entry]:
    """The study and sweep inputs of computation ``kind``, by name."""
    return {item.name: item for item in VOCABULARY if kind in item.kinds}


def fields(names: Iterable[str]) -> dict[str, str]:
    """Input name -> the settings field it sets (``mesh_size`` -> ``size``), for ``names``."""
    return {name: entry(name).settings_field for name in names}


def suggestion(word: str, known: Any) -> str:
    """``" (did you mean 'x'?)"`` for the closest of ``known`` to ``word`` ("" if none is)."""
    close = difflib.get_close_matches(word, [str(k) for k in known], n=1, cutoff=0.5)
    if not close:
        lowered = {str(k).lower(): str(k) for k in known}
        close = [lowered[word.lower()]] if word.lower() in lowered else []
    return f" (did you mean {close[0]!r}?)" if close else ""


def _value_text(item: Entry, value: Any) -> str:
    if value is None:
        return _UNSET[item.group]
    if isinstance(value, bool):
        return str(value).lower()
    return f"{value:.6g}" if isinstance(value, int | float) else str(value)


def _default_text(item: Entry) -> str:
    """The defaults by kind, and in a sweep where it has its own."""
    shown: dict[str, list] = {}
    for kind in item.kinds or (None,):
        shown.setdefault(_value_text(item, item.default_for(kind)), []).append(kind)
    if len(shown) == 1:
        text = next(iter(shown))
    else:
        text = ", ".join(f"{text} ({', '.join(kinds)})" for text, kinds in shown.items())
    for kind, value in item.sweep_default.items():
        value_text = "the model's" if value is None else _value_text(item, value)
        text += f"; {value_text} in a {kind} sweep"
    return text


_UNSET = {"case": "derived", "numerics": "-", "output": "-"}


def parameter_table(cli: argparse.ArgumentParser) -> str:
    """The documentation's parameter tables (markdown), one per group of inputs (the case, the
    numerics, the output): each input's key, its option with the commands of ``cli`` (the
    command line's parser) that take it, or none (a study and sweep key only), its default,
    meaning, unit, valid values and kinds."""
    [commands] = [a for a in cli._actions if isinstance(a, argparse._SubParsersAction)]
    taken: dict[str, list[str]] = {}
    for command, parser in commands.choices.items():
        for option in parser._option_string_actions:
            taken.setdefault(option, []).append(command)
    titles = {"case": "The case", "numerics": "The numerics", "output": "What is written"}
    parts = []
    for group in dict.fromkeys(item.group for item in VOCABULARY):
        parts += [f"### {titles.get(group, group)}", ""]
        parts += ["| Key, CLI option | Default | Meaning [unit] |", "|---|---|---|"]
        for item in (item for item in VOCABULARY if item.group == group):
            valid = item.range_text()
            if any(item.range_text(kind) != valid for kind in item.kinds):
                valid = f"{valid}; FEM {item.range_text(FEM_KINDS[0])}"
            if item.type == "floats" and item.max_items:
                valid += f"; at most {item.max_items} values"
            meaning = item.meaning.replace("|", "\\|") + (f" [{item.unit}]" if item.unit else "")
            if item.old_names:
                meaning += f" (formerly {', '.join(f'`{n}`' for n in item.old_names)})"
            on = taken.get(item.cli_option)
            option = f"`{item.cli_option}` ({', '.join(on)})" if on else "study and sweep key only"
            kinds = f"Kinds: {', '.join(item.kinds)}" if item.kinds else "Not a study or sweep key"
            parts.append(
                f"| `{item.name}`<br>{option} | {_default_text(item)} | "
                f"{meaning}. {f'Valid: {valid}. ' if valid else ''}{kinds}. |"
            )
        parts.append("")
    return "\n".join(parts)
