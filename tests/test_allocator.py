"""The command line's process keeps freed memory for its next arrays (shtaerman.allocator)."""

import os
import subprocess
import sys

import pytest

GLIBC = (getattr(os, "confstr", lambda _n: "")("CS_GNU_LIBC_VERSION") or "").startswith("glibc")

PROBE = """
import resource, sys
import numpy as np
if sys.argv[1] == "kept":
    from shtaerman.allocator import keep_freed_memory
    assert keep_freed_memory()
before = resource.getrusage(resource.RUSAGE_SELF).ru_minflt
for _ in range(10):
    block = np.ones(64 << 17)  # 64 MB, above glibc's largest dynamic mmap threshold (32 MB)
    del block
print(resource.getrusage(resource.RUSAGE_SELF).ru_minflt - before)
"""


def _faults(mode: str) -> int:
    run = subprocess.run([sys.executable, "-c", PROBE, mode], capture_output=True, text=True)
    assert run.returncode == 0, run.stderr
    return int(run.stdout)


@pytest.mark.skipif(not GLIBC, reason="glibc's mallopt only")
def test_freed_arrays_are_reused_without_faulting_their_pages_in_again():
    """Ten 64 MB arrays touched and freed in turn: glibc maps each afresh (16,384 pages each,
    163,840 faults); kept on the heap, only the first faults (16,384). A factor 4 leaves room for
    the interpreter's own faults and another kernel's page size."""
    assert _faults("kept") * 4 < _faults("default")


def test_the_console_script_keeps_freed_memory_before_it_runs_the_command_line(monkeypatch):
    """entry.main calls it: the CLI's process is ours to tune, a library import is not."""
    import signal

    from shtaerman import entry

    calls = []
    monkeypatch.setattr(entry, "keep_freed_memory", lambda: calls.append(1))
    monkeypatch.setattr(sys, "argv", ["shtaerman", "tables", "--help"])
    saved = {number: signal.getsignal(number) for number in (signal.SIGINT, signal.SIGTERM)}
    try:
        with pytest.raises(SystemExit):  # argparse's --help
            entry.main()
    finally:  # entry.main leaves both signals ignored, as the process exits
        for number, handler in saved.items():
            signal.signal(number, handler)
    assert calls == [1]
