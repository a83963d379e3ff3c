"""One FE impact run, whatever the body: :class:`ImpactRun`, the peaks of its histories, the
separation time and the marching loop every body steps in (:func:`march_steps`).

Every impact of the FEM (the linear body with its one factorization, a rubber at finite
strain, massless or with inertia, elastic or relaxing, on a half-space or a pad, with any
interface) ends in the same record: the striker's histories, the maxima, the energy account and
the costs. What only some runs have is optional: the contact radius and central pressure
histories (the linear body), the split of the losses (a relaxing or frictional body), the
fields kept (the linear body's for pictures, an elastic rubber's solution) and the Newton
iterations (finite strain).
"""

from __future__ import annotations

import math
from collections.abc import Callable, Sequence
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any

import numpy as np

from ..validation import InputError, bound_text, validate_positive

if TYPE_CHECKING:
    from .elasticity import ElasticSolution, ElasticSystem
    from .viscoelastic import ShearMemory, ViscoelasticShear

__all__ = [
    "MAX_STEPS",
    "SUMMARY_KEYS",
    "ImpactRun",
    "finished_run",
    "fitted_peak",
    "impact_parameters",
    "march_steps",
    "mesh_counts",
    "parabola_peak",
    "refined_steps",
    "separation_time",
    "validate_steps",
]

MAX_STEPS = 100_000
"""Most time steps per quasi-static impact duration t_y of an impact run (either body)."""
SUMMARY_KEYS = (
    *("x_max", "P_max", "t_x_max", "t_contact", "v_out", "restitution"),
    *("energy_radiated_fraction", "energy_balance_error", "reflected_energy_fraction"),
)
"""The scalars of every run (the ``dynamic`` object of ``shtaerman dynamic --json``)."""


@dataclass(frozen=True, eq=False)
class ImpactRun:
    """An FE impact: histories, maxima, energy bookkeeping and costs (SI units).

    Attributes
    ----------
    t, x, v, force : numpy.ndarray
        Time from first touch (s), striker approach X (m, into the body), its velocity X'
        (m/s, downward) and the contact force P (N), every step.
    energies : dict of str to numpy.ndarray
        Per step, J: ``striker_kinetic``, ``body_kinetic``, ``strain``, ``absorbed`` (by an
        absorbing layer, cumulative) and ``numerical`` (E0 minus the rest); as the body has
        them ``dissipated`` (cumulative), ``contact_term``, ``inner``, ``inner_kinetic`` and
        ``slip`` (see the driver that made the run).
    x_max, P_max, t_x_max : float
        Largest approach (m), largest force (N) and the time of x_max (s).
    t_contact, v_out, restitution : float
        Separation time (s), rebound speed (m/s, upward) and e = v_out / v0; nan if the striker
        never separates in the run.
    energy_radiated_fraction : float
        1 - e^2: the share of M v0^2 / 2 left in the body.
    energy_balance_error : float
        max over t of |numerical| / E0.
    reflected_energy_fraction : float
        What the far boundary sends back (the driver defines its measure); nan where none is
        measured, 0 for a massless body.
    mesh, timings, parameters : dict
        Mesh counts and geometry (m); seconds per phase; inputs and derived scales (SI).
    contact_radius, central_pressure : numpy.ndarray or None
        Contact radius a (m) and axis pressure p0 (Pa) every step, where the run records them.
    losses : dict of str to float
        Fractions of M v0^2 / 2 lost in the body: ``energy_dissipated_fraction`` (a relaxing
        or frictional body) and for the linear viscoelastic body ``energy_wave_fraction`` and
        ``energy_hysteresis_fraction``; {} for an elastic frictionless body.
    newton_iterations : int or None
        Newton iterations over the run (finite strain).
    retried : str
        What of the run was retried, in one line ("" for nothing): time steps cut in halves
        (finite strain), a level run again with more time steps (the error-estimate ladder).
    relaxes : bool
        Whether the body relaxes (a finite-strain body with a Prony series; the linear body
        keeps its relaxing shear as ``material``); not written to JSON.
    system, snapshots, material, memories
        The fields kept for pictures (the linear body): its system, the state at requested
        times, its relaxing shear and its memories there (see :meth:`field_solution`).
    kept : KeptStates or None
        A rubber's solution at the steps nearest the requested times (an elastic rubber;
        :class:`.finite_dynamic.KeptStates`); None otherwise.
    """

    t: np.ndarray = field(repr=False)
    x: np.ndarray = field(repr=False)
    v: np.ndarray = field(repr=False)
    force: np.ndarray = field(repr=False)
    energies: dict[str, np.ndarray] = field(repr=False)
    x_max: float
    P_max: float
    t_x_max: float
    t_contact: float
    v_out: float
    restitution: float
    energy_radiated_fraction: float
    energy_balance_error: float
    reflected_energy_fraction: float
    mesh: dict[str, Any]
    timings: dict[str, float]
    parameters: dict[str, Any]
    contact_radius: np.ndarray | None = field(default=None, repr=False)
    central_pressure: np.ndarray | None = field(default=None, repr=False)
    losses: dict[str, float] = field(default_factory=dict)
    newton_iterations: int | None = None
    retried: str = ""
    relaxes: bool = False
    system: ElasticSystem | None = field(default=None, repr=False)
    snapshots: dict[float, tuple[float, np.ndarray, np.ndarray]] = field(
        default_factory=dict, repr=False
    )
    material: ViscoelasticShear | None = field(default=None, repr=False)
    memories: dict[float, ShearMemory | None] = field(default_factory=dict, repr=False)
    kept: Any = field(default=None, repr=False)  # KeptStates: finite_dynamic imports this module

    def summary(self) -> dict[str, float]:
        """The scalar results: :data:`SUMMARY_KEYS`, the losses and, with friction at the
        striker's surface recorded as slip, ``energy_slip_fraction`` (of M v0^2 / 2)."""
        summary = {key: float(getattr(self, key)) for key in SUMMARY_KEYS} | self.losses
        if "interface" in self.parameters and "slip" in self.energies:
            energy0 = 0.5 * self.parameters["mass"] * self.parameters["velocity"] ** 2
            summary["energy_slip_fraction"] = float(self.energies["slip"][-1]) / energy0
        return summary

    def history_columns(self) -> dict[str, np.ndarray]:
        """t (s), x (m), v (m/s), P (N) and, where recorded, a (m) and p0 (Pa), one row a
        step."""
        columns = {"t": self.t, "x": self.x, "v": self.v, "P": self.force}
        if self.contact_radius is not None:
            columns.update(a=self.contact_radius, p0=self.central_pressure)
        return columns

    def to_dict(self) -> dict[str, object]:
        """JSON-ready: scalars, histories as lists, energies, mesh, timings, parameters (SI;
        non-finite numbers None)."""
        return {
            **{key: _clean(value) for key, value in self.summary().items()},
            "history": {key: column.tolist() for key, column in self.history_columns().items()},
            "energies": {key: column.tolist() for key, column in self.energies.items()},
            "mesh": dict(self.mesh),
            "timings": dict(self.timings),
            "parameters": {key: _clean(value) for key, value in self.parameters.items()},
        }

    def field_solution(self, time_requested: float) -> tuple[float, ElasticSolution, np.ndarray]:
        """Fields kept for a requested time: (actual time s, solution, velocity vector m/s).

        The solution carries u, the mean pressure and the stresses (von Mises included) at
        the mesh vertices (a viscoelastic body's relaxed deviatoric stress from its branches);
        the velocity is the full dof vector (zero on the pressure dofs).
        """
        from .elasticity import postprocess

        if time_requested not in self.snapshots:
            raise KeyError(f"no snapshot kept for t = {time_requested!r} s; ask run_impact")
        actual, coefficients, velocity = self.snapshots[time_requested]
        memory = self.memories.get(time_requested)
        deviatoric = None
        if self.material is not None and memory is not None:  # the relaxing shear stress
            deviatoric = self.material.deviatoric_stress(memory)
        solution = postprocess(self.system, coefficients, np.zeros_like(coefficients), deviatoric)
        return actual, solution, velocity


def _clean(value: Any) -> Any:
    """A float, None where not finite; anything else (a string parameter) as it is."""
    if isinstance(value, (int, float, np.floating)) and not isinstance(value, bool):
        return float(value) if math.isfinite(value) else None
    return value


def parabola_peak(t: np.ndarray, y: np.ndarray) -> tuple[float, float]:
    """Peak value and time of the parabola through the largest sample k and its neighbours;
    the sample itself at an end or where y is not concave there."""
    k = int(np.argmax(y))
    if k == 0 or k == y.size - 1:
        return float(y[k]), float(t[k])
    y0, y1, y2 = y[k - 1], y[k], y[k + 1]
    curvature = y0 - 2.0 * y1 + y2
    if curvature >= 0:
        return float(y1), float(t[k])
    shift = 0.5 * (y0 - y2) / curvature
    return float(y1 - 0.25 * (y0 - y2) * shift), float(t[k] + shift * (t[k + 1] - t[k]))


def fitted_peak(t: np.ndarray, y: np.ndarray, k: int, half_width: int) -> float:
    """Peak of the least-squares parabola through samples k - w .. k + w (w = ``half_width``).

    The fit averages out the damped residue of the stiff-mode ripple on the force's flat top,
    which a 3-point parabola would follow.
    """
    window = slice(max(k - half_width, 0), min(k + half_width + 1, y.size))
    centre, scale = t[k], t[1] - t[0]
    c2, c1, c0 = np.polyfit((t[window] - centre) / scale, y[window], 2)
    if c2 >= 0:
        return float(y[k])
    return float(c0 - 0.25 * c1 * c1 / c2)


def impact_parameters(
    indenter: Any,
    half_space: Any,
    striker: tuple[float, float, float],
    time_step: float,
    friction: float | None,
) -> dict[str, float]:
    """The inputs every run reports (SI): ``striker`` (mass kg, velocity m/s, body density
    kg/m^3), the striker's profile, E2, nu2, the time step (s) and the interface: none
    frictionless, ``interface`` bonded with Coulomb's ``friction`` where finite (JSON has no
    inf)."""
    mass, velocity, density = striker
    parameters = {"mass": mass, "velocity": velocity, "density2": density}
    profile = {"shape_coefficient": getattr(indenter, "shape_coefficient", None)}
    profile["exponent"] = getattr(indenter, "exponent", None)  # None: a sphere or a table
    parameters.update(profile)
    parameters.update(E2=half_space.youngs_modulus, nu2=half_space.poisson_ratio)
    parameters["time_step"] = time_step
    if friction is not None:
        slip = {} if math.isinf(friction) else {"friction": friction}
        parameters.update(interface="bonded", **slip)
    return parameters


def mesh_counts(
    mesh: Any, dofs: int, candidates: int, refined: float, layer: Any
) -> dict[str, Any]:
    """Nodes, elements, dofs, contact candidates and the refined radius (m) of a run; a
    layer's thickness (m) and base (``layer``: settings with ``thickness`` and ``base``)."""
    counts = {"nodes": int(mesh.p.shape[1]), "elements": int(mesh.t.shape[1])}
    counts.update(dofs=int(dofs), contact_candidates=int(candidates), refined_radius=refined)
    if layer.thickness is not None:
        counts.update(thickness=layer.thickness, base=layer.base)
    return counts


def separation_time(t: np.ndarray, force: np.ndarray, q: float, k: int) -> float:
    """Time where P vanishes between steps k - 1 (P > 0) and k (P = 0).

    Near a smooth separation P ~ (t_s - t)^q, so P^(1/q) is linear: extrapolate it from the
    last two loaded steps (exact to O(dt^2) instead of O(dt)).
    """
    if k < 2 or force[k - 2] <= 0:
        return float(t[k - 1])
    y1, y2 = force[k - 2] ** (1 / q), force[k - 1] ** (1 / q)
    if y1 <= y2:
        return float(t[k - 1])
    return float(np.clip(t[k - 1] + y2 * (t[k - 1] - t[k - 2]) / (y1 - y2), t[k - 1], t[k]))


Step = Callable[[], Sequence[tuple[tuple[float, ...], bool]]]
"""A body's next time step: its rows (t first, the contact force P fourth, SI), each with
whether the contact ended there; none once the run is over."""


def march_steps(
    step: Step, first: tuple[float, ...], exponent: float, tail: tuple[float, float] = (0.0, 0.0)
) -> tuple[np.ndarray, float]:
    """Step from first touch until ``tail`` = (time s, slack s) after the contact ended, or
    until ``step`` has no more rows: the rows as a table (one a step, ``first`` included) and
    the separation time (s; :func:`separation_time` with q = ``exponent`` of P ~ x^q; nan if
    the contact never ended)."""
    rows, t_contact, end = [first], math.nan, math.inf
    while new := step():
        for row, ended in new:
            rows.append(row)
            if ended and math.isnan(t_contact):
                times, forces = np.array([r[0] for r in rows]), np.array([r[3] for r in rows])
                t_contact = separation_time(times, forces, exponent, len(rows) - 1)
                end = row[0] + tail[0]
            if row[0] >= end - tail[1]:
                return np.array(rows), t_contact
    return np.array(rows), t_contact


def finished_run(
    histories: tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray],
    energies: dict[str, np.ndarray],
    peaks: tuple[float, float, float],
    t_contact: float,
    energy0: float,
    **context: Any,
) -> ImpactRun:
    """The run of ``histories`` t (s), X (m), V (m/s), P (N), its ``energies`` (J, with
    ``numerical``) and ``peaks`` x_max (m), P_max (N), t_x_max (s): the rebound speed, the
    restitution and 1 - e^2 where the contact ended (``t_contact`` s, nan: never), the energy
    balance error over ``energy0`` = M v0^2 / 2 (J); ``context`` the rest of
    :class:`ImpactRun` (mesh, timings, parameters, ...)."""
    t, x, v, force = histories
    v_out = restitution = radiated = math.nan
    if not math.isnan(t_contact):  # the last velocity: the striker flies freely then
        v_out = -float(v[-1])
        restitution = v_out / float(v[0])  # a float, as JSON writes it
        radiated = 1.0 - restitution**2
    return ImpactRun(
        t=t,
        x=x,
        v=v,
        force=force,
        energies=energies,
        x_max=peaks[0],
        P_max=peaks[1],
        t_x_max=peaks[2],
        t_contact=t_contact,
        v_out=v_out,
        restitution=restitution,
        energy_radiated_fraction=radiated,
        energy_balance_error=float(np.max(np.abs(energies["numerical"])) / energy0),
        **context,
    )


def refined_steps(steps: int, factor: float, limits: tuple[int, int]) -> int:
    """The time steps per t_y of settings refined by ``factor`` (> 0): ``steps`` x ``factor``
    rounded, or InputError naming ``refine`` and its range where they leave ``limits``."""
    factor = validate_positive("refine", factor)
    low, high = limits
    if not low - 0.5 <= steps * factor < high + 0.5:  # round(steps) in range
        raise InputError(
            f"refine must lie in [{bound_text(low / steps, 'low')}, "
            f"{bound_text(high / steps, 'high')}] with {steps} steps per t_y (it scales the "
            f"time steps, {low}-{high} allowed, and divides the mesh sizes), got {factor!r}",
            "refine",
        )
    return round(steps * factor)


def validate_steps(steps: object, limits: tuple[int, int]) -> None:
    """Raise InputError naming ``steps`` unless it is an integer within ``limits``: time steps
    per quasi-static impact duration (fewer cannot resolve the impact)."""
    if not isinstance(steps, (int, np.integer)) or not (limits[0] <= steps <= limits[1]):
        raise InputError(
            f"steps (time steps per impact duration) must be an integer in [{limits[0]}, "
            f"{limits[1]}] (fewer cannot resolve the impact), got {steps!r}",
            "steps",
        )
