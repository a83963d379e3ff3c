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
LIGHT_FEM = (
    "shtaerman.fem",
    "shtaerman.fem.mesh",
    "shtaerman.fem.impact_limits",
    "shtaerman.fem.impact_run",
)
"""The FEM modules the parsers read constants from (mesh defaults, step limits, result keys):
numpy and the standard library only, gmsh and scikit-fem imported where they mesh."""
PARSING = [
    ["--help"],
    *([name, "--help"] for name in ("impact", "contact", "dynamic", "effects", "fit", "sweep")),
    *([name, "--help"] for name in ("verify", "validate", "init-study", "prony-plot", "tables")),
    ["impact", "--mass", "-1"],
    ["contact", "--E2", "0"],
    ["dynamic", "--time-steps", "1"],
]
"""Calls the parser ends (help: exit code 0; a refused input: 2)."""
SCIPY = ("scipy.special", "scipy.optimize", "scipy.interpolate", "scipy.integrate")
"""What the parsing calls need neither (0.3-0.5 s of CPU; the exact impact needs them)."""
COMPUTING = [["tables"], ["impact"], ["impact", "--json"]]
"""Calls of the exact models, run after :data:`PARSING`."""
PROBE = """\
import contextlib, io, json, sys
from shtaerman.cli import main
heavy, light, commands = json.loads(sys.argv[1])
heavy = tuple(heavy)
found = []
for argv in commands:
    with contextlib.redirect_stdout(io.StringIO()), contextlib.redirect_stderr(io.StringIO()):
        try:
            code = main(argv)
        except SystemExit as stop:
            code = stop.code
    loaded = [m for m in sys.modules if m.startswith(heavy)]
    loaded += [m for m in sys.modules if m.startswith("shtaerman.fem.") and m not in light]
    found.append([argv, code, sorted(loaded)])
print(json.dumps(found))
"""


def _probe(heavy: tuple[str, ...], commands: list[list[str]]) -> list:
    """[argv, exit code, the heavy modules loaded after it] of each call, run in order in one
    fresh interpreter (the test session has imported everything)."""
    arguments = json.dumps([heavy, sorted(LIGHT_FEM), commands])
    done = subprocess.run(
        [sys.executable, "-c", PROBE, arguments], capture_output=True, text=True, check=False
    )
    assert done.returncode == 0, done.stderr
    found = json.loads(done.stdout)
    assert [argv for argv, _, _ in found] == commands
    return found


def test_the_parsers_the_exact_impact_and_a_refusal_load_no_fem():
    """Each call's exit code is the expected one (so it ran: help 0, a refusal 2, the exact
    models 0), and after it none of :data:`HEAVY` (a prefix: its submodules too), nor an FEM
    module outside :data:`LIGHT_FEM`, is loaded; after the parsing calls, no :data:`SCIPY`."""
    found = _probe((*HEAVY, *SCIPY), PARSING)
    assert [code for _, code, _ in found] == [0] * 12 + [2, 2, 2]
    assert [(argv, loaded) for argv, _, loaded in found if loaded] == []
    found = _probe(HEAVY, PARSING + COMPUTING)
    assert [code for _, code, _ in found] == [0] * 12 + [2, 2, 2] + [0, 0, 0]
    assert [(argv, loaded) for argv, _, loaded in found if loaded] == []
