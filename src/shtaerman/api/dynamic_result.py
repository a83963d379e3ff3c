"""The outcome of an impact, for every body: :class:`DynamicResult` (``dynamic --json``)."""

from __future__ import annotations

import math
import warnings
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any

from ..output.files import json_safe

if TYPE_CHECKING:
    from ..problem import Problem

__all__ = ["DIFFERENCES", "DynamicResult", "check_separated"]

DIFFERENCES = {"x": "x_c", "P": "P_c", "t": "t_c"}
"""The compared quantities and their keys in ``differences``: quasi-static x_c / x_max - 1,
P_c / P_max - 1 and t_c / (t_contact / 2) - 1."""


def _dynamic_key(name: str, doc: str) -> Any:
    return property(lambda self: self.dynamic[name], doc=doc)


@dataclass(frozen=True)
class DynamicResult:
    """The dynamic impact: the keys of ``shtaerman dynamic --json`` (SI units).

    ``dynamic`` holds the FE results; each is also an attribute (``x_max``, ``P_max``,
    ``restitution``, ...). ``differences`` are quasi-static / dynamic - 1 for ``x_c``
    (against x_max), ``P_c`` (P_max) and ``t_c`` (t_contact / 2); ``differences_error``
    their estimated absolute errors. The ladder's keys are None without the estimate, and
    without its levels all passing (``estimate_missing`` then says why; ``mesh_ladder`` shows
    the levels).
    ``solution`` is the finest FE run (histories, fields), ``ladder`` the error-estimate
    ladder; neither is part of :meth:`to_dict`. One type for every body: ``model`` names the
    material model; a rubber at finite strain adds ``rubber`` (its constants) and ``prony``
    (its series, as given) and has no ``radiation_estimate`` (the first-order estimate is the
    linear half-space's). ``profile`` names the striker's profile (``kind`` and
    ``parameters``, as ``impact --json``).
    """

    quasi_static: dict[str, float]
    dynamic: dict[str, float]
    differences: dict[str, float]
    radiation_estimate: dict[str, float] | None
    mesh: dict[str, Any]
    timings: dict[str, float]
    parameters: dict[str, float]
    model: str = "linear"
    rubber: dict[str, Any] | None = None
    prony: str | None = None
    differences_error: dict[str, float] | None = None
    error_estimate: dict[str, float] | None = None
    extrapolated: dict[str, float] | None = None
    estimate_details: dict[str, dict[str, Any]] | None = None
    mesh_ladder: tuple[dict[str, Any], ...] | None = None
    estimate_missing: str | None = None
    profile: dict[str, Any] | None = None
    viscoelastic_quasi_static: dict[str, Any] | None = None
    viscoelastic_differences: dict[str, float] | None = None
    viscoelastic_differences_error: dict[str, float] | None = None
    solution: Any = field(default=None, repr=False, compare=False)
    ladder: Any = field(default=None, repr=False, compare=False)

    x_max = _dynamic_key("x_max", "Maximum approach, m.")
    P_max = _dynamic_key("P_max", "Maximum contact force, N.")
    t_x_max = _dynamic_key("t_x_max", "Time of the maximum approach, s.")
    t_contact = _dynamic_key("t_contact", "Contact duration, s.")
    v_out = _dynamic_key("v_out", "Rebound velocity, m/s.")
    restitution = _dynamic_key("restitution", "Coefficient of restitution e = v_out / v0.")
    energy_radiated_fraction = _dynamic_key(
        "energy_radiated_fraction", "Energy carried away by waves, 1 - e^2 of M v0^2 / 2."
    )
    energy_balance_error = _dynamic_key(
        "energy_balance_error", "Energy account error, of M v0^2 / 2."
    )
    reflected_energy_fraction = _dynamic_key(
        "reflected_energy_fraction", "Energy reflected by the far boundary, of the radiated."
    )

    @property
    def energy_dissipated_fraction(self) -> float:
        """Energy dissipated by a viscoelastic half-space (of M v0^2 / 2; nan if elastic)."""
        return self.dynamic.get("energy_dissipated_fraction", math.nan)

    @property
    def energy_hysteresis_fraction(self) -> float:
        """The part of 1 - e^2 lost to hysteresis (of M v0^2 / 2; nan if elastic)."""
        return self.dynamic.get("energy_hysteresis_fraction", math.nan)

    @property
    def energy_wave_fraction(self) -> float:
        """The part of 1 - e^2 carried away by waves (of M v0^2 / 2; nan if elastic)."""
        return self.dynamic.get("energy_wave_fraction", math.nan)

    def history(self) -> dict[str, Any]:
        """The histories t, x, v, P, a, p0 at every time step (arrays, SI units)."""
        return self.solution.history_columns()

    def to_dict(self) -> dict[str, Any]:
        """The JSON object of ``shtaerman dynamic --json``: non-finite numbers
        are None (the CLI's null)."""
        document: dict[str, Any] = {"quasi_static": dict(self.quasi_static)}
        if self.viscoelastic_quasi_static is not None:
            document["viscoelastic_quasi_static"] = dict(self.viscoelastic_quasi_static)
        document.update(dynamic=dict(self.dynamic), differences=dict(self.differences))
        if self.differences_error is not None:
            document["differences_error"] = dict(self.differences_error)
        for key in ("viscoelastic_differences", "viscoelastic_differences_error"):
            if getattr(self, key) is not None:
                document[key] = dict(getattr(self, key))
        if self.radiation_estimate is not None:
            document["radiation_estimate"] = self.radiation_estimate
        document.update(mesh=self.mesh, timings=self.timings, parameters=self.parameters)
        if self.profile is not None:
            document["profile"] = dict(self.profile)
        document["model"] = self.model
        if self.rubber is not None:
            document["rubber"] = dict(self.rubber)
        if self.prony is not None:
            document["prony"] = self.prony
        if self.mesh_ladder is not None:
            document.update(
                error_estimate=self.error_estimate,
                extrapolated=self.extrapolated,
                estimate_details=self.estimate_details,
                mesh_ladder=[dict(level) for level in self.mesh_ladder],
            )
        if self.estimate_missing is not None:
            document["estimate_missing"] = self.estimate_missing
        return json_safe(document)


def check_separated(dynamic: dict[str, float], run_time: float) -> None:
    """Raise NumericalFailureError when the striker had not left the body by the end of the
    run (``run_time``, s): its contact duration, rebound and losses do not exist, and the
    reflection measure is meaningless (the JSON's nulls, a 'reflected energy nan' used to
    follow)."""
    from ..validation import NumericalFailureError

    if not math.isfinite(dynamic.get("t_contact", math.nan)):
        raise NumericalFailureError(
            f"the striker had not separated from the body at the end of the run "
            f"({run_time:.3g} s): a strongly relaxing body (Prony weights summing near 1) or a "
            "pad it sinks through holds it longer; lower the Prony weights or the velocity"
        )


UNTRUSTED = ", so this run's numbers are not to be trusted"
"""How a failed check's reasons end, on every route that states them."""


def check_failures(result: DynamicResult, problem: Problem) -> list[str]:
    """The studies' own checks (:func:`shtaerman.study.dynamic.loader.dynamic_check_failures`)
    that the run of ``problem`` fails, one reason each: its energy balance, and the energy
    reflected back (of the radiated energy; of M v0^2/2 on a layer; none without waves)."""
    from ..study.dynamic.loader import dynamic_check_failures

    of = "the radiated" if problem.geometry.thickness is None else "M v0^2/2"
    massless = problem.cell.loading == "massless"  # no waves: nothing to reflect
    reflected = 0.0 if massless else result.reflected_energy_fraction
    radiated = result.energy_radiated_fraction
    return dynamic_check_failures(result.energy_balance_error, reflected, of, radiated)


def warn_failed_checks(result: DynamicResult, problem: Problem) -> None:
    """A :class:`shtaerman.guards.FailedCheckWarning`, one line, when the run fails a check."""
    from ..guards import FailedCheckWarning

    failures = check_failures(result, problem)
    if failures:
        warnings.warn("; ".join(failures) + UNTRUSTED, FailedCheckWarning, stacklevel=3)
