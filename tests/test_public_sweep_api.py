"""What ``sh.sweep`` takes and returns is public too: ``sh.SweepSpec``, ``sh.SweepOutcome``."""

import inspect
import subprocess
import sys

import pytest

import shtaerman as sh
import shtaerman.sweep.engine as engine
import shtaerman.sweep.spec as spec


def test_the_sweeps_spec_and_outcome_are_public_names():
    assert sh.SweepSpec is spec.SweepSpec and sh.SweepOutcome is engine.SweepOutcome
    assert {"SweepSpec", "SweepOutcome"} <= set(sh.__all__) <= set(dir(sh))
    loaded = spec.load_sweep(spec.find_sweep("nu-grid"))
    assert isinstance(loaded, sh.SweepSpec)


def test_naming_them_does_not_load_them_with_the_package():
    code = "import sys, shtaerman; print('shtaerman.sweep' in sys.modules)"
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    assert out.stdout.strip() == "False"


def test_help_of_sh_sweep_is_the_calls_then_the_packages():
    """adv53: help(sh.sweep) showed the package's docstring alone ('Parameter sweeps: ...'),
    not what sh.sweep(...) takes; it shows the call's first, with its signature."""
    import inspect
    import pydoc

    from shtaerman.api.studies import sweep

    text = pydoc.render_doc(sh.sweep, renderer=pydoc.plaintext)
    call = inspect.getdoc(sweep).splitlines()[0]
    assert call in text and "path_or_spec : str, path or SweepSpec" in text
    assert f"sh.sweep{inspect.signature(sweep)}" in text
    assert text.index(call) < text.index("Parameter sweeps: a TOML grid")  # the package's after


def test_sh_sweep_takes_what_the_command_line_takes(tmp_path):
    """guards55: 'sweep --figure-format svg' had no keyword in sh.sweep (TypeError), and
    force='False' was taken as true."""
    from shtaerman.api.studies import sweep
    from shtaerman.cli import build_parser

    (command,) = (
        choices["sweep"]
        for action in build_parser()._actions
        if isinstance(choices := getattr(action, "choices", None), dict) and "sweep" in choices
    )
    options = {action.dest for action in command._actions} - {"help", "sweep"}
    assert options and options <= set(inspect.signature(sweep).parameters) - {"path_or_spec"}
    out = tmp_path / "out"
    with pytest.raises(sh.InputError, match=r"^figure_format must be one of png, svg, pdf, got"):
        sh.sweep("impact-velocity", out=out, figure_format="bmp")  # refused before a cluster
    with pytest.raises(sh.InputError, match=r"^force must be True or False, got 'False'"):
        sh.sweep("impact-velocity", out=out, force="False")
    with pytest.raises(sh.InputError, match=r"^progress must be True, False or None, got 'no'"):
        sh.sweep("impact-velocity", out=out, progress="no")  # ran with a progress bar
    assert not out.exists()
