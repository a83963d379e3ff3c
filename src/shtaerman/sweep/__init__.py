"""Parameter sweeps: a TOML grid of cases of one kind, run on dask.distributed.

>>> from shtaerman.sweep import load_sweep, run_sweep
>>> outcome = run_sweep(load_sweep("sweeps/impact-velocity.toml"), "out", workers=2)

See :mod:`shtaerman.sweep.spec` (the file), :mod:`shtaerman.sweep.kinds` (what a case computes,
and how to add a kind), :mod:`shtaerman.sweep.engine` (the cluster and the result folder) and
:mod:`shtaerman.sweep.figures`.
"""

from .engine import SweepInterrupted, SweepOutcome, run_sweep
from .kinds import KINDS, Kind, Parameter, register_kind
from .spec import SweepError, SweepSpec, find_sweep, load_sweep, parse_sweep

__all__ = [
    "KINDS",
    "Kind",
    "Parameter",
    "SweepError",
    "SweepInterrupted",
    "SweepOutcome",
    "SweepSpec",
    "find_sweep",
    "load_sweep",
    "parse_sweep",
    "register_kind",
    "run_sweep",
]
