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


def _study(tmp_path, shipped, *changes):
    """A shipped study file with ``changes`` ((old line start, new line)) and no [sweep]."""
    text = (SOURCE.parents[1] / "fem" / shipped).read_text().partition("\n[sweep]")[0]
    lines = text.splitlines()
    for start, line in changes:
        lines = [line if old.startswith(start) else old for old in lines]
    study = tmp_path / shipped
    study.write_text("\n".join(lines) + "\n")
    return study


def test_a_finite_strain_study_far_out_of_reach_names_the_finite_strain_limit(tmp_path):
    """A finite-strain study at 1e30 kg (x/a 5.4e3) was refused 'beyond the 100 up to which
    an FE impact is run', the linear FE's reach: its loader passed no finite flag, where the
    API names the finite-strain contact's 1.2 (9957c5f)."""
    import pytest

    from shtaerman.study.schema import StudyError, load_study

    study = _study(tmp_path, "finite_strain.toml", ("mass =", "mass = 1e30"))
    with pytest.raises(StudyError) as caught:
        load_study(study)
    said = str(caught.value)
    assert "beyond the 1.2 up to which the finite-strain contact converges" in said, said
    assert "the 100 " not in said, said
