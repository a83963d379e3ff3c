"""``shtaerman.dynamic(model=...)``: the impact on a rubber half-space at finite strain."""

from __future__ import annotations

import math
from pathlib import Path
from typing import TYPE_CHECKING

from ..theory.contact import PowerLawContact
from ..theory.impact import solve_impact
from ..vocabulary import entry
from .dynamic_result import DynamicResult, check_separated

if TYPE_CHECKING:
    from ..problem import Interface, Problem
    from ..theory.viscoelastic import PronySeries

__all__ = ["finite_dynamic"]


def finite_dynamic(
    problem: Problem,
    *,
    time_steps: int | None = None,
    mesh_size: float | None = None,
    out: str | Path | None = None,
    force: bool = False,
    figure_format: str = "png",
) -> DynamicResult:
    """The impact of a rigid striker on a rubber body at finite strain.

    Parameters
    ----------
    problem : Problem
        An impact on a rubber body (``problem.body.finite``): its density 0 gives the
        finite-strain quasi-static impact (massless body), in [1e-6, 1e6] kg/m^3 the body with
        inertia (waves); with a Prony series the isochoric stress relaxes
        (:mod:`shtaerman.fem.finite_viscoelastic`), E2 and nu2 being the instantaneous values.
    time_steps : int, optional
        Steps per quasi-static impact duration (default 50; 100 with inertia).
    mesh_size : float, optional
        Smallest element / refined radius (default the finite-strain contact's).
    out : path, optional
        A new folder for dynamic.json, history.csv, energies.csv and dynamic_history.png
        (:func:`shtaerman.output.finite.write_finite_impact`); an existing one is replaced only
        with ``force``.
    figure_format : {"png", "svg", "pdf"}
        "svg" or "pdf" also writes the figure in that format beside its PNG.

    Returns
    -------
    DynamicResult
        With ``model``, ``rubber`` and ``prony`` set; no radiation estimate or error bars.
    """
    from dataclasses import replace

    from ..fem.finite_contact import FINITE_MESH
    from ..fem.finite_dynamic import INERTIA_MESH, FiniteImpactSettings, run_finite_impact
    from ..output.files import output_folder, staged_folder
    from ..output.finite import write_finite_impact
    from ..plots.formats import check_figure_format
    from .layer_options import layer_mesh

    check_figure_format(figure_format)
    folder = output_folder(out, force=force)  # checked before the run

    indenter, body = problem.striker.indenter, problem.body.material
    mass, velocity = problem.striker.mass, problem.striker.velocity
    rho = body.density
    if mesh_size is not None:
        mesh_size = entry("mesh_size").check(mesh_size, "dynamic")
    if time_steps is not None:  # the command line's range: one guard on every route
        time_steps = entry("time_steps").check(time_steps, "dynamic")
    default = FINITE_MESH if rho == 0 else INERTIA_MESH
    mesh = default if mesh_size is None else replace(default, size=mesh_size)
    settings = FiniteImpactSettings(steps=time_steps, mesh=layer_mesh(mesh, problem.geometry))
    rubber, series = problem.body.rubber(), problem.body.prony
    friction = _friction(problem.interface)
    run = run_finite_impact(indenter, body, rho, mass, velocity, settings, rubber, series, friction)
    law = PowerLawContact(indenter, body.youngs_modulus / (1.0 - body.poisson_ratio**2))
    quasi = solve_impact(mass, velocity, law)
    summary = run.summary()
    check_separated(summary, float(run.t[-1]))
    differences = {
        "x_c": quasi.x_c / summary["x_max"] - 1.0,
        "P_c": quasi.P_c / summary["P_max"] - 1.0,
        "t_c": quasi.t_c / (0.5 * summary["t_contact"]) - 1.0,
    }
    result = DynamicResult(
        quasi_static={key: quasi.maxima()[key] for key in ("x_c", "P_c", "t_c", "t_y")},
        dynamic=summary,
        differences=differences,
        radiation_estimate=None,
        mesh=run.mesh,
        timings=run.timings,
        parameters=run.parameters,
        model=problem.body.model,
        rubber=rubber.to_dict(),
        prony=None if series is None else _prony_text(series),
        solution=run,
    )
    if folder is not None:
        with staged_folder(folder, force=force) as stage:
            write_finite_impact(result, quasi, stage, figure_format)
    return result


def _prony_text(series: PronySeries) -> str:
    """``g1:tau1,g2:tau2,...`` of a Prony series (tau in s)."""
    return ",".join(f"{g:g}:{tau:g}" for g, tau in zip(series.weights, series.times, strict=True))


def _friction(interface: Interface) -> float | None:
    """The impact's friction: None frictionless, inf bonded (no slip), else Coulomb's mu."""
    if interface.kind == "frictionless":
        return None
    return math.inf if interface.friction is None else interface.friction
