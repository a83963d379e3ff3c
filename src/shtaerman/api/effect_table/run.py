"""``shtaerman.effects``: run the full problem and the variants that switch each effect off."""

from __future__ import annotations

import contextlib
import dataclasses
import re
import time
import warnings
from collections.abc import Callable, Iterator, Mapping
from typing import Any

from ...problem import Problem, check_options, in_python_words
from ...validation import (
    InputError,
    NumericalFailureError,
    caller_stacklevel,
    validate_positive,
)
from ..fem_dynamic import check_dynamic, checked_options, dynamic
from .table import QUANTITIES, EffectTable, Run, refusal_words
from .variants import Parts, Variant, parts_of, variants

__all__ = ["effects"]

Progress = Callable[[str], None]


def _describe(parts: Parts) -> dict[str, Any]:
    """The full problem's parts in words and numbers (the table's header)."""
    from ...theory.sneddon import profile_inputs

    striker, body = parts["striker"], parts["body"]
    prony = body.prony
    shape = profile_inputs(striker.indenter)  # a sphere's, a table's: A and n None
    indenter = {"A": shape["shape_coefficient"], "n": shape["exponent"]}
    return {
        "indenter": {**indenter, **({"profile": shape["profile"]} if "profile" in shape else {})},
        "mass": striker.mass,
        "velocity": striker.velocity,
        "E2": body.material.youngs_modulus,
        "nu2": body.material.poisson_ratio,
        "density2": body.material.density,
        "model": body.model,
        "prony": None if prony is None else list(zip(prony.weights, prony.times, strict=True)),
        "geometry": parts["geometry"].name,
        "thickness": parts["geometry"].thickness,
        "interface": parts["interface"].name,
        "friction": parts["interface"].friction,
    }


def _options(problem: Problem, given: dict[str, Any]) -> tuple[dict[str, Any], tuple[str, ...]]:
    """The numerical options of ``given`` that ``problem``'s combination takes, and a note for
    each it does not (:func:`shtaerman.problem.check_options`), left out of its run."""
    taken, notes = dict(given), []
    for _ in given:  # a refusal names one option (of taken), dropped: at most each once
        try:
            check_options(problem, taken)
        except InputError as refused:
            name = refused.parameter
            del taken[name]
            notes.append(f"{name} not applied: {str(refused).removeprefix(f'{name}: ')}")
        else:
            break
    else:
        check_options(problem, taken)  # every option dropped: nothing left to refuse
    return taken, tuple(notes)


NO_ESTIMATE = (
    "the run gave no error estimate (see its estimate_missing)",
    "the estimate was switched off (estimate=False)",
)
"""Why a run has no error estimate: with the estimate asked, without it."""


OWN_INPUTS = {
    "pad": ("thickness", "base", "layer_rate"),
    "waves": ("density2",),
    "viscoelasticity": ("prony",),
    "friction": ("friction",),
    "finite strain": ("model", "mooney_ratio", "yeoh", "gent_limit", "volumetric"),
}
"""The inputs of an effect: one of them refused where the effect is alone (the paper's problem
with it) is bad input, as ``shtaerman dynamic`` refuses it, not a row of the table."""


def _own_input(error: Exception, effect: str | None) -> bool:
    """Whether ``error`` is an :class:`InputError` naming an input of ``effect``."""
    if not isinstance(error, InputError):
        return False
    leading = re.match(r"(\w+): ", str(error))
    name = error.parameter or (leading[1] if leading else None)
    return name in OWN_INPUTS.get(effect or "", ())


def _refuses_the_table(variant: Variant, error: Exception) -> bool:
    """Whether a run's ``error`` is bad input of the whole table, not a row's refusal."""
    if variant.role in ("none", "full") and isinstance(error, InputError):
        return True  # the paper's problem, or the impact the options describe (as 'dynamic')
    return variant.role == "alone" and _own_input(error, variant.effect)  # no run measures it


def check_runs(rows: tuple[Variant, ...], given: dict[str, Any]) -> None:
    """Refuse, before any run and in one line, what a run would refuse for the table as a
    whole (:func:`_refuses_the_table`) for its inputs alone (:func:`shtaerman.api.fem_dynamic.
    check_dynamic`, nothing computed): the full problem first, as ``shtaerman dynamic``
    refuses it (its combination, an option, a validity limit), so no progress line comes
    before the refusal."""
    for variant in sorted(rows, key=lambda row: row.role != "full"):
        try:
            problem = Problem(**variant.parts)
        except InputError:
            if variant.role == "full":
                raise  # parts that do not combine: no table of their effects
            continue  # its combination: the row says so
        options, _ = _options(problem, given)
        try:
            check_dynamic(problem, **options)
        except InputError as error:
            if _refuses_the_table(variant, error):
                raise


def checked_table(
    problem: Problem | Mapping[str, Any], refine: float, estimate: bool, numerics: dict
) -> tuple[Parts, tuple[Variant, ...], tuple[str, ...], dict[str, Any]]:
    """The parts, variants, absent effects and numerical options of the table of
    :func:`effects` with these numerics (None: a run's default), refused as :func:`effects`
    refuses them before any run (:func:`check_runs`); nothing computed beyond the exact
    impacts. An effects study checks its ``[numerics]`` and ``[quick]`` with it at load."""
    sizes = {name: numerics.get(name) for name in ("time_steps", "mesh_size")}
    given = _numerics(refine, estimate, sizes)
    more = {name: value for name, value in numerics.items() if name not in sizes}
    given.update(_numerics(1.0, True, more))
    parts = parts_of(problem)
    rows, absent = variants(parts)
    check_runs(rows, given)
    return parts, rows, absent, given


def _run(variant: Variant, given: dict[str, Any], estimate: bool) -> Run:
    """One variant: refused (its combination, an option or a guard), failed, or its numbers."""
    start = time.perf_counter()
    try:
        problem = Problem(**variant.parts)
    except InputError as error:
        return Run(variant.label, variant.role, variant.effect, "-", refused=f"refused: {error}")
    cell = str(problem.cell)
    options, notes = _options(problem, given)
    head = dict(label=variant.label, role=variant.role, effect=variant.effect, cell=cell)
    try:
        result = dynamic(problem, **options)
    except (InputError, NumericalFailureError) as error:
        kind = "refused" if isinstance(error, InputError) else "failed"
        if _refuses_the_table(variant, error):
            raise
        seconds = time.perf_counter() - start
        return Run(**head, refused=f"{kind}: {error}", seconds=seconds, notes=notes)
    values = {key: float(getattr(result, key)) for key in QUANTITIES}
    details, seconds = result.estimate_details, time.perf_counter() - start
    errors = details and {key: float(details[key]["absolute_error"]) for key in QUANTITIES}
    missing = result.estimate_missing and f"no error estimate: {result.estimate_missing}"
    note = None if errors else missing or NO_ESTIMATE[not estimate]
    return Run(**head, values=values, errors=errors, error_note=note, seconds=seconds, notes=notes)


def _numerics(refine: float, estimate: bool, options: Mapping[str, Any]) -> dict[str, Any]:
    """The numerical keywords given (not None, not the default), each checked now."""
    if not isinstance(estimate, bool):
        raise InputError(f"estimate must be True or False, got {estimate!r}", "estimate")
    given = checked_options(options)
    if validate_positive("refine", refine) != 1.0:
        given["refine"] = refine
    if not estimate:
        given["estimate"] = False
    return given


def _order(variant: Variant) -> tuple[bool, int]:
    """Cheapest first: the linear problems before the rubbers, fewer effects first."""
    return (variant.parts["body"].finite, 0 if variant.role == "none" else 1)


def _reference(parts: Parts) -> dict[str, float]:
    """The paper's exact quasi-static impact (:func:`shtaerman.impact`): x_c, P_c, t_c, t_y."""
    from ..quasi_static import impact

    striker, body = parts["striker"], parts["body"]
    quasi = impact(striker.indenter, body.material, mass=striker.mass, velocity=striker.velocity)
    return {key: float(getattr(quasi, key)) for key in ("x_c", "P_c", "t_c", "t_y")}


@in_python_words
def effects(
    problem: Problem | Mapping[str, Any],
    *,
    refine: float = 1.0,
    estimate: bool = True,
    time_steps: int | None = None,
    mesh_size: float | None = None,
    mesh_margin: float | None = None,
    domain_factor: float | None = None,
    growth: float | None = None,
    layer_rate: float | None = None,
    progress: Progress | None = None,
    kept: Mapping[str, Run] | None = None,
    finished: Callable[[Run], None] | None = None,
) -> EffectTable:
    """The effect table of an impact: which of its effects moves P_max, x_max, t_contact and e.

    Runs (:func:`shtaerman.dynamic`) the problem with every effect off (the paper's problem,
    by FE), each of its effects alone, the full problem and the full problem without each
    effect, and measures each against the paper's exact quasi-static impact
    (:func:`shtaerman.impact`). A variant whose combination, option or validity guard is
    refused, or whose run fails, shows its one-line reason in its row; the others run.

    Parameters
    ----------
    problem : Problem or mapping
        The full impact (:meth:`shtaerman.Problem.impact`), or its parts as a mapping
        (:func:`shtaerman.problem.parts`); they must combine and run as ``shtaerman dynamic``
        runs them (the table measures the effects against the full problem).
    refine, estimate, time_steps, mesh_size, mesh_margin, domain_factor, growth, layer_rate
        The numerics of :func:`shtaerman.dynamic`, for every run (a run whose combination does
        not take one runs without it, and its row says so). None: each run's default.
    progress : callable, optional
        Receives one line per run (its label, combination and time).
    kept : mapping, optional
        Runs made before with these inputs (an interrupted table's), by variant label: not
        run again (their warnings are not said again).
    finished : callable, optional
        Receives each run this call makes as soon as it is made (to keep it on disk).

    Returns
    -------
    EffectTable

    Raises
    ------
    shtaerman.validation.InputError
        Before any run: if a part or a numerical option is out of range, the full problem is
        refused (its combination, an option or a validity limit, in ``shtaerman dynamic``'s
        words) or the paper's problem itself (every effect off) is refused with these
        numerics; or an effect alone is refused for its own input (:data:`OWN_INPUTS`: a pad's
        thickness outside its range for this impact).
    """
    numerics = dict(time_steps=time_steps, mesh_size=mesh_size, mesh_margin=mesh_margin)
    numerics |= dict(domain_factor=domain_factor, growth=growth, layer_rate=layer_rate)
    parts, rows, absent, given = checked_table(problem, refine, estimate, numerics)
    report = progress or (lambda _line: None)
    said: Said = {}
    with _recorded(said, "quasi-static (paper)"):
        reference = _reference(parts)
    done: list[tuple[dict[str, Any], Run, list[Any]]] = []
    first: dict[str, str] = {}  # each refusal's first run: its reason is said once
    kept, told = kept or {}, finished or (lambda _run: None)
    for index, variant in enumerate(sorted(rows, key=_order), start=1):
        head = f"effects: run {index}/{len(rows)}: {variant.label}"
        shared = next(((run, keys) for p, run, keys in done if p == variant.parts), None)
        if shared is None and variant.label in kept:
            run = kept[variant.label]
            keys = [_record(said, variant.label, *_warning(*pair)) for pair in run.warned]
            report(f"{head}: kept from an earlier run")
        elif shared is None:
            report(f"{head} ...")
            with _recorded(said, variant.label) as keys:
                run = _run(variant, given, estimate)
            run = dataclasses.replace(run, warned=tuple(_named(key, text) for key, text in keys))
            told(run)
            refused = refusal_words(run.refused, variant.label, first)
            report(f"{head}: {refused or f'done in {run.seconds:.1f} s'}")
        else:
            run, keys = shared
            report(f"{head}: the same problem as {run.label}")
            for key, text in keys:  # the same run: its warnings apply to this row too
                said[key].append((variant.label, text))
            row = dict(label=variant.label, role=variant.role, effect=variant.effect)
            run = dataclasses.replace(run, **row, seconds=0.0)
        done.append((variant.parts, run, keys))
    _say_once(said, 1 + len(rows))
    by_label = {run.label: run for _, run, _ in done}
    runs = tuple(by_label[variant.label] for variant in rows)
    return EffectTable(reference, runs, absent, _describe(parts))


Said = dict[tuple[type[Warning], str], list[tuple[str, str]]]
"""The runs' warnings: (category, text with its numbers masked) -> (run label, text) each."""
_NUMBER = re.compile(r"[-+]?\d+(?:\.\d*)?(?:e[-+]?\d+)?")


@contextlib.contextmanager
def _recorded(said: Said, label: str) -> Iterator[list]:
    """Record the warnings of one run into ``said``; yields the (key, text) this run gave."""
    keys: list[tuple[tuple[type[Warning], str], str]] = []
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        yield keys
    for warning in caught:
        text = str(warning.message)
        if _key(warning.category, text) not in [known for known, _ in keys]:
            keys.append(_record(said, label, warning.category, text))


def _key(category: type[Warning], text: str) -> tuple[type[Warning], str]:
    return category, _NUMBER.sub("#", text)


def _record(said: Said, label: str, category: type[Warning], text: str) -> tuple[tuple, str]:
    """Record the warning ``text`` of the run ``label`` into ``said``; its key and text."""
    key = _key(category, text)
    said.setdefault(key, []).append((label, text))
    return key, text


def _named(key: tuple, text: str) -> tuple[str, str]:
    """A recorded warning as :attr:`Run.warned` keeps it: (``module.qualname``, text)."""
    return f"{key[0].__module__}.{key[0].__qualname__}", text


def _warning(name: str, text: str) -> tuple[type[Warning], str]:
    """A kept run's warning (:func:`_named`) as its category and text: the loaded warning
    class of that name (UserWarning if none is). Looked up among the loaded subclasses of
    Warning, not imported: a name in an edited incomplete.json must not import a module."""
    todo: list[type[Warning]] = [Warning]
    while todo:
        category = todo.pop()
        if f"{category.__module__}.{category.__qualname__}" == name:
            return category, text
        todo.extend(category.__subclasses__())
    return UserWarning, text


def _say_once(said: Said, total: int) -> None:
    """Each warning of the runs once (the same limit passed by several runs at other numbers
    is one warning), with the runs it applies to; none named: all ``total``, the quasi-static
    reference included."""
    for (category, _), given in said.items():
        labels, texts = [label for label, _ in given], {text for _, text in given}
        where = "" if len(labels) == total else f" (runs: {', '.join(labels)}"
        if len(texts) > 1:
            where += f"{'; ' if where else ' ('}the numbers are {labels[0]}'s"
        where += ")" if where else ""
        warnings.warn(given[0][1] + where, category, stacklevel=caller_stacklevel())
