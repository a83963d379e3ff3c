"""``shtaerman init-study``: a commented template that loads, never overwriting by accident.

That the written study also runs (``verify my-study.toml --quick``, exit 0) is the README's own
example, run by tests/test_readme.py.
"""

import dataclasses
import re
import warnings

import pytest

from shtaerman.cli import main
from shtaerman.study.run import run_study
from shtaerman.study.schema import find_study, load_study, shipped_studies


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


def uncommented(template: str) -> str:
    """``template`` with its optional tables and keys uncommented, all but the [layer] block: a
    layer excludes the convergence study (its errors are against the half-space), and its
    block loads on its own (test_layer_study)."""
    template = re.sub(r"(?m)^# \[layer\][^\n]*\n(?:#[^\n]*\n)*", "", template)
    return re.sub(r"(?m)^# (?=\[|[A-Za-z0-9_]+ = )", "", template)


def test_commented_keys_are_valid_when_uncommented(tmp_path):
    path = tmp_path / "all.toml"
    assert main(["init-study", str(path)]) == 0
    path.write_text(uncommented(path.read_text()))  # every optional table and key
    studies = load_study(path)
    assert [(s.name, s.velocity) for s in studies] == [
        ("all-v01", 1.0),
        ("all-v02", 2.0),
        ("all-v03", 3.0),
    ]
    assert studies[0].convergence_sizes and studies[0].mesh.size == pytest.approx(1 / 150, 1e-3)


def test_refuses_to_overwrite_without_force(tmp_path, capsys):
    """adv53: init-study said "'F' exists; use --force to replace it" and impact --history
    "--history: 'F' exists (use --force to replace it)": one wording, output.files's, naming
    the parameter (FILE here)."""
    path = tmp_path / "mine.toml"
    path.write_text("precious\n")
    assert main(["init-study", str(path)]) == 2
    said = f"'{path}' exists; use --force to replace it\n"
    assert capsys.readouterr().err == f"shtaerman: error: FILE: {said}"
    assert main(["impact", "--history", str(path)]) == 2
    assert capsys.readouterr().err == f"shtaerman: error: --history: {said}"
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


@pytest.mark.parametrize("kind", ["contact", "dynamic", "finite-strain"])
def test_every_kind_has_a_template_in_todays_keys(tmp_path, capsys, kind):
    path = tmp_path / f"my-{kind}.toml"
    assert main(["init-study", "--kind", kind, str(path)]) == 0
    assert f"shtaerman verify {path} --quick" in capsys.readouterr().out
    with warnings.catch_warnings():
        warnings.simplefilter("error")  # no deprecated key in a template
        [study] = load_study(path)
        path.write_text(uncommented(path.read_text()))
        assert load_study(path)  # every commented key is valid too
    assert study.kind == kind and study.name == f"my-{kind}"


def test_dynamic_template_is_the_shipped_study_over_fewer_velocities(tmp_path):
    path = tmp_path / "dyn.toml"
    assert main(["init-study", "--kind", "dynamic", str(path)]) == 0
    [study] = load_study(path)
    [shipped] = load_study(find_study("dynamic"))
    assert (study.velocities, study.example, study.quick_velocities) == (
        (1.0, 2.0, 3.0),
        2.0,
        (1.0, 2.0),
    )
    assert study.settings == shipped.settings and study.quick_settings == shipped.quick_settings
    assert (study.indenter, study.half_space, study.density, study.mass) == (
        shipped.indenter,
        shipped.half_space,
        shipped.density,
        shipped.mass,
    )


@pytest.mark.parametrize("kind", ["contact", "dynamic"])
def test_template_runs_as_written(tmp_path, kind):
    """The quick run of the contact and dynamic templates passes its checks (a few seconds)."""
    path = tmp_path / "run.toml"
    assert main(["init-study", "--kind", kind, str(path)]) == 0
    [study] = load_study(path)
    outcome = run_study(study, quick=True)
    assert outcome.passed, [c for c in outcome.checks if not c.passed]


def test_an_unknown_kind_is_one_line_exit_2(tmp_path, capsys):
    assert main(["init-study", "--kind", "impact", str(tmp_path / "x.toml")]) == 2
    err = capsys.readouterr().err
    assert "--kind" in err and "dynamic" in err and err.count("\n") == 1
    assert not (tmp_path / "x.toml").exists()


def test_force_under_a_file_size_limit_keeps_the_users_file(tmp_path):
    """'ulimit -f 1' cuts the ~3 KB template short: the user's file stays as it was and no
    stage is left (opened with 'w', the truncated template replaced it)."""
    import resource
    import subprocess
    import sys

    path = tmp_path / "mine.toml"
    path.write_text("precious\n")

    def limit():
        resource.setrlimit(
            resource.RLIMIT_FSIZE, (1024, resource.getrlimit(resource.RLIMIT_FSIZE)[1])
        )

    done = subprocess.run(
        [sys.executable, "-m", "shtaerman", "init-study", str(path), "--force"],
        capture_output=True,
        text=True,
        preexec_fn=limit,
        check=False,
    )
    assert done.returncode == 2 and "cannot write" in done.stderr
    assert done.stderr.count("\n") == 1
    assert path.read_text() == "precious\n"
    assert sorted(p.name for p in tmp_path.iterdir()) == ["mine.toml"]


def test_a_file_name_that_is_not_utf8_is_written_whole(tmp_path, capsys):
    """A name with a byte that is not UTF-8 (s\\xff.toml) gets the whole template, shown as
    s\\xff in its text and in the message (it raised UnicodeEncodeError after creating an empty
    file)."""
    import os

    path = tmp_path / os.fsdecode(b"s\xff.toml")
    assert main(["init-study", str(path)]) == 0
    assert "s\\xff.toml" in capsys.readouterr().out
    text = path.read_bytes().decode("utf-8")
    assert text.startswith("# A shtaerman cross-check study") and "s\\xff.toml --quick" in text


def schema_keys(struct: type, prefix: str = "") -> set[str]:
    """Every key path (``table.key``) a study schema accepts, its tables included."""
    from typing import get_args, get_type_hints

    from shtaerman.study.schema import Table

    keys, hints = set(), get_type_hints(struct)
    for name in struct.__struct_fields__:
        table = next(
            (
                c
                for c in (hints[name], *get_args(hints[name]))
                if isinstance(c, type) and issubclass(c, Table)
            ),
            None,
        )
        keys.add(prefix + name)
        if table is not None:
            keys |= schema_keys(table, f"{prefix}{name}.")
    return keys


def template_keys(template: str) -> set[str]:
    """The key paths a template shows, written or commented out (``# key = ...``, and an
    alternative inside a comment, ``#   # key = ...``), each under the table above it."""
    keys, table = set(), ""
    for line in template.splitlines():
        header = re.match(r"#?\s*\[([a-z_]+)\]", line)
        if header:
            table = header[1]
            keys.add(table)
            continue
        key = re.match(r"#?[ #]*([A-Za-z_][A-Za-z0-9_]*) = ", line)
        if key:
            keys.add(f"{table}.{key[1]}" if table else key[1])
    return keys


SCHEMAS = {
    "contact": "shtaerman.study.contact.loader:_StudyFile",
    "dynamic": "shtaerman.study.dynamic.loader:_DynamicFile",
    "finite-strain": "shtaerman.study.finite.loader:_FiniteFile",
    "effects": "shtaerman.api.effect_table.study:_EffectsFile",
}
"""Study kind -> the schema its loader decodes a file with."""


@pytest.mark.parametrize("kind", sorted(SCHEMAS))
def test_every_key_of_the_kinds_schema_is_in_its_template(kind):
    """A [quick] key counts as shown where its [numerics] twin is: the template says [quick]
    takes the [numerics] keys."""
    import importlib

    from shtaerman.cli.init_study import TEMPLATES

    module, _, name = SCHEMAS[kind].partition(":")
    accepted = schema_keys(getattr(importlib.import_module(module), name))
    shown = template_keys(TEMPLATES[kind])
    twins = {
        f"quick.{key.removeprefix('numerics.')}" for key in shown if key.startswith("numerics.")
    }
    assert re.search(r"(?m)^#? ?\[quick\].*the \[numerics\] keys", TEMPLATES[kind])
    assert sorted(accepted - shown - twins) == []
    assert shown - accepted == {"kind"}  # and nothing the schema refuses


def test_the_template_kinds_are_the_study_kinds():
    from shtaerman.cli.init_study import TEMPLATES
    from shtaerman.study.kinds import study_kinds

    assert sorted(TEMPLATES) == sorted(SCHEMAS) == study_kinds()
