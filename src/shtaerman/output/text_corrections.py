"""The text of a finite-strain study's ``corrections`` entry: whether the wave and finite-strain
corrections add (:mod:`shtaerman.study.finite.corrections`)."""

from __future__ import annotations

from collections.abc import Mapping
from typing import Any

__all__ = ["QUICK_WORDS", "corrections_finding", "corrections_table"]

LABELS = {"x_max": "x_max / x_c", "P_max": "P_max / P_c", "t_contact": "t_contact / t_y"}
"""A quantity's row label: the impact's number against the paper's quasi-static one."""
QUICK_WORDS = (
    " (quick: coarse meshes and time steps; P_max with inertia is off by a few tenths of a "
    "point there, as much as the departure: run the study without --quick for the answer)."
)
"""The quick run's caveat, ending the finding."""


def corrections_table(data: Mapping[str, Any], model: str) -> dict[str, object]:
    """Per velocity, the shifts (%) of each column, nonlinear - sum (percentage points), and
    the restitution e; ``model`` is the rubber model's label."""
    rows = []
    for row in data["rows"]:
        shifts, e, departure = row["shifts"], row["restitution"], row["departure"]
        v0 = f"{row['velocity']:g} m/s"
        for key, label in LABELS.items():
            cells = [f"{100 * shifts[column][key]:+.2f} %" for column in shifts]
            rows.append([v0, f"{label} - 1", *cells, f"{departure[key]:+.2f} pp"])
        cells = [f"{e[column]:.4f}" for column in shifts]
        rows.append([v0, "e", *cells, f"{departure['restitution']:+.4f}"])
    quick = " (quick: coarse meshes and time steps)" if data.get("quick") else ""
    return {
        "title": "Do the corrections add? Against the paper's quasi-static x_c, P_c, t_y: the "
        "linear dynamic impact (waves), the massless finite-strain impact, their sum as "
        f"independent corrections and the nonlinear dynamic impact ({model} rubber with "
        f"density2 = {data['density2']:g} kg/m^3: both at once){quick}",
        "header": [
            "v0",
            "quantity",
            "linear dynamic",
            "finite-strain quasi-static",
            "sum of the two",
            "nonlinear dynamic",
            "nonlinear - sum",
        ],
        "rows": rows,
    }


def corrections_finding(data: Mapping[str, Any], model: str) -> str:
    """One sentence: how far the nonlinear dynamic impact departs from the sum of the two
    corrections (P_max at each velocity, the largest on x_max and t_contact) and which way."""
    rows = data["rows"]
    at = ", ".join(
        f"{r['departure']['P_max']:+.2f} pp at {r['velocity']:g} m/s "
        f"(nonlinear {100 * r['shifts']['nonlinear']['P_max']:+.2f} % against the sum "
        f"{100 * r['shifts']['sum']['P_max']:+.2f} %)"
        for r in rows
    )
    worst = {k: max(abs(r["departure"][k]) for r in rows) for k in ("x_max", "t_contact")}
    last = rows[-1]
    way = (
        "less"
        if abs(last["shifts"]["nonlinear"]["P_max"]) < abs(last["shifts"]["sum"]["P_max"])
        else "more"
    )
    return (
        f"Do the corrections add? The nonlinear dynamic impact ({model} rubber with inertia, "
        f"density2 = {data['density2']:g} kg/m^3) departs from the sum of the linear dynamic "
        f"and the finite-strain quasi-static corrections on P_max by {at}: at "
        f"{last['velocity']:g} m/s the combined impact moves P_max {way} than the sum says; "
        f"at most {worst['x_max']:.2f} pp on x_max and {worst['t_contact']:.2f} pp on "
        f"t_contact; restitution e = {last['restitution']['nonlinear']:.4f} against the "
        f"linear dynamic {last['restitution']['linear_dynamic']:.4f} at "
        f"{last['velocity']:g} m/s" + (QUICK_WORDS if data.get("quick") else ".")
    )
