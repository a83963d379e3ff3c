"""Error bars for the dynamic impact: a ladder refining mesh and time step together.

Three runs with :meth:`shtaerman.fem.dynamic_contact.DynamicSettings.refined` factors K/2,
K/sqrt(2) and K (element sizes / sqrt(2) and time steps x sqrt(2) per level) and Richardson
estimates (:mod:`shtaerman.study.richardson`) of the finest run's x_max, P_max, t_contact,
restitution and radiated fraction 1 - e^2 (and a viscoelastic body's split of it into
dissipated, wave and hysteresis fractions). There is no exact solution to compare with here:
the estimate is what the number carries. A quantity derived from a run (a ratio to the
quasi-static value) is estimated by Richardson on its own values over the levels
(:meth:`DynamicLadder.estimate`), not by propagating the estimates above.

The estimator (:data:`DYNAMIC_ORDER`, :data:`DYNAMIC_SANE`, ``fallback="largest"``): x_max
converges regularly, while P_max, t_contact and e scatter from level to level (the graded
meshes are not nested), so the larger of the two differences between consecutive levels is
reported where no clean order is observed. Its effectivity is measured in
``benchmarks/bench_dynamic_study.py`` (c).
"""

from __future__ import annotations

import math
from collections.abc import Callable, Sequence
from dataclasses import dataclass
from operator import attrgetter

from ...fem.dynamic_contact import (
    MAX_SIZE,
    MIN_STEPS,
    DynamicSettings,
    ImpactRun,
    run_dynamic_impact,
)
from ...theory.indenter import PowerLawIndenter
from ...theory.materials import Material
from ...theory.viscoelastic import PronySeries
from ...validation import InputError, validate_positive
from ..ladder import LADDER_RATIO
from ..richardson import Estimate, richardson

__all__ = [
    "DYNAMIC_ESTIMATED",
    "DYNAMIC_ORDER",
    "DYNAMIC_SANE",
    "LOSS_ESTIMATED",
    "DynamicLadder",
    "check_ladder",
    "complete_ladder",
    "run_dynamic_ladder",
]

DYNAMIC_ESTIMATED = ("x_max", "P_max", "t_contact", "restitution", "energy_radiated_fraction")
"""The dynamic results that get an error estimate."""
LOSS_ESTIMATED = (
    "energy_dissipated_fraction",
    "energy_wave_fraction",
    "energy_hysteresis_fraction",
)
"""A viscoelastic body's split of 1 - e^2 (:attr:`ImpactRun.losses`), estimated
too when the runs have it."""
DYNAMIC_ORDER = 2.0
"""Asymptotic order used for the correction: generalized-alpha is second order in dt, and the
graded P2 mesh converges at 2.2-2.7 here (x_max refining only the mesh); the smaller order
gives the larger, conservative correction. With each ladder's observed order (x_max: 1.8-3.7,
the time and mesh parts mixing), the estimate fell to 0.51 of the difference to the finest run."""
DYNAMIC_SANE = (1.0, 5.0)
"""Observed orders taken as asymptotic (as :data:`.accuracy.SANE_ORDERS`); otherwise, and for
differences that do not shrink monotonically, the largest of the two differences."""


@dataclass(frozen=True)
class DynamicLadder:
    """Three dynamic runs, coarse to fine, and the estimates of the finest.

    Attributes
    ----------
    refines : tuple of float
        Refinement factors of the levels.
    settings : tuple of DynamicSettings
        The numerical settings of the levels.
    results : tuple of ImpactRun
        The runs; ``results[-1]`` is the answer.
    estimates : dict of str to Estimate
        Per quantity of :data:`DYNAMIC_ESTIMATED` (and of :data:`LOSS_ESTIMATED` for a
        viscoelastic body).
    """

    refines: tuple[float, ...]
    settings: tuple[DynamicSettings, ...]
    results: tuple[ImpactRun, ...]
    estimates: dict[str, Estimate]

    @property
    def finest(self) -> ImpactRun:
        """The finest run: the reported numbers."""
        return self.results[-1]

    def estimate(self, quantity: Callable[[ImpactRun], float]) -> Estimate:
        """Richardson on ``quantity`` of each level's run (e.g. x_c / x_max - 1)."""
        return _over_levels(self.results, quantity)

    def to_dict(self, estimates: dict[str, Estimate] | None = None) -> dict[str, object]:
        """The JSON keys ``error_estimate``, ``extrapolated``, ``mesh_ladder`` and details,
        of ``estimates`` (default: :attr:`estimates`)."""
        estimates = self.estimates if estimates is None else estimates
        return {
            "error_estimate": {k: e.error for k, e in estimates.items()},
            "extrapolated": {k: e.extrapolated for k, e in estimates.items()},
            "estimate_details": {k: e.to_dict() for k, e in estimates.items()},
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


def check_ladder(settings: DynamicSettings) -> None:
    """Raise :class:`~shtaerman.validation.InputError` unless the ladder's coarsest level
    (``settings.refined(1/2)``: mesh sizes x2, steps / 2) is valid, before anything runs."""
    fewest = math.ceil((MIN_STEPS - 0.5) * LADDER_RATIO**2)  # its level rounds to MIN_STEPS
    if settings.steps < fewest:  # the usual cause: name the input the user gave
        raise InputError(
            f"time_steps: the error-estimate ladder's coarsest level halves the time steps, so "
            f"it needs at least {fewest} per t_y, got {settings.steps}",
            "time_steps",
        )
    largest = MAX_SIZE / LADDER_RATIO**2
    if settings.size > largest * (1.0 + 1e-12):
        raise InputError(
            f"mesh_size: the error-estimate ladder's coarsest level doubles the mesh size, so it "
            f"must lie in (0, {largest:g}] with the estimate (or turn the estimate off), got "
            f"{settings.size!r}",
            "mesh_size",
        )
    try:
        settings.refined(1.0 / LADDER_RATIO**2)
    except InputError as error:
        raise InputError(
            f"the error-estimate ladder's coarsest level (mesh x2, steps / 2) is invalid: {error}"
        ) from None


def _over_levels(results: Sequence[ImpactRun], quantity: Callable[[ImpactRun], float]) -> Estimate:
    values = [quantity(result) for result in results]
    return richardson(
        values, LADDER_RATIO, order=DYNAMIC_ORDER, sane=DYNAMIC_SANE, fallback="largest"
    )


def complete_ladder(
    finest: ImpactRun,
    indenter: PowerLawIndenter,
    half_space: Material,
    density: float,
    mass: float,
    velocity: float,
    settings: DynamicSettings,
    *,
    refine: float = 1.0,
    progress: Callable[[str], None] | None = None,
    prony: PronySeries | None = None,
    friction: float | None = None,
) -> DynamicLadder:
    """The ladder of a run already made with ``settings`` (and ``prony``, ``friction``): the
    two coarser levels (``settings.refined(1/2)`` and ``refined(1/sqrt 2)``) are run, then the
    estimates."""
    report = progress or (lambda _line: None)
    coarse = [settings.refined(1.0 / LADDER_RATIO**2), settings.refined(1.0 / LADDER_RATIO)]
    results = []
    for level in coarse:
        result = run_dynamic_impact(
            indenter, half_space, density, mass, velocity, level, prony=prony, friction=friction
        )
        report(f"dynamic ladder: {result.mesh['dofs']} dofs, {level.steps} steps")
        results.append(result)
    results.append(finest)
    refines = (refine / LADDER_RATIO**2, refine / LADDER_RATIO, refine)
    estimates = {key: _over_levels(results, attrgetter(key)) for key in DYNAMIC_ESTIMATED}
    if finest.losses:
        for key in LOSS_ESTIMATED:
            estimates[key] = _over_levels(results, lambda r, key=key: r.losses[key])
    return DynamicLadder(refines, (*coarse, settings), tuple(results), estimates)


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
        Passed to the finest run (e.g. ``snapshot_times``); ``prony`` and ``friction`` to
        every level.

    Returns
    -------
    DynamicLadder
    """
    refine = validate_positive("refine", refine)
    finest = (DynamicSettings() if settings is None else settings).refined(refine)
    check_ladder(finest)  # every level checked before any run
    result = run_dynamic_impact(indenter, half_space, density, mass, velocity, finest, **options)
    return complete_ladder(
        result,
        indenter,
        half_space,
        density,
        mass,
        velocity,
        finest,
        refine=refine,
        progress=progress,
        prony=options.get("prony"),  # type: ignore[arg-type]
        friction=options.get("friction"),  # type: ignore[arg-type]
    )
