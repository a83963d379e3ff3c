"""Command-line interface: ``shtaerman impact | tables | contact | verify``.

Thin: each subcommand parses, calls the library, prints. Bad input gives one line on stderr
naming the parameter and its valid range, and exit code 2.
"""

from __future__ import annotations

import argparse
import json
import math
import re
import sys
import time
import warnings
from collections.abc import Callable, Sequence
from pathlib import Path

import numpy as np

from .. import __version__
from ..output.files import json_safe, write_csv
from ..paper.comparison import paper_tables, tables_text
from ..theory.contact import PowerLawContact
from ..theory.impact import ImpactResult, solve_impact
from ..theory.impact_ode import integrate_impact
from ..theory.indenter import PowerLawIndenter
from ..theory.materials import RIGID, Material, effective_modulus
from ..validation import InputError, validate_increasing, validate_poisson, validate_positive

EXIT_INPUT = 2


class _Parser(argparse.ArgumentParser):
    """argparse that reports a usage error as one line (no usage dump) with exit code 2.

    It also reads ``-2e11`` as a (negative) number, so the range check can name it, rather than
    as an unknown option.
    """

    def __init__(self, *args, **kwargs) -> None:
        super().__init__(*args, **kwargs)
        self._negative_number_matcher = re.compile(r"^-(\d+\.?\d*|\.\d+)([eE][-+]?\d+)?$")

    def error(self, message: str) -> None:  # type: ignore[override]
        raise InputError(message)


def _add_impact(sub: argparse._SubParsersAction) -> None:
    p = sub.add_parser("impact", help="exact quasi-static impact (the paper's example by default)")
    p.add_argument("--mass", default="0.7", help="striker mass M in kg (default 0.7)")
    p.add_argument("--velocity", default="3", help="approach velocity v0 in m/s (default 3)")
    _add_indenter_options(p)
    p.add_argument("--E1", default="2e11", help="striker Young's modulus in Pa, or 'inf' (rigid)")
    p.add_argument("--nu1", default="0.25", help="striker Poisson's ratio (default 0.25)")
    _add_half_space_options(p)
    p.add_argument("--json", action="store_true", help="print one JSON object (SI units)")
    p.add_argument("--history", metavar="FILE.csv", help="write t,x,P,a,p0 over [0, t_y]")
    p.add_argument("--points", default="201", help="rows of --history (>= 2, default 201)")
    p.add_argument(
        "--check", action="store_true", help="also integrate the ODE numerically and compare"
    )
    p.set_defaults(run=_run_impact)


def _add_indenter_options(p: argparse.ArgumentParser) -> None:
    p.add_argument("--shape-coefficient", default="5", help="A in z = A r^n, m^(1-n) (default 5)")
    p.add_argument("--exponent", default="1.5", help="n in z = A r^n (default 1.5)")


def _add_half_space_options(p: argparse.ArgumentParser) -> None:
    p.add_argument("--E2", default="7.5e6", help="half-space Young's modulus in Pa (default 7.5e6)")
    p.add_argument("--nu2", default="0.5", help="half-space Poisson's ratio (default 0.5)")


def _add_tables(sub: argparse._SubParsersAction) -> None:
    p = sub.add_parser("tables", help="the paper's Tables 1-6: printed, exact, difference")
    p.add_argument("--json", action="store_true", help="print one JSON object")
    p.set_defaults(run=_run_tables)


def _add_contact(sub: argparse._SubParsersAction) -> None:
    p = sub.add_parser("contact", help="FEM frictionless contact against Shtaerman's solution")
    _add_indenter_options(p)
    _add_half_space_options(p)
    p.add_argument(
        "--depths",
        help="depths in m, comma-separated, increasing (default: 8 up to "
        "the paper's impact x_c, contact radii a_c/3 .. a_c)",
    )
    p.add_argument("--json", action="store_true", help="print one JSON object (SI units)")
    p.add_argument("--out", metavar="DIR", help="write VTU fields and CSV curves to DIR")
    p.add_argument("--force", action="store_true", help="replace a non-empty --out folder")
    mesh = p.add_argument_group("mesh controls (relative to the largest contact)")
    mesh.add_argument("--mesh-size", default=None, help="smallest element / refined radius")
    mesh.add_argument("--mesh-margin", default=None, help="refined radius / geometric radius, > 1")
    mesh.add_argument("--domain-factor", default=None, help="domain radius / refined radius")
    mesh.add_argument("--growth", default=None, help="element size growth per unit distance")
    mesh.add_argument("--solver", default="auto", help="auto, superlu or pardiso")
    p.set_defaults(run=_run_contact)


def _add_verify(sub: argparse._SubParsersAction) -> None:
    p = sub.add_parser("verify", help="run cross-check studies: FEM -> impact -> report")
    p.add_argument(
        "studies",
        nargs="*",
        metavar="STUDY.toml",
        help="study files (default: every shipped study)",
    )
    p.add_argument(
        "--out",
        metavar="DIR",
        help="result folder (default: a new shtaerman-results-<time> folder)",
    )
    p.add_argument("--quick", action="store_true", help="coarse meshes (seconds; for CI)")
    p.add_argument("--force", action="store_true", help="replace an existing --out folder")
    p.set_defaults(run=_run_verify)


def build_parser() -> argparse.ArgumentParser:
    """The ``shtaerman`` argument parser with its subcommands."""
    parser = _Parser(prog="shtaerman", description=__doc__.splitlines()[0])
    parser.add_argument("--version", action="version", version=f"shtaerman {__version__}")
    sub = parser.add_subparsers(dest="command", required=True, parser_class=_Parser)
    _add_impact(sub)
    _add_tables(sub)
    _add_contact(sub)
    _add_verify(sub)
    return parser


def _striker(args: argparse.Namespace) -> Material:
    if str(args.E1).strip().lower() in {"inf", "rigid"}:
        return RIGID
    return Material(validate_positive("E1", args.E1, "Pa"), validate_poisson("nu1", args.nu1))


def _half_space(args: argparse.Namespace) -> Material:
    return Material(validate_positive("E2", args.E2, "Pa"), validate_poisson("nu2", args.nu2))


def _indenter(args: argparse.Namespace) -> PowerLawIndenter:
    return PowerLawIndenter(
        validate_positive("shape-coefficient", args.shape_coefficient, "m^(1-n)"),
        validate_positive("exponent", args.exponent),
    )


def _points(value: str) -> int:
    try:
        points = int(value)
    except ValueError:
        points = 0
    if points < 2:
        raise InputError(f"points must be an integer >= 2, got {value!r}")
    return points


def _history_path(value: str | None) -> Path | None:
    """The --history file, checked before any work: its folder must exist."""
    if value is None:
        return None
    path = Path(value).expanduser()
    if not path.parent.is_dir():
        raise InputError(f"history: folder {str(path.parent)!r} does not exist")
    return path


def _run_impact(args: argparse.Namespace) -> int:
    mass = validate_positive("mass", args.mass, "kg")
    velocity = validate_positive("velocity", args.velocity, "m/s")
    striker, half_space, indenter = _striker(args), _half_space(args), _indenter(args)
    points, history = _points(args.points), _history_path(args.history)
    law = PowerLawContact(indenter, effective_modulus(striker, half_space))
    result = solve_impact(mass, velocity, law)
    report = {**result.maxima(), "force_exponent": result.force_exponent, "modulus": law.modulus}
    if args.check:
        report["ode_check"] = _ode_check(result)
    if history is not None:
        write_csv(history, result.history(points).columns())
    print(json.dumps(json_safe(report), indent=2) if args.json else _impact_text(result, report))
    return 0


def _ode_check(result: ImpactResult) -> dict[str, float]:
    numerical = integrate_impact(result.mass, result.velocity, result.law.force, result.x_c)
    exact = result.history(2001)
    x, _ = numerical.sample(exact.t[:-1])
    return {
        "x_c": numerical.x_c,
        "t_c": numerical.t_c,
        "t_y": numerical.t_y,
        "rebound_velocity": numerical.rebound_velocity,
        "max_history_difference": float(np.max(np.abs(x - exact.x[:-1])) / result.x_c),
    }


def _impact_text(result: ImpactResult, report: dict) -> str:
    law = result.law
    n, A = law.indenter.exponent, law.indenter.shape_coefficient
    rows = [
        f"Quasi-static impact of z = {A:g} r^{n:g} on an elastic half-space (SI units)",
        f"  mass M                    {result.mass:>14.6g} kg",
        f"  approach velocity v0      {result.velocity:>14.6g} m/s",
        f"  combined modulus E*       {law.modulus:>14.6e} Pa",
        f"  force law P = beta x^q    q = {result.force_exponent:.6g}",
        f"  beta                      {result.beta:>14.6e} N/m^{result.force_exponent:.4g}",
        f"  max approach x_c          {result.x_c:>14.6e} m",
        f"  max force P_c             {result.P_c:>14.6e} N",
        f"  max contact radius a_c    {result.a_c:>14.6e} m",
        f"  max central pressure p_c  {result.p_c:>14.6e} Pa",
        f"  compression time t_c      {result.t_c:>14.6e} s",
        f"  impact duration t_y       {result.t_y:>14.6e} s",
        f"  impulse 2 M v0            {result.impulse:>14.6e} N s",
        f"  impulse, paper eq. (16)   {result.impulse_simpson:>14.6e} N s",
    ]
    if not math.isfinite(result.p_c):
        rows.append("  (n <= 1: the pressure at the centre of the contact is unbounded)")
    if "ode_check" in report:
        check = report["ode_check"]
        rows.append(
            f"  ODE cross-check: x_c {check['x_c'] / result.x_c - 1:+.1e}, "
            f"t_y {check['t_y'] / result.t_y - 1:+.1e}, "
            f"history max |dx|/x_c {check['max_history_difference']:.1e}"
        )
    return "\n".join(rows)


def _depths(text: str | None) -> np.ndarray | None:
    if text is None:
        return None
    return validate_increasing("depths", [item for item in text.split(",") if item.strip()], "m")


def _mesh_settings(args: argparse.Namespace):
    from ..fem.mesh import MeshSettings

    options = {
        "size": args.mesh_size,
        "margin": args.mesh_margin,
        "domain": args.domain_factor,
        "growth": args.growth,
    }
    names = {"size": "mesh-size", "margin": "mesh-margin", "domain": "domain-factor"}
    chosen = {
        key: validate_positive(names.get(key, key), value)
        for key, value in options.items()
        if value is not None
    }
    return MeshSettings(**chosen)


def _run_contact(args: argparse.Namespace) -> int:
    from ..output.export import write_indentation
    from ..output.files import check_output_folder, staged_folder
    from ..study.indentation import run_indentation

    indenter, half_space = _indenter(args), _half_space(args)
    depths, mesh = _depths(args.depths), _mesh_settings(args)
    out = check_output_folder(Path(args.out), force=args.force) if args.out else None
    result = run_indentation(indenter, half_space, depths, mesh, backend=args.solver)
    report = result.to_dict()
    if out is not None:
        with staged_folder(out) as stage:
            write_indentation(result, stage)
            (stage / "contact.json").write_text(json.dumps(json_safe(report), indent=2))
    print(json.dumps(json_safe(report), indent=2) if args.json else _contact_text(report))
    return 0


def _contact_text(report: dict) -> str:
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
        f"({errors['beta']:.1e});  exponent {report['exponent_fem']:.6f} vs "
        f"{report['exponent_analytic']:.6f} ({errors['exponent']:.1e})",
        f"  p0/pavg exact {report['central_to_mean_analytic']:.4f};  pressure profile L2 error "
        f"<= {errors['pressure_profile']:.1e}",
        f"  mesh: {mesh['nodes']} nodes, {mesh['elements']} P2 triangles, {mesh['dofs']} dofs, "
        f"{mesh['contact_candidates']} contact candidates; solver {report['solver']}",
        "  time (s): " + ", ".join(f"{k} {v:.3f}" for k, v in timings.items()),
    ]
    return "\n".join(rows)


def _default_out() -> Path:
    stamp = time.strftime("%Y%m%d-%H%M%S")
    path, counter = Path(f"shtaerman-results-{stamp}"), 1
    while path.exists():
        counter += 1
        path = Path(f"shtaerman-results-{stamp}-{counter}")
    return path


def _run_verify(args: argparse.Namespace) -> int:
    from ..output.files import check_output_folder
    from ..output.folder import run_verification
    from ..study.schema import load_study, shipped_studies

    paths = [Path(p) for p in args.studies] or shipped_studies()
    studies = [study for path in paths for study in load_study(path)]
    names = [study.name for study in studies]
    duplicates = sorted({name for name in names if names.count(name) > 1})
    if duplicates:
        raise InputError(f"studies: two studies are named {duplicates[0]!r}; rename one")
    out = check_output_folder(Path(args.out) if args.out else _default_out(), force=args.force)
    results = run_verification(studies, out, quick=args.quick)
    print(_verify_text(results, out))
    return 0 if results["passed"] else 1


def _verify_text(results: dict, out: Path) -> str:
    lines = [f"{'study':<24} verdict  worst contact error  worst impact difference"]
    for name, study in results["studies"].items():
        contact = max(c["value"] for c in study["checks"] if c["name"].startswith("contact"))
        impact = max(abs(c["value"]) for c in study["checks"] if c["name"].startswith("impact"))
        verdict = "PASS" if study["passed"] else "FAIL"
        lines.append(f"{name:<24} {verdict:<8} {contact:>19.1e}  {impact:>23.1e}")
    lines.append(f"results: {out / 'results.json'}  report: {out / 'report.html'}")
    return "\n".join(lines)


def _run_tables(args: argparse.Namespace) -> int:
    tables = paper_tables()
    if args.json:
        print(json.dumps(json_safe({"tables": [table.to_dict() for table in tables]}), indent=2))
    else:
        print(tables_text(tables))
    return 0


def _report_warnings(caught: list[warnings.WarningMessage]) -> None:
    for warning in caught:
        print(f"shtaerman: warning: {warning.message}", file=sys.stderr)


def main(argv: Sequence[str] | None = None) -> int:
    """Run the CLI; returns the exit code (0 success, 1 failed check, 2 bad input)."""
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        try:
            args = build_parser().parse_args(argv)
            run: Callable[[argparse.Namespace], int] = args.run
            code = run(args)
        except InputError as error:
            _report_warnings(caught)
            print(f"shtaerman: error: {error}", file=sys.stderr)
            return EXIT_INPUT
    _report_warnings([w for w in caught if not issubclass(w.category, DeprecationWarning)])
    return code


if __name__ == "__main__":
    sys.exit(main())
