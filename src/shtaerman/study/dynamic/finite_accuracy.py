"""Error bars for the finite-strain impact: the dynamic ladder over the rubber body.

The levels are those of the linear impact (:mod:`.accuracy`): refine / 2, refine / sqrt(2) and
refine, each dividing the mesh size field (:meth:`shtaerman.fem.mesh.MeshSettings.refined`) and
multiplying the time steps by its factor, so h and dt shrink together. The estimates are the
same Richardson estimates (:data:`.accuracy.DYNAMIC_ORDER`, ``fallback="largest"``) of
x_max, P_max, t_contact, e and 1 - e^2 (and a viscoelastic body's dissipated fraction).

A level whose run fails numerically (a Newton or a step equation that does not converge) is run
again with :data:`RETRY_STEPS` times its time steps; it then enters the ladder with those steps
(its time error is smaller than its place in the ladder assumes, which enlarges the last
difference: the estimate stays on the safe side). If the retry fails too, the run keeps the
levels that passed, reports the finest of them and marks the estimate as missing, with the
reason (:attr:`FiniteLadder.missing`) and a warning; it fails only when no level passed.
"""

from __future__ import annotations

import math
import warnings
from collections.abc import Callable, Sequence
from dataclasses import dataclass, replace
from typing import Any

from ...fem.finite_dynamic import (
    MAX_STEPS,
    MIN_STEPS,
    FiniteImpactSettings,
    ImpactRun,
    run_finite_impact,
)
from ...fem.hyperelastic import NewtonError
from ...fem.rubber import GentLockError, RubberModel
from ...guards import ValidityWarning
from ...theory.indenter import PowerLawIndenter
from ...theory.materials import Material
from ...theory.viscoelastic import PronySeries
from ...validation import (
    InputError,
    NumericalFailureError,
    caller_stacklevel,
    validate_positive,
)
from ..ladder import LADDER_RATIO
from ..richardson import Estimate, richardson
from .accuracy import DYNAMIC_ESTIMATED, DYNAMIC_ORDER, DYNAMIC_SANE

__all__ = [
    "RETRY_STEPS",
    "EstimateMissingWarning",
    "FiniteImpact",
    "FiniteLadder",
    "check_finite_ladder",
    "ladder_estimates",
    "over_levels",
    "refined",
    "run_finite_ladder",
]

RETRY_STEPS = 2
"""A failed level is run once more with this many times its time steps."""
FAILURES = (NewtonError, NumericalFailureError)
"""The numerical failures of a run that a retry may cure (bad input is not retried)."""


class EstimateMissingWarning(UserWarning):
    """A ladder level failed twice: the finest level that passed is reported, with no
    error estimate."""


@dataclass(frozen=True)
class FiniteImpact:
    """The inputs of :func:`shtaerman.fem.finite_dynamic.run_finite_impact` but its settings
    (SI units): the striker, the rubber body, its density, model, Prony series and the
    indenter's friction."""

    indenter: PowerLawIndenter
    half_space: Material
    density: float
    mass: float
    velocity: float
    rubber: RubberModel | None = None
    prony: PronySeries | None = None
    friction: float | None = None
    """None frictionless, inf bonded (no slip), else Coulomb's mu."""

    def run(self, settings: FiniteImpactSettings) -> ImpactRun:
        """One run with ``settings``."""
        return run_finite_impact(
            self.indenter,
            self.half_space,
            self.density,
            self.mass,
            self.velocity,
            settings,
            self.rubber,
            self.prony,
            self.friction,
        )


@dataclass(frozen=True)
class FiniteLadder:
    """The levels of a finite-strain impact, coarse to fine, and the estimates of the finest.

    Attributes
    ----------
    refines : tuple of float
        Refinement factors of the levels.
    settings : tuple of FiniteImpactSettings
        The settings each level ran with (a retried level's doubled steps).
    results : tuple of ImpactRun or None
        The runs; None where a level failed twice.
    failures : tuple of str
        Per level, "" or what failed (a retry that passed is noted too).
    estimates : dict of str to Estimate
        Per quantity; empty when the estimate is missing.
    missing : str
        Why the estimate is missing ("" when there is one).
    """

    refines: tuple[float, ...]
    settings: tuple[FiniteImpactSettings, ...]
    results: tuple[ImpactRun | None, ...]
    failures: tuple[str, ...]
    estimates: dict[str, Estimate]
    missing: str = ""

    @property
    def finest(self) -> ImpactRun:
        """The finest run that passed: the reported numbers."""
        return next(r for r in reversed(self.results) if r is not None)

    def estimate(self, quantity: Callable[[Any], float]) -> Estimate | None:
        """Richardson on ``quantity`` of each level's run (None when the estimate is missing)."""
        if self.missing:
            return None
        return over_levels(self.results, quantity)

    def to_dict(self, estimates: dict[str, Estimate] | None = None) -> dict[str, object]:
        """The JSON keys ``error_estimate``, ``extrapolated``, ``estimate_details`` (None
        when the estimate is missing; then ``estimate_missing`` says why) and
        ``mesh_ladder`` (a failed level's dofs and seconds None, its ``failure`` named)."""
        estimates = self.estimates if estimates is None else estimates
        levels = []
        for refine, level, result, failure in zip(
            self.refines, self.settings, self.results, self.failures, strict=True
        ):
            row: dict[str, Any] = {"refine": refine, "steps": level.steps}
            row["dofs"] = None if result is None else int(result.mesh["dofs"])
            row["seconds"] = None if result is None else float(result.timings["total"])
            levels.append({**row, **({"failure": failure} if failure else {})})
        document: dict[str, object] = {"mesh_ladder": levels}
        if self.missing:
            document.update(error_estimate=None, extrapolated=None, estimate_details=None)
            return {**document, "estimate_missing": self.missing}
        document["error_estimate"] = {k: e.error for k, e in estimates.items()}
        document["extrapolated"] = {k: e.extrapolated for k, e in estimates.items()}
        document["estimate_details"] = {k: e.to_dict() for k, e in estimates.items()}
        return document


def refined(settings: FiniteImpactSettings, factor: float) -> FiniteImpactSettings:
    """Resolved ``settings`` with the mesh size field divided and the time steps multiplied by
    ``factor`` (> 1 refines)."""
    factor = validate_positive("refine", factor)
    assert settings.steps is not None and settings.mesh is not None, "resolve the settings first"
    steps = settings.steps * factor
    if not MIN_STEPS - 0.5 <= steps < MAX_STEPS + 0.5:
        raise InputError(
            f"refine {factor:g} gives {steps:.4g} time steps per t_y from {settings.steps}; "
            f"{MIN_STEPS}-{MAX_STEPS} are allowed",
            "refine",
        )
    return replace(settings, steps=round(steps), mesh=settings.mesh.refined(factor))


def check_finite_ladder(settings: FiniteImpactSettings, refine: float, estimate: bool) -> None:
    """Raise InputError, before any run, unless every level of the ladder ending at
    ``refine`` (only that level without ``estimate``) has valid settings."""
    refine = validate_positive("refine", refine)
    lowest = refine / 2.0 if estimate else refine
    if settings.steps is not None and settings.steps * lowest < MIN_STEPS - 0.5:
        fewest = math.ceil((MIN_STEPS - 0.5) / lowest)
        coarsest = "the error-estimate ladder's coarsest level halves" if estimate else "refine"
        raise InputError(
            f"time_steps: {coarsest} the time steps (refine {lowest:g}), so it needs at least "
            f"{fewest} per t_y, got {settings.steps}; or run without the estimate "
            "(estimate=False, --no-estimate)",
            "time_steps",
        )
    mesh = settings.mesh
    assert mesh is not None, "resolve the settings first"
    smallest = max(mesh.size, mesh.axis_size, mesh.growth, mesh.axis_growth) * refine / lowest
    if refine < smallest * (1.0 - 1e-12):
        raise InputError(
            f"refine must be >= {smallest:.3g} with these mesh settings ("
            + ("the error-estimate ladder's coarsest mesh, refine / 2," if estimate else "it")
            + f" keeps every size and growth <= 1), got {refine!r}"
            + ("; or run without the estimate (estimate=False, --no-estimate)" if estimate else ""),
            "refine",
        )


def over_levels(results: Any, quantity: Callable[[Any], float]) -> Estimate:
    """Richardson on ``quantity`` over the levels; a level without the value (nan) gives an
    estimate of nan error (method ``missing``)."""
    values = [quantity(result) for result in results]
    if all(math.isfinite(value) for value in values):
        return richardson(
            values, LADDER_RATIO, order=DYNAMIC_ORDER, sane=DYNAMIC_SANE, fallback="largest"
        )
    fine = values[-1]
    return Estimate(fine, fine, math.nan, math.nan, "missing", "a level gave no value")


def _level(
    impact: FiniteImpact, settings: FiniteImpactSettings
) -> tuple[FiniteImpactSettings, ImpactRun | Exception, str]:
    """One level run; on a numerical failure run again with :data:`RETRY_STEPS` x its time
    steps. Returns the settings last used, the result (or the retry's error) and a note."""
    try:
        return settings, impact.run(settings), ""
    except GentLockError:  # the rubber's limit, not the numerics: no retry cures it
        raise
    except FAILURES as error:
        first = f"{settings.steps} steps failed ({error})"
    assert settings.steps is not None
    retry = replace(settings, steps=min(RETRY_STEPS * settings.steps, MAX_STEPS))
    try:
        return retry, impact.run(retry), f"{first}; passed with {retry.steps} steps"
    except FAILURES as error:
        return retry, error, f"{first}; the retry with {retry.steps} steps failed too ({error})"


def run_finite_ladder(
    impact: FiniteImpact,
    settings: FiniteImpactSettings,
    *,
    refine: float = 1.0,
    estimate: bool = True,
) -> FiniteLadder:
    """The finite-strain impact at refine (and then, with ``estimate``, at refine / 2 and
    refine / sqrt(2)), with error estimates.

    Parameters
    ----------
    impact : FiniteImpact
        The case.
    settings : FiniteImpactSettings
        Resolved settings of refine 1 (:meth:`FiniteImpactSettings.resolved`).
    refine : float
        Refinement of the finest level.
    estimate : bool
        Run the two coarser levels and estimate (else one level, no estimates).

    Returns
    -------
    FiniteLadder

    Raises
    ------
    shtaerman.validation.InputError
        Settings out of range on some level (before any run).
    NewtonError, shtaerman.validation.NumericalFailureError
        When no level passed (the finest level's retry's error); a Gent rubber's lock
        (:class:`shtaerman.fem.rubber.GentLockError`) at once, without retry.
    """
    check_finite_ladder(settings, refine, estimate)
    factors = (refine / 2.0, refine / LADDER_RATIO, refine) if estimate else (refine,)
    runs = {factors[-1]: _level(impact, refined(settings, factors[-1]))}  # the finest first:
    for factor in factors[:-1]:  # its refusals (a Gent lock) come before any other cost
        with warnings.catch_warnings():  # the reported level's validity warnings only
            if isinstance(runs[factors[-1]][1], ImpactRun):
                warnings.simplefilter("ignore", ValidityWarning)
            runs[factor] = _level(impact, refined(settings, factor))
    used, outcomes, notes = zip(*(runs[factor] for factor in factors), strict=True)
    results = tuple(r if isinstance(r, ImpactRun) else None for r in outcomes)
    if all(result is None for result in results):
        raise outcomes[-1]
    missing, estimates = "", {}
    if None in results:
        failed = [f"refine {f:.3g}: {n}" for f, n, r in zip(factors, notes, results, strict=True)]
        missing = "a ladder level failed twice, " + "; ".join(
            line for line, r in zip(failed, results, strict=True) if r is None
        )
        warnings.warn(
            f"no error estimate: {missing}; the finest level that passed is reported. More "
            "time steps (time_steps, --time-steps) or a finer mesh (refine, --refine) may pass",
            EstimateMissingWarning,
            stacklevel=caller_stacklevel(),
        )
    elif estimate:
        estimates = ladder_estimates(results)
    return FiniteLadder(factors, used, results, notes, estimates, missing)


def ladder_estimates(results: Sequence[ImpactRun]) -> dict[str, Estimate]:
    """The estimates of the last of three levels' runs (coarse to fine): the quantities of
    :data:`.accuracy.DYNAMIC_ESTIMATED` and a viscoelastic body's dissipated fraction; not
    1 - e^2 of a massless elastic body (0 by construction, its energy-conserving stepping's
    round-off has no relative error)."""
    finest = results[-1]
    keys = list(DYNAMIC_ESTIMATED)
    if "energy_dissipated_fraction" in finest.losses:
        keys.append("energy_dissipated_fraction")
    elif finest.parameters["density2"] == 0:
        keys.remove("energy_radiated_fraction")
    return {key: over_levels(results, lambda r, key=key: r.summary()[key]) for key in keys}
