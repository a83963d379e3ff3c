"""The tests run on the BLAS threads they ask for: CI's second pass asks for two (Makefile), and
its header line (tests/conftest.py) must not claim threads that the computation does not use."""

import os

import pytest
from conftest import asked_blas_threads
from threadpoolctl import threadpool_info


def test_blas_runs_on_the_threads_asked():
    cores = len(os.sched_getaffinity(0)) if hasattr(os, "sched_getaffinity") else os.cpu_count()
    blas = [info for info in threadpool_info() if info["user_api"] == "blas"]
    assert blas, "numpy and scipy load a BLAS"
    checked = 0
    for info in blas:
        asked = asked_blas_threads(info["internal_api"])
        if asked is None:
            continue  # -n 0 and nothing asked: the library's default
        # a BLAS gives no more threads than cores; beyond them, at most what was asked
        assert (
            info["num_threads"] == asked if asked <= (cores or 1) else info["num_threads"] <= asked
        ), info
        checked += 1
    if not checked:
        pytest.skip("no BLAS thread count asked (one process, no *_NUM_THREADS set)")
