"""``shtaerman fit``: the rubber's constants from a measurement, with 95 % intervals."""

from __future__ import annotations

import argparse
import contextlib
import sys
from collections.abc import Iterator
from typing import TYPE_CHECKING

from ..fitting.data import FE_REFINE, KIND_COLUMNS, KINDS, article, parse_units
from ..problem import RUBBER_OPTIONS, Problem
from ..theory.materials import RIGID, Material
from ..validation import InputError
from ..vocabulary import entry
from . import common

if TYPE_CHECKING:
    from ..fitting.result import FitResult

__all__ = ["fit_text", "register", "run"]

DESCRIPTION = """\
Fit the unknowns of a problem to a measurement by the exact quasi-static models: the power-law
contact law (indentation), the Ateb impact or with --prony the viscoelastic one (Lee-Radok,
Ting) (force-history, rebound, resilience). The known values are the usual options; those of
the unknowns are the starting values. A force history or rebound data on a pad
(--thickness), with waves (--density2) or at finite strain (--model) are corrected by FE
impacts at the fitted point (fit, FE runs, fit again: a handful of rounds, one FE run per
drop velocity of rebound data); their error estimates and the viscoelastic impact's step
error widen the intervals. An indentation curve at finite strain (--model) or on a pad
(--thickness) is fitted by FE contact curves (E2 scales out: one FE curve; one shape constant
besides, 3 or more: --fit E2,mooney_ratio with --model mooney-rivlin, E2,yeoh_c2 with yeoh (c3
held), E2,gent_limit with gent, E2,nu2 on a bonded pad). Friction is not fitted.

KIND and the CSV columns it reads (header 'name [unit]'):
  indentation     depth [m], force [N]                      -> E2 (or nu2 with E2 known;
                                                               with --model a shape constant)
  force-history   time [s], force [N]                       -> E2, time_offset, baseline,
                                                               mass or velocity, prony, tau
  rebound         velocity [m/s] with restitution [1] and/or contact_time [s] -> E2, prony, tau,
                                                               mass
  resilience      velocity [m/s], resilience [1] (ISO 4662, e^2)             -> prony, tau;
                                                               or E2 or mass, tau known

The result gives each unknown's value and 95 % interval, and identifiable false (with its
bounds as the interval) for what the data cannot determine."""
NOTES = {
    "out": "fit.json (the --json object), fit.csv (data, fit, residual) and fit.png",
    "E2": "known, or the starting value with --fit E2",
    "nu2": "known, or the starting value with --fit nu2",
    "mass": "known, or the starting value with --fit mass",
    "velocity": "of a force history: known, or the starting value with --fit velocity",
    "prony": "the starting values with --fit prony (the g_i) and --fit tau (the tau_i); its "
    "number of terms is the fitted series'",
}
"""What ``fit`` does with some of its options."""
DERIVED = {
    "E1": "2e+11; rigid, the FE runs' striker, in a fit they correct (--thickness, --density2, "
    "--model)",
    "density2": "unset: no waves",
    "refine": f"{FE_REFINE:g}: a coarse mesh with its error estimate, seconds a run",
    "mooney_ratio": "0, the start of --fit mooney_ratio; only with --model mooney-rivlin",
    "yeoh": "0,0; only with --model yeoh; c2 the start of --fit yeoh_c2",
    "gent_limit": "none: required with --model gent; the start of --fit gent_limit",
}
"""The defaults of ``fit`` that differ from the other commands'."""
PRONY_HELP = (
    "shear relaxation of the half-space, the Prony series g1:tau1,g2:tau2,... (tau_i in s): "
    "G(t) = G0 [1 - sum g_i (1 - exp(-t/tau_i))], E2 the instantaneous modulus; the fit uses "
    "the viscoelastic quasi-static impact, and with --fit prony the g_i, with --fit tau the "
    "tau_i are the starting values (the others fixed); unset: elastic"
)
"""The help of ``--prony`` for a fit."""


def register(commands: argparse._SubParsersAction) -> None:
    """Add the ``fit`` subcommand."""
    p = commands.add_parser(
        "fit",
        help="fit E2 (and nu2, Prony weights, ...) to a measured curve, history or rebound",
        description=DESCRIPTION,
    )
    p.add_argument("kind", choices=KINDS, metavar="KIND", help=f"one of {', '.join(KINDS)}")
    p.add_argument(
        "data",
        type=common.path_text,
        metavar="DATA.csv",
        help="the measurement, a CSV 'name [unit]'",
    )
    inputs = (*common.CASE, *common.PROFILES, "E1", "nu1", "E2", "nu2", "prony", "density2",
              "thickness", "base", "model", *RUBBER_OPTIONS, "unknowns", "noise", "time_offset",
              "baseline", "units", "resample", "refine", "json", "out", "force")  # fmt: skip
    common.add_inputs(p, inputs, None, notes=NOTES, derived=DERIVED)
    prony = next(a for a in p._actions if "--prony" in a.option_strings)
    prony.help = PRONY_HELP  # the series' own help speaks of --model, which fit does not take
    common.add_figure_format(p)
    p.set_defaults(handler=run)


USED_BY = {
    "mass": ("force-history", "rebound", "resilience"),
    "velocity": ("force-history",),  # rebound data give one per row
    "time_offset": ("force-history",),
    "baseline": ("force-history",),
}
"""The kinds of data an option of the impact applies to (refused for the others)."""
PASSED = ("unknowns", "noise", "time_offset", "baseline", "resample", "out", "force")
"""Options :func:`shtaerman.fit` takes as they are parsed."""


def refuse_unused(args: argparse.Namespace) -> None:
    """InputError naming an option the kind of data does not use, or a --units column it
    does not read."""
    for name, kinds in USED_BY.items():
        if common.given(args, name) and args.kind not in kinds:
            raise InputError(
                f"{entry(name).cli_option}: applies to {' or '.join(kinds)} data, not to "
                f"{article(args.kind)}"
            )
    needed, some = KIND_COLUMNS[args.kind]
    for column in parse_units(args.units):
        if column not in (*needed, *some):
            raise InputError(
                f"--units: {article(args.kind)} reads no column {column!r} (it reads "
                f"{', '.join((*needed, *some))})"
            )


def _problem(args: argparse.Namespace) -> Problem:
    """The problem the options describe: its known parts and the unknowns' starts."""
    from ..fitting.corrections import needs_fe  # here, not at load (see run)

    density = args.density2 if common.given(args, "density2") else None
    body = Material(args.E2, args.nu2, density)
    if args.E1 is not None:  # given: the FE fits refuse it where their rigid striker drops it
        return common.impact_problem(args, body, striker=common.striker(args))
    steel = Material(entry("E1").default_for(None), args.nu1)
    problem = common.impact_problem(args, body, striker=steel)
    # unset: the FE runs' rigid striker where they correct the fit, as dynamic's and contact's
    return common.impact_problem(args, body, striker=RIGID) if needs_fe(problem) else problem


def run(args: argparse.Namespace) -> int:
    """Fit (:func:`shtaerman.fit`) and print the fitted values or the JSON."""
    from ..fitting.run import fit  # here, not at load: the fit loads the theory and scipy

    common.refuse_idle_output_options(args, ("out",))
    with common.in_option_words(), _data_as_argument():
        refuse_unused(args)
        result = fit(
            args.kind,
            args.data,
            _problem(args),
            **common.keywords(args, PASSED),
            units=parse_units(args.units),
            refine=FE_REFINE if args.refine is None else args.refine,
            figure_format=args.figure_format,
            progress=lambda line: print(line, file=sys.stderr, flush=True),
        )
    if args.json:
        common.print_json(result.to_dict())
    else:
        print(fit_text(result))
    return 0


@contextlib.contextmanager
def _data_as_argument() -> Iterator[None]:
    """Re-raise sh.fit's refusal of its keyword data (``data: cannot read ...``) naming the
    argument the command line took, DATA."""
    try:
        yield
    except InputError as error:
        if error.parameter != "data" or not str(error).startswith("data: "):
            raise
        raise InputError("DATA" + str(error)[len("data") :], "data") from None


def _corrections_text(result: FitResult) -> list[str]:
    """The corrections line(s) of the text output."""
    if not result.corrections:
        return ["  corrections:   none (a half-space of no density at small strain)"]
    rows = []
    for item in result.corrections:
        if "nodes" in item:  # an indentation's FE curves
            nodes = ", ".join(f"{r:.4g}" for r in item["nodes"])
            where = f", at {item['shape']} {nodes}" if item["shape"] else ""
            sizes = f"force error {item['fe_error']['force']:.2g}{where}"
            rows.append(f"  corrections:   {item['name']}: {sizes} ({result.fe_runs} FE runs)")
            continue
        if "force_scale" in item:  # a force history's
            sizes = f"peak force x{item['force_scale']:.4g}, contact time x{item['time_scale']:.4g}"
        else:  # rebound data's, per velocity
            e = ", ".join(f"{r:.4g}" for r in item["restitution_scale"])
            t = ", ".join(f"{r:.4g}" for r in item["time_scale"])
            sizes = f"restitution x({e}), contact time x({t}) per velocity"
        rows.append(f"  corrections:   {item['name']}: {sizes} at the fitted point "
                    f"({result.fe_runs} FE runs)")  # fmt: skip
    return rows


def fit_text(result: FitResult) -> str:
    """The fitted values, intervals and residual as text."""
    rows = [
        f"Fit of {result.kind} data ({result.data['rows']} rows of {result.data['source']})",
        f"  forward model: {result.forward_model}",
        *_corrections_text(result),
        f"  {'unknown':<12} {'value':>13} {'95 % interval':>29}  unit",
    ]
    for name, item in result.fitted.items():
        interval = f"[{item['low']:.6g}, {item['high']:.6g}]"
        note = "" if item["identifiable"] else "  not identifiable from these data"
        rows.append(f"  {name:<12} {item['value']:>13.6g} {interval:>29}  {item['unit']}{note}")
        if "reason" in item:
            rows.append(f"  {'':<12} ({item['reason']})")
    noise = result.noise
    how = "estimated from the residual" if noise["estimated"] else "given"
    units = [item["unit"].removeprefix("1 ") for item in (result.residual, noise)]  # relative
    fitted = any(item["identifiable"] for item in result.fitted.values())
    where = "" if fitted else " at the values above (none fitted)"  # the noise's residual too
    rows.append(
        f"  residual rms {result.residual['rms']:.4g} {units[0]}{where}; "
        f"noise {noise['value']:.4g} {units[1]} ({how})"
    )
    return "\n".join(rows)
