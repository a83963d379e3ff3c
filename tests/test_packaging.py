"""The wheel carries the package data a non-editable install needs."""

import subprocess
import sys
import zipfile
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
SHIPPED = [
    "shtaerman/paper/paper_tables.json",
    "shtaerman/cli/__init__.py",
    "shtaerman/py.typed",
    "shtaerman/output/templates/report.md.j2",
    "shtaerman/output/templates/report.html.j2",
    "shtaerman/meshes/halfspace.geo",
    "shtaerman/meshes/layer.geo",
    "shtaerman/studies/paper.toml",
    "shtaerman/studies/hertz.toml",
    "shtaerman/studies/compressible.toml",
    "shtaerman/studies/table4.toml",
    "shtaerman/studies/extended/rubber_models.toml",
    "shtaerman/studies/extended/silicone.toml",
    "shtaerman/data/prony/zhermack-elite-double-32.csv",
    "shtaerman/sweeps/nu-grid.toml",
    "shtaerman/sweeps/impact-velocity.toml",
    "shtaerman/cli/templates/contact.toml.in",
    "shtaerman/cli/templates/dynamic.toml.in",
    "shtaerman/cli/templates/effects.toml.in",
    "shtaerman/cli/templates/finite-strain.toml.in",
    "shtaerman/cli/templates/indenter.toml.in",
]


@pytest.fixture(scope="module")
def wheel_names(tmp_path_factory):
    out = tmp_path_factory.mktemp("wheel")
    subprocess.run(
        [
            sys.executable,
            "-m",
            "pip",
            "wheel",
            str(ROOT),
            "--no-deps",
            "--no-build-isolation",
            "--quiet",
            "--wheel-dir",
            str(out),
        ],
        check=True,
        capture_output=True,
    )
    [wheel] = out.glob("shtaerman-*.whl")
    with zipfile.ZipFile(wheel) as archive:
        return {name: archive.read(name) for name in archive.namelist()}


@pytest.mark.parametrize("name", SHIPPED)
def test_wheel_ships(wheel_names, name):
    assert name in wheel_names


def test_console_script_is_declared(wheel_names):
    [entry_points] = [n for n in wheel_names if n.endswith("entry_points.txt")]
    declared = wheel_names[entry_points].decode().split()
    # the entry holds SIGINT and SIGTERM while the command line is imported (tests/test_entry.py)
    assert "shtaerman = shtaerman.entry:main".split() == declared[declared.index("shtaerman") :][:3]
