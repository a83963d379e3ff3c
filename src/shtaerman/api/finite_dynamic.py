"""``shtaerman.dynamic(model=...)``: the impact on a rubber half-space at finite strain."""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any

from ..theory.contact import PowerLawContact
from ..theory.impact import solve_impact
from ..theory.indenter import PowerLawIndenter
from ..theory.materials import Material
from ..validation import InputError
from ..vocabulary import entry
from .quasi_static import check_bodies

if TYPE_CHECKING:
    from ..fem.finite_dynamic import FiniteImpactResult

__all__ = ["FiniteDynamicResult", "finite_dynamic", "finite_strain_route"]


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


def check_unsupported(model: str, given: dict[str, Any]) -> None:
    """Refuse, in one line naming it, an option the finite-strain impact does not take."""
    for name, value in given.items():
        if value is not None and value is not False:
            raise InputError(
                f"{name}: not supported with model {model!r} (the finite-strain impact takes "
                f"mass, velocity, density2, time_steps, mesh_size, thickness, base (bonded), "
                "prony and the rubber options)",
                name,
            )


def finite_strain_route(
    indenter: PowerLawIndenter,
    body: Material,
    model: str,
    unsupported: dict[str, Any],
    kept: dict[str, Any],
    rubber: dict[str, Any],
) -> FiniteDynamicResult:
    """:func:`finite_dynamic` from ``shtaerman.dynamic``'s keywords, refusing in one line
    the linear impact's options it does not take (``unsupported``, None or False when not
    given) and the rubber options with the linear model. ``rubber`` may also give
    ``density`` (kg/m^3, 0: massless body) in place of the body's."""
    allowed = ("mooney_ratio", "yeoh", "gent_limit", "volumetric", "density", "prony")
    unknown = sorted(set(rubber) - set(allowed))
    if unknown:
        raise TypeError(f"dynamic() got unexpected keyword arguments {unknown}")
    if model == "linear":
        name = next(iter(rubber))
        where = " (the linear model takes the body's density)" if name == "density" else ""
        raise InputError(f"{name}: applies to the finite-strain models only{where}", name)
    check_unsupported(model, unsupported)
    for name in ("mesh_size",):  # the range the command line states
        if kept.get(name) is not None:
            kept = {**kept, name: entry(name).check(kept[name], "dynamic")}
    return finite_dynamic(indenter, body, model=model, **kept, **rubber)


def finite_dynamic(
    indenter: PowerLawIndenter,
    body: Material,
    *,
    mass: float,
    velocity: float,
    model: str = "neo-hookean",
    density: float | None = None,
    time_steps: int | None = None,
    mesh_size: float | None = None,
    thickness: float | None = None,
    base: str | None = None,
    mooney_ratio: float | None = None,
    yeoh: Any = None,
    gent_limit: float | None = None,
    volumetric: str | None = None,
    prony: Any = None,
) -> FiniteDynamicResult:
    """The impact of a rigid striker z = A r^n on a rubber half-space at finite strain.

    Parameters
    ----------
    indenter : PowerLawIndenter
        n > 1.
    body : Material
        Small-strain E2 (Pa), nu2 in [0, 0.5]; its density unless ``density`` is given.
    mass, velocity : float
        Striker mass (kg) and impact velocity (m/s).
    model : str
        ``neo-hookean``, ``mooney-rivlin``, ``yeoh`` or ``gent`` (:mod:`shtaerman.fem.rubber`).
    density : float, optional
        Half-space density in kg/m^3; 0: massless body (the finite-strain quasi-static
        impact); in [1e-6, 1e6]: the body with inertia (waves).
    time_steps : int, optional
        Steps per quasi-static impact duration (default 50; 100 with inertia).
    mesh_size : float, optional
        Smallest element / refined radius (default the finite-strain contact's).
    thickness : float, optional
        A rubber layer of this thickness (m) on a rigid base instead of the half-space.
    base : str, optional
        The layer's base: ``bonded`` only at finite strain (the default with ``thickness``).
    mooney_ratio, yeoh, gent_limit, volumetric
        The rubber model's options (:func:`shtaerman.fem.rubber.rubber_model`).
    prony : PronySeries or str, optional
        Shear relaxation of the isochoric stress (``g1:tau1,...``, tau in s;
        :mod:`shtaerman.fem.finite_viscoelastic`): E2, nu2 are then the instantaneous values;
        with density 0 the quasi-static viscoelastic impact at finite strain.

    Returns
    -------
    FiniteDynamicResult

    Raises
    ------
    shtaerman.validation.InputError
        An input out of range.
    """
    from dataclasses import replace

    from ..fem.finite_contact import FINITE_MESH
    from ..fem.finite_dynamic import (
        INERTIA_MESH,
        FiniteImpactSettings,
        check_density,
        run_finite_impact,
    )
    from ..fem.rubber import rubber_model
    from ..fem.viscoelastic import prony_input
    from .layer_options import layer_mesh

    check_bodies(indenter, body)
    rubber = rubber_model(model, mooney_ratio, yeoh, gent_limit, volumetric)
    series = prony_input(prony)
    rho = check_density(body.density if density is None else density)
    default = FINITE_MESH if rho == 0 else INERTIA_MESH
    mesh = default if mesh_size is None else replace(default, size=mesh_size)
    mesh = layer_mesh(mesh, {"thickness": thickness, "base": base, "model": model})
    settings = FiniteImpactSettings(steps=time_steps, mesh=mesh)
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
        model=model,
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
