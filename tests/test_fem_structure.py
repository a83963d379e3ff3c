"""Structure of ``shtaerman.fem``: short functions, no private name shared across modules,
no history in the docstrings (one room per idea)."""

import ast
import re
from pathlib import Path

import pytest

FEM = Path(__file__).resolve().parents[1] / "src" / "shtaerman" / "fem"
MODULES = sorted(FEM.glob("*.py"))
MAX_BODY = 60
"""Most lines of a function body, docstring excluded."""


def _body_lines(node: ast.FunctionDef | ast.AsyncFunctionDef) -> int:
    body = node.body
    first = body[0]
    docstring = isinstance(first, ast.Expr) and isinstance(first.value, ast.Constant)
    if docstring and isinstance(first.value.value, str):
        if len(body) == 1:
            return 0
        first = body[1]
    return node.end_lineno - first.lineno + 1


def long_functions(source: str) -> list[str]:
    """Functions whose body (docstring excluded) exceeds ``MAX_BODY`` lines."""
    return [
        f"{node.name} ({_body_lines(node)} lines)"
        for node in ast.walk(ast.parse(source))
        if isinstance(node, ast.FunctionDef | ast.AsyncFunctionDef) and _body_lines(node) > MAX_BODY
    ]


def private_imports(source: str) -> list[str]:
    """``from .module import _name`` of a private name of another module."""
    return [
        f"{node.module}.{alias.name}"
        for node in ast.walk(ast.parse(source))
        if isinstance(node, ast.ImportFrom) and node.level
        for alias in node.names
        if alias.name.startswith("_")
    ]


@pytest.mark.parametrize("path", MODULES, ids=lambda p: p.name)
def test_no_function_body_over_60_lines(path):
    assert long_functions(path.read_text(encoding="utf-8")) == []


@pytest.mark.parametrize("path", MODULES, ids=lambda p: p.name)
def test_no_private_name_imported_across_modules(path):
    assert private_imports(path.read_text(encoding="utf-8")) == []


@pytest.mark.parametrize("path", MODULES, ids=lambda p: p.name)
def test_docstrings_carry_no_issue_numbers(path):
    # history belongs to the commits; measurements to benchmarks/FEM_NOTES.md
    assert re.findall(r"\bissue \d+", path.read_text(encoding="utf-8"), re.IGNORECASE) == []


def test_the_checks_can_fail():
    long = "def f():\n    '''doc'''\n" + "    x = 1\n" * 61
    assert long_functions(long) == ["f (61 lines)"]
    assert long_functions("def f():\n    '''doc'''\n" + "    x = 1\n" * 60) == []
    assert private_imports("from .contact import _contact_radius, edge_radius\n") == [
        "contact._contact_radius"
    ]
    assert private_imports("from .contact import edge_radius\n") == []
