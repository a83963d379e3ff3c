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
