"""Writing results safely: strict JSON, CSV files, folders staged aside and moved into place
only when complete.

The rules, for a result folder ``DIR`` (and likewise a single result file):

- The work happens in ``.DIR.partial-PID`` beside it (PID: the writing process). Every
  temporary lives in there, and it is removed on any failure, Ctrl-C or SIGTERM. After a SIGKILL
  it stays; the next run writing ``DIR`` removes it once its process is gone, and refuses to
  start while that process still runs (two runs writing one folder: one wins, one is refused).
- ``DIR`` itself is reserved at the start with ``os.mkdir`` (atomic: exactly one run gets it)
  and the finished folder is renamed onto that empty reservation at the end, so the complete
  folder appears in one step and never replaces anything it was not told to. An old ``DIR``
  (``force``) is moved into the staging folder first and restored if the run fails; it must
  be one this tool wrote, holding no file its marker does not list (a user's note is never
  deleted).
- Folders and files get the permissions of the umask (0777/0666 masked), like ``mkdir`` and
  ``open`` would give, not the 0700/0600 of ``mkdtemp``/``mkstemp``.
- The current folder, its parents and symbolic links are refused as result folders: replacing
  them would pull the ground from under the shell (``--out .``) or act on a folder the user did
  not name. A single result file may be a special file (``/dev/null``, a FIFO, ``/dev/stdout``):
  it is written directly, never replaced.
"""

from __future__ import annotations

import contextlib
import csv
import errno
import glob
import itertools
import json
import math
import os
import re
import shutil
import stat
import sys
import warnings
from collections.abc import Iterable, Iterator, Mapping
from pathlib import Path

import numpy as np
from numpy.typing import ArrayLike

from .. import vocabulary
from ..signals import deferred
from ..validation import InputError

__all__ = [
    "CSV_UNITS",
    "FOLDER_MARKER",
    "SWEEP_MARKER",
    "KeepStaged",
    "check_folder_path",
    "check_folder_place",
    "check_output_file",
    "check_output_folder",
    "csv_header",
    "file_mode",
    "folder_lock",
    "json_safe",
    "missing_folder",
    "naming_output",
    "output_folder",
    "probe_removable",
    "resumable",
    "staged_file",
    "staged_folder",
    "write_csv",
]

STAGE_SUFFIX = ".partial-"
"""Staging names are ``.NAME.partial-PID``."""
FOLDER_MARKER = ".shtaerman-folder.json"
"""Written into every result folder :func:`staged_folder` makes: ``force`` replaces only a
folder that holds it (a folder this tool wrote), never a user's own folder."""
FOLDER_FORMAT = "shtaerman-folder-1"
SWEEP_MARKER = ".shtaerman-sweep.json"
"""What makes a folder a sweep folder (:mod:`shtaerman.sweep.engine`: its ``--resume`` and
``--force`` touch no other; the other routes name it as a sweep's, not a foreign folder)."""
KEEP_FILE = "keep"
"""In a staging folder: the name of the file whose presence in ``content`` makes what a killed
run staged worth keeping (:func:`staged_folder`'s ``keep_marker``)."""


def missing_folder(folder: Path) -> str:
    """Why ``folder``, the parent of an output, cannot hold it (for a one-line error)."""
    if folder.exists() or folder.is_symlink():
        return f"parent {str(folder)!r} is not a folder"
    return f"parent folder {str(folder)!r} does not exist"


def _umask() -> int:
    mask = os.umask(0)
    os.umask(mask)
    return mask


def file_mode() -> int:
    """Permissions of a new file under the umask (0666 masked), as ``open`` would give it."""
    return 0o666 & ~_umask()


def _stage_path(target: Path, pid: int | None = None) -> Path:
    return target.with_name(f".{target.name}{STAGE_SUFFIX}{os.getpid() if pid is None else pid}")


def _alive(pid: int) -> bool:
    try:
        os.kill(pid, 0)
    except ProcessLookupError:
        return False
    except PermissionError:  # someone else's process
        return True
    return True


def _stages(target: Path) -> list[tuple[int, Path]]:
    """Staging folders/files of ``target`` by any process: (pid, path)."""
    pattern = re.compile(re.escape(f".{target.name}{STAGE_SUFFIX}") + r"(\d+)$")
    found = []
    with contextlib.suppress(OSError):
        for entry in os.scandir(target.parent):
            match = pattern.match(entry.name)
            if match:
                found.append((int(match.group(1)), Path(entry.path)))
    return found


def _remove(path: Path) -> None:
    if path.is_dir() and not path.is_symlink():
        shutil.rmtree(path, ignore_errors=True)
    else:
        with contextlib.suppress(FileNotFoundError):
            path.unlink()


def _clean_stale(target: Path, stage: Path) -> None:
    """Undo what a killed run left: restore the folder it was replacing, drop its reservation.

    When the killed run had already filled ``target`` (a sweep writes in place), the folder it
    was replacing is kept beside it as ``NAME.replaced-PID`` and a warning says where."""
    retired, content = stage / "replaced", stage / "content"
    if _worth_keeping(stage):
        _keep_stale(target, stage)
        return
    with contextlib.suppress(OSError):
        if content.is_dir() or retired.is_dir():
            if target.is_dir() and not target.is_symlink() and not any(target.iterdir()):
                os.rmdir(target)  # its empty reservation
            if retired.is_dir() and not os.path.lexists(target):
                os.rename(retired, target)
        if retired.is_dir():
            kept = target.with_name(f"{target.name}.replaced-{stage.name.rsplit('-', 1)[-1]}")
            os.rename(retired, kept)
            warnings.warn(
                f"a killed run was replacing {str(target)!r}; the folder it replaced is kept "
                f"as {str(kept)!r}",
                stacklevel=2,
            )
    _remove(stage)


def _worth_keeping(stage: Path) -> bool:
    """True when ``stage`` (a killed run's) has content its run marked as resumable."""
    try:
        marker = (stage / KEEP_FILE).read_text(encoding="utf-8")
    except (OSError, UnicodeDecodeError):
        return False
    return bool(marker) and "/" not in marker and resumable(stage / "content", marker)


def _keep_stale(target: Path, stage: Path) -> None:
    """Move a killed run's resumable content into place as ``target`` (as an interrupted run
    would have), or beside it when ``target`` holds something else (the folder a --force run
    was replacing, put back as then); a warning says where."""
    pid = stage.name.rsplit("-", 1)[-1]
    with contextlib.suppress(OSError):
        if target.is_dir() and not target.is_symlink() and not any(target.iterdir()):
            os.rmdir(target)  # its empty reservation
        if (stage / "replaced").is_dir():  # --force: the folder it was replacing stays whole
            os.rename(stage / "replaced", target)
    place = target
    try:
        os.rename(stage / "content", target)  # fails if target holds anything
    except OSError:
        place = target.with_name(f"{target.name}.incomplete-{pid}")
        try:
            os.rename(stage / "content", place)
        except OSError:
            return  # another run took it meanwhile
    warnings.warn(
        f"a killed run (pid {pid}) left its finished part in {str(place)!r}; complete it with "
        "--resume --out on that folder",
        stacklevel=2,
    )
    _remove(stage)


def adopt_killed_runs(parent: Path, prefix: str) -> None:
    """Put in place what killed runs left beside the folders ``parent/prefix*`` (as the next run
    writing each folder would; a warning names each), so a run under a new name finds them."""
    pattern = re.compile(rf"\.({re.escape(prefix)}.*){re.escape(STAGE_SUFFIX)}\d+$")
    with contextlib.suppress(OSError):
        for entry in os.scandir(parent):
            match = pattern.match(entry.name)
            if match:
                _other_writers(parent / match.group(1))


def _other_writers(target: Path) -> list[int]:
    """Clean the staging leftovers of dead processes; return the pids of live writers
    (this process included: one process writes one target at a time)."""
    live = []
    for pid, path in _stages(target):
        if pid == os.getpid() or _alive(pid):
            live.append(pid)
        else:  # left by a SIGKILL: its process is gone
            _clean_stale(target, path)
    return sorted(live)


def _busy(option: str, target: Path, pids: list[int]) -> InputError:
    return InputError(
        f"{option}: another shtaerman run (pid {pids[0]}) is writing {str(target)!r}; wait for "
        f"it, or remove {str(_stage_path(target, pids[0]))!r} if no such run exists",
        option,
    )


def _absolute(path: Path) -> Path:
    """``path`` made absolute without resolving symbolic links (``..`` folded lexically)."""
    return Path(os.path.abspath(os.fspath(path)))


def _is_cwd_or_parent(path: Path) -> bool:
    try:
        here = Path.cwd().resolve()
        real = path.resolve()
    except OSError:
        return False
    return real == here or real in here.parents


def probe_writable(option: str, folder: Path, name: str) -> None:
    """Raise InputError unless a staging entry ``name`` can be created in ``folder``."""
    probe = folder / name
    try:
        os.mkdir(probe)
    except FileExistsError:
        return
    except OSError as error:
        raise _unwritable(option, folder, error) from None
    os.rmdir(probe)


def _unwritable(option: str, folder: Path, error: OSError) -> InputError:
    """Why no entry could be made in ``folder``, as the refusal of ``option``."""
    if error.errno == errno.ENOENT and not folder.is_dir():
        return InputError(f"{option}: {missing_folder(folder)}", option)
    reason = error.strerror or str(error)
    if error.errno == errno.ENOENT:  # /proc: the folder is there
        reason = "its file system takes no new files"
    return InputError(f"{option}: cannot write in {str(folder)!r} ({reason})", option)


FS_IOC_GETFLAGS = 0x80086601
"""Linux's ioctl that reads an inode's attribute flags (``lsattr``)."""
UNREMOVABLE_FLAGS = 0x10 | 0x20
"""FS_IMMUTABLE_FL (``chattr +i``) and FS_APPEND_FL (``chattr +a``): not even root removes
such a file, or anything from such a folder."""


def _unremovable(path: str) -> bool:
    """Whether ``path`` (not followed) is immutable or append-only; False where the file
    system keeps no such flags."""
    import fcntl  # POSIX only, as the flags are Linux's

    try:
        handle = os.open(path, os.O_RDONLY | os.O_NOFOLLOW | os.O_NONBLOCK)
    except OSError:  # a symbolic link, a socket: removed as a name, whatever it points to
        return False
    try:
        flags = int.from_bytes(fcntl.ioctl(handle, FS_IOC_GETFLAGS, bytes(4)), sys.byteorder)
    except OSError:  # no such flags here (ENOTTY, EOPNOTSUPP)
        return False
    finally:
        os.close(handle)
    return bool(flags & UNREMOVABLE_FLAGS)


def probe_removable(option: str, folder: Path) -> None:
    """Raise InputError, before any run, if the folder a run would replace holds an entry that
    cannot be removed (immutable or append-only: ``chattr +i`` / ``+a``, the folder included):
    moved into the run's staging folder, it would stay there as a stray ``.NAME.partial-PID``."""
    for root, folders, files in os.walk(folder):
        for name in [".", *folders, *files]:
            path = os.path.normpath(os.path.join(root, name))
            if _unremovable(path):
                where = os.path.relpath(path, folder)
                what = f"{str(folder)!r}" if where == "." else f"{where!r} in {str(folder)!r}"
                raise InputError(
                    f"{option}: cannot replace {str(folder)!r}: {what} is immutable or "
                    "append-only (lsattr shows it); make it removable (chattr -i -a) or write "
                    "the results to another folder",
                    option,
                )


class KeepStaged(BaseException):
    """Raised inside :func:`staged_folder`: move what is staged into place, then raise ``reason``.

    For a run stopped part way whose finished part is complete in itself and says what is
    missing (a marker file the caller wrote), so that a later run can complete it.
    """

    def __init__(self, reason: BaseException) -> None:
        super().__init__(str(reason))
        self.reason = reason


def resumable(folder: Path, marker: str | None) -> bool:
    """True when ``folder`` holds ``marker`` as a regular file (not a symbolic link)."""
    if marker is None:
        return False
    try:
        return stat.S_ISREG(os.lstat(folder / marker).st_mode)
    except OSError:
        return False


def ours(folder: Path) -> bool:
    """True when ``folder`` holds :data:`FOLDER_MARKER` as a regular file: a result folder this
    tool wrote."""
    return resumable(folder, FOLDER_MARKER)


def _mark(folder: Path, *, sealed: bool = False) -> None:
    """Write :data:`FOLDER_MARKER` into ``folder`` (a new file: a hard-linked old one is not
    written through); ``sealed``: with the list of the files the folder holds now."""
    content: dict[str, object] = {"format": FOLDER_FORMAT}
    if sealed:
        content["files"] = sorted(_files_in(folder) - {FOLDER_MARKER})
    temporary = folder / f".{FOLDER_MARKER}.tmp"
    temporary.write_text(json.dumps(content), encoding="utf-8")
    os.replace(temporary, folder / FOLDER_MARKER)


def _files_in(folder: Path) -> set[str]:
    """Paths (POSIX, relative to ``folder``) of every non-folder entry below it."""
    found = set()
    for root, folders, files in os.walk(folder):
        here = Path(root).relative_to(folder)
        links = [name for name in folders if os.path.islink(os.path.join(root, name))]
        found.update((here / name).as_posix() for name in [*files, *links])
    return found


def _foreign_files(folder: Path) -> list[str]:
    """Files in a folder this tool wrote that its marker does not list (a user's additions);
    none for a marker without a list (an interrupted run, an older version)."""
    try:
        listed = json.loads((folder / FOLDER_MARKER).read_text(encoding="utf-8"))["files"]
    except (OSError, ValueError, KeyError, TypeError):
        return []
    return sorted(_files_in(folder) - set(listed) - {FOLDER_MARKER})


def _check_replaceable(
    option: str,
    path: object,
    target: Path,
    force: bool,
    marker: str | None,
    keep_marker: str | None = None,
) -> None:
    """Raise unless the folder ``target`` (``path`` as given) may be written: empty, holding
    ``marker`` (a run to complete), or with ``force`` a folder this tool wrote holding only
    the files its marker lists. Refused, the message says what works: ``keep_marker`` is the
    file an interrupted run of this command leaves (it can be completed with resume=True)."""
    if not any(target.iterdir()):
        return
    folder, new = f"{option}: folder {str(path)!r}", f"name a new folder with {_named(option)}"
    if not force and not resumable(target, marker):
        raise InputError(f"{folder} {_occupied(option, target, marker, keep_marker)}", option)
    if force and not ours(target):
        raise InputError(
            f"{folder} was not written by shtaerman (no {FOLDER_MARKER}); force=True replaces only "
            f"result folders of this tool: {new}",
            option,
        )
    if force and (foreign := _foreign_files(target)):
        more = f" and {len(foreign) - 1} more" if len(foreign) > 1 else ""
        raise InputError(
            f"{folder} holds {foreign[0]!r}{more}, not written by shtaerman; force=True replaces "
            f"only what this tool wrote: move it or {new}",
            option,
        )


def _occupied(option: str, target: Path, marker: str | None, keep_marker: str | None) -> str:
    """What the non-empty folder ``target`` holds and what works instead of writing it as
    asked (no force; ``marker``: a resume asked): resume=True for an interrupted run, the
    folder an interrupted force=True run kept beside it, force=True for a result folder of
    this tool, a new folder for another program's."""
    new = f"name a new folder with {_named(option)}"
    if marker is None and resumable(target, keep_marker):
        return (
            f"holds an interrupted run ({keep_marker}); complete it with resume=True and the "
            "same inputs, or start again with force=True"
        )
    state = f"holds no interrupted run to complete (no {marker})" if marker else "is not empty"
    if (target / SWEEP_MARKER).is_file():  # shtaerman sweep's: completed by that command
        return f"{state}; it is the result of shtaerman sweep (completed by its --resume): {new}"
    if not ours(target):  # force would refuse it too
        return f"{state}; it was not written by shtaerman: {new}"
    beside = sorted(
        (place for place in target.parent.glob(f"{glob.escape(target.name)}.incomplete-*")
         if place.is_dir() and resumable(place, marker or keep_marker)),
        key=lambda place: place.stat().st_mtime,
    )  # fmt: skip
    if beside:
        return (
            f"{state}; an interrupted force=True run that was replacing it kept its finished "
            f"part in {str(beside[-1])!r}: complete that with out={str(beside[-1])!r} "
            "resume=True, or replace this folder with force=True"
        )
    return f"{state}; use force=True to replace it"


def _named(option: str) -> str:
    """Option ``option`` as a keyword to give (``out=...``, which the command line spells
    ``--out``), or as written when it is no keyword (``FILE``, ``--out``)."""
    return f"{option}=..." if option.isidentifier() else option


@contextlib.contextmanager
def naming_output(option: str, target: Path) -> Iterator[None]:
    """An OS error that names no file (a full disk: ``[Errno 28]``) raised again naming the
    output being written, e.g. "(writing --history 'h.csv')"; ``option`` a keyword (``out``,
    spelled ``--out``) or as written (``FILE``, ``--out``)."""
    try:
        yield
    except OSError as error:
        if error.filename is not None or error.errno is None:
            raise
        keyword = option.isidentifier() and option.islower()
        flag = f"--{option.replace('_', '-')}" if keyword else option
        where = f"{error.strerror} (writing {flag} {str(target)!r})"
        raise OSError(error.errno, where) from error


def _refuse_link(path: Path, option: str, kind: str) -> None:
    """Raise InputError when ``path`` itself is a symbolic link (also a broken one): a write
    there would land in whatever it points to, not in the ``kind`` ("folder", "file") named."""
    if path.is_symlink():
        raise InputError(
            f"{option}: {str(path)!r} is a symbolic link; name the {kind} itself "
            f"({os.path.realpath(path)!r})",
            option,
        )


@contextlib.contextmanager
def _path_errors(option: str, path: object) -> Iterator[None]:
    """An invalid name (a NUL byte) or an OS error on ``path`` as an InputError naming it."""
    try:
        yield
    except InputError:
        raise
    except ValueError as error:
        raise InputError(f"{option}: {str(path)!r} is not a valid path ({error})", option) from None
    except OSError as error:
        raise InputError(f"{option}: {str(path)!r}: {error.strerror or error}", option) from None


def check_folder_path(path: Path, option: str = "out") -> Path:
    """``path`` made absolute (symbolic links not resolved), or raise InputError when it names
    no folder, is a symbolic link, or is the current folder or one of its parents."""
    with _path_errors(option, path):
        raw = Path(path).expanduser()
        target = _absolute(raw)
        if not target.name or target == target.parent:
            raise InputError(f"{option}: {str(path)!r} names no folder to create", option)
        _refuse_link(raw, option, "folder")
        if _is_cwd_or_parent(target):
            raise InputError(
                f"{option}: {str(path)!r} is the current folder or one of its parents; name a "
                f"new folder (e.g. {option} results)",
                option,
            )
    return target


def output_path(out: object) -> Path:
    """A Python caller's ``out``, a path or a string (the vocabulary's ``out``), as a Path."""
    path = os.fspath(out) if isinstance(out, os.PathLike) else out
    return Path(vocabulary.entry("out").check(path))


def output_folder(out: object, *, force: bool) -> Path | None:
    """:func:`check_output_folder` of a Python caller's ``out`` (:func:`output_path`; None:
    no folder)."""
    return None if out is None else check_output_folder(output_path(out), force=force)


@contextlib.contextmanager
def folder_lock(target: Path, option: str = "out") -> Iterator[Path]:
    """Hold ``target`` for this run: the staging folder ``.NAME.partial-PID`` beside it, which
    every writer of ``target`` checks (a run killed meanwhile is cleaned up by the next). Yields
    that folder; a ``replaced`` folder inside it is restored by the next run after a SIGKILL.

    Raises
    ------
    InputError
        If another live run writes ``target``.
    """
    live = [pid for pid in _other_writers(target) if pid != os.getpid()]
    if live:
        raise _busy(option, target, live)
    try:
        stage = _claim(target, option)
    except OSError as error:
        raise _unwritable(option, target.parent, error) from None
    try:
        yield stage
    finally:
        shutil.rmtree(stage, ignore_errors=True)


def check_output_folder(
    path: Path,
    *,
    force: bool,
    option: str = "out",
    resume_marker: str | None = None,
    keep_marker: str | None = None,
) -> Path:
    """Return ``path`` (absolute) if a run may write there, or raise before any work is done.

    Its place is :func:`check_folder_place`'s (``resume_marker`` given: a resume, refused on a
    folder that does not exist). A folder that exists and is not empty is refused unless
    ``force`` is set, or unless it holds the file ``resume_marker`` (a run left it incomplete,
    to be completed). ``keep_marker``: the file an interrupted run of the caller leaves (a
    refusal then names resume=True where it works).
    """
    target = check_folder_place(path, option, resume=resume_marker is not None)
    with _path_errors(option, path):
        if target.is_dir():
            _check_replaceable(option, path, target, force, resume_marker, keep_marker)
            if any(target.iterdir()):  # replaced (force) or completed (resume): removed
                probe_removable(option, target)
    return target


def check_folder_place(path: Path, option: str = "out", *, resume: bool = False) -> Path:
    """Return ``path`` (absolute) if a result folder may be made or completed there, or raise
    InputError before any work: the refusals of :func:`check_folder_path`, an existing entry
    that is no folder, a parent that is missing or no folder, another live run writing it (a
    killed run's leftovers are cleaned first, which may put its folder back), with ``resume``
    a folder that does not exist or is empty (nothing to complete: an interrupted run keeps
    what it saved, else nothing), and a parent that takes no new entry.
    The one check of the place of every result folder (:func:`check_output_folder`, a sweep's);
    what the folder may hold is each caller's."""
    target = check_folder_path(path, option)
    with _path_errors(option, path):
        if target.exists() and not target.is_dir():
            raise InputError(f"{option}: {str(path)!r} exists and is not a folder", option)
        if not target.parent.is_dir():
            raise InputError(f"{option}: {missing_folder(target.parent)}", option)
        live = _other_writers(target)  # first: cleaning may restore a folder
        if live:
            raise _busy(option, target, live)
        if resume and not (target.is_dir() and any(target.iterdir())):
            state = "is empty" if target.is_dir() else "does not exist"
            raise InputError(
                f"resume: the folder {str(path)!r} ({_named(option)}) {state}, so there is "
                "nothing to complete; drop resume=True to start a new run",
                "resume",
            )
        probe_writable(option, target.parent, _stage_path(target).name)
    return target


def _claim(target: Path, option: str) -> Path:
    """Create this run's staging folder beside ``target``; refuse when a rival runs."""
    stage = _stage_path(target)
    try:
        os.mkdir(stage)
    except FileExistsError:
        raise _busy(option, target, [os.getpid()]) from None
    # two runs that started together both see each other's staging folder: the lower pid wins
    rivals = [pid for pid, _ in _stages(target) if pid != os.getpid() and _alive(pid)]
    if rivals and min(rivals) < os.getpid():
        os.rmdir(stage)
        raise _busy(option, target, rivals)
    return stage


def _link_tree(source: Path, destination: Path) -> None:
    """Hard-link (copy where links fail) the tree ``source`` into ``destination``; symbolic
    links are recreated as links, never followed."""

    def link(src: str, dst: str) -> None:
        try:
            os.link(src, dst, follow_symlinks=False)
        except OSError:
            shutil.copy2(src, dst, follow_symlinks=False)

    shutil.copytree(source, destination, symlinks=True, copy_function=link, dirs_exist_ok=True)


def _retire(target: Path, retired: Path, option: str) -> None:
    """Move the folder a run replaces aside (atomic: only one run can take it)."""
    try:
        os.rename(target, retired)
    except OSError as error:  # a read-only or immutable folder: before any run
        raise InputError(
            f"{option}: cannot replace {str(target)!r} ({error.strerror or error}); "
            "make it writable, or write the results to another folder",
            option,
        ) from None


def _reserve(target: Path, option: str) -> None:
    """Create ``target``, the reservation (atomic: only one run gets it)."""
    try:
        os.mkdir(target)
    except FileExistsError:
        raise InputError(
            f"{option}: {str(target)!r} was created by another program meanwhile", option
        ) from None


@contextlib.contextmanager
def staged_folder(
    target: Path,
    *,
    force: bool = False,
    option: str = "out",
    resume_marker: str | None = None,
    keep_marker: str | None = None,
) -> Iterator[Path]:
    """Yield a folder to fill; on success it becomes ``target`` in one rename.

    ``target`` may exist only as an empty folder, or (``force``) as a folder this tool wrote
    (:data:`FOLDER_MARKER`, written into every folder made here with the list of its files)
    holding only the files listed, which is then replaced. A
    folder holding the file ``resume_marker`` is replaced too, and the yielded folder starts
    with its content (hard links) for the run to complete. On any failure (an exception,
    Ctrl-C, SIGTERM raised as an exception) everything written is removed and ``target`` is
    left exactly as it was; :class:`KeepStaged` instead moves what is staged into place and
    raises its reason, or with ``force`` keeps the old folder whole and moves what is staged
    beside it (:func:`incomplete_path`, set as the reason's ``kept_in``). After a SIGKILL,
    the next run writing ``target`` moves the staged folder into place when it holds the file
    ``keep_marker`` (a replaced folder is put back, the staged one beside it).

    Raises
    ------
    InputError
        If another run is writing ``target``, or ``target`` is not ours to replace.
    """
    target = check_output_folder(
        target, force=force, option=option, resume_marker=resume_marker, keep_marker=keep_marker
    )
    stage = _claim(target, option)
    content, retired = stage / "content", stage / "replaced"
    reserved = False
    try:
        resumed = resumable(target, resume_marker)
        if os.path.lexists(target):  # checked again: another program may have written it
            _check_replaceable(option, target, target, force, resume_marker, keep_marker)
            _retire(target, retired, option)
        _reserve(target, option)
        reserved = True
        os.mkdir(content)
        if resumed:
            _link_tree(retired, content)
        _mark(content)
        if keep_marker is not None:
            (stage / KEEP_FILE).write_text(keep_marker, encoding="utf-8")
        try:
            with naming_output(option, target):
                yield content
        except KeepStaged as keep:
            _mark(content, sealed=True)
            if os.path.lexists(retired) and not resumed:  # --force: the old folder stays whole
                keep.reason.kept_in = _keep_beside(content, retired, target)
                reserved = False
                raise keep.reason from None
            _publish(content, target, option)
            reserved = False
            _discard(retired)
            raise keep.reason from None
        _mark(content, sealed=True)
        _publish(content, target, option)
        reserved = False
        _discard(retired)
    except BaseException:
        with deferred():  # a second Ctrl-C must not break the put-back
            if reserved:
                with contextlib.suppress(OSError):
                    os.rmdir(target)  # only if still our empty reservation
            if os.path.lexists(retired) and not os.path.lexists(target):
                os.rename(retired, target)  # put the old folder back
        raise
    finally:
        with deferred():  # nor the removal of the stage
            shutil.rmtree(stage, ignore_errors=True)


def incomplete_path(target: Path) -> Path:
    """Where the finished part of an interrupted run that was replacing ``target`` is kept:
    ``NAME.incomplete-PID`` beside it (``target`` keeps the folder it replaced), or
    ``NAME.incomplete-PID-2``, ``-3``, ... when that name is taken (process ids come back: an
    earlier run's kept part must not be overwritten, nor block the put-back)."""
    first = target.with_name(f"{target.name}.incomplete-{os.getpid()}")
    taken = itertools.count(2)
    place = first
    while os.path.lexists(place):
        place = first.with_name(f"{first.name}-{next(taken)}")
    return place


def _keep_beside(content: Path, retired: Path, target: Path) -> Path:
    """Put the replaced folder ``retired`` back as ``target`` (its reservation removed) and the
    interrupted run's ``content`` beside it (:func:`incomplete_path`); returns where."""
    with deferred():  # a second Ctrl-C must not break the put-back
        os.rmdir(target)  # our empty reservation
        os.rename(retired, target)
        place = incomplete_path(target)
        os.rename(content, place)
    return place


def _discard(retired: Path) -> None:
    """Mark the replaced folder as superseded once the new one is in place, so that a run
    killed while deleting the stage leaves nothing :func:`_clean_stale` would keep."""
    with contextlib.suppress(OSError):
        os.rename(retired, retired.with_name("superseded"))


def _publish(content: Path, target: Path, option: str) -> None:
    """Rename the finished ``content`` onto the empty reservation ``target``."""
    try:
        os.rename(content, target)  # onto our empty reservation: atomic, complete at once
    except OSError as error:  # someone wrote into the reservation meanwhile
        raise InputError(
            f"{option}: {str(target)!r} was changed by another program during the run "
            f"({error.strerror}); it was left alone and this run's results discarded",
            option,
        ) from None


def check_output_file(path: str | Path, *, force: bool, option: str = "history") -> Path:
    """Return ``path`` if a run may write that file, or raise before any work is done.

    A regular file is replaced only with ``force``, and never when it (or its folder) is
    immutable or append-only; a special file (``/dev/null``, a FIFO, a
    terminal, also through a link: ``/dev/stdout``) is written into, never replaced; a folder
    and a symbolic link to anything else (a file elsewhere, nothing) are refused.
    """
    if not os.fspath(path):
        raise InputError(f"{option}: an empty name names no file", option)
    path = Path(path).expanduser()
    with _path_errors(option, path):
        if path.exists():  # follows symbolic links, also /dev/stdout -> /proc/self/fd/1
            mode = path.stat().st_mode
            if stat.S_ISDIR(mode):
                raise InputError(f"{option}: {str(path)!r} is a folder", option)
            if not stat.S_ISREG(mode):  # a device, a FIFO, a terminal: written into
                if not os.access(path, os.W_OK):
                    raise InputError(f"{option}: cannot write {str(path)!r}", option)
                return path
        _refuse_link(path, option, "file")
        if path.exists() and not force:
            raise InputError(
                f"{option}: {str(path)!r} exists; use force=True to replace it", option
            )
        real = Path(os.path.realpath(path))
        if real.exists() and (_unremovable(str(real)) or _unremovable(str(real.parent))):
            raise InputError(
                f"{option}: cannot replace {str(path)!r}: it or its folder is immutable or "
                "append-only (lsattr shows it); make it removable (chattr -i -a) or write "
                "another file",
                option,
            )
        if not real.parent.is_dir():
            raise InputError(f"{option}: {missing_folder(path.parent)}", option)
        live = _other_writers(real)
        if live:
            raise _busy(option, real, live)
        probe_writable(option, real.parent, _stage_path(real).name)
    return path


@contextlib.contextmanager
def staged_file(path: Path, *, force: bool = False, option: str = "history") -> Iterator[Path]:
    """Yield a path to write; on success it becomes ``path`` in one step.

    A regular ``path`` is written as ``.NAME.partial-PID`` beside it and then linked into place
    (no ``force``: ``os.link`` fails if ``path`` appeared meanwhile, nothing is replaced) or
    renamed over it (``force``). A special file is yielded as is and written directly. The
    permissions follow the umask.
    """
    path = check_output_file(path, force=force, option=option)
    if path.exists() and not path.is_file():  # a special file: written directly
        with naming_output(option, path):
            yield path
        return
    real = Path(os.path.realpath(path))
    stage = _stage_path(real)
    if os.path.lexists(stage):
        raise _busy(option, real, [os.getpid()])
    try:
        with naming_output(option, path):
            yield stage
        os.chmod(stage, file_mode())
        if force:
            os.replace(stage, real)
        else:
            try:
                os.link(stage, real)
            except FileExistsError:
                raise InputError(
                    f"{option}: {str(path)!r} was created by another program meanwhile; "
                    f"use force=True to replace it",
                    option,
                ) from None
    finally:
        _remove(stage)


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


CSV_UNITS = {
    # impact histories
    "t": "s",
    "x": "m",
    "v": "m/s",
    "P": "N",
    "a": "m",
    "p0": "Pa",
    # contact curves and pressure profiles
    "depth": "m",
    "force": "N",
    "force_nodal_sum": "N",
    "contact_radius": "m",
    "central_pressure": "Pa",
    "force_analytic": "N",
    "contact_radius_analytic": "m",
    "central_pressure_analytic": "Pa",
    "central_to_mean": "1",
    "pressure_profile_error": "1",
    "active_set_iterations": "1",
    "r": "m",
    "pressure": "Pa",
    "pressure_analytic": "Pa",
    "gap": "m",
    "strain_energy": "J",
    # finite strain beside the linear solution
    "depth_to_radius": "1",
    "force_linear": "N",
    "force_linear_fem": "N",
    "force_ratio": "1",
    "force_ratio_fem": "1",
    "radius_ratio": "1",
    "newton_iterations": "1",
}
"""The unit of every CSV column name, shown in the header as ``name [unit]`` (``[1]``:
dimensionless): ``t [s],x [m],P [N],a [m],p0 [Pa]`` for an impact history."""


def csv_header(names: Iterable[str]) -> list[str]:
    """``name [unit]`` for each column name; a name that already carries ``[unit]`` is kept.

    Raises
    ------
    ValueError
        For a name of unknown unit: add it to :data:`CSV_UNITS` (no column without a unit).
    """
    header = []
    for name in names:
        if name.endswith("]") and " [" in name:
            header.append(name)
        elif name in CSV_UNITS:
            header.append(f"{name} [{CSV_UNITS[name]}]")
        else:
            raise ValueError(f"CSV column {name!r} has no unit; add it to CSV_UNITS")
    return header


def write_csv(path: Path, columns: Mapping[str, ArrayLike]) -> None:
    """Write equal-length columns under a header ``name [unit]`` (:func:`csv_header`).

    Write into a :func:`staged_folder` or a :func:`staged_file`: they make the result appear
    complete or not at all.
    """
    header = csv_header(columns)
    with open(path, "w", newline="", encoding="utf-8") as stream:
        writer = csv.writer(stream)
        writer.writerow(header)
        writer.writerows(zip(*(np.asarray(c) for c in columns.values()), strict=True))
