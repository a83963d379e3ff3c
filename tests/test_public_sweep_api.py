"""What ``sh.sweep`` takes and returns is public too: ``sh.SweepSpec``, ``sh.SweepOutcome``."""

import subprocess
import sys

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
