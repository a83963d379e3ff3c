"""``shtaerman dynamic --model MODEL``: the impact on a rubber half-space at finite strain."""

from __future__ import annotations

import math

from ..output.case import interface_words
from .contact import exact_owner, layer_rows, profile_words

PAD = "the quasi-static column is the half-space's"
"""What a pad's text compares with."""


def profile_rows(report: dict) -> list[str]:
    """The striker's profile when it is not the power law (the quasi-static column is then
    Sneddon's, by quadrature); [] for the power law."""
    if report.get("profile", {"kind": "power-law"})["kind"] == "power-law":
        return []
    return [f"  striker: {profile_words(report)} (quasi-static: Sneddon's contact law)"]


def finite_dynamic_text(report: dict) -> str:
    """A readable summary (SI units); a quantity the run could not give is nan."""
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
    is missing ([] without the estimate); first what was retried, if anything."""
    retried = [f"  retried: {report['retried']}"] if report.get("retried") else []
    if report.get("mesh_ladder") is None:
        return retried
    levels = ", ".join(
        f"{lv['dofs']} dofs/{lv['steps']} steps" if lv["dofs"] is not None else "failed"
        for lv in report["mesh_ladder"]
    )
    if report.get("estimate_missing"):
        return [*retried, f"  no error estimate (ladder {levels}): {report['estimate_missing']}"]
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
