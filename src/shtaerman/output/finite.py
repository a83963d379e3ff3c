"""Files and figures of a finite-strain study (and of ``contact --model neo-hookean --out``).

Files, every column and field named with its unit (``name [unit]``, ``[1]``: dimensionless):

- ``finite_curve.csv``: per depth the finite-strain force, contact radius, central pressure,
  stored energy and Newton iterations beside the linear exact and same-mesh linear FEM values;
- ``history_<variant>.csv``: the impact histories t, x, P, a, p(0) (linear exact, linear FEM,
  finite strain);
- ``field_at_x_c.vtu``: the deformed-state fields (reference r-z section, displacements in m,
  Cauchy stresses in Pa) at the computed depth nearest the finite-strain x_c, with the depth,
  force, contact radius, material and model as VTK field data;
- ``field_<i>_t<t>s.vtu`` of ``dynamic --model ... --out``: the same fields of the impact at the
  steps nearest 0.5, 1 and 1.5 t_c, with the time, depth and force (no contact radius).
"""

from __future__ import annotations

from pathlib import Path
from types import SimpleNamespace
from typing import TYPE_CHECKING, Any

import numpy as np

from ..plots.finite import (
    nearest_step,
    plot_finite_impact,
    plot_finite_ratios,
    plot_finite_section,
)
from ..plots.labels import model_label
from .export import field_mesh, step_field_data, write_histories, write_vtu
from .files import write_csv

if TYPE_CHECKING:
    from ..fem.contact.finite import FiniteContactCurve, FiniteContactStep
    from ..fem.impact_run import ImpactRun
    from ..study.finite.indentation import FiniteIndentationResult
    from ..study.finite.runner import FiniteStudyOutcome

__all__ = ["write_finite_curve", "write_finite_field", "write_finite_study", "write_impact_fields"]


CURVE_KEYS = (
    *("depth", "depth_to_radius", "force", "force_linear", "force_linear_fem", "force_ratio"),
    *("force_ratio_fem", "contact_radius", "radius_ratio", "central_pressure", "central_to_mean"),
    *("strain_energy", "newton_iterations"),
)
"""The columns of a study's finite_curve.csv (units: :data:`.files.CSV_UNITS`)."""
CAPTIONS = {
    "finite_ratios": "Real rubber against Shtaerman: P/(beta x^q) (top) and p(0)/p_avg (bottom) "
    "against depth / linear contact radius, the neo-Hookean FEM (red) beside the linear FEM "
    "on the same mesh (blue) and the exact linear values (black); grey bands 1 % and 5 %",
    "finite_section": "Von Mises stress on the deformed r-z section (true scale) under the "
    "rigid indenter, at the computed depth nearest the finite-strain x_c",
    "finite_impact": "Impact x(t) and P(t): the paper's linear model (black), the linear FEM "
    "(blue, dotted) and neo-Hookean finite strain (red, dashed)",
}


def write_finite_field(
    curve: FiniteContactCurve, step: FiniteContactStep, material: object, path: Path
) -> Path:
    """The deformed-state fields of ``step`` as a VTU of the reference r-z section (x = r,
    y = z in m; warp by ``displacement [m]`` for the deformed shape), as
    :func:`.export.field_mesh` writes the linear body's, with the rubber model as a flag."""
    model = curve.system.material.model
    scalars = step_field_data(step, curve.indenter, material, model)
    scalars["strain_energy [J]"] = step.strain_energy
    solution = SimpleNamespace(system=curve.system, **curve.system.fields(step.solution))
    write_vtu(path, field_mesh(solution, scalars))
    return path


def write_impact_fields(
    run: ImpactRun, indenter: object, material: Any, model: str, folder: Path
) -> None:
    """``field_<i>_t<t>s.vtu`` of a rubber's impact at each time its run kept (the step
    nearest it, :class:`~shtaerman.fem.finite_dynamic.KeptStates`): the fields of
    :func:`write_finite_field`, with that step's time, depth and force as field data."""
    kept = run.kept
    assert kept is not None
    for index, wanted in enumerate(sorted(kept.states)):
        actual, fields = kept.fields(wanted)
        k = int(np.argmin(np.abs(run.t - actual)))
        step = SimpleNamespace(depth=float(run.x[k]), force=float(run.force[k]))
        scalars = {"time [s]": actual, **step_field_data(step, indenter, material, model)}
        solution = SimpleNamespace(system=kept.system, **fields)
        write_vtu(folder / f"field_{index}_t{actual:.6e}s.vtu", field_mesh(solution, scalars))


def write_finite_curve(result: FiniteIndentationResult, folder: Path) -> list[Path]:
    """``finite_curve.csv`` and ``field_max_depth.vtu`` of a finite-strain contact run (what
    ``shtaerman contact --model neo-hookean --out`` writes beside contact.json)."""
    folder = Path(folder)
    rows = result.step_table()
    curve_path = folder / "finite_curve.csv"
    write_csv(curve_path, {k: [row[k] for row in rows] for k in rows[0]})
    field_path = folder / "field_max_depth.vtu"
    write_finite_field(result.curve, result.steps[-1], result.half_space, field_path)
    return [curve_path, field_path]


def write_finite_study(
    outcome: FiniteStudyOutcome, folder: Path, root: Path, figure_format: str = "png"
) -> tuple[dict[str, str], dict[str, str]]:
    """A finite-strain study's files and figures in ``folder`` (created), paths from ``root``
    (``figure_format`` "svg" or "pdf": each chart also in that format beside its PNG)."""
    folder = Path(folder)
    folder.mkdir()
    rows = outcome.rows()
    written = [folder / "finite_curve.csv"]
    write_csv(written[0], {k: [row[k] for row in rows] for k in CURVE_KEYS})
    written += write_histories(outcome.histories, folder)
    step = outcome.finite.steps[nearest_step(outcome)]
    written.append(
        write_finite_field(
            outcome.finite.curve, step, outcome.study.half_space, folder / "field_at_x_c.vtu"
        )
    )
    fmt, model = {"figure_format": figure_format}, model_label(outcome.study.rubber.name)
    captions = {key: text.replace("neo-Hookean", model) for key, text in CAPTIONS.items()}
    figures = {
        captions["finite_ratios"]: plot_finite_ratios(outcome, folder / "finite_ratios.png", **fmt),
        f"{captions['finite_section']} ({step.depth * 1e3:.3g} mm)": plot_finite_section(
            outcome, folder / "finite_section.png"
        ),
        captions["finite_impact"]: plot_finite_impact(outcome, folder / "finite_impact.png", **fmt),
    }
    files = {path.stem: str(path.relative_to(root)) for path in written}
    return files, {caption: str(path.relative_to(root)) for caption, path in figures.items()}
