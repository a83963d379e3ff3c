"""The package's code shape: no import cycle, no private name imported across modules, and no
function body over 60 lines, anywhere in ``src/shtaerman``.

Imports are read from the source (``ast``), wherever they stand: module level, inside a function
or under ``if TYPE_CHECKING:``. Each checker has a probe that shows it can fail.
"""

from __future__ import annotations

import ast
from pathlib import Path

PACKAGE = Path(__file__).resolve().parents[1] / "src" / "shtaerman"
MAX_BODY_LINES = 60


def _module_name(path: Path, root: Path) -> str:
    """Dotted name of a source file under ``root`` (``pkg/__init__.py`` is ``pkg``)."""
    parts = path.relative_to(root.parent).with_suffix("").parts
    return ".".join(parts[:-1] if parts[-1] == "__init__" else parts)


def _modules(root: Path) -> dict[str, Path]:
    return {_module_name(path, root): path for path in sorted(root.rglob("*.py"))}


def _imports(path: Path, root: Path, modules: dict[str, Path]) -> list[tuple[str, str | None]]:
    """(module, name) pairs a file imports from its own package; ``name`` is None for a plain
    ``import a.b``, and a submodule imported by ``from pkg import sub`` is its own module."""
    here = _module_name(path, root)
    package = here if path.name == "__init__.py" else here.rpartition(".")[0]
    top = root.name
    found: list[tuple[str, str | None]] = []
    for node in ast.walk(ast.parse(path.read_text(encoding="utf-8"))):
        if isinstance(node, ast.Import):
            found += [(a.name, None) for a in node.names if a.name.split(".")[0] == top]
        elif isinstance(node, ast.ImportFrom):
            if node.level:
                base = package.split(".")[: len(package.split(".")) - node.level + 1]
                module = ".".join(base + ([node.module] if node.module else []))
            else:
                module = node.module or ""
            if module.split(".")[0] != top:
                continue
            for alias in node.names:
                sub = f"{module}.{alias.name}"
                found.append((sub, None) if sub in modules else (module, alias.name))
    return found


def _graph(root: Path) -> dict[str, set[str]]:
    """Module -> the package modules it imports (itself excluded)."""
    modules = _modules(root)
    return {
        name: {target for target, _ in _imports(path, root, modules) if target != name}
        for name, path in modules.items()
    }


def _cycles(graph: dict[str, set[str]]) -> list[list[str]]:
    """The strongly connected components with more than one module (Tarjan), each sorted."""
    index: dict[str, int] = {}
    low: dict[str, int] = {}
    stack: list[str] = []
    on_stack: set[str] = set()
    found: list[list[str]] = []

    def visit(node: str) -> None:
        index[node] = low[node] = len(index)
        stack.append(node)
        on_stack.add(node)
        for target in sorted(graph.get(node, ())):
            if target not in index:
                visit(target)
                low[node] = min(low[node], low[target])
            elif target in on_stack:
                low[node] = min(low[node], index[target])
        if low[node] == index[node]:
            component = []
            while True:
                member = stack.pop()
                on_stack.discard(member)
                component.append(member)
                if member == node:
                    break
            if len(component) > 1:
                found.append(sorted(component))

    for node in sorted(graph):
        if node not in index:
            visit(node)
    return sorted(found)


def _is_private(name: str) -> bool:
    return name.startswith("_") and not (name.startswith("__") and name.endswith("__"))


def _private_imports(root: Path) -> list[str]:
    """``file imports module._name`` for every private name taken from another module."""
    modules = _modules(root)
    found = []
    for name, path in modules.items():
        for module, imported in _imports(path, root, modules):
            target = imported if imported is not None else module.rpartition(".")[2]
            if module != name and _is_private(target):
                found.append(f"{path.relative_to(root)} imports {module}.{imported or ''}")
    return found


def _body_lines(function: ast.FunctionDef | ast.AsyncFunctionDef) -> int:
    """Lines from the first statement after the docstring to the end of the body."""
    body = function.body
    first = body[0]
    if (
        len(body) > 1
        and isinstance(first, ast.Expr)
        and isinstance(first.value, ast.Constant)
        and isinstance(first.value.value, str)
    ):
        body = body[1:]
    return body[-1].end_lineno - body[0].lineno + 1


def _long_functions(root: Path, limit: int = MAX_BODY_LINES) -> list[str]:
    """``file:function (lines)`` for every function whose body exceeds ``limit`` lines."""
    found = []
    for path in sorted(root.rglob("*.py")):
        for node in ast.walk(ast.parse(path.read_text(encoding="utf-8"))):
            if isinstance(node, ast.FunctionDef | ast.AsyncFunctionDef):
                lines = _body_lines(node)
                if lines > limit:
                    found.append(f"{path.relative_to(root)}:{node.name} ({lines})")
    return found


def test_no_import_cycle():
    assert _cycles(_graph(PACKAGE)) == []


def test_no_private_name_imported_across_modules():
    assert _private_imports(PACKAGE) == []


def test_no_function_body_over_60_lines():
    assert _long_functions(PACKAGE) == []


def _write(root: Path, files: dict[str, str]) -> Path:
    for name, text in files.items():
        path = root / "shtaerman" / name
        path.parent.mkdir(parents=True, exist_ok=True)
        path.write_text(text, encoding="utf-8")
    return root / "shtaerman"


def test_cycle_checker_sees_type_checking_and_function_imports(tmp_path):
    """A cycle closed only under TYPE_CHECKING, or only inside a function, is still a cycle."""
    root = _write(
        tmp_path,
        {
            "__init__.py": "",
            "study/__init__.py": "",
            "study/a.py": "from typing import TYPE_CHECKING\nif TYPE_CHECKING:\n"
            "    from .b import B\n",
            "study/b.py": "from . import a\n",
            "study/c.py": "def f():\n    from shtaerman.study.d import g\n",
            "study/d.py": "import shtaerman.study.c\n",
            "study/e.py": "from . import a, b\n",
        },
    )
    assert _cycles(_graph(root)) == [
        ["shtaerman.study.a", "shtaerman.study.b"],
        ["shtaerman.study.c", "shtaerman.study.d"],
    ]


def test_private_import_checker_sees_private_names(tmp_path):
    """``_name`` from another module is caught; dunders, aliases and own names are not."""
    root = _write(
        tmp_path,
        {
            "__init__.py": "__version__ = '0'\n",
            "plots/__init__.py": "",
            "plots/a.py": "def _helper(): ...\ndef public(): ...\n",
            "plots/b.py": "from .a import public as _public\nfrom .. import __version__\n"
            "def f():\n    from .a import _helper\n",
        },
    )
    assert _private_imports(root) == ["plots/b.py imports shtaerman.plots.a._helper"]


def test_length_checker_counts_the_body_after_the_docstring(tmp_path):
    """The docstring is not counted; 60 body lines pass and 61 fail."""
    body = "".join(f"    x{i} = {i}\n" for i in range(60))
    text = (
        f'def fits():\n    """Doc."""\n{body}'
        f'def too_long():\n    """Doc\n    on two lines."""\n{body}    return x0\n'
    )
    root = _write(tmp_path, {"long.py": text})
    assert _long_functions(root) == ["long.py:too_long (61)"]


TESTS = Path(__file__).resolve().parent
LEFT_TEST_IMPORTS = {"test_finite_friction.py": {"test_finite_bonded"}}
"""Test modules that still import another (its helpers belong in a helper module): the
finite-strain friction tests, which the friction work of the impact is changing."""


def _test_module_imports(folder: Path) -> dict[str, set[str]]:
    """File name -> the test modules (``test_*``) it imports, for each ``test_*.py`` there."""
    found: dict[str, set[str]] = {}
    for path in sorted(folder.glob("test_*.py")):
        names = set()
        for node in ast.walk(ast.parse(path.read_text(), str(path))):
            if isinstance(node, ast.ImportFrom) and node.module:
                names.add(node.module)
            elif isinstance(node, ast.Import):
                names |= {alias.name for alias in node.names}
        imported = {name for name in names if name.split(".")[-1].startswith("test_")}
        if imported:
            found[path.name] = imported
    return found


def test_no_test_module_imports_another():
    """Shared test helpers live in helper modules (figure_helpers, study_texts, ...): a test
    module imported by another has its tests collected twice and ties the two together."""
    assert _test_module_imports(TESTS) == LEFT_TEST_IMPORTS


def test_test_import_checker_sees_an_imported_test_module(tmp_path):
    (tmp_path / "test_a.py").write_text("from test_b import helper\nimport figure_helpers\n")
    (tmp_path / "test_b.py").write_text("def helper(): ...\n")
    assert _test_module_imports(tmp_path) == {"test_a.py": {"test_b"}}
