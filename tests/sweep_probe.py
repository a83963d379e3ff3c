"""A sweep kind for the tests: y = x^2 + 1, with markers, a delay and a chosen failure.

Importing this module registers the kind ``probe``. Each computation writes a marker file
``x=<x>-pid=<pid>-<random>.start`` when it begins and ``...done`` when it ends into
``marker_dir``, so a test can count how often each case was computed and find the worker
process running it. The dask workers import this module by reference: ``tests/`` must be on
their ``sys.path`` (a LocalCluster inherits the test process's; subprocesses get PYTHONPATH).
"""

import os
import time
import uuid
from pathlib import Path

from shtaerman.sweep import Kind, Parameter, register_kind
from shtaerman.sweep.kinds import CaseResult
from shtaerman.validation import InputError


def probe_case(params: dict) -> CaseResult:
    x = params["x"]
    stem = f"x={x!r}-pid={os.getpid()}-{uuid.uuid4().hex[:8]}"
    folder = Path(params["marker_dir"]) if params["marker_dir"] else None
    if folder is not None:
        (folder / f"{stem}.start").touch()
    time.sleep(params["sleep"])
    if x == params["fail_at"]:
        raise RuntimeError(f"probe asked to fail at x = {x!r}\nsecond line of the message")
    if folder is not None:
        (folder / f"{stem}.done").touch()
    return CaseResult({"y": x * x + 1.0, "twice": 2 * x}, ())


def probe_check(params: dict) -> None:
    if params["x"] < 0:
        raise InputError(f"x must be >= 0, got {params['x']!r}")


PROBE = register_kind(
    Kind(
        name="probe",
        description="test kind: y = x^2 + 1",
        parameters={
            "x": Parameter(0.0, "m"),
            "sleep": Parameter(0.0, "s"),
            "fail_at": Parameter(-1.0, "m"),
            "marker_dir": Parameter("", type="str"),
        },
        outputs={"y": "m^2", "twice": "m"},
        case=probe_case,
        check=probe_check,
    )
)


def computations(folder: Path, suffix: str = "done") -> dict[float, int]:
    """How many computations of each x finished (``done``) or began (``start``)."""
    counts: dict[float, int] = {}
    for path in Path(folder).glob(f"*.{suffix}"):
        x = float(path.name.split("-pid=")[0].removeprefix("x="))
        counts[x] = counts.get(x, 0) + 1
    return counts


def finished_sweep(folder: Path, xs: str = "1.0", name: str = "out") -> tuple[Path, Path]:
    """A probe sweep over x = ``xs`` (TOML list items) run into ``folder / name``: (its
    file, its result folder)."""
    from shtaerman.cli import main

    sweep = Path(folder) / "p.toml"
    sweep.write_text(f'name = "p"\nkind = "probe"\n[axes]\nx = [{xs}]\n')
    out = Path(folder) / name
    assert main(["sweep", str(sweep), "--out", str(out), "--workers", "1"]) == 0
    return sweep, out
