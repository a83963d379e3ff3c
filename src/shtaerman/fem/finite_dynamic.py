"""Impact of a rigid power-law striker on a rubber half-space at finite strain, in time.

The massless body (density 0): the striker (mass M, depth X, X(0) = 0, X'(0) = v0) obeys
M X'' = -P(X), where P(X) is the force of the static finite-strain contact at depth X
(:mod:`.contact.finite`: Newton with frictionless contact against the indenter in the current
configuration, mixed u-p, any rubber model of :mod:`.rubber`), solved at every step.

Time stepping (:func:`.stepper.march_massless`): the energy-conserving midpoint discrete
gradient on the striker,

    X_{n+1} - X_n = dt (V_n + V_{n+1}) / 2,
    M (V_{n+1} - V_n) = -dt (Pi(X_{n+1}) - Pi(X_n)) / (X_{n+1} - X_n),

with Pi(X) the stored energy of the static contact at depth X (Pi = 0 without contact). It
conserves M V^2 / 2 + Pi(X) exactly at every step, so the restitution is 1 up to the Newton
tolerances, and it is second order. Each step solves the scalar equation in X_{n+1} by a
secant iteration, every evaluation being a static contact solve warm-started from the last
converged state. After the striker leaves (X_{n+1} <= 0) its speed is final. A step whose
contact fails (its Newton, or the secant) is cut in two halves of dt / 2, recursively up to
:data:`.stepper.MAX_STEP_CUTS` times, each half a step of its own with its history committed
(near separation a relaxing body with friction let many stuck nodes go in one step, and the
Newton after that jump stalled at 0.5 mm of the researcher's pad at 50 steps); the run's
``retried`` says how many steps were cut.

The body with inertia (density > 0, :func:`.stepper.march_inertial`): Wood-Bossak-Zienkiewicz
time stepping (rho_inf 0.9 by default; second order) of the body, with its consistent mass less
the normal mass of the contact candidates (:func:`.elasticity.redistribute_normal_mass`: their
u_z follow the indenter quasi-statically, without chatter), the inertial force and its tangent
added to the contact Newton's residual and tangent. The striker's own Bossak equation M ((1 -
a_m) A_{n+1} + a_m A_n) + P(X_{n+1}) = 0 is solved by a secant in X_{n+1}, each evaluation a
contact solve of the body's step. Each step starts from x and X extrapolated linearly in time
(from the last state where that start passes a Gent rubber's limit: near its lock every cut of
the step failed so), each Newton with its loaded candidates kept on the indenter in the first
iterate, and halves an update that inverts an element (damped Newton). A step whose Newton or
secant still fails (near separation the extrapolated start lifts the surface with the leaving
striker) is cut in two halves of dt / 2, recursively up to :data:`.stepper.MAX_STEP_CUTS`
times, each half a Bossak step recorded as a step of its own (the energy account is that of the
smaller steps); a step that converges is unchanged. A step that fails in every cut from a state
squeezing an element beside the striker's tip (J < :data:`.contact.finite.SQUEEZED_J`) raises
:class:`.contact.finite.SqueezedTipError`, which names the element and no time steps (the
elastic z = 8 r^1.3 pad failed so at x/a 1.4-1.6 at every step and mesh tried). No absorbing
layer: the far arc lies ``mesh.domain`` refined radii away, beyond the waves' reach during the
contact; the kinetic energy beyond half its radius at the end is reported. The run stops when
the contact force vanishes with the striker rebounding (separation time from P^(1/q)
extrapolated between steps).

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

from ..guards import (
    MAX_DEPTH_RATIO,
    check_reach,
    check_within_layer,
    depth_ratio,
    reach_velocity,
    warn_outside_validity,
)
from ..theory.contact import PowerLawContact
from ..theory.impact import QuasiStaticValidityWarning, solve_impact
from ..theory.materials import Material, validate_density
from ..theory.profile_impact import ProfileImpactResult, solve_profile_impact
from ..theory.sneddon import Indenter, SneddonContact, contact_law
from ..theory.viscoelastic import PronySeries, elastic_impact
from ..validation import (
    InputError,
    LimitError,
    bound_text,
    validate_poisson,
    validate_positive,
)
from .contact.finite import (
    FINITE_BASE,
    FINITE_MESH,
    MAX_ITERATIONS,
    NEWTON_TOLERANCE,
    NewtonStepper,
    geometric_radius,
    tip_exponent,
)
from .contact.finite_stick import HistoryStepper
from .finite_viscoelastic import ViscoelasticBody
from .hyperelastic import NeoHookean, assemble_hyperelastic
from .impact_limits import FINITE_MIN_STEPS, INERTIA_STEPS, MASSLESS_STEPS
from .impact_run import (
    MAX_STEPS,
    ImpactRun,
    finished_run,
    impact_parameters,
    mesh_counts,
    parabola_peak,
    refined_steps,
    validate_steps,
)
from .mesh import HALF_SPACE, Geometry, MeshSettings, resolved_depths
from .rubber import RubberModel
from .stepper import (
    QuasiStaticBody,
    TimeScheme,
    far_kinetic,
    inertial_system,
    march_inertial,
    march_massless,
)
from .viscoelastic import sizing_impact

__all__ = [
    "FiniteImpactSettings",
    "FiniteImpactSetup",
    "KeptStates",
    "impact_mesh",
    "pad_reach_note",
    "prepare_finite_impact",
]

IMPACT_MESH = replace(FINITE_MESH, axis_size=1e-4)
"""The impact's default mesh, massless or with inertia: FINITE_MESH graded to 1e-4 of the
refined radius at the axis, not 1e-6 (the impact reports no central pressure, and x_max and
P_max move by < 1e-5: benchmarks/FEM_NOTES.md). On the 1e-6 grading a Newton whose contact
set changes at the axis stalls: the first iterates move the u_r of the axis elements by more
than their width and the damped Newton halves its updates to nothing. That happened with
inertia after the turning point. Not 1e-3 (before session 54): a thin pad pressed to x/H ~
0.9 squeezes the elements beside the tip, and the 1e-3 grading's axis element inverts first
(4 mm pad, z = 5 r^1.5, mesh 0.2: the static curve at 3.4 mm, where 1e-4 runs to 3.85 mm;
benchmarks/FEM_NOTES.md, "Axis node cycling"). A bonded or Coulomb indenter's mesh is graded
no finer than :data:`FRICTION_AXIS`."""
FRICTION_AXIS = 1e-3
"""The finest axis grading (of the refined radius) of a bonded or Coulomb impact's default
mesh (:func:`impact_mesh`). Near separation the relaxing surface lags the leaving striker and
the active set lets the stuck nodes at the axis go at once; the finer the axis elements, the
further the first Newton iterates overshoot them: on 1e-6 the researcher's pad failed at 0.5
mm of a 3.5 mm approach, with 8 times the steps too; on 1e-4 a step of it is cut in halves
and it costs 3.3 times the CPU of 1e-3 (z = 2.011 r^1.3 on a 12 mm pad, Prony 0.3:1e-3,
mesh 0.2: 39.6 s against 12.2 s bonded, 37.5 s against 11.5 s Coulomb 0.5, load 5-7)."""
IMPACT_MARGIN = 1.3
"""Refined radius / geometric contact radius at the small-strain x_c (the finite-strain contact
is wider by a few per cent)."""


PAD_DEPTH = "; on a pad, which stops the striker a little sooner than this depth, "
"""The words a pad's reach refusal shares: the depth it names is the half-space's, an upper
bound (with a Prony series the relaxing or the fully relaxed half-space's)."""
PAD_FRICTION_REACH = (
    PAD_DEPTH + "a bonded or Coulomb indenter cannot pass it; "
    "interface='frictionless' runs beyond it with a warning"
)
"""The end of the refusal of a frictional finite-strain impact on a pad beyond the reach."""
PAD_MASSLESS_REACH = (
    PAD_DEPTH + "a massless body (density2=0) cannot pass it; "
    "with inertia (density2=...) interface='frictionless' runs beyond it with a warning"
)
"""The end of the refusal of a massless finite-strain impact on a pad beyond the reach."""


def impact_mesh(friction: float | None) -> MeshSettings:
    """The default mesh of an impact with Coulomb ``friction`` (None, 0: frictionless; inf:
    bonded): :data:`IMPACT_MESH` (read at call time: tests swap in coarse ones), graded at
    the axis no finer than :data:`FRICTION_AXIS` where the indenter holds the surface."""
    if not friction:
        return IMPACT_MESH
    return replace(IMPACT_MESH, axis_size=max(IMPACT_MESH.axis_size, FRICTION_AXIS))


def pad_reach_note(pad: bool, friction: float | None, density: float) -> str | None:
    """The end of the reach refusal (:func:`shtaerman.guards.check_reach`) of a finite-strain
    impact on a ``pad`` (else the half-space: ""), with Coulomb ``friction`` (None, 0:
    frictionless; inf: bonded) and ``density`` (kg/m^3; 0: massless); None where it runs
    beyond the upper reach with a warning (its floor, :data:`.guards.MIN_FINITE_DEPTH_RATIO`,
    holds): the frictionless pad with inertia. A massless body
    follows the static curve, which does not converge beyond the reach (z = 8 r^1.3 on a 12 mm
    pad, 0.12 kg at 1.5 m/s: Newton failed at 2.6 mm of the 5.75 mm after 11 CPU s); a
    frictional contact fails at separation."""
    if not pad:
        return ""
    if density == 0.0:
        return PAD_MASSLESS_REACH
    return PAD_FRICTION_REACH if friction else None


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
        :data:`IMPACT_MESH`.
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
            validate_steps(self.steps, (FINITE_MIN_STEPS, MAX_STEPS))
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

    def resolved(self, density: float, friction: float | None = None) -> FiniteImpactSettings:
        """These settings with the defaults of the massless body (``density`` 0) or of the
        body with inertia filled in, the mesh :func:`impact_mesh` of ``friction``."""
        steps = self.steps
        if steps is None:
            steps = MASSLESS_STEPS if density == 0 else INERTIA_STEPS
        mesh = impact_mesh(friction) if self.mesh is None else self.mesh
        return replace(self, steps=steps, mesh=mesh)

    def refined(self, factor: float) -> FiniteImpactSettings:
        """These (resolved) settings with the mesh size field divided and the time steps
        multiplied by ``factor`` (> 1 refines), as
        :meth:`shtaerman.fem.dynamic_contact.DynamicSettings.refined`."""
        assert self.steps is not None and self.mesh is not None, "resolve the settings first"
        steps = refined_steps(self.steps, factor, (FINITE_MIN_STEPS, MAX_STEPS))
        return replace(self, steps=steps, mesh=self.mesh.refined(factor))


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

    def march(self, snapshot_times: tuple[float, ...] = (), energy_series: bool = True) -> tuple:
        """Step the run, keeping the solution of the step nearest each of ``snapshot_times``
        (s; none with a Prony series, :class:`KeptStates`): the columns, Newton iterations,
        separation time (s; None: the massless elastic body), the kinetic energy beyond half
        the domain radius at the end / (M v0^2 / 2) (nan: massless), the steps cut and the
        kept states (None: no times). ``energy_series``: the linear body's (its energies
        inside R_a); the rubber keeps every step's energies."""
        _, _, rho, mass, velocity, _ = self.inputs
        x_c, t_y, duration, q, _ = self.scales
        dt, stepper = t_y / self.settings.steps, self.stepper
        kept = KeptStates.of(stepper.system, snapshot_times)
        observe = None if kept is None else kept.offer
        if rho == 0.0:
            body = QuasiStaticBody(stepper, dt)
            columns, separation = march_massless(body, mass, velocity, (duration, q), observe)
            return columns, body.iterations, separation, 0.0, body.cuts, kept
        scheme = TimeScheme.bossak(self.settings.spectral_radius, dt)
        inertial = inertial_system(stepper, rho, scheme)
        columns, iterations, separation, last = march_inertial(
            stepper, inertial, (mass, velocity), (x_c, duration, q), observe
        )
        far = far_kinetic(inertial, last.v) / (0.5 * mass * velocity**2)
        return columns, iterations, separation, far, inertial.cuts, kept

    def result(self, marched: tuple, timings: dict[str, float]) -> ImpactRun:
        """The run of ``marched`` (what :meth:`march` returned), ``timings`` its costs (s)."""
        columns, iterations, separation, far, cuts, kept = marched
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
        context.update(relaxes=isinstance(self.stepper.system, ViscoelasticBody), kept=kept)
        if cuts:
            context["retried"] = cut_note(cuts, settings.steps)
        result = _result(columns, mass, context, separation)
        relaxed = getattr(self.stepper.system, "prony", None)
        layer = (result.x_max, self.mesh.get("thickness"))
        g_inf = 1.0 if relaxed is None else relaxed.g_inf
        check_within_layer(indenter, layer, (mass, velocity), x_c, g_inf)
        warn_outside_validity(indenter, result.x_max, None, finite=True)
        return result


class KeptStates:
    """The rubber's solution x = [u (m), p (Pa)] at the step nearest each requested time (s):
    one vector a time, replaced while the steps come nearer (:meth:`offer`, told every
    accepted step)."""

    def __init__(self, system: Any, times: tuple[float, ...]) -> None:
        self.system, self.times = system, tuple(times)
        self.states: dict[float, tuple[float, np.ndarray]] = {}
        """Requested time -> (the step's time (s), its solution)."""

    @classmethod
    def of(cls, system: Any, times: tuple[float, ...]) -> KeptStates | None:
        """The keeper of ``system``'s states at ``times``; None without times, or for a body
        with a Prony series (its relaxed stress is not recovered at the vertices)."""
        return None if not times or isinstance(system, ViscoelasticBody) else cls(system, times)

    def offer(self, t: float, x: np.ndarray) -> None:
        """The step accepted at time ``t`` (s) with solution ``x``: kept where nearer a
        requested time."""
        for wanted in self.times:
            kept = self.states.get(wanted)
            if kept is None or abs(t - wanted) < abs(kept[0] - wanted):
                self.states[wanted] = (t, x.copy())

    def fields(self, wanted: float) -> tuple[float, dict[str, np.ndarray]]:
        """The time (s) of the step kept for ``wanted`` and its vertex fields
        (:meth:`.hyperelastic.HyperelasticSystem.fields`)."""
        actual, x = self.states[wanted]
        return actual, self.system.fields(x)


def cut_note(cuts: int, steps: int) -> str:
    """What a run whose ``cuts`` time steps (of ``steps`` per t_y) were cut in halves says."""
    return f"{cuts} of the {steps} time steps per t_y cut in halves where the contact failed"


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
    exact: ProfileImpactResult | None = None,
    geometry: Geometry = HALF_SPACE,
) -> FiniteImpactSetup:
    """Check, mesh and assemble the impact of a rigid striker on a rubber at finite strain
    (the arguments of :func:`.impact.run_impact`, the body's ``rubber`` default neo-Hookean,
    ``friction`` None or 0 frictionless, ``exact`` a profile's sizing impact when solved
    already, ``geometry`` the body's shape).

    Raises
    ------
    shtaerman.validation.InputError
        Inputs out of range.
    """
    rho, mass, velocity, law = _checked(indenter, half_space, density, mass, velocity)
    settings = (FiniteImpactSettings() if settings is None else settings).resolved(rho, friction)
    q = law.force_exponent
    with warnings.catch_warnings():  # the caller warns of a fast impact beside its results
        warnings.simplefilter("ignore", QuasiStaticValidityWarning)
        if isinstance(law, PowerLawContact):
            quasi = solve_impact(mass, velocity, law)
        elif exact is None:  # a sphere, a table: Sneddon's law, the impact by quadrature
            quasi = solve_profile_impact(mass, velocity, law)
        else:
            quasi = exact
    x_c, t_y = quasi.x_c, quasi.t_y
    if geometry.thickness is not None and geometry.base != "bonded":
        raise InputError(FINITE_BASE, "base")
    unbounded = geometry.thickness is None  # a pad stops the striker short of x_c
    # on a pad x_c bounds the depth from above (the pad is stiffer; z = 8 r^1.3 on a 12 mm
    # pad reached x/a 2.26 against 2.27): a frictional contact does not converge beyond the
    # reach (that case failed at separation after 15 min), a frictionless one warns
    note = pad_reach_note(not unbounded, friction, rho)  # None: the floor alone
    layer = resolved_depths(geometry, indenter, settings.margin)  # a pad's: its remedy's too
    reach = (indenter, law, (mass, velocity), prony)
    x_size, duration = check_finite_reach(reach, note, layer, (x_c, t_y))
    refined = settings.margin * geometric_radius(indenter, x_size)
    refined *= geometry.zone_factor(tip_exponent(indenter))  # 1 on the half-space
    clock = [time.perf_counter()]
    mesh = settings.mesh.build(refined, geometry)
    clock.append(time.perf_counter())
    stepper = _assembled(mesh, indenter, half_space, (rubber, prony, friction), refined)
    clock.append(time.perf_counter())
    counts = (stepper.system.n_dofs, stepper.nodes.radius.size)
    return FiniteImpactSetup(
        stepper=stepper,
        settings=settings,
        inputs=(indenter, half_space, rho, mass, velocity, friction),
        scales=(x_c, t_y, duration, q, law.beta),
        mesh=mesh_counts(mesh, *counts, refined, geometry),
        timings={"mesh": clock[1] - clock[0], "assembly": clock[2] - clock[1]},
    )


def check_finite_reach(
    reach: tuple, note: str | None, layer: tuple | None, scales: tuple[float, float]
) -> tuple[float, float]:
    """:func:`shtaerman.guards.check_reach` of a finite-strain impact, ``reach`` = (indenter,
    its exact law, (mass kg, velocity m/s), Prony series or None), at the elastic x_c (m) of
    ``scales`` = (x_c, t_y s) and then at the relaxed body's deeper quasi-static x_max, which
    bounds a relaxing pad's depth too (``note``, ``layer``: as check_reach takes them). Its
    refusal is that of :func:`check_fully_relaxed` where it refuses. Returns
    :func:`_relaxed_extent`'s depth (m) and longest run (s)."""
    indenter, law, impact, prony = reach
    x_size = None  # the relaxed depth, once sized
    try:
        check_reach(indenter, scales[0], impact, True, note, layer)  # before the sizing
        x_size, duration = _relaxed_extent(law, *impact, prony, scales)
        if x_size > scales[0]:
            check_reach(indenter, x_size, impact, True, note, layer)
    except LimitError:  # beyond the reach: refused in the fully relaxed body's words
        check_fully_relaxed(reach, note, layer, depth=x_size)
        raise
    return x_size, duration


FULLY_RELAXED = (
    "; with a Prony series the depth and the remedies are the fully relaxed body's (modulus "
    "g_inf E*), an upper bound (the relaxing body's own limit was not found)"
)
"""The words a refusal at :func:`check_fully_relaxed`'s depth ends with, before its note,
where :func:`_tight_remedies` finds no root."""
TIGHT = (
    "; with a Prony series the depth is the relaxing body's quasi-static one, which the run checks"
)
"""The words a refusal at :func:`check_fully_relaxed`'s depth ends with, before its note,
naming :func:`_tight_remedies`."""


def check_fully_relaxed(
    reach: tuple,
    note: str | None,
    layer: tuple | None,
    waves: Callable | None = None,
    depth: float | None = None,
) -> None:
    """:func:`shtaerman.guards.check_reach` at the fully relaxed body's quasi-static x_c
    (modulus g_inf E*) of ``reach`` = (indenter, its exact law, (mass kg, velocity m/s), Prony
    series or None), where it lies beyond the finite-strain reach; nothing without relaxation
    or within it (the floor is the elastic x_c's). That x_c, a power law in M v0^2, bounds a
    relaxing body's depth at every velocity. The refusal gives the depth the run checks
    (:func:`relaxed_depth`) and the velocity and the mass at which it reaches the reach
    (:func:`_reach_root`, bracketed by the fully relaxed body's remedies; those scaled from
    the viscoelastic depth were refused in turn: a slower impact relaxes more); where that
    root is not found, the fully relaxed body's depth and remedies. ``note``, ``layer``,
    ``waves``: as check_reach takes them; :data:`TIGHT` or :data:`FULLY_RELAXED` ends the
    refusal before ``note``; ``depth``: the run's depth (m) where sized already (None: here)."""
    indenter, law, impact, prony = reach
    if prony is None or prony.g_inf >= 1.0 or note is None:  # None: no upper reach
        return
    relaxed = replace(law, modulus=law.modulus * prony.g_inf)
    x_relaxed = elastic_impact(*impact, relaxed).x_c
    if depth_ratio(indenter, x_relaxed) > MAX_DEPTH_RATIO:
        tight = _tight_remedies(reach, x_relaxed)
        if tight is None:
            note = FULLY_RELAXED + note
            check_reach(indenter, x_relaxed, impact, True, note, layer, waves)
        if depth is None:  # the run's: its headline and shape
            depth = relaxed_depth(law, *impact, prony)
        check_reach(indenter, depth, impact, True, TIGHT + note, layer, waves, tight)


def relaxed_depth(law: PowerLawContact, mass: float, velocity: float, prony: PronySeries) -> float:
    """The depth (m) a finite-strain impact's run checks against the reach
    (:func:`check_finite_reach`): :func:`_relaxed_extent`'s at the elastic impact's scales."""
    with warnings.catch_warnings():  # of a fast impact: its run's caller warns
        warnings.simplefilter("ignore", QuasiStaticValidityWarning)
        quasi = elastic_impact(mass, velocity, law)
    return _relaxed_extent(law, mass, velocity, prony, (quasi.x_c, quasi.t_y))[0]


def _tight_remedies(reach: tuple, x_relaxed: float) -> tuple[float, float] | None:
    """The mass (kg) and the velocity (m/s) of ``reach`` (:func:`check_fully_relaxed`'s) at
    which :func:`relaxed_depth` reaches the reach, each with the other input kept
    (:func:`_reach_root` from the fully relaxed body's remedies, whose depth ``x_relaxed`` m
    bounds it); None for a profile's law (its impact a quadrature, seconds each) or where a
    root is not found."""
    indenter, law, (mass, velocity), prony = reach
    slow = reach_velocity(indenter, x_relaxed, velocity)  # the fully relaxed body's
    if not isinstance(law, PowerLawContact) or not slow:
        return None
    try:
        fast = _reach_root(
            lambda v: relaxed_depth(law, mass, v, prony), indenter, float(slow), velocity
        )
        light = mass * (float(slow) / velocity) ** 2  # x_c: M v0^2
        heavy = _reach_root(lambda m: relaxed_depth(law, m, velocity, prony), indenter, light, mass)
    except InputError:  # the series relaxes too far within a slower impact
        return None
    return None if fast is None or heavy is None else (heavy, fast)


def _reach_root(
    depth: Callable[[float], float], indenter: Indenter, low: float, high: float
) -> float | None:
    """The largest input (m/s or kg) between ``low`` and ``high`` whose ``depth`` (m) lies
    within :data:`shtaerman.guards.MAX_DEPTH_RATIO` of ``indenter``: bisection in its log
    until both ends show the same three digits rounded down (as a refusal shows them), the
    end that passes; None where ``low`` does not pass or ``high`` does (no root between)."""

    def passes(value: float) -> bool:
        return depth_ratio(indenter, depth(value)) <= MAX_DEPTH_RATIO

    if not passes(low) or passes(high):
        return None
    for _ in range(64):  # a root on a three-digit value: the ends never show the same
        if bound_text(low, "high") == bound_text(high, "high"):
            break
        middle = math.sqrt(low * high)
        low, high = (middle, high) if passes(middle) else (low, middle)
    return low


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
    return rho, mass, velocity, contact_law(indenter, half_space.plane_strain_modulus)


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
        stepper.modified = True  # its factorizations reused across evaluations and steps
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
