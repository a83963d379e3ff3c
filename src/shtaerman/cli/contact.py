"""``shtaerman contact``: the FEM frictionless contact against Shtaerman's exact solution."""

from __future__ import annotations

import argparse
import contextlib
import dataclasses
import json
import math
from pathlib import Path

import numpy as np

from ..fem.finite_contact import FINITE_MESH
from ..fem.mesh import DEFAULTS, MeshSettings
from ..fem.solver import BACKENDS
from ..output.files import check_output_folder, json_safe, staged_folder
from ..validation import InputError, validate_increasing, validate_positive
from .common import add_figure_format, add_half_space_options, add_indenter_options, print_json
from .common import half_space as read_half_space
from .common import indenter as read_indenter

MODELS = ("linear", "neo-hookean")
"""Material models of ``--model``: the first is the default."""

MESH_OPTIONS = {
    "mesh_size": ("size", "smallest element size / refined radius"),
    "mesh_margin": ("margin", "refined radius / largest geometric contact radius, in (1, 10]"),
    "domain_factor": ("domain", "domain radius / refined radius, in [1e2, 1e7]"),
    "growth": ("growth", "element size growth per unit distance from the refined zone"),
    "max_dofs": ("max_dofs", "refuse a mesh estimated (before meshing) above this many unknowns"),
}
"""Command-line mesh options: the MeshSettings field each sets, and its meaning."""


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
    add_half_space_options(p)
    p.add_argument(
        "--model",
        default="linear",
        choices=MODELS,
        help="linear elasticity (Shtaerman's setting) or a neo-Hookean solid at finite strain "
        "with the same E2, nu2 at small strain (total Lagrangian, contact in the current "
        "configuration; any depth ladder, load stepping is internal)",
    )
    p.add_argument(
        "--depths",
        metavar="D1,D2,...",
        help="depths in m, comma-separated, increasing (default: 8 up to the impact x_c of "
        "0.7 kg at 3 m/s, contact radii a_c/3 .. a_c)",
    )
    p.add_argument("--json", action="store_true", help="print one JSON object (SI units)")
    p.add_argument("--out", metavar="DIR", help="write VTU fields and CSV curves to DIR")
    p.add_argument("--force", action="store_true", help="replace an existing --out folder")
    add_figure_format(p)
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
    mesh = p.add_argument_group(
        "expert mesh controls (relative to the largest contact; --mesh-size alone does not "
        "refine the far field, the axis grading or the growth: use --refine)"
    )
    for option, (field, meaning) in MESH_OPTIONS.items():
        mesh.add_argument(
            "--" + option.replace("_", "-"),
            metavar="X",
            help=f"{meaning} (default: {getattr(DEFAULTS, field):.6g} linear, "
            f"{getattr(FINITE_MESH, field):.6g} neo-hookean)",
        )
    mesh.add_argument("--solver", default="auto", choices=("auto", *BACKENDS), help="sparse solver")
    p.set_defaults(handler=run)


def _depths(text: str | None) -> np.ndarray | None:
    if text is None:
        return None
    return validate_increasing("depths", [item for item in text.split(",") if item.strip()], "m")


def mesh_settings(args: argparse.Namespace, base: MeshSettings = DEFAULTS) -> MeshSettings:
    """MeshSettings from the mesh options over ``base``; errors name the option, not the field."""
    chosen = {
        field: getattr(args, option)
        for option, (field, _) in MESH_OPTIONS.items()
        if getattr(args, option) is not None
    }
    for option, (field, _) in MESH_OPTIONS.items():
        if field not in chosen:
            continue
        try:
            MeshSettings(**{field: chosen[field]})
        except InputError as error:
            raise InputError(f"{option.replace('_', '-')}: {error}") from None
    return dataclasses.replace(base, **{field: float(value) for field, value in chosen.items()})


def run(args: argparse.Namespace) -> int:
    """Run the contact curve and print it (text or JSON); write fields if asked."""
    from ..output.export import write_indentation
    from ..plots.gallery import contact_figures
    from ..study.accuracy import run_ladder, run_to_accuracy
    from ..study.indentation import run_indentation

    indenter, half_space = read_indenter(args), read_half_space(args)
    max_time = validate_positive("max-time", args.max_time, "s")
    if args.accuracy is not None and args.model == "neo-hookean":
        raise InputError(
            "accuracy: applies to the linear model only; for --model neo-hookean use --refine "
            "K, whose estimates come with every run"
        )
    if args.accuracy is not None and args.no_estimate:
        raise InputError("accuracy: needs the error estimates; drop --no-estimate")
    if args.model == "neo-hookean":
        return _run_finite(args, indenter, half_space)
    depths, mesh = _depths(args.depths), mesh_settings(args)
    refine = validate_positive("refine", args.refine)
    tolerance = None if args.accuracy is None else validate_positive("accuracy", args.accuracy)
    if tolerance is not None and refine != 1.0:
        raise InputError(
            f"refine: --accuracy chooses the refinement itself (its ladder starts at refine 1), "
            f"got --refine {refine:g}; drop one of them"
        )
    if not args.no_estimate:
        _check_coarsest(mesh, refine)
    out = None
    if args.out is not None:
        out = check_output_folder(Path(args.out), force=args.force)
    with contextlib.ExitStack() as stack:  # the folder is reserved before the FEM starts
        stage = (
            stack.enter_context(staged_folder(out, force=args.force)) if out is not None else None
        )
        if args.no_estimate:
            result = run_indentation(
                indenter, half_space, depths, mesh.refined(refine), backend=args.solver
            )
            ladder = None
        elif tolerance is None:
            ladder = run_ladder(
                indenter, half_space, depths, mesh, refine=refine, backend=args.solver
            )
        else:
            ladder = run_to_accuracy(
                indenter,
                half_space,
                tolerance,
                depths,
                mesh,
                max_time=max_time,
                backend=args.solver,
            )
        if ladder is not None:
            result = ladder.finest
        report = {**result.to_dict(), **(ladder.to_dict() if ladder else {})}
        if stage is not None:
            write_indentation(result, stage)
            contact_figures(result, stage, args.figure_format)
            (stage / "contact.json").write_text(json.dumps(json_safe(report), indent=2))
    if args.json:
        print_json(report)
    else:
        print(contact_text(report))
    return 0


def _check_coarsest(mesh: MeshSettings, refine: float) -> None:
    """Refuse at once a ladder whose coarsest level (refine / 2) is not a valid mesh."""
    from ..study.accuracy import check_ladder

    try:
        check_ladder(mesh, refine)
    except InputError as error:
        raise InputError(f"{error}; or pass --no-estimate") from None


def _run_finite(args: argparse.Namespace, indenter, half_space) -> int:
    """``--model neo-hookean``: the finite-strain curve on the 3-mesh ladder (or the K mesh
    alone with --no-estimate); with --out also contact.json, the curve CSV and the deformed
    fields at the largest depth (VTU)."""
    from ..output.finite import write_finite_curve
    from ..study.finite_indentation import run_finite_ladder, run_finite_study

    depths, mesh = _depths(args.depths), mesh_settings(args, FINITE_MESH)
    refine = validate_positive("refine", args.refine)
    mesh.refined(refine)  # the finest level first: its message names --refine's value
    if not args.no_estimate:
        _check_coarsest(mesh, refine)
    if args.solver == "pardiso":
        raise InputError("solver: the neo-hookean model uses superlu only, got 'pardiso'")
    out = check_output_folder(Path(args.out), force=args.force) if args.out else None
    with contextlib.ExitStack() as stack:  # the folder is reserved before the FEM starts
        stage = (
            stack.enter_context(staged_folder(out, force=args.force)) if out is not None else None
        )
        if args.no_estimate:
            result = run_finite_study(indenter, half_space, depths, mesh.refined(refine))
            report = result.to_dict()
        else:
            ladder = run_finite_ladder(indenter, half_space, depths, mesh, refine=refine)
            result = ladder.finest
            report = {**result.to_dict(), **ladder.to_dict()}
        if stage is not None:
            write_finite_curve(result, stage)
            (stage / "contact.json").write_text(json.dumps(json_safe(report), indent=2))
    if args.json:
        print_json(report)
    else:
        print(finite_contact_text(report))
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
        f"exponent {report['exponent_fem']:.6f} vs linear {report['exponent_analytic']:.6f}",
        f"  mesh: {mesh['nodes']} nodes, {mesh['elements']} P2 triangles, {mesh['dofs']} dofs, "
        f"{mesh['contact_candidates']} contact candidates",
        "  time (s): " + ", ".join(f"{k} {v:.3f}" for k, v in timings.items()),
    ]
    if "error_estimate" in report:
        rows += _estimate_text(report)
    return "\n".join(rows)


def _exponent_text(report: dict) -> str:
    if not math.isfinite(report["exponent_fem"]):
        return "exponent: fitted only from >= 2 depths"
    return (
        f"exponent {report['exponent_fem']:.6f} vs {report['exponent_analytic']:.6f} "
        f"({report['errors']['exponent']:.1e})"
    )


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
