"""A sweep or a run replacing a folder that holds an immutable file (``chattr +i``; root only)
is refused before it starts (polish49): the run moved the old folder into its staging folder
``.NAME.partial-PID``, could not remove it at the end, failed after computing everything
("Operation not permitted (results.json); the finished cases are saved in ...") and left the
staging folder behind."""

from __future__ import annotations

import os
import shutil
import subprocess

import pytest

from shtaerman.cli import main

CHATTR = shutil.which("chattr")
pytestmark = pytest.mark.skipif(
    CHATTR is None or os.geteuid() != 0, reason="chattr +i needs root and e2fsprogs"
)


@pytest.fixture
def immutable():
    """``immutable(path)``: chattr +i ``path``, undone at the end (else tmp_path stays)."""
    made = []

    def make(path):
        done = subprocess.run([CHATTR, "+i", str(path)], capture_output=True, check=False)
        if done.returncode != 0:
            pytest.skip(f"this file system keeps no immutable flag ({done.stderr.strip()!r})")
        made.append(path)

    yield make
    for path in made:
        subprocess.run([CHATTR, "-i", str(path)], check=True)


def test_a_forced_sweep_onto_a_folder_holding_an_immutable_file_is_refused_before_it_runs(
    tmp_path, immutable, capsys
):
    from sweep_probe import finished_sweep  # registers the kind "probe"

    sweep, out = finished_sweep(tmp_path, "1.0, 2.0", "i1")
    before = sorted(path.name for path in out.rglob("*"))
    immutable(out / "results.json")
    capsys.readouterr()
    code = main(["sweep", str(sweep), "--out", str(out), "--force", "--workers", "1"])
    said = capsys.readouterr().err.strip()
    assert code == 2 and "\n" not in said, said  # bad input: one line
    assert said.endswith(
        f"--out: cannot replace '{out}': 'results.json' in '{out}' is immutable or append-only "
        "(lsattr shows it); make it removable (chattr -i -a) or write the results to another "
        "folder"
    ), said
    assert sorted(path.name for path in tmp_path.iterdir()) == ["i1", "p.toml"]  # no stage
    assert sorted(path.name for path in out.rglob("*")) == before  # the old sweep is whole


def test_a_resumed_folder_whose_marker_is_immutable_is_refused_before_it_runs(tmp_path, immutable):
    from shtaerman.output.files import staged_folder
    from shtaerman.validation import InputError

    out = tmp_path / "i1"
    with staged_folder(out) as stage:
        (stage / "incomplete.json").write_text("{}\n")
    immutable(out / "incomplete.json")
    with pytest.raises(InputError, match=r"'incomplete.json' in .* is immutable or append-only"):
        with staged_folder(out, resume_marker="incomplete.json"):
            pytest.fail("the run started on a folder it cannot remove")
    assert [path.name for path in tmp_path.iterdir()] == ["i1"]  # no stage left


def test_a_forced_history_onto_an_immutable_file_is_refused_before_it_runs(
    tmp_path, immutable, capsys
):
    """adv49: ``--history h.csv --force`` onto a chattr +i h.csv computed the whole impact, then
    failed renaming its stage over the file ('[Errno 1] Operation not permitted', exit 1)."""
    history = tmp_path / "h.csv"
    history.write_text("t [s]\n0.0\n")
    immutable(history)
    code = main(["impact", "--history", str(history), "--force"])
    said = capsys.readouterr().err.strip()
    assert code == 2 and "\n" not in said, said  # bad input: one line, before the run
    assert said.endswith(
        f"--history: cannot replace '{history}': it or its folder is immutable or append-only "
        "(lsattr shows it); make it removable (chattr -i -a) or write another file"
    ), said
    assert history.read_text() == "t [s]\n0.0\n"  # untouched
    assert sorted(path.name for path in tmp_path.iterdir()) == ["h.csv"]  # no stage left
