"""``shtaerman init-study``: a commented template that loads, never overwriting by accident.

That the written study also runs (``verify my-study.toml --quick``, exit 0) is the README's own
example, run by tests/test_readme.py.
"""

import dataclasses
import re

import pytest

from shtaerman.cli import main
from shtaerman.study.schema import load_study, shipped_studies


def test_template_is_the_paper_example_named_after_its_file(tmp_path, capsys):
    path = tmp_path / "my-study.toml"
    assert main(["init-study", str(path)]) == 0
    assert f"shtaerman verify {path} --quick" in capsys.readouterr().out
    [study] = load_study(path)
    [paper] = load_study(next(p for p in shipped_studies() if p.stem == "paper"))
    assert study.name == "my-study"
    # the shipped paper study but for its name, text and convergence study
    same = {"name": paper.name, "description": paper.description, "source": paper.source}
    assert dataclasses.replace(study, **same, convergence_sizes=paper.convergence_sizes) == paper


def test_commented_keys_are_valid_when_uncommented(tmp_path):
    path = tmp_path / "all.toml"
    assert main(["init-study", str(path)]) == 0
    text = path.read_text()
    text = re.sub(r"(?m)^# (?=\[|[a-z_]+ = )", "", text)  # every optional table and key
    path.write_text(text)
    studies = load_study(path)
    assert [(s.name, s.velocity) for s in studies] == [
        ("all-v01", 1.0),
        ("all-v02", 2.0),
        ("all-v03", 3.0),
    ]
    assert studies[0].convergence_sizes and studies[0].mesh.size == pytest.approx(1 / 150, 1e-3)


def test_refuses_to_overwrite_without_force(tmp_path, capsys):
    path = tmp_path / "mine.toml"
    path.write_text("precious\n")
    assert main(["init-study", str(path)]) == 2
    assert (
        capsys.readouterr().err == f"shtaerman: error: '{path}' exists; use --force to replace it\n"
    )
    assert path.read_text() == "precious\n"
    assert main(["init-study", str(path), "--force"]) == 0
    assert load_study(path)[0].name == "mine"


@pytest.mark.parametrize("name", ["study.txt", "folder"])
def test_bad_targets_are_one_line_errors(tmp_path, capsys, name):
    (tmp_path / "folder").mkdir()
    target = tmp_path / name
    assert main(["init-study", str(target)]) == 2
    err = capsys.readouterr().err
    assert err.startswith("shtaerman: error: ") and err.count("\n") == 1
    assert not (tmp_path / "study.txt").exists()
