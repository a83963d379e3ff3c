"""Running a sweep on dask.distributed: one task per case, each result on disk as it arrives.

The result folder::

    DIR/.shtaerman-sweep.json  the marker that makes DIR a sweep folder (--resume, --force)
    DIR/sweep.toml          the sweep file, copied (``--resume`` checks its fixed parameters)
    DIR/cases/<index>.json  one record per finished case (its inputs, outputs and a digest),
                            written atomically as it completes
    DIR/cases/unused/       records of cases a resumed grid dropped (reused if they return)
    DIR/cases.csv           one row per case, sorted by index (written at the end)
    DIR/results.json        spec, cases, summary, timings (written at the end)
    DIR/figures/*.png       per output: curves over a 1-axis sweep, heat maps over 2 axes

Nothing is lost: a case that raises is recorded with its error (one line) and the others go on;
a case beyond a validity limit of the model (:attr:`~shtaerman.sweep.spec.SweepSpec.refused`)
is recorded "refused" with its reason, not run;
a worker that dies mid-case has its case rerun by dask on another worker (the scheduler
reschedules tasks of lost workers); an interrupted sweep (SIGINT, SIGTERM) keeps every finished
case, and ``resume=True`` computes only the cases without a valid record, matched by inputs.
"""

from __future__ import annotations

import contextlib
import csv
import hashlib
import io
import json
import logging
import os
import queue
import re
import shutil
import signal
import socket
import stat
import sys
import tempfile
import threading
import time
import tomllib
import uuid
import warnings
from collections.abc import Callable, Iterator, Mapping
from dataclasses import dataclass, replace
from pathlib import Path
from typing import Any

from ..output.files import (
    SWEEP_MARKER,
    check_folder_place,
    file_mode,
    folder_lock,
    incomplete_path,
    json_safe,
    probe_removable,
    probe_writable,
)
from ..plots.formats import check_figure_format
from ..problem import worded
from ..signals import deferred
from ..validation import InputError, LimitError
from .guard import SCRATCH_ENV, check_not_bootstrapping, raise_if_unguarded
from .kinds import CaseResult, unit_suffix
from .spec import Case, SweepSpec

__all__ = [
    "SweepInterrupted",
    "SweepOutcome",
    "dask_client",
    "default_workers",
    "execute_case",
    "is_sweep_folder",
    "read_records",
    "run_sweep",
    "worker_count",
]

SPEC_FILE = "sweep.toml"
CASES_DIR = "cases"
UNUSED_DIR = "unused"
"""Inside ``cases``: the records of cases a resumed grid no longer holds (reused if it does)."""
MARKER_FILE = SWEEP_MARKER
"""What makes a folder a sweep folder (``--resume`` and ``--force`` touch no other)."""
MARKER_FORMAT = "shtaerman-sweep-1"
RECORD_NAME = re.compile(r"(0|[1-9][0-9]*)\.json|[0-9a-f]{16}\.json")
MAX_RECORD_BYTES = 1 << 20
"""Largest case record read on ``--resume`` (a record is about 1 kB)."""
BLAS_ENV = {"OMP_NUM_THREADS": "1", "OPENBLAS_NUM_THREADS": "1", "MKL_NUM_THREADS": "1"}
"""Worker environment of the local cluster: one BLAS thread per single-threaded worker (read
as a spawned worker starts; :func:`execute_case` caps BLAS again, for forked workers)."""
START_METHOD = "fork" if sys.platform == "linux" else "spawn"
"""How the local cluster starts its worker processes: a fork inherits this process's imports
and its workers get their signal handlers from the preload (``_worker.py``); nothing may be
drawn before they start (VTK's OpenGL state). Spawn elsewhere: macOS system libraries are not
safe in a forked child. Measurements: benchmarks/FEM_NOTES.md, "Sweep cluster"."""
QUIET_CLUSTER = {
    "distributed.worker.profile.enabled": False,
    "distributed.admin.system-monitor.interval": "60s",
    "distributed.admin.tick.interval": "1s",
    "distributed.worker.memory.monitor-interval": "500ms",
}
"""Dask's own monitoring, off or slowed in the local cluster (it feeds a dashboard and log
warnings this tool has neither; a worker past its memory limit is still stopped; what it cost:
benchmarks/FEM_NOTES.md, "Sweep cluster")."""
NANNY_POLL = 0.005
"""s: how often a nanny of the local cluster looks whether its worker has started, while the
cluster starts (:func:`_nanny_poll`; against dask's 0.05 s: benchmarks/FEM_NOTES.md, "Sweep
cluster")."""
SIGNAL_LATENCY = 0.1
"""Longest wait, s, between SIGINT/SIGTERM and the sweep stopping to save and shut down."""
PENDING_PER_WORKER = 4
"""Tasks submitted to the cluster ahead of their results, per worker thread: the grid goes to
dask in batches, so its first case is saved within seconds however large the grid (a map of
1e5 tasks at once saved none in 200 s: benchmarks/FEM_NOTES.md, "left66")."""
CONNECT_TIMEOUT = "10s"
"""How long to try reaching an existing scheduler (``scheduler=``)."""


class SweepInterrupted(Exception):  # noqa: N818 (a signal, like KeyboardInterrupt)
    """SIGINT or SIGTERM during a sweep; finished cases are on disk: ``saved`` of the ``total``
    cases to compute (as a resume counts them: "from an earlier run"), beside the ``refused``
    ones (recorded, never computed; judged again by the resume)."""

    def __init__(self, signum: int, saved: int = 0, total: int = 0, refused: int = 0) -> None:
        super().__init__(signal.Signals(signum).name)
        self.signum, self.saved, self.total, self.refused = signum, saved, total, refused
        self.restored = False
        """True when a --force run was stopped and the sweep it replaced was put back."""
        self.kept_in: Path | None = None
        """Where such a run's saved cases are (None: it saved none)."""


@dataclass(frozen=True)
class SweepOutcome:
    """What a call of :func:`run_sweep` did.

    Attributes
    ----------
    out : Path
        The result folder.
    total, succeeded, failed : int
        Cases in the grid, recorded with outputs, recorded with an error.
    lost : int
        Cases without a record because the cluster could not run them (a worker died more
        often than dask allows, the scheduler went away); rerun them with ``resume=True``.
    computed, reused : int
        Cases computed by this call, and records kept from an earlier call (``resume``).
    seconds : float
        Wall time of this call, s.
    workers : int
        Worker threads of the cluster used.
    lost_reason : str, optional
        Why the first lost case could not run.
    warned : int
        Cases whose computation issued warnings (listed in ``results.json``).
    figures : tuple of Path
        The figures this call drew (none over 3 or more axes, nor when not asked or failed).
    refused : int
        Cases recorded "refused": beyond a validity limit of the model, at the file's load
        (not run: neither computed nor reused) or met while the case ran (computed).
    """

    out: Path
    total: int
    succeeded: int
    failed: int
    lost: int
    computed: int
    reused: int
    seconds: float
    workers: int
    lost_reason: str | None = None
    warned: int = 0
    figures: tuple[Path, ...] = ()
    refused: int = 0

    @property
    def exit_code(self) -> int:
        """0 when every case succeeded or was refused (outside the model's validity, its
        reason in its row), 1 when any failed or is missing, 2 when every case was refused
        (as a sweep refused whole at its load is)."""
        if self.total and self.refused == self.total:
            return 2
        return 0 if self.succeeded + self.refused == self.total else 1


def default_workers() -> int:
    """Cores this process may use (the default number of local workers)."""
    try:
        return max(1, len(os.sched_getaffinity(0)))
    except AttributeError:  # not on Linux
        return max(1, os.cpu_count() or 1)


WORKER_MEMORY = {"impact": 250e6, "contact": 400e6, "dynamic": 400e6}
"""Resident memory of a local worker process running cases of a sweep kind, bytes (dask and
the kind's modules, about 230 MB, and the case's own arrays); other kinds: the largest."""


def available_memory() -> float:
    """Memory that new processes may use on this machine, bytes (psutil's available)."""
    import psutil

    return float(psutil.virtual_memory().available)


def worker_count(asked: int | None, tasks: int, memory: float, what: str = "cases") -> int:
    """Local worker processes to start for ``tasks`` tasks (``what``: their name, plural):
    ``asked`` (default: the cores), at most one per task and at most what the available memory
    holds at ``memory`` bytes per worker (at least one). Prints one line on stderr when that is
    fewer than asked, or when the memory caps the default.
    """
    wanted = asked or default_workers()
    available = available_memory()
    fits = max(1, int(available // memory))
    count = max(1, min(wanted, tasks, fits))
    if count < wanted and (count < tasks or asked is not None):
        if count == fits and fits < min(wanted, tasks):
            why = (
                f"the available memory ({available / 1e9:.1f} GB) holds {fits} of about "
                f"{memory / 1e6:.0f} MB"
            )
        else:
            why = f"{tasks} {what} to compute"
        print(f"shtaerman: starting {count} of {wanted} workers: {why}", file=sys.stderr)
    return count


# --- on the worker ----------------------------------------------------------------------------


def _one_line(error: BaseException) -> str:
    text = " ".join(str(error).split())
    return f"{type(error).__name__}: {text}" if text else type(error).__name__


def _scalar(name: str, value: Any) -> float | int:
    if hasattr(value, "item") and not isinstance(value, str):
        value = value.item()
    if isinstance(value, bool) or not isinstance(value, int | float):
        raise TypeError(f"output {name!r} is not a number: {value!r}")
    return value


def _worker_address() -> str:
    try:
        from distributed import get_worker

        return get_worker().address
    except (ImportError, ValueError):
        return "in-process"


def execute_case(case: Callable[[dict], CaseResult], index: int, params: dict) -> dict:
    """Run one case; never raises for the case's own errors (they are recorded).

    BLAS is capped to one thread (threadpoolctl) whatever the worker's environment, so an
    existing cluster with several threads per worker does not oversubscribe its cores.

    This is the one place a case's checks become its status, for every kind: the
    :class:`~shtaerman.sweep.kinds.CaseResult` a case returns is "ok" without failures, else
    "failed" with its reasons and its outputs kept; a case that returns no ``CaseResult`` (no
    verdict) or raises is "failed" without outputs, but "refused" (its reason in the file's
    words) where it meets a validity limit (:class:`~shtaerman.validation.LimitError`) that
    the file's load could not foresee. A case whose ladder lost a level is "ok"
    with its ``estimate_missing`` (its finest level that passed; its error outputs NaN).

    Returns
    -------
    dict
        ``index``, ``status`` ("ok", "failed" or "refused"; a refusal at the file's load is
        the client's, :func:`refused_records`), ``outputs``, ``error`` (one line or None),
        ``estimate_missing`` (one line or None), ``warnings``, ``seconds`` (wall, s),
        ``cpu_seconds`` (CPU time of the thread that ran the case, s), ``worker``, ``host``,
        ``pid``.
    """
    from threadpoolctl import threadpool_limits

    start, cpu = time.perf_counter(), time.thread_time()
    outputs: dict[str, float | int] = {}
    error = missing = None
    status = "ok"
    with threadpool_limits(limits=1), warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        try:
            result = case(dict(params))
            if not isinstance(result, CaseResult):
                raise TypeError(
                    f"the kind's case returned {type(result).__name__}, not a CaseResult "
                    "(outputs and the failures of its checks)"
                )
            outputs = {str(name): _scalar(name, value) for name, value in result.outputs.items()}
            missing = " ".join(result.estimate_missing.split()) or None
            if result.failures:  # it ran, but its own checks fail: kept, as failed
                error = "check failed: " + " ".join("; ".join(result.failures).split())
                status = "failed"
        except LimitError as exc:  # a validity limit met in the run, not at the file's load
            outputs, error, status = {}, worded(" ".join(str(exc).split()), "file"), "refused"
        except Exception as exc:
            outputs, error, status = {}, _one_line(exc), "failed"
    return {
        "index": index,
        "status": status,
        "outputs": outputs,
        "error": error,
        "estimate_missing": missing,
        "warnings": sorted({worded(str(w.message), "file") for w in caught}),  # its keys
        "seconds": time.perf_counter() - start,
        "cpu_seconds": time.thread_time() - cpu,
        "worker": _worker_address(),
        "host": socket.gethostname(),
        "pid": os.getpid(),
    }


# --- the result folder --------------------------------------------------------------------------


def _atomic_write(path: Path, text: str) -> None:
    """Write ``text`` to ``path`` through a temporary file in the same folder + os.replace
    (a symbolic link at ``path`` is replaced, never followed)."""
    handle, temporary = tempfile.mkstemp(dir=path.parent, prefix=f".{path.name}.", suffix=".tmp")
    try:
        os.fchmod(handle, file_mode())  # mkstemp makes 0600; results are shared like any file
        with os.fdopen(handle, "w", newline="") as stream:
            stream.write(text)
        os.replace(temporary, path)
    except BaseException as error:
        Path(temporary).unlink(missing_ok=True)
        if isinstance(error, OSError) and error.filename is None and error.errno is not None:
            raise OSError(error.errno, error.strerror, str(path)) from error  # a full disk
        raise


def _read_regular(path: Path, limit: int = MAX_RECORD_BYTES) -> str | None:
    """The UTF-8 text of ``path`` if it is a regular file (not a link, FIFO or device) of at
    most ``limit`` bytes; None otherwise."""
    try:
        handle = os.open(path, os.O_RDONLY | os.O_NOFOLLOW | os.O_NONBLOCK)
    except OSError:
        return None
    with os.fdopen(handle, "rb") as stream:
        info = os.fstat(handle)
        if not stat.S_ISREG(info.st_mode) or info.st_size > limit:
            return None
        try:
            return stream.read(limit + 1).decode("utf-8")
        except (OSError, UnicodeDecodeError):
            return None


def _digest(record: Mapping[str, Any]) -> str:
    body = {key: value for key, value in record.items() if key != "digest"}
    return hashlib.sha256(json.dumps(body, sort_keys=True).encode()).hexdigest()


def _sealed(record: Mapping[str, Any]) -> dict:
    """``record`` as strict JSON data with its ``digest`` (a hand edit or damage shows)."""
    safe = json_safe({key: value for key, value in record.items() if key != "digest"})
    return {**safe, "digest": _digest(safe)}


def _write_record(out: Path, record: dict) -> None:
    _atomic_write(out / CASES_DIR / f"{record['index']}.json", json.dumps(record))


def _load_record(path: Path) -> dict | None:
    """The record in ``path`` if it is one this tool wrote, unchanged; None otherwise."""
    text = _read_regular(path)
    if text is None:
        return None
    try:
        record = json.loads(text)
    except (ValueError, RecursionError):
        return None
    valid = (
        isinstance(record, dict)
        and record.get("digest") == _digest(record)
        and isinstance(record.get("index"), int)
        and record.get("status") in {"ok", "failed", "refused"}
        and isinstance(record.get("inputs"), dict)
        and isinstance(record.get("outputs"), dict)
        and isinstance(record.get("seconds"), int | float)
    )
    return record if valid else None


def _case_key(params: Mapping[str, Any]) -> str:
    return json.dumps(json_safe(dict(params)), sort_keys=True)


def _record_files(out: Path) -> list[Path]:
    """The record files of ``out/cases`` and of its ``unused`` folder (kept records of cases
    no longer in the grid); a symbolic link there is refused."""
    folders = [out / CASES_DIR, out / CASES_DIR / UNUSED_DIR]
    files = []
    for folder in folders:
        if folder.is_symlink() or (os.path.lexists(folder) and not folder.is_dir()):
            raise InputError(
                f"resume: {str(folder)!r} is not a folder (a symbolic link?)", "resume"
            )
        if folder.is_dir():
            files += [p for p in sorted(folder.iterdir()) if RECORD_NAME.fullmatch(p.name)]
    return files


def read_records(out: str | Path, cases: list[Case]) -> dict[int, dict]:
    """The saved records of ``cases`` in ``out``, matched by their inputs (so a grid whose
    axes were reordered or extended keeps them), each relabelled with its case's index and
    axis values. A file that holds no valid record (edited, damaged or not a file) is said in a
    warning, and its case is computed again."""
    wanted = {_case_key(case.params): case for case in cases}
    records: dict[int, dict] = {}
    for path in _record_files(Path(out)):
        record = _load_record(path)
        if record is None:
            warnings.warn(
                f"{path} is not a case record this tool wrote (edited or damaged); its case is "
                "computed again",
                stacklevel=3,
            )
            continue
        case = wanted.get(_case_key(record["inputs"]))
        if case is None or case.index in records:
            continue
        record = {**record, "index": case.index, "axis_values": case.axis_values}
        records[case.index] = _sealed(record)
    return records


def _settle_records(out: Path, records: Mapping[int, dict]) -> None:
    """Give every kept record its current file name ``cases/<index>.json``; valid records of
    cases no longer in the grid move to ``cases/unused``. Each step keeps every record in at
    least one file, so an interruption anywhere loses none."""
    cases, unused = out / CASES_DIR, out / CASES_DIR / UNUSED_DIR
    top = {p.name: _load_record(p) for p in cases.iterdir() if RECORD_NAME.fullmatch(p.name)}
    current = {f"{index}.json": record for index, record in records.items()}
    for name, record in top.items():
        if record is not None and current.get(name) != record:
            unused.mkdir(exist_ok=True)
            _atomic_write(unused / f"{record['digest'][:16]}.json", json.dumps(record))
    for name, record in current.items():
        if top.get(name) != record:
            _atomic_write(cases / name, json.dumps(record))
    for name, record in top.items():
        if name not in current and record is not None:
            (cases / name).unlink()
    if unused.is_dir():
        keys = {_case_key(record["inputs"]) for record in records.values()}
        for path in list(unused.iterdir()):
            record = _load_record(path)
            if record is not None and _case_key(record["inputs"]) in keys:
                path.unlink()


def _first_difference(old: Any, new: Any, prefix: str = "") -> str | None:
    if isinstance(old, dict) and isinstance(new, dict):
        for key in sorted(set(old) | set(new)):
            where = f"{prefix}.{key}" if prefix else str(key)
            if key not in old or key not in new:
                return where
            found = _first_difference(old[key], new[key], where)
            if found:
                return found
        return None
    return None if old == new else (prefix or "(top level)")


def is_sweep_folder(out: Path) -> bool:
    """True when ``out`` holds the marker a sweep writes (a regular file of that format)."""
    text = _read_regular(out / MARKER_FILE, 4096)
    try:
        return text is not None and json.loads(text).get("format") == MARKER_FORMAT
    except (ValueError, AttributeError):
        return False


def _check_same_sweep(spec: SweepSpec, out: Path) -> None:
    """Refuse to resume ``out`` with a sweep that differs in more than its axis values."""
    text = _read_regular(out / SPEC_FILE, 1 << 20)
    try:
        old = tomllib.loads(text) if text is not None else None
    except (tomllib.TOMLDecodeError, RecursionError):
        old = None
    key = "the file" if old is None else None
    if old is not None:
        fixed = {k: v for k, v in old.items() if k != "axes"}
        key = _first_difference(fixed, {k: v for k, v in spec.data.items() if k != "axes"})
        axes = old.get("axes")
        if key is None and (not isinstance(axes, dict) or set(axes) != set(spec.axes)):
            key = "axes (their names)"
    if key is not None:
        raise InputError(
            f"resume: {str(out)!r} holds a different sweep ({key} differs from {spec.path}); a "
            "resume may add or change axis values only: use another --out, or --force to start "
            "again",
            "resume",
        )


_SWEEP_ENTRIES = {MARKER_FILE, SPEC_FILE, CASES_DIR, "cases.csv", "results.json", "figures"}
"""The top-level entries of a sweep folder, all written by :func:`run_sweep`."""


def _foreign_entries(out: Path) -> list[str]:
    """Paths (relative to ``out``) of what a sweep folder holds that no sweep wrote."""
    found = sorted(name for name in os.listdir(out) if name not in _SWEEP_ENTRIES)
    cases = out / CASES_DIR
    for folder in (cases, cases / UNUSED_DIR):
        if folder.is_dir():
            where = folder.relative_to(out).as_posix()
            ours = {UNUSED_DIR} if folder == cases else set()
            names = sorted(os.listdir(folder))
            found += [f"{where}/{n}" for n in names if not (RECORD_NAME.fullmatch(n) or n in ours)]
    figures = out / "figures"
    if figures.is_dir():
        names = sorted(os.listdir(figures))
        found += [f"figures/{n}" for n in names if not n.endswith((".png", ".svg", ".pdf"))]
    return found


def _check_folder(
    spec: SweepSpec, out: Path, backup: Path, *, resume: bool, force: bool
) -> Callable[[], None]:
    """Check what the result folder holds (its place: :func:`check_folder_place`), touching
    nothing; returns what makes it ready (called once the cluster is up, so that an
    unreachable scheduler leaves no folder behind)."""
    if resume and out.is_dir():  # completed in place
        probe_writable("out", out, f".{out.name}.probe")
    full = out.is_dir() and any(out.iterdir())
    if full and not is_sweep_folder(out):  # resume or force would refuse it: not suggested
        flag = "resume" if resume else "force" if force else None  # at most one (above)
        acts = f", and {flag}=True acts on sweep folders only" if flag else ""
        raise InputError(
            f"out: folder {str(out)!r} is not a sweep folder (no {MARKER_FILE} written by "
            f"shtaerman sweep){acts}: name a new folder with out=...",
            "out",
        )
    if full and resume:
        _check_same_sweep(spec, out)
        return lambda: _atomic_write(out / SPEC_FILE, spec.text)
    if full and not force:
        raise InputError(
            f"out: folder {str(out)!r} exists; use resume=True to complete it or force=True to "
            "replace it",
            "out",
        )
    if full:  # moved aside until the new sweep completes: a read-only folder cannot be
        probe_writable("out", out, f".{out.name}.probe")
        probe_removable("out", out)  # then removed: what cannot be would stay in the lock
    foreign = _foreign_entries(out) if full else []
    if foreign:
        raise InputError(
            f"out: folder {str(out)!r} holds {foreign[0]!r}, not written by shtaerman sweep; "
            "--force replaces only what this tool wrote: move it or name a new folder with --out",
            "out",
        )

    def create() -> None:
        if full:  # kept until the new sweep completes (see _replaced)
            os.replace(out, backup)
        made = not out.is_dir()
        out.mkdir(exist_ok=True)
        try:
            (out / CASES_DIR).mkdir()
            _atomic_write(out / SPEC_FILE, spec.text)
            marker = {"format": MARKER_FORMAT, "name": spec.name, "kind": spec.kind}
            _atomic_write(out / MARKER_FILE, json.dumps(marker))
        except BaseException:  # a full disk: no half-made folder that refuses the same run
            with deferred():
                shutil.rmtree(out / CASES_DIR, ignore_errors=True)
                (out / SPEC_FILE).unlink(missing_ok=True)
                if made:
                    out.rmdir()
            raise

    return create


@contextlib.contextmanager
def _replaced(out: Path, backup: Path, saved_new: Callable[[], bool]) -> Iterator[None]:
    """Drop the sweep ``--force`` replaces (``backup``) when the block ends normally. If it
    raises, put it back whole; the cases the new sweep saved go beside it
    (:func:`shtaerman.output.files.incomplete_path`, the error's ``kept_in``), for
    ``--resume`` there."""
    try:
        yield
    except BaseException as error:
        if backup.is_dir():
            with deferred():  # a second Ctrl-C must not break the put-back
                kept = incomplete_path(out) if saved_new() else None
                if kept is None:
                    shutil.rmtree(out, ignore_errors=True)
                else:
                    os.replace(out, kept)
                os.replace(backup, out)
            with contextlib.suppress(AttributeError):  # an OSError's line names it too
                error.kept_in = kept
            if isinstance(error, SweepInterrupted):
                error.restored = True
        raise
    if backup.is_dir():
        shutil.rmtree(backup)


def _unlink_links(folder: Path) -> None:
    """Remove symbolic links at ``folder`` and in it, so that what is drawn there stays there."""
    if folder.is_symlink() or (os.path.lexists(folder) and not folder.is_dir()):
        folder.unlink()
    if folder.is_dir():
        for path in folder.iterdir():
            if path.is_symlink():
                path.unlink()


# --- the cluster ------------------------------------------------------------------------------


QUIET_LOGGERS = ("distributed", "tornado", "asyncio")
"""Loggers silenced during a run: what they would say (worker restarts, a task given up after
its worker died, unresponsive loops, connections closed at shutdown) reaches the user as this
tool's own one-line messages, or not at all."""


@contextlib.contextmanager
def _quiet_dask() -> Iterator[None]:
    """Dask's log records (up to ERROR and CRITICAL) and warnings hidden for the run."""
    loggers = [logging.getLogger(name) for name in QUIET_LOGGERS]
    levels = [logger.level for logger in loggers]
    for logger in loggers:
        logger.setLevel(logging.CRITICAL + 1)
    try:
        with warnings.catch_warnings():
            warnings.filterwarnings("ignore", module=r"distributed(\.|$)")
            yield
    finally:
        for logger, level in zip(loggers, levels, strict=True):
            logger.setLevel(level)


def _connect(scheduler: str, stop: _StopFlag | None) -> Any:
    """A client of the existing ``scheduler``, made in a helper thread: a peer that accepts
    the connection and never answers cannot hold this process past the connect timeout, and
    SIGINT/SIGTERM (``stop``) end the wait at once."""
    from dask.utils import parse_timedelta
    from distributed import Client

    made: dict[str, Any] = {}

    def connect() -> None:
        try:
            made["client"] = Client(scheduler, timeout=CONNECT_TIMEOUT)
        except Exception as error:
            made["error"] = error

    thread = threading.Thread(target=connect, name="shtaerman-connect", daemon=True)
    thread.start()
    seconds = parse_timedelta(CONNECT_TIMEOUT)
    deadline = time.monotonic() + seconds + 5.0  # dask's own timeout first, when it works
    while thread.is_alive() and time.monotonic() < deadline:
        thread.join(0.05)
        if stop is not None:
            stop.check()
    error = made.get("error")
    if thread.is_alive():
        error = TimeoutError(f"no answer within {seconds:g} s")
    if error is not None:  # refused, malformed, not a dask scheduler (its answer undecodable)
        raise InputError(f"scheduler: cannot connect to {scheduler!r} ({_one_line(error)})")
    return made["client"]


@contextlib.contextmanager
def _client(
    workers: int | None, scheduler: str | None, stop: _StopFlag | None = None
) -> Iterator[Any]:
    import dask
    from distributed import Client

    if scheduler is not None:
        client = _connect(scheduler, stop)
        try:
            yield client
        finally:
            _close(client)
        return
    # (dask's MALLOC_TRIM_THRESHOLD_=65536 there is overridden by the preload: _worker.py)
    environ = dict(dask.config.get("distributed.nanny.pre-spawn-environ", {}))
    # the workers log only what is critical: a task's exception reaches the client with the
    # future anyway, and a worker busy in the FEM when the run ends (an input refused, Ctrl-C)
    # would print a "heartbeat" traceback at shutdown (a spawned worker reads this; a forked
    # one imported dask before it was set, so the preload quiets it: _worker.py)
    environ["DASK_LOGGING__DISTRIBUTED"] = "critical"
    scratch = tempfile.mkdtemp(prefix="shtaerman-dask-")  # private (0700), never a planted link
    environ[SCRATCH_ENV] = scratch  # where a worker that re-runs an unguarded script says so
    saved = dict(os.environ)  # dask's nanny writes into this process's
    try:
        settings = {
            "distributed.nanny.pre-spawn-environ": environ,
            "distributed.worker.multiprocessing-method": START_METHOD,
            "temporary-directory": scratch,
            **QUIET_CLUSTER,
        }
        # the workers inherit it, whatever an earlier run left here (a stale scratch folder
        # made the unguarded-script guard look in a deleted folder); restored below
        os.environ[SCRATCH_ENV] = scratch
        with dask.config.set(settings):
            cluster = _local_cluster(workers, scratch)
        try:
            client = Client(cluster)
            try:
                yield client
            finally:
                _close(client)
        finally:
            with deferred():  # a second Ctrl-C must not break the shutdown
                cluster.close()
    finally:
        shutil.rmtree(scratch, ignore_errors=True)
        _restore_environment(saved)


def _close(client: Any) -> None:
    """Close ``client``, whose run has ended: a second Ctrl-C must not break the shutdown, nor
    dask's TimeoutError of a close that took over its 60 s replace the run's outcome (it
    did, after SIGTERM with 1e5 cases pending: "timed out after 60 s.", said as a failed
    write); what the cases need is saved, and the cluster is closed after it."""
    with deferred(), contextlib.suppress(TimeoutError):
        client.close()


def _restore_environment(saved: dict[str, str]) -> None:
    """This process's environment as ``saved`` (the whole of it): a key added since goes
    (dask's nanny adds its own), a changed one gets its value back."""
    for key in set(os.environ) - set(saved):
        os.environ.pop(key, None)
    for key, value in saved.items():
        if os.environ.get(key) != value:
            os.environ[key] = value


@contextlib.contextmanager
def _nanny_poll() -> Iterator[None]:
    """:data:`NANNY_POLL` as dask's start poll (``WorkerProcess._init_msg_interval``, private:
    dask has no setting for it) while the block runs, dask's own again after it, so that a
    cluster the user starts in this process is left as dask made it."""
    from distributed.nanny import WorkerProcess

    dask_own = WorkerProcess.__dict__["_init_msg_interval"]
    WorkerProcess._init_msg_interval = NANNY_POLL
    try:
        yield
    finally:
        WorkerProcess._init_msg_interval = dask_own


def _local_cluster(workers: int | None, scratch: str) -> Any:
    from distributed import LocalCluster

    try:
        with _nanny_poll():
            return LocalCluster(
                n_workers=workers or default_workers(),
                local_directory=scratch,
                threads_per_worker=1,
                processes=True,
                dashboard_address=None,
                # no dashboard; the scheduler's HTTP endpoint on a free port, not 8787 (shared)
                scheduler_kwargs={"dashboard": False, "dashboard_address": ":0"},
                silence_logs=logging.ERROR,
                env=BLAS_ENV,
                preload=["shtaerman.sweep._worker"],  # workers leave Ctrl-C to this process
            )
    except Exception:
        raise_if_unguarded(scratch)
        raise


@contextlib.contextmanager
def dask_client(workers: int | None = None, scheduler: str | None = None) -> Iterator[Any]:
    """A quiet dask client: a local cluster of ``workers`` single-threaded processes (default:
    the cores; BLAS capped to one thread each), or the existing ``scheduler``."""
    with _quiet_dask(), _client(workers, scheduler) as client:
        yield client


class _StopFlag:
    """SIGINT/SIGTERM set a flag (main thread only); the loop checks it between results.
    Inside :meth:`raising` (the summary and figures, once every case is saved) a signal
    raises at once instead."""

    def __init__(self) -> None:
        self.signum: int | None = None
        self._previous: dict[int, Any] = {}
        self._raise = False

    def __enter__(self) -> _StopFlag:
        if threading.current_thread() is threading.main_thread():
            for s in (signal.SIGINT, signal.SIGTERM):
                self._previous[s] = signal.signal(s, self._handler)
        return self

    def _handler(self, signum: int, frame: object) -> None:
        self.signum = self.signum or signum
        if self._raise:
            self._raise = False  # once: a second signal must not break the clean-up
            raise SweepInterrupted(signum)

    def check(self) -> None:
        if self.signum is not None:
            raise SweepInterrupted(self.signum)

    @contextlib.contextmanager
    def raising(self) -> Iterator[None]:
        """A signal raises :class:`SweepInterrupted` where it lands (one already caught, on
        entry; one swallowed on the way, e.g. by a callback, on exit)."""
        self.check()
        self._raise = True
        try:
            yield
        finally:
            self._raise = False
        self.check()

    def __exit__(self, *exc: object) -> None:
        for s, old in self._previous.items():
            signal.signal(s, old)


def _progress(total: int, initial: int, name: str, show: bool | None):
    from tqdm import tqdm

    if show is None:
        ci = os.environ.get("CI", "").strip().lower() in {"1", "true", "yes"}
        show = sys.stderr.isatty() and not ci
    return tqdm(
        total=total, initial=initial, desc=name, unit="case", file=sys.stderr, disable=not show
    )


def run_sweep(
    spec: SweepSpec,
    out: str | Path,
    *,
    workers: int | None = None,
    scheduler: str | None = None,
    resume: bool = False,
    force: bool = False,
    retries: int = 2,
    progress: bool | None = None,
    figures: bool = True,
    figure_format: str = "png",
) -> SweepOutcome:
    """Run every case of ``spec`` on a dask cluster and write the result folder ``out``.

    Parameters
    ----------
    spec : SweepSpec
        From :func:`shtaerman.sweep.load_sweep` (every case's inputs already checked).
    out : path
        Result folder, created once the cluster is up. An existing one is refused unless
        ``resume`` (complete it: saved records are reused by their inputs, so the sweep may
        add or change axis values but not its fixed parameters) or ``force`` (replace it;
        only a folder a sweep wrote is ever removed). A completed ``resume`` of the
        ``NAME.incomplete-PID`` an interrupted ``force`` left replaces ``NAME``, and a completed
        ``resume`` or ``force`` removes the ``out.replaced-PID`` a killed ``force`` left.
    workers : int, optional
        Single-threaded local worker processes (default: the usable cores; at most the cases).
    scheduler : str, optional
        Address of an existing cluster's scheduler, e.g. ``"tcp://host:8786"``.
    retries : int
        Reruns dask grants a task that raised outside the case (a case's own exception is
        recorded, never retried).
    progress : bool, optional
        Progress bar on stderr; default: when stderr is a terminal and ``CI`` is not set.
    figures : bool
        Draw ``out/figures``.
    figure_format : {"png", "svg", "pdf"}
        "svg" or "pdf" also writes each figure in that format beside its PNG.

    Raises
    ------
    InputError
        Bad folder, different sweep on resume, unreachable scheduler (nothing computed).
    SweepInterrupted
        On SIGINT/SIGTERM in the main thread, after the cluster is shut down; finished cases
        are on disk.
    """
    check_not_bootstrapping()  # a worker of this very sweep, running an unguarded script
    if workers is not None and scheduler is not None:
        raise InputError(
            "workers: applies to the local cluster only, not to --scheduler", "workers"
        )
    if workers is not None and workers < 1:
        raise InputError(f"workers must be an integer >= 1, got {workers!r}")
    check_figure_format(figure_format)
    if resume and force:
        raise InputError(
            "resume=True and force=True exclude each other: resume=True keeps the folder"
        )
    start = time.perf_counter()
    out = check_folder_place(Path(out), "out", resume=resume)
    cases = spec.cases()
    with folder_lock(out, "out") as lock:
        backup = lock / "replaced"
        ready = _check_folder(spec, out, backup, resume=resume, force=force)
        saved = read_records(out, cases) if resume and is_sweep_folder(out) else None
        # a refused case is judged again at each load: recorded anew, or run if now within
        # (its old record kept in its file until the run's replaces it)
        records = {i: r for i, r in (saved or {}).items() if r["status"] != "refused"}
        refused = refused_records(spec, cases, records)
        if saved is None:
            ready = _writing(ready, out, refused)
        else:
            ready = _settled(ready, out, {**saved, **refused})
        run = _Run(spec, out, cases, {**records, **refused}, len(records), start, len(refused))
        with _replaced(out, backup, run.saved_new), _StopFlag() as stop:
            outcome = run.execute(
                ready, workers, scheduler, retries, progress, figures and figure_format, stop
            )
        if outcome.lost == 0 and (resume or force):  # complete: a replacement is finished
            _drop_replaced(out)
            outcome = _finish_force(outcome) if resume else outcome
        return outcome


INCOMPLETE_NAME = re.compile(r"(.+)\.incomplete-[0-9]+(?:-[0-9]+)?")
"""Where an interrupted ``--force`` run keeps its saved cases (output.files.incomplete_path)."""


def _finish_force(outcome: SweepOutcome) -> SweepOutcome:
    """A completed ``NAME.incomplete-PID`` (the saved part of an interrupted ``--force`` run,
    completed there by ``--resume``) replaces the sweep folder ``NAME`` beside it, as that
    run would have; one line on stderr. Returns ``outcome`` with the folder's new place."""
    out = outcome.out
    match = INCOMPLETE_NAME.fullmatch(out.name)
    target = out.with_name(match.group(1)) if match else out
    if target == out or target.is_symlink() or not is_sweep_folder(target):
        return outcome
    if _foreign_entries(target):  # --force replaces only what a sweep wrote
        return outcome
    try:
        with folder_lock(target, "out") as lock, deferred():
            os.replace(target, lock / "replaced")  # removed with the lock's folder
            os.replace(out, target)
    except InputError as busy:  # another run writes it: this one stays complete where it is
        print(f"shtaerman: {out} is complete and stays there ({busy})", file=sys.stderr)
        return outcome
    print(f"shtaerman: the --force run completed in {out} now replaces {target}", file=sys.stderr)
    figures = tuple(target / path.relative_to(out) for path in outcome.figures)
    return replace(outcome, out=target, figures=figures)


def _drop_replaced(out: Path) -> None:
    """Remove the sweeps a killed ``--force`` run was replacing with ``out``, now complete: the
    next run on ``out`` kept each as ``NAME.replaced-PID`` (:mod:`shtaerman.output.files`),
    and ``--resume`` completed the replacement. One line on stderr for each."""
    pattern = re.compile(re.escape(f"{out.name}.replaced-") + r"[0-9]+")
    for old in sorted(out.parent.iterdir()):
        if pattern.fullmatch(old.name) and not old.is_symlink() and is_sweep_folder(old):
            if not _foreign_entries(old):  # only what a sweep wrote, as --force removes
                shutil.rmtree(old)
                print(
                    f"shtaerman: removed {old}, the sweep a killed --force run was replacing "
                    f"with {out}, now complete",
                    file=sys.stderr,
                )


def refused_records(spec: SweepSpec, cases: list[Case], saved: Mapping[int, dict]) -> dict:
    """The records of the cases ``spec`` refuses (beyond a validity limit of the model),
    made in the client without running them: status "refused", the reason in ``error``, no
    outputs; but for those ``saved`` holds computed (kept, as any case's saved record)."""
    nothing = {"outputs": {}, "estimate_missing": None, "warnings": [], "seconds": 0.0}
    nobody = {"cpu_seconds": 0.0, "worker": None, "host": None, "pid": None}
    return {
        case.index: _case_record(
            case,
            {"index": case.index, "status": "refused", "error": spec.refused[case.index]}
            | nothing
            | nobody,
        )
        for case in cases
        if case.index in spec.refused and case.index not in saved
    }


def _writing(ready: Callable[[], None], out: Path, records: dict) -> Callable[[], None]:
    """``ready``, then ``records`` (the refused cases') written in the ready folder."""

    def write() -> None:
        ready()
        for record in records.values():
            _write_record(out, record)

    return write


def _settled(ready: Callable[[], None], out: Path, records: dict) -> Callable[[], None]:
    def settle() -> None:
        (out / CASES_DIR).mkdir(exist_ok=True)
        _settle_records(out, records)
        ready()

    return settle


class _Run:
    """One call of :func:`run_sweep` once its folder is checked: what is saved, what is not."""

    def __init__(self, spec, out, cases, records, reused, start, fresh=0) -> None:
        self.spec, self.out, self.cases, self.records = spec, out, cases, records
        self.reused, self.start = reused, start
        self.fresh = fresh  # records of refused cases made by this run, not computed

    def saved_new(self) -> bool:
        """True once this run has saved a computed case."""
        return len(self.records) > self.reused + self.fresh

    def execute(self, ready, workers, scheduler, retries, progress, figures, stop) -> SweepOutcome:
        """Compute the cases without a record, then write the summary if none is missing."""
        pending = [case for case in self.cases if case.index not in self.records]
        lost: dict[int, str] = {}
        used_workers, drawn = 0, None
        try:
            if not pending:
                ready()
            else:
                done = self.reused + self.fresh
                bar = _progress(len(self.cases), done, self.spec.name, progress)

                def draw(client: Any, workers: int) -> list | None:
                    return self._draw(self._outcome(lost, workers), figures, client, stop)

                used_workers, drawn = _compute(
                    self.spec, self.out, ready, pending, self.records, lost, workers,
                    scheduler, retries, bar, stop, draw if figures else None,
                )  # fmt: skip
            outcome = self._outcome(lost, used_workers)
            if outcome.lost == 0:  # all saved: a signal stops the summary, kept for resume
                with stop.raising():
                    files = _write_results(
                        self.spec, self.out, self.cases, self.records, outcome, figures, drawn
                    )
                outcome = replace(outcome, figures=tuple(files))
        except SweepInterrupted as interrupted:
            interrupted.saved = len(self.records) - self.fresh  # the refused: all fresh
            interrupted.total, interrupted.refused = len(self.cases) - self.fresh, self.fresh
            raise
        return outcome

    def _draw(self, outcome: SweepOutcome, figure_format: str, client: Any, stop: _StopFlag):
        """The figures' files, each figure drawn as a task on the cluster of ``client`` (None
        when a case is missing; [] when drawing failed, said in a warning)."""
        from .figures import draw_figures

        if outcome.lost:
            return None
        results = _results(self.spec, self.cases, self.records, outcome)
        return _or_warn(lambda: draw_figures(results, figure_format, _mapper(client, stop)))

    def _outcome(self, lost: dict[int, str], used_workers: int) -> SweepOutcome:
        records = self.records
        return SweepOutcome(
            out=self.out,
            total=len(self.cases),
            succeeded=sum(r["status"] == "ok" for r in records.values()),
            failed=sum(r["status"] == "failed" for r in records.values()),
            refused=sum(r["status"] == "refused" for r in records.values()),
            lost=len(self.cases) - len(records),
            computed=len(records) - self.reused - self.fresh,
            reused=self.reused,
            seconds=time.perf_counter() - self.start,
            workers=used_workers,
            lost_reason=next(iter(lost.values()), None),
            warned=sum(bool(r.get("warnings")) for r in records.values()),
        )


def _compute(
    spec: SweepSpec,
    out: Path,
    ready: Callable[[], None],
    pending: list[Case],
    records: dict[int, dict],
    lost: dict[int, str],
    workers: int | None,
    scheduler: str | None,
    retries: int,
    bar: Any,
    stop: _StopFlag,
    draw: Callable[[Any, int], Any] | None,
) -> tuple[int, Any]:
    """Run ``pending`` cases, each record written as it arrives; then ``draw(client, workers)``
    (the figures, drawn on the cluster) before it shuts down. Returns the worker count and
    what ``draw`` returned (None without it).

    With ``draw``, the figures' module is imported before a local cluster forks its workers:
    they inherit matplotlib rather than each importing it after the last case."""
    case_function = spec.kind_spec.case
    token = uuid.uuid4().hex[:8]
    keys = [f"sweep-{spec.name}-case-{c.index}-{token}" for c in pending]
    with bar, _quiet_dask():
        if scheduler is None:  # no more processes than cases, nor than the memory holds
            memory = WORKER_MEMORY.get(spec.kind, max(WORKER_MEMORY.values()))
            workers = worker_count(workers, len(pending), memory)
            if draw is not None:
                from . import figures  # noqa: F401 (imported once: the forked workers inherit it)
        with _client(workers, scheduler, stop) as client:
            stop.check()
            ready()
            nthreads = sum(client.nthreads().values())
            calls = [(case_function, c.index, c.params) for c in pending]
            window = PENDING_PER_WORKER * max(nthreads, 1)
            for i, future in _as_finished(client, execute_case, calls, stop, window, keys, retries):
                _collect(out, future, pending[i], records, lost)
                bar.update(1)
            return nthreads, None if draw is None else draw(client, nthreads)


def _mapper(client: Any, stop: _StopFlag) -> Callable[..., list[Any]]:
    """``map`` on the cluster of ``client``: each call a task, the results in order, with
    SIGINT/SIGTERM (``stop``) seen within :data:`SIGNAL_LATENCY`."""

    def mapped(function: Callable[..., Any], *arguments: list[Any]) -> list[Any]:
        calls = list(zip(*arguments, strict=True))
        results: list[Any] = [None] * len(calls)
        for i, future in _as_finished(client, function, calls, stop, max(len(calls), 1)):
            results[i] = future.result()
        return results

    return mapped


def _as_finished(
    client: Any,
    function: Callable[..., Any],
    calls: list[tuple],
    stop: _StopFlag,
    window: int,
    keys: list[str] | None = None,
    retries: int = 0,
) -> Iterator[tuple[int, Any]]:
    """(i, future of ``function(*calls[i])``), each as it finishes, with SIGINT/SIGTERM
    (``stop``) seen within :data:`SIGNAL_LATENCY`. At most ``window`` tasks are pending:
    more are submitted, in one batch, when half of them have finished."""
    finished: queue.SimpleQueue = queue.SimpleQueue()
    live: dict[int, Any] = {}  # the pending futures (dask cancels a task whose future is freed)
    submitted = 0
    while submitted < len(calls) or live:
        if len(live) <= window // 2 and submitted < len(calls):
            batch = range(submitted, min(submitted + window - len(live), len(calls)))
            futures = client.map(
                function, *zip(*(calls[i] for i in batch), strict=True),
                key=None if keys is None else [keys[i] for i in batch],
                retries=retries, pure=False,
            )  # fmt: skip
            for i, future in zip(batch, futures, strict=True):
                live[i] = future
                future.add_done_callback(lambda _, i=i: finished.put(i))
            submitted = batch.stop
        done = None
        while done is None:
            stop.check()
            with contextlib.suppress(queue.Empty):
                done = finished.get(timeout=SIGNAL_LATENCY)
        yield done, live.pop(done)


def _lost_reason(error: Exception) -> str:
    """Why the cluster could not run a case, in a few words."""
    if type(error).__name__ == "KilledWorker":
        return "KilledWorker: the worker processes running it died"
    return _one_line(error)


def _collect(out: Path, future: Any, case: Case, records: dict, lost: dict) -> None:
    """Write the record of a finished future (or note a case the cluster could not run)."""
    try:
        result = future.result()
    except Exception as error:  # lost worker beyond dask's allowance, scheduler gone
        lost[case.index] = _lost_reason(error)
        return
    finally:
        future.release()
    record = _case_record(case, result)
    _write_record(out, record)
    records[case.index] = record


def _case_record(case: Case, result: dict) -> dict:
    """The saved record of ``case``: what :func:`execute_case` returned (or a refused case's
    like it) with the case's inputs and axis values, sealed by its digest."""
    return _sealed({**result, "inputs": case.params, "axis_values": case.axis_values})


# --- aggregate outputs --------------------------------------------------------------------------


def _cell(value: Any) -> str:
    if value is None:
        return ""
    if isinstance(value, float):
        return repr(value)
    if isinstance(value, list):
        return json.dumps(value)
    return str(value)


def csv_columns(spec: SweepSpec) -> list[tuple[str, str, str]]:
    """(header, source, key) of every column of ``cases.csv``: case, axes, outputs, status,
    error, and why the case's error estimate is missing (empty when it is not)."""
    kind = spec.kind_spec
    columns = [("case", "index", "index")]
    for name in spec.axes:
        columns.append((unit_suffix(name, kind.parameters[name].unit), "axis", name))
    for name, unit in spec.outputs.items():
        columns.append((unit_suffix(name, unit), "output", name))
    columns += [("status", "status", "status"), ("error", "error", "error")]
    return [*columns, ("estimate_missing", "estimate_missing", "estimate_missing")]


def cases_csv(spec: SweepSpec, cases: list[Case], records: Mapping[int, dict]) -> str:
    """The text of ``cases.csv``: one row per case, sorted by index; full float precision."""
    columns = csv_columns(spec)
    stream = io.StringIO()
    writer = csv.writer(stream, lineterminator="\n")
    writer.writerow([header for header, _, _ in columns])
    for case in cases:
        record = records[case.index]
        where = {"axis": case.axis_values, "output": record["outputs"]}
        writer.writerow(
            [
                case.index if source == "index" else _cell(where.get(source, record).get(key))
                for _, source, key in columns
            ]
        )
    return stream.getvalue()


def _results(
    spec: SweepSpec, cases: list[Case], records: Mapping[int, dict], outcome: SweepOutcome
) -> dict[str, Any]:
    """The content of ``results.json``."""
    from ..version import __version__

    kind = spec.kind_spec
    ordered = [records[case.index] for case in cases]
    return {
        "shtaerman": __version__,
        "spec": spec.to_dict(),
        "kind": {
            "name": kind.name,
            "description": kind.description,
            "outputs": spec.outputs,
            "levels": {k: list(v) for k, v in kind.levels.items() if k in spec.outputs},
            "categories": {k: list(v) for k, v in kind.categories.items() if k in spec.outputs},
            "nondeterministic_outputs": list(kind.nondeterministic),
            "parameter_units": {name: p.unit for name, p in kind.parameters.items()},
        },
        "columns": [header for header, _, _ in csv_columns(spec)],
        "cases": ordered,
        "summary": {
            "cases": outcome.total,
            "succeeded": outcome.succeeded,
            "failed": outcome.failed,
            "failed_cases": [r["index"] for r in ordered if r["status"] == "failed"],
            "refused": outcome.refused,
            "refused_cases": [r["index"] for r in ordered if r["status"] == "refused"],
            "estimate_missing": {
                str(r["index"]): r["estimate_missing"] for r in ordered if r.get("estimate_missing")
            },
            "warnings": {str(r["index"]): r["warnings"] for r in ordered if r.get("warnings")},
        },
        "timings": {
            "wall": outcome.seconds,
            "computed_in_last_run": outcome.computed,
            "reused_from_earlier_runs": outcome.reused,
            "workers_in_last_run": outcome.workers,
            "case_seconds_sum": sum(r["seconds"] for r in ordered),
            "case_seconds_max": max(r["seconds"] for r in ordered),
        },
    }


def _write_results(
    spec: SweepSpec,
    out: Path,
    cases: list[Case],
    records: Mapping[int, dict],
    outcome: SweepOutcome,
    figures: str | bool,
    drawn: list | None = None,
) -> list[Path]:
    """cases.csv, results.json and (``figures``: False or the figure format) the figures:
    the files ``drawn`` on the cluster, else those drawn from the same results by an earlier
    run (:func:`~shtaerman.sweep.figures.kept_figures`), else drawn here; returns the figures
    written or kept."""
    _atomic_write(out / "cases.csv", cases_csv(spec, cases, records))
    text = json.dumps(json_safe(_results(spec, cases, records, outcome)), indent=2)
    previous = None
    if figures and drawn is None:  # nothing computed: the figures may be there already
        previous = _read_regular(out / "results.json", 2 * len(text) + MAX_RECORD_BYTES)
    _atomic_write(out / "results.json", text)
    if not figures:
        return []
    from .figures import kept_figures, sweep_figures

    def write() -> list[Path]:
        _unlink_links(out / "figures")
        kept = kept_figures(previous, text, out / "figures", figures)
        return kept or sweep_figures(out / "results.json", out / "figures", figures, drawn)

    return _or_warn(write)


def _or_warn(draw: Callable[[], list]) -> list:
    """What ``draw`` returns; [] when it fails, said in a warning (the results are safe)."""
    try:
        return draw()
    except SweepInterrupted:
        raise
    except Exception as error:
        warnings.warn(f"figures not drawn: {_one_line(error)}", stacklevel=3)
        return []
