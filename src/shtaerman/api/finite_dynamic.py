"""``shtaerman.dynamic(model=...)``: the impact on a rubber half-space at finite strain."""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any

from ..theory.contact import PowerLawContact
from ..theory.impact import solve_impact
from ..vocabulary import entry

if TYPE_CHECKING:
    from ..fem.finite_dynamic import FiniteImpactResult
    from ..problem import Problem

__all__ = ["FiniteDynamicResult", "finite_dynamic"]


@dataclass(frozen=True)
class FiniteDynamicResult:
    """The finite-strain impact: the keys of ``shtaerman dynamic --model ... --json`` (SI).

    ``dynamic`` holds the FE results (the linear dynamic impact's keys); ``quasi_static`` the
    paper's (Shtaerman's small-strain law, Ateb solution); ``differences`` quasi-static /
    dynamic - 1 of x (x_c against x_max), P (P_c against P_max) and t (t_c against
    t_contact / 2). ``solution`` is the FE run (histories), not part of :meth:`to_dict`.
    """

    model: str
    rubber: dict[str, Any]
    quasi_static: dict[str, float]
    dynamic: dict[str, float]
    differences: dict[str, float]
    mesh: dict[str, float]
    timings: dict[str, float]
    parameters: dict[str, float]
    solution: FiniteImpactResult = field(repr=False, compare=False)
    prony: str | None = None

    def __getattr__(self, name: str) -> Any:
        dynamic = self.__dict__.get("dynamic", {})
        if name in dynamic:
            return dynamic[name]
        raise AttributeError(name)

    def history(self) -> dict[str, Any]:
        """The histories t, x, v, P at every time step (arrays, SI units)."""
        return self.solution.history_columns()

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready (nan as None)."""

        def clean(values: dict[str, Any]) -> dict[str, Any]:
            return {
                key: None if isinstance(value, float) and not math.isfinite(value) else value
                for key, value in values.items()
            }

        return {
            "model": self.model,
            "rubber": dict(self.rubber),
            "quasi_static": clean(self.quasi_static),
            "dynamic": clean(self.dynamic),
            "differences": clean(self.differences),
            "mesh": dict(self.mesh),
            "timings": dict(self.timings),
            "parameters": clean(self.parameters),
            **({"prony": self.prony} if self.prony is not None else {}),
        }


def finite_dynamic(
    problem: Problem, *, time_steps: int | None = None, mesh_size: float | None = None
) -> FiniteDynamicResult:
    """The impact of a rigid striker on a rubber body at finite strain.

    Parameters
    ----------
    problem : Problem
        An impact on a rubber body (``problem.body.finite``): its density 0 gives the
        finite-strain quasi-static impact (massless body), in [1e-6, 1e6] kg/m^3 the body with
        inertia (waves); with a Prony series the isochoric stress relaxes
        (:mod:`shtaerman.fem.finite_viscoelastic`), E2 and nu2 being the instantaneous values.
    time_steps : int, optional
        Steps per quasi-static impact duration (default 50; 100 with inertia).
    mesh_size : float, optional
        Smallest element / refined radius (default the finite-strain contact's).

    Returns
    -------
    FiniteDynamicResult
    """
    from dataclasses import replace

    from ..fem.finite_contact import FINITE_MESH
    from ..fem.finite_dynamic import INERTIA_MESH, FiniteImpactSettings, run_finite_impact
    from .layer_options import layer_mesh

    indenter, body = problem.striker.indenter, problem.body.material
    mass, velocity = problem.striker.mass, problem.striker.velocity
    rho = body.density
    if mesh_size is not None:
        mesh_size = entry("mesh_size").check(mesh_size, "dynamic")
    default = FINITE_MESH if rho == 0 else INERTIA_MESH
    mesh = default if mesh_size is None else replace(default, size=mesh_size)
    settings = FiniteImpactSettings(steps=time_steps, mesh=layer_mesh(mesh, problem.geometry))
    rubber, series = problem.body.rubber(), problem.body.prony
    run = run_finite_impact(indenter, body, rho, mass, velocity, settings, rubber, series)
    law = PowerLawContact(indenter, body.youngs_modulus / (1.0 - body.poisson_ratio**2))
    quasi = solve_impact(mass, velocity, law)
    summary = run.summary()
    differences = {
        "x_c": quasi.x_c / summary["x_max"] - 1.0,
        "P_c": quasi.P_c / summary["P_max"] - 1.0,
        "t_c": quasi.t_c / (0.5 * summary["t_contact"]) - 1.0,
    }
    return FiniteDynamicResult(
        model=problem.body.model,
        rubber=rubber.to_dict(),
        quasi_static={key: quasi.maxima()[key] for key in ("x_c", "P_c", "t_c", "t_y")},
        dynamic=summary,
        differences=differences,
        mesh=run.mesh,
        timings=run.timings,
        parameters=run.parameters,
        solution=run,
        prony=None if series is None else _prony_text(series),
    )


def _prony_text(series: Any) -> str:
    """``g1:tau1,g2:tau2,...`` of a Prony series (tau in s)."""
    return ",".join(f"{g:g}:{tau:g}" for g, tau in zip(series.weights, series.times, strict=True))
