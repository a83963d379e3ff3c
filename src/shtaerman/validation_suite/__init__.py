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
        coefficient only; the tolerances hold at both.
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
    """The rows as plain text, grouped by case and source as docs/validation.md's tables are:
    a group's head names the case and the whole reference, the quantity and why the tolerance
    is that wide (a refuted source's argument); a row, its whole inputs and numbers; the last
    line counts the verdicts (a source refuted is expected: it does not fail the run)."""
    lines, group = [], None
    for row in rows:
        if (row.case, row.source) != group:
            group = (row.case, row.source)
            lines += ["", f"{row.case}: {row.source}", f"  {row.quantity}. Tolerance: {row.why}"]
        lines.append(
            f"  {row.inputs}: published {row.published:.4f}, suite {row.value:.4f} "
            f"+- {row.error_bar:.1e}, difference {row.difference:+.4f}, tolerance "
            f"{row.tolerance:.4f}: {row.verdict}"
        )
    counts = {v: sum(row.verdict == v for row in rows) for v in ("agrees", "refuted", "DISAGREES")}
    lines.append(
        f"\n{len(rows)} rows: {counts['agrees']} agree, {counts['refuted']} refute their source "
        f"(expected, the argument in docs/validation.md), {counts['DISAGREES']} disagree "
        "beyond tolerance"
    )
    return "\n".join(lines).lstrip("\n")
