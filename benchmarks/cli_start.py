"""CPU cost of starting the command line: a fresh ``python -m shtaerman ...`` per command.

Run: python benchmarks/cli_start.py [--repeat 3]. For each command (the top-level help, the
exact impact, the paper's tables, a subcommand's help, a refused input) prints the CPU seconds
(user + system, of the child process, best of ``--repeat``) and their ratio to a fresh
``python -c "import numpy, scipy.sparse"`` measured in the same run: the ratio is what moves
when the imports change, the seconds move with the machine's load (printed beside them). CPU,
not wall time: on a shared machine the wall time measures the neighbours.
"""

from __future__ import annotations

import argparse
import os
import resource
import subprocess
import sys

COMMANDS = (
    ("--help",),
    ("impact",),
    ("tables",),
    ("contact", "--help"),
    ("impact", "--mass", "-1"),
)
"""The commands timed (each a fresh process)."""
BASELINE = ("-c", "import numpy, scipy.sparse")
"""The floor every command pays: the numerical stack's import."""


def cpu_seconds(arguments: tuple[str, ...]) -> float:
    """CPU seconds (user + system) of one fresh ``python ARGUMENTS`` child process."""
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    subprocess.run(
        [sys.executable, *arguments], stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL
    )
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    return (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)


def best(arguments: tuple[str, ...], repeat: int) -> float:
    """The least CPU seconds of ``repeat`` runs (the others paid for neighbours' cache misses)."""
    return min(cpu_seconds(arguments) for _ in range(repeat))


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeat", type=int, default=3, help="runs per command (default 3)")
    repeat = parser.parse_args().repeat
    floor = best(BASELINE, repeat)
    print(f"load average {os.getloadavg()[0]:.2f}; baseline 'import numpy, scipy.sparse': "
          f"{floor:.2f} CPU s (best of {repeat})")  # fmt: skip
    print(f"{'command':<28} {'CPU s':>6} {'ratio':>6}  load")
    for command in COMMANDS:
        seconds = best(("-m", "shtaerman", *command), repeat)
        line = f"{' '.join(command):<28} {seconds:6.2f} {seconds / floor:6.2f}"
        print(f"{line}  {os.getloadavg()[0]:.2f}")


if __name__ == "__main__":
    main()
