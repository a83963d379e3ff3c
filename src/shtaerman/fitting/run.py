"""``sh.fit``: the rubber's constants from a measurement, with 95 % intervals."""

from __future__ import annotations

import dataclasses
import warnings
from collections.abc import Mapping, Sequence
from pathlib import Path

import numpy as np
from numpy.typing import ArrayLike

from ..guards import warn_outside_validity
from ..output.files import output_folder
from ..problem import Problem, check_outputs, in_python_words
from ..theory.impact import QUASI_STATIC_VELOCITY_LIMIT, QuasiStaticValidityWarning
from ..theory.sneddon import contact_law
from ..theory.viscoelastic import elastic_impact
from ..validation import InputError, caller_stacklevel, validate_positive
from ..vocabulary import checked_positive, entry
from .corrections import fe_parts, needs_fe
from .data import (
    FE_REFINE,
    Measurement,
    check_history_options,
    measured_unit,
    measurement,
    resampled,
)
from .engine import Progress, Solution, solve
from .fe_indentation import finite_indentation_fit
from .iteration import corrected_fit, forward_error, widened
from .models import Known, Model, all_values, build_model
from .result import FitResult, fitted_entries, known_values, shown_names

__all__ = ["FE_REFINE", "fit", "known_of"]

ABSCISSA = {"indentation": "depth", "force-history": "time"}
"""The data column each kind's figure and fit.csv run along (rebound data: the velocity)."""


def known_of(problem: Problem, kind: str, *, time_offset: float | None = None,
             baseline: float = 0.0, steps: int = 200) -> Known:  # fmt: skip
    """The known parts of ``problem`` (its E2 and nu2 are the starting values), refusing the
    parts whose corrections the fit does not have (friction; waves in an indentation) and an
    impact's measurement without the striker's mass (and a
    force history's velocity)."""
    if problem.body.material.density and kind == "indentation":
        raise InputError(
            "density2: the FE correction of waves is fitted for an impact's force history or "
            "rebound data; an indentation is quasi-static (leave density2 unset)",
            "density2",
        )
    if problem.interface.kind != "frictionless":
        raise InputError("interface: the fit takes a frictionless contact only", "interface")
    striker, body = problem.striker, problem.body.material
    needed = {"mass": kind != "indentation", "velocity": kind == "force-history"}
    for name, needs in needed.items():
        if needs and getattr(striker, name) is None:
            raise InputError(
                f"{name}: a {kind} fit needs the striker's {name} (known, or the starting "
                f"value of a fitted one); give it in the problem (Problem.impact)",
                name,
            )
    return Known(
        indenter=striker.indenter,
        striker=striker.material,
        E2=body.youngs_modulus,
        nu2=body.poisson_ratio,
        mass=validate_positive("mass", 1.0 if striker.mass is None else striker.mass, "kg"),
        velocity=1.0 if striker.velocity is None else striker.velocity,
        prony=problem.body.prony,
        time_offset=None if time_offset is None else float(time_offset),
        baseline=float(baseline),
        steps=int(steps),
    )


def _check_loss(measured: Measurement, problem: Problem) -> None:
    """Refuse a restitution or resilience below 1, with no contact time, and no Prony series.

    The elastic impact loses no energy (e = 1 at every velocity), so E2 could not move it.
    Waves (density2) do radiate energy, but the fit holds their FE correction fixed while it
    fits the exact model (:mod:`.iteration`), so no fitted value moves that loss either: the
    model's only loss that the unknowns move is the Prony series' hysteresis."""
    observed = [n for n in ("restitution", "resilience") if n in measured.columns]
    if problem.body.prony is not None or "contact_time" in measured.columns or not observed:
        return
    name = observed[0]
    if np.all(measured.columns[name] >= 1.0):
        return
    raise InputError(
        f"prony: {name} below 1 needs a loss the fit can move: give the rubber's Prony series "
        "(g1:tau1,...; fit its weights with --fit prony); the elastic body loses nothing (e = "
        "1), and the waves' loss (density2) enters as an FE ratio held fixed in the fit",
        "prony",
    )


def _names(unknowns: Sequence[str] | str) -> list[str]:
    """The names of ``unknowns`` ("E2,nu2" or ["E2", "nu2"]); an empty item ("E2,,nu2", a
    slip) and anything but strings are refused, naming the keyword (the CLI: --fit)."""
    parts = [unknowns] if isinstance(unknowns, str) else unknowns
    if not isinstance(parts, list | tuple) or not all(isinstance(p, str) for p in parts):
        raise InputError(
            f"unknowns: give names, as 'E2,nu2' or ['E2', 'nu2'], got {unknowns!r}", "unknowns"
        )
    names = [name.strip() for part in parts for name in part.split(",")]
    if "" in names and names != [""]:  # "" names none: refused with the choices
        raise InputError(
            f"unknowns: an empty name in {unknowns!r}; separate the names by single commas",
            "unknowns",
        )
    names = [name for name in names if name]
    twice = sorted({name for name in names if names.count(name) > 1})
    if twice:  # a slip for another name (E2,E2 for E2,nu2): not silently one unknown
        raise InputError(
            f"unknowns: {', '.join(twice)} named twice; name each unknown once", "unknowns"
        )
    return names


@in_python_words
def fit(
    kind: str,
    data: str | Path | Mapping[str, ArrayLike],
    problem: Problem,
    *,
    unknowns: Sequence[str] | str = ("E2",),
    noise: float | None = None,
    time_offset: float | None = None,
    baseline: float = 0.0,
    units: Mapping[str, str] | None = None,
    resample: int | None = None,
    steps: int = 200,
    refine: float = FE_REFINE,
    out: str | Path | None = None,
    force: bool = False,
    figure_format: str = "png",
    progress: Progress | None = None,
) -> FitResult:
    """Fit the unknowns of ``problem`` to a measurement by the exact quasi-static models.

    Parameters
    ----------
    kind : str
        ``indentation`` (depth, force), ``force-history`` (time, force), ``rebound``
        (velocity with restitution and/or contact_time) or ``resilience`` (velocity,
        resilience = e^2, ISO 4662).
    data : str, Path or mapping
        A CSV with a header ``name [unit]``, or the columns in SI units.
    problem : Problem
        The known parts (striker, mass, velocity, Prony times); its E2, nu2, mass, velocity
        and Prony weights are the starting values of those fitted.
    unknowns : sequence of str
        Names to fit: E2, nu2, mass, velocity, time_offset, baseline, prony (the weights g_i
        of the problem's series), tau (its relaxation times tau_i in s, fitted in log; one
        outside the measured time range is not identifiable, and its g_i with it),
        mooney_ratio, yeoh_c2 or gent_limit (an indentation of a mooney-rivlin, yeoh or
        gent body: FE curves, :data:`~shtaerman.fitting.fe_indentation.SHAPE_AXES`); which a kind
        takes: see ``--help``.
    noise : float, optional
        Standard deviation of the data in the residual's unit (N for a force; relative for
        rebound data); None: estimated from the residual.
    time_offset, baseline : float
        The force history's time of first touch in s and its zero force in N, or the
        starting values of fitted ones, both refused outside the record (see
        :func:`~shtaerman.fitting.data.check_history_options`). time_offset None: 0, or read
        off the data when fitted.
    units : mapping, optional
        Column -> unit for CSV header cells that give none (a CSV only: a mapping's columns
        are SI, and units beside them are refused).
    resample : int, optional
        Points to resample a force history (uniform in time) or an indentation (uniform in
        depth) onto before the fit, by linear interpolation, in [3, 1e7]; None: the rows as
        read.
    steps : int
        Time steps per t_c of the viscoelastic impact (with a Prony series).
    refine : float
        The mesh and time-step refinement of the FE runs that correct a force history for a
        pad (thickness), waves (density2 > 0) or finite strain (model); each FE run comes
        with its error estimate (0.6, the default, is the least the finite-strain ladder
        takes).
    out : str or Path, optional
        Folder to write fit.json, fit.csv and the figure fit.png into.
    force : bool
        Replace ``out`` if shtaerman wrote it.
    figure_format : str
        png, or svg / pdf besides.
    progress : callable, optional
        Told a line of progress every few evaluations of the forward model on a long record
        (:data:`~shtaerman.fitting.engine.PROGRESS_VALUES` values or more).

    Returns
    -------
    FitResult
    """
    if not isinstance(problem, Problem):  # a dict or None failed on problem.body
        raise InputError(
            "problem must be a Problem (Problem.impact or Problem.curve), got "
            f"{type(problem).__name__}",
            "problem",
        )
    check_outputs(out, force=force, estimate=True, figure_format=figure_format)
    folder = output_folder(out, force=force)
    names = _names(unknowns)
    if time_offset is None and "time_offset" not in names:
        time_offset = 0.0  # known: 0; fitted: the start read off the data
    measured, rows_read = _read(kind, data, units, resample, time_offset, baseline)
    known = known_of(problem, kind, time_offset=time_offset, baseline=baseline, steps=steps)
    _check_loss(measured, problem)
    refine = checked_positive("refine", refine)
    if needs_fe(problem) and "nu2" in names and kind != "indentation":
        raise InputError(
            "unknowns: nu2 cannot be fitted with the FE corrections (on a pad and in the waves it "
            "acts beyond the combined modulus the exact model sees); give nu2 and fit E2",
            "unknowns",
        )
    if noise is not None:
        noise = checked_positive("noise", noise)
    with warnings.catch_warnings():  # the search may try any velocity: warned once below
        warnings.simplefilter("ignore", QuasiStaticValidityWarning)
        try:
            known, model, sol, extra = _fitted(problem, known, measured, names, noise, refine,
                                               progress)  # fmt: skip
        except InputError as error:  # its FE runs always estimate: no estimate=False here
            from ..study.ladder import WITHOUT_ESTIMATE

            said = str(error).removesuffix(WITHOUT_ESTIMATE)
            raise InputError(said, error.parameter) from None
    _check_velocities(measured, known, model, sol)
    _check_span(measured, known, model, sol)
    if kind == "indentation":  # the same depth limits as every contact route
        deepest = float(np.max(measured.columns["depth"]))  # within the law's reach: checked
        warn_outside_validity(problem.striker.indenter, deepest, problem.geometry.thickness,
                              problem.body.finite, "the data's deepest depth")  # fmt: skip
    result = _result(kind, measured, known, model, sol, names)
    reason, shape = extra.pop("reason", None), extra.pop("shape", None)
    if reason is not None:
        result.fitted[shape]["reason"] = reason
    result = dataclasses.replace(result, **extra, data={**result.data, "rows_read": rows_read})
    if folder is not None:
        from ..output.fit import write_fit

        write_fit(result, folder, force=force, figure_format=figure_format)
    return result


def _fitted(problem: Problem, known: Known, measured: Measurement, names: list[str],
            noise: float | None, refine: float, progress: Progress | None,
            ) -> tuple[Known, Model, Solution, dict]:  # fmt: skip
    """The known parts, model and solution (intervals widened by the forward model's own
    error) and the result's fields on the corrections and the forward error."""
    if measured.kind == "indentation" and needs_fe(problem):
        model, sol, curves, reason, shifts = finite_indentation_fit(
            problem, measured, names, noise, refine, progress
        )
        entry = {
            "name": f"FE contact curves: {fe_parts(problem)}",
            "shape": None if curves.axis is None else curves.axis.name,
            "nodes": sorted(curves.table),
            "fe_error": {"force": curves.error},
        }
        return known, model, sol, {
            "corrections": [entry], "fe_runs": len(curves.table), "reason": reason,
            "shape": entry["shape"],
            "forward_model": model.description, "forward_error": _forward_entries(model, shifts),
        }  # fmt: skip
    if needs_fe(problem):
        known, model, sol, corrections = corrected_fit(problem, known, measured, names, noise,
                                                       refine)  # fmt: skip
    else:
        model, corrections = build_model(known, measured, names), []
        sol = solve(model, noise, progress=progress)
    shifts = forward_error(known, measured, names, noise, model, sol)
    return (
        known,
        model,
        widened(sol, shifts),
        {
            "corrections": [c.entry(problem) for c in corrections[-1:]],
            "fe_runs": sum(c.runs for c in corrections),
            "forward_model": model.description
            + ("; corrected by FE impacts (see corrections)" if corrections else ""),
            "forward_error": _forward_entries(model, shifts),
        },
    )


def _read(kind: str, data: str | Path | Mapping[str, ArrayLike], units: Mapping[str, str] | None,
          resample: int | None, time_offset: float | None, baseline: float,
          ) -> tuple[Measurement, int]:  # fmt: skip
    """The measurement, resampled if asked, with the force history's offset (None: fitted from
    a start read off the data, not checked) and baseline checked against it, and the number of
    rows read."""
    measured = measurement(kind, data, units)  # the kind checked first
    rows = measured.rows
    if resample is not None:
        measured = resampled(measured, entry("resample").check(resample))
    if kind == "force-history":
        offset = None if time_offset is None else entry("time_offset").check(time_offset)
        check_history_options(measured, offset, entry("baseline").check(baseline))
    return measured, rows


def _forward_entries(model: Model, shifts: dict[str, np.ndarray]) -> dict[str, dict]:
    """Fitted name -> source -> the shift its interval took in from the forward model's own
    error (natural units; E_star, the combined modulus, in Pa)."""
    names = [p.name for p in model.parameters]
    return {n: {k: float(abs(v[j])) for k, v in shifts.items()} for j, n in enumerate(names)}


def _check_velocities(measured: Measurement, known: Known, model: Model, sol: Solution) -> None:
    """One :class:`QuasiStaticValidityWarning` if an impact of the fit is faster than the
    quasi-static theory's stated validity."""
    if measured.kind == "indentation":
        return
    names = [p.name for p in model.parameters]
    fitted = sol.values[names.index("velocity")] if "velocity" in names else known.velocity
    velocities = measured.columns.get("velocity", np.array([fitted]))
    fastest = float(np.max(velocities))
    if fastest > QUASI_STATIC_VELOCITY_LIMIT:
        warnings.warn(
            f"velocity {fastest:.4g} m/s exceeds {QUASI_STATIC_VELOCITY_LIMIT:g} m/s, the stated "
            "validity of the quasi-static impact theory the fit uses",
            QuasiStaticValidityWarning,
            stacklevel=caller_stacklevel(),
        )


SPAN_FACTOR = 100.0
"""A force history spanning more than this many contact times of the fitted model, or less
than one such fraction of one, is warned of: its time column's unit is likely wrong (20 s of
a record of 20 ms labelled ``time [s]``, a factor 1000)."""


def _check_span(measured: Measurement, known: Known, model: Model, sol: Solution) -> None:
    """One warning if a force history's time span is a factor :data:`SPAN_FACTOR` or more
    from the fitted model's contact time (its elastic impact's t_y): no refusal, a hint. A
    wrong force unit moves the fitted contact time too (1000x the force: 1e-3 of the time)."""
    if measured.kind != "force-history":
        return
    values = all_values(
        known, dict(zip([p.name for p in model.parameters], sol.values, strict=True))
    )
    law = contact_law(known.indenter, values["E_star"])
    contact = elastic_impact(values["mass"], values["velocity"], law).t_y
    time = measured.columns["time"]
    span = float(time[-1] - time[0])
    if contact / SPAN_FACTOR < span < contact * SPAN_FACTOR:
        return
    warnings.warn(
        f"{measured.source}: the record spans {span:.3g} s, {span / contact:.3g} times the "
        f"fitted model's contact time {contact:.3g} s; check the units in the header (e.g. "
        "'time [ms]', 'force [kN]')",
        UserWarning,
        stacklevel=caller_stacklevel(),
    )


def _result(
    kind: str, measured: Measurement, known: Known, model: Model, sol: Solution, names: list[str]
) -> FitResult:
    """The :class:`FitResult` of solution ``sol``."""
    params = [p.name for p in model.parameters]
    rms = float(np.sqrt(np.mean(sol.residual**2)))
    scale = np.abs(model.observed) if model.relative else 1.0
    relative = sol.residual / scale
    return FitResult(
        kind=kind,
        fitted=fitted_entries(known, params, sol, names),
        correlation={"names": shown_names(params, names), "matrix": sol.correlation.tolist()},
        residual={
            "rms": float(np.sqrt(np.mean(relative**2))) if model.relative else rms,
            "max": float(np.max(np.abs(relative))),
            "unit": model.unit,
            "values": int(model.observed.size),
        },
        noise={"value": sol.noise, "unit": model.unit, "estimated": sol.noise_estimated},
        forward_model=model.description,
        corrections=[],
        data={"source": measured.source, "rows": measured.rows, "units": dict(measured.units)},
        known=known_values(known),
        evaluations=sol.evaluations,
        curves=_curves(kind, measured, sol),
    )


def _curves(kind: str, measured: Measurement, sol: Solution) -> dict[str, np.ndarray]:
    """The columns of fit.csv, headed ``name [unit]`` (SI): the abscissa, then each observed
    column beside its fit (``NAME_fit``), and for a force the residual fit - data."""
    axis = ABSCISSA.get(kind, "velocity")
    curves = {f"{axis} [{measured_unit(axis)}]": measured.columns[axis]}
    observed = [name for name in measured.columns if name not in ("depth", "time", "velocity")]
    rows = measured.rows
    for k, name in enumerate(observed):
        unit = measured_unit(name)
        curves[f"{name} [{unit}]"] = measured.columns[name]
        curves[f"{name}_fit [{unit}]"] = sol.model[k * rows : (k + 1) * rows]
    if kind in ABSCISSA:
        curves["residual [N]"] = sol.residual
    return curves
