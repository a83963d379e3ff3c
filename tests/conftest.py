"""Fixtures shared across test modules: one quick run of the shipped paper and Hertz studies.

The quick studies (coarse meshes, the paper's with its three coarsest convergence meshes) are
the suite's most expensive computation. They run once per session: ``quick_outcomes`` holds
their outcomes, and ``quick_verify`` runs ``shtaerman verify --quick`` end to end on the same
two study files, its ``run_study`` calls served from ``quick_outcomes`` (the identical study
and mode, checked, so the result folder is what a plain run writes).

Under pytest-xdist (``-n auto`` in pyproject.toml, at most two workers unless
``PYTEST_XDIST_AUTO_NUM_WORKERS`` or ``-n N`` says otherwise; ``-n 0`` runs in one process), each
worker computes the session and module fixtures its tests need (``quick_outcomes`` once for
all), on one BLAS thread unless
``OPENBLAS_NUM_THREADS`` (``OMP_``, ``MKL_``) asks for more. ``SHTAERMAN_TEST_ORDER=reversed``
runs the tests in the reverse of their collection order. CI's second pass does both (Makefile).
"""

import fcntl
import json
import os
import pickle
import signal
from pathlib import Path

if os.environ.get("PYTEST_XDIST_WORKER"):  # one BLAS/OpenMP thread per worker (before numpy),
    for _variable in ("OMP_NUM_THREADS", "OPENBLAS_NUM_THREADS", "MKL_NUM_THREADS"):  # unless asked
        os.environ.setdefault(f"SHTAERMAN_ASKED_{_variable}", os.environ.get(_variable, ""))
        os.environ.setdefault(_variable, "1")

import pytest
from headless import chromium, find_chromium

import shtaerman.output.folder
from shtaerman.cli import main
from shtaerman.study.contact.runner import StudyOutcome
from shtaerman.study.run import run_study
from shtaerman.study.schema import load_study, shipped_studies

QUICK_STUDIES = ("paper", "hertz")
BLAS_VARIABLES = {"openblas": "OPENBLAS_NUM_THREADS", "mkl": "MKL_NUM_THREADS"}
"""The variable that sets each BLAS's threads (``OMP_NUM_THREADS`` for any other)."""
TEST_ORDER = "SHTAERMAN_TEST_ORDER"
"""``reversed``: the reverse of the collection order, which swaps every pair of tests, so that a
test that depends on another having run before it fails in one of CI's two passes (a shuffle
swaps only half of the pairs, and needs a plugin)."""
AUTO_WORKERS = 2
"""Workers of ``-n auto``: measured on 2 cores; each worker holds its own FE runs in memory."""


@pytest.hookimpl(optionalhook=True)
def pytest_xdist_auto_num_workers(config) -> int | None:
    """``-n auto``: the available cores, at most :data:`AUTO_WORKERS` (None: a whole number in
    ``PYTEST_XDIST_AUTO_NUM_WORKERS`` decides, as pytest-xdist reads it)."""
    if os.environ.get("PYTEST_XDIST_AUTO_NUM_WORKERS", "").strip().isdigit():
        return None
    cores = len(os.sched_getaffinity(0)) if hasattr(os, "sched_getaffinity") else os.cpu_count()
    return max(1, min(AUTO_WORKERS, cores or 1))


def asked_blas_threads(internal_api: str) -> int | None:
    """The threads this process asks of a BLAS (``internal_api`` as threadpoolctl names it), or
    None: the library's own default."""
    variable = BLAS_VARIABLES.get(internal_api, "OMP_NUM_THREADS")
    value = os.environ.get(f"SHTAERMAN_ASKED_{variable}", os.environ.get(variable, "")).strip()
    if value.isdigit():
        return int(value)
    return 1 if os.environ.get("PYTEST_XDIST_WORKER") else None


def pytest_report_header(config) -> list[str]:
    """The BLAS threads the tests run on, and their order."""
    from threadpoolctl import threadpool_info

    workers = getattr(config.option, "numprocesses", None)
    lines = []
    for info in threadpool_info():
        if info["user_api"] != "blas":
            continue
        threads = info["num_threads"]  # this process's (the tests' own with -n 0)
        if workers:  # the workers': what was asked, else 1 (set above before numpy loads)
            threads = asked_blas_threads(info["internal_api"]) or 1
        where = "per xdist worker" if workers else "in this process"
        lines.append(
            f"BLAS threads: {threads} {where} ({info['internal_api']} {info['version']}, "
            f"{info.get('architecture')})"
        )
    order = os.environ.get(TEST_ORDER) or "collection"
    return [*lines, f"test order: {order} ({TEST_ORDER})"]


def pytest_configure(config) -> None:
    """Refuse an unknown ``SHTAERMAN_TEST_ORDER`` before any test is collected, and deliver
    SIGINT as a terminal does: a shell's background job (``pytest ... &``, nohup) starts with
    SIGINT ignored, which Python, its xdist workers and every subprocess inherit, and the
    interrupt tests then see a run that rightly ignores their Ctrl-C (exit 0, not 130)."""
    order = os.environ.get(TEST_ORDER, "")
    if order not in ("", "reversed"):
        raise pytest.UsageError(f"{TEST_ORDER}: 'reversed' or unset, not {order!r}")
    if signal.getsignal(signal.SIGINT) == signal.SIG_IGN:
        signal.signal(signal.SIGINT, signal.default_int_handler)


def pytest_collection_modifyitems(config, items) -> None:
    """Reverse the tests when ``SHTAERMAN_TEST_ORDER=reversed`` (each xdist worker collects
    the same reversed list, so they agree)."""
    if os.environ.get(TEST_ORDER) == "reversed":
        items.reverse()


def quick_study_files() -> list[str]:
    """Paths of the shipped paper and Hertz study files."""
    return [str(p) for p in shipped_studies() if p.stem in QUICK_STUDIES]


@pytest.fixture(scope="session")
def quick_outcomes(tmp_path_factory, worker_id) -> dict[str, StudyOutcome]:
    """The paper and Hertz studies run with ``quick=True``, by study name: once per session,
    shared by the xdist workers through a pickle in their common temporary folder (the first
    computes it under a lock, the others read it: ~60 CPU s each)."""
    if worker_id == "master":  # not under xdist
        return _quick_outcomes()
    shared = tmp_path_factory.getbasetemp().parent / "quick_outcomes.pickle"
    with open(shared.with_suffix(".lock"), "w") as lock:
        fcntl.flock(lock, fcntl.LOCK_EX)  # released when the file closes
        if shared.is_file():
            return pickle.loads(shared.read_bytes())
        outcomes = _quick_outcomes()
        temporary = shared.with_suffix(".partial")
        temporary.write_bytes(pickle.dumps(outcomes))
        temporary.replace(shared)
        return outcomes


def _quick_outcomes() -> dict[str, StudyOutcome]:
    studies = [study for path in quick_study_files() for study in load_study(path)]
    return {study.name: run_study(study, quick=True) for study in studies}


@pytest.fixture(scope="session")
def quick_outcome(quick_outcomes) -> StudyOutcome:
    """The paper study's quick outcome (about 5k dofs)."""
    return quick_outcomes["paper"]


@pytest.fixture(scope="session")
def quick_verify(quick_outcomes, tmp_path_factory) -> tuple[int, Path, dict]:
    """``shtaerman verify --quick --out DIR paper.toml hertz.toml``: (exit code, DIR, results).

    Files, figures and reports are written as in any run; the two studies' computations are
    taken from :func:`quick_outcomes` (each served once, for exactly the study it was run for).
    """
    served = []

    def cached_run_study(study, *, quick=False, progress=None):
        outcome = quick_outcomes.get(study.name)
        if quick and outcome is not None and outcome.study == study:
            served.append(study.name)
            return outcome
        return run_study(study, quick=quick, progress=progress)

    out = tmp_path_factory.mktemp("verify") / "run"
    with pytest.MonkeyPatch.context() as patch:
        patch.setattr(shtaerman.output.folder, "run_study", cached_run_study)
        code = main(
            ["verify", "--quick", "--workers", "1", "--out", str(out), *quick_study_files()]
        )
    assert sorted(served) == sorted(QUICK_STUDIES)
    return code, out, json.loads((out / "results.json").read_text())


@pytest.fixture(scope="session")
def browser(tmp_path_factory):
    """A function running headless Chromium, with no network, with the given arguments; it
    returns the browser's stdout (tests/headless.py).

    Session-scoped so that, without a browser, the tests skip before any costly fixture runs.
    """
    found = find_chromium()
    if found is None:
        pytest.skip("no Chromium on PATH: install Debian's 'chromium' (.ci/run does so)")
    return chromium(found, tmp_path_factory.mktemp("chromium-profile"))


@pytest.fixture
def steps_six_and_seven_fail(monkeypatch) -> None:
    """The finite-strain impact with inertia fails its 6th and 7th step attempts (an inverted
    element): the 6th step and its first half, so the run cuts it to quarter, quarter, half."""
    import shtaerman.fem.stepper as stepper
    from shtaerman.fem.hyperelastic import NewtonError

    calls, step = [], stepper._dynamic_step

    def failing(*args):
        calls.append(None)
        if len(calls) in (6, 7):
            raise NewtonError("an element inverted (J <= 0)")
        return step(*args)

    monkeypatch.setattr(stepper, "_dynamic_step", failing)
