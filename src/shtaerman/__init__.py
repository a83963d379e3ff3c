"""shtaerman: FEM cross-check of Shtaerman's power-law contact and the impact it implies.

The public API (``import shtaerman as sh``; see :mod:`shtaerman.api`)::

    indenter = sh.PowerLawIndenter(shape_coefficient=12.0, exponent=1.8)
    rubber = sh.Material(youngs_modulus=4e6, poisson_ratio=0.49, density=1100.0)
    q = sh.impact(indenter, rubber, mass=0.25, velocity=2.0)   # exact quasi-static impact
    ball = sh.SphereIndenter(radius=0.01)    # or sh.TabulatedIndenter.from_csv("tip.csv")
    q = sh.impact(ball, rubber, mass=0.25, velocity=2.0)       # Sneddon's sphere, exact
    c = sh.contact(indenter, rubber, mass=0.25, velocity=2.0)  # FEM curve up to q.x_c
    d = sh.dynamic(indenter, rubber, mass=0.25, velocity=2.0)  # dynamic FE impact
    case = sh.Problem.impact(indenter, rubber, mass=0.25, velocity=2.0, thickness=0.012)
    d = sh.dynamic(case, time_steps=200)                       # the same, from one Problem
    table = sh.effects(case)                  # which effect (pad, waves, ...) moves P_max most
    fitted = sh.fit("indentation", "curve.csv", case, unknowns=["E2"])  # E2 from a measurement
    sh.run_study("paper", out="results"); sh.sweep("nu-grid", workers=2)   # -> sh.SweepOutcome

Names are imported on first use, so ``import shtaerman`` loads neither numpy nor the FEM.
``sh.sweep`` is the :mod:`shtaerman.sweep` package, callable as :func:`shtaerman.api.sweep`.
"""

from __future__ import annotations

import importlib
import inspect
import sys
import types
from typing import TYPE_CHECKING, Any

if TYPE_CHECKING:
    from .api import (
        RIGID,
        Body,
        ContactResult,
        DynamicResult,
        DynamicSettings,
        EffectTable,
        FitResult,
        Geometry,
        ImpactResult,
        InputError,
        Interface,
        LimitError,
        Loading,
        Material,
        MeshSettings,
        PowerLawIndenter,
        Problem,
        SphereIndenter,
        Striker,
        StudyResults,
        TabulatedIndenter,
        contact,
        dynamic,
        effects,
        fit,
        impact,
        run_study,
        sweep,
    )
    from .sweep.engine import SweepOutcome
    from .sweep.spec import SweepSpec

from .lazy import lazy_names
from .version import __version__

__all__ = [
    "RIGID",
    "Body",
    "ContactResult",
    "DynamicResult",
    "DynamicSettings",
    "EffectTable",
    "FitResult",
    "Geometry",
    "ImpactResult",
    "InputError",
    "Interface",
    "LimitError",
    "Loading",
    "Material",
    "MeshSettings",
    "PowerLawIndenter",
    "Problem",
    "SphereIndenter",
    "Striker",
    "StudyResults",
    "SweepOutcome",
    "SweepSpec",
    "TabulatedIndenter",
    "__version__",
    "contact",
    "dynamic",
    "effects",
    "fit",
    "impact",
    "run_study",
    "sweep",
]


_FROM_SWEEP = ("SweepOutcome", "SweepSpec")
"""What :func:`sweep` takes and returns, from :mod:`shtaerman.sweep`."""

_api_name = lazy_names(
    __name__,
    {
        ".sweep": _FROM_SWEEP,
        ".api": tuple(set(__all__) - {*_FROM_SWEEP, "__version__", "sweep"}),
    },
)


def __getattr__(name: str) -> Any:
    """The API's names, imported from :mod:`shtaerman.api` (or :mod:`shtaerman.sweep`) on
    first use; ``sweep`` is the :mod:`shtaerman.sweep` package."""
    if name == "sweep":
        return importlib.import_module(".sweep", __name__)
    return _api_name(name)


def __dir__() -> list[str]:
    """The public API and the subpackages already imported."""
    loaded = {
        key
        for key, value in globals().items()
        if isinstance(value, types.ModuleType) and value.__name__.startswith(__name__ + ".")
    }
    return sorted(set(__all__) | loaded)


class _CallableSweep(types.ModuleType):
    """The :mod:`shtaerman.sweep` package, also callable as :func:`shtaerman.api.sweep`."""

    def __call__(self, *args: Any, **kwargs: Any) -> Any:
        from .api.studies import sweep

        return sweep(*args, **kwargs)

    @property
    def __signature__(self) -> inspect.Signature:
        from .api.studies import sweep

        return inspect.signature(sweep)

    def _doc(self) -> str:
        """``help(sh.sweep)``: the call's docstring (what ``sh.sweep(...)`` does), then the
        package's (its modules), where help showed the package's alone."""
        from .api.studies import sweep

        call = f"{inspect.cleandoc(sweep.__doc__ or '')}\n\nsh.sweep{inspect.signature(sweep)}"
        package = inspect.cleandoc(self.__dict__.get("__doc__") or "")
        return f"{call}\n\nThe package {self.__name__}: {package}"

    def _set_doc(self, value: str | None) -> None:
        self.__dict__["__doc__"] = value  # a reload sets the package's

    __doc__ = property(_doc, _set_doc)  # type: ignore[assignment]


class _Package(types.ModuleType):
    """This package: its ``sweep`` subpackage, once imported, becomes callable (``sh.sweep``
    both runs a sweep and is the package)."""

    def __setattr__(self, name: str, value: Any) -> None:
        if name == "sweep" and isinstance(value, types.ModuleType):
            value.__class__ = _CallableSweep
        super().__setattr__(name, value)


sys.modules[__name__].__class__ = _Package
