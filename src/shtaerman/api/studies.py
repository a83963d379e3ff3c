"""``shtaerman.run_study`` and ``shtaerman.sweep``: studies and sweeps from Python."""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass, field
from pathlib import Path
from typing import TYPE_CHECKING, Any

from .. import vocabulary
from ..validation import InputError

if TYPE_CHECKING:
    from ..sweep.engine import SweepOutcome
    from ..sweep.spec import SweepSpec

__all__ = ["StudyResults", "run_study", "sweep"]


@dataclass(frozen=True)
class StudyResults:
    """The studies of one file (or shipped name), run.

    Attributes
    ----------
    passed : bool
        Every check of every study passed.
    studies : dict of str to dict
        Per study name: its entry of ``results.json`` (without ``out``: no files, figures);
        its ``warnings``: the validity warnings its runs issued, once each ([] within every
        limit of :mod:`shtaerman.guards`).
    out : pathlib.Path or None
        The result folder written (results.json, report.md, report.html, files, figures).
    outcomes : tuple
        The studies' outcome objects (numbers, fields and checks), in file order.
    """

    passed: bool
    studies: dict[str, dict[str, Any]]
    out: Path | None = None
    outcomes: tuple[Any, ...] = field(default=(), repr=False, compare=False)

    def to_dict(self) -> dict[str, Any]:
        """``passed`` and ``studies``, as JSON data."""
        return {"passed": self.passed, "studies": self.studies}


def run_study(
    name_or_path: str | Path,
    out: str | Path | None = None,
    quick: bool = False,
    *,
    force: bool = False,
    progress: Callable[[str], None] | None = None,
) -> StudyResults:
    """Run the studies of a study file, or of a shipped study by name (e.g. ``"paper"``).

    Parameters
    ----------
    name_or_path : str or path
        A study file (.toml) or the name of a shipped study.
    out : path, optional
        Write a result folder there, as ``shtaerman verify --out`` does (a new or empty
        folder; any folder with ``force``). Default: compute only.
    quick : bool
        Coarse meshes (seconds; the checks' tolerances are those of ``verify --quick``).
    progress : callable, optional
        Receives one line per stage.

    Raises
    ------
    shtaerman.validation.InputError
        A missing or invalid study file (naming the file and the key).

    Warns
    -----
    shtaerman.guards.ValidityWarning
        Each validity limit a study's runs passed, once, naming the study (also recorded in
        its entry's ``warnings`` and in the reports).
    """
    from ..output.files import json_safe, output_folder, staged_folder
    from ..output.folder import finish_verification, study_entry
    from ..output.report import study_document
    from ..study.run import run_study as run_one
    from ..study.schema import find_study, load_study

    studies = load_study(find_study(str(name_or_path)))
    report = progress or (lambda _line: None)
    folder = output_folder(out, force=force)
    if folder is None:
        outcomes = tuple(run_one(study, quick=quick, progress=report) for study in studies)
        documents = {o.study.name: json_safe(study_document(o, {})) for o in outcomes}
        return StudyResults(all(o.passed for o in outcomes), documents, None, outcomes)
    with staged_folder(folder, force=force) as stage:
        outcomes, entries = [], {}
        for study in studies:
            outcome = run_one(study, quick=quick, progress=report)
            entries[study.name] = study_entry(outcome, stage)
            outcomes.append(outcome)
        results = finish_verification(stage, entries, quick=quick)
    return StudyResults(bool(results["passed"]), results["studies"], folder, tuple(outcomes))


def sweep(
    path_or_spec: str | Path | SweepSpec,
    workers: int | None = None,
    scheduler: str | None = None,
    out: str | Path | None = None,
    resume: bool = False,
    *,
    force: bool = False,
    progress: bool | None = False,
    figure_format: str = "png",
) -> SweepOutcome:
    """Run a sweep (a file, a shipped sweep's name, or a spec) on dask.distributed.

    Parameters
    ----------
    path_or_spec : str, path or SweepSpec
        A sweep file, the name of a shipped sweep (e.g. ``"nu-grid"``), or a spec from
        :func:`shtaerman.sweep.load_sweep` / :func:`shtaerman.sweep.parse_sweep`.
    workers : int, optional
        Processes of the local cluster, one thread each (default: the usable cores).
    scheduler : str, optional
        Address of an existing cluster, e.g. ``"tcp://host:8786"`` (not with ``workers``).
    out : path, optional
        Result folder (default ``sweep-<name>``): cases.csv, results.json, figures.
    resume : bool
        Complete the sweep in ``out``: compute only the cases without a saved result.
    force : bool
        Replace a result folder a sweep wrote (never files you added) once this run
        completes; interrupted, the old folder stays whole and this run's saved cases are kept
        beside it in ``out.incomplete-PID`` (``resume=True`` there completes them and moves
        them to ``out``). Not with ``resume``.
    progress : bool, optional
        Progress bar on stderr (None: when stderr is a terminal).
    figure_format : {"png", "svg", "pdf"}
        The figures' files: png (200 dpi), or svg / pdf (vector, text kept as text) written
        beside each chart's PNG (``shtaerman sweep --figure-format``).

    Returns
    -------
    shtaerman.sweep.SweepOutcome
        Counts of cases computed, reused, failed, refused (beyond a validity limit of the
        model: recorded, not run); ``exit_code``.
    """
    from ..output.files import output_path
    from ..sweep.engine import run_sweep
    from ..sweep.spec import SweepSpec, find_sweep, load_sweep

    if isinstance(path_or_spec, SweepSpec):
        spec = path_or_spec
    elif isinstance(path_or_spec, str | Path):
        spec = load_sweep(find_sweep(path_or_spec))
    else:
        raise InputError(
            f"sweep: give a sweep file, a shipped sweep's name or a SweepSpec, got "
            f"{type(path_or_spec).__name__}",
            "sweep",
        )
    if workers is not None and scheduler is not None:
        raise InputError("workers: sizes the local cluster; drop it with scheduler", "workers")
    if workers is not None:
        workers = vocabulary.entry("workers").check(workers)
    flags = {"resume": resume, "force": force, "progress": progress}  # "False" is true
    for name, value in flags.items():
        if not isinstance(value, bool) and not (name == "progress" and value is None):
            either = "True, False or None" if name == "progress" else "True or False"
            raise InputError(f"{name} must be {either}, got {value!r}", name)
    folder = Path(f"sweep-{spec.name}") if out is None else output_path(out)
    return run_sweep(
        spec,
        folder,
        workers=workers,
        scheduler=scheduler,
        resume=resume,
        force=force,
        progress=progress,
        figure_format=figure_format,
    )
