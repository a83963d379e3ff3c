"""Error bars for the dynamic impact: a ladder refining mesh and time step together.

Three runs with :meth:`shtaerman.fem.dynamic_contact.DynamicSettings.refined` factors K/2,
K/sqrt(2) and K (element sizes / sqrt(2) and time steps x sqrt(2) per level) and Richardson
estimates (:mod:`.richardson`) of the finest run's x_max, P_max, t_contact and restitution.
There is no exact solution to compare with here: the estimate is what the number carries.
The coarse levels cost about 0.5 of the finest (dofs / 2 and steps / sqrt 2 per level).
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass

from ..fem.dynamic_contact import DynamicImpactResult, DynamicSettings, run_dynamic_impact
from ..theory.indenter import PowerLawIndenter
from ..theory.materials import Material
from ..validation import validate_positive
from .accuracy import LADDER_RATIO
from .richardson import Estimate, richardson

__all__ = ["DYNAMIC_ESTIMATED", "DynamicLadder", "run_dynamic_ladder"]

DYNAMIC_ESTIMATED = ("x_max", "P_max", "t_contact", "restitution")
"""The dynamic results that get an error estimate."""


@dataclass(frozen=True)
class DynamicLadder:
    """Three dynamic runs, coarse to fine, and the estimates of the finest.

    Attributes
    ----------
    refines : tuple of float
        Refinement factors of the levels.
    settings : tuple of DynamicSettings
        The numerical settings of the levels.
    results : tuple of DynamicImpactResult
        The runs; ``results[-1]`` is the answer.
    estimates : dict of str to Estimate
        Per quantity of :data:`DYNAMIC_ESTIMATED`.
    """

    refines: tuple[float, ...]
    settings: tuple[DynamicSettings, ...]
    results: tuple[DynamicImpactResult, ...]
    estimates: dict[str, Estimate]

    @property
    def finest(self) -> DynamicImpactResult:
        """The finest run: the reported numbers."""
        return self.results[-1]

    def to_dict(self) -> dict[str, object]:
        """The JSON keys ``error_estimate``, ``extrapolated``, ``mesh_ladder`` and details."""
        return {
            "error_estimate": {k: e.error for k, e in self.estimates.items()},
            "extrapolated": {k: e.extrapolated for k, e in self.estimates.items()},
            "estimate_details": {k: e.to_dict() for k, e in self.estimates.items()},
            "mesh_ladder": [
                {
                    "refine": refine,
                    "dofs": int(result.mesh["dofs"]),
                    "steps": level.steps,
                    "seconds": float(result.timings.get("total", float("nan"))),
                }
                for refine, level, result in zip(
                    self.refines, self.settings, self.results, strict=True
                )
            ],
        }


def run_dynamic_ladder(
    indenter: PowerLawIndenter,
    half_space: Material,
    density: float,
    mass: float,
    velocity: float,
    settings: DynamicSettings | None = None,
    *,
    refine: float = 1.0,
    progress: Callable[[str], None] | None = None,
    **options: object,
) -> DynamicLadder:
    """The dynamic impact at refine / 2, refine / sqrt(2) and refine, with error estimates.

    Parameters
    ----------
    indenter, half_space, density, mass, velocity, settings
        As for :func:`shtaerman.fem.dynamic_contact.run_dynamic_impact` (SI units).
    refine : float
        Refinement of the finest level (1: ``settings`` as given).
    progress : callable, optional
        Receives one line per level.
    **options
        Passed to every run (e.g. ``snapshot_times``; used for the finest run only).

    Returns
    -------
    DynamicLadder
    """
    refine = validate_positive("refine", refine)
    settings = DynamicSettings() if settings is None else settings
    refines = (refine / LADDER_RATIO**2, refine / LADDER_RATIO, refine)
    levels = [settings.refined(factor) for factor in refines]  # all checked before any run
    report = progress or (lambda _line: None)
    results = []
    for index, level in enumerate(levels):
        extra = options if index == len(levels) - 1 else {}
        result = run_dynamic_impact(indenter, half_space, density, mass, velocity, level, **extra)
        report(f"dynamic x{refines[index]:.3g}: {result.mesh['dofs']} dofs, {level.steps} steps")
        results.append(result)
    estimates = {
        key: richardson([getattr(r, key) for r in results], LADDER_RATIO)
        for key in DYNAMIC_ESTIMATED
    }
    return DynamicLadder(refines, tuple(levels), tuple(results), estimates)
