"""The reach refusal finished (session 57): a contact curve's depths set by an impact, refused
by one check (guards.check_profile_reach) in the words of each route."""

import ast
from pathlib import Path

SOURCE = Path(__file__).resolve().parents[1] / "src" / "shtaerman"


def test_the_profile_reach_is_a_guard_every_route_imports_from_guards():
    """It lived in study/contact/loader.py while the API, the sweeps and the finite-strain
    loader used it: each now imports it from guards, beside check_reach."""
    from shtaerman import guards

    assert guards.check_profile_reach.__module__ == "shtaerman.guards"
    importers = []
    for path in SOURCE.rglob("*.py"):
        for node in ast.walk(ast.parse(path.read_text(encoding="utf-8"))):
            if isinstance(node, ast.ImportFrom):
                if any(alias.name == "check_profile_reach" for alias in node.names):
                    importers.append((path.relative_to(SOURCE).as_posix(), node.module))
    assert len(importers) == 4, importers  # the API, a contact sweep, both study loaders
    assert all(module.endswith("guards") for _, module in importers), importers
