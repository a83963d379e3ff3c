"""``shtaerman dynamic``: the elastodynamic FE impact against the quasi-static theory."""

from __future__ import annotations

import argparse
import math
import warnings
from pathlib import Path

from ..api.dynamic_result import UNTRUSTED, check_failures
from ..api.fem_contact import RUBBER_OPTIONS
from ..api.fem_dynamic import SETTINGS_OPTIONS, dynamic
from ..fem.impact_limits import FINITE_MIN_STEPS as FINITE_STEPS
from ..fem.impact_limits import INERTIA_STEPS, MASSLESS_STEPS, MAX_SIZE, MIN_STEPS
from ..fem.mesh import FINITE_MESH
from ..output.files import staged_file, write_csv
from ..problem import worded
from ..theory.materials import Material
from ..validation import InputError
from . import common
from .contact import exact_owner, layer_rows, profile_words
from .impact import history_path

NOTES = {
    "history": "t, x, v, P at every time step (the linear body also a, p0)",
    "out": "dynamic.json, history.csv, energies.csv and the figures; the fields at the "
    "steps nearest 0.5, 1 and 1.5 t_c (field_*.vtu; the linear body also wave_field_*.png; "
    "a rubber with --prony none: its relaxed stress is not recovered)",
    "force": "an existing --history file or --out folder",
}
"""What ``dynamic`` does with its output options."""
DERIVED = {
    "thickness": "none: the half-space",
    "base": "bonded; only with --thickness",
    "layer_rate": "10 on a layer, 0 (none) on the half-space",
}
"""Inputs whose default follows from the others, and that default in words."""
MODEL_NOTES = {
    "model": "a rubber model: the finite-strain impact (--density2 0: massless body, the "
    "finite-strain quasi-static impact; > 0: with inertia and waves)"
}


def register(commands: argparse._SubParsersAction) -> None:
    """Add the ``dynamic`` subcommand."""
    p = commands.add_parser(
        "dynamic",
        help="elastodynamic FE impact (waves included) against the quasi-static theory",
        description=(
            "Rigid striker z = A r^n (or an exact sphere, --sphere-radius, or a tabulated z(r), "
            "--profile) (mass M, velocity v0) on an elastic half-space with "
            "inertia: axisymmetric Taylor-Hood P2-P1 FEM, generalized-alpha time stepping, "
            "exact unilateral contact every step. Reports the rebound, the energy carried "
            "away by elastic waves and the first-order estimate of it; with --prony the "
            "half-space is viscoelastic and the loss is split into waves and hysteresis; "
            "--density2 0 takes the waves out. SI units. Exit code 1 "
            "(with a warning) when the energy balance is off by more than 1e-2 of M v0^2/2, or "
            "the far boundary reflects more than 1e-2 of the radiated energy. --thickness H: "
            "a layer on a rigid base (bonded or lubricated) whose base reflects the waves, with "
            "a lateral absorber; its reflected energy is what comes back near the contact "
            "after separation, of M v0^2/2."
        ),
    )
    inputs = (*common.CASE, *common.PROFILES, "E2", "nu2", "density2", "prony", "thickness", "base")
    inputs = (*inputs, "interface", "friction")
    inputs = (*inputs, "json", "history", "out", "force")
    common.add_inputs(p, inputs, "dynamic", derived=DERIVED, notes=NOTES)
    common.add_inputs(p, ("model", *RUBBER_OPTIONS), "dynamic", notes=MODEL_NOTES)
    common.add_figure_format(p)
    accuracy = p.add_argument_group(
        "accuracy (error estimates of x_max, P_max, t_contact, e from a 3-level ladder: "
        "K/2, K/sqrt(2), K)"
    )
    common.add_inputs(
        accuracy, ("refine", "estimate"), "dynamic", notes={"refine": "the time step too"}
    )
    numerics = p.add_argument_group(
        "expert numerical controls (relative to the quasi-static impact; --refine scales the "
        "mesh sizes and steps together)"
    )
    finite = {
        "time_steps": f"the estimate's coarsest level halves them, so with it at least "
        f"{2 * MIN_STEPS} (a level needs {MIN_STEPS}); with --model the default is "
        f"{INERTIA_STEPS} ({MASSLESS_STEPS} with --density2 0) and a level needs {FINITE_STEPS}",
        "mesh_size": "it sizes the surface elements of the refined zone (radius --mesh-margin x "
        "a_c: 12.5 mm in the paper's example, 0.31 mm elements at 0.025); the axis grading and "
        "the far field's growth set most of the mesh (0.025 to 0.2 change its dofs by under "
        "10 %): --refine refines all of it; the linear estimate's coarsest level doubles it, so "
        f"with it at most {MAX_SIZE / 2:g}; with --model the default is "
        f"1/{1 / FINITE_MESH.size:.0f}",
    }
    aliases = {"time_steps": ("--steps",)}
    common.add_inputs(
        numerics, tuple(SETTINGS_OPTIONS), "dynamic", derived=DERIVED, aliases=aliases, notes=finite
    )
    p.set_defaults(handler=run)


PHYSICS = ("model", *RUBBER_OPTIONS, "prony", "thickness", "base", "interface", "friction")
"""The problem's parts besides the striker and the body's elasticity (``effects`` passes them
when given; :func:`.common.impact_problem` every part the command takes)."""


def _numerics(args: argparse.Namespace) -> dict[str, object]:
    """The numerical and output keywords of :func:`shtaerman.dynamic`: the numerics given (the
    others None: the model's own defaults, and the layer's rate where it has one; one the
    problem does not take, :func:`shtaerman.dynamic` refuses)."""
    chosen = {n: getattr(args, n) if common.given(args, n) else None for n in SETTINGS_OPTIONS}
    outputs = common.keywords(args, ("refine", "estimate", "out", "force", "figure_format"))
    return {**chosen, **outputs}


def run(args: argparse.Namespace) -> int:
    """Run the dynamic impact (:func:`shtaerman.dynamic`); print text or JSON; write the
    history and folder if asked."""
    from ..guards import FailedCheckWarning  # here, not at load: the guards load scipy

    with common.in_option_words():
        problem = common.impact_problem(args, Material(args.E2, args.nu2, args.density2))
    common.refuse_idle_output_options(args, ("out", "history"))
    history = history_path(args.history, force=args.force)
    _refuse_history_in_out(history, args.out)
    with common.in_option_words(), warnings.catch_warnings():
        warnings.simplefilter("ignore", FailedCheckWarning)  # said below, with the exit code
        result = dynamic(problem, **_numerics(args))
    common.warn_volumetric(args)  # after the run: a refused input is the one line
    report = result.to_dict()
    if history is not None:
        with staged_file(history, force=args.force) as stage:
            write_csv(stage, result.history())
    if args.json:
        common.print_json(report)
    else:
        print(finite_dynamic_text(report) if problem.body.finite else dynamic_text(report))
    failures = check_failures(result, problem)
    if failures:
        common.warn(worded("; ".join(failures), "cli") + UNTRUSTED)
        return 1
    return 0


def _refuse_history_in_out(history: Path | None, out: str | None) -> None:
    """Refuse a --history file inside the --out folder: the folder holds history.csv already,
    and a file it did not list would block every later --out --force onto it."""
    if history is None or out is None:
        return
    folder = Path(out).resolve()
    if folder in history.resolve().parents:
        raise InputError(
            f"--history: {str(history)!r} is inside the --out folder {out!r}, which holds "
            "history.csv already; give a file outside it, or leave --history out",
            "history",
        )


def _loss_label(dyn: dict, massless: bool) -> str:
    """The 1 - e^2 row's name: all of it is waves in an elastic body with inertia, not in a
    viscoelastic or massless one."""
    lost = massless or not math.isnan(dyn["energy_dissipated_fraction"])
    return "energy lost 1-e^2       " if lost else "energy to waves 1-e^2   "


def _reflected(fraction: float, of: str) -> str:
    """The reflected energy ``fraction`` of ``of`` as printed; n/a where nothing radiated
    (0/0: a striker far slower than the waves, as --json's null says)."""
    return f"{fraction:.1e} of {of}" if fraction == fraction else "n/a (nothing radiated)"


def _unsigned_zero(value: float) -> float:
    """``value`` to 6 decimals with no sign on a zero: round-off (a massless run's 1 - e^2 is
    -1e-13) prints 0.000000, not -0.000000."""
    return round(value, 6) + 0.0


def _losses_text(dyn: dict, massless: bool) -> list[str]:
    """A viscoelastic run's 1 - e^2 split into waves and hysteresis, all hysteresis in a
    massless body (no waves); [] for an elastic one."""
    if math.isnan(dyn["energy_dissipated_fraction"]):
        return []
    waves = f"    of which waves        {_unsigned_zero(dyn['energy_wave_fraction']):<14.6f}  "
    return [
        *([] if massless else [waves + "(beyond R_a, absorbed)"]),
        f"    {'all of it' if massless else 'of which'} hysteresis   "
        f"{_unsigned_zero(dyn['energy_hysteresis_fraction']):<14.6f}  "
        f"(dissipated {_unsigned_zero(dyn['energy_dissipated_fraction']):.6f}, the rest to be "
        "dissipated near the contact)",
    ]


def _estimate(estimate: dict, mesh: dict, key: str) -> str:
    """The first-order half-space estimate of ``key`` beside the FE value, in words; on a pad
    it does not apply (the base reflects what the half-space radiates), and says so once;
    a massless body has none (no waves)."""
    if not estimate and "thickness" not in mesh:
        return ""
    if "thickness" in mesh:
        return " (the half-space estimate does not apply to a pad)" if key == "restitution" else ""
    words = "first-order estimate" + (" of the waves" if key == "energy_fraction" else "")
    return f" ({words} {estimate[key]:.6f})"


def dynamic_text(report: dict) -> str:
    """A readable summary (SI units); a quantity the run could not give (JSON null) is nan."""
    from ..output.text_dynamic import differences_text, viscoelastic_rows
    from ..study.dynamic.loader import reflection_reference

    qs, dyn, est = (
        {key: math.nan if value is None else value for key, value in (report[part] or {}).items()}
        for part in ("quasi_static", "dynamic", "radiation_estimate")
    )
    mesh, timings = report["mesh"], report["timings"]
    of = reflection_reference("thickness" in mesh, report.get("rubber") is not None)
    massless = report["parameters"]["density2"] == 0
    rows = [
        "Dynamic FE impact against the quasi-static theory (rigid striker, SI units)",
        *profile_rows(report),
        *layer_rows(report, PAD),
        *interface_rows(report["parameters"]),
        "                          dynamic FEM     quasi-static"
        + (" elastic (the paper's)" if report.get("viscoelastic_quasi_static") else ""),
        f"  max approach x (m)      {dyn['x_max']:<14.6e}  {qs['x_c']:.6e}",
        f"  max force P (N)         {dyn['P_max']:<14.6e}  {qs['P_c']:.6e}",
        f"  time of max x (s)       {dyn['t_x_max']:<14.6e}  {qs['t_c']:.6e}",
        f"  contact duration (s)    {dyn['t_contact']:<14.6e}  {qs['t_y']:.6e}",
        f"  restitution e           {dyn['restitution']:<14.6f}  "
        f"1{_estimate(est, mesh, 'restitution')}",
        f"  {_loss_label(dyn, massless)}{_unsigned_zero(dyn['energy_radiated_fraction']):<14.6f}  "
        f"0{_estimate(est, mesh, 'energy_fraction')}",
        *_losses_text(dyn, massless),
        differences_text(report),
        *viscoelastic_rows(report),
        f"  energy balance error    {dyn['energy_balance_error']:.1e} of M v0^2/2"
        + ("" if massless else f";  reflected {_reflected(dyn['reflected_energy_fraction'], of)}"),
        f"  mesh: {mesh['nodes']} nodes, {mesh['elements']} P2 triangles, {mesh['dofs']} dofs, "
        f"{mesh['contact_candidates']} contact candidates",
        "  time (s): " + ", ".join(f"{k} {v:.2f}" for k, v in timings.items()),
    ]
    return "\n".join(rows + ladder_rows(report))


PAD = "the quasi-static column is the half-space's"
"""What a pad's text compares with."""


def profile_rows(report: dict) -> list[str]:
    """The striker's profile when it is not the power law (the quasi-static column is then
    Sneddon's, by quadrature); [] for the power law."""
    if report.get("profile", {"kind": "power-law"})["kind"] == "power-law":
        return []
    return [f"  striker: {profile_words(report)} (quasi-static: Sneddon's contact law)"]


def finite_dynamic_text(report: dict) -> str:
    """The finite-strain impact's summary (``--model``, SI units); a quantity the run could not
    give is nan."""
    from ..output.text_dynamic import viscoelastic_rows

    qs, dyn = (
        {key: math.nan if value is None else value for key, value in report[part].items()}
        for part in ("quasi_static", "dynamic")
    )
    mesh = report["mesh"]
    rows = [
        f"Finite-strain impact ({report['model']}, density2 "
        f"{report['parameters']['density2']:g} kg/m^3) against the quasi-static theory (SI)",
        *profile_rows(report),
        *layer_rows(report, PAD),
        f"                          finite strain   quasi-static ({exact_owner(report)})",
        f"  max approach x (m)      {dyn['x_max']:<14.6e}  {qs['x_c']:.6e}",
        f"  max force P (N)         {dyn['P_max']:<14.6e}  {qs['P_c']:.6e}",
        f"  time of max x (s)       {dyn['t_x_max']:<14.6e}  {qs['t_c']:.6e}",
        f"  contact duration (s)    {dyn['t_contact']:<14.6e}  {qs['t_y']:.6e}",
        f"  restitution e           {dyn['restitution']:<14.6f}  1",
        *interface_rows(report["parameters"]),
        *prony_rows(report),
        *viscoelastic_rows(report, "finite strain"),
        f"  energy balance error    {dyn['energy_balance_error']:.1e} of M v0^2/2",
        f"  mesh: {mesh['nodes']} nodes, {mesh['elements']} P2 triangles, {mesh['dofs']} dofs",
        "  time (s): "
        + ", ".join(f"{k} {v:.2f}" for k, v in report["timings"].items() if v is not None),
    ]
    return "\n".join(rows + ladder_rows(report))


def ladder_rows(report: dict) -> list[str]:
    """The error-estimate ladder's levels and estimated relative errors, or why the estimate
    is missing ([] without the estimate); first what was retried, if anything. Both are
    the API's words, spelled here as options (``time_steps=...`` is ``--time-steps``)."""
    retried = [f"  retried: {worded(report['retried'], 'cli')}"] if report.get("retried") else []
    if report.get("mesh_ladder") is None:
        return retried
    levels = ", ".join(
        f"{lv['dofs']} dofs/{lv['steps']} steps" if lv["dofs"] is not None else "failed"
        for lv in report["mesh_ladder"]
    )
    if report.get("estimate_missing"):
        missing = worded(report["estimate_missing"], "cli")
        return [*retried, f"  no error estimate (ladder {levels}): {missing}"]
    errors = report["error_estimate"].items()
    return [
        *retried,
        f"  estimated relative errors (ladder {levels}): "
        + ", ".join(
            f"{key} {'n/a' if value is None else format(value, '.1e')}" for key, value in errors
        ),
    ]


def interface_rows(parameters: dict) -> list[str]:
    """The line naming a bonded or Coulomb indenter (none when frictionless)."""
    from ..output.case import interface_words  # here, not at load: it loads the theory

    if "interface" not in parameters:
        return []
    return [f"  {interface_words(parameters['interface'], parameters.get('friction'))}"]


def prony_rows(report: dict) -> list[str]:
    """The Prony series and the energy dissipated by it and by friction (none for an elastic
    body on a frictionless indenter)."""
    rows = []
    if report.get("prony") is not None:
        rows.append(f"  Prony series g:tau      {report['prony']} (isochoric stress relaxes)")
    share = report["dynamic"].get("energy_dissipated_fraction")
    if share is not None:
        rows.append(
            f"  energy dissipated       {share:.6f} of M v0^2/2 by separation "
            f"(1 - e^2 = {report['dynamic']['energy_radiated_fraction']:.6f})"
        )
    return rows
