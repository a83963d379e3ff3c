"""Sweeps on real dask clusters: same rows whatever the cluster, nothing lost, nothing twice.

- ``cases.csv`` is byte-identical on 1 local worker, 2 local workers and an existing cluster
  (``dask scheduler`` + ``dask worker`` subprocesses on 127.0.0.1);
- a worker process killed (SIGKILL) mid-case: dask reruns its case, every case is saved once;
- ``resume`` computes exactly the cases without a record (counted by marker files);
- SIGTERM: one line saying how to resume, no traceback, finished cases kept, then resumed;
- a case that raises is recorded with its one-line error, the others complete, exit code 1.

The kind ``probe`` (tests/sweep_probe.py) writes a marker per computation; the dask workers
import it by reference, so ``tests/`` is on their path (inherited, or PYTHONPATH).
"""

import contextlib
import csv
import json
import math
import os
import signal
import subprocess
import sys
import threading
import time
from pathlib import Path

import dask
import pytest
import sweep_probe
from distributed import Client

from shtaerman.cli import main
from shtaerman.sweep import load_sweep, run_sweep

ROOT = Path(__file__).resolve().parents[1]
ENV = {**os.environ, "PYTHONPATH": os.pathsep.join([str(ROOT / "src"), str(ROOT / "tests")])}

IMPACT = """\
name = "impact-grid"
kind = "impact"
[parameters]
mass = 0.7
[axes]
velocity = [0.5, 2.0, 4.5]
exponent = [1.5, 2.0]
"""


def probe_sweep(tmp_path, xs, *, sleep=0.0, fail_at=-1.0, name="probe"):
    markers = tmp_path / "markers"
    markers.mkdir(exist_ok=True)
    path = tmp_path / f"{name}.toml"
    path.write_text(
        f'name = "{name}"\nkind = "probe"\n[parameters]\nsleep = {sleep}\nfail_at = {fail_at}\n'
        f'marker_dir = "{markers}"\n[axes]\nx = {list(map(float, xs))}\n'
    )
    return path, markers


def case_files(out):
    return sorted(int(p.stem) for p in (out / "cases").glob("*.json"))


def csv_rows(out):
    with open(out / "cases.csv", newline="") as stream:
        return list(csv.DictReader(stream))


@pytest.fixture(scope="module")
def external_cluster(tmp_path_factory):
    """``dask scheduler --port 0`` and ``dask worker`` (2 processes) on 127.0.0.1."""
    folder = tmp_path_factory.mktemp("cluster")
    scheduler_file = folder / "scheduler.json"
    processes = [
        subprocess.Popen(
            [
                sys.executable,
                "-m",
                "distributed.cli.dask_scheduler",
                "--host",
                "127.0.0.1",
                "--port",
                "0",
                "--no-dashboard",
                "--scheduler-file",
                str(scheduler_file),
            ],
            env=ENV,
            stdout=subprocess.DEVNULL,
            stderr=subprocess.DEVNULL,
        )
    ]
    try:
        deadline = time.monotonic() + 60
        while not scheduler_file.exists():
            assert time.monotonic() < deadline, "the scheduler did not start"
            time.sleep(0.1)
        processes.append(
            subprocess.Popen(
                [
                    sys.executable,
                    "-m",
                    "distributed.cli.dask_worker",
                    "--scheduler-file",
                    str(scheduler_file),
                    "--nworkers",
                    "2",
                    "--nthreads",
                    "1",
                    "--no-dashboard",
                ],
                env=ENV,
                stdout=subprocess.DEVNULL,
                stderr=subprocess.DEVNULL,
            )
        )
        address = json.loads(scheduler_file.read_text())["address"]
        with Client(address, timeout="30s") as client:
            client.wait_for_workers(2, timeout=60)
        yield address
    finally:
        if scheduler_file.exists():  # the quick way down: the scheduler stops its workers
            with (
                contextlib.suppress(OSError, TimeoutError),
                Client(json.loads(scheduler_file.read_text())["address"], timeout="5s") as client,
            ):
                client.shutdown()
        for process in reversed(processes):
            with contextlib.suppress(subprocess.TimeoutExpired):
                process.wait(timeout=10)
            process.terminate()
        for process in reversed(processes):
            try:
                process.wait(timeout=20)
            except subprocess.TimeoutExpired:
                process.kill()
                process.wait()


def test_same_rows_on_one_two_and_an_existing_cluster(tmp_path, external_cluster):
    path = tmp_path / "impact.toml"
    path.write_text(IMPACT)
    spec = load_sweep(path)
    one = run_sweep(spec, tmp_path / "one", workers=1, figures=False)
    two = run_sweep(spec, tmp_path / "two", workers=2, figures=False)
    remote = run_sweep(spec, tmp_path / "remote", scheduler=external_cluster, figures=False)
    assert (one.workers, two.workers, remote.workers) == (1, 2, 2)
    assert one.exit_code == two.exit_code == remote.exit_code == 0
    text = (tmp_path / "one" / "cases.csv").read_text()
    assert text == (tmp_path / "two" / "cases.csv").read_text()
    assert text == (tmp_path / "remote" / "cases.csv").read_text()
    rows = csv_rows(tmp_path / "one")
    assert [r["case"] for r in rows] == [str(i) for i in range(6)]
    assert rows[0]["velocity [m/s]"] == "0.5" and rows[0]["exponent"] == "1.5"
    assert float(rows[0]["x_c [m]"]) > 0 and rows[0]["status"] == "ok" and rows[0]["error"] == ""
    # the remote cases really ran on the external workers, not in this process
    workers = {
        json.loads((tmp_path / "remote/cases" / f"{i}.json").read_text())["pid"] for i in range(6)
    }
    assert os.getpid() not in workers


def test_a_failing_case_is_recorded_and_the_others_complete(tmp_path, capsys, external_cluster):
    path, _ = probe_sweep(tmp_path, [1, 2, 3, 4], fail_at=3.0)
    out = str(tmp_path / "out")
    code = main(["sweep", str(path), "--out", out, "--scheduler", external_cluster])
    out, err = capsys.readouterr()
    assert code == 1, err
    assert "4 cases, 3 ok, 1 failed" in out
    rows = csv_rows(tmp_path / "out")
    assert [r["status"] for r in rows] == ["ok", "ok", "failed", "ok"]
    assert rows[2]["error"] == (
        "RuntimeError: probe asked to fail at x = 3.0 second line of the message"
    )
    assert rows[2]["y [m^2]"] == "" and rows[3]["y [m^2]"] == "17.0"
    results = json.loads((tmp_path / "out/results.json").read_text())
    assert results["summary"]["failed_cases"] == [2]


class FirstCaseKiller(threading.Thread):
    """SIGKILLs the worker process running the first case to start, 0.3 s into it."""

    def __init__(self, markers):
        super().__init__()
        self.markers, self.x, self.pid = markers, None, None

    def run(self):
        deadline = time.monotonic() + 60
        while self.pid is None and time.monotonic() < deadline:
            started = sorted(self.markers.glob("*.start"))
            if started:
                name = started[0].name
                self.x = float(name.split("-pid=")[0].removeprefix("x="))
                self.pid = int(name.split("-pid=")[1].split("-")[0])
                time.sleep(0.3)  # well inside the 1 s case
                os.kill(self.pid, signal.SIGKILL)
            time.sleep(0.02)


def test_a_worker_killed_mid_case_has_its_case_rerun(tmp_path, external_cluster):
    """On the external cluster (``dask worker`` with its nanny): the nanny starts a new worker
    process, the scheduler reruns the lost case."""
    xs = [1, 2, 3, 4]
    path, markers = probe_sweep(tmp_path, xs, sleep=1.0)
    killer = FirstCaseKiller(markers)
    killer.start()
    spec = load_sweep(path)
    outcome = run_sweep(spec, tmp_path / "out", scheduler=external_cluster, figures=False)
    killer.join()
    assert killer.pid is not None, "no case started"
    assert outcome.exit_code == 0 and outcome.succeeded == 4 and outcome.lost == 0
    assert case_files(tmp_path / "out") == list(range(4))
    rows = csv_rows(tmp_path / "out")
    assert [float(r["x [m]"]) for r in rows] == [float(x) for x in xs]  # each case once
    assert all(r["status"] == "ok" for r in rows)
    # the killed computation never finished; its case ran again, on another process
    done = sweep_probe.computations(markers)
    assert done == {float(x): 1 for x in xs}
    assert sweep_probe.computations(markers, "start")[killer.x] == 2
    record = json.loads((tmp_path / "out/cases" / f"{xs.index(killer.x)}.json").read_text())
    assert record["pid"] != killer.pid


def test_a_case_dask_gives_up_on_is_left_for_resume(tmp_path):
    """With no failures allowed, dask gives up on the killed worker's case (KilledWorker): no
    record is written for it, the exit code is 1, no summary; --resume computes just the
    cases without a record."""
    xs = [1, 2, 3]
    path, markers = probe_sweep(tmp_path, xs, sleep=1.0)
    spec, out = load_sweep(path), tmp_path / "out"
    killer = FirstCaseKiller(markers)
    killer.start()
    with dask.config.set({"distributed.scheduler.allowed-failures": 0}):
        outcome = run_sweep(spec, out, workers=2, figures=False)
    killer.join()
    # the killed case is lost; so may be a case dask had already queued on that worker
    lost = set(range(3)) - set(case_files(out))
    assert xs.index(killer.x) in lost
    assert (outcome.exit_code, outcome.lost, outcome.succeeded) == (1, len(lost), 3 - len(lost))
    assert "KilledWorker" in outcome.lost_reason
    assert not (out / "cases.csv").exists() and not (out / "results.json").exists()
    again = run_sweep(spec, out, workers=1, resume=True, figures=False)
    assert (again.exit_code, again.computed, again.reused) == (0, len(lost), 3 - len(lost))
    assert sweep_probe.computations(markers) == {float(x): 1 for x in xs}


def test_resume_computes_only_the_missing_cases(tmp_path, external_cluster):
    xs = [1, 2, 3, 4, 5]
    path, markers = probe_sweep(tmp_path, xs)
    out = tmp_path / "out"
    spec = load_sweep(path)
    assert run_sweep(spec, out, scheduler=external_cluster, figures=False).computed == 5
    first = (out / "cases.csv").read_text()
    # an interrupted sweep: two records never written, no aggregate files yet
    for index in (1, 3):
        (out / "cases" / f"{index}.json").unlink()
    (out / "cases.csv").unlink()
    (out / "results.json").unlink()
    outcome = run_sweep(spec, out, scheduler=external_cluster, resume=True, figures=False)
    assert (outcome.computed, outcome.reused, outcome.succeeded) == (2, 3, 5)
    assert sweep_probe.computations(markers) == {1.0: 1, 2.0: 2, 3.0: 1, 4.0: 2, 5.0: 1}
    assert (out / "cases.csv").read_text() == first
    # a complete sweep resumed: nothing to compute, nothing changes
    again = run_sweep(spec, out, resume=True, figures=False)
    assert (again.computed, again.reused) == (0, 5)
    assert sum(sweep_probe.computations(markers).values()) == 7


@pytest.mark.parametrize("signum", [signal.SIGTERM, signal.SIGINT])
def test_a_signal_keeps_finished_cases_and_says_how_to_resume(tmp_path, signum):
    """SIGTERM to the sweep's process; SIGINT to its whole process group, as Ctrl-C in a
    terminal does (the workers too: they must stay quiet and leave the shutdown to it)."""
    xs = [1, 2, 3, 4, 5, 6]
    path, markers = probe_sweep(tmp_path, xs, sleep=0.3)
    out = tmp_path / "out"
    program = "import sys, sweep_probe; from shtaerman.cli import main; sys.exit(main())"
    process = subprocess.Popen(
        [sys.executable, "-c", program, "sweep", str(path), "--out", str(out), "--workers", "2"],
        env=ENV,
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
        text=True,
        start_new_session=True,  # its own process group: the SIGINT reaches only it
    )
    deadline = time.monotonic() + 60
    while len(case_files(out) if (out / "cases").is_dir() else []) < 2:
        assert process.poll() is None and time.monotonic() < deadline, process.communicate()
        time.sleep(0.02)
    if signum == signal.SIGINT:
        os.killpg(process.pid, signum)
    else:
        process.send_signal(signum)
    stdout, stderr = process.communicate(timeout=60)
    assert process.returncode == 128 + signum and stdout == ""
    assert "Traceback" not in stderr
    [line] = stderr.strip().splitlines()
    name = signal.Signals(signum).name
    assert line.startswith(f"shtaerman: sweep 'probe' interrupted ({name}): ")
    assert f"resume with: shtaerman sweep {path} --out {out} --resume" in line
    saved = case_files(out)
    assert 2 <= len(saved) < len(xs)
    assert f"{len(saved)} of {len(xs)} cases saved" in line
    assert not (out / "cases.csv").exists()
    if signum == signal.SIGINT:
        return  # the resume after an interruption is the same whatever the signal
    # resume: the saved cases are not computed again, the others are, each saved once
    outcome = run_sweep(load_sweep(path), out, workers=1, resume=True, figures=False)
    assert outcome.exit_code == 0 and outcome.reused == len(saved)
    assert case_files(out) == list(range(len(xs)))
    done = sweep_probe.computations(markers)
    assert all(done[float(xs[i])] == 1 for i in saved)
    assert [float(r["x [m]"]) for r in csv_rows(out)] == [float(x) for x in xs]


def _signal_while_the_figures_are_drawn(monkeypatch, signum):
    from shtaerman.sweep import figures

    draw = figures.sweep_figures

    def signalled(*args, **kwargs):
        os.kill(os.getpid(), signum)
        return draw(*args, **kwargs)

    monkeypatch.setattr(figures, "sweep_figures", signalled)


def _signal_while_the_cluster_shuts_down(monkeypatch, signum):
    from distributed import LocalCluster

    close = LocalCluster.close

    def signalled(self, *args, **kwargs):
        os.kill(os.getpid(), signum)
        return close(self, *args, **kwargs)

    monkeypatch.setattr(LocalCluster, "close", signalled)


@pytest.mark.parametrize(
    "window", [_signal_while_the_figures_are_drawn, _signal_while_the_cluster_shuts_down]
)
@pytest.mark.parametrize("signum", [signal.SIGINT, signal.SIGTERM])
def test_a_signal_after_the_last_case_stops_the_sweep_and_resume_completes_it(
    tmp_path, capfd, monkeypatch, window, signum
):
    """A signal after every case is saved (while the cluster shuts down, or the figures are
    drawn) was ignored or lost: exit 0. It stops the sweep (130/143, the resume line), every
    record stays, and a resume writes the summary and figures without computing a case."""
    path, markers = probe_sweep(tmp_path, [1, 2])
    out = tmp_path / "out"
    window(monkeypatch, signum)
    code = main(["sweep", str(path), "--out", str(out), "--workers", "1"])
    stdout, stderr = capfd.readouterr()
    assert code == 128 + signum and stdout == ""
    name = signal.Signals(signum).name
    assert stderr == (
        f"shtaerman: sweep 'probe' interrupted ({name}): all 2 cases saved in {out}, its summary "
        f"and figures not all written; write them with: shtaerman sweep {path} --out {out} "
        "--resume --workers 1\n"
    )
    assert case_files(out) == [0, 1]
    assert not list(out.glob("figures/*.png"))  # stopped before the first figure
    monkeypatch.undo()
    assert main(["sweep", str(path), "--out", str(out), "--resume"]) == 0
    assert "nothing to compute, 2 from an earlier run" in capfd.readouterr().out
    assert [float(r["y [m^2]"]) for r in csv_rows(out)] == [2.0, 5.0]
    assert list((out / "figures").glob("*.png"))  # the figures the interrupted run did not draw
    assert sweep_probe.computations(markers) == {1.0: 1, 2.0: 1}


def test_one_tiny_contact_case(tmp_path):
    """The FEM kind through the cluster: a coarse mesh, one depth, errors within reason."""
    path = tmp_path / "c.toml"
    path.write_text(
        'name = "c"\nkind = "contact"\n[parameters]\nmesh_size = 0.0333\ndomain_factor = 1e3\n'
        "growth = 0.5\naxis_size = 1e-3\naxis_growth = 0.3\ndepths = [2e-3, 4e-3]\n"
        "[axes]\nnu2 = [0.5]\n"
    )
    outcome = run_sweep(load_sweep(path), tmp_path / "out", workers=1, figures=False)
    assert outcome.exit_code == 0
    [row] = csv_rows(tmp_path / "out")
    # coarse mesh (about 2.7k dofs): the fixed-exponent beta within 1 % of Shtaerman's
    assert float(row["error_beta"]) < 1e-2
    assert float(row["beta_fem [N/m^q]"]) == pytest.approx(
        float(row["beta_analytic [N/m^q]"]), rel=1e-2
    )
    assert int(row["dofs"]) > 1000 and float(row["seconds [s]"]) > 0


def test_warnings_of_a_case_are_recorded_and_reported(tmp_path, capsys, external_cluster):
    path = tmp_path / "fast.toml"
    path.write_text('name = "fast"\nkind = "impact"\n[axes]\nvelocity = [3.0, 6.0]\n')
    code = main(
        ["sweep", str(path), "--out", str(tmp_path / "out"), "--scheduler", external_cluster]
    )
    out, err = capsys.readouterr()
    assert "2 cases, 2 ok, 0 failed" in out
    assert code == 0  # a warning is not a failure
    assert err.strip() == (
        f"shtaerman: warning: 1 case(s) issued warnings (summary.warnings in "
        f"{tmp_path / 'out' / 'results.json'})"
    )
    results = json.loads((tmp_path / "out/results.json").read_text())
    [message] = results["summary"]["warnings"]["1"]
    assert "velocity 6 m/s exceeds 5 m/s" in message
    assert results["cases"][0]["warnings"] == []


def test_resume_extends_the_grid_and_computes_only_the_new_cases(tmp_path, capsys):
    path, markers = probe_sweep(tmp_path, [1, 2, 3])
    out = tmp_path / "out"
    assert run_sweep(load_sweep(path), out, workers=1, figures=False).computed == 3
    # new values on the axis, between and after the saved ones: their cases only
    extended, _ = probe_sweep(tmp_path, [1, 1.5, 2, 3, 4])
    outcome = run_sweep(load_sweep(extended), out, workers=1, resume=True, figures=False)
    assert (outcome.computed, outcome.reused, outcome.succeeded) == (2, 3, 5)
    assert sweep_probe.computations(markers) == {1.0: 1, 1.5: 1, 2.0: 1, 3.0: 1, 4.0: 1}
    assert case_files(out) == list(range(5))
    rows = csv_rows(out)
    assert [float(r["x [m]"]) for r in rows] == [1, 1.5, 2, 3, 4]
    assert [float(r["y [m^2]"]) for r in rows] == [x * x + 1 for x in (1, 1.5, 2, 3, 4)]
    for index, x in enumerate((1, 1.5, 2, 3, 4)):
        record = json.loads((out / "cases" / f"{index}.json").read_text())
        assert record["index"] == index and record["inputs"]["x"] == x
    # a changed value: the dropped case's record is kept aside and reused if it comes back
    changed, _ = probe_sweep(tmp_path, [1, 5])
    outcome = run_sweep(load_sweep(changed), out, workers=1, resume=True, figures=False)
    assert (outcome.computed, outcome.reused) == (1, 1)
    assert case_files(out) == [0, 1]
    back, _ = probe_sweep(tmp_path, [1, 1.5, 2, 3, 4, 5])
    outcome = run_sweep(load_sweep(back), out, workers=1, resume=True, figures=False)
    assert (outcome.computed, outcome.reused) == (0, 6)
    assert sweep_probe.computations(markers) == {x: 1 for x in (1.0, 1.5, 2.0, 3.0, 4.0, 5.0)}
    assert [float(r["x [m]"]) for r in csv_rows(out)] == [1, 1.5, 2, 3, 4, 5]
    assert not list((out / "cases" / "unused").iterdir())
    # a changed fixed parameter is still refused, one line
    moved = tmp_path / "moved.toml"
    moved.write_text(back.read_text().replace("sleep = 0.0", "sleep = 0.001"))
    assert main(["sweep", str(moved), "--out", str(out), "--resume"]) == 2
    err = capsys.readouterr().err
    assert "holds a different sweep (parameters.sleep differs" in err and err.count("\n") == 1


AB = """\
name = "ab"
kind = "impact"
[axes]
velocity = [1.0, 2.0]
mass = [0.1, 10.0]
"""


def test_resume_after_reordering_axes_keeps_each_result_with_its_case(tmp_path):
    ab = tmp_path / "ab.toml"
    ab.write_text(AB)
    ba = tmp_path / "ba.toml"
    ba.write_text(
        AB.replace(
            "velocity = [1.0, 2.0]\nmass = [0.1, 10.0]", "mass = [0.1, 10.0]\nvelocity = [1.0, 2.0]"
        )
    )
    out, fresh = tmp_path / "r", tmp_path / "fresh"
    run_sweep(load_sweep(ab), out, workers=1, figures=False)
    for index in (2, 3):
        (out / "cases" / f"{index}.json").unlink()
    outcome = run_sweep(load_sweep(ba), out, workers=1, resume=True, figures=False)
    assert (outcome.computed, outcome.reused) == (2, 2)
    run_sweep(load_sweep(ba), fresh, workers=1, figures=False)
    assert (out / "cases.csv").read_text() == (fresh / "cases.csv").read_text()
    for index in range(4):
        record = json.loads((out / "cases" / f"{index}.json").read_text())
        assert {k: record["inputs"][k] for k in record["axis_values"]} == record["axis_values"]


def test_resume_recomputes_hand_edited_or_damaged_records(tmp_path, capsys):
    path, markers = probe_sweep(tmp_path, [1, 2, 3, 4, 5, 6])
    out = tmp_path / "out"
    assert run_sweep(load_sweep(path), out, workers=1, figures=False).computed == 6
    first = (out / "cases.csv").read_text()
    cases = out / "cases"
    (cases / "0.json").write_text("[1, 2]")
    record = json.loads((cases / "1.json").read_text())
    del record["outputs"]
    (cases / "1.json").write_text(json.dumps(record))
    record = json.loads((cases / "2.json").read_text())
    record["outputs"]["y"] = -5.0  # a plausible-looking edit
    (cases / "2.json").write_text(json.dumps(record))
    (cases / "3.json").unlink()
    os.mkfifo(cases / "3.json")
    (cases / "4.json").unlink()
    (cases / "4.json").symlink_to("/dev/zero")
    (cases / "01.json").write_text((cases / "5.json").read_text().replace("2.0", "7.0"))
    (cases / "5.json").write_bytes(b"\xff" + b"[" * 5000)
    code = main(["sweep", str(path), "--out", str(out), "--resume", "--workers", "1"])
    _, err = capsys.readouterr()
    assert code == 0 and "Traceback" not in err
    assert err.count("is not a case record this tool wrote") == 6
    assert (out / "cases.csv").read_text() == first
    assert sweep_probe.computations(markers) == {float(x): 2 for x in range(1, 7)}


def test_a_forced_run_that_fails_at_the_end_keeps_its_cases(tmp_path, capsys, monkeypatch):
    """The old sweep stays whole (the new one did not finish); the new run's cases are kept
    beside it, and the printed command completes them there without computing them again."""
    import errno

    from shtaerman.sweep import engine

    path, markers = probe_sweep(tmp_path, [1, 2])
    out = tmp_path / "out"
    assert main(["sweep", str(path), "--out", str(out), "--workers", "1"]) == 0
    capsys.readouterr()
    old_csv = (out / "cases.csv").read_text()

    def full(*args, **kwargs):
        raise OSError(errno.ENOSPC, "No space left on device", str(out / "cases.csv"))

    monkeypatch.setattr(engine, "_write_results", full)
    assert main(["sweep", str(path), "--out", str(out), "--workers", "1", "--force"]) == 1
    err = capsys.readouterr().err
    beside = tmp_path / f"out.incomplete-{os.getpid()}"
    assert err.count("\n") == 1 and "No space left on device" in err
    assert f"complete them with: shtaerman sweep {path} --out {beside} --resume" in err
    assert (out / "cases.csv").read_text() == old_csv
    assert case_files(beside) == [0, 1] and not (beside / "cases.csv").exists()
    assert sorted(p.name for p in tmp_path.iterdir() if p.name.startswith(".")) == []
    monkeypatch.undo()
    assert main(["sweep", str(path), "--out", str(beside), "--resume"]) == 0
    assert sweep_probe.computations(markers) == {1.0: 2, 2.0: 2}


def test_resume_does_not_follow_a_link_planted_among_the_figures(tmp_path):
    path = tmp_path / "ab.toml"
    path.write_text(AB.replace("mass = [0.1, 10.0]\n", ""))
    out = tmp_path / "out"
    run_sweep(load_sweep(path), out, workers=1)
    precious = tmp_path / "precious"
    precious.write_text("mine")
    (out / "figures" / "x_c.png").unlink()
    (out / "figures" / "x_c.png").symlink_to(precious)
    outcome = run_sweep(load_sweep(path), out, resume=True)  # nothing to compute: no cluster
    assert (outcome.computed, outcome.reused) == (0, 2)
    assert precious.read_text() == "mine"
    assert not (out / "figures" / "x_c.png").is_symlink()
    assert (out / "figures" / "x_c.png").stat().st_size > 1000


def test_a_dynamic_case_whose_checks_fail_is_recorded_failed_with_its_reason(monkeypatch):
    # a rubber 1000x denser than rubber on a coarse mesh: the energy account is off by about
    # the whole kinetic energy; `shtaerman dynamic` warns and exits 1 on the same inputs. The
    # wave speed guard refuses it before any mesh (v0 = 2 c_s): lifted to reach the run's check
    from shtaerman.sweep.engine import execute_case
    from shtaerman.sweep.kinds import get_kind

    monkeypatch.setattr("shtaerman.guards.wave_limit", lambda *_: math.inf)

    kind = get_kind("dynamic")
    params = {**kind.defaults(), "density2": 1e6, "steps": 100, "mesh_size": 0.05}
    record = execute_case(kind.case, 0, params)
    assert record["status"] == "failed"
    assert record["error"].startswith("check failed: energy balance error ")
    assert "exceeds 0.01" in record["error"]
    assert record["outputs"]["energy_balance_error"] > 0.01  # the numbers are kept to see


def test_no_more_workers_than_cases_and_a_private_scratch_folder(tmp_path, monkeypatch):
    import tempfile

    # a link planted where dask puts its scratch space by default must not be followed
    victim = tmp_path / "victim"
    victim.mkdir()
    temporary = tmp_path / "tmp"
    temporary.mkdir()
    (temporary / "dask-scratch-space").symlink_to(victim)
    monkeypatch.setattr(tempfile, "tempdir", str(temporary))
    monkeypatch.setenv("TMPDIR", str(temporary))
    path, _ = probe_sweep(tmp_path, [1, 2])
    outcome = run_sweep(load_sweep(path), tmp_path / "out", workers=4, figures=False)
    assert outcome.exit_code == 0 and outcome.workers == 2
    assert list(victim.iterdir()) == []
    assert sorted(p.name for p in temporary.iterdir()) == ["dask-scratch-space"]


def test_a_case_dask_gives_up_on_is_one_line_of_ours_and_no_dask_log(tmp_path, capfd):
    """After KilledWorker the CLI says how many cases could not run and how to complete them,
    in its own words: no "distributed.scheduler - ERROR" line, no "nothing to compute"."""
    path, markers = probe_sweep(tmp_path, [1, 2, 3], sleep=1.0)
    out = tmp_path / "out"
    killer = FirstCaseKiller(markers)
    killer.start()
    with dask.config.set({"distributed.scheduler.allowed-failures": 0}):
        code = main(["sweep", str(path), "--out", str(out), "--workers", "2"])
    killer.join()
    stdout, stderr = capfd.readouterr()
    assert code == 1 and killer.pid is not None
    lost = 3 - len(case_files(out))
    assert lost >= 1 and "nothing to compute" not in stdout
    assert f"3 cases, {3 - lost} ok, 0 failed ({3 - lost} computed on 2 workers)" in stdout
    [line] = stderr.strip().splitlines()
    cases = f"{lost} case{'s' * (lost != 1)}"  # "1 case" (session 67)
    assert line.startswith(f"shtaerman: {cases} could not run (KilledWorker: ")
    assert line.endswith(
        f"complete them with: shtaerman sweep {path} --out {out} --resume --workers 2"
    )
    assert "distributed" not in stderr


def test_sigterm_while_the_cluster_starts_says_nothing_was_saved(tmp_path, capfd, monkeypatch):
    """SIGTERM while the local cluster starts: one line, no folder named that does not
    exist, no dask log."""
    import shtaerman.sweep.engine as engine

    start = engine._local_cluster

    def terminated_while_starting(workers, scratch):
        os.kill(os.getpid(), signal.SIGTERM)
        return start(workers, scratch)

    monkeypatch.setattr(engine, "_local_cluster", terminated_while_starting)
    path, _ = probe_sweep(tmp_path, [1, 2, 3, 4, 5, 6])
    out = tmp_path / "st1"
    assert main(["sweep", str(path), "--out", str(out), "--workers", "2"]) == 128 + signal.SIGTERM
    stdout, stderr = capfd.readouterr()
    assert stdout == "" and not out.exists()
    assert stderr == "shtaerman: sweep 'probe' interrupted (SIGTERM) before any case was saved\n"


def test_workers_are_capped_at_the_cases_and_the_memory_with_one_line(tmp_path, capfd, monkeypatch):
    """--workers 16 for 2 cases started 17 processes (one per case now, and said so); the
    available memory caps the workers too."""
    import shtaerman.sweep.engine as engine

    path, _ = probe_sweep(tmp_path, [1, 2])
    assert main(["sweep", str(path), "--out", str(tmp_path / "a"), "--workers", "16"]) == 0
    stdout, stderr = capfd.readouterr()
    assert "(2 computed on 2 workers)" in stdout
    assert stderr == "shtaerman: starting 2 of 16 workers: 2 cases to compute\n"
    monkeypatch.setattr(
        engine, "available_memory", lambda: 1.5 * max(engine.WORKER_MEMORY.values())
    )
    assert main(["sweep", str(path), "--out", str(tmp_path / "b"), "--workers", "2"]) == 0
    stdout, stderr = capfd.readouterr()
    assert "(2 computed on 1 worker)" in stdout
    assert stderr == (
        "shtaerman: starting 1 of 2 workers: the available memory (0.6 GB) holds 1 of about "
        "400 MB\n"
    )
