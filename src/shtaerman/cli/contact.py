"""``shtaerman contact``: the FEM frictionless contact against Shtaerman's exact solution."""

from __future__ import annotations

import argparse
import math

import numpy as np

from ..api.fem_contact import MESH_OPTIONS, MODELS, contact
from ..fem.finite_contact import FINITE_MESH
from ..fem.mesh import DEFAULTS, MeshSettings
from ..fem.solver import BACKENDS
from ..validation import InputError, validate_increasing, validate_positive
from .common import (
    FEM_POISSON_LOW,
    PAPER,
    add_figure_format,
    add_half_space_options,
    add_indenter_options,
    print_json,
)
from .common import half_space as read_half_space
from .common import indenter as read_indenter

MESH_HELP = {
    "mesh_size": "smallest element size / refined radius",
    "mesh_margin": "refined radius / largest geometric contact radius, in (1, 10]",
    "domain_factor": "domain radius / refined radius, in [1e2, 1e7]",
    "growth": "element size growth per unit distance from the refined zone",
    "max_dofs": "refuse a mesh estimated (before meshing) above this many unknowns",
}
"""Meaning of each command-line mesh option (the MeshSettings field: MESH_OPTIONS)."""


def register(commands: argparse._SubParsersAction) -> None:
    """Add the ``contact`` subcommand."""
    p = commands.add_parser(
        "contact",
        help="FEM frictionless contact against Shtaerman's solution",
        description=(
            "Press a rigid indenter z = A r^n into the FEM half-space (gmsh + scikit-fem, "
            "Taylor-Hood P2-P1) and compare force, contact radius and central pressure with "
            "the exact solution. SI units."
        ),
    )
    add_indenter_options(p)
    add_half_space_options(p, FEM_POISSON_LOW)
    _add_case_options(p)
    _add_accuracy_options(p)
    _add_mesh_options(p)
    p.set_defaults(handler=run)


def _add_case_options(p: argparse.ArgumentParser) -> None:
    """--model, the impact of the default depths, --depths and the outputs."""
    p.add_argument(
        "--model",
        default="linear",
        choices=MODELS,
        help="linear elasticity (Shtaerman's setting) or a neo-Hookean solid at finite strain "
        "with the same E2, nu2 at small strain (total Lagrangian, contact in the current "
        "configuration; any depth ladder, load stepping is internal)",
    )
    p.add_argument(
        "--mass",
        metavar="KG",
        help=f"striker mass M in kg of the impact whose x_c the default depths reach "
        f"(default: {PAPER['mass']})",
    )
    p.add_argument(
        "--velocity",
        metavar="M/S",
        help=f"approach velocity v0 in m/s of that impact (default: {PAPER['velocity']})",
    )
    p.add_argument(
        "--depths",
        metavar="D1,D2,...",
        help="depths in m, comma-separated, increasing (default: 8 up to the x_c of the "
        "impact of --mass at --velocity on this indenter and half-space, contact radii "
        "a_c/3 .. a_c)",
    )
    p.add_argument("--json", action="store_true", help="print one JSON object (SI units)")
    p.add_argument(
        "--out",
        metavar="DIR",
        help="write contact.json, CSV curves, VTU fields and (linear model) the figures "
        "force_depth.png and pressure.png to DIR",
    )
    p.add_argument("--force", action="store_true", help="replace an existing --out folder")
    add_figure_format(p)


def _add_accuracy_options(p: argparse.ArgumentParser) -> None:
    """--refine, --no-estimate, --accuracy and --max-time."""
    accuracy = p.add_argument_group(
        "accuracy (every FEM number with an error estimate from a 3-mesh ladder)"
    )
    accuracy.add_argument(
        "--refine",
        default="1",
        metavar="K",
        help="divide the whole mesh size field by K (dofs ~ K^2); the ladder adds K/2 and "
        "K/sqrt(2) for the Richardson estimate",
    )
    accuracy.add_argument(
        "--no-estimate",
        action="store_true",
        help="run the K mesh only (no error_estimate in the JSON; about 40 %% faster)",
    )
    accuracy.add_argument(
        "--accuracy",
        metavar="TOL",
        help="refine until the estimated relative error of force and beta is <= TOL (linear "
        "model only)",
    )
    accuracy.add_argument(
        "--max-time",
        default="60",
        metavar="S",
        help="time budget of --accuracy in s (only with --accuracy)",
    )


def _add_mesh_options(p: argparse.ArgumentParser) -> None:
    """The expert mesh controls and --solver."""
    mesh = p.add_argument_group(
        "expert mesh controls (relative to the largest contact; --mesh-size alone does not "
        "refine the far field, the axis grading or the growth: use --refine)"
    )
    for option, field in MESH_OPTIONS.items():
        mesh.add_argument(
            "--" + option.replace("_", "-"),
            metavar="X",
            help=f"{MESH_HELP[option]} (default: {getattr(DEFAULTS, field):.6g} linear, "
            f"{getattr(FINITE_MESH, field):.6g} neo-hookean)",
        )
    mesh.add_argument("--solver", default="auto", choices=("auto", *BACKENDS), help="sparse solver")


def _depths(text: str | None) -> np.ndarray | None:
    if text is None:
        return None
    return validate_increasing("depths", [item for item in text.split(",") if item.strip()], "m")


def mesh_settings(args: argparse.Namespace, base: MeshSettings = DEFAULTS) -> MeshSettings:
    """MeshSettings from the mesh options over ``base``; errors name the option, not the field."""
    from ..api.fem_contact import mesh_settings as settings

    options = {option: getattr(args, option) for option in MESH_OPTIONS}
    return settings(base, options, lambda name: name.replace("_", "-"))


def _optional(name: str, value: str | None, unit: str) -> float | None:
    return None if value is None else validate_positive(name, value, unit)


def _check_combinations(args: argparse.Namespace) -> None:
    """Refuse options that exclude each other, in the command line's words."""
    if args.accuracy is not None and args.model == "neo-hookean":
        raise InputError(
            "accuracy: applies to the linear model only; for --model neo-hookean use --refine "
            "K, whose estimates come with every run"
        )
    if args.accuracy is not None and args.no_estimate:
        raise InputError("accuracy: needs the error estimates; drop --no-estimate")
    if args.accuracy is not None and validate_positive("refine", args.refine) != 1.0:
        raise InputError(
            f"refine: --accuracy chooses the refinement itself (its ladder starts at refine 1), "
            f"got --refine {float(args.refine):g}; drop one of them"
        )


def run(args: argparse.Namespace) -> int:
    """Run the contact curve (:func:`shtaerman.contact`) and print it (text or JSON)."""
    indenter, half_space = read_indenter(args), read_half_space(args, FEM_POISSON_LOW)
    max_time = validate_positive("max-time", args.max_time, "s")
    _check_combinations(args)
    result = contact(
        indenter,
        half_space,
        mass=_optional("mass", args.mass, "kg"),
        velocity=_optional("velocity", args.velocity, "m/s"),
        depths=_depths(args.depths),
        model=args.model,
        refine=validate_positive("refine", args.refine),
        estimate=not args.no_estimate,
        accuracy=_optional("accuracy", args.accuracy, ""),
        max_time=max_time,
        mesh=mesh_settings(args, FINITE_MESH if args.model == "neo-hookean" else DEFAULTS),
        solver=args.solver,
        out=args.out,
        force=args.force,
        figure_format=args.figure_format,
    )
    report = result.to_dict()
    if args.json:
        print_json(report)
    elif result.model == "neo-hookean":
        print(finite_contact_text(report))
    else:
        print(contact_text(report))
    return 0


def finite_contact_text(report: dict) -> str:
    """The finite-strain contact curve beside the linear exact values (SI units)."""
    rows = [
        f"Neo-Hookean contact of z = {report['shape_coefficient']:g} r^{report['exponent']:g} "
        f"on E2 = {report['E2']:g} Pa, nu2 = {report['nu2']:g} (finite strain; 'lin' = "
        "Shtaerman's linear solution)",
        "  depth (m)    force (N)   /lin     radius (m)  /lin     p(0) (Pa)   /lin    p0/pavg"
        "  energy (J)  Newton",
    ]
    for step in report["steps"]:
        ratios = [
            step[k] / step[f"{k}_analytic"] for k in ("force", "contact_radius", "central_pressure")
        ]
        rows.append(
            f"  {step['depth']:.4e}  {step['force']:.5e} {ratios[0]:.4f}  "
            f"{step['contact_radius']:.4e}  {ratios[1]:.4f}  {step['central_pressure']:.4e} "
            f"{ratios[2]:.4f}  {step['central_to_mean']:.4f}   {step['strain_energy']:.4e}  "
            f"{step['newton_iterations']}"
        )
    mesh, timings = report["mesh"], report["timings"]
    rows += [
        f"  beta (q fixed) {report['beta_fem']:.6e} vs linear {report['beta_analytic']:.6e};  "
        f"{_exponent_text(report, 'linear')}",
        f"  mesh: {mesh['nodes']} nodes, {mesh['elements']} P2 triangles, {mesh['dofs']} dofs, "
        f"{mesh['contact_candidates']} contact candidates",
        "  time (s): " + ", ".join(f"{k} {v:.3f}" for k, v in timings.items()),
    ]
    if "error_estimate" in report:
        rows += _estimate_text(report)
    return "\n".join(rows)


def _exponent_text(report: dict, against: str = "") -> str:
    """The fitted exponent against Shtaerman's (and its error, where there is a true one)."""
    fitted = report["exponent_fem"]
    if fitted is None or not math.isfinite(fitted):
        return "exponent: fitted only from >= 2 depths"
    text = f"exponent {fitted:.6f} vs {(against + ' ') if against else ''}"
    text += f"{report['exponent_analytic']:.6f}"
    if "errors" in report:
        text += f" ({report['errors']['exponent']:.1e})"
    return text


def contact_text(report: dict) -> str:
    """The contact curve as a readable table (SI units)."""
    head = (
        f"FEM contact of z = {report['shape_coefficient']:g} r^{report['exponent']:g} on "
        f"E2 = {report['E2']:g} Pa, nu2 = {report['nu2']:g} (E* = {report['modulus']:.6g} Pa)"
    )
    rows = [
        head,
        "  depth (m)    force (N)   rel.err   radius (m)  rel.err   p(0) (Pa)   rel.err  p0/pavg",
    ]
    for step in report["steps"]:
        errors = [
            step[k] / step[f"{k}_analytic"] - 1
            for k in ("force", "contact_radius", "central_pressure")
        ]
        rows.append(
            f"  {step['depth']:.4e}  {step['force']:.5e} {errors[0]:+.1e}  "
            f"{step['contact_radius']:.4e}  {errors[1]:+.1e}  {step['central_pressure']:.4e} "
            f"{errors[2]:+.1e}  {step['central_to_mean']:.4f}"
        )
    mesh, timings, errors = report["mesh"], report["timings"], report["errors"]
    rows += [
        f"  beta (q fixed) {report['beta_fem']:.6e} vs exact {report['beta_analytic']:.6e} "
        f"({errors['beta']:.1e});  {_exponent_text(report)}",
        f"  p0/pavg exact {report['central_to_mean_analytic']:.4f};  pressure profile L2 error "
        f"<= {errors['pressure_profile']:.1e}",
        f"  mesh: {mesh['nodes']} nodes, {mesh['elements']} P2 triangles, {mesh['dofs']} dofs, "
        f"{mesh['contact_candidates']} contact candidates; solver {report['solver']}",
        "  time (s): " + ", ".join(f"{k} {v:.3f}" for k, v in timings.items()),
    ]
    if "error_estimate" in report:
        rows += _estimate_text(report)
    return "\n".join(rows)


def _estimate_text(report: dict) -> list[str]:
    ladder = report["mesh_ladder"]
    estimate, true = report["error_estimate"], report.get("true_error")
    head = (
        f"  estimated errors (ladder {', '.join(str(level['dofs']) for level in ladder)} dofs, "
        f"{sum(level['seconds'] for level in ladder):.1f} s):"
    )
    cells = [
        f"{key} {estimate[key]:.1e}" + (f" (true {true[key]:.1e})" if true else "")
        for key in ("force", "beta", "contact_radius", "central_pressure")
        if key in estimate
    ]
    lines = [head, "    " + ", ".join(cells)]
    target = report.get("accuracy_target")
    if target is not None:
        reached = max(estimate[key] for key in ("force", "beta") if key in estimate)
        lines.append(f"  accuracy target {target:g}: met (force and beta estimate {reached:.1e})")
    return lines
