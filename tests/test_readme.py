"""The README's examples are real: every ``console`` command runs, and the Python block too.

Each console block runs in a fresh folder, its commands in order, in-process through
``shtaerman.cli.main`` (a command's files are there for the next one, e.g. ``init-study`` then
``verify my-study.toml``). ``make TARGET`` lines are checked against the Makefile, and
``source .venv/bin/activate`` against the Makefile's virtual environment; every other line must
be a ``shtaerman`` command that exits with 0. Study computations already made this session for
the same study (tests/conftest.py) are reused; everything else runs.
"""

import re
import shlex
from pathlib import Path

import pytest

import shtaerman.output.folder
from shtaerman.cli import main
from shtaerman.study.run import run_study

ROOT = Path(__file__).resolve().parents[1]
README = (ROOT / "README.md").read_text(encoding="utf-8")
MAKEFILE = (ROOT / "Makefile").read_text(encoding="utf-8")
BLOCKS = re.findall(r"```console\n(.*?)```", README, re.DOTALL)
PYTHON = re.findall(r"```python\n(.*?)```", README, re.DOTALL)


def commands(block: str) -> list[str]:
    """The block's commands, trailing comments ("  # ...") removed."""
    lines = (re.sub(r"\s+#\s.*$", "", line).strip() for line in block.splitlines())
    return [line for line in lines if line]


def test_readme_has_console_examples():
    assert len(BLOCKS) >= 4
    every = [command for block in BLOCKS for command in commands(block)]
    assert "shtaerman init-study my-study.toml" in every
    assert "shtaerman verify my-study.toml --quick" in every
    assert every.index("shtaerman init-study my-study.toml") < every.index(
        "shtaerman verify my-study.toml --quick"
    )


@pytest.mark.parametrize(
    "block", BLOCKS, ids=[commands(b)[0].split("  ")[0].replace(" ", "_") for b in BLOCKS]
)
def test_console_block_runs(block, tmp_path, monkeypatch, capsys, quick_outcomes):
    def cached_run_study(study, *, quick=False, progress=None):
        outcome = quick_outcomes.get(study.name)
        if quick and outcome is not None and outcome.study == study:
            return outcome
        return run_study(study, quick=quick, progress=progress)

    monkeypatch.setattr(shtaerman.output.folder, "run_study", cached_run_study)
    monkeypatch.chdir(tmp_path)
    for command in commands(block):
        words = shlex.split(command)
        if words[0] == "make":
            assert re.search(rf"^{words[1]}:", MAKEFILE, re.MULTILINE), command
        elif words[0] == "source":
            venv = re.search(r"^VENV \?= (\S+)$", MAKEFILE, re.MULTILINE).group(1)
            assert words[1] == f"{venv}/bin/activate", command
        else:
            assert words[0] in ("shtaerman", ".venv/bin/shtaerman"), command
            code = 0
            try:
                code = main(words[1:])
            except SystemExit as exit:  # --help and --version exit through argparse
                code = exit.code
            _, err = capsys.readouterr()
            assert code == 0, f"{command}: exit {code}\n{err}"
            assert "Traceback" not in err, command


def test_python_example_runs():
    [block] = PYTHON
    namespace = {}
    exec(compile(block, "README.md", "exec"), namespace)
    q, curve = namespace["q"], namespace["curve"]
    # the numbers the README's comments show (this case, exact)
    assert q.x_c == pytest.approx(4.6252e-3, rel=1e-4)
    assert q.P_c == pytest.approx(276.266, rel=1e-5)
    assert q.t_c == pytest.approx(3.3827e-3, rel=1e-4)
    # the FEM curve reaches this case's x_c and agrees with Shtaerman's force there within
    # twice its own estimate (the estimator's measured effectivity is >= 0.55)
    assert curve.depth[-1] == pytest.approx(q.x_c, rel=1e-12)
    assert curve.force[-1] == pytest.approx(q.P_c, rel=2 * curve.error_estimate["force"])
