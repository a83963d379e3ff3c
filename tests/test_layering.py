"""The package's layers import only downward (data flows one way; README "Layout").

theory -> paper -> fem -> study -> plots -> output -> cli: each layer may import the ones listed
for it and nothing else. A new upward import fails here, naming the file and the import.
"""

import ast
from pathlib import Path

import pytest

PACKAGE = Path(__file__).resolve().parents[1] / "src" / "shtaerman"
BASE = {"validation", "vocabulary", "version", "signals", "input_file", "allocator", "lazy"}
ALLOWED = {
    "theory": {"theory"},
    # the validity limits of a computed depth: measured with the exact theory's contact radius
    "guards": {"guards", "theory"},
    # the case, checked once: its parts' values (the theory's bodies and the FEM's rubber and
    # Prony inputs) and what combines; every layer above the FEM builds or reads one
    "problem": {"problem", "guards", "theory", "fem"},
    "paper": {"paper", "theory"},
    # fem: the FEM and the pure theory it is measured against (the dynamic run's scales come
    # from the exact impact and the Rayleigh wave speed)
    "fem": {
        "fem",
        "guards",
        "theory.materials",
        "theory.indenter",
        "theory.contact",
        "theory.impact",
        "theory.radiation",
        "theory.layer",
        "theory.viscoelastic",
        "theory.sneddon",  # the exact contact of any profile (the power law's included)
        "theory.profiles",
        "theory.prony_sources",  # a Prony series given as moduli, a CSV or a shipped name
        "theory.profile_impact",  # a profile's exact quasi-static impact sizes its FE impact
    },
    "study": {"study", "fem", "theory", "paper", "guards", "problem"},
    "plots": {"plots", "study", "fem", "theory", "paper", "problem"},
    "output": {"output", "plots", "study", "fem", "theory", "paper", "guards", "problem"},
    # sweeps orchestrate studies and write their own folder; only the CLI sits above them
    "sweep": {"sweep", "output", "plots", "study", "fem", "theory", "paper", "guards", "problem"}
    # one exception, named: a rubber impact case runs sh.dynamic itself (imported in the case,
    # not at load), so that a sweep row is the command line's numbers by construction
    | {"api.fem_dynamic"}
    # and an effects case runs sh.effects (the table of shtaerman effects), the same way
    | {"api.effect_table"}
    # a dynamic case fails on the command line's own checks (energy balance, reflections)
    | {"api.dynamic_result"}
    # an impact case runs sh.impact, so that its row carries the command line's validity
    # warning (x/a beyond small strain) by construction
    | {"api.quasi_static"}
    # sweep/cli.py, the sweep command's parser, declares --workers as verify's does (one
    # option builder from the vocabulary, its range in the help and the error)
    | {"cli.common"},
    # the public Python API stands beside the CLI: everything below it, not the CLI
    "api": {"api", "sweep", "output", "plots", "study", "fem", "theory", "paper", "guards"}
    | {"problem", "fitting"},
    # fitting a measurement is the API run backwards: it corrects its exact models by
    # sh.dynamic's FE runs, and sh.fit re-exports it (api/__init__ names it, nothing else)
    "fitting": {"fitting", "api", "output", "plots", "study", "fem", "theory", "paper", "guards"}
    | {"problem"},
}


def _imports(path: Path, root: Path = PACKAGE) -> list[str]:
    """Absolute shtaerman sub-module names imported by a source file (relative ones resolved)."""
    package = path.relative_to(root.parent).with_suffix("").parts[:-1]
    found = []
    for node in ast.walk(ast.parse(path.read_text(encoding="utf-8"))):
        if isinstance(node, ast.ImportFrom):
            if node.level:
                base = list(package[: len(package) - node.level + 1])
                module = ".".join(base + ([node.module] if node.module else []))
            else:
                module = node.module or ""
            names = [module] if node.module else [f"{module}.{a.name}" for a in node.names]
            found += names
        elif isinstance(node, ast.Import):
            found += [alias.name for alias in node.names]
    return [name.removeprefix("shtaerman.") for name in found if name.startswith("shtaerman.")]


def _allowed(layer: str, target: str) -> bool:
    permitted = ALLOWED[layer] | BASE
    return any(target == p or target.startswith(p + ".") for p in permitted)


@pytest.mark.parametrize("layer", sorted(ALLOWED))
def test_layer_imports_only_downward(layer):
    module = PACKAGE / f"{layer}.py"  # a layer of one module (problem, guards) or a package
    files = [module] if module.exists() else sorted((PACKAGE / layer).rglob("*.py"))
    assert files, f"layer {layer} has no modules"
    upward = [
        f"{path.relative_to(PACKAGE)} imports shtaerman.{target}"
        for path in files
        for target in _imports(path)
        if not _allowed(layer, target)
    ]
    assert upward == []


@pytest.mark.parametrize("module", sorted(BASE))
def test_base_modules_import_only_the_base(module):
    """The base (input checks and the vocabulary) sits under every layer: it imports none."""
    targets = _imports(PACKAGE / f"{module}.py")
    assert [t for t in targets if not any(t == b or t.startswith(b + ".") for b in BASE)] == []


def test_checker_sees_an_upward_import(tmp_path):
    """The checker itself can fail: an fem module importing a study is caught."""
    probe = tmp_path / "shtaerman" / "fem" / "probe.py"
    probe.parent.mkdir(parents=True)
    probe.write_text("from ..study.run import run_study\nfrom . import mesh\n")
    targets = _imports(probe, tmp_path / "shtaerman")
    assert targets == ["study.run", "fem.mesh"]
    assert not _allowed("fem", "study.run")
    assert _allowed("fem", "fem.mesh")


def _imported_names(path: Path) -> list[tuple[str, str]]:
    """(module, name) of every ``from shtaerman.X import name`` in a file (relative resolved)."""
    package = path.relative_to(PACKAGE.parent).with_suffix("").parts[:-1]
    found = []
    for node in ast.walk(ast.parse(path.read_text(encoding="utf-8"))):
        if isinstance(node, ast.ImportFrom) and node.level:
            base = list(package[: len(package) - node.level + 1])
            module = ".".join(base + ([node.module] if node.module else []))
            found += [(module.removeprefix("shtaerman."), a.name) for a in node.names]
    return found


def test_plots_only_read_results():
    """plots takes result types and constants from study and fem, never a function that
    computes (a FEM run, a fit, a study): CamelCase classes and UPPER_CASE names only."""
    computing = [
        f"{path.relative_to(PACKAGE)} imports {module}.{name}"
        for path in sorted((PACKAGE / "plots").rglob("*.py"))
        for module, name in _imported_names(path)
        if module.split(".")[0] in ("study", "fem")
        and not (name[:1].isupper() and (name.isupper() or "_" not in name))
    ]
    assert computing == []
