"""``shtaerman impact``: the exact quasi-static impact (the paper's example by default)."""

from __future__ import annotations

import argparse
import math
from pathlib import Path
from typing import TYPE_CHECKING

from ..output.files import check_output_file, staged_file, write_csv
from ..theory.materials import Material
from ..validation import InputError
from . import common

if TYPE_CHECKING:
    from ..theory.impact import ImpactResult
    from ..theory.sneddon import Indenter

NOTES = {
    "history": "columns t [s], x [m], P [N], a [m], p0 [Pa] over [0, t_y]",
    "force": "an existing --history file",
}
"""What ``impact`` does with its output options."""


def register(commands: argparse._SubParsersAction) -> None:
    """Add the ``impact`` subcommand."""
    p = commands.add_parser(
        "impact",
        help="exact quasi-static impact (the paper's example by default)",
        description="Exact quasi-static impact M x'' = -P(x), SI units: Ateb functions for "
        "z = A r^n, Sneddon's integrals and quadrature for a sphere or a tabulated profile.",
    )
    inputs = (
        *common.CASE,
        *common.PROFILES,
        "E1",
        "nu1",
        "E2",
        "nu2",
        "json",
        "history",
        "points",
        "force",
        "check",
    )
    common.add_inputs(p, inputs, "impact", notes=NOTES)
    p.set_defaults(handler=run)


def history_path(value: str | None, *, force: bool) -> Path | None:
    """The --history file, checked before any work (see :func:`check_output_file`); an error
    names the option (``--history: ...``), as the other options' do."""
    if value is None:
        return None
    with common.in_option_words():
        return check_output_file(value, force=force, option="history")


IDLE = {"points": "the rows of the history file", "force": "it lets the run replace it"}
"""The options that act on the --history file, and what they do there."""


def refuse_idle_options(args: argparse.Namespace) -> None:
    """Refuse, in one line, --points or --force given without --history (they did nothing)."""
    for name, what in IDLE.items():
        if common.given(args, name) and args.history is None:
            raise InputError(
                f"--{name}: applies with --history only ({what}); give --history too", name
            )


def run(args: argparse.Namespace) -> int:
    """Solve the impact (:func:`shtaerman.impact`) and print it; write the history if asked."""
    from ..api.quasi_static import impact  # here, not at load: the theory loads scipy

    refuse_idle_options(args)
    history = history_path(args.history, force=args.force)
    with common.in_option_words():
        result = impact(
            common.indenter(args),
            Material(args.E2, args.nu2),
            mass=args.mass,
            velocity=args.velocity,
            striker=common.striker(args),
            check=args.check,
        )
    report = result.to_dict()
    if history is not None:
        with staged_file(history, force=args.force) as stage:
            write_csv(stage, result.history(args.points).columns())
    if args.json:
        common.print_json(report)
    else:
        print(_impact_text(result.solution, report))
    return 0


def _striker_words(indenter: Indenter) -> str:
    """The striker's profile in words for the text report."""
    if indenter.kind == "sphere":
        return f"an exact sphere of radius {indenter.radius:g} m"
    if indenter.kind == "tabulated":
        return f"the tabulated profile {indenter.source} ({indenter.radii.size} points)"
    return f"z = {indenter.shape_coefficient:g} r^{indenter.exponent:g}"


def _impact_text(result: ImpactResult, report: dict) -> str:
    law = result.law
    rows = [
        f"Quasi-static impact of {_striker_words(law.indenter)} on an elastic half-space "
        "(SI units)",
        f"  mass M                    {result.mass:>14.6g} kg",
        f"  approach velocity v0      {result.velocity:>14.6g} m/s",
        f"  combined modulus E*       {law.modulus:>14.6e} Pa",
    ]
    if law.indenter.kind == "power-law":
        q = result.force_exponent
        rows.append(f"  force law P = beta x^q    q = {q:.6g}")
        rows.append(f"  beta                      {result.beta:>14.6e} N/m^{q:.4g}")
    else:
        rows.append("  force law (Sneddon)       exact, no power law (quadrature)")
    rows += [
        f"  max approach x_c          {result.x_c:>14.6e} m",
        f"  max force P_c             {result.P_c:>14.6e} N",
        f"  max contact radius a_c    {result.a_c:>14.6e} m",
        f"  max central pressure p_c  {result.p_c:>14.6e} Pa",
        f"  compression time t_c      {result.t_c:>14.6e} s",
        f"  impact duration t_y       {result.t_y:>14.6e} s",
        f"  impulse 2 M v0            {result.impulse:>14.6e} N s",
        f"  impulse, paper eq. (16)   {result.impulse_simpson:>14.6e} N s",
    ]
    if not math.isfinite(result.p_c) and law.indenter.kind == "power-law":
        rows.append("  (n <= 1: the pressure at the centre of the contact is unbounded)")
    if "ode_check" in report:
        check = report["ode_check"]
        rows.append(
            f"  ODE cross-check: x_c {check['x_c'] / result.x_c - 1:+.1e}, "
            f"t_y {check['t_y'] / result.t_y - 1:+.1e}, "
            f"history max |dx|/x_c {check['max_history_difference']:.1e}"
        )
    return "\n".join(rows)
