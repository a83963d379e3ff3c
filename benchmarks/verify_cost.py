"""CPU and wall time of the main job (`shtaerman verify`) per study, against a reference.

Run: python benchmarks/verify_cost.py [NAME ...] [--quick] [--job]. Each study runs in a fresh
process, as a dask task runs it (one BLAS thread): printed are the CPU time (user + sys of
the process and its threads) of its imports, of its computation (``run_study``) and of its
files and figures (``study_entry``), its wall time, and the load average before it. Then the
figures of no study and the reports (``finish_verification``), and the totals.

Other jobs share the machine, so the wall time is unreliable and the CPU time is what compares
across runs; the reference, one SuperLU factorization of a fixed 2-D Laplacian (the kind of
work that dominates the studies), is timed before and after in this process, and the total is
also printed as a multiple of it. Beside each study: its files and figures over its compute
(``write/comp``) and in references (``write ref``). ``--warm`` writes each study's files and
figures a second time in its process and prints that CPU (``warm``): the cost without the
process's one-off imports, fonts and OpenGL context, which a dask worker pays once for all its
studies (``write`` pays them in every study, one process each). ``--job`` also times the whole
``shtaerman verify`` (both workers) as one command: its wall time and the CPU of it and its
children.
``--save FILE`` writes the rows and the reference as JSON; ``--against FILE`` (a run saved so,
e.g. on the code before a change) prints each study's CPU in references before and now, and
their ratio, with the load of both runs. Asserts nothing about time.
"""

from __future__ import annotations

import argparse
import json
import os
import resource
import subprocess
import sys
import tempfile
import time
from pathlib import Path

HERE = Path(__file__).resolve()


def cpu() -> float:
    """CPU seconds (user + sys) of this process, all its threads."""
    usage = resource.getrusage(resource.RUSAGE_SELF)
    return usage.ru_utime + usage.ru_stime


def children_cpu() -> float:
    """CPU seconds (user + sys) of the waited-for child processes."""
    usage = resource.getrusage(resource.RUSAGE_CHILDREN)
    return usage.ru_utime + usage.ru_stime


def load() -> float:
    """One-minute load average."""
    return os.getloadavg()[0]


def reference(size: int = 250, repeat: int = 3) -> float:
    """Least CPU seconds of ``repeat`` SuperLU factorizations of the 5-point Laplacian on a
    ``size`` x ``size`` grid (62,500 unknowns; about 0.3 s on an idle core)."""
    import numpy as np
    import scipy.sparse as sp
    import scipy.sparse.linalg as spla
    from threadpoolctl import threadpool_limits

    line = sp.diags([-np.ones(size - 1), 2 * np.ones(size), -np.ones(size - 1)], [-1, 0, 1])
    matrix = sp.csc_matrix(sp.kronsum(line, line))
    best = float("inf")
    with threadpool_limits(limits=1, user_api="blas"):
        for _ in range(repeat):
            start = cpu()
            spla.splu(matrix)
            best = min(best, cpu() - start)
    return best


def one_study(name: str, stage: Path, quick: bool, warm: bool = False) -> dict[str, object]:
    """Run the study ``name`` in this (fresh) process and write it into ``stage``; with
    ``warm``, write it again into a temporary folder and time that too."""
    start, wall = cpu(), time.perf_counter()
    from threadpoolctl import threadpool_limits

    from shtaerman.output.folder import study_entry
    from shtaerman.study.run import run_study
    from shtaerman.study.schema import load_study, shipped_studies

    study = next(s for p in shipped_studies() for s in load_study(p) if s.name == name)
    imported = cpu()
    with threadpool_limits(limits=1, user_api="blas"):
        outcome = run_study(study, quick=quick)
        computed = cpu()
        entry = study_entry(outcome, stage)
    written = cpu()
    (stage / f"{name}.entry.json").write_text(json.dumps(entry), encoding="utf-8")
    row = {
        "import": imported - start,
        "compute": computed - imported,
        "write": written - computed,
        "wall": time.perf_counter() - wall,
    }
    if warm:
        with tempfile.TemporaryDirectory() as again, threadpool_limits(limits=1, user_api="blas"):
            study_entry(outcome, Path(again))
        row["warm"] = cpu() - written
    return row


def finish(stage: Path, names: list[str], quick: bool) -> dict[str, object]:
    """The figures of no study and the reports, from the entries ``one_study`` left."""
    start, wall = cpu(), time.perf_counter()
    from shtaerman.output.folder import finish_verification

    imported = cpu()
    entries = {
        name: json.loads((stage / f"{name}.entry.json").read_text(encoding="utf-8"))
        for name in names
    }
    finish_verification(stage, entries, quick=quick)
    return {
        "import": imported - start,
        "compute": 0.0,
        "write": cpu() - imported,
        "wall": time.perf_counter() - wall,
    }


def in_child(arguments: list[str]) -> dict[str, float]:
    """Run this script with ``arguments`` in a fresh process; its JSON line."""
    done = subprocess.run(
        [sys.executable, str(HERE), *arguments], capture_output=True, text=True, check=True
    )
    return json.loads(done.stdout.strip().splitlines()[-1])


def whole_job(quick: bool) -> tuple[float, float]:
    """Wall and CPU seconds (it and its children) of ``shtaerman verify`` in a new folder."""
    command = [str(Path(sys.executable).with_name("shtaerman")), "verify"]
    with tempfile.TemporaryDirectory() as folder:
        before, start = children_cpu(), time.perf_counter()
        subprocess.run(
            [*command, "--out", str(Path(folder) / "run"), *(["--quick"] if quick else [])],
            capture_output=True,
            check=False,
        )
        return time.perf_counter() - start, children_cpu() - before


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("names", nargs="*", help="study names (default: the shipped studies)")
    parser.add_argument("--quick", action="store_true", help="coarse meshes, as in CI")
    parser.add_argument("--job", action="store_true", help="also the whole verify command")
    parser.add_argument("--warm", action="store_true", help="also each study's files again")
    parser.add_argument("--save", type=Path, help="write this run's rows as JSON")
    parser.add_argument("--against", type=Path, help="a saved run: print before/now ratios")
    parser.add_argument("--one", help=argparse.SUPPRESS)
    parser.add_argument("--finish", action="store_true", help=argparse.SUPPRESS)
    parser.add_argument("--stage", type=Path, help=argparse.SUPPRESS)
    args = parser.parse_args()
    if args.one or args.finish:
        run = one_study(args.one, args.stage, args.quick, args.warm) if args.one else None
        print(json.dumps(run or finish(args.stage, args.names, args.quick)))
        return
    names = args.names or shipped_names()
    flag = ["--quick"] if args.quick else []
    first = reference()
    print(f"reference (SuperLU, 62.5k-unknown Laplacian): {first:.3f} s CPU; load {load():.2f}")
    print(
        f"{'study':<22}{'import':>8}{'compute':>9}{'write':>8}{'CPU s':>8}{'wall s':>8}"
        f"{'write/comp':>11}{'write ref':>10}{'warm' if args.warm else '':>7}  load"
    )
    rows = {}
    with tempfile.TemporaryDirectory() as folder:
        for name in [*names, "(finish)"]:
            before = load()
            extra = ["--finish", *names] if name == "(finish)" else ["--one", name]
            rows[name] = row = in_child([*extra, "--stage", folder, *flag, *warm_flag(args)])
            row["cpu"] = row["import"] + row["compute"] + row["write"]
            print(f"{name:<22}{row_text(row, first)}  {before:.2f}", flush=True)
    last = reference()
    total = sum(row["cpu"] for row in rows.values())
    parts = {key: sum(row[key] for row in rows.values()) for key in ("import", "compute", "write")}
    mean = 0.5 * (first + last)
    warm = sum(row.get("warm", 0.0) for row in rows.values())
    print(
        f"total CPU {total:.1f} s (imports {parts['import']:.1f}, compute {parts['compute']:.1f}, "
        f"files and figures {parts['write']:.1f} = {parts['write'] / mean:.0f} references"
        + (f", warm {warm:.1f}" if args.warm else "")
        + f") = {total / mean:.0f} references; reference {first:.3f} -> {last:.3f} s; "
        f"load {load():.2f}"
    )
    run = {"reference": mean, "load": load(), "rows": rows}
    if args.save:
        args.save.write_text(json.dumps(run, indent=1), encoding="utf-8")
    if args.against:
        compare(json.loads(args.against.read_text(encoding="utf-8")), run)
    if args.job:
        wall, used = whole_job(args.quick)
        print(
            f"shtaerman verify: {wall:.1f} s wall, {used:.1f} s CPU (= {used / mean:.0f} "
            f"references); load {load():.2f}"
        )


def warm_flag(args: argparse.Namespace) -> list[str]:
    return ["--warm"] if args.warm else []


def row_text(row: dict[str, float], reference_cpu: float) -> str:
    """A study's CPU parts (s), wall time (s), its files and figures over its compute and in
    references, and with ``--warm`` their CPU the second time."""
    compute = row["compute"]
    ratio = f"{row['write'] / compute:>11.2f}" if compute > 0 else f"{'-':>11}"
    warm = f"{row['warm']:>7.1f}" if "warm" in row else f"{'':>7}"
    return (
        f"{row['import']:>8.1f}{compute:>9.1f}{row['write']:>8.1f}{row['cpu']:>8.1f}"
        f"{row['wall']:>8.1f}{ratio}{row['write'] / reference_cpu:>10.1f}{warm}"
    )


def compare(before: dict, now: dict) -> None:
    """Per study: CPU in references (SuperLU factorizations of the same run) before and now,
    and now / before."""
    print(
        f"against a saved run (reference {before['reference']:.3f} s, load {before['load']:.2f}; "
        f"now {now['reference']:.3f} s, load {now['load']:.2f}): CPU in references"
    )
    print(f"{'study':<22}{'before':>8}{'now':>8}{'now/before':>12}")
    totals = [0.0, 0.0]
    for name, row in now["rows"].items():
        if name not in before["rows"]:
            continue
        old = before["rows"][name]["cpu"] / before["reference"]
        new = row["cpu"] / now["reference"]
        totals = [totals[0] + old, totals[1] + new]
        print(f"{name:<22}{old:>8.0f}{new:>8.0f}{new / old:>12.2f}")
    print(f"{'total':<22}{totals[0]:>8.0f}{totals[1]:>8.0f}{totals[1] / totals[0]:>12.2f}")


def shipped_names() -> list[str]:
    """The names of the shipped studies `shtaerman verify` runs by default."""
    from shtaerman.study.schema import load_study, shipped_studies

    return [study.name for path in shipped_studies() for study in load_study(path)]


if __name__ == "__main__":
    main()
