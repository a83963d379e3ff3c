"""A full disk names the output that failed (left66).

ENOSPC carries no file name: ``shtaerman dynamic --history /dev/full`` said only "[Errno 28] No
space left on device" (adv66). Every command's write path now names the output it was writing:
a history file, a figure (``prony-plot --out``), a sweep's own files.
"""

import errno
import os
from pathlib import Path

import pytest

from shtaerman.cli import main

FULL = Path("/dev/full")  # Linux: every write fails with ENOSPC
linux = pytest.mark.skipif(not FULL.exists(), reason="needs /dev/full")
NO_SPACE = "[Errno 28] No space left on device"
TAIL = "; every output is complete or absent (nothing partial is kept)\n"


@linux
def test_a_history_on_a_full_disk_names_its_option_and_file(capsys):
    assert main(["impact", "--history", str(FULL)]) == 1  # a machine's failure, not bad input
    said = capsys.readouterr().err
    assert said == f"shtaerman: error: {NO_SPACE} (writing --history '{FULL}'){TAIL}"


@linux
def test_a_figure_on_a_full_disk_names_its_option_and_file(tmp_path, capsys):
    figure = tmp_path / "p.png"
    figure.symlink_to(FULL)  # a device is written into (check_output_file), here a full one
    assert main(["prony-plot", "--out", str(figure), "0.3:0.1"]) == 1
    said = capsys.readouterr().err
    assert said == f"shtaerman: error: {NO_SPACE} (writing --out '{figure}'){TAIL}"


def test_a_sweep_file_on_a_full_disk_is_named(tmp_path, monkeypatch):
    from shtaerman.sweep import engine

    def full(source, target):
        raise OSError(errno.ENOSPC, os.strerror(errno.ENOSPC))

    monkeypatch.setattr(engine.os, "replace", full)
    with pytest.raises(OSError) as raised:
        engine._atomic_write(tmp_path / "results.json", "{}")
    assert (raised.value.errno, raised.value.filename) == (
        errno.ENOSPC,
        str(tmp_path / "results.json"),
    )
    assert list(tmp_path.iterdir()) == []  # the temporary file removed


def test_a_sweep_folder_whose_marker_found_the_disk_full_is_removed(tmp_path, monkeypatch):
    """Its sweep.toml and cases/ were left without the marker: "nothing was saved", and the
    same command then refused the folder as "not a sweep folder" (left66). Now none is left."""
    from shtaerman.sweep import engine, parse_sweep

    spec = parse_sweep('name = "g"\nkind = "impact"\n[axes]\nvelocity = [1.0]\n')
    real = engine._atomic_write

    def full(path, text):
        if path.name == engine.MARKER_FILE:
            raise OSError(errno.ENOSPC, os.strerror(errno.ENOSPC), str(path))
        real(path, text)

    monkeypatch.setattr(engine, "_atomic_write", full)
    create = engine._check_folder(
        spec, tmp_path / "out", tmp_path / "old", resume=False, force=False
    )
    with pytest.raises(OSError, match="No space left on device"):
        create()
    assert list(tmp_path.iterdir()) == []
