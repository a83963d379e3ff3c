"""The local cluster's worker processes (issue 32: two workers worth two).

On Linux the workers fork from the sweep's process: they inherit its imports instead of
importing numpy, scipy and scikit-fem again (about 1.2 s of CPU a worker, the largest part of
a sweep's fixed cost), so an unguarded script no longer runs again in them. Dask's own
monitoring (statistical profiler, system monitor) is off there, and a worker keeps freed memory
for its next arrays instead of faulting them in again. Each record carries the CPU
seconds of its case, the measure of how much two cases at once slow each other down.
"""

import logging
import os
import signal
import subprocess
import sys
import time
import types
from pathlib import Path

import pytest

from shtaerman.sweep import engine
from shtaerman.sweep.engine import execute_case
from shtaerman.sweep.kinds import CaseResult

SRC = Path(__file__).resolve().parents[1] / "src"
MARKER = "_shtaerman_test_parent_module"

linux = pytest.mark.skipif(sys.platform != "linux", reason="workers fork on Linux only")


def _refaults() -> int:
    """Page faults of writing a 40 MB block from malloc again once the first one is freed."""
    import ctypes
    import resource

    libc = ctypes.CDLL(None)
    libc.malloc.restype, libc.free.argtypes = ctypes.c_void_p, [ctypes.c_void_p]
    faults = []
    for _ in range(2):
        block = libc.malloc(40_000_000)
        before = resource.getrusage(resource.RUSAGE_SELF).ru_minflt
        ctypes.memset(block, 1, 40_000_000)
        faults.append(resource.getrusage(resource.RUSAGE_SELF).ru_minflt - before)
        libc.free(block)
    return faults[1]


def _worker_state() -> dict:
    import dask

    return {
        "inherited": MARKER in sys.modules,
        # a fresh mapping faults each of its 9766 pages in, reused heap memory none of them
        # (1000: room for Python's own allocations meanwhile, many times over)
        "memory kept": _refaults() < 1000,
        "profiler": dask.config.get("distributed.worker.profile.enabled"),
        "memory monitor": dask.config.get("distributed.worker.memory.monitor-interval"),
        "sigterm": signal.getsignal(signal.SIGTERM) is signal.SIG_DFL,
        "sigint": signal.getsignal(signal.SIGINT) is signal.SIG_IGN,
        "heartbeat errors logged": logging.getLogger("distributed.worker").isEnabledFor(
            logging.ERROR
        ),
    }


def _worker_diagnosis() -> dict:
    """What the preload did and what the signals are, for the assertion's message."""
    import threading

    worker = sys.modules.get("shtaerman.sweep._worker")
    return {
        "preload": getattr(worker, "SET_UP", "module not imported"),
        "thread": threading.current_thread().name,
        "main": threading.current_thread() is threading.main_thread(),
        "handlers": [repr(signal.getsignal(s)) for s in (signal.SIGINT, signal.SIGTERM)],
    }


@linux
def test_local_workers_fork_with_this_process_state_but_their_own_signals(monkeypatch):
    """A module only this process imported is there in the worker (a spawned worker starts
    empty); the sweep's SIGTERM handler, inherited by the fork, is the default again there
    (it only set a flag, so the worker could not be terminated); the profiler is off; a freed
    array's memory serves the next one (glibc)."""
    monkeypatch.setitem(sys.modules, MARKER, types.ModuleType(MARKER))
    with engine._StopFlag(), engine._quiet_dask(), engine._client(1, None) as client:
        [state] = client.run(_worker_state).values()
        [diagnosis] = client.run(_worker_diagnosis).values()
    assert state == {
        "inherited": True,
        "memory kept": True,
        "profiler": False,
        "memory monitor": "500ms",
        "sigterm": True,
        "sigint": True,
        "heartbeat errors logged": False,
    }, diagnosis


_CONFUSED = """
import signal, threading
from shtaerman.sweep import _worker
main = threading._main_thread
threading._main_thread = threading.Thread(name="the parent's main thread")
try:
    assert threading.current_thread() is not threading.main_thread()
    signal.signal(signal.SIGTERM, lambda *_: None)
    _worker.dask_setup(None)
finally:  # the interpreter's shutdown waits on the real one
    threading._main_thread = main
assert signal.getsignal(signal.SIGINT) is signal.SIG_IGN, _worker.SET_UP
assert signal.getsignal(signal.SIGTERM) is signal.SIG_DFL, _worker.SET_UP
"""


def test_the_preload_sets_the_signals_where_threading_misnames_the_main_thread():
    """CI (pass 2: two BLAS threads, reversed order) once forked a worker whose threading
    module still held the parent's main thread: ``current_thread() is main_thread()`` was
    False in the child's only thread, and the preload left the sweep's handlers (the SET_UP
    it recorded: 'MainThread is not the main thread'). Python's own check decides now."""
    env = {**os.environ, "PYTHONPATH": str(SRC)}
    child = subprocess.run(
        [sys.executable, "-c", _CONFUSED], env=env, capture_output=True, timeout=60
    )
    assert child.returncode == 0, child.stderr.decode()


@linux
def test_an_unguarded_script_runs_its_sweep_once_on_forked_workers(tmp_path):
    """Spawned workers ran the main script again (hence the guard's message); forked ones do
    not, so the script runs to its end."""
    (tmp_path / "g.toml").write_text('name = "g"\nkind = "impact"\n[axes]\nvelocity = [0.5, 1.0]\n')
    script = tmp_path / "unguarded.py"
    script.write_text(
        'import shtaerman as sh\nsh.sweep("g.toml", workers=2, out="run")\nprint("after")\n'
    )
    env = {**os.environ, "PYTHONPATH": str(SRC)}
    done = subprocess.run(
        [sys.executable, str(script)], cwd=tmp_path, env=env, capture_output=True, text=True
    )
    assert (done.returncode, done.stdout) == (0, "after\n"), done.stderr
    assert (tmp_path / "run/cases.csv").read_text().count("\n") == 3  # header + 2 cases


def _sleeping(params: dict) -> CaseResult:
    time.sleep(params["seconds"])
    return CaseResult({"y": 1.0}, ())


def _spinning(params: dict) -> CaseResult:
    start = time.thread_time()
    while time.thread_time() - start < params["seconds"]:
        pass
    return CaseResult({"y": 1.0}, ())


def test_a_record_has_the_cpu_seconds_of_its_case():
    asleep = execute_case(_sleeping, 0, {"seconds": 0.3})
    busy = execute_case(_spinning, 1, {"seconds": 0.3})
    # a sleep costs the thread no CPU; 0.1 s covers the bookkeeping around the case many times
    assert asleep["seconds"] >= 0.3 and asleep["cpu_seconds"] < 0.1
    # the spin ends once its thread has had 0.3 s of CPU, whatever else the machine runs
    assert busy["cpu_seconds"] >= 0.3 and busy["seconds"] >= busy["cpu_seconds"] - 0.01


def test_the_nanny_start_poll_is_set_while_the_cluster_starts_and_dask_s_again_after():
    """engine.NANNY_POLL is written into dask's WorkerProcess._init_msg_interval (private): if
    dask renamed it, the assignment would do nothing and each start would wait 25-33 ms again.
    It was left set for the whole process, a user's own clusters too; now dask's value is back
    once the local cluster has started."""
    import inspect

    from distributed.nanny import WorkerProcess

    assert "await asyncio.sleep(self._init_msg_interval)" in inspect.getsource(WorkerProcess)
    dask_own = WorkerProcess._init_msg_interval
    assert dask_own != engine.NANNY_POLL
    seen = []
    start = WorkerProcess.start

    async def starting(self):
        seen.append(self._init_msg_interval)
        return await start(self)

    with pytest.MonkeyPatch.context() as patch:
        patch.setattr(WorkerProcess, "start", starting)
        with engine._quiet_dask(), engine._client(1, None):
            assert WorkerProcess._init_msg_interval == dask_own
    assert seen == [engine.NANNY_POLL]
