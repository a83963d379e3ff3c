"""``shtaerman effects``: which effect of an impact moves P_max, x_max, t_contact and e."""

from __future__ import annotations

import argparse
import sys

from ..api.effect_table import effects
from ..api.effect_table.report import FILES, table_text, write_table
from ..api.fem_contact import RUBBER_OPTIONS
from ..api.fem_dynamic import SETTINGS_OPTIONS
from ..problem import parts
from ..theory.materials import Material
from ..validation import InputError
from .common import (
    CASE,
    PROFILES,
    add_inputs,
    given,
    in_option_words,
    indenter,
    keywords,
    print_json,
)
from .dynamic import DERIVED, MODEL_NOTES, PHYSICS

NOTES = {"out": ", ".join(FILES), "force": "an existing --out folder"}


def register(commands: argparse._SubParsersAction) -> None:
    """Add the ``effects`` subcommand."""
    p = commands.add_parser(
        "effects",
        help="effect table: which effect (pad, waves, finite strain, Prony, friction) moves "
        "the impact most",
        description=(
            "Runs the impact the options describe (as 'shtaerman dynamic' does) with every "
            "effect off (the paper's problem, by FE), each effect alone, the full problem and "
            "the full problem without each effect, and tables the changes of P_max, x_max, "
            "t_contact and e from the paper's quasi-static impact with their error bars, the "
            "interaction (full - sum of the single changes) and the dominant effect. The "
            "effects: the pad (--thickness), the waves (--density2 > 0), finite strain "
            "(--model), viscoelasticity (--prony), friction (--interface bonded, --friction). "
            "The full problem is checked first, as 'shtaerman dynamic' checks it: refused, the "
            "table is refused in one line before any run. A variant that is refused or fails "
            "shows its reason in its row (each reason once); the others run. Progress on "
            "stderr, SI units."
        ),
    )
    inputs = (*CASE, *PROFILES, "E2", "nu2", "density2", "prony", "thickness", "base", "interface")
    add_inputs(
        p, (*inputs, "friction", "json", "out", "force"), "dynamic", derived=DERIVED, notes=NOTES
    )
    add_inputs(p, ("model", *RUBBER_OPTIONS), "dynamic", notes=MODEL_NOTES)
    accuracy = p.add_argument_group("accuracy (each run's error-estimate ladder)")
    add_inputs(accuracy, ("refine", "estimate"), "dynamic")
    numerics = p.add_argument_group("numerical controls (every run; see 'shtaerman dynamic')")
    add_inputs(numerics, tuple(SETTINGS_OPTIONS), "dynamic", aliases={"time_steps": ("--steps",)})
    p.set_defaults(handler=run)


def _progress(line: str) -> None:
    print(line, file=sys.stderr, flush=True)


def run(args: argparse.Namespace) -> int:
    """Run the effect table (:func:`shtaerman.effects`); print text or JSON; write --out."""
    from ..output.files import output_folder, staged_folder

    if given(args, "force") and args.out is None:
        raise InputError("--force: applies with --out only (it lets the run replace what is there)")
    with in_option_words():
        physics = {name: getattr(args, name) for name in PHYSICS if given(args, name)}
        body = Material(args.E2, args.nu2, args.density2)
        full = parts(indenter(args), body, mass=args.mass, velocity=args.velocity, **physics)
        folder = output_folder(args.out, force=args.force)
        names = ("refine", "estimate", *(n for n in SETTINGS_OPTIONS if given(args, n)))
        table = effects(full, **keywords(args, names), progress=_progress)
    if args.json:  # printed first: a failed --out (a full disk) does not lose the table
        print_json(table.to_dict())
    else:
        print(table_text(table))
    if folder is not None:
        sys.stdout.flush()
        with staged_folder(folder, force=args.force) as stage:
            write_table(table, stage)
    return 0
