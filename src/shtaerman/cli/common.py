"""What the subcommands share: the parser class, option groups, input conversion, output."""

from __future__ import annotations

import argparse
import contextlib
import json
import math
import re
import sys
import warnings
from collections.abc import Iterable, Iterator, Mapping
from typing import TYPE_CHECKING, Any

from ..output.files import json_safe
from ..plots.formats import add_figure_format
from ..problem import KEYWORDS, Problem, check_outputs, worded
from ..theory.materials import RIGID, Material
from ..validation import InputError, NumericalFailureError
from ..vocabulary import DeprecatedKeyWarning, Entry, entry

if TYPE_CHECKING:
    from ..theory.sneddon import Indenter

__all__ = [
    "Input",
    "Parser",
    "add_figure_format",
    "add_inputs",
    "given",
    "impact_problem",
    "in_option_words",
    "indenter",
    "keywords",
    "path_text",
    "print_json",
    "refuse_idle_output_options",
    "striker",
    "warn",
    "warn_volumetric",
]

CASE = ("mass", "velocity", "shape_coefficient", "exponent")
"""The striker and its impact: the first options of the computing subcommands."""
PROFILES = ("sphere_radius", "profile")
"""The striker profiles beyond the power law (``impact`` and ``contact``), each in place of
--shape-coefficient and --exponent."""


class HelpFormatter(argparse.RawDescriptionHelpFormatter):
    """Help that shows every default value and keeps the description's line breaks."""

    def _get_help_string(self, action: argparse.Action) -> str:
        text = action.help or ""
        shown = action.default not in (None, argparse.SUPPRESS) and not isinstance(
            action.default, bool
        )
        if not shown or "(default" in text:
            return text
        return f"{text} (default: %(default)s)"


class Parser(argparse.ArgumentParser):
    """argparse that reports a usage error as one line (no usage dump) with exit code 2.

    It also reads a value that starts with a negative number (``-2e11``, ``-1e-3,2e-3``,
    ``-1;1e6:1e-3``) as a value, so its check can name it, rather than as an unknown option;
    a value that still reads as an option is explained (attach it: ``--history=-h.csv``).
    """

    def __init__(self, *args, **kwargs) -> None:
        kwargs.setdefault("formatter_class", HelpFormatter)
        super().__init__(*args, **kwargs)
        self._negative_number_matcher = re.compile(r"^-\.?\d")  # -2e11, -1e-3,2e-3, -1;E1:tau1

    def error(self, message: str) -> None:  # type: ignore[override]
        missing = re.fullmatch(r"argument ([^/:]+)\S*: expected one argument", message)
        if missing:
            option = missing[1]
            message += (
                f" (a value that starts with '-' reads as an option: attach it, {option}=-VALUE)"
            )
        unknown = re.fullmatch(r"unrecognized arguments: (.*)", message)
        if unknown:
            message += self._taken_elsewhere(unknown[1].split())
        raise InputError(re.sub(r"^argument ([^/:\s]+)(/\S+)?: ", r"\1: ", message))

    def _taken_elsewhere(self, tokens: list[str]) -> str:
        """Which other commands take the unrecognized options ``tokens`` (``--friction`` given
        to ``fit``), in words to append; empty if none does."""
        commands = next(
            (a.choices for a in self._actions if isinstance(a, argparse._SubParsersAction)), {}
        )
        said = []
        for option in dict.fromkeys(token.partition("=")[0] for token in tokens):
            takers = [
                name for name, sub in commands.items() if option in sub._option_string_actions
            ]
            if option.startswith("--") and takers:
                said.append(f"{option} is an option of {', '.join(takers)}")
        return f" ({'; '.join(said)}; not of this command)" if said else ""


def path_text(text: str) -> str:
    """A file or folder name of the command line (an argparse ``type``): an empty one names
    none, where ``Path("")`` would be the current folder."""
    if not text:
        raise argparse.ArgumentTypeError("an empty name names no file or folder")
    return text


METAVARS = {
    "shape_coefficient": "A",
    "exponent": "N",
    "density2": "KG/M3",
    "prony": "G1:TAU1,...",
    "depths": "D1,D2,...",
    "history": "FILE.csv",
    "profile": "FILE.csv",
    "out": "DIR",
    "refine": "K",
    "accuracy": "TOL",
    "max_time": "S",
    "mooney_ratio": "R",
    "yeoh": "C2,C3",
    "gent_limit": "JM",
    "unknowns": "NAME,...",
    "units": "COLUMN=UNIT,...",
}
"""The placeholder of an option's value in the help, where its unit does not make one."""


class Input(argparse.Action):
    """Store a vocabulary input, converted and checked by its entry as it is read: a value
    outside the range of computation ``kind`` is an InputError naming the option. Any other
    option string of the action (a deprecated alias, e.g. ``--steps``) works with a one-line
    warning."""

    def __init__(self, *args: Any, item: Entry, kind: str | None, **kwargs: Any) -> None:
        self.item, self.kind = item, kind
        super().__init__(*args, **kwargs)

    def __call__(self, parser, namespace, values, option_string=None) -> None:  # type: ignore[override]
        spelled = vars(namespace).setdefault("_spelled", {})
        if spelled.setdefault(self.dest, option_string) != option_string:
            raise InputError(
                f"{spelled[self.dest]} and {option_string} name one input; keep "
                f"{self.item.cli_option}"
            )
        if option_string is not None and option_string != self.item.cli_option:
            warnings.warn(
                f"{option_string} is deprecated; write {self.item.cli_option} (the old option "
                "works for one release)",
                DeprecatedKeyWarning,
                stacklevel=2,
            )
        value = self.item.parse(values, self.kind, called=self.item.cli_option)
        setattr(namespace, self.dest, value)


def _help(item: Entry, kind: str | None, default: str, note: str = "") -> str:
    """Meaning (and the command's ``note``), unit, valid range and default of ``item`` in
    computation ``kind``."""
    text = item.meaning + (f": {note}" if note else "") + (f", in {item.unit}" if item.unit else "")
    valid = "" if item.choices else item.range_text(kind)
    text += f", {valid}" if valid else ""
    return (text + (f" (default: {default})" if default else "")).replace("%", "%%")


def _shown(value: Any) -> str:
    return f"{value:.6g}" if isinstance(value, float) else "" if value is None else str(value)


def add_inputs(
    parser: argparse.ArgumentParser | argparse._ArgumentGroup,
    names: Iterable[str],
    kind: str | None,
    *,
    derived: Mapping[str, str] | None = None,
    aliases: Mapping[str, tuple[str, ...]] | None = None,
    notes: Mapping[str, str] | None = None,
) -> None:
    """Add the option of each vocabulary input of ``names``, with the default and valid range
    of computation ``kind``, and help from its meaning, unit, range and default.

    ``derived`` maps inputs whose default follows from other inputs (None when not given) to
    the help's words for that default; ``aliases`` maps inputs to deprecated option names;
    ``notes`` adds what the command does with an input (e.g. the files --out writes).
    """
    derived, aliases, notes = derived or {}, aliases or {}, notes or {}
    for name in names:
        item, note = entry(name), notes.get(name, "")
        default = None if name in derived else item.default_for(kind)
        shown = derived.get(name, _shown(default))
        options = (item.cli_option, *aliases.get(name, ()))
        if item.type == "flag":
            parser.add_argument(*options, action="store_true", help=_help(item, kind, "", note))
        elif item.type == "bool":  # an option that switches it off: --no-estimate
            text = f"run without the {item.meaning[0].lower()}{item.meaning[1:]}"
            parser.add_argument(*options, action="store_false", dest=name, help=text)
        else:
            parser.add_argument(
                *options,
                action=Input if item.type != "path" else "store",
                **({"type": path_text} if item.type == "path" else {}),
                default=default,
                dest=name,  # the keyword, also where the option is named otherwise (--fit)
                metavar=METAVARS.get(name) or _metavar(item),
                help=_help(item, kind, shown, note),
                choices=item.choices or None,
                **({"item": item, "kind": kind} if item.type != "path" else {}),
            )


def _metavar(item: Entry) -> str:
    if item.type == "int":
        return "N"
    if item.type == "str":
        return "{" + ",".join(item.choices) + "}" if item.choices else "TEXT"
    return item.unit.upper() if item.unit and "^" not in item.unit else "X"


@contextlib.contextmanager
def in_option_words() -> Iterator[None]:
    """Re-raise an :class:`InputError` (or a numerical failure) of the API, and say again each
    warning it issued, in the command line's words (:func:`shtaerman.problem.worded`:
    ``--mass: ...``, ``give --interface bonded too``, ``(--refine, --mesh-size)``): the user of
    the CLI gave options, not keywords."""
    caught: list[warnings.WarningMessage] = []
    try:
        with warnings.catch_warnings(record=True) as caught, _spoken_errors():
            warnings.simplefilter("always")  # each said again below, as the caller filters it
            yield
    finally:
        for said in caught:
            text = worded(str(said.message), "cli")
            warnings.warn_explicit(text, said.category, said.filename, said.lineno)


@contextlib.contextmanager
def _spoken_errors() -> Iterator[None]:
    """The errors of :func:`in_option_words`."""
    try:
        yield
    except InputError as error:
        spoken = worded(str(error), "cli", parameter=error.parameter)
        if spoken == str(error):
            raise
        raise type(error)(spoken, error.parameter) from None
    except NumericalFailureError as error:  # what to change: the options to give
        spoken = worded(str(error), "cli")  # no parameter at fault: its head is left as is
        if spoken == str(error):
            raise
        raise NumericalFailureError(spoken) from None


def given(args: argparse.Namespace, name: str) -> bool:
    """Whether the option of input ``name`` was on the command line, even with its default
    value (an option stored as read, a path or a flag, counts where it differs from its
    default)."""
    if name in vars(args).get("_spelled", {}):
        return True
    item = entry(name)
    return item.type in ("path", "flag", "bool") and getattr(args, name) != item.default_for(None)


def refuse_idle_output_options(args: argparse.Namespace, targets: tuple[str, ...]) -> None:
    """Refuse, in one line, the options that act on written outputs when nothing is written:
    ``--figure-format`` (not png) without ``--out``, ``--force`` without any of ``targets``."""
    with in_option_words():  # the API's refusal (shtaerman.problem.check_outputs)
        check_outputs(args.out, force=True, estimate=True, figure_format=args.figure_format)
    if given(args, "force") and all(getattr(args, name) is None for name in targets):
        where = " or ".join(entry(name).cli_option for name in targets)
        raise InputError(
            f"--force: applies with {where} only (it lets the run replace what is there); "
            f"give {where} too",
            "force",
        )


def keywords(args: argparse.Namespace, names: Iterable[str]) -> dict[str, Any]:
    """The parsed options ``names`` as the API's keywords (an option's dest is its keyword)."""
    return {name: getattr(args, name) for name in names}


def impact_problem(args: argparse.Namespace, body: Material, **parts: Any) -> Problem:
    """The impact the options describe (:meth:`shtaerman.problem.Problem.impact`): the
    striker's profile, ``body``, --mass, --velocity, ``parts`` and every other part of the
    problem that the command takes and was given."""
    names = [name for name in KEYWORDS if name not in ("mass", "velocity") and name in vars(args)]
    chosen = {name: getattr(args, name) for name in names if given(args, name)}
    mass, velocity = args.mass, args.velocity
    return Problem.impact(indenter(args), body, mass=mass, velocity=velocity, **chosen, **parts)


def striker(args: argparse.Namespace) -> Material:
    """The striker's material from --E1 (in Pa; inf: rigid) and --nu1."""
    return RIGID if math.isinf(args.E1) else Material(args.E1, args.nu1)


def indenter(args: argparse.Namespace) -> Indenter:
    """The striker's profile: z = A r^n from --shape-coefficient and --exponent, or the
    sphere of --sphere-radius, or the table of --profile (one of the three)."""
    from ..theory.indenter import PowerLawIndenter  # here, not at load: it loads scipy.special
    from ..theory.profiles import SphereIndenter, TabulatedIndenter

    chosen = [name for name in PROFILES if getattr(args, name, None) is not None]
    power_law = [name for name in ("shape_coefficient", "exponent") if given(args, name)]
    if len(chosen) > 1 or (chosen and power_law):
        first, second = (chosen + power_law)[:2]
        raise InputError(
            f"{entry(first).cli_option}: give one striker profile: the power law "
            "(--shape-coefficient, --exponent), --sphere-radius or --profile; "
            f"{entry(second).cli_option} was given too",
            first,
        )
    if chosen == ["sphere_radius"]:
        return SphereIndenter(args.sphere_radius)
    if chosen == ["profile"]:
        return TabulatedIndenter.from_csv(args.profile)
    return PowerLawIndenter(args.shape_coefficient, args.exponent)


def print_json(document: object) -> None:
    """Print strict JSON (non-finite numbers as null) on stdout."""
    print(json.dumps(json_safe(document), indent=2))


def warn(message: str) -> None:
    """One warning line on stderr."""
    print(f"shtaerman: warning: {message}", file=sys.stderr)


def warn_volumetric(args: argparse.Namespace) -> None:
    """Warn that --volumetric, when given, changes nothing at --nu2 0.5 (an incompressible
    body stores no volumetric energy); the run goes on."""
    if given(args, "volumetric") and args.nu2 == 0.5:
        warn("--volumetric has no effect at --nu2 0.5 (no volumetric energy): ignored")
