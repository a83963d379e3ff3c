"""What ``shtaerman sweep`` says at the end names what it wrote, and nothing it did not."""

from pathlib import Path

import pytest

from shtaerman.cli import main

AXES = {
    1: "velocity = [1.0, 2.0]",
    3: "velocity = [1.0, 2.0]\nmass = [0.5, 0.7]\nexponent = [1.5, 2.0]",
}


@pytest.mark.parametrize("axes", sorted(AXES))
def test_the_results_line_names_only_what_the_sweep_wrote(tmp_path, capsys, axes):
    # figures are drawn over 1 or 2 axes only: a 3-axis sweep printed a figures folder it never
    # made; the line now lists exactly the entries of the folder it names, figures included
    path = tmp_path / "grid.toml"
    path.write_text(f'name = "grid"\nkind = "impact"\n[axes]\n{AXES[axes]}\n')
    out = tmp_path / "out"
    assert main(["sweep", str(path), "--out", str(out), "--workers", "1"]) == 0
    [line] = [s for s in capsys.readouterr().out.splitlines() if s.startswith("results: ")]
    named = [Path(word) for word in line.split()[1:]]
    assert all(p.parent == out for p in named), line
    drawn = sorted(p.name for p in (out / "figures").glob("*.png"))
    assert ("figures" in {p.name for p in named}) == bool(drawn), (line, drawn)
    assert bool(drawn) == (axes == 1)
    assert all(p.exists() for p in named), line
