"""The CLI's standard streams: a closed stdout, a quitting stdout reader, a quitting FIFO reader."""

import os
import subprocess
import sys
import threading

import pytest

CLI = [sys.executable, "-m", "shtaerman"]


def test_closed_stdout_is_refused_before_anything_runs(tmp_path):
    """Started with '>&-', every result would vanish with exit 0: refuse with one line."""
    history = tmp_path / "h.csv"
    done = subprocess.run(
        [*CLI, "impact", "--history", str(history)],
        stdout=subprocess.DEVNULL,
        stderr=subprocess.PIPE,
        text=True,
        preexec_fn=lambda: os.close(1),
        check=False,
    )
    assert done.returncode == 2
    assert done.stderr.strip().splitlines() == [
        "shtaerman: error: standard output is closed; redirect it to a file or to /dev/null "
        "(e.g. '> run.log')"
    ]
    assert not history.exists()  # refused before computing or writing anything


def test_stdout_reader_quitting_is_a_quiet_success():
    """'shtaerman impact | head -c 1' stops quietly with exit 0, as Unix tools do."""
    process = subprocess.Popen(
        [*CLI, "impact", "--json"], stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True
    )
    process.stdout.close()  # the reader is gone before the first write
    stderr = process.stderr.read()
    assert process.wait(timeout=120) == 0
    assert stderr == ""


@pytest.mark.skipif(not hasattr(os, "mkfifo"), reason="needs POSIX FIFOs")
def test_history_fifo_reader_quitting_is_a_failure(tmp_path):
    """A --history FIFO whose reader quits early loses the history: exit 1, one line."""
    fifo = tmp_path / "h.csv"
    os.mkfifo(fifo)

    def read_ten_bytes() -> None:
        with open(fifo, "rb") as reader:
            reader.read(10)

    reader = threading.Thread(target=read_ten_bytes)
    reader.start()
    done = subprocess.run(
        [*CLI, "impact", "--history", str(fifo), "--points", "100000"],
        capture_output=True,
        text=True,
        timeout=120,
        check=False,
    )
    reader.join(timeout=10)
    assert done.returncode == 1
    assert done.stdout == ""
    assert "the reader of an output pipe quit before the output was complete" in done.stderr
    assert len(done.stderr.strip().splitlines()) == 1
