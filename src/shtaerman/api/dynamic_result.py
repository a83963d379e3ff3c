"""The outcome of an impact, for every body: :class:`DynamicResult` (``dynamic --json``)."""

from __future__ import annotations

import math
import warnings
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any

from ..fem.impact_run import SUMMARY_KEYS
from ..output.files import json_safe
from ..validation import caller_stacklevel

if TYPE_CHECKING:
    from ..problem import Problem

__all__ = ["DIFFERENCES", "DYNAMIC_KEYS", "DynamicResult", "check_separated"]

DIFFERENCES = {"x": "x_c", "P": "P_c", "t": "t_c"}
"""The compared quantities and their keys in ``differences``: quasi-static x_c / x_max - 1,
P_c / P_max - 1 and t_c / (t_contact / 2) - 1."""
DYNAMIC_KEYS = (*SUMMARY_KEYS, "energy_dissipated_fraction", "energy_wave_fraction")
DYNAMIC_KEYS += ("energy_hysteresis_fraction", "energy_slip_fraction")
"""The keys of ``dynamic`` on every route (null where the body has no such quantity)."""
SECTIONS = ("viscoelastic_quasi_static", "differences_error", "viscoelastic_differences")
SECTIONS += ("viscoelastic_differences_error", "radiation_estimate", "rubber", "prony")
SECTIONS += ("error_estimate", "extrapolated", "estimate_details", "mesh_ladder")
"""The optional parts of the JSON: present on every route, null where the case has none."""
PARTS = {
    "parameters": (
        *("mass", "velocity", "density2", "shape_coefficient", "exponent", "E2", "nu2"),
        *("time_step", "time_steps", "mesh_size", "spectral_radius", "shear_wave_speed"),
        *("rayleigh_wave_speed", "layer_start", "layer_ramp", "layer_rate", "quasi_static_x_c"),
        *("quasi_static_t_y", "quasi_static_a_c", "beta", "solver_backward_error"),
    ),
    "mesh": (
        *("nodes", "elements", "dofs", "contact_candidates", "refined_radius"),
        *("estimated_dofs", "domain_radius", "smallest_size"),
    ),
    "timings": ("mesh", "assembly", "factorization", "stepping", "total"),
}
"""The keys of the nested parts on every route, every body (null where the body has none, the
reason in ``not_given`` as ``part.key``); beside them, where the case has them, ``interface``
and ``friction`` (parameters), ``thickness`` and ``base`` (mesh)."""


def _dynamic_key(name: str, doc: str) -> Any:
    return property(lambda self: self.dynamic.get(name, math.nan), doc=doc)


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
    ladder; neither is part of :meth:`to_dict`. One type and one JSON schema for every body
    (:meth:`to_dict`): ``model`` names the material model, ``rubber`` its constants at finite
    strain, ``prony`` the series as given; ``radiation_estimate`` is the linear elastic
    half-space's first-order estimate of its waves (None for a rubber, on a pad and for a
    massless body). ``profile`` names the
    striker's profile (``kind`` and ``parameters``, as ``impact --json``).
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
        "energy_radiated_fraction", "Energy left in the body, 1 - e^2 of M v0^2 / 2."
    )
    energy_balance_error = _dynamic_key(
        "energy_balance_error", "Energy account error, of M v0^2 / 2."
    )
    reflected_energy_fraction = _dynamic_key(
        "reflected_energy_fraction",
        "Energy reflected back: what came back inside R_a after separation, of the "
        "radiated (on a pad of M v0^2 / 2); a rubber's, the kinetic energy beyond half the "
        "domain at separation, of M v0^2 / 2.",
    )
    energy_dissipated_fraction = _dynamic_key(
        "energy_dissipated_fraction", "Energy dissipated (of M v0^2 / 2; nan if elastic)."
    )
    energy_hysteresis_fraction = _dynamic_key(
        "energy_hysteresis_fraction", "Part of 1 - e^2 lost to hysteresis (nan if elastic)."
    )
    energy_wave_fraction = _dynamic_key(
        "energy_wave_fraction", "Part of 1 - e^2 carried away by waves (nan if elastic)."
    )

    @property
    def retried(self) -> str | None:
        """What the runs retried, in one line (a ladder level run again with more time steps,
        time steps cut in halves, and with which steps); None for nothing."""
        return getattr(self.solution, "retried", "") or None

    def history(self) -> dict[str, Any]:
        """The histories t, x, v, P at every time step and, of the linear body, a and p0
        (arrays, SI units; a rubber's impact records no contact radius)."""
        return self.solution.history_columns()

    def to_dict(self) -> dict[str, Any]:
        """The JSON object of ``shtaerman dynamic --json``, one schema for every body: every
        key of :data:`DYNAMIC_KEYS` and :data:`SECTIONS` is there, null where the case has no
        such quantity, and ``not_given`` says why for each null (``dynamic.<key>`` for a key of
        ``dynamic``); other non-finite numbers are null too (the CLI's null);
        ``estimate_missing`` is null unless the estimate is missing, ``retried`` unless a run
        was retried or cut time steps (:attr:`retried`)."""
        dynamic = {key: self.dynamic.get(key) for key in DYNAMIC_KEYS} | dict(self.dynamic)
        document: dict[str, Any] = {
            "quasi_static": dict(self.quasi_static),
            "viscoelastic_quasi_static": self.viscoelastic_quasi_static,
            "dynamic": dynamic,
            "differences": dict(self.differences),
        }
        document.update({key: getattr(self, key) for key in SECTIONS[1:]})
        document.update({part: _filled(getattr(self, part), part) for part in PARTS})
        document.update(profile=self.profile, model=self.model)
        if self.mesh_ladder is not None:
            document["mesh_ladder"] = [dict(level) for level in self.mesh_ladder]
        document["estimate_missing"] = self.estimate_missing
        document["retried"] = self.retried
        document["not_given"] = self.not_given()
        return json_safe(document)

    def not_given(self) -> dict[str, str]:
        """Why each null of :meth:`to_dict` is null (key -> reason; ``dynamic.<key>`` for a
        key of ``dynamic`` the run did not record)."""
        elastic, massless = self.prony is None, self.parameters.get("density2") == 0
        out = {
            f"dynamic.{key}": _unrecorded_reason(key, elastic, massless, self.parameters)
            for key in DYNAMIC_KEYS
            if not _finite(self.dynamic.get(key))
        }
        radiated = self.dynamic.get("energy_radiated_fraction")
        if "dynamic.reflected_energy_fraction" in out and _finite(radiated):
            from ..study.dynamic.loader import unmeasured_reflection

            out["dynamic.reflected_energy_fraction"] = unmeasured_reflection(radiated)
        for key in (key for key in SECTIONS if getattr(self, key) is None):
            out[key] = self._section_reason(key, elastic, massless)
        for part, keys in PARTS.items():
            given = getattr(self, part)
            for key in (key for key in keys if not _finite(given.get(key))):
                out[f"{part}.{key}"] = _part_reason(key, self.rubber is not None, massless)
        return out

    def _section_reason(self, key: str, elastic: bool, massless: bool) -> str:
        """Why the optional part ``key`` of the JSON is null."""
        if key.startswith("viscoelastic") and self.viscoelastic_quasi_static is None:
            if elastic:
                return "an elastic body: the paper's elastic impact (quasi_static) is the reference"
            return "no viscoelastic quasi-static reference for this case"
        if key == "radiation_estimate":
            if massless:
                return NO_WAVES
            pad = "; not a pad's" if "thickness" in self.mesh else ""
            return "the first-order estimate is of the linear elastic half-space's waves" + pad
        if key == "rubber":
            return "a linear body has no rubber constants"
        if key == "prony":
            return "an elastic body (no Prony series)"
        return self.estimate_missing or "the error estimate was switched off (--no-estimate)"


NO_WAVES = "a massless body radiates no waves"
UNRECORDED = "not recorded by this model"


def _unrecorded_reason(key: str, elastic: bool, massless: bool, parameters: dict) -> str:
    """Why ``dynamic.<key>`` is null: the body has no such quantity, or the model does not
    record it."""
    frictional = "interface" in parameters
    if key == "energy_dissipated_fraction" and elastic and not frictional:
        return "an elastic body on a frictionless indenter dissipates nothing"
    if key in ("energy_wave_fraction", "energy_hysteresis_fraction"):
        if not elastic:
            return "the finite-strain impact records the dissipated energy only"
        residue = "numerical residue (no waves)" if massless else "waves"
        return f"an elastic body has no hysteresis: 1 - e^2 is all {residue}"
    if key == "energy_slip_fraction" and not frictional:
        return "a frictionless indenter"
    return UNRECORDED


def _filled(given: dict[str, Any], part: str) -> dict[str, Any]:
    """The part ``given`` with every key of :data:`PARTS` (None where absent), in that order,
    then the case's own keys."""
    return {key: given.get(key) for key in PARTS[part]} | dict(given)


FACTORIZES = "the finite-strain impact factorizes in each Newton step (in stepping)"
PART_REASONS = {
    "time_steps": "the linear impact gives its time_step (s)",
    "mesh_size": "the linear mesh gives its smallest_size (m)",
    "solver_backward_error": FACTORIZES,
    "factorization": FACTORIZES,
    "smallest_size": "the finite-strain mesh gives its mesh_size (of the refined radius)",
}
"""Why a key of :data:`PARTS` is null where it is null for one kind of body only (else
:data:`UNRECORDED`)."""
WAVE_KEYS = ("shear_wave_speed", "rayleigh_wave_speed", "layer_start", "layer_ramp", "layer_rate")
"""The parameters of the waves and of the absorbing layer that takes them."""


def _part_reason(key: str, finite: bool, massless: bool) -> str:
    """Why ``key`` of a part of :data:`PARTS` is null for this body."""
    if key == "spectral_radius" and massless:
        return "a massless body has no time integration of its own (a static contact each step)"
    if key not in WAVE_KEYS:
        return PART_REASONS.get(key, UNRECORDED)
    if massless:
        return NO_WAVES
    if finite:
        return "the finite-strain impact has no absorbing layer and reports no wave speeds"
    return "no absorbing layer: the far boundary lies beyond the waves' reach (or layer_rate 0)"


def _finite(value: Any) -> bool:
    """Whether ``value`` is a finite number (not None, nan or inf: the JSON's null)."""
    return isinstance(value, (int, float)) and math.isfinite(value)


def check_separated(dynamic: dict[str, float], run_time: float) -> None:
    """Raise NumericalFailureError when the striker had not left the body by the end of the
    run (``run_time``, s): its contact duration, rebound and losses do not exist, and the
    reflection measure is meaningless."""
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
    reflected back (of :func:`~shtaerman.study.dynamic.loader.reflection_reference`; none
    without waves)."""
    from ..study.dynamic.loader import dynamic_check_failures, reflection_reference

    of = reflection_reference("thickness" in result.mesh, result.rubber is not None)
    massless = problem.cell.loading == "massless"  # no waves: nothing to reflect
    reflected = 0.0 if massless else result.reflected_energy_fraction
    radiated = result.energy_radiated_fraction
    return dynamic_check_failures(result.energy_balance_error, reflected, of, radiated)


def warn_failed_checks(result: DynamicResult, problem: Problem) -> None:
    """A :class:`shtaerman.guards.FailedCheckWarning`, one line, when the run fails a check."""
    from ..guards import FailedCheckWarning

    failures = check_failures(result, problem)
    if failures:
        warnings.warn(
            "; ".join(failures) + UNTRUSTED, FailedCheckWarning, stacklevel=caller_stacklevel()
        )
