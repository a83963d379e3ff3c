"""``shtaerman effects``: which effect of an impact moves P_max, x_max, t_contact and e."""

from __future__ import annotations

import argparse
import math
import shlex
import sys
from dataclasses import asdict
from pathlib import Path
from types import SimpleNamespace
from typing import Any

from ..api.effect_table import effects
from ..api.effect_table.report import FILES, said, table_text, write_table
from ..api.effect_table.table import EffectTable, Run
from ..api.effect_table.variants import parts_of, variants
from ..api.fem_contact import RUBBER_OPTIONS
from ..api.fem_dynamic import SETTINGS_OPTIONS
from ..problem import parts
from ..theory.materials import Material
from ..validation import InputError
from .common import (
    CASE,
    PROFILES,
    add_figure_format,
    add_inputs,
    given,
    in_option_words,
    indenter,
    keywords,
    print_json,
    refuse_idle_output_options,
)
from .dynamic import DERIVED, MODEL_NOTES, PHYSICS

NOTES = {
    "out": f"{', '.join(FILES)} and the figure effects.png; each finished run is kept at "
    "once (an interrupted table keeps them there, --resume completes it)",
    "force": "an existing --out folder, once the table is done (interrupted, the old folder "
    "stays whole and the finished runs are kept beside it, in OUT.incomplete-PID)",
}


INPUTS = (*CASE, *PROFILES, "E2", "nu2", "density2", "prony", "thickness", "base")
INPUTS += ("interface", "friction")
"""The physics options of the table (besides the model and its rubber options)."""


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
    add_inputs(p, (*INPUTS, "json", "out", "force"), "dynamic", derived=DERIVED, notes=NOTES)
    add_figure_format(p)
    add_inputs(p, ("model", *RUBBER_OPTIONS), "dynamic", notes=MODEL_NOTES)
    accuracy = p.add_argument_group("accuracy (each run's error-estimate ladder)")
    add_inputs(accuracy, ("refine", "estimate"), "dynamic")
    numerics = p.add_argument_group("numerical controls (every run; see 'shtaerman dynamic')")
    add_inputs(numerics, tuple(SETTINGS_OPTIONS), "dynamic", aliases={"time_steps": ("--steps",)})
    p.add_argument(
        "--resume",
        action="store_true",
        help="complete the table an interrupted run left in --out: run only the variants it "
        "lacks (the same options)",
    )
    p.set_defaults(handler=run)


def _progress(line: str) -> None:
    print(said(line, "cli"), file=sys.stderr, flush=True)


def run(args: argparse.Namespace) -> int:
    """Run the effect table (:func:`shtaerman.effects`); print text or JSON; write --out."""
    from ..output.files import check_output_folder, output_path
    from ..output.folder import PROGRESS_FILE, VerifyInterrupted
    from .verify import stopped_code

    if (given(args, "force") or args.resume) and args.out is None:
        option = "resume" if args.resume else "force"
        raise InputError(f"--{option}: applies with --out only (it names the folder to write)")
    if args.resume and args.force:
        raise InputError("--resume and --force exclude each other: --resume keeps the folder")
    refuse_idle_output_options(args, ("out",))
    with in_option_words():
        physics = {name: getattr(args, name) for name in PHYSICS if given(args, name)}
        body = Material(args.E2, args.nu2, args.density2)
        full = parts(indenter(args), body, mass=args.mass, velocity=args.velocity, **physics)
        folder = None
        if args.out is not None:
            marker = PROGRESS_FILE if args.resume else None
            folder = output_path(args.out)
            folder = check_output_folder(
                folder, force=args.force, resume_marker=marker, keep_marker=PROGRESS_FILE
            )
        names = ("refine", "estimate", *(n for n in SETTINGS_OPTIONS if given(args, n)))
        options = keywords(args, names)
        if folder is None:
            _print(effects(full, **options, progress=_progress), args.json)
            return 0
        try:
            _table_into(folder, full, options, args)
        except VerifyInterrupted as stop:
            print(_interrupted_text(stop, folder), file=sys.stderr)
            return stopped_code(stop.cause)
    written = ", ".join(path.name for path in sorted(folder.glob("effects.*")))
    print(f"shtaerman: the table is in {folder}: {written}", file=sys.stderr)
    return 0


def _print(table: EffectTable, as_json: bool) -> None:
    if as_json:
        print_json(table.to_dict())
    else:
        print(table_text(table, "cli"))


def _table_into(folder: Path, full: dict, options: dict, args: argparse.Namespace) -> None:
    """Run the table into ``folder`` (staged; each finished run saved in :data:`PROGRESS_FILE`
    at once, as verify saves its studies: an interrupted table keeps them, --resume reuses
    them); print it, then write its files."""
    from ..output.files import json_safe, staged_folder
    from ..output.folder import (
        PROGRESS_FILE,
        Resuming,
        keep_finished,
        kept_entries,
        save_progress,
    )

    rows, _ = variants(parts_of(full))
    # a kept run is matched on --resume as verify matches a study: by name and fingerprint
    keys = [SimpleNamespace(name=row.label, parts=row.parts) for row in rows]
    names = (*INPUTS, "model", *RUBBER_OPTIONS, "refine", "estimate", *SETTINGS_OPTIONS)
    inputs = {name: getattr(args, name) for name in names}  # a resume gives them again
    words = Resuming("--resume", "table", "variants", "complete it with the same options")
    with staged_folder(
        folder, force=args.force, resume_marker=PROGRESS_FILE if args.resume else None,
        keep_marker=PROGRESS_FILE,
    ) as stage:  # fmt: skip
        entries = kept_entries(stage, keys, quick=False, inputs=inputs, words=words)
        kept = {label: _stored_run(entry) for label, entry in entries.items()}

        def finished(run: Run) -> None:
            entries[run.label] = json_safe(asdict(run))
            save_progress(stage, keys, entries, False, inputs)

        try:  # stopped or failed while its files are written, the runs are kept too
            table = effects(full, **options, progress=_progress, kept=kept, finished=finished)
            _print(table, args.json)  # first: a failed --out (a full disk) does not lose it
            sys.stdout.flush()
            write_table(table, stage)
            table.plot(stage / "effects.png", args.figure_format)
        except BaseException as error:
            keep_finished(stage, keys, entries, error, quick=False, inputs=inputs)
        (stage / PROGRESS_FILE).unlink(missing_ok=True)


def _stored_run(entry: dict) -> Run:
    """A run from its saved entry (JSON: its notes a list, a non-finite value None), checked
    as the :class:`Run` it was: an edited or damaged entry is refused as a damaged
    :data:`~shtaerman.output.folder.PROGRESS_FILE` is, in one line (no traceback)."""
    import msgspec

    from ..output.folder import PROGRESS_FILE

    numbers = {
        key: {name: math.nan if value is None else value for name, value in entry[key].items()}
        for key in ("values", "errors")
        if isinstance(entry.get(key), dict)
    }
    try:
        return msgspec.convert({**entry, **numbers}, Run)
    except msgspec.ValidationError:
        raise InputError(
            f"--resume: {PROGRESS_FILE} is not one this tool wrote; use --force to start again"
        ) from None


def _interrupted_text(stop: Any, out: Path) -> str:
    """What an interrupted table kept, and how to complete it."""
    if isinstance(stop.cause, Exception):
        reason = " ".join(said(str(stop.cause), "cli").split()) or type(stop.cause).__name__
        reason = f"error: {reason};"
    else:
        reason = "interrupted:" if isinstance(stop.cause, KeyboardInterrupt) else "terminated:"
    kept = "" if stop.kept_in is None else f" ({str(out)!r} unchanged: --force keeps it whole)"
    place = out if stop.kept_in is None else stop.kept_in
    return (
        f"shtaerman: {reason} {stop.kept} finished run(s) kept in {str(place)!r}{kept}, the "
        "table not written; complete it with the same options and "
        f"--out {shlex.quote(str(place))} --resume"
    )
