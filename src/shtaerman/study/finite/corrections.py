"""Whether the corrections add: the wave and finite-strain corrections of the paper's impact,
computed apart and together, at the velocities of a finite-strain study's ``[corrections]``.

At each velocity the linear dynamic impact, the finite-strain quasi-static impact and the
nonlinear dynamic impact run through the code of ``shtaerman dynamic``; each is reported as its
shifts against the paper's x_c, P_c and t_y, and the nonlinear impact's departure from the sum of
the two corrections says how well they add (benchmarks/FEM_NOTES.md, "Study error estimates").
"""

from __future__ import annotations

import time
from dataclasses import replace
from typing import Any

from ...fem import finite_dynamic, impact
from ...fem.dynamic_contact import DynamicSettings
from ...theory.materials import Material
from ..dynamic.case import run_case
from ..run import Progress
from .loader import FiniteStudy

__all__ = ["COLUMNS", "QUANTITIES", "QUICK_SETTINGS", "correction_row", "run_corrections"]

QUANTITIES = {"x_max": "x_c", "P_max": "P_c", "t_contact": "t_y"}
"""Each impact's quantity -> the paper's quasi-static value it is measured against."""
COLUMNS = ("linear_dynamic", "finite_strain", "sum", "nonlinear")
"""The columns: the two corrections apart, their sum (as independent) and both at once."""
QUICK_SETTINGS = {
    "linear_dynamic": {"time_steps": 60, "mesh_size": 0.1},
    "finite_strain": {"time_steps": 20, "mesh_size": 0.2},
    "nonlinear": {"time_steps": 20, "mesh_size": 0.2},
}
"""``verify --quick``: coarse meshes and time steps (the shifts within a few tenths of a point
of the defaults'); otherwise every run takes the command's defaults."""


def _linear(
    study: FiniteStudy, velocity: float, density: float, options: dict[str, Any]
) -> tuple[dict[str, float], dict[str, float]]:
    """The paper's quasi-static maxima and the linear dynamic impact's numbers (SI)."""
    settings = DynamicSettings()
    if options:
        settings = replace(settings, steps=options["time_steps"], size=options["mesh_size"])
    body = Material(study.half_space.youngs_modulus, study.half_space.poisson_ratio, density)
    case = run_case(study.indenter, body, density, study.mass, velocity, settings)
    return case.quasi.maxima(), case.result.summary()


def _finite(
    study: FiniteStudy, velocity: float, density: float, options: dict[str, Any]
) -> dict[str, float]:
    """The study's rubber struck at ``velocity`` (m/s), massless (``density`` 0) or not."""
    # the defaults read at call time, as ``shtaerman dynamic`` does (tests swap in coarse ones)
    mesh = finite_dynamic.IMPACT_MESH
    if "mesh_size" in options:
        mesh = replace(mesh, size=options["mesh_size"])
    settings = finite_dynamic.FiniteImpactSettings(steps=options.get("time_steps"), mesh=mesh)
    run = impact.run_impact(
        study.indenter, study.half_space, density, study.mass, velocity, settings, study.rubber
    )
    return run.summary()


def _impacts(
    study: FiniteStudy, velocity: float, density: float, quick: bool, report: Progress
) -> tuple[dict[str, float], dict[str, dict[str, float]]]:
    """The paper's quasi-static x_c, P_c, t_y and the three impacts' numbers."""
    settings = QUICK_SETTINGS if quick else {column: {} for column in QUICK_SETTINGS}
    report(f"{study.name}: corrections at v0 = {velocity:g} m/s: linear dynamic impact")
    maxima, linear = _linear(study, velocity, density, settings["linear_dynamic"])
    out = {"linear_dynamic": linear}
    for column, rho, words in (
        ("finite_strain", 0.0, "massless finite-strain impact"),
        ("nonlinear", density, "nonlinear dynamic impact"),
    ):
        report(f"{study.name}: corrections at v0 = {velocity:g} m/s: {words}")
        out[column] = _finite(study, velocity, rho, settings[column])
    return {key: maxima[key] for key in QUANTITIES.values()}, out


def correction_row(
    velocity: float, reference: dict[str, float], impacts: dict[str, dict[str, float]]
) -> dict[str, Any]:
    """One velocity's entry from the paper's ``reference`` (x_c, P_c, t_y in SI) and the
    impacts' numbers (x_max, P_max, t_contact, restitution per column but ``sum``): the
    ``shifts`` (fractions) of every column, ``restitution``, and ``departure``: nonlinear -
    sum, in percentage points (the restitution's as a difference of e)."""
    shifts = {
        column: {
            key: impacts[column][key] / reference[ref] - 1.0 for key, ref in QUANTITIES.items()
        }
        for column in ("linear_dynamic", "finite_strain", "nonlinear")
    }
    shifts["sum"] = {
        key: shifts["linear_dynamic"][key] + shifts["finite_strain"][key] for key in QUANTITIES
    }
    e = {column: impacts[column]["restitution"] for column in shifts if column != "sum"}
    e["sum"] = e["linear_dynamic"] + e["finite_strain"] - 1.0
    departure = {key: 100.0 * (shifts["nonlinear"][key] - shifts["sum"][key]) for key in QUANTITIES}
    departure["restitution"] = e["nonlinear"] - e["sum"]
    return {
        "velocity": velocity,
        "reference": dict(reference),
        "impacts": {column: dict(impacts[column]) for column in impacts},
        "shifts": {column: shifts[column] for column in COLUMNS},
        "restitution": {column: e[column] for column in COLUMNS},
        "departure": departure,
    }


def run_corrections(
    study: FiniteStudy, quick: bool = False, progress: Progress | None = None
) -> dict[str, Any] | None:
    """The ``[corrections]`` entry of a study's results.json (None without the table).

    Parameters
    ----------
    study : FiniteStudy
    quick : bool
        Coarse runs (:data:`QUICK_SETTINGS`); otherwise each impact at the command's defaults.
    progress : callable, optional
        Receives a line per impact run.

    Returns
    -------
    dict or None
        ``density2`` (kg/m^3), ``quick``, ``settings`` (the run options), ``rows`` (one
        :func:`correction_row` per velocity, in the file's order) and ``cpu_seconds``.
    """
    if study.corrections is None:
        return None
    report = progress or (lambda _line: None)
    cpu = time.process_time()
    rows = []
    for velocity in study.corrections.velocities:
        reference, impacts = _impacts(study, velocity, study.corrections.density, quick, report)
        rows.append(correction_row(velocity, reference, impacts))
    return {
        "density2": study.corrections.density,
        "quick": quick,
        "settings": QUICK_SETTINGS if quick else "the dynamic command's defaults",
        "rows": rows,
        "cpu_seconds": time.process_time() - cpu,
    }
