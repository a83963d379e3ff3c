"""The console script's entry (src/shtaerman/entry.py): a SIGINT or SIGTERM that arrives while
the command line is still being imported (about a second of numpy, scipy, dask) stops the run
with the usual line and exit code, not a traceback or a silent kill (issue 31, items 5-6)."""

import subprocess
import sys

import pytest

PROBE = """
import os, signal, sys
import shtaerman.entry as entry

class SignalDuringImport:  # sends the signal as the command line starts to be imported
    def find_spec(self, name, path, target=None):
        if name == "shtaerman.cli":
            os.kill(os.getpid(), signal.{name})
        return None

sys.meta_path.insert(0, SignalDuringImport())
sys.argv = ["shtaerman", "impact", "--json"]
sys.exit(entry.main())
"""


@pytest.mark.parametrize(
    ("name", "code", "word"), [("SIGINT", 130, "interrupted"), ("SIGTERM", 143, "terminated")]
)
def test_a_signal_during_the_import_stops_the_run_cleanly(name, code, word):
    run = subprocess.run(
        [sys.executable, "-c", PROBE.replace("{name}", name)], capture_output=True, text=True
    )
    assert run.returncode == code, run.stderr
    assert run.stdout == ""  # the impact never ran
    assert (
        run.stderr
        == f"shtaerman: {word}; every output is complete or absent (nothing partial is kept)\n"
    )


def test_the_entry_runs_the_command_line():
    run = subprocess.run(
        [sys.executable, "-m", "shtaerman", "impact", "--json"], capture_output=True, text=True
    )
    assert run.returncode == 0 and '"x_c"' in run.stdout


def test_an_ignored_signal_stays_ignored():
    """A '&' job ignores SIGINT: the entry must not turn it into a stop."""
    probe = PROBE.replace("{name}", "SIGINT").replace(
        "import shtaerman.entry as entry",
        "signal.signal(signal.SIGINT, signal.SIG_IGN)\nimport shtaerman.entry as entry",
    )
    run = subprocess.run([sys.executable, "-c", probe], capture_output=True, text=True)
    assert run.returncode == 0 and '"x_c"' in run.stdout, run.stderr


AFTER = """
import os, signal, sys
import shtaerman.cli as cli
import shtaerman.entry as entry

run = cli.main

def run_then_signal(argv=None):
    code = run(["impact", "--json"])
    os.kill(os.getpid(), signal.{name})  # the instant after the command line handed back
    return code

cli.main = run_then_signal
sys.exit(entry.main())
"""


@pytest.mark.parametrize(
    ("name", "code", "word"), [("SIGINT", 130, "interrupted"), ("SIGTERM", 143, "terminated")]
)
def test_a_signal_right_after_the_last_output_stops_cleanly(name, code, word):
    """A signal just after the run used to meet the default handler: a KeyboardInterrupt
    traceback, or a silent death by SIGTERM (-15)."""
    run = subprocess.run(
        [sys.executable, "-c", AFTER.replace("{name}", name)], capture_output=True, text=True
    )
    assert run.returncode == code, run.stderr
    assert '"x_c"' in run.stdout  # the run's output is complete
    assert (
        run.stderr
        == f"shtaerman: {word}; every output is complete or absent (nothing partial is kept)\n"
    )
