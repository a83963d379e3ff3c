"""The command line's process keeps freed memory for its next arrays (shtaerman.allocator)."""

import os
import subprocess
import sys

import pytest

GLIBC = (getattr(os, "confstr", lambda _n: "")("CS_GNU_LIBC_VERSION") or "").startswith("glibc")

PROBE = """
import sys
import numpy as np
if sys.argv[1] == "kept":
    from shtaerman.allocator import keep_freed_memory
    assert keep_freed_memory()
pages = lambda: int(open("/proc/self/statm").read().split()[1])
before = pages()
block = np.ones(64 << 17)  # 64 MB, above glibc's largest dynamic mmap threshold (32 MB)
del block
print((pages() - before) * 4096 >> 20)
"""


def _resident_after_free(mode: str) -> int:
    """MB still resident after a 64 MB array was touched and freed."""
    run = subprocess.run([sys.executable, "-c", PROBE, mode], capture_output=True, text=True)
    assert run.returncode == 0, run.stderr
    return int(run.stdout)


@pytest.mark.skipif(not GLIBC or not os.path.exists("/proc/self/statm"), reason="glibc, Linux")
def test_a_freed_array_stays_with_the_process_for_the_next():
    """glibc maps a 64 MB array afresh and unmaps it when it is freed (nothing stays
    resident); kept, its 64 MB stay on the heap for the next arrays. Resident pages, not page
    faults: with transparent huge pages a 64 MB array faults 32 times or 16,384 times."""
    assert _resident_after_free("default") < 8
    assert _resident_after_free("kept") >= 56


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
