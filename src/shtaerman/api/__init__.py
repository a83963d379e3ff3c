"""The public Python API, re-exported by :mod:`shtaerman` (``import shtaerman as sh``).

- :func:`impact`: the exact quasi-static impact (Ateb functions);
- :func:`contact`: the FEM contact curve against Shtaerman's solution, with error estimates;
- :func:`dynamic`: the elastodynamic FE impact against the quasi-static theory;
- :func:`run_study`, :func:`sweep`: study files and parameter sweeps.

Every result is a frozen dataclass whose attributes are the keys of the matching CLI
command's ``--json`` object, and whose ``to_dict()`` is that object.
"""

from ..theory.indenter import PowerLawIndenter
from ..theory.materials import RIGID, Material
from ..validation import InputError
from .fem_contact import ContactResult, contact
from .fem_dynamic import DynamicResult, dynamic
from .quasi_static import ImpactResult, impact
from .studies import StudyResults, run_study, sweep

__all__ = [
    "RIGID",
    "ContactResult",
    "DynamicResult",
    "ImpactResult",
    "InputError",
    "Material",
    "PowerLawIndenter",
    "StudyResults",
    "contact",
    "dynamic",
    "impact",
    "run_study",
    "sweep",
]
