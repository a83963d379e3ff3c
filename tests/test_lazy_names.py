"""The packages that import their names on first use (shtaerman, shtaerman.api,
shtaerman.sweep; see shtaerman/lazy.py) list each name twice: in the ``if TYPE_CHECKING:``
imports that type checkers and the docs read, and in the table the lazy ``__getattr__``
imports from. The two lists must agree, name for name and module for module."""

import ast
import importlib
from pathlib import Path

import pytest

PACKAGE = Path(__file__).resolve().parents[1] / "src" / "shtaerman"


def type_checking_imports(source: str) -> dict[str, str]:
    """{name: module} of the ``from M import name`` under ``if TYPE_CHECKING:``, the module
    written relative as in the source (``..problem``, ``.spec``)."""
    found = {}
    for node in ast.walk(ast.parse(source)):
        if isinstance(node, ast.If) and ast.unparse(node.test) == "TYPE_CHECKING":
            for statement in node.body:
                assert isinstance(statement, ast.ImportFrom), ast.unparse(statement)
                home = "." * statement.level + (statement.module or "")
                found |= {alias.name: home for alias in statement.names}
    return found


def homes_of(table: dict[str, tuple[str, ...]]) -> dict[str, str]:
    return {name: home for home, names in table.items() for name in names}


@pytest.mark.parametrize("package", ["shtaerman.api", "shtaerman.sweep"])
def test_type_checking_imports_equal_the_lazy_table(package):
    module = importlib.import_module(package)
    source = Path(module.__file__).read_text()
    assert type_checking_imports(source) == homes_of(module._HOMES)
    assert set(module.__all__) <= set(homes_of(module._HOMES))


def test_top_level_names_resolve_to_their_type_checking_imports():
    """Every name of ``shtaerman.__all__`` is imported under TYPE_CHECKING (but the version,
    imported at load) and resolves, lazily, to the object that import names."""
    import shtaerman

    declared = type_checking_imports((PACKAGE / "__init__.py").read_text())
    assert set(declared) == set(shtaerman.__all__) - {"__version__"}
    for name, home in declared.items():
        if name == "sweep":  # the package itself, callable as the api's sweep
            assert getattr(shtaerman, name).__name__ == "shtaerman.sweep"
            continue
        expected = getattr(importlib.import_module(home, "shtaerman"), name)
        assert getattr(shtaerman, name) is expected, name


def test_the_check_sees_a_name_missing_from_the_table():
    """Probe: a TYPE_CHECKING import the table lacks makes the comparison differ."""
    source = "if TYPE_CHECKING:\n    from .spec import A as A\n    from .kinds import B as B\n"
    assert type_checking_imports(source) != homes_of({".spec": ("A",)})
    assert type_checking_imports(source) == homes_of({".spec": ("A",), ".kinds": ("B",)})


def test_an_unknown_name_is_an_attribute_error():
    import shtaerman
    import shtaerman.api
    import shtaerman.sweep

    for module in (shtaerman, shtaerman.api, shtaerman.sweep):
        with pytest.raises(AttributeError, match="has no attribute 'no_such_name'"):
            module.no_such_name  # noqa: B018
