"""Error bars for the impact, every body: one ladder refining mesh and time step together.

Three runs at refinement K/2, K/sqrt(2) and K (``settings.refined(factor)``: sizes / factor,
time steps x factor) and Richardson estimates (:mod:`shtaerman.study.richardson`) of the finest
run's x_max, P_max, t_contact, restitution and 1 - e^2 (and :data:`LOSS_ESTIMATED`); the linear
body and the rubber at finite strain climb the same ladder. A level that fails numerically is
run again with :data:`RETRY_STEPS` times its time steps, up to :data:`RETRIES` times; if those
fail too, the finest level that passed answers without estimate (:attr:`ImpactLadder.missing`,
a warning). Retries, failures and the estimator's choices: benchmarks/FEM_NOTES.md, "Study
error estimates".
"""

from __future__ import annotations

import math
import warnings
from collections.abc import Callable, Sequence
from dataclasses import dataclass, replace
from typing import Any, Protocol, TypeVar

from ...fem.contact.finite import SqueezedTipError
from ...fem.dynamic_contact import DynamicSettings
from ...fem.finite_dynamic import FiniteImpactSettings
from ...fem.impact_limits import FINITE_MIN_STEPS, MAX_SIZE, MIN_STEPS
from ...fem.impact_run import ImpactRun
from ...fem.rubber import GentLockError
from ...guards import ValidityWarning
from ...validation import (
    InputError,
    NumericalFailureError,
    caller_stacklevel,
    validate_positive,
)
from ..ladder import LADDER_RATIO, WITHOUT_ESTIMATE
from ..ladder import check_ladder as check_mesh_ladder
from ..richardson import Estimate, at_most_order, richardson

__all__ = [
    "DYNAMIC_ESTIMATED",
    "DYNAMIC_ORDER",
    "DYNAMIC_SANE",
    "LOSS_ESTIMATED",
    "RETRY_STEPS",
    "EstimateMissingWarning",
    "ImpactLadder",
    "RetriedWarning",
    "check_ladder",
    "ladder_estimates",
    "over_levels",
    "run_ladder",
]

DYNAMIC_ESTIMATED = ("x_max", "P_max", "t_contact", "restitution", "energy_radiated_fraction")
"""The impact's results that get an error estimate."""
LOSS_ESTIMATED = (
    "energy_dissipated_fraction",
    "energy_wave_fraction",
    "energy_hysteresis_fraction",
)
"""A viscoelastic body's split of 1 - e^2 (:attr:`ImpactRun.losses`), estimated too where the
runs have it (a rubber at finite strain records the dissipated fraction only)."""
DYNAMIC_ORDER = 2.0
"""Asymptotic order used for the correction: generalized-alpha's second order in dt, the
smaller of the time and mesh orders (benchmarks/FEM_NOTES.md, "Study error estimates")."""
DYNAMIC_SANE = (1.0, 5.0)
"""Observed orders taken as asymptotic (as :data:`.accuracy.SANE_ORDERS`); otherwise, and for
differences that do not shrink monotonically, the largest of the two differences."""
LEVELS = (1.0 / LADDER_RATIO**2, 1.0 / LADDER_RATIO, 1.0)
"""Refinement of each level relative to the finest, coarse to fine."""
RETRY_STEPS = 2
"""A failed level is run again with this many times its last time steps."""
RETRIES = 2
"""How many times a failed level is run again: z = 0.804 r^1.01 at finite strain with inertia
(0.12 kg, 1.5 m/s) failed at 100 and 200 steps at first contact and passed at 400."""
FAILURES = (NumericalFailureError,)
"""The numerical failures of a run (a NewtonError among them) that a retry may cure (bad input
is not retried)."""


class EstimateMissingWarning(UserWarning):
    """A ladder level failed on its retries too: the finest level that passed is reported,
    with no error estimate."""


class RetriedWarning(UserWarning):
    """A level failed at its time steps and passed with more (:data:`RETRY_STEPS` times, up to
    :data:`RETRIES` times), or cut some time steps in halves: its result is of the steps it
    passed with, not of those asked for."""


class ImpactSettings(Protocol):
    """What the ladder needs of a body's numerical settings."""

    steps: Any

    def refined(self, factor: float) -> Any:
        """The settings with mesh sizes / ``factor`` and time steps x ``factor``."""


Settings = TypeVar("Settings", bound=ImpactSettings)


@dataclass(frozen=True)
class ImpactLadder:
    """The levels of an impact, coarse to fine, and the estimates of the finest.

    Attributes
    ----------
    refines : tuple of float
        Refinement factors of the levels.
    settings : tuple
        The settings each level ran with (a retried level's doubled steps).
    results : tuple of ImpactRun or None
        The runs; None where a level failed on its retries too.
    estimates : dict of str to Estimate
        Per quantity; empty when the estimate is missing.
    failures : tuple of str
        Per level, "" or what failed (a retry that passed is noted too); () for none.
    missing : str
        Why the estimate is missing ("" when there is one).
    """

    refines: tuple[float, ...]
    settings: tuple[Any, ...]
    results: tuple[ImpactRun | None, ...]
    estimates: dict[str, Estimate]
    failures: tuple[str, ...] = ()
    missing: str = ""

    @property
    def finest(self) -> ImpactRun:
        """The finest run that passed: the reported numbers."""
        return next(r for r in reversed(self.results) if r is not None)

    def estimate(self, quantity: Callable[[Any], float]) -> Estimate | None:
        """Richardson on ``quantity`` of each level's run (e.g. x_c / x_max - 1); None when
        the estimate is missing."""
        return None if self.missing else over_levels(self.results, quantity)

    def to_dict(self, estimates: dict[str, Estimate] | None = None) -> dict[str, object]:
        """The JSON keys ``error_estimate``, ``extrapolated``, ``estimate_details`` (None
        when the estimate is missing; then ``estimate_missing`` says why) and
        ``mesh_ladder`` (a failed level's dofs and seconds None, its ``failure`` named) of
        ``estimates`` (default: :attr:`estimates`)."""
        estimates = self.estimates if estimates is None else estimates
        failures = self.failures or ("",) * len(self.results)
        levels = []
        for refine, level, result, failure in zip(
            self.refines, self.settings, self.results, failures, strict=True
        ):
            row: dict[str, Any] = {"refine": refine, "steps": level.steps}
            row["dofs"] = None if result is None else int(result.mesh["dofs"])
            row["seconds"] = (
                None if result is None else float(result.timings.get("total", math.nan))
            )
            levels.append({**row, **({"failure": failure} if failure else {})})
        document: dict[str, object] = {"mesh_ladder": levels}
        if self.missing:
            document.update(error_estimate=None, extrapolated=None, estimate_details=None)
            return {**document, "estimate_missing": self.missing}
        document["error_estimate"] = {k: e.error for k, e in estimates.items()}
        document["extrapolated"] = {k: e.extrapolated for k, e in estimates.items()}
        document["estimate_details"] = {k: e.to_dict() for k, e in estimates.items()}
        return document


def check_ladder(
    settings: DynamicSettings | FiniteImpactSettings, refine: float = 1.0, estimate: bool = True
) -> None:
    """Raise InputError, before any run, unless every level of the ladder ending at ``refine``
    (only that level without ``estimate``) is valid, every body: ``settings`` (resolved) are
    of refinement 1; the message names the input to change (time_steps, mesh_size, refine)."""
    refine = validate_positive("refine", refine)
    lowest = refine * LEVELS[0] if estimate else refine
    least = FINITE_MIN_STEPS if isinstance(settings, FiniteImpactSettings) else MIN_STEPS
    advice = WITHOUT_ESTIMATE if estimate else ""
    if settings.steps is not None and settings.steps * lowest < least - 0.5:
        coarsest = "the error-estimate ladder's coarsest level halves" if estimate else "refine"
        raise InputError(
            f"time_steps: {coarsest} the time steps (refine {lowest:g}), so it needs at least "
            f"{math.ceil((least - 0.5) / lowest)} per t_y, got {settings.steps}{advice}",
            "time_steps",
        )
    if isinstance(settings, FiniteImpactSettings):
        assert settings.mesh is not None, "resolve the settings first"
        check_mesh_ladder(settings.mesh, refine, estimate=estimate, sized=False, advice=advice)
        return
    if settings.size / lowest > MAX_SIZE * (1.0 + 1e-12):
        raise InputError(
            f"mesh_size: the error-estimate ladder's coarsest level doubles the mesh size, so it "
            f"must lie in (0, {MAX_SIZE * lowest:g}] with the estimate at refine {refine:g} (or "
            f"turn the estimate off), got {settings.size!r}",
            "mesh_size",
        )
    try:
        settings.refined(lowest)
    except InputError as error:
        raise InputError(
            f"the error-estimate ladder's coarsest level (mesh x2, steps / 2) is invalid: {error}",
            error.parameter,
        ) from None


def over_levels(results: Sequence[Any], quantity: Callable[[Any], float]) -> Estimate:
    """Richardson on ``quantity`` over the levels; a level without the value (nan) gives an
    estimate of nan error (method ``missing``)."""
    values = [quantity(result) for result in results]
    if all(math.isfinite(value) for value in values):
        return at_most_order(
            richardson, values, LADDER_RATIO, DYNAMIC_ORDER, sane=DYNAMIC_SANE, fallback="largest"
        )
    fine = values[-1]
    return Estimate(fine, fine, math.nan, math.nan, "missing", "a level gave no value")


def ladder_estimates(results: Sequence[ImpactRun]) -> dict[str, Estimate]:
    """The estimates of the last of three levels' runs (coarse to fine): the quantities of
    :data:`DYNAMIC_ESTIMATED` and the losses of :data:`LOSS_ESTIMATED` the runs have; not
    1 - e^2 of a massless elastic body (0 by construction, its energy-conserving stepping's
    round-off has no relative error)."""
    finest = results[-1]
    keys = [*DYNAMIC_ESTIMATED, *(key for key in LOSS_ESTIMATED if key in finest.losses)]
    if finest.parameters.get("density2") == 0 and not finest.losses:
        keys.remove("energy_radiated_fraction")
    return {key: over_levels(results, lambda r, key=key: r.summary()[key]) for key in keys}


def _level(
    run: Callable[[Settings], ImpactRun], settings: Settings
) -> tuple[Settings, ImpactRun | Exception, str]:
    """One level run; on a numerical failure run again with :data:`RETRY_STEPS` x its time
    steps, up to :data:`RETRIES` times. Returns the settings last used, the result (or the last
    error) and a note (a retried run's ``retried`` says it too)."""
    try:
        return settings, run(settings), ""
    except GentLockError:  # the rubber's limit, not the numerics: no retry cures it
        raise
    except SqueezedTipError as error:  # nor the tip's: more steps fail alike
        return settings, error, f"{settings.steps} steps failed ({error}); not retried"
    except FAILURES as error:
        said, failed = [f"{settings.steps} steps failed ({error})"], error
    for _ in range(RETRIES):
        try:
            retry = replace(settings, steps=RETRY_STEPS * settings.steps)
        except InputError:  # already at the most time steps: a retry would fail the same way
            return settings, failed, "; ".join([*said, "no retry beyond the most time steps"])
        try:
            result = run(retry)
        except FAILURES as error:
            settings, failed = retry, error
            said.append(f"the retry with {retry.steps} steps failed too ({error})")
            continue
        note = "; ".join([*said, f"passed with {retry.steps} steps"])
        return retry, replace(result, retried="; ".join(filter(None, (note, result.retried)))), note
    return settings, failed, "; ".join(said)


def run_ladder(
    run: Callable[[Settings], ImpactRun],
    settings: Settings,
    *,
    refine: float = 1.0,
    estimate: bool = True,
    first: Callable[[Settings], ImpactRun] | None = None,
    progress: Callable[[str], None] | None = None,
) -> ImpactLadder:
    """The impact at ``settings`` (the finest level, of refinement ``refine``) and, with
    ``estimate``, at its refinement 1/2 and 1/sqrt(2), with error estimates.

    Parameters
    ----------
    run : callable
        One run of the impact with given settings (every body:
        :func:`~shtaerman.fem.impact.run_impact`).
    settings : DynamicSettings or FiniteImpactSettings
        The finest level's settings (resolved).
    refine : float
        The finest level's refinement, as reported.
    estimate : bool
        Run the two coarser levels and estimate (else one level, no estimates).
    first : callable, optional
        The finest level's run (e.g. keeping its fields); default ``run``.
    progress : callable, optional
        Receives one line per level run here.

    Returns
    -------
    ImpactLadder

    Raises
    ------
    NewtonError, shtaerman.validation.NumericalFailureError
        When no level passed (the finest level's last error); a Gent rubber's lock
        (:class:`shtaerman.fem.rubber.GentLockError`) at once, without retry, and so a
        squeezed tip (:class:`shtaerman.fem.contact.finite.SqueezedTipError`) on the finest
        level.
    """
    report = progress or (lambda _line: None)
    factors = LEVELS if estimate else LEVELS[-1:]
    runs = {1.0: _level(first or run, settings)}
    if isinstance(runs[1.0][1], SqueezedTipError):  # the impact to change: before more cost
        raise runs[1.0][1]
    for factor in factors[:-1]:  # the finest first: its refusals come before any other cost
        with warnings.catch_warnings():  # the reported level's validity warnings only
            if isinstance(runs[1.0][1], ImpactRun):
                warnings.simplefilter("ignore", ValidityWarning)
            runs[factor] = _level(run, settings.refined(factor))
        if isinstance(runs[factor][1], ImpactRun):
            report(f"ladder: {runs[factor][1].mesh['dofs']} dofs, {runs[factor][0].steps} steps")
    used, outcomes, notes = zip(*(runs[factor] for factor in factors), strict=True)
    results = tuple(r if isinstance(r, ImpactRun) else None for r in outcomes)
    if all(result is None for result in results):
        raise outcomes[-1]
    refines = tuple(refine * factor for factor in factors)
    said = _say_retries(refines, results)
    if said:  # the reported run carries the ladder's one line
        last = max(i for i, result in enumerate(results) if result is not None)
        results = (*results[:last], replace(results[last], retried=said), *results[last + 1 :])
    missing = _missing(refines, notes, results)
    estimates = ladder_estimates(results) if estimate and not missing else {}
    return ImpactLadder(refines, used, results, estimates, notes, missing)


def _say_retries(refines: tuple[float, ...], results: tuple[ImpactRun | None, ...]) -> str:
    """Say once, in one line, what the levels that passed retried (a level run again with
    more time steps, time steps cut in halves: their steps are not the asked); returns the
    line ("" for none)."""
    retried = [
        f"refine {f:.3g}: {r.retried}"
        for f, r in zip(refines, results, strict=True)
        if r is not None and r.retried
    ]
    if not retried:
        return ""
    line = "; ".join(retried) + " (the result is of the steps it passed with)"
    warnings.warn(f"retried: {line}", RetriedWarning, stacklevel=caller_stacklevel())
    return line


def _missing(
    refines: tuple[float, ...], notes: tuple[str, ...], results: tuple[ImpactRun | None, ...]
) -> str:
    """Why the estimate is missing ("" when every level passed), said once as a warning."""
    if None not in results:
        return ""
    failed = [
        f"refine {f:.3g}: {n}" for f, n, r in zip(refines, notes, results, strict=True) if r is None
    ]
    missing = "a ladder level failed on its retries too, " + "; ".join(failed)
    warnings.warn(
        f"no error estimate: {missing}; the finest level that passed is reported. More "
        "time steps (time_steps, --time-steps) or a finer mesh (refine, --refine) may pass",
        EstimateMissingWarning,
        stacklevel=caller_stacklevel(),
    )
    return missing
