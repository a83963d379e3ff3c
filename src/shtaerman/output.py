"""Writing result folders safely: staged aside, moved into place only when complete."""

from __future__ import annotations

import contextlib
import os
import shutil
import tempfile
from collections.abc import Iterator
from pathlib import Path

from .validation import InputError

__all__ = ["check_output_folder", "staged_folder"]


def check_output_folder(path: Path, *, force: bool, option: str = "out") -> Path:
    """Return ``path`` if a run may write there, or raise before any work is done.

    A folder that exists and is not empty is refused unless ``force`` is set; its parent must
    exist.
    """
    path = Path(path).expanduser()
    if path.exists() and not path.is_dir():
        raise InputError(f"{option}: {str(path)!r} exists and is not a folder")
    if path.is_dir() and any(path.iterdir()) and not force:
        raise InputError(f"{option}: folder {str(path)!r} is not empty (use --force to replace it)")
    if not path.parent.is_dir():
        raise InputError(f"{option}: parent folder {str(path.parent)!r} does not exist")
    return path


@contextlib.contextmanager
def staged_folder(target: Path) -> Iterator[Path]:
    """Yield a fresh folder beside ``target``; on success it replaces ``target``.

    On any failure (an exception, Ctrl-C) the staging folder is removed and ``target`` is left
    exactly as it was, so nothing half-written ever looks complete.
    """
    target = Path(target)
    stage = Path(tempfile.mkdtemp(prefix=f".{target.name}.", suffix=".partial", dir=target.parent))
    try:
        yield stage
    except BaseException:
        shutil.rmtree(stage, ignore_errors=True)
        raise
    if target.exists():
        retired = target.with_name(f".{target.name}.replaced-{os.getpid()}")
        target.rename(retired)
        stage.rename(target)
        shutil.rmtree(retired, ignore_errors=True)
    else:
        stage.rename(target)
