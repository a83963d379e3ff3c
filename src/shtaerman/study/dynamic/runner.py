"""Running a dynamic study: a :func:`~.case.run_case` per approach velocity, its checks and
the velocity limits of the quasi-static model.

The relative differences are quasi-static / dynamic - 1. Every velocity's run is the finest
level of an error-estimate ladder (:mod:`.accuracy`; ``verify --quick`` skips it): x_max, P_max,
t_contact, e, 1 - e^2 and the differences themselves carry Richardson estimates. The velocity
up to which the quasi-static value holds to 1 % (5 %) is interpolated linearly between the
computed velocities where |difference| crosses the level (the differences grow monotonically
with v0), and stated only where the estimated error of the difference is below a fifth of the
level (:mod:`shtaerman.study.limits`).
"""

from __future__ import annotations

import math
import time
from collections.abc import Callable, Sequence
from dataclasses import asdict, dataclass

from ...fem.dynamic_contact import DynamicSettings
from ...theory.impact import check_velocity
from ...theory.materials import RIGID, effective_modulus
from ...theory.radiation import impact_radiation
from ...theory.sneddon import contact_law, profile_inputs
from ..checks import Check, Outcome
from ..contact.interface import shtaerman_applies
from ..limits import LEVELS, thresholds
from .case import COMPARED, DynamicCase, finite_settings, problem_case
from .loader import DynamicStudy, energy_checks, reflection_reference

__all__ = ["SEPARATION_SNAPSHOT", "DynamicStudyOutcome", "run_dynamic_study"]

SEPARATION_SNAPSHOT = 1.05
"""The wave field after separation is kept at this multiple of the quasi-static t_y."""

Progress = Callable[[str], None]


@dataclass(frozen=True)
class DynamicStudyOutcome(Outcome):
    """A dynamic study's cases, checks and summary (SI units)."""

    study: DynamicStudy
    cases: tuple[DynamicCase, ...]
    checks: list[Check]
    seconds: float
    quick: bool = False
    cpu_seconds: float = math.nan

    @property
    def example(self) -> DynamicCase:
        """The case at the study's example velocity."""
        return next(case for case in self.cases if case.velocity == self.study.example)

    @property
    def velocities(self) -> list[float]:
        return [case.velocity for case in self.cases]

    def estimate_curve(self, points: int = 60) -> dict[str, list[float]]:
        """The first-order estimate over the study's velocity range: ``velocity`` (m/s),
        ``energy_fraction`` lambda and ``restitution`` sqrt(1 - lambda)."""
        study, low, high = self.study, self.velocities[0], self.velocities[-1]
        law = contact_law(study.indenter, effective_modulus(RIGID, study.half_space))
        curve: dict[str, list[float]] = {"velocity": [], "energy_fraction": [], "restitution": []}
        for i in range(points):
            v = low + (high - low) * i / (points - 1)
            estimate = impact_radiation(study.mass, v, law, study.density, study.half_space)
            curve["velocity"].append(v)
            curve["energy_fraction"].append(estimate.energy_fraction)
            curve["restitution"].append(estimate.restitution)
        return curve

    @property
    def estimated(self) -> bool:
        """Whether every case carries error estimates (a quick run skips the ladder)."""
        return all(case.estimated for case in self.cases)

    def difference_errors(self) -> dict[str, list[float]] | None:
        """Per compared quantity (and "all": the largest of the three) the estimated absolute
        error of the difference at every velocity; ``None`` without estimates."""
        if not self.estimated:
            return None
        estimates = [case.estimates() for case in self.cases]
        errors = {
            key: [e[f"difference_{key}"].absolute_error for e in estimates] for key in COMPARED
        }
        errors["all"] = [max(errors[k][i] for k in COMPARED) for i in range(len(self.cases))]
        return errors

    def limits(self) -> dict[str, dict[str, dict]]:
        """Per compared quantity (x, P, t, and "all": the worst of them) and level ("1%",
        "5%"): the velocity limit of :func:`shtaerman.study.limits.thresholds`, with the
        estimated error deciding it and whether that resolves the level."""
        rows = {key: [case.differences()[key] for case in self.cases] for key in COMPARED}
        rows["all"] = [max(abs(rows[k][i]) for k in COMPARED) for i in range(len(self.cases))]
        errors = self.difference_errors()
        return {
            key: {
                f"{100 * level:g}%": thresholds(
                    self.velocities, values, level, None if errors is None else errors[key]
                )
                for level in LEVELS
            }
            for key, values in rows.items()
        }

    def document(self) -> dict[str, object]:
        """The study's numbers for results.json (:mod:`shtaerman.output.text_dynamic` adds the
        display ``tables`` and ``findings`` and the common keys)."""
        study, settings = self.study, self.settings
        return {
            "inputs": {
                **profile_inputs(study.indenter),
                "E2": study.half_space.youngs_modulus,
                "nu2": study.half_space.poisson_ratio,
                "density2": study.density,
                **({"prony": study.prony_text} if study.prony is not None else {}),
                **({} if study.geometry.thickness is None else asdict(study.geometry)),
                **study.physics,
                "mass": study.mass,
                "velocities": self.velocities,
                "example": study.example,
            },
            "settings": asdict(settings),
            "cases": [
                {"velocity": case.velocity, **case.document(), "differences": case.differences()}
                for case in self.cases
            ],
            "estimated": self.estimated,
            "limits": self.limits(),
            "cpu_seconds": self.cpu_seconds,
        }

    @property
    def settings(self) -> DynamicSettings:
        return self.study.quick_settings if self.quick else self.study.settings


def first_order_applies(study: DynamicStudy) -> bool:
    """Whether the first-order wave estimate (:func:`~shtaerman.theory.radiation.
    impact_radiation`: a linear elastic half-space with mass under Shtaerman's frictionless
    striker) is this study's: no Prony series, no layer, a linear body, and an interface under
    which the frictionless contact is exact (:func:`~shtaerman.study.contact.interface.
    shtaerman_applies`: frictionless, mu = 0, or any grip on nu2 = 0.5, Dundurs' beta = 0)."""
    if study.prony is not None or study.geometry.thickness is not None or study.finite:
        return False
    interface = study.problem(study.velocities[0]).interface
    return shtaerman_applies(interface, study.half_space.poisson_ratio)


def _checks(study: DynamicStudy, cases: Sequence[DynamicCase]) -> list[Check]:
    tol, checks, estimated = study.tolerances, [], first_order_applies(study)
    reflects = not (study.finite and study.density == 0)  # a massless rubber has no waves
    of = reflection_reference(study.geometry.thickness is not None, study.finite)
    for case in cases:
        v, r = f"v0 = {case.velocity:g} m/s", case.result
        balance, reflected = r.energy_balance_error, r.reflected_energy_fraction
        radiated = r.energy_radiated_fraction  # nothing radiated: no reflection (0/0)
        checks += energy_checks(
            balance,
            reflected,
            where=f" {v}",
            tolerances=tol,
            reflects=reflects,
            of=of,
            radiated=radiated,
        )
        if estimated and 0 < case.estimate.energy_fraction < tol.estimate_below:
            checks.append(
                Check(
                    f"loss / first-order estimate - 1 {v}",
                    case.differences()["loss_vs_estimate"],
                    tol.estimate,
                )
            )
    return checks


def run_dynamic_study(
    study: DynamicStudy, quick: bool = False, progress: Progress | None = None
) -> DynamicStudyOutcome:
    """Run the dynamic impact at every velocity of the study (``quick``: its quick variant).

    The example velocity keeps the fields at the quasi-static t_c and at
    :data:`SEPARATION_SNAPSHOT` t_y for the wave-field pictures. Every velocity also runs the
    error-estimate ladder's two coarser levels, except in a quick run.
    """
    report = progress or (lambda _line: None)
    start, cpu = time.perf_counter(), time.process_time()
    velocities = study.quick_velocities if quick else study.velocities
    settings = study.quick_settings if quick else study.settings
    cases = []
    for velocity in velocities:
        report(
            f"{study.name}: dynamic impact at v0 = {velocity:g} m/s"
            + ("" if quick else " (and 2 coarser levels for the error estimates)")
        )
        problem = study.problem(velocity)
        numerics = study.quick_finite_numerics if quick else study.finite_numerics
        level = settings  # a rubber's: resolved from its numerics
        if problem.body.finite:
            level = finite_settings(problem, **numerics, estimate=not quick)
        example = velocity == study.example
        shots = (lambda q: (q.t_c, SEPARATION_SNAPSHOT * q.t_y)) if example else None
        refine = numerics.get("refine", 1.0)
        quasi = study.exact.get(velocity)  # the loader's, else the case solves it
        if quasi is not None:
            check_velocity(velocity)  # the solve's warning, when the run skips it
        options = dict(snapshots=shots, ladder=not quick, refine=refine, quasi=quasi)
        options["energy_series"] = False  # a study writes no energies.csv: R_a's at the end
        cases.append(problem_case(problem, level, **options))
    return DynamicStudyOutcome(
        study=study,
        cases=tuple(cases),
        checks=_checks(study, cases),
        seconds=time.perf_counter() - start,
        quick=quick,
        cpu_seconds=time.process_time() - cpu,
    )
