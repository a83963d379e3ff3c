"""``sh.sweep`` in a script without an ``if __name__ == "__main__":`` guard (issue 31).

dask's workers run the main script again; unguarded, each started the sweep anew and the
run ended in a wall of dask tracebacks whose last line blamed "another shtaerman run".
"""

import os
import subprocess
import sys
from pathlib import Path

SRC = Path(__file__).resolve().parents[1] / "src"
SWEEP = """\
name = "g"
kind = "impact"
[parameters]
mass = 0.25
[axes]
velocity = [0.5, 1.0]
"""
SPAWNED = (  # the workers of a local cluster fork on Linux and run no script: spawn them
    'from shtaerman.sweep import engine\nengine.START_METHOD = "spawn"\n'
)


def test_an_unguarded_script_fails_in_one_line_naming_the_guard(tmp_path):
    (tmp_path / "g.toml").write_text(SWEEP)
    script = tmp_path / "unguarded.py"
    script.write_text(
        SPAWNED
        + 'import shtaerman as sh\nsh.sweep("g.toml", workers=1, out="run")\nprint("after")\n'
    )
    env = {**os.environ, "PYTHONPATH": str(SRC)}
    done = subprocess.run(
        [sys.executable, str(script)], cwd=tmp_path, env=env, capture_output=True, text=True
    )
    err = done.stderr
    assert done.returncode == 1 and "after" not in done.stdout, err
    # the script's own traceback, ending in the reason and the remedy; none from the workers
    assert err.count("Traceback") == 1, err
    assert err.rstrip().splitlines()[-1] == (
        "shtaerman.validation.InputError: sweep: the main script starts a sweep as it is "
        "imported, and dask's worker processes import it again; start it under "
        "'if __name__ == \"__main__\":' (a notebook needs no guard)"
    )
    assert "another shtaerman run" not in err and "Nanny" not in err
    assert sorted(p.name for p in tmp_path.iterdir()) == ["g.toml", "unguarded.py"]


def test_a_process_of_ones_own_pool_says_it_in_its_one_line(tmp_path):
    """Outside a sweep's cluster (no scratch folder named), the new process prints the reason."""
    script = tmp_path / "pool.py"
    script.write_text(
        "import multiprocessing\n"
        "from shtaerman.sweep.engine import run_sweep\n"
        "run_sweep(None, 'run')\n"  # the child stops before it reads anything
    )
    child = (
        "import multiprocessing, runpy, sys\n"
        "multiprocessing.current_process()._inheriting = True\n"  # what spawn sets
        f"runpy.run_path({str(script)!r}, run_name='__mp_main__')\n"
    )
    env = {k: v for k, v in os.environ.items() if k != "SHTAERMAN_SWEEP_SCRATCH"}
    env["PYTHONPATH"] = str(SRC)
    done = subprocess.run(
        [sys.executable, "-c", child], cwd=tmp_path, env=env, capture_output=True, text=True
    )
    assert done.returncode == 1
    assert done.stderr.count("\n") == 1 and "if __name__ ==" in done.stderr


def test_a_stale_scratch_folder_in_the_environment_does_not_hide_the_guard(tmp_path):
    """dask's nanny wrote its workers' environment into the parent process and left it there:
    a script started from that process inherited a scratch folder already deleted, its workers
    marked the deleted folder, and the run ended in "Nanny failed to start" alone."""
    (tmp_path / "g.toml").write_text(SWEEP)
    script = tmp_path / "unguarded.py"
    script.write_text(
        SPAWNED + 'import shtaerman as sh\nsh.sweep("g.toml", workers=1, out="run")\n'
    )
    env = {**os.environ, "PYTHONPATH": str(SRC), "SHTAERMAN_SWEEP_SCRATCH": str(tmp_path / "x")}
    done = subprocess.run(
        [sys.executable, str(script)], cwd=tmp_path, env=env, capture_output=True, text=True
    )
    assert "start it under 'if __name__" in done.stderr.rstrip().splitlines()[-1], done.stderr


def test_a_sweep_leaves_the_environment_as_it_found_it(tmp_path, monkeypatch):
    import shtaerman as sh

    (tmp_path / "g.toml").write_text(SWEEP)
    monkeypatch.chdir(tmp_path)
    before = dict(os.environ)
    sh.sweep("g.toml", workers=1, out="run")
    assert dict(os.environ) == before  # dask's nanny added SHTAERMAN_SWEEP_SCRATCH, OMP_...
