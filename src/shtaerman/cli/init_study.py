"""``shtaerman init-study FILE.toml``: write a commented template study to start from."""

from __future__ import annotations

import argparse
import os
from pathlib import Path

from ..output.files import staged_file
from ..validation import InputError
from .common import add_inputs, path_text

__all__ = ["STUDY_TEMPLATE", "TEMPLATES", "register", "run", "write_template"]

TEMPLATE_FOLDER = Path(__file__).with_name("templates")
"""The commented templates, ``<kind>.toml.in`` (``str.format`` fields ``{file}``, ``{name}``
and, but the contact one, ``{indenter}``: ``indenter.toml.in``, the rigid striker's table)."""


def _template(name: str) -> str:
    """The text of the template file ``name`` (:data:`TEMPLATE_FOLDER`)."""
    return (TEMPLATE_FOLDER / f"{name}.toml.in").read_text(encoding="utf-8")


INDENTER = _template("indenter")
"""The [indenter] table of a rigid striker, shared by the templates but the contact one."""
STUDY_TEMPLATE = _template("contact")
"""The contact study template (the default kind)."""

TEMPLATES = {
    kind: _template(kind).format(indenter=INDENTER.rstrip(), file="{file}", name="{name}")
    for kind in ("contact", "dynamic", "finite-strain", "effects")
}
"""Study kind -> its commented template (the rigid striker's [indenter] written once)."""


def register(commands: argparse._SubParsersAction) -> None:
    """Add the ``init-study`` subcommand."""
    p = commands.add_parser(
        "init-study",
        help="write a commented template study (TOML) to edit and verify",
        description=(
            "Write a commented template study of a kind: the paper's worked example with every\n"
            "key explained. Edit it, then run 'shtaerman verify FILE.toml --quick'."
        ),
    )
    p.add_argument("file", type=path_text, metavar="FILE.toml", help="the study file to write")
    p.add_argument(
        "--kind",
        default="contact",
        choices=tuple(TEMPLATES),
        help="the study's kind: the static FEM contact, the dynamic FE impact, the "
        "finite-strain contact, or the effect table of an impact",
    )
    add_inputs(p, ("force",), None)
    p.set_defaults(handler=run)


def write_template(path: Path, *, force: bool = False, kind: str = "contact") -> Path:
    """Write the template of study ``kind`` (:data:`TEMPLATES`) to ``path`` (a new file unless
    ``force``); returns it.

    The file appears whole or not at all: it is written beside ``path`` and renamed into place,
    so a write cut short (a full disk, a file-size limit) leaves the file there untouched.

    Raises
    ------
    shtaerman.validation.InputError
        If ``kind`` has no template, or ``path`` does not end in .toml, exists (without
        ``force``), is not a regular file, or cannot be written.
    """
    if kind not in TEMPLATES:
        raise InputError(f"kind must be one of {sorted(TEMPLATES)}, got {kind!r}")
    shown = display_path(path)
    if path.suffix != ".toml":
        raise InputError(f"FILE must end in .toml, got '{shown}'")
    if path.is_symlink() or (path.exists() and not path.is_file()):
        raise InputError(f"'{shown}' exists and is not a regular file; pick another FILE")
    text = TEMPLATES[kind].format(file=shown, name=display_path(Path(path.stem)))
    try:
        with staged_file(path, force=force, option="FILE") as stage:
            stage.write_text(text, encoding="utf-8")
    except OSError as error:
        reason = os.strerror(error.errno) if error.errno else error  # the file is named here
        raise InputError(f"cannot write '{shown}': {reason}") from None
    return path


def display_path(path: Path) -> str:
    """``path`` as printable text: bytes that are not UTF-8 in its name shown as ``\\xff``."""
    return os.fsencode(path).decode("utf-8", "backslashreplace")


def run(args: argparse.Namespace) -> int:
    """Write the template and say how to run it."""
    path = display_path(write_template(Path(args.file), force=args.force, kind=args.kind))
    print(f"wrote {path}: edit it, then run 'shtaerman verify {path} --quick'")
    return 0
