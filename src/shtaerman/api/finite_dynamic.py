"""``shtaerman.dynamic(model=...)``: the impact on a rubber half-space at finite strain."""

from __future__ import annotations

from pathlib import Path
from typing import TYPE_CHECKING, Any

from ..study.dynamic.case import compare, finite_case
from ..study.dynamic.finite_accuracy import FiniteLadder
from ..theory.impact import ImpactResult
from .dynamic_result import DIFFERENCES, DynamicResult, check_separated

if TYPE_CHECKING:
    from ..problem import Problem
    from ..theory.viscoelastic import PronySeries

__all__ = ["finite_dynamic"]


def finite_dynamic(
    problem: Problem,
    *,
    time_steps: int | None = None,
    mesh_size: float | None = None,
    refine: float = 1.0,
    estimate: bool = True,
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
    refine : float
        Divide the mesh size field by it and multiply the time steps by it (the finest level).
    estimate : bool
        Also run the ladder's coarser levels (refine / 2, refine / sqrt 2) for the error
        estimates (:mod:`shtaerman.study.dynamic.finite_accuracy`); a level that fails twice
        leaves the estimate missing (``estimate_missing`` says why) and the finest level that
        passed is reported.
    out : path, optional
        A new folder for dynamic.json, history.csv, energies.csv and dynamic_history.png
        (:func:`shtaerman.output.finite.write_finite_impact`); an existing one is replaced only
        with ``force``.
    figure_format : {"png", "svg", "pdf"}
        "svg" or "pdf" also writes the figure in that format beside its PNG.

    Returns
    -------
    DynamicResult
        With ``model``, ``rubber`` and ``prony`` set, the ladder's keys with ``estimate``; no
        radiation estimate.
    """
    from ..output.files import output_folder, staged_folder
    from ..output.finite import write_finite_impact
    from ..plots.formats import check_figure_format

    check_figure_format(figure_format)
    folder = output_folder(out, force=force)  # checked before the run
    numbers = dict(time_steps=time_steps, mesh_size=mesh_size, refine=refine)
    case = finite_case(problem, **numbers, estimate=estimate)
    ladder, run, quasi = case.ladder, case.result, case.quasi
    summary = run.summary()
    check_separated(summary, float(run.t[-1]))
    series = problem.body.prony
    result = DynamicResult(
        quasi_static={key: quasi.maxima()[key] for key in ("x_c", "P_c", "t_c", "t_y")},
        dynamic=summary,
        differences={DIFFERENCES[k]: value for k, value in compare(quasi, run).items()},
        radiation_estimate=None,
        mesh=run.mesh,
        timings=run.timings,
        parameters=run.parameters,
        model=problem.body.model,
        rubber=problem.body.rubber().to_dict(),
        prony=None if series is None else _prony_text(series),
        solution=run,
        ladder=ladder,
        **(_ladder_keys(ladder, quasi) if ladder is not None else {}),
    )
    if folder is not None:
        with staged_folder(folder, force=force) as stage:
            write_finite_impact(result, quasi, stage, figure_format)
    return result


def _ladder_keys(ladder: FiniteLadder, quasi: ImpactResult) -> dict[str, Any]:
    """The DynamicResult fields of the ladder: the estimates of the finest run and of its
    differences against the quasi-static impact (None when the estimate is missing)."""
    document = ladder.to_dict()
    errors = None
    if not ladder.missing:
        errors = {}
        for key, name in DIFFERENCES.items():
            estimate = ladder.estimate(lambda r, key=key: compare(quasi, r)[key])
            errors[name] = estimate.absolute_error
    return {
        "differences_error": errors,
        "error_estimate": document["error_estimate"],
        "extrapolated": document["extrapolated"],
        "estimate_details": document["estimate_details"],
        "mesh_ladder": tuple(document["mesh_ladder"]),
        "estimate_missing": document.get("estimate_missing"),
    }


def _prony_text(series: PronySeries) -> str:
    """``g1:tau1,g2:tau2,...`` of a Prony series (tau in s)."""
    return ",".join(f"{g:g}:{tau:g}" for g, tau in zip(series.weights, series.times, strict=True))
