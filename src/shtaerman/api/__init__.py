"""The public Python API, re-exported by :mod:`shtaerman` (``import shtaerman as sh``).

- :func:`impact`: the exact quasi-static impact (Ateb functions);
- :func:`contact`: the FEM contact curve against Shtaerman's solution, with error estimates;
- :func:`dynamic`: the elastodynamic FE impact against the quasi-static theory;
- :func:`effects`: the effect table of an impact (the pad, the waves, finite strain, ...);
- :func:`fit`: the rubber's constants from a measurement, with 95 % intervals;
- :func:`run_study`, :func:`sweep`: study files and parameter sweeps.

Every result is a frozen dataclass whose attributes are the keys of the matching CLI
command's ``--json`` object, and whose ``to_dict()`` is that object. The public names are
listed once, in :data:`shtaerman.__all__`. Names are imported on first use, so that
``shtaerman.api.quasi_static`` (the command line's ``impact``) loads neither the FEM nor
scipy.stats.
"""

from __future__ import annotations

import sys
from typing import TYPE_CHECKING

from ..lazy import lazy_names

if TYPE_CHECKING:
    from ..fem.dynamic_contact import DynamicSettings as DynamicSettings
    from ..fem.mesh import MeshSettings as MeshSettings
    from ..fitting.result import FitResult as FitResult
    from ..fitting.run import fit as fit
    from ..problem import Body as Body
    from ..problem import Geometry as Geometry
    from ..problem import Interface as Interface
    from ..problem import Loading as Loading
    from ..problem import Problem as Problem
    from ..problem import Striker as Striker
    from ..theory.indenter import PowerLawIndenter as PowerLawIndenter
    from ..theory.materials import RIGID as RIGID
    from ..theory.materials import Material as Material
    from ..theory.profiles import SphereIndenter as SphereIndenter
    from ..theory.profiles import TabulatedIndenter as TabulatedIndenter
    from ..validation import InputError as InputError
    from ..validation import LimitError as LimitError
    from .dynamic_result import DynamicResult as DynamicResult
    from .effect_table import EffectTable as EffectTable
    from .effect_table import effects as effects
    from .fem_contact import ContactResult as ContactResult
    from .fem_contact import contact as contact
    from .fem_dynamic import dynamic as dynamic
    from .quasi_static import ImpactResult as ImpactResult
    from .quasi_static import impact as impact
    from .studies import StudyResults as StudyResults
    from .studies import run_study as run_study
    from .studies import sweep as sweep

_HOMES = {
    "..fem.dynamic_contact": ("DynamicSettings",),
    "..fem.mesh": ("MeshSettings",),
    "..fitting.result": ("FitResult",),
    "..fitting.run": ("fit",),
    "..problem": ("Body", "Geometry", "Interface", "Loading", "Problem", "Striker"),
    "..theory.indenter": ("PowerLawIndenter",),
    "..theory.materials": ("RIGID", "Material"),
    "..theory.profiles": ("SphereIndenter", "TabulatedIndenter"),
    "..validation": ("InputError", "LimitError"),
    ".dynamic_result": ("DynamicResult",),
    ".effect_table": ("EffectTable", "effects"),
    ".fem_contact": ("ContactResult", "contact"),
    ".fem_dynamic": ("dynamic",),
    ".quasi_static": ("ImpactResult", "impact"),
    ".studies": ("StudyResults", "run_study", "sweep"),
}
"""The module of each public name (relative to this package)."""

_PACKAGE = sys.modules[__name__.rpartition(".")[0]]  # shtaerman, loaded before its subpackages
__all__ = [  # not __version__, sweep types
    name for name in _PACKAGE.__all__ if any(name in names for names in _HOMES.values())
]


__getattr__ = lazy_names(__name__, _HOMES)
