"""The command line starts without the FEM: its parsers, the exact impact and a refused input
import none of the heavy modules (benchmarks/cli_start.py: ~1 s of CPU a call less)."""

import json
import subprocess
import sys

HEAVY = (
    "skfem",
    "gmsh",
    "meshio",
    "matplotlib",
    "pyvista",
    "vtkmodules",
    "dask",
    "distributed",
    "scipy.stats",
    "shtaerman.sweep.engine",
    "shtaerman.fitting.run",
)
"""Modules no parser, no exact impact and no refusal needs (each costs 0.1-1.4 s of CPU)."""
LIGHT_FEM = {"shtaerman.fem", "shtaerman.fem.mesh", "shtaerman.fem.impact_limits"}
LIGHT_FEM |= {"shtaerman.fem.impact_run"}
"""The FEM modules the parsers read constants from (mesh defaults, step limits, result keys):
numpy and the standard library only, gmsh and scikit-fem imported where they mesh."""
COMMANDS = [
    ["--help"],
    *([name, "--help"] for name in ("impact", "contact", "dynamic", "effects", "fit", "sweep")),
    *([name, "--help"] for name in ("verify", "validate", "init-study", "prony-plot", "tables")),
    ["impact"],
    ["impact", "--json"],
    ["tables"],
    ["impact", "--mass", "-1"],
    ["contact", "--E2", "0"],
    ["dynamic", "--time-steps", "1"],
]
"""The calls checked, in one fresh interpreter: what each loads is checked after it."""
PROBE = """\
import contextlib, io, json, sys
from shtaerman.cli import main
heavy, light, commands = json.loads(sys.argv[1])
found = []
for argv in commands:
    with contextlib.redirect_stdout(io.StringIO()), contextlib.redirect_stderr(io.StringIO()):
        try:
            code = main(argv)
        except SystemExit as stop:
            code = stop.code
    loaded = [m for m in sys.modules if m.split(".")[0] in heavy or m in heavy]
    loaded += [m for m in sys.modules if m.startswith("shtaerman.fem.") and m not in light]
    found.append([argv, code, sorted(loaded)])
print(json.dumps(found))
"""


def test_the_parsers_the_exact_impact_and_a_refusal_load_no_fem():
    """Each call's exit code is the expected one (so the call ran: help 0, impact 0, refusal
    2) and after it none of :data:`HEAVY`, nor an FEM module outside :data:`LIGHT_FEM`, is
    loaded. A fresh interpreter: the test session has imported everything."""
    arguments = json.dumps([HEAVY, sorted(LIGHT_FEM), COMMANDS])
    done = subprocess.run(
        [sys.executable, "-c", PROBE, arguments], capture_output=True, text=True, check=False
    )
    assert done.returncode == 0, done.stderr
    found = json.loads(done.stdout)
    assert [argv for argv, _, _ in found] == COMMANDS
    assert [code for _, code, _ in found] == [0] * 15 + [2, 2, 2]
    assert [(argv, loaded) for argv, _, loaded in found if loaded] == []
