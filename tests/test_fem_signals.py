"""SIGTERM across the METIS ordering, whose C code traps it (:mod:`shtaerman.signals`)."""

import ctypes
import signal
import sys

import numpy as np
import pymetis
import pytest
import scipy.sparse as sp

from shtaerman.fem.solver import factorize_scaled, nested_dissection

N = 30
PATTERN = sp.diags([1.0] * 4, [-N, -1, 1, N], shape=(N * N, N * N), format="csr")
GROUPS = np.arange(N * N)

pytestmark = pytest.mark.skipif(not hasattr(signal, "pthread_sigmask"), reason="no signal masks")


class _Stop(BaseException):
    pass


def _stop(signum, frame):
    raise _Stop


@pytest.fixture
def sigterm_handler():
    """Install a SIGTERM handler for the test; the handler and the mask are restored after."""
    previous = signal.getsignal(signal.SIGTERM)
    mask = signal.pthread_sigmask(signal.SIG_BLOCK, [])
    yield lambda handler: signal.signal(signal.SIGTERM, handler)
    signal.signal(signal.SIGTERM, previous)
    signal.pthread_sigmask(signal.SIG_SETMASK, mask)


def _metis(monkeypatch, blocks: bool) -> list[int]:
    """pymetis whose first call fails as METIS does when a SIGTERM lands in it.

    GKlib's own C handler takes the signal (Python's never runs) and jumps out of the ordering,
    leaving SIGTERM blocked in the thread; pymetis then raises. Later calls are METIS's.
    (Letting a real SIGTERM land in METIS also hangs or aborts now and then; not for a test.)
    """
    real, calls = pymetis.nested_dissection, []

    def failing_once(*args, **kwargs):
        calls.append(1)
        if len(calls) > 1:
            return real(*args, **kwargs)
        if blocks:
            signal.pthread_sigmask(signal.SIG_BLOCK, [signal.SIGTERM])
        raise RuntimeError("Caught an unknown exception!")

    monkeypatch.setattr(pymetis, "nested_dissection", failing_once)
    return calls


def test_a_sigterm_caught_by_metis_reaches_a_handler_that_raises(monkeypatch, sigterm_handler):
    # the CLI's handler: it had never run, and the CLI exited 1 with pymetis's RuntimeError
    _metis(monkeypatch, blocks=True)
    sigterm_handler(_stop)
    with pytest.raises(_Stop):
        nested_dissection(PATTERN, GROUPS)
    assert signal.SIGTERM not in signal.pthread_sigmask(signal.SIG_BLOCK, [])


def test_after_a_handler_that_returns_the_ordering_is_made_again(monkeypatch, sigterm_handler):
    seen = []
    calls = _metis(monkeypatch, blocks=True)
    sigterm_handler(lambda signum, frame: seen.append(signum))
    order = nested_dissection(PATTERN, GROUPS)
    assert seen == [signal.SIGTERM]
    assert len(calls) == 2
    np.testing.assert_array_equal(np.sort(order), GROUPS)
    assert signal.SIGTERM not in signal.pthread_sigmask(signal.SIG_BLOCK, [])


def test_the_dynamic_solvers_fallback_does_not_swallow_the_sigterm(monkeypatch, sigterm_handler):
    # it falls back to SuperLU on a RuntimeError: the SIGTERM was lost and the run went on
    _metis(monkeypatch, blocks=True)
    sigterm_handler(_stop)
    with pytest.raises(_Stop):
        factorize_scaled((PATTERN + 4.0 * sp.eye(N * N)).tocsc(), GROUPS, 1e-6)


def test_other_metis_failures_are_not_taken_for_a_sigterm(monkeypatch, sigterm_handler):
    _metis(monkeypatch, blocks=False)
    sigterm_handler(_stop)
    with pytest.raises(RuntimeError, match="unknown exception"):
        nested_dissection(PATTERN, GROUPS)


class _SigAction(ctypes.Structure):
    """glibc's struct sigaction on Linux (sigset_t: 1024 bits)."""

    _fields_ = (
        ("handler", ctypes.c_void_p),
        ("mask", ctypes.c_ubyte * 128),
        ("flags", ctypes.c_int),
        ("restorer", ctypes.c_void_p),
    )


def _sigterm_flags() -> int:
    action = _SigAction()
    assert ctypes.CDLL(None).sigaction(signal.SIGTERM, None, ctypes.byref(action)) == 0
    return action.flags


@pytest.mark.skipif(sys.platform != "linux", reason="reads glibc's struct sigaction")
def test_metis_leaves_the_sigterm_handler_as_python_installed_it(sigterm_handler):
    # GKlib put the handler back with signal(), which adds SA_RESTART: a SIGTERM no longer
    # interrupted a blocking read, and Python's handler waited for the read to end
    sigterm_handler(_stop)
    before = _sigterm_flags()
    nested_dissection(PATTERN, GROUPS)
    assert _sigterm_flags() == before
