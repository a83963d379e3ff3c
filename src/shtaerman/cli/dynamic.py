"""``shtaerman dynamic``: the elastodynamic FE impact against the quasi-static theory."""

from __future__ import annotations

import argparse
import math

from ..api.fem_dynamic import dynamic
from ..fem.dynamic_contact import DynamicSettings, validate_density
from ..output.files import write_csv
from ..study.dynamic import DynamicTolerances
from ..theory.materials import Material
from ..validation import InputError, validate_positive
from .common import (
    FEM_POISSON_LOW,
    PAPER,
    add_figure_format,
    add_half_space_options,
    add_indenter_options,
    print_json,
    warn,
)
from .common import half_space as read_half_space
from .common import indenter as read_indenter
from .impact import history_path

DEFAULT_DENSITY = "1100"
"""kg/m^3, natural rubber; the paper gives no density (it neglects inertia)."""
ENERGY_BALANCE_LIMIT = DynamicTolerances().energy_balance
"""A run whose energy account is off by more (of M v0^2/2) warns and exits with code 1."""

CONTROLS = {
    "steps": ("steps", int, "time steps per quasi-static impact duration t_y, >= 50"),
    "mesh_size": ("size", float, "smallest element size / refined radius"),
    "mesh_margin": ("margin", float, "refined radius / quasi-static contact radius, > 1"),
    "domain_factor": ("domain", float, "domain radius / refined radius, in [1e2, 1e7]"),
    "growth": ("growth", float, "element size growth per unit distance, in (0, 1]"),
    "layer_rate": ("layer_rate", float, "absorbing-layer damping rate x t_y (0: no layer)"),
}
"""Numerical options: the DynamicSettings field each sets, its type and meaning."""


def register(commands: argparse._SubParsersAction) -> None:
    """Add the ``dynamic`` subcommand."""
    p = commands.add_parser(
        "dynamic",
        help="elastodynamic FE impact (waves included) against the quasi-static theory",
        description=(
            "Rigid striker z = A r^n (mass M, velocity v0) on an elastic half-space with "
            "inertia: axisymmetric Taylor-Hood P2-P1 FEM, generalized-alpha time stepping, "
            "exact unilateral contact every step. Reports the rebound, the energy carried "
            "away by elastic waves and the first-order estimate of it. SI units. Exit code 1 "
            "(with a warning) when the energy balance is off by more than 1e-2 of M v0^2/2."
        ),
    )
    p.add_argument("--mass", default=PAPER["mass"], metavar="KG", help="striker mass M in kg")
    p.add_argument(
        "--velocity", default=PAPER["velocity"], metavar="M/S", help="approach velocity v0 in m/s"
    )
    add_indenter_options(p)
    add_half_space_options(p, FEM_POISSON_LOW)
    p.add_argument(
        "--density2",
        default=DEFAULT_DENSITY,
        metavar="KG/M3",
        help="half-space density in kg/m^3 (the paper gives none; 1100 is natural rubber)",
    )
    p.add_argument("--json", action="store_true", help="print one JSON object (SI units)")
    p.add_argument("--history", metavar="FILE.csv", help="write t,x,v,P,a,p0 every time step")
    p.add_argument("--out", metavar="DIR", help="write JSON, CSV histories and VTU fields to DIR")
    p.add_argument("--force", action="store_true", help="replace an existing --history / --out")
    add_figure_format(p)
    accuracy = p.add_argument_group("accuracy (error estimates from a 3-level ladder)")
    accuracy.add_argument(
        "--refine",
        default="1",
        metavar="K",
        help="divide the mesh size field and the time step by K together; the ladder adds "
        "K/2 and K/sqrt(2) for the Richardson estimates of x_max, P_max, t_contact, e",
    )
    accuracy.add_argument(
        "--no-estimate",
        action="store_true",
        help="skip the two coarser runs (no error_estimate in the JSON; about 40 %% faster)",
    )
    numerics = p.add_argument_group(
        "expert numerical controls (relative to the quasi-static impact; --refine scales the "
        "mesh sizes and steps together)"
    )
    defaults = DynamicSettings()
    for option, (field, _, meaning) in CONTROLS.items():
        numerics.add_argument(
            "--" + option.replace("_", "-"),
            default=f"{getattr(defaults, field):.6g}",
            metavar="X",
            help=meaning,
        )
    p.set_defaults(handler=run)


def settings_from(args: argparse.Namespace) -> DynamicSettings:
    """DynamicSettings from the numerical options; errors name the option."""
    values = {}
    for option, (field, kind, _) in CONTROLS.items():
        text = getattr(args, option)
        name = option.replace("_", "-")
        try:
            number = float(text)
        except ValueError:
            raise InputError(f"{name} must be a number, got {text!r}") from None
        if kind is int:
            if not math.isfinite(number) or number != int(number):
                raise InputError(f"{name} must be an integer, got {text!r}")
            number = int(number)
        values[field] = number
    try:
        return DynamicSettings(**values)
    except InputError as error:
        raise InputError(f"{error}") from None


def run(args: argparse.Namespace) -> int:
    """Run the dynamic impact (:func:`shtaerman.dynamic`); print text or JSON; write the
    history and folder if asked."""
    mass = validate_positive("mass", args.mass, "kg")
    velocity = validate_positive("velocity", args.velocity, "m/s")
    density = validate_density(args.density2)
    indenter, half_space = read_indenter(args), read_half_space(args, FEM_POISSON_LOW)
    body = Material(half_space.youngs_modulus, half_space.poisson_ratio, density)
    settings = settings_from(args)
    history = history_path(args.history, force=args.force)
    result = dynamic(
        indenter,
        body,
        mass=mass,
        velocity=velocity,
        refine=validate_positive("refine", args.refine),
        estimate=not args.no_estimate,
        settings=settings,
        out=args.out,
        force=args.force,
        figure_format=args.figure_format,
    )
    report = result.to_dict()
    if history is not None:
        write_csv(history, result.history())
    if args.json:
        print_json(report)
    else:
        print(dynamic_text(report))
    balance = report["dynamic"]["energy_balance_error"]
    if not balance <= ENERGY_BALANCE_LIMIT:  # NaN included
        warn(
            f"energy balance error {balance:.1e} of M v0^2/2 exceeds {ENERGY_BALANCE_LIMIT:g}: "
            "the mesh and time steps (sized from the quasi-static impact) do not resolve this "
            "impact, so its numbers are not to be trusted"
        )
        return 1
    return 0


def _differences_text(report: dict) -> str:
    """Quasi-static / dynamic - 1 in per cent, with the estimated error where there is one."""
    errors = report.get("differences_error") or {}
    cells = []
    for key, value in report["differences"].items():
        error = errors.get(key)
        spread = f" ± {100 * error:.2f}" if error is not None else ""
        cells.append(f"{key} {100 * value:+.2f}{spread} %")
    return (
        "  quasi-static / dynamic - 1  " + ", ".join(cells) + "\n"
        "                              (x_c against x_max, P_c against P_max, t_c against "
        "t_contact / 2)"
    )


def dynamic_text(report: dict) -> str:
    """A readable summary (SI units)."""
    qs, dyn, est = report["quasi_static"], report["dynamic"], report["radiation_estimate"]
    mesh, timings = report["mesh"], report["timings"]
    rows = [
        "Dynamic FE impact against the quasi-static theory (rigid striker, SI units)",
        "                          dynamic FEM     quasi-static",
        f"  max approach x (m)      {dyn['x_max']:<14.6e}  {qs['x_c']:.6e}",
        f"  max force P (N)         {dyn['P_max']:<14.6e}  {qs['P_c']:.6e}",
        f"  time of max x (s)       {dyn['t_x_max']:<14.6e}  {qs['t_c']:.6e}",
        f"  contact duration (s)    {dyn['t_contact']:<14.6e}  {qs['t_y']:.6e}",
        f"  restitution e           {dyn['restitution']:<14.6f}  1 (first-order estimate "
        f"{est['restitution']:.6f})",
        f"  energy to waves 1-e^2   {dyn['energy_radiated_fraction']:<14.6f}  0 (first-order "
        f"estimate {est['energy_fraction']:.6f})",
        _differences_text(report),
        f"  energy balance error    {dyn['energy_balance_error']:.1e} of M v0^2/2;  reflected "
        f"{dyn['reflected_energy_fraction']:.1e} of the radiated",
        f"  mesh: {mesh['nodes']} nodes, {mesh['elements']} P2 triangles, {mesh['dofs']} dofs, "
        f"{mesh['contact_candidates']} contact candidates",
        "  time (s): " + ", ".join(f"{k} {v:.2f}" for k, v in timings.items()),
    ]
    if "error_estimate" in report:
        ladder = ", ".join(f"{lv['dofs']} dofs/{lv['steps']} steps" for lv in report["mesh_ladder"])
        estimate = report["error_estimate"]
        rows += [
            f"  estimated relative errors (ladder {ladder}): "
            + ", ".join(f"{key} {value:.1e}" for key, value in estimate.items())
        ]
    return "\n".join(rows)
