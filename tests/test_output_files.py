"""Outputs that never lose or fake anything: staged folders and files (issue 7, item 3)."""

import json
import os
import shutil
import signal
import stat
import subprocess
import sys
import time
from pathlib import Path

import pytest

from shtaerman.cli import main
from shtaerman.output.files import (
    FOLDER_MARKER,
    check_output_folder,
    staged_file,
    staged_folder,
    write_csv,
)
from shtaerman.validation import InputError


def run(capsys, *argv):
    code = main(list(argv))
    out, err = capsys.readouterr()
    return code, out, err


def names(folder: Path) -> list[str]:
    """The entries of ``folder`` but the marker of a result folder of this tool."""
    return sorted(p.name for p in folder.iterdir() if p.name != FOLDER_MARKER)


def ours(folder: Path) -> Path:
    """``folder`` created as a result folder this tool wrote (with its marker)."""
    folder.mkdir()
    (folder / FOLDER_MARKER).write_text('{"format": "shtaerman-folder-1"}')
    return folder


def dead_pid() -> int:
    child = subprocess.Popen([sys.executable, "-c", "pass"])
    child.wait()
    return child.pid


@pytest.fixture
def umask_022():
    previous = os.umask(0o022)
    yield
    os.umask(previous)


def test_permissions_follow_the_umask(tmp_path, umask_022):
    # mkdtemp/mkstemp would give 0700 and 0600
    with staged_folder(tmp_path / "run") as stage:
        write_csv(stage / "a.csv", {"x": [1.0]})
    assert stat.S_IMODE((tmp_path / "run").stat().st_mode) == 0o755
    with staged_file(tmp_path / "h.csv") as stage:
        write_csv(stage, {"x": [1.0]})
    assert stat.S_IMODE((tmp_path / "h.csv").stat().st_mode) == 0o644


def test_the_target_is_reserved_during_the_run(tmp_path):
    target = tmp_path / "run"
    with staged_folder(target) as stage:
        assert target.is_dir()  # reserved with os.mkdir: another run cannot take the name
        with pytest.raises(FileExistsError):
            os.mkdir(target)
        # a second writer of the same folder is refused before it starts
        with pytest.raises(InputError, match="another shtaerman run"):
            check_output_folder(target, force=True)
        (stage / "f.txt").write_text("1")
    assert (target / "f.txt").read_text() == "1"
    assert sorted(p.name for p in tmp_path.iterdir()) == ["run"]  # no debris


def test_a_reservation_filled_by_someone_else_is_not_replaced(tmp_path):
    target = tmp_path / "run"
    with pytest.raises(InputError, match="changed by another program"):
        with staged_folder(target) as stage:
            (stage / "mine.txt").write_text("mine")
            (target / "theirs.txt").write_text("theirs")
    assert [p.name for p in target.iterdir()] == ["theirs.txt"]
    assert sorted(p.name for p in tmp_path.iterdir()) == ["run"]


def test_a_failed_forced_run_restores_the_old_folder(tmp_path):
    target = ours(tmp_path / "run")
    (target / "old.txt").write_text("old")
    with pytest.raises(RuntimeError):
        with staged_folder(target, force=True) as stage:
            assert not (target / "old.txt").exists()
            (stage / "new.txt").write_text("new")
            raise RuntimeError("boom")
    assert names(target) == ["old.txt"]
    assert sorted(p.name for p in tmp_path.iterdir()) == ["run"]
    with staged_folder(target, force=True) as stage:
        (stage / "new.txt").write_text("new")
    assert names(target) == ["new.txt"] and (target / FOLDER_MARKER).is_file()
    assert sorted(p.name for p in tmp_path.iterdir()) == ["run"]


def test_a_full_folder_is_not_replaced_without_force(tmp_path):
    target = tmp_path / "run"
    target.mkdir()
    (target / "old.txt").write_text("old")
    with pytest.raises(InputError, match="not empty"):
        with staged_folder(target):
            pass
    assert [p.name for p in target.iterdir()] == ["old.txt"]


def test_a_full_folder_advises_force_only_when_force_would_replace_it(tmp_path):
    target = tmp_path / "run"
    target.mkdir()
    (target / "old.txt").write_text("old")
    foreign = "not empty; it was not written by shtaerman: name a new folder"
    with pytest.raises(InputError, match=foreign) as error:
        check_output_folder(target, force=False)
    assert "--force" not in str(error.value)  # --force refuses a folder this tool did not write
    with staged_folder(target / "ours") as stage:
        (stage / "new.txt").write_text("new")
    with pytest.raises(InputError, match="not empty; use force=True to replace it"):
        check_output_folder(target / "ours", force=False)
    assert check_output_folder(target / "ours", force=True) == target / "ours"


def test_a_stale_staging_folder_of_a_dead_process_is_cleaned(tmp_path):
    target = tmp_path / "run"
    pid = dead_pid()
    stale = tmp_path / f".run.partial-{pid}"
    (stale / "content").mkdir(parents=True)
    target.mkdir()  # its reservation
    (stale / "content" / "half.csv").write_text("1,")
    with staged_folder(target) as stage:
        (stage / "f.txt").write_text("1")
    assert sorted(p.name for p in tmp_path.iterdir()) == ["run"]


def test_a_stale_forced_run_gives_the_old_folder_back(tmp_path):
    target = tmp_path / "run"
    stale = tmp_path / f".run.partial-{dead_pid()}"
    (stale / "replaced").mkdir(parents=True)
    (stale / "replaced" / "old.txt").write_text("old")
    (stale / "content").mkdir()
    target.mkdir()
    with pytest.raises(InputError, match="not empty"):
        check_output_folder(target, force=False)
    assert [p.name for p in target.iterdir()] == ["old.txt"]
    assert sorted(p.name for p in tmp_path.iterdir()) == ["run"]


def test_a_live_writer_is_reported(tmp_path):
    sleeper = subprocess.Popen([sys.executable, "-c", "import time; time.sleep(60)"])
    try:
        (tmp_path / f".run.partial-{sleeper.pid}").mkdir()
        with pytest.raises(InputError, match=f"pid {sleeper.pid}"):
            check_output_folder(tmp_path / "run", force=True)
    finally:
        sleeper.kill()
        sleeper.wait()


@pytest.mark.parametrize("name", [".", "..", "", "/"])
def test_current_folder_and_parents_are_refused(tmp_path, monkeypatch, capsys, name):
    monkeypatch.chdir(tmp_path)
    (tmp_path / "keep.txt").write_text("keep")
    code, out, err = run(capsys, "contact", "--out", name, "--force", "--depths", "1e-3")
    assert code == 2 and out == ""
    assert err.startswith("shtaerman: error: --out:") and err.count("\n") == 1
    assert sorted(p.name for p in tmp_path.iterdir()) == ["keep.txt"]


def test_a_symlinked_out_folder_is_refused(tmp_path, monkeypatch, capsys):
    monkeypatch.chdir(tmp_path)
    (tmp_path / "real").mkdir()
    (tmp_path / "link").symlink_to(tmp_path / "real")
    code, _, err = run(capsys, "contact", "--out", "link", "--force", "--depths", "1e-3")
    assert code == 2 and "symbolic link" in err and err.count("\n") == 1
    assert (tmp_path / "link").is_symlink() and list((tmp_path / "real").iterdir()) == []
    assert sorted(p.name for p in tmp_path.iterdir()) == ["link", "real"]


@pytest.mark.parametrize("name", ["a\0b", "x" * 300, "file.txt/sub", "missing/sub"])
def test_bad_out_names_are_one_line_errors(tmp_path, monkeypatch, capsys, name):
    monkeypatch.chdir(tmp_path)
    (tmp_path / "file.txt").write_text("")
    code, _, err = run(capsys, "contact", "--out", name, "--depths", "1e-3")
    assert code == 2 and err.startswith("shtaerman: error: --out:") and err.count("\n") == 1
    assert sorted(p.name for p in tmp_path.iterdir()) == ["file.txt"]
    if name.endswith("/sub"):  # the reason is named: a file is not a missing folder
        expected = "is not a folder" if name.startswith("file") else "does not exist"
        assert expected in err


@pytest.mark.skipif(not Path("/sys").is_dir(), reason="needs Linux /sys (read-only to mkdir)")
def test_a_folder_that_takes_no_new_entries_is_named_as_such(tmp_path, monkeypatch):
    """mkdir in /proc fails with ENOENT although /proc exists: not "No such file"."""
    import errno

    def refused(path, *args):
        raise FileNotFoundError(errno.ENOENT, "No such file or directory", str(path))

    monkeypatch.setattr(os, "mkdir", refused)
    with pytest.raises(InputError, match=r"in '.+' \(its file system takes no new files\)$"):
        check_output_folder(tmp_path / "run", force=False)


def test_an_unwritable_parent_is_refused_before_computing(capsys, monkeypatch):
    if os.access("/sys", os.W_OK) and not _mkdir_fails("/sys"):
        pytest.skip("/sys is writable here")
    import shtaerman.output.folder as folder

    def computed(*args, **kwargs):
        raise AssertionError("the studies ran")

    monkeypatch.setattr(folder, "run_verification", computed)
    code, _, err = run(capsys, "verify", "paper", "--out", "/sys/shtaerman-test")
    assert code == 2 and "cannot write in '/sys'" in err and err.count("\n") == 1


def _mkdir_fails(folder: str) -> bool:
    try:
        os.mkdir(os.path.join(folder, ".shtaerman-probe"))
    except OSError:
        return True
    os.rmdir(os.path.join(folder, ".shtaerman-probe"))
    return False


def test_history_to_a_device_writes_into_it(capsys):
    before = os.stat(os.devnull)
    code, _, err = run(capsys, "impact", "--history", os.devnull, "--points", "5")
    assert code == 0 and err == ""
    after = os.stat(os.devnull)
    assert stat.S_ISCHR(after.st_mode) and after.st_rdev == before.st_rdev


def test_history_to_a_fifo(tmp_path, capsys):
    fifo = tmp_path / "pipe"
    os.mkfifo(fifo)
    reader = subprocess.Popen(["cat", str(fifo)], stdout=subprocess.PIPE)
    code, _, _ = run(capsys, "impact", "--history", str(fifo), "--points", "3")
    text = reader.communicate(timeout=60)[0].decode()
    assert code == 0 and stat.S_ISFIFO(fifo.stat().st_mode)
    assert len(text.splitlines()) == 4  # header + 3 rows


def test_history_leaves_no_temporary_and_refuses_a_folder(tmp_path, capsys):
    path = tmp_path / "h.csv"
    assert run(capsys, "impact", "--history", str(path), "--points", "3")[0] == 0
    assert sorted(p.name for p in tmp_path.iterdir()) == ["h.csv"]
    code, _, err = run(capsys, "impact", "--history", str(tmp_path), "--force")
    assert code == 2 and "is a folder" in err


@pytest.mark.parametrize("command", ["impact", "dynamic"])
@pytest.mark.parametrize("force", [[], ["--force"]])
def test_a_symlinked_history_is_refused_and_its_target_kept(tmp_path, capsys, command, force):
    """Issue 31 item 4: ``ln -s precious.csv h.csv; impact --history h.csv --force`` replaced
    precious.csv; a link into another folder (dynamic) did the same. Refused as --out is."""
    elsewhere, here = tmp_path / "elsewhere", tmp_path / "here"
    elsewhere.mkdir(), here.mkdir()
    precious, link, dangling = elsewhere / "precious.csv", here / "h.csv", here / "new.csv"
    precious.write_text("precious")
    link.symlink_to(precious)
    dangling.symlink_to(elsewhere / "absent.csv")
    for name in (link, dangling):
        code, out, err = run(capsys, command, "--history", str(name), *force)
        assert code == 2 and out == "" and err.count("\n") == 1
        assert "--history: " in err and "is a symbolic link; name the file itself" in err
    assert precious.read_text() == "precious" and sorted(p.name for p in elsewhere.iterdir()) == [
        "precious.csv"
    ]
    assert link.is_symlink() and dangling.is_symlink() and len(list(here.iterdir())) == 2


def test_history_to_a_link_to_a_device_writes_into_it(tmp_path, capsys):
    """Writing into a special file replaces nothing: a link to one (as /dev/stdout is, to
    /proc/self/fd/1) stays allowed."""
    link = tmp_path / "null"
    link.symlink_to(os.devnull)
    code, _, err = run(capsys, "impact", "--history", str(link), "--points", "3")
    assert code == 0 and err == "" and link.is_symlink() and os.path.exists(os.devnull)
    assert stat.S_ISCHR(os.stat(os.devnull).st_mode)


def test_sigterm_during_contact_out_leaves_nothing(tmp_path):
    env = {**os.environ, "PYTHONPATH": str(Path(__file__).parents[1] / "src")}
    child = subprocess.Popen(
        [sys.executable, "-m", "shtaerman", "contact", "--out", "run", "--mesh-size", "0.004"],
        cwd=tmp_path,
        env=env,
        stderr=subprocess.PIPE,
    )
    for _ in range(600):  # wait until the run has reserved its folder (no wall-clock assertion)
        if (tmp_path / "run").exists() or child.poll() is not None:
            break
        time.sleep(0.05)
    child.send_signal(signal.SIGTERM)
    _, err = child.communicate(timeout=300)
    if child.returncode == 0:
        pytest.skip("the run finished before the signal")
    assert child.returncode == 143 and b"terminated" in err
    assert list(tmp_path.iterdir()) == []


def test_sigkill_leftovers_are_cleaned_by_the_next_run(tmp_path):
    env = {**os.environ, "PYTHONPATH": str(Path(__file__).parents[1] / "src")}
    child = subprocess.Popen(
        [sys.executable, "-m", "shtaerman", "contact", "--out", "run", "--mesh-size", "0.004"],
        cwd=tmp_path,
        env=env,
        stderr=subprocess.DEVNULL,
    )
    for _ in range(600):
        if (tmp_path / "run").exists() or child.poll() is not None:
            break
        time.sleep(0.05)
    child.kill()
    child.wait()
    if not (tmp_path / f".run.partial-{child.pid}").exists():
        pytest.skip("the run finished before the signal")
    with staged_folder(tmp_path / "run") as stage:
        (stage / "f.txt").write_text("1")
    assert sorted(p.name for p in tmp_path.iterdir()) == ["run"]


def test_keep_staged_moves_the_finished_part_into_place(tmp_path):
    from shtaerman.output.files import KeepStaged

    target = tmp_path / "run"
    with pytest.raises(KeyboardInterrupt):
        with staged_folder(target) as stage:
            (stage / "done.txt").write_text("done")
            (stage / "marker").write_text("{}")
            raise KeepStaged(KeyboardInterrupt())
    assert names(target) == ["done.txt", "marker"]
    assert sorted(p.name for p in tmp_path.iterdir()) == ["run"]
    # a folder without the marker is not resumed; one with it starts the stage with its files
    with pytest.raises(InputError, match="holds no interrupted run"):
        check_output_folder(target, force=False, resume_marker="other")
    with pytest.raises(RuntimeError):
        with staged_folder(target, resume_marker="marker") as stage:
            assert (stage / "done.txt").read_text() == "done"
            (stage / "done.txt").unlink()
            raise RuntimeError("boom")
    assert names(target) == ["done.txt", "marker"]  # restored
    with staged_folder(target, resume_marker="marker") as stage:
        (stage / "marker").unlink()
        (stage / "more.txt").write_text("more")
    assert names(target) == ["done.txt", "more.txt"]
    assert sorted(p.name for p in tmp_path.iterdir()) == ["run"]


def test_a_planted_marker_link_is_not_a_resumable_folder(tmp_path):
    target = tmp_path / "run"
    target.mkdir()
    (target / "notes.txt").write_text("mine")
    (target / "marker").symlink_to(tmp_path / "elsewhere")
    with pytest.raises(InputError, match="holds no interrupted run"):
        with staged_folder(target, resume_marker="marker"):
            pass
    assert sorted(p.name for p in target.iterdir()) == ["marker", "notes.txt"]


def test_a_killed_run_that_had_filled_its_folder_keeps_the_one_it_replaced(tmp_path):
    import warnings

    from shtaerman.output.files import folder_lock

    target = tmp_path / "run"
    pid = dead_pid()
    stale = tmp_path / f".run.partial-{pid}"
    (stale / "replaced").mkdir(parents=True)
    (stale / "replaced" / "old.txt").write_text("old")
    (stale / "replaced" / FOLDER_MARKER).write_text('{"format": "shtaerman-folder-1"}')
    target.mkdir()
    (target / "new.txt").write_text("new")  # a sweep writes in place
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        with folder_lock(target):
            pass
    assert (tmp_path / f"run.replaced-{pid}" / "old.txt").read_text() == "old"
    assert (target / "new.txt").read_text() == "new"
    [warning] = caught
    assert f"run.replaced-{pid}" in str(warning.message)
    assert sorted(p.name for p in tmp_path.iterdir()) == ["run", f"run.replaced-{pid}"]


def test_a_forced_run_marks_the_folder_it_replaced_superseded_once_published(tmp_path, monkeypatch):
    """A run killed while deleting its stage, after the new folder is in place: the old one
    is marked superseded first, so the next run neither keeps it as NAME.replaced-PID nor
    warns (it did, for verify and contact --force, as if a sweep had been interrupted)."""
    import shutil
    import warnings

    target = ours(tmp_path / "run")
    (target / "old.txt").write_text("old")
    stages = []
    monkeypatch.setattr(shutil, "rmtree", lambda path, **kw: stages.append(path))  # killed
    with staged_folder(target, force=True) as stage:
        (stage / "new.txt").write_text("new")
    monkeypatch.undo()
    [stage] = stages
    assert sorted(p.name for p in stage.iterdir()) == ["superseded"]
    stage.rename(tmp_path / f".run.partial-{dead_pid()}")  # left by a process now dead
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        with staged_folder(target, force=True) as again:  # the next run cleans it silently
            (again / "newer.txt").write_text("newer")
    assert sorted(p.name for p in tmp_path.iterdir()) == ["run"]
    assert (target / "newer.txt").read_text() == "newer"


@pytest.mark.parametrize("marker", ["missing", "link", "folder"])
def test_force_replaces_no_folder_this_tool_did_not_write(tmp_path, capsys, marker):
    """--force replaced any folder, a user's project folder too: only a folder holding the
    marker this tool writes (a regular file, not a link to one) is replaced."""
    project = tmp_path / "project"
    project.mkdir()
    (project / "notes.txt").write_text("mine")
    if marker == "link":
        (tmp_path / "m.json").write_text("{}")
        (project / FOLDER_MARKER).symlink_to(tmp_path / "m.json")
    elif marker == "folder":
        (project / FOLDER_MARKER).mkdir()
    with pytest.raises(InputError, match="was not written by shtaerman"):
        with staged_folder(project, force=True):
            pass
    for argv in (
        ["contact", "--depths", "1e-3"],
        ["dynamic", "--no-estimate"],
        ["verify", "--quick", "paper"],
    ):
        code, out, err = run(capsys, *argv, "--out", str(project), "--force")
        assert code == 2 and out == "" and err.count("\n") == 1, (argv, err)
        assert f"error: --out: folder '{project}' was not written by shtaerman" in err  # adv49
        assert "name a new folder with --out" in err
    assert names(project) == ["notes.txt"] and (project / "notes.txt").read_text() == "mine"
    expected = ["m.json", "project"] if marker == "link" else ["project"]
    assert sorted(p.name for p in tmp_path.iterdir()) == expected


@pytest.mark.parametrize("state", ["not empty", "not ours", "an added file"])
def test_a_folder_refused_for_what_it_holds_names_the_option(tmp_path, state):
    """adv49: these refusals carried no parameter, so the command line said 'out: folder ...'
    where every other --out refusal says '--out: ...'."""
    folder = tmp_path / "r"
    with staged_folder(folder) as stage:
        (stage / "a.csv").write_text("1\n")
    if state == "not ours":
        (folder / FOLDER_MARKER).unlink()
    if state != "not empty":
        (folder / "note.txt").write_text("mine")
    with pytest.raises(InputError) as refused:
        with staged_folder(folder, force=state != "not empty"):
            pytest.fail("the run started")
    assert refused.value.parameter == "out", refused.value


def test_a_killed_run_that_kept_a_resumable_part_has_it_moved_into_place(tmp_path):
    """After a SIGKILL, a stage whose content holds its ``keep_marker`` file (a verify's
    progress) is moved into place by the next run writing the folder, with a warning saying
    where; without that file it is removed as before. A forced run's: the folder it was
    replacing is put back whole, its finished part beside it (as on SIGTERM)."""
    target = tmp_path / "run"
    pid = dead_pid()
    stale = tmp_path / f".run.partial-{pid}"
    (stale / "content" / "done").mkdir(parents=True)
    (stale / "content" / "progress.json").write_text("{}")
    (stale / "keep").write_text("progress.json")
    target.mkdir()  # its reservation
    with pytest.warns(UserWarning, match=f"left its finished part in '{target}'"):
        check_output_folder(target, force=False, resume_marker="progress.json")
    assert sorted(p.name for p in target.iterdir()) == ["done", "progress.json"]
    assert sorted(p.name for p in tmp_path.iterdir()) == ["run"]
    shutil.rmtree(target)
    (stale / "content" / "done").mkdir(parents=True)
    (stale / "content" / "progress.json").write_text("{}")
    (stale / "keep").write_text("progress.json")
    (stale / "replaced").mkdir()  # a forced run: the folder it was replacing
    (stale / "replaced" / "old.txt").write_text("old")
    (stale / "replaced" / FOLDER_MARKER).write_text('{"format": "shtaerman-folder-1"}')
    target.mkdir()
    beside = tmp_path / f"run.incomplete-{pid}"
    with pytest.warns(UserWarning, match=f"left its finished part in '{beside}'"):
        check_output_folder(target, force=True)
    assert names(target) == ["old.txt"] and (target / "old.txt").read_text() == "old"
    assert sorted(p.name for p in beside.iterdir()) == ["done", "progress.json"]
    assert sorted(p.name for p in tmp_path.iterdir()) == ["run", beside.name]
    # the stage is recorded as keepable only for a run that asks for it
    with staged_folder(tmp_path / "other", keep_marker="progress.json") as stage:
        assert (stage.parent / "keep").read_text() == "progress.json"
    with staged_folder(tmp_path / "plain") as stage:
        assert not (stage.parent / "keep").exists()


def test_force_keeps_the_files_a_user_added_to_a_result_folder(tmp_path):
    """--force deleted a note the user had put into a result folder: the marker now lists the
    files the run wrote, and a folder holding others is refused, with nothing touched."""
    target = tmp_path / "run"
    with staged_folder(target) as stage:
        (stage / "sub").mkdir()
        (stage / "sub" / "a.csv").write_text("1")
    assert json.loads((target / FOLDER_MARKER).read_text())["files"] == ["sub/a.csv"]
    (target / "sub" / "notes.txt").write_text("mine")
    with pytest.raises(InputError, match=r"holds 'sub/notes.txt', not written by shtaerman"):
        check_output_folder(target, force=True)
    with pytest.raises(InputError, match=r"move it or name a new folder with out=\.\.\."):
        with staged_folder(target, force=True):
            pass
    assert (target / "sub" / "notes.txt").read_text() == "mine"
    (target / "sub" / "notes.txt").unlink()
    (target / "sub" / "a.csv").unlink()  # a file the user deleted is no obstacle
    with staged_folder(target, force=True) as stage:
        (stage / "b.csv").write_text("2")
    assert names(target) == ["b.csv"]


def test_a_full_disk_names_the_output_it_was_writing(tmp_path):
    """ENOSPC carries no file name: the message said only "[Errno 28] No space left on
    device" (adversary); it now names the option and the folder, and nothing is left."""
    import errno

    target = tmp_path / "run"
    with pytest.raises(OSError, match=r"No space left on device \(writing --out '.*run'\)") as e:
        with staged_folder(target) as stage:
            (stage / "a.txt").write_text("x")
            raise OSError(errno.ENOSPC, os.strerror(errno.ENOSPC))
    assert e.value.errno == errno.ENOSPC
    assert not target.exists() and sorted(p.name for p in tmp_path.iterdir()) == []


def test_an_existing_folder_is_refused_in_the_words_of_its_route(tmp_path, capsys):
    """adv52: ``sh.run_study(out=existing)`` (and ``sh.dynamic``, ``sh.contact``: one
    output_folder) answered Python with 'use --force', an option it does not take. The
    refusal is written with keywords (``force=True``, ``out=...``) and the command line
    spells them as its options."""
    import shtaerman as sh

    done, foreign = ours(tmp_path / "done"), tmp_path / "foreign"
    foreign.mkdir()
    (foreign / "note.txt").write_text("mine")
    with pytest.raises(InputError, match=r"use force=True to replace it$"):
        sh.run_study("paper", out=done, quick=True)
    with pytest.raises(InputError, match=r"name a new folder with out=\.\.\.$"):
        sh.run_study("paper", out=foreign, quick=True)
    code, _, err = run(capsys, "verify", "--out", str(done))
    assert code == 2 and err.endswith("not empty; use --force to replace it\n"), err
    code, _, err = run(capsys, "verify", "--out", str(foreign))
    assert code == 2 and err.endswith("name a new folder with --out\n"), err


def test_a_refused_folder_names_what_works_for_an_interrupted_run(tmp_path):
    """Adversary 53: after an interrupted force=True run the finished part is in
    NAME.incomplete-PID, but a resume of NAME said 'use force=True' and did not point there;
    and writing an interrupted folder without resume also said force=True, where resume=True
    completes it. The refusal names what works (files.py, every command that resumes)."""
    from shtaerman.output.files import KeepStaged

    target = ours(tmp_path / "run")
    (target / "old.txt").write_text("old")
    with pytest.raises(KeyboardInterrupt) as stopped:
        with staged_folder(target, force=True, keep_marker="marker") as stage:
            (stage / "marker").write_text("{}")
            raise KeepStaged(KeyboardInterrupt())
    kept = stopped.value.kept_in
    assert kept.name.startswith("run.incomplete-") and (kept / "marker").is_file()
    with pytest.raises(InputError) as refused:
        check_output_folder(target, force=False, resume_marker="marker", keep_marker="marker")
    said = str(refused.value)
    assert said.startswith(f"out: folder '{target}' holds no interrupted run to complete")
    assert f"complete that with out='{kept}' resume=True" in said
    with pytest.raises(InputError) as refused:
        check_output_folder(kept, force=False, keep_marker="marker")
    said = str(refused.value)
    assert "holds an interrupted run (marker); complete it with resume=True" in said
    assert check_output_folder(kept, force=False, resume_marker="marker") == kept  # it does
    # a folder another program wrote: neither resume nor force touches it
    foreign = tmp_path / "mine"
    foreign.mkdir()
    (foreign / "notes.txt").write_text("mine")
    for resume in (None, "marker"):
        with pytest.raises(InputError, match=r"not written by shtaerman: name a new folder"):
            check_output_folder(foreign, force=False, resume_marker=resume, keep_marker="marker")


def test_effects_names_the_resume_on_the_command_line(tmp_path, capsys):
    """The same refusal in the command line's words (cli.effects passes its marker)."""
    folder = ours(tmp_path / "table")
    (folder / "incomplete.json").write_text("{}")
    code, out, err = run(capsys, "effects", "--out", str(folder))
    assert code == 2 and out == "" and err.count("\n") == 1, err
    assert "holds an interrupted run (incomplete.json); complete it with --resume" in err, err
