"""Parameter sweeps: a TOML grid of cases of one kind, run on dask.distributed.

>>> from shtaerman.sweep import load_sweep, run_sweep
>>> outcome = run_sweep(load_sweep("sweeps/impact-velocity.toml"), "out", workers=2)

See :mod:`shtaerman.sweep.spec` (the file), :mod:`shtaerman.sweep.kinds` (what a case computes,
and how to add a kind), :mod:`shtaerman.sweep.engine` (the cluster and the result folder) and
:mod:`shtaerman.sweep.figures`.

Names are imported on first use: the command line registers ``shtaerman sweep`` (and a dask
worker runs its preload, ``_worker.py``) without loading the engine, the kinds or the FEM.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

from ..lazy import lazy_names

if TYPE_CHECKING:
    from .engine import SweepInterrupted as SweepInterrupted
    from .engine import SweepOutcome as SweepOutcome
    from .engine import run_sweep as run_sweep
    from .kinds import KINDS as KINDS
    from .kinds import Kind as Kind
    from .kinds import Parameter as Parameter
    from .kinds import register_kind as register_kind
    from .spec import SweepError as SweepError
    from .spec import SweepSpec as SweepSpec
    from .spec import find_sweep as find_sweep
    from .spec import load_sweep as load_sweep
    from .spec import parse_sweep as parse_sweep

_HOMES = {
    ".engine": ("SweepInterrupted", "SweepOutcome", "run_sweep"),
    ".kinds": ("KINDS", "Kind", "Parameter", "register_kind"),
    ".spec": ("SweepError", "SweepSpec", "find_sweep", "load_sweep", "parse_sweep"),
}
"""The module of each public name."""

__all__ = sorted(  # constants, classes, functions
    (name for names in _HOMES.values() for name in names),
    key=lambda name: (not name.isupper(), name.islower(), name),
)


__getattr__ = lazy_names(__name__, _HOMES)
