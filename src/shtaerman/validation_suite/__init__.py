"""The validation suite: published results, each recomputed by the suite as a user would
(``shtaerman validate``; the table of docs/validation.md).

- :mod:`.layer`: Dimitriadis et al. (2002) and Garcia & Garcia (2018), a sphere on an
  incompressible layer, and the first-order coefficient of a lubricated base;
- :mod:`.hunter`: Hunter (1957), the energy radiated as elastic waves in an impact;
- :mod:`.long2011`: Long et al. (2011), a neo-Hookean layer at finite strain.
"""

from __future__ import annotations

from collections.abc import Callable

from .row import Row

__all__ = ["Row", "run_suite", "suite_text"]


def run_suite(quick: bool = False, progress: Callable[[str], None] | None = None) -> list[Row]:
    """Every row of the suite.

    Parameters
    ----------
    quick : bool
        Coarse meshes (``refine`` 0.5, 0.6 at finite strain) and the lubricated first-order
        coefficient only: about 20 s instead of about 1 min; the tolerances hold at both.
    progress : callable, optional
        Called with the name of each case as it starts.
    """
    from .hunter import hunter_rows  # here, not at load: they load the FEM's API and scipy
    from .layer import layer_rows, slope_rows
    from .long2011 import long_rows

    refine = 0.5 if quick else 1.0
    cases = (
        ("layer (Dimitriadis 2002, Garcia 2018)", lambda: layer_rows(refine)),
        (
            "layer, first-order coefficient",
            lambda: slope_rows(("lubricated",) if quick else ("lubricated", "bonded")),
        ),
        ("elastic waves (Hunter 1957)", lambda: hunter_rows(refine=refine)),
        ("finite strain on a layer (Long 2011)", lambda: long_rows(max(refine, 0.6))),
    )
    rows: list[Row] = []
    for name, run in cases:
        if progress is not None:
            progress(name)
        rows.extend(run())
    return rows


def suite_text(rows: list[Row]) -> str:
    """The rows as a plain-text table, one line per row, grouped by case."""
    lines = []
    case = None
    for row in rows:
        if row.case != case:
            case = row.case
            lines.append(f"\n{case}")
        lines.append(
            f"  {row.source[:44]:44s} {row.inputs[:34]:34s} published {row.published:9.4f}  "
            f"suite {row.value:9.4f} +- {row.error_bar:.1e}  diff {row.difference:+.4f}  "
            f"tol {row.tolerance:.4f}  {row.verdict}"
        )
    failed = sum(row.verdict == "DISAGREES" for row in rows)
    lines.append(f"\n{len(rows)} rows, {failed} disagreeing beyond tolerance")
    return "\n".join(lines).lstrip("\n")
