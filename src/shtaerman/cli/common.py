"""What the subcommands share: the parser class, option groups, input conversion, output."""

from __future__ import annotations

import argparse
import json
import re
import sys

from ..output.files import json_safe
from ..plots.formats import add_figure_format
from ..theory.indenter import PowerLawIndenter
from ..theory.materials import RIGID, Material
from ..validation import InputError, validate_poisson, validate_positive

__all__ = [
    "Parser",
    "add_figure_format",
    "add_half_space_options",
    "add_indenter_options",
    "half_space",
    "indenter",
    "print_json",
    "striker",
]

PAPER = {
    "mass": "0.7",
    "velocity": "3",
    "shape_coefficient": "5",
    "exponent": "1.5",
    "E1": "2e11",
    "nu1": "0.25",
    "E2": "7.5e6",
    "nu2": "0.5",
}
"""The paper's worked example (section 5), the default of every subcommand."""


class HelpFormatter(argparse.RawDescriptionHelpFormatter):
    """Help that shows every default value and keeps the description's line breaks."""

    def _get_help_string(self, action: argparse.Action) -> str:
        text = action.help or ""
        if action.default in (None, False, argparse.SUPPRESS) or "%(default)" in text:
            return text
        return f"{text} (default: %(default)s)"


class Parser(argparse.ArgumentParser):
    """argparse that reports a usage error as one line (no usage dump) with exit code 2.

    It also reads ``-2e11`` as a (negative) number, so the range check can name it, rather than
    as an unknown option.
    """

    def __init__(self, *args, **kwargs) -> None:
        kwargs.setdefault("formatter_class", HelpFormatter)
        super().__init__(*args, **kwargs)
        self._negative_number_matcher = re.compile(r"^-(\d+\.?\d*|\.\d+)([eE][-+]?\d+)?$")

    def error(self, message: str) -> None:  # type: ignore[override]
        raise InputError(message)


def add_indenter_options(parser: argparse.ArgumentParser) -> None:
    """--shape-coefficient and --exponent of the striker profile z = A r^n."""
    parser.add_argument(
        "--shape-coefficient",
        default=PAPER["shape_coefficient"],
        metavar="A",
        help="A in z = A r^n, m^(1-n)",
    )
    parser.add_argument("--exponent", default=PAPER["exponent"], metavar="N", help="n in z = A r^n")


FEM_POISSON_LOW = 0.0
"""Smallest nu2 the FEM commands (contact, dynamic) accept: the FEM's validated range."""


def poisson_range(low: float = -1.0) -> str:
    """The range text of :func:`shtaerman.validation.validate_poisson` for ``low``."""
    return "(-1, 0.5]" if low == -1.0 else f"[{low:g}, 0.5]"


def add_half_space_options(parser: argparse.ArgumentParser, poisson_low: float = -1.0) -> None:
    """--E2 and --nu2 of the half-space (the paper's rubber by default); ``poisson_low`` is
    the smallest nu2 the command accepts (its help states the range)."""
    parser.add_argument(
        "--E2", default=PAPER["E2"], metavar="PA", help="half-space Young's modulus in Pa"
    )
    parser.add_argument(
        "--nu2",
        default=PAPER["nu2"],
        metavar="X",
        help=f"half-space Poisson's ratio, {poisson_range(poisson_low)}",
    )


def striker(args: argparse.Namespace) -> Material:
    """The striker's material from --E1 (a number in Pa, or 'inf' for rigid) and --nu1.

    --nu1 must lie in (-1, 0.5] even for a rigid striker, where it does not enter E*.
    """
    nu1 = validate_poisson("nu1", args.nu1)
    if str(args.E1).strip().lower() in {"inf", "rigid"}:
        return RIGID
    return Material(validate_positive("E1", args.E1, "Pa"), nu1)


def half_space(args: argparse.Namespace, poisson_low: float = -1.0) -> Material:
    """The half-space's material from --E2 and --nu2 (nu2 in [poisson_low, 0.5])."""
    return Material(
        validate_positive("E2", args.E2, "Pa"),
        validate_poisson("nu2", args.nu2, low=poisson_low),
    )


def indenter(args: argparse.Namespace) -> PowerLawIndenter:
    """The profile z = A r^n from --shape-coefficient and --exponent."""
    return PowerLawIndenter(
        validate_positive("shape-coefficient", args.shape_coefficient, "m^(1-n)"),
        validate_positive("exponent", args.exponent),
    )


def print_json(document: object) -> None:
    """Print strict JSON (non-finite numbers as null) on stdout."""
    print(json.dumps(json_safe(document), indent=2))


def warn(message: str) -> None:
    """One warning line on stderr."""
    print(f"shtaerman: warning: {message}", file=sys.stderr)
