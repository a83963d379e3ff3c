"""Impact of a rigid power-law striker on a rubber half-space at finite strain, in time.

The massless body (density 0): the striker (mass M, depth X, X(0) = 0, X'(0) = v0) obeys
M X'' = -P(X), where P(X) is the force of the static finite-strain contact at depth X
(:mod:`.finite_contact`: Newton with frictionless contact against the indenter in the current
configuration, mixed u-p, any rubber model of :mod:`.rubber`), solved at every step.

Time stepping: the energy-conserving midpoint discrete gradient on the striker,

    X_{n+1} - X_n = dt (V_n + V_{n+1}) / 2,
    M (V_{n+1} - V_n) = -dt (Pi(X_{n+1}) - Pi(X_n)) / (X_{n+1} - X_n),

with Pi(X) the stored energy of the static contact at depth X (Pi = 0 without contact). It
conserves M V^2 / 2 + Pi(X) exactly at every step, so the restitution is 1 up to the Newton
tolerances, and it is second order. Each step solves the scalar equation in X_{n+1} by a
secant iteration, every evaluation being a static contact solve warm-started from the last
converged state. After the striker leaves (X_{n+1} <= 0) its speed is final.

The body with inertia (density > 0): Wood-Bossak-Zienkiewicz time stepping (rho_inf 0.9 by
default; second order) of the body, with its consistent mass less the normal mass of the contact
candidates (:func:`.mass.redistribute_normal_mass`: their u_z follow the indenter
quasi-statically, without chatter), the inertial force and its tangent added to the contact
Newton's residual and tangent. The striker's own Bossak equation
M ((1 - a_m) A_{n+1} + a_m A_n) + P(X_{n+1}) = 0 is solved by a secant in X_{n+1}, each
evaluation a contact solve of the body's step. Each step starts from x and X extrapolated
linearly in time, each Newton with its loaded candidates kept on the indenter in the first
iterate, and halves an update that inverts an element (damped Newton). A step whose Newton or
secant still fails (near separation the extrapolated start lifts the surface with the leaving
striker) is cut in two halves of dt / 2, recursively up to MAX_STEP_CUTS times, each half a
Bossak step recorded as a step of its own (the energy account is that of the smaller steps);
a step that converges is unchanged. No absorbing layer: the far arc lies ``mesh.domain``
refined radii away, beyond the waves' reach during the contact; the kinetic energy beyond half its
radius at the end is reported. The run stops when the contact force vanishes with the striker
rebounding (separation time from P^(1/q) extrapolated between steps).

:func:`prepare_finite_impact` is the finite-strain body of the one driver
(:func:`.impact.run_impact`): both bodies march in :func:`.impact_run.march_steps` and end in
one :class:`.impact_run.ImpactRun`. The massless body carries no kinetic energy and radiates
nothing; with inertia the energies are the striker's and the body's kinetic energy, the stored
energy and the numerical rest.

A Prony series (``prony``) makes the rubber viscoelastic (:mod:`.finite_viscoelastic`: its
isochoric stress relaxes); the history is committed when a step (or a cut step's half)
converges, and the energies gain the dissipated energy. The massless viscoelastic body has no
stored energy function of X: its striker steps by the trapezoidal rule, M (V_{n+1} - V_n) =
-dt (P_n + P_{n+1}) / 2 with the same X update (second order; the energy account closes to
second order in dt), each evaluation a static contact with the committed history and the
relaxation over dt, until the force vanishes with the striker rebounding (the surface, still
recovering, lags behind it); a series with every g_i = 0 is the elastic run. The refined zone
and the run's length are sized by the larger of the elastic and the quasi-static viscoelastic
impact (:func:`.viscoelastic.sizing_impact`).
"""

from __future__ import annotations

import math
import time
import warnings
from collections.abc import Callable
from dataclasses import dataclass, replace
from typing import Any

import numpy as np
import scipy.sparse as sp

from ..guards import MAX_DEPTH_RATIO, check_reach, depth_ratio, warn_outside_validity
from ..theory.contact import PowerLawContact
from ..theory.impact import QuasiStaticValidityWarning, solve_impact
from ..theory.materials import Material, validate_density
from ..theory.profile_impact import solve_profile_impact
from ..theory.sneddon import Indenter, SneddonContact, contact_law
from ..theory.viscoelastic import PronySeries
from ..validation import InputError, NumericalFailureError, validate_poisson, validate_positive
from .contact import EDGE_MARGIN
from .elasticity import consistent_mass, redistribute_normal_mass
from .finite_contact import (
    FINITE_BASE,
    FINITE_MESH,
    MAX_ITERATIONS,
    NEWTON_TOLERANCE,
    ContactOutgrowsMeshError,
    NewtonStepper,
    extrapolate,
    geometric_radius,
    tip_exponent,
)
from .finite_stick import HistoryStepper
from .finite_viscoelastic import ViscoelasticBody
from .hyperelastic import NeoHookean, NewtonError, assemble_hyperelastic
from .impact_run import (
    MAX_STEPS,
    ImpactRun,
    finished_run,
    impact_parameters,
    march_steps,
    mesh_counts,
    parabola_peak,
    refined_steps,
    validate_steps,
)
from .mesh import MeshSettings
from .rubber import GentLockError, RubberModel, gent_locks
from .stepper import TimeScheme
from .viscoelastic import sizing_impact

__all__ = [
    "FiniteImpactSettings",
    "FiniteImpactSetup",
    "prepare_finite_impact",
]

MIN_STEPS = 20
SECANT_TOLERANCE = 1e-10
"""The step's scalar equation is solved to |residual| <= this * M v0 / dt."""
MAX_SECANT = 30
DEPTH_RESOLUTION = 1e-12
"""A secant update below this x the depth (with inertia: x the quasi-static x_c) is converged:
the contact solves carry noise of their Newton tolerance, which keeps the step's residual above
SECANT_TOLERANCE where the step is small (the massless turning point: the discrete gradient over
a step of ~1e-4 of the depth) or the contact set flips between two converged states (a Coulomb
edge node near separation)."""
MAX_HALVINGS = 6
MAX_STEP_CUTS = 4
"""Halvings of a time step of the body with inertia whose Newton or secant failed."""
MAX_BACKTRACKS = 10
"""Halvings of a Newton update of the body with inertia that inverts an element (damped Newton)."""
MASSLESS_STEPS = 50
INERTIA_STEPS = 100
INERTIA_MESH = replace(FINITE_MESH, axis_size=1e-3)
"""The body with inertia's default mesh: FINITE_MESH graded to 1e-3 of the refined radius at
the axis, not 1e-6 (the impact reports no central pressure; on the 1e-6 grading the first
Newton iterates of a step move the u_r of the axis elements by more than their width, and the
damped Newton stalls)."""
IMPACT_MARGIN = 1.3
"""Refined radius / geometric contact radius at the small-strain x_c (the finite-strain contact
is wider by a few per cent)."""


PAD_FRICTION_REACH = (
    "; on a pad the depth is that of the half-space (an upper bound: the pad stops the "
    "striker a little sooner), which a bonded or Coulomb indenter cannot pass; "
    "--interface frictionless runs beyond it with a warning"
)
"""The end of the refusal of a frictional finite-strain impact on a pad beyond the reach."""


@dataclass(frozen=True)
class FiniteImpactSettings:
    """Numerical controls of the finite-strain impact.

    Attributes
    ----------
    steps : int or None
        Time steps per quasi-static (small-strain) impact duration t_y, >= 20; None: 50 for
        the massless body, 100 with inertia (its energy balance is second order in dt).
    mesh : MeshSettings or None
        Mesh of the half-space; its ``margin`` is replaced by ``margin`` below. None:
        :data:`.finite_contact.FINITE_MESH` for the massless body, :data:`INERTIA_MESH` with
        inertia.
    margin : float
        Refined (candidate) radius / geometric contact radius (x_c / A)^(1/n) at the
        small-strain x_c, > 1.
    spectral_radius : float
        rho_inf in [0, 1] of the Wood-Bossak-Zienkiewicz scheme of the body with inertia
        (1: the trapezoidal rule, no numerical damping); unused by the massless body.
    """

    steps: int | None = None
    mesh: MeshSettings | None = None
    margin: float = IMPACT_MARGIN
    spectral_radius: float = 0.9

    def __post_init__(self) -> None:
        if self.steps is not None:
            validate_steps(self.steps, (MIN_STEPS, MAX_STEPS))
        if not (isinstance(self.margin, (int, float)) and math.isfinite(self.margin)) or (
            self.margin <= 1.0
        ):
            raise InputError(f"margin must be > 1, got {self.margin!r}", "margin")
        rho_inf = self.spectral_radius
        if isinstance(rho_inf, bool) or not (
            isinstance(rho_inf, (int, float)) and 0.0 <= rho_inf <= 1.0
        ):
            raise InputError(
                f"spectral_radius must lie in [0, 1], got {rho_inf!r}", "spectral_radius"
            )

    def resolved(self, density: float) -> FiniteImpactSettings:
        """These settings with the defaults of the massless body (``density`` 0) or of the
        body with inertia filled in."""
        massless = density == 0
        steps = self.steps
        if steps is None:
            steps = MASSLESS_STEPS if massless else INERTIA_STEPS
        mesh = self.mesh
        if mesh is None:
            mesh = FINITE_MESH if massless else INERTIA_MESH
        return replace(self, steps=steps, mesh=mesh)

    def refined(self, factor: float) -> FiniteImpactSettings:
        """These (resolved) settings with the mesh size field divided and the time steps
        multiplied by ``factor`` (> 1 refines), as
        :meth:`shtaerman.fem.dynamic_contact.DynamicSettings.refined`."""
        assert self.steps is not None and self.mesh is not None, "resolve the settings first"
        steps = refined_steps(self.steps, factor, (MIN_STEPS, MAX_STEPS))
        return replace(self, steps=steps, mesh=self.mesh.refined(factor))


@dataclass
class _State:
    """A converged static contact at depth X (m): solution, multipliers, force (N), stored
    energy and, for a relaxing body at a committed step, the dissipated energy (J)."""

    depth: float
    x: np.ndarray
    lam: np.ndarray
    force: float
    energy: float
    dissipated: float = 0.0


class _QuasiStaticBody:
    """The massless body: the static contact state at any depth, warm-started.

    A viscoelastic body (:class:`.finite_viscoelastic.ViscoelasticBody`) is solved with the
    history of its committed steps, its relaxation over steps of ``dt`` (s; this object is its
    clock); it is ``relaxing`` when some g_i > 0 (with every g_i = 0 it is elastic).
    """

    def __init__(self, stepper: NewtonStepper, dt: float | None = None) -> None:
        self.stepper = stepper
        n = stepper.system.n_dofs
        self.zero = _State(0.0, np.zeros(n), np.zeros(stepper.nodes.radius.size), 0.0, 0.0)
        self.history = [self.zero]
        self.iterations = 0
        self.dt = dt
        self.deepest = 0.0  # the largest committed depth (m)
        system = stepper.system
        self.viscous = isinstance(system, ViscoelasticBody)
        self.relaxing = self.viscous and any(g > 0.0 for g in system.prony.weights)
        self.frictional = isinstance(stepper, HistoryStepper)
        self.history_dependent = self.relaxing or self.frictional
        if self.viscous:
            system.clock = self
        if self.relaxing:  # its unloading releases the contact under a history: damped Newton
            stepper.backtracks = MAX_BACKTRACKS

    def at(self, depth: float) -> _State:
        """The static state at ``depth`` (m); an elastic body's is 0 without contact (depth
        <= 0), a relaxing body's is solved at every depth (its history deforms it)."""
        if depth <= 0.0 and not self.relaxing:  # no contact: the free striker at this depth
            return _State(depth, self.zero.x, self.zero.lam, 0.0, 0.0)
        try:
            return self._solve(depth, MAX_HALVINGS)
        except GentLockError as error:  # the rubber's limit, an input: --gent-limit
            if error.parameter == "gent_limit":
                raise
            limit = self.stepper.system.material.gent_limit
            raise GentLockError.locking(limit, depth) from None
        except NewtonError as error:  # the run's numerics, not its input
            raise NumericalFailureError(
                f"the finite-strain contact failed at depth {depth:g} m ({error}); the body "
                "is strained beyond what this mesh resolves: a finer --mesh-size, more "
                "--time-steps or a lower --velocity (on a pad: a thicker --thickness)"
            ) from error

    def accept(self, state: _State) -> None:
        """Keep ``state`` as the newest converged one (the predictor's base)."""
        self.history = [*self.history[-1:], state]

    def commit(self, state: _State) -> _State:
        """``state`` as the end of a time step: a relaxing body's and a bonded or Coulomb
        contact's history committed, and the stored and dissipated energies (J) there; an
        elastic frictionless body's ``state`` unchanged."""
        if not self.history_dependent:
            return state
        system, stepper = self.stepper.system, self.stepper
        if self.frictional and (state.depth > 0.0 or self.relaxing):  # else: the run ends
            stepper.commit(state.x)
        dissipated = getattr(stepper, "dissipated", 0.0)
        if self.relaxing:
            system.commit(state.x)
            self.deepest = max(self.deepest, state.depth)
            state = replace(state, energy=system.energy(state.x))
            dissipated += system.dissipated
        return replace(state, dissipated=dissipated)

    def _solve(self, depth: float, halvings: int) -> _State:
        states = [(state.depth, state.x, state.lam) for state in self.history]
        guess_x, guess_lam = extrapolate(states, depth)
        # a relaxing body's corrections measured on the deepest depth (it unloads to X <= 0)
        scale = max(depth, self.deepest) if self.relaxing else None
        try:
            x, lam, iterations, _ = self.stepper.solve(depth, guess_x, guess_lam, scale)
        except NewtonError as error:
            last = self.history[-1]
            locked = gent_locks(error, self.stepper.system, last.x, depth, last=halvings == 0)
            if locked is not None:
                raise locked from None
            if halvings == 0:
                raise
            middle = 0.5 * (depth + last.depth)
            if middle <= 0.0 and not self.relaxing:
                raise
            self.accept(self._solve(middle, halvings - 1))
            return self._solve(depth, halvings - 1)
        self.iterations += iterations
        energy = self.stepper.system.energy(x)
        return _State(depth, x, lam, float(lam.sum()), energy)


def _discrete_gradient(a: _State, b: _State) -> float:
    """(Pi_b - Pi_a) / (X_b - X_a) in N; the mean force when the depths nearly coincide."""
    step = b.depth - a.depth
    if abs(step) <= 1e-7 * max(abs(a.depth), abs(b.depth), 1e-300):
        return 0.5 * (a.force + b.force)
    return (b.energy - a.energy) / step


def _mean_force(a: _State, b: _State) -> float:
    """(P_a + P_b) / 2 in N: the trapezoidal rule's force over a step."""
    return 0.5 * (a.force + b.force)


def _step(
    body: _QuasiStaticBody,
    state: _State,
    v: float,
    mass: float,
    scales: tuple[float, float],
    gradient: Any = _discrete_gradient,
) -> tuple[_State, float]:
    """One step X_{n+1} - X_n = dt (V_n + V_{n+1}) / 2, M (V_{n+1} - V_n) = -dt G: the new
    state and velocity. ``scales``: dt (s) and the contact stiffness guess of the secant's
    first slope k (N/m); ``gradient``: G (N) of the states at the step's ends, the discrete
    gradient of the stored energy or the trapezoidal rule's mean force."""
    dt, k = scales

    def residual(depth: float) -> tuple[float, _State]:
        trial = body.at(depth)
        return 2.0 * mass * ((depth - state.depth) / dt - v) / dt + gradient(state, trial), trial

    scale = mass * max(abs(v), 1e-300) / dt
    # the linearized step: 2 M / dt^2 (D - dt v) + P_n + k D / 2 = 0 for D = X_{n+1} - X_n
    slope = 2.0 * mass / dt**2 + 0.5 * k
    start = state.depth + (2.0 * mass * v / dt - state.force) / slope
    limits = (SECANT_TOLERANCE * scale, lambda d: DEPTH_RESOLUTION * max(abs(d), abs(state.depth)))
    depth, new = _secant(residual, (start, slope, mass / dt**2), limits, state.depth)
    return new, 2.0 * (depth - state.depth) / dt - v


def _secant(
    residual: Callable[[float], tuple[float, Any]],
    start: tuple[float, float, float],
    limits: tuple[float, Callable[[float], float]],
    depth: float,
) -> tuple[float, Any]:
    """The striker's depth X_{n+1} (m) at the end of a step, by a secant on the step's
    equation ``residual``(X) (N, and the body's state there), and that state.

    ``start``: the first X (m), the first slope and the least slope (N/m; the step's own
    slope is at least the striker's inertia: half of it is kept); ``limits``: the residual's
    tolerance (N) and, of X, the update (m) at the contact solves' noise floor; ``depth`` X_n.
    """
    d0, slope, least = start
    r0, got = residual(d0)
    for _ in range(MAX_SECANT):
        if abs(r0) <= limits[0]:
            return d0, got
        d1 = d0 - r0 / slope
        if abs(d1 - d0) <= limits[1](d0):  # at the solves' noise floor
            return d0, got
        r1, got = residual(d1)
        if d1 != d0:
            slope = max((r1 - r0) / (d1 - d0), least)
        d0, r0 = d1, r1
    raise NumericalFailureError(
        f"the striker's step equation did not converge at depth {depth:g} m; raise the time steps"
    )


def _march(
    body: _QuasiStaticBody, mass: float, velocity: float, dt: float, scales: tuple[float, float]
) -> tuple[tuple[np.ndarray, ...], float | None]:
    """Step from first touch until the striker leaves (or the longest run).

    An elastic frictionless body steps by the discrete gradient of its stored energy, until X
    is back to 0. A relaxing body, or a bonded or Coulomb contact, has no stored energy
    function of X: it steps by the trapezoidal rule on the contact force (second order, as
    Ting's quasi-static impact in :func:`shtaerman.theory.viscoelastic.viscoelastic_impact`),
    its history committed at every step, until the force vanishes with the striker
    rebounding. ``scales``: the longest run (s) and q of P ~ X^q. Returns the columns t, X,
    V, P, stored energy and, for a viscoelastic body or a contact with friction, the body's
    kinetic (0) and dissipated energies (SI); and the separation time (s; None for an elastic
    frictionless body, nan if the run ended first).
    """
    duration, exponent = scales
    state, v, t, k = body.zero, velocity, 0.0, 0.0
    extra = (0.0, 0.0) if body.viscous or body.frictional else ()
    gradient = _mean_force if body.history_dependent else _discrete_gradient

    def step() -> list[tuple[tuple, bool]]:
        nonlocal state, v, t, k
        if not t < duration or (t > 0.0 and state.depth <= 0.0):  # the longest run; X back
            return []
        new, v = _step(body, state, v, mass, (dt, k), gradient)
        if new.depth > 0 and state.depth > 0 and new.depth != state.depth:
            k = max((new.force - state.force) / (new.depth - state.depth), 0.0)
        state, t = body.commit(new), t + dt
        if state.depth > 0:
            body.accept(state)
        row = (t, state.depth, v, state.force, state.energy)
        row += (0.0, state.dissipated) if extra else ()
        ended = (state.force == 0.0 and v < 0.0) or state.depth <= 0.0
        return [(row, body.history_dependent and ended)]

    table, separation = march_steps(step, (0.0, 0.0, v, 0.0, 0.0, *extra), exponent)
    return tuple(table.T), (separation if body.history_dependent else None)


def _turning_point(
    x: np.ndarray, v: np.ndarray, force: np.ndarray, mass: float
) -> tuple[float, float]:
    """x_max (m) and P_max (N) from the step's energy identity M V^2 / 2 + Pi(X) = E0.

    From the sample k of largest X: x_max = X_k + M V_k^2 / (2 P_k) to first order in the
    (small) kinetic energy left there, corrected by the quadratic through the samples
    (X, P) around k; P_max is that quadratic at x_max.
    """
    k = int(np.argmax(x))
    if k == 0 or k == x.size - 1 or force[k] <= 0:
        return float(x[k]), float(force[k])
    around = slice(k - 1, k + 2)
    curve = np.polyfit(x[around] - x[k], force[around], 2)
    energy = 0.5 * mass * v[k] ** 2  # Pi(x_max) - Pi(X_k) = int_Xk^x_max P dX
    step = energy / force[k]
    for _ in range(20):  # Newton on int_0^s P(X_k + y) dy = energy
        c2, c1, c0 = curve
        work = c2 * step**3 / 3 + c1 * step**2 / 2 + c0 * step
        step -= (work - energy) / np.polyval(curve, step)
    return float(x[k] + step), float(np.polyval(curve, step))


@dataclass(frozen=True, eq=False)
class FiniteImpactSetup:
    """A finite-strain impact ready to step (the body of :func:`.impact.run_impact`; SI).

    Attributes
    ----------
    stepper : NewtonStepper
        The rubber's contact Newton (a bonded or Coulomb one with friction).
    settings : FiniteImpactSettings
        Resolved for the density.
    inputs : tuple
        The striker's profile, the body's small-strain material, its density (kg/m^3), the
        striker's mass (kg) and velocity (m/s), the friction (None: frictionless).
    scales : tuple
        The quasi-static (small-strain) x_c (m) and t_y (s), the longest run (s), q of
        P ~ X^q and beta (N/m^q) of the exact law.
    mesh : dict
        As in :class:`.impact_run.ImpactRun`.
    timings : dict of str to float
        Seconds: ``mesh``, ``assembly``.
    """

    stepper: NewtonStepper
    settings: FiniteImpactSettings
    inputs: tuple[Indenter, Material, float, float, float, float | None]
    scales: tuple[float, float, float, float, float]
    mesh: dict[str, Any]
    timings: dict[str, float]

    def march(self, snapshot_times: tuple[float, ...] = ()) -> tuple:
        """Step the run (no fields are kept: ``snapshot_times`` is the linear body's): the
        columns, Newton iterations, separation time (s; None: the massless elastic body) and
        the kinetic energy beyond half the domain radius at the end / (M v0^2 / 2) (nan:
        massless)."""
        _, _, rho, mass, velocity, _ = self.inputs
        x_c, t_y, duration, q, _ = self.scales
        dt, stepper = t_y / self.settings.steps, self.stepper
        if rho == 0.0:
            body = _QuasiStaticBody(stepper, dt)
            columns, separation = _march(body, mass, velocity, dt, (duration, q))
            return columns, body.iterations, separation, math.nan
        scheme = TimeScheme.bossak(self.settings.spectral_radius, dt)
        inertial = _inertial(stepper, rho, scheme)
        columns, iterations, separation, last = _march_inertial(
            stepper, inertial, (mass, velocity), (x_c, duration, q)
        )
        far = _far_kinetic(inertial, last.v) / (0.5 * mass * velocity**2)
        return columns, iterations, separation, far

    def result(self, marched: tuple, timings: dict[str, float]) -> ImpactRun:
        """The run of ``marched`` (what :meth:`march` returned), ``timings`` its costs (s)."""
        columns, iterations, separation, far = marched
        indenter, half_space, rho, mass, velocity, friction = self.inputs
        (x_c, t_y, _, _, beta), settings = self.scales, self.settings
        striker = (mass, velocity, rho)
        parameters = impact_parameters(
            indenter, half_space, striker, t_y / settings.steps, friction or None
        )
        parameters.update(quasi_static_x_c=x_c, quasi_static_t_y=t_y, beta=beta)
        parameters.update(time_steps=settings.steps, mesh_size=settings.mesh.size)
        if rho > 0:
            parameters.update(spectral_radius=settings.spectral_radius)
        context = {"timings": timings, "mesh": self.mesh, "parameters": parameters}
        context.update(newton_iterations=iterations, reflected_energy_fraction=far)
        result = _result(columns, mass, context, separation)
        warn_outside_validity(indenter, result.x_max, settings.mesh.thickness, finite=True)
        return result


def prepare_finite_impact(
    indenter: Indenter,
    half_space: Material,
    density: float,
    mass: float,
    velocity: float,
    settings: FiniteImpactSettings | None = None,
    rubber: RubberModel | None = None,
    prony: PronySeries | None = None,
    friction: float | None = None,
) -> FiniteImpactSetup:
    """Check, mesh and assemble the impact of a rigid striker on a rubber at finite strain
    (the arguments of :func:`.impact.run_impact`, the body's ``rubber`` default neo-Hookean,
    ``friction`` None or 0 frictionless).

    Raises
    ------
    shtaerman.validation.InputError
        Inputs out of range.
    """
    rho, mass, velocity, law = _checked(indenter, half_space, density, mass, velocity)
    settings = (FiniteImpactSettings() if settings is None else settings).resolved(rho)
    q = law.force_exponent
    with warnings.catch_warnings():  # the caller warns of a fast impact beside its results
        warnings.simplefilter("ignore", QuasiStaticValidityWarning)
        if isinstance(law, PowerLawContact):
            quasi = solve_impact(mass, velocity, law)
        else:  # a sphere, a table: Sneddon's law, the impact by quadrature
            quasi = solve_profile_impact(mass, velocity, law)
    x_c, t_y = quasi.x_c, quasi.t_y
    if settings.mesh.thickness is not None and settings.mesh.base != "bonded":
        raise InputError(FINITE_BASE, "base")
    unbounded = settings.mesh.thickness is None  # a pad stops the striker short of x_c
    if unbounded or friction:  # before the viscoelastic sizing, which warns of fast impacts
        # on a pad x_c bounds the depth from above (the pad is stiffer; z = 8 r^1.3 on a 12 mm
        # pad reached x/a 2.26 against 2.27): a frictional contact does not converge beyond
        # the reach (that case failed at separation after 15 min), a frictionless one warns
        note = "" if unbounded else PAD_FRICTION_REACH
        check_reach(indenter, x_c, (mass, velocity), q, finite=True, note=note)
    x_size, duration = _relaxed_extent(law, mass, velocity, prony, (x_c, t_y))
    if unbounded and x_size > x_c:
        check_reach(indenter, x_size, (mass, velocity), q, finite=True)
    refined = settings.margin * geometric_radius(indenter, x_size)
    refined *= settings.mesh.zone_factor(tip_exponent(indenter))  # 1 on the half-space
    clock = [time.perf_counter()]
    mesh = settings.mesh.build(refined)
    clock.append(time.perf_counter())
    stepper = _assembled(mesh, indenter, half_space, (rubber, prony, friction), refined)
    clock.append(time.perf_counter())
    counts = (stepper.system.n_dofs, stepper.nodes.radius.size)
    return FiniteImpactSetup(
        stepper=stepper,
        settings=settings,
        inputs=(indenter, half_space, rho, mass, velocity, friction),
        scales=(x_c, t_y, duration, q, law.beta),
        mesh=mesh_counts(mesh, *counts, refined, settings.mesh),
        timings={"mesh": clock[1] - clock[0], "assembly": clock[2] - clock[1]},
    )


def _relaxed_extent(
    law: PowerLawContact,
    mass: float,
    velocity: float,
    prony: PronySeries | None,
    scales: tuple[float, float],
) -> tuple[float, float]:
    """The depth (m) that sizes the refined zone and the longest run (s): the elastic x_c and
    3 t_y (``scales`` x_c, t_y), or with a Prony series having some g_i > 0 the larger of
    those and of the quasi-static viscoelastic impact's x_max and 3 t_contact.

    Raises
    ------
    shtaerman.validation.InputError
        Naming ``prony`` for a series that relaxes too far within the impact.
    """
    x_c, t_y = scales
    if prony is None or not any(g > 0.0 for g in prony.weights):
        return x_c, 3.0 * t_y
    slow = sizing_impact(mass, velocity, law, prony, t_y)
    return max(x_c, slow.x_max), 3.0 * max(t_y, slow.t_contact)


def _checked(
    indenter: Indenter, half_space: Material, density: object, mass: float, velocity: float
) -> tuple[float, float, float, PowerLawContact | SneddonContact]:
    """Density (kg/m^3), mass (kg), velocity (m/s) and the exact law (Shtaerman's, or
    Sneddon's for a sphere or a table), every input checked."""
    rho = validate_density("density2", density)
    mass = validate_positive("mass", mass, "kg")
    velocity = validate_positive("velocity", velocity, "m/s")
    validate_poisson("nu2", half_space.poisson_ratio, low=0.0)
    if indenter.kind == "power-law" and indenter.exponent <= 1.0:
        raise InputError(f"exponent must be > 1 with a rubber model, got {indenter.exponent!r}")
    modulus = half_space.youngs_modulus / (1.0 - half_space.poisson_ratio**2)
    return rho, mass, velocity, contact_law(indenter, modulus)


def _assembled(
    mesh: Any,
    indenter: Indenter,
    half_space: Material,
    model: tuple[RubberModel | None, PronySeries | None, float | None],
    refined: float,
) -> NewtonStepper:
    """The rubber on ``mesh`` assembled, and its contact Newton (candidates up to ``refined``);
    ``model``: the rubber model (None: neo-Hookean), the Prony series (None: elastic) and the
    friction (None or 0: frictionless; else a :class:`.finite_stick.HistoryStepper`)."""
    rubber, prony, friction = model
    constants = (half_space.youngs_modulus, half_space.poisson_ratio)
    material = NeoHookean(*constants) if rubber is None else rubber.material(*constants)
    system = assemble_hyperelastic(mesh, material)
    limits = (NEWTON_TOLERANCE, MAX_ITERATIONS)
    if friction:
        stepper = HistoryStepper(system, indenter, refined, limits, friction)
    else:
        stepper = NewtonStepper(system, indenter, refined, *limits)
    if prony is not None:
        stepper.system = ViscoelasticBody(system, prony)
    return stepper


def _result(
    columns: tuple[np.ndarray, ...],
    mass: float,
    context: dict[str, Any],
    separation: float | None = None,
) -> ImpactRun:
    """Maxima, separation and energies of a run: ``columns`` t, X, V, P, Pi and, with inertia
    or a viscoelastic body, the body's kinetic energy and then its dissipated energy;
    ``context`` its timings, mesh, parameters and Newton iterations; ``separation`` the time
    (s) P vanished (None: the massless elastic body, X back to 0)."""
    t, x, v, force, strain = columns[:5]
    energy0 = 0.5 * mass * v[0] * v[0]
    kinetic = 0.5 * mass * v * v
    zeros = np.zeros_like(t)
    body = columns[5] if len(columns) > 5 else zeros
    numerical = energy0 - kinetic - strain - body
    energies = {"striker_kinetic": kinetic, "body_kinetic": body, "strain": strain}
    energies.update(absorbed=zeros, numerical=numerical)
    if len(columns) > 6:  # a viscoelastic or frictional body: what it dissipated
        numerical -= columns[6]
        energies["dissipated"] = columns[6]
        fraction = float(columns[6][-1]) / energy0
        context = {**context, "losses": {"energy_dissipated_fraction": fraction}}
    _, t_x_max = parabola_peak(t, x)
    t_contact = math.nan
    if separation is None:
        x_max, p_max = _turning_point(x, v, force, mass)
        if x[-1] <= 0.0 and x.size > 2:  # X back to 0 between the last two steps
            t_contact = float(t[-2] + (t[-1] - t[-2]) * x[-2] / (x[-2] - x[-1]))
    else:  # P not a function of X: the parabolas through the samples around the largest
        x_max, p_max = parabola_peak(t, x)[0], parabola_peak(t, force)[0]
        t_contact = separation
    peaks = (x_max, p_max, t_x_max)
    return finished_run((t, x, v, force), energies, peaks, t_contact, energy0, **context)


# --- the body with inertia --------------------------------------------------------------------


class _InertialSystem:
    """The hyperelastic system seen by the contact Newton during one Bossak step.

    Residual R(x) + M ((1 - a_m) a(x) + a_m a_n) with a(x) = (x - x_hat) / (beta dt^2) (N),
    tangent K_T(x) + (1 - a_m) / (beta dt^2) M; everything else is the static system's.
    """

    def __init__(self, system: Any, mass: sp.csr_matrix, scheme: TimeScheme) -> None:
        self.static = system
        self.mass = mass
        self.alpha_m, self.beta, self.gamma = scheme.alpha_m, scheme.beta, scheme.gamma
        self.dt = scheme.dt  # halved where a step is cut
        coo = mass.tocoo()
        self.mass_data = np.zeros(system.pattern.nnz)
        np.add.at(self.mass_data, system.pattern.find(coo.row, coo.col), coo.data)
        self.x_hat = np.zeros(system.n_dofs)
        self.a_n = np.zeros(system.n_dofs)

    def __getattr__(self, name: str) -> Any:
        return getattr(self.static, name)

    def acceleration(self, x: np.ndarray) -> np.ndarray:
        """a_{n+1} (m/s^2) of the step ending at x."""
        return (x - self.x_hat) / (self.beta * self.dt**2)

    def residual(self, x: np.ndarray, state: Any = None) -> np.ndarray:
        """Internal plus inertial forces (N) and the pressure equation (m^3)."""
        inertia = (1.0 - self.alpha_m) * self.acceleration(x) + self.alpha_m * self.a_n
        return self.static.residual(x, state) + self.mass @ inertia

    def tangent_data(self, x: np.ndarray, state: Any = None) -> np.ndarray:
        """The effective tangent's data in the system's pattern (N/m)."""
        factor = (1.0 - self.alpha_m) / (self.beta * self.dt**2)
        return self.static.tangent_data(x, state) + factor * self.mass_data


@dataclass
class _Dynamic:
    """State at a step: body x, v, a; multipliers; striker X (m), V (m/s), A (m/s^2); Pi (J);
    ``previous`` the body x and striker X (m) of the step before, ``interval`` (s) the time
    step that led here."""

    x: np.ndarray
    v: np.ndarray
    a: np.ndarray
    lam: np.ndarray
    depth: float
    speed: float
    accel: float
    energy: float
    previous: tuple[np.ndarray, float]
    interval: float
    dissipated: float = 0.0

    def predicted(self, dt: float) -> tuple[np.ndarray, np.ndarray, float]:
        """The start of a step of ``dt`` (s): x and X extrapolated linearly in time, the
        multipliers."""
        x_old, depth_old = self.previous
        if dt == self.interval:
            return 2.0 * self.x - x_old, self.lam, 2.0 * self.depth - depth_old
        ratio = dt / self.interval
        return (
            self.x + ratio * (self.x - x_old),
            self.lam,
            self.depth + ratio * (self.depth - depth_old),
        )


def _body_step(
    stepper: NewtonStepper, start: tuple[np.ndarray, np.ndarray, float], depth: float, scale: float
) -> tuple[np.ndarray, np.ndarray, int]:
    """The body's step against the striker at ``depth`` (m): x, lambda, Newton iterations.

    ``start``: a converged x, lambda of the same step and its depth (m) (the last step's at
    first). Every Newton starts from the last converged x, the multipliers of its loaded candidates
    raised by c (d_last - d) where the indenter withdraws, so that the first iterate keeps
    them on the indenter and lifts the surface with it (a first active set from the gap alone
    releases the lightly loaded, massless candidates next to the axis and folds their small
    elements). A failing Newton is continued in depth within the step: halved, up to
    MAX_HALVINGS times. ``scale`` (m) measures the Newton corrections.
    """
    x, lam, done = start
    total, increment, cuts = 0, depth - done, 0
    while True:
        trial = done + increment
        if abs(depth - trial) <= 1e-9 * scale:
            trial = depth
        guess = lam + stepper.weight * max(done - trial, 0.0) * (lam > 0)
        try:
            x_new, lam_new, iterations, _ = stepper.solve(trial, x, guess, scale)
        except NewtonError:
            cuts += 1
            if cuts > MAX_HALVINGS:
                raise
            increment *= 0.5
            continue
        x, lam, done, total = x_new, lam_new, trial, total + iterations
        if trial == depth:
            return x, lam, total
        increment = depth - done if abs(2.0 * increment) > abs(depth - done) else 2 * increment


def _dynamic_step(
    stepper: NewtonStepper,
    inertial: _InertialSystem,
    state: _Dynamic,
    mass: float,
    scales: tuple[float, float, float],
) -> tuple[_Dynamic, int]:
    """One step of body and striker, and its Newton iterations.

    The striker's Bossak equation M ((1 - a_m) A_{n+1} + a_m A_n) + P(X_{n+1}) = 0 is solved
    for X_{n+1} by a secant, each evaluation a body step. ``scales``: the contact stiffness
    guess of the first slope (N/m), the depth (m) and the force (N) scales of the tolerances.
    """
    alpha_m, beta, dt = inertial.alpha_m, inertial.beta, inertial.dt
    inertial.x_hat = state.x + dt * state.v + dt**2 * (0.5 - beta) * state.a
    inertial.a_n = state.a
    big_hat = state.depth + dt * state.speed + dt**2 * (0.5 - beta) * state.accel
    stiffness = mass * (1.0 - alpha_m) / (beta * dt**2)
    k, depth_scale, force_scale = scales
    load = mass * alpha_m * state.accel
    iterations, latest = 0, state.predicted(dt)

    def residual(depth: float) -> tuple[float, tuple[np.ndarray, np.ndarray]]:
        nonlocal iterations, latest
        x, lam, count = _body_step(stepper, latest, depth, depth_scale)
        iterations, latest = iterations + count, (x, lam, depth)
        return stiffness * (depth - big_hat) + load + float(lam.sum()), (x, lam)

    slope = stiffness + k  # the linearized force P_n + k (X - X_n)
    d0 = (stiffness * big_hat + k * state.depth - load - float(state.lam.sum())) / slope
    limits = (SECANT_TOLERANCE * force_scale, lambda _: DEPTH_RESOLUTION * depth_scale)
    depth, (x, lam) = _secant(residual, (d0, slope, 0.5 * stiffness), limits, state.depth)
    return _advanced(stepper, inertial, state, (x, lam, depth, big_hat)), iterations


def _cut_step(
    stepper: NewtonStepper,
    inertial: _InertialSystem,
    state: _Dynamic,
    mass: float,
    scales: tuple[float, float, float],
    cuts: int = 0,
) -> tuple[list[_Dynamic], int]:
    """One time step of :func:`_dynamic_step`, or where it fails, the step in two halves.

    Each half is a Bossak step of dt / 2 (same alpha_m, beta, gamma), started like any step
    from the state before it, and cut again where it fails, at most MAX_STEP_CUTS deep. The
    halves' states are recorded as steps of their own, so the energy account holds at every
    recorded state as with uniform steps; the second half is skipped if the first ends the
    contact. Returns the states reached (in time order) and the converged Newton iterations.
    A step that needs no cut is the uncut step, bit for bit.
    """
    try:
        new, iterations = _dynamic_step(stepper, inertial, state, mass, scales)
        return [new], iterations
    except (NewtonError, NumericalFailureError):
        if cuts == MAX_STEP_CUTS:
            raise
    dt = inertial.dt
    inertial.dt = 0.5 * dt
    try:
        first, iterations = _cut_step(stepper, inertial, state, mass, scales, cuts + 1)
        if _separated(first[-1]):
            return first, iterations
        second, more = _cut_step(stepper, inertial, first[-1], mass, scales, cuts + 1)
    finally:
        inertial.dt = dt
    return first + second, iterations + more


def _separated(state: _Dynamic) -> bool:
    """Whether the contact has ended: no contact force, the striker rebounding."""
    return float(state.lam.sum()) == 0.0 and state.speed < 0


def _advanced(
    stepper: NewtonStepper, inertial: _InertialSystem, state: _Dynamic, solved: tuple
) -> _Dynamic:
    """The Bossak update of velocities and accelerations from ``solved`` = (x, lambda,
    X_{n+1} (m), the striker's predictor X_hat (m)); the body's and the contact's histories
    committed."""
    x, lam, depth, big_hat = solved
    beta, gamma, dt = inertial.beta, inertial.gamma, inertial.dt
    a = inertial.acceleration(x)
    accel = (depth - big_hat) / (beta * dt**2)
    body = inertial.static
    if isinstance(body, ViscoelasticBody):
        body.commit(x)
    if isinstance(stepper, HistoryStepper):
        stepper.commit(x)
    return _Dynamic(
        x=x,
        v=state.v + dt * ((1.0 - gamma) * state.a + gamma * a),
        a=a,
        lam=lam,
        depth=depth,
        speed=state.speed + dt * ((1.0 - gamma) * state.accel + gamma * accel),
        accel=accel,
        energy=body.energy(x),
        previous=(state.x, state.depth),
        interval=dt,
        dissipated=getattr(body, "dissipated", 0.0) + getattr(stepper, "dissipated", 0.0),
    )


def _march_inertial(
    stepper: NewtonStepper,
    inertial: _InertialSystem,
    striker: tuple[float, float],
    scales: tuple[float, float, float],
) -> tuple[tuple[np.ndarray, ...], int, float, _Dynamic]:
    """Step from first touch until the contact force vanishes with the striker rebounding.

    ``striker``: mass M (kg) and v0 (m/s); ``scales``: the depth scale (m), the longest
    run (s) and q of P ~ X^q (for the separation time between steps). Returns the columns
    t, X, V, P, Pi, body kinetic energy (SI), the Newton iterations and the separation time
    (s; nan if the run ended first) and the last state.
    """
    mass, velocity = striker
    depth_scale, duration, exponent = scales
    zero, lam = np.zeros(inertial.static.n_dofs), np.zeros(stepper.nodes.radius.size)
    state = _Dynamic(zero, zero, zero, lam, 0.0, velocity, 0.0, 0.0, (zero, 0.0), inertial.dt)
    dissipative = isinstance(inertial.static, ViscoelasticBody) or isinstance(
        stepper, HistoryStepper
    )
    total, k, t, deepest = 0, 0.0, 0.0, 0.0
    force_scale = mass * velocity / inertial.dt

    def step() -> list[tuple[tuple, bool]]:
        nonlocal state, total, k, t, deepest
        if not t < duration:
            return []
        try:
            states, iterations = _cut_step(
                stepper, inertial, state, mass, (k, depth_scale, force_scale)
            )
        except NewtonError as error:
            if isinstance(error, GentLockError):  # in every cut step: the rubber locks
                limit = stepper.system.material.gent_limit  # within the step: the depth it
                reached = state.depth + abs(state.speed) * inertial.dt  # was going to
                raise GentLockError.locking(limit, reached) from None
            raise _step_failure(stepper, (t, state.depth, deepest), error) from None
        total, rows = total + iterations, []
        for new in states:
            force, previous = float(new.lam.sum()), float(state.lam.sum())
            if new.depth != state.depth:
                k = max((force - previous) / (new.depth - state.depth), 0.0)
            _check_candidates(stepper, new.lam, new.depth)
            state, t, deepest = new, t + new.interval, max(deepest, new.depth)
            body = 0.5 * float(state.v @ (inertial.mass @ state.v))
            row = (t, state.depth, state.speed, force, state.energy, body)
            rows.append(((*row, state.dissipated) if dissipative else row, _separated(state)))
            if rows[-1][1]:
                break
        return rows

    first = (0.0, 0.0, velocity, 0.0, 0.0, 0.0, *((0.0,) if dissipative else ()))
    table, separation = march_steps(step, first, exponent)
    return tuple(table.T), total, separation, state


def _step_failure(
    stepper: NewtonStepper, at: tuple[float, float, float], error: Exception
) -> NumericalFailureError:
    """The failure of a step from time ``at[0]`` (s) at striker depth ``at[1]`` (m), the run
    having reached ``at[2]`` (m): with a bonded or Coulomb indenter beyond the validated x/a
    (:data:`.guards.MAX_DEPTH_RATIO`) that limit is named (near separation the last ring in
    contact slides back inward down the steep flank and folds the surface: the A = 8 pad,
    x/a 2.29), else what may help."""
    where = (
        f"the step from t = {at[0]:.4g} s (striker depth {at[1]:.4g} m): {error}, also in "
        f"steps cut {MAX_STEP_CUTS} times; "
    )
    ratio = depth_ratio(stepper.indenter, at[2])
    if isinstance(stepper, HistoryStepper) and ratio > MAX_DEPTH_RATIO:
        return NumericalFailureError(
            where + f"the bonded indenter reached x/a = {ratio:.3g}, beyond the "
            f"finite-strain contact's validated {MAX_DEPTH_RATIO:g}, where its last ring in "
            "contact slides back along the steep striker as it leaves: a blunter striker "
            "(a smaller --shape-coefficient or a slower --velocity) or --interface "
            "frictionless (run beyond x/a 1.2 with a warning)"
        )
    return NumericalFailureError(
        where + "the body with inertia cannot follow this impact at these settings (other "
        "time steps may help; a striker faster than the shear waves never converges): "
        "--density2 0 gives the massless finite-strain impact"
    )


def _far_kinetic(inertial: _InertialSystem, v: np.ndarray) -> float:
    """Kinetic energy (J) of the velocities ``v`` (m/s) beyond half the domain radius: what
    the waves carried to the far arc, from where it could come back."""
    locations = inertial.static.displacement_basis.doflocs
    distance = np.hypot(locations[0], locations[1])
    far = np.zeros_like(v)
    outer = np.flatnonzero(distance > 0.5 * distance.max())
    far[outer] = v[outer]
    return 0.5 * float(far @ (inertial.mass @ far))


def _check_candidates(stepper: NewtonStepper, lam: np.ndarray, depth: float) -> None:
    """Refuse a contact (multipliers ``lam``, N) that reached the edge of the candidates."""
    loaded = np.flatnonzero(lam > 0)
    if loaded.size and loaded[-1] + EDGE_MARGIN >= lam.size:
        r = stepper.nodes.radius
        raise ContactOutgrowsMeshError(
            f"depth {depth:g} m: the contact zone reaches R = {r[loaded[-1]]:.4g} m, the edge "
            f"of the refined region ({r[-1]:.4g} m); raise the margin"
        )


def _inertial(stepper: NewtonStepper, density: float, scheme: TimeScheme) -> _InertialSystem:
    """The body's consistent mass (``density`` kg/m^3) without the normal mass of the contact
    candidates, wrapped with the Bossak ``scheme`` around the stepper's system (which it
    replaces in the stepper, whose Newton then back-tracks an update that inverts an element)."""
    system = stepper.system
    mass = redistribute_normal_mass(consistent_mass(system, density), stepper.nodes.uz)
    inertial = _InertialSystem(system, mass, scheme)
    if isinstance(system, ViscoelasticBody):
        system.clock = inertial  # its step constants follow the (possibly cut) time step
    stepper.system = inertial
    stepper.backtracks = MAX_BACKTRACKS
    return inertial
