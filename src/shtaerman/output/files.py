"""Writing results safely: strict JSON, atomic CSV files, folders staged aside and moved into
place only when complete."""

from __future__ import annotations

import contextlib
import csv
import math
import os
import shutil
import tempfile
from collections.abc import Iterator, Mapping
from pathlib import Path

import numpy as np
from numpy.typing import ArrayLike

from ..validation import InputError

__all__ = ["check_output_folder", "json_safe", "staged_folder", "write_csv"]


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


def json_safe(value: object) -> object:
    """``value`` with non-finite floats as None (strict JSON) and numpy scalars as floats."""
    if isinstance(value, dict):
        return {str(key): json_safe(item) for key, item in value.items()}
    if isinstance(value, list | tuple):
        return [json_safe(item) for item in value]
    if hasattr(value, "item") and not isinstance(value, str):
        value = value.item()
    if isinstance(value, float) and not math.isfinite(value):
        return None
    return value


def write_csv(path: Path, columns: Mapping[str, ArrayLike]) -> None:
    """Write equal-length columns under a header of their names, atomically.

    The file appears complete or not at all: a failure leaves any old file intact.
    """
    path = Path(path)
    handle, temporary = tempfile.mkstemp(dir=path.parent, prefix=f".{path.name}.", suffix=".tmp")
    try:
        with os.fdopen(handle, "w", newline="") as stream:
            writer = csv.writer(stream)
            writer.writerow(columns)
            writer.writerows(zip(*(np.asarray(c) for c in columns.values()), strict=True))
        os.replace(temporary, path)
    except BaseException:
        Path(temporary).unlink(missing_ok=True)
        raise
