"""``shtaerman contact``: the FEM frictionless contact against Shtaerman's exact solution."""

from __future__ import annotations

import argparse
import math
from inspect import signature

from ..api.fem_contact import MESH_OPTIONS, RUBBER_OPTIONS, contact
from ..fem.mesh import DEFAULTS, FINITE_MESH
from ..plots.labels import model_label
from ..problem import worded
from ..theory.materials import Material
from ..vocabulary import entry, fields
from . import common


def register(commands: argparse._SubParsersAction) -> None:
    """Add the ``contact`` subcommand."""
    p = commands.add_parser(
        "contact",
        help="FEM frictionless contact against Shtaerman's solution",
        description=(
            "Press a rigid indenter z = A r^n (or an exact sphere, --sphere-radius, or a "
            "tabulated z(r), --profile) into the FEM half-space (gmsh + scikit-fem, "
            "Taylor-Hood P2-P1) and compare force, contact radius and central pressure with "
            "the exact solution (Shtaerman's, or Sneddon's). The default depths reach the x_c "
            "of the impact of --mass at --velocity. --model neo-hookean (mooney-rivlin, yeoh, "
            "gent): a rubber at finite strain with the same E2, nu2 at small strain. --out "
            "writes contact.json, CSV curves, VTU fields and the figures. SI units."
        ),
    )
    inputs = ("shape_coefficient", "exponent", *common.PROFILES, "E2", "nu2", "thickness", "base")
    inputs = (*inputs, "interface")
    inputs = (*inputs, "friction", "model", *RUBBER_OPTIONS, "prony", "rate", "mass", "velocity")
    outputs = ("depths", "json", "out", "force")
    common.add_inputs(p, (*inputs, *outputs), "contact", derived=DERIVED, notes=NOTES)
    common.add_figure_format(p)
    accuracy = p.add_argument_group(
        "accuracy (every FEM number with an error estimate from a 3-mesh ladder: K/2, K/sqrt(2), K)"
    )
    common.add_inputs(accuracy, ("refine", "estimate", "accuracy", "max_time"), "contact")
    mesh = p.add_argument_group(
        "expert mesh controls (relative to the largest contact; --mesh-size alone does not "
        "refine the far field, the axis grading or the growth: use --refine)"
    )
    common.add_inputs(mesh, (*MESH_OPTIONS, "solver"), "contact", derived=DERIVED)
    p.set_defaults(handler=run)


def _mesh_default(field: str) -> str:
    linear, finite = getattr(DEFAULTS, field), getattr(FINITE_MESH, field)
    return f"{linear:.6g}" if linear == finite else f"{linear:.6g} linear, {finite:.6g} neo-hookean"


DERIVED = {
    **{name: f"{entry(name).default:g}; not with --depths" for name in ("mass", "velocity")},
    "depths": "8 up to the x_c of the impact of --mass at --velocity, contact radii a_c/3 .. a_c",
    "thickness": "none: the half-space",
    "base": "bonded; only with --thickness",
    "mooney_ratio": "0; only with --model mooney-rivlin",
    "yeoh": "0,0; only with --model yeoh",
    "gent_limit": "none: required with --model gent",
    "volumetric": "quadratic; finite-strain models only (no effect at nu2 = 0.5)",
    "friction": "none: no slip; only with --interface bonded",
    "rate": "none: required with --prony, only with it",
    **{option: _mesh_default(field) for option, field in fields(MESH_OPTIONS).items()},
}
"""Inputs whose default follows from the others, and that default in words."""
NOTES = {
    "mass": "with --velocity, sets the impact whose x_c the default depths reach",
    "velocity": "with --mass, sets the impact whose x_c the default depths reach",
    "out": "contact.json, CSV curves, VTU fields, force_depth.png and (linear model) pressure.png",
    "force": "an existing --out folder",
}
"""What ``contact`` does with its output options."""


def run(args: argparse.Namespace) -> int:
    """Run the contact curve (:func:`shtaerman.contact`) and print it (text or JSON)."""
    common.refuse_idle_output_options(args, ("out",))
    options = common.keywords(args, set(vars(args)) & set(signature(contact).parameters))
    if not common.given(args, "max_time"):  # the API's default: the budget of accuracy, if given
        options["max_time"] = None
    with common.in_option_words():
        result = contact(common.indenter(args), Material(args.E2, args.nu2), **options)
    common.warn_volumetric(args)  # after the run: a refused input is the one line
    report = result.to_dict()
    if args.json:
        common.print_json(report)
    elif result.finite:
        print(finite_contact_text(report))
    else:
        print(contact_text(report))
    return 0


def exact_owner(report: dict) -> str:
    """Whose exact solution the curve is compared with: Shtaerman's or Sneddon's."""
    kind = report.get("profile", {"kind": "power-law"})["kind"]
    return "Shtaerman" if kind == "power-law" else "Sneddon"


def profile_words(report: dict) -> str:
    """The striker's profile of a contact report in words."""
    profile = report.get("profile", {"kind": "power-law"})
    if profile["kind"] == "sphere":
        return f"an exact sphere of radius {profile['parameters']['radius']:g} m"
    if profile["kind"] == "tabulated":
        return f"the tabulated profile {profile['parameters']['file']}"
    return f"z = {report['shape_coefficient']:g} r^{report['exponent']:g}"


def finite_contact_text(report: dict) -> str:
    """The finite-strain contact curve beside the linear exact values (SI units)."""
    rows = [
        f"{_model_words(report)} contact of {profile_words(report)} "
        f"on E2 = {report['E2']:g} Pa, nu2 = {report['nu2']:g} (finite strain; 'lin' = "
        f"{exact_owner(report)}'s linear solution)" + _impact_words(report),
        *layer_rows(report, "/lin = against the linear half-space, not the layer"),
        *_interface_rows(report, "/lin = against the frictionless linear solution"),
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
    rows.append(
        f"  beta (q fixed) {report['beta_fem']:.6e} vs linear {report['beta_analytic']:.6e};  "
        f"{_exponent_text(report, 'linear')}"
    )
    return _closing(report, rows, "")


def _closing(report: dict, rows: list[str], solver: str) -> str:
    """``rows`` and the mesh, timing and estimate rows of a contact report, as one text."""
    mesh = report["mesh"]
    rows += [
        f"  mesh: {mesh['nodes']} nodes, {mesh['elements']} P2 triangles, {mesh['dofs']} dofs, "
        f"{mesh['contact_candidates']} contact candidates{solver}",
        "  time (s): " + ", ".join(f"{k} {v:.3f}" for k, v in report["timings"].items()),
    ]
    return "\n".join(rows + (_estimate_text(report) if "error_estimate" in report else []))


def _interface_rows(report: dict, compared: str) -> list[str]:
    """The row naming a bonded indenter and what the columns are ``compared`` with; none when
    frictionless."""
    mesh = report["mesh"]
    if "interface" not in mesh:
        return []
    slip = (
        f"Coulomb friction {mesh['friction']:g}"
        if "friction" in mesh
        else "no slip once in contact"
    )
    return [f"  {mesh['interface']} indenter ({slip}): {compared}"]


def _model_words(report: dict) -> str:
    """ "Neo-Hookean", "Mooney-Rivlin (r = 0.3)", ... with the volumetric energy if not the
    default."""
    model, label = report["model"], model_label(report["model"])
    words = label[0].upper() + label[1:]  # the title's first word: "Neo-Hookean"
    shape = {
        "mooney-rivlin": lambda: f"r = {report['mooney_ratio']:g}",
        "yeoh": lambda: "c2, c3 = {:g}, {:g}".format(*report["yeoh"]),
        "gent": lambda: f"Jm = {report['gent_limit']:g}",
    }
    details = [shape[model]()] if model in shape else []
    compressible = report.get("nu2", 0.0) < 0.5  # no volumetric energy at nu2 = 0.5
    if compressible and report.get("volumetric", "quadratic") != "quadratic":
        details.append(f"{report['volumetric']} volumetric energy")
    return words + (f" ({', '.join(details)})" if details else "")


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


def _ratio_text(ratio: float | None) -> str:
    """p0/pavg of the exact solution: null (depth dependent) for another profile."""
    return "depends on depth" if ratio is None else f"{ratio:.4f}"


def contact_text(report: dict) -> str:
    """The contact curve as a readable table (SI units)."""
    head = (
        f"FEM contact of {profile_words(report)} on "
        f"E2 = {report['E2']:g} Pa, nu2 = {report['nu2']:g} (E* = {report['modulus']:.6g} Pa)"
    )
    rows = [head + _impact_words(report)]
    if "prony" in report:
        rows.append(
            f"  viscoelastic (Prony {report['prony']}) pressed at {report['rate']:g} m/s: "
            "rel.err against Lee-Radok (exact at nu2 = 0.5); forces are nodal sums; beta "
            "holds the elastic q (beta / beta0 = the mean force ratio), the exponent is free"
        )
    rows += layer_rows(report, "rel.err = departure from the half-space")
    rows += _interface_rows(report, "rel.err = departure from the frictionless solution")
    rows.append(
        "  depth (m)    force (N)   rel.err   radius (m)  rel.err   p(0) (Pa)   rel.err  p0/pavg"
    )
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
    errors = report["errors"]
    against, error = _reference_words(report)
    rows += [
        f"  beta (q fixed) {report['beta_fem']:.6e} vs {against} {report['beta_analytic']:.6e} "
        f"({errors['beta']:.1e});  {_exponent_text(report, '' if against == 'exact' else against)}",
        f"  p0/pavg {against} {_ratio_text(report['central_to_mean_analytic'])};  pressure "
        f"profile L2 {error} <= {errors['pressure_profile']:.1e}",
    ]
    return _closing(report, rows, f"; solver {report['solver']}")


def layer_rows(report: dict, compared: str) -> list[str]:
    """The row naming the layer and what the columns are ``compared`` with; none without one."""
    mesh = report["mesh"]
    if "thickness" not in mesh:
        return []
    return [f"  layer H = {mesh['thickness']:g} m on a {mesh['base']} rigid base: {compared}"]


def _reference_words(report: dict) -> tuple[str, str]:
    """What the analytic columns are and what their difference is called: Shtaerman's exact
    solution and an error, or, on a layer or under a bonded indenter, the half-space's or the
    frictionless solution and a departure from it."""
    if "thickness" in report["mesh"]:
        return "half-space", "departure from the half-space"
    if "interface" in report["mesh"]:
        return "frictionless", "departure from the frictionless solution"
    return "exact", "error"


def _impact_words(report: dict) -> str:
    """ "; depths up to the x_c of M = 0.25 kg at 2 m/s" when the impact set the depths."""
    if report.get("mass") is None:
        return ""
    return f"; depths up to the x_c of M = {report['mass']:g} kg at {report['velocity']:g} m/s"


def _estimate_text(report: dict) -> list[str]:
    ladder = report["mesh_ladder"]
    if report.get("estimate_missing"):  # a level failed: the finest that passed is reported
        dofs = ", ".join("failed" if lv["dofs"] is None else str(lv["dofs"]) for lv in ladder)
        return [f"  no error estimate (ladder {dofs}): {worded(report['estimate_missing'], 'cli')}"]
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
    depths = ", ".join(f"{k} {v:.4e}" for k, v in report.get("extrapolated_depth", {}).items())
    lines += [f"    at the worst depth (m): {depths}"] if depths else []
    target = report.get("accuracy_target")
    if report.get("accuracy_unreached"):  # a level beyond the first three failed
        lines.append(f"  {worded(report['accuracy_unreached'], 'cli')}")
    elif target is not None:
        reached = max(estimate[key] for key in ("force", "beta") if key in estimate)
        lines.append(f"  accuracy target {target:g}: met (force and beta estimate {reached:.1e})")
    return lines
