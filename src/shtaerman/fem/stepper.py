"""Time stepping of a rigid striker and the elastic body in unilateral contact.

The discrete problem (:class:`ImpactProblem`): the striker (mass M, its downward displacement
X, X(0) = 0, X'(0) = v0) and the body of free dofs x,

    M_h a + D v + K x = -S F,    M X'' = -1^T F,
    g_i = f(r_i) - X - u_z,i >= 0,   F >= 0,   F . g = 0,

with M_h the mass (normal mass taken off the contact candidates), D the damping of the
absorbing layer, F the nodal contact forces (N, pushing the surface down) and S the injection
of the candidate u_z dofs.

Time stepping (:func:`advance`): generalized-alpha (Chung and Hulbert 1993, :class:`TimeScheme`)
applied to the body and the striker alike; Newmark average acceleration is its special case
alpha_m = alpha_f = 0. Both are implicit, unconditionally stable and second order. Each step:
one predictor back-substitution with the effective matrix
K_eff = (1 - a_f) K + (1 - a_f) gamma / (beta dt) D + (1 - a_m) / (beta dt^2) M_h (factorized
once), then the gap at step n+1 is affine in the contact forces (C the surface compliance of
K_eff),

    g = g_pred + (1 - a_f) (C + beta dt^2 / ((1 - a_m) M) 1 1^T) F,

an LCP with a symmetric positive definite matrix solved exactly by
:func:`.contact.complementarity`, and the correction x = x_pred - (1 - a_f) W F with
W = K_eff^-1 S kept dense; C = S^T W. The contact forces enter the alpha-weighted balance like
any load; the gap is enforced at n+1.

A bonded (no slip) or Coulomb striker (``friction`` of :class:`ImpactProblem`: inf or mu >= 0)
adds the candidates' u_r dofs: each step is then the static bonded or Coulomb contact
(:func:`.stick.stick_slip_step`) against the effective stiffness with the step's load,
A = (1 - a_f) (S'^T K_eff^-1 S' + the striker's term on the u_z block), S' injecting u_z and
u_r, reach the clearance f - X_pred - u_z,pred and radial offset u_r,pred; the stuck radii and
slip directions are committed at the end of the step. The shear enters the alpha-weighted
balance like the normal forces.

A viscoelastic body (:mod:`.viscoelastic`) replaces K x by its internal force: K at the
step's effective shear modulus times x plus the history force of its Prony branches, which
enters the predictor as a load.

Energy bookkeeping (:func:`march`): striker and body kinetic energy, strain energy (stored), the
work absorbed by the layer (by the midpoint velocity; exact for Newmark), the energy dissipated
by a viscoelastic body, the work dissipated by slip at the contact (-T . du_r of the shear T
at step n+1 over the nodes sliding then, mu F |du_r| >= 0), and the rest as the scheme's
numerical dissipation, of which the contact
term -1/2 (F_n + F_{n+1}) . (g_{n+1} - g_n) is computed separately (for Newmark the two agree
to round-off).

The rubber at finite strain (:mod:`.finite_dynamic`, whose docstring states the schemes) steps
here too: the massless body by the discrete gradient of its stored energy, or the trapezoidal
rule on the contact force where the body relaxes or the contact has friction
(:func:`march_massless`, a static contact of :class:`QuasiStaticBody` per evaluation of the
striker's step equation); the body with inertia by the Wood-Bossak-Zienkiewicz scheme,
:meth:`TimeScheme.bossak` (generalized-alpha with alpha_f = 0), each step a contact Newton of
the body with its inertial terms (:func:`inertial_system`) inside a secant on the striker's
equation (:func:`march_inertial`). Either cuts a failing step in halves.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass, field, replace
from functools import cached_property, partial
from typing import TYPE_CHECKING, Any

import numpy as np
import scipy.sparse as sp
from threadpoolctl import threadpool_limits

from ..guards import LOCKED, MAX_DEPTH_RATIO, depth_ratio, reach_velocity
from ..validation import InputError, NumericalFailureError
from .contact.constraints import (
    EDGE_MARGIN,
    ContactOutgrowsMeshError,
    central_pressure,
    edge_radius,
    in_halves,
)
from .contact.finite import NewtonStepper, SqueezedTipError, extrapolate, squeeze_note
from .contact.finite_stick import HistoryStepper
from .contact.linear import complementarity, recover_pressure
from .contact.stick import CoupledCompliance, StickState, stick_slip_step
from .elasticity import ElasticSystem, consistent_mass, redistribute_normal_mass
from .finite_viscoelastic import ViscoelasticBody
from .hyperelastic import NewtonError
from .impact_run import march_steps
from .rubber import GentLimitError, GentLockError, gent_locks
from .solver import Factorization

if TYPE_CHECKING:
    from .viscoelastic import ShearMemory, ViscoelasticShear

__all__ = [
    "ContactCandidates",
    "ContactEdgeReachedError",
    "ImpactHistory",
    "ImpactProblem",
    "ImpactState",
    "QuasiStaticBody",
    "Striker",
    "TimeScheme",
    "advance",
    "far_kinetic",
    "inertial_system",
    "march",
    "march_inertial",
    "march_massless",
]

ENERGY_NAMES = (
    "striker_kinetic",
    "body_kinetic",
    "strain",
    "absorbed",
    "numerical",
    "contact_term",
    "inner",
    "dissipated",
    "inner_kinetic",
    "slip",
)
"""Keys of :attr:`ImpactHistory.energies`, in J."""
UNSTABLE_BALANCE = 1e-3
"""|numerical energy| / (M v0^2 / 2) beyond which a contact that spreads to the edge of the
refined zone is blamed on the time stepping, not on the zone."""
RUNAWAY_BALANCE = 10.0
"""|numerical energy| / (M v0^2 / 2) at which a run stops: ten times the energy it was given
is no longer a resolution error but a time stepping gone unstable."""


class ContactEdgeReachedError(InputError):
    """The contact spread to the last candidates: the refined zone is too small."""


@dataclass(frozen=True)
class TimeScheme:
    """Generalized-alpha parameters and the time step.

    Attributes
    ----------
    dt : float
        Time step in s.
    alpha_m, alpha_f, beta, gamma : float
        The scheme's weights (Newmark average acceleration: 0, 0, 1/4, 1/2).
    """

    dt: float
    alpha_m: float
    alpha_f: float
    beta: float
    gamma: float

    @classmethod
    def generalized_alpha(cls, spectral_radius: float | None, dt: float) -> TimeScheme:
        """Chung and Hulbert's scheme with high frequencies damped to ``spectral_radius``.

        alpha_m = (2 rho_inf - 1)/(rho_inf + 1), alpha_f = rho_inf/(rho_inf + 1),
        gamma = 1/2 - alpha_m + alpha_f, beta = (1 - alpha_m + alpha_f)^2 / 4. ``None``:
        Newmark average acceleration (energy-conserving, no damping).
        """
        if spectral_radius is None:
            return cls(dt, 0.0, 0.0, 0.25, 0.5)
        rho = float(spectral_radius)
        alpha_m = (2.0 * rho - 1.0) / (rho + 1.0)
        alpha_f = rho / (rho + 1.0)
        beta = 0.25 * (1.0 - alpha_m + alpha_f) ** 2
        return cls(dt, alpha_m, alpha_f, beta, 0.5 - alpha_m + alpha_f)

    @classmethod
    def bossak(cls, spectral_radius: float, dt: float) -> TimeScheme:
        """Wood, Bossak and Zienkiewicz's case of the scheme: alpha_f = 0 (the internal force at
        the step's end, as a nonlinear body wants), alpha_m = (rho_inf - 1)/(rho_inf + 1), the
        same gamma and beta (second order; 1 is the trapezoidal rule)."""
        alpha_m = (float(spectral_radius) - 1.0) / (float(spectral_radius) + 1.0)
        return cls(dt, alpha_m, 0.0, 0.25 * (1.0 - alpha_m) ** 2, 0.5 - alpha_m)


@dataclass(frozen=True)
class Striker:
    """The rigid striker: mass M in kg and impact velocity v0 in m/s (downward)."""

    mass: float
    velocity: float

    @property
    def kinetic_energy(self) -> float:
        """M v0^2 / 2 in J."""
        return 0.5 * self.mass * self.velocity**2


@dataclass(frozen=True, eq=False)
class ContactCandidates:
    """Surface nodes that may touch, by increasing radius.

    Attributes
    ----------
    dofs : numpy.ndarray
        Their u_z dofs.
    position : numpy.ndarray
        Index of those dofs among the free dofs.
    radius : numpy.ndarray
        r_i in m.
    profile : numpy.ndarray
        Striker profile f(r_i) in m.
    surface_factor : tuple
        :func:`.contact.mass_factor` of their surface matrix (pressure recovery).
    """

    dofs: np.ndarray
    position: np.ndarray
    radius: np.ndarray
    profile: np.ndarray
    surface_factor: tuple = field(repr=False)


@dataclass(frozen=True, eq=False)
class ImpactProblem:
    """The discretized impact, everything factorized: what :func:`advance` needs.

    Attributes
    ----------
    system : ElasticSystem
        Stiffness K (``system.matrix``) and the dof layout.
    free : numpy.ndarray
        Free (unclamped) dofs.
    candidates : ContactCandidates
    striker : Striker
    scheme : TimeScheme
    body_mass, damping : scipy.sparse.csr_matrix
        M_h (kg) and D (kg/s) on all dofs.
    inner_stiffness, inner_mass : scipy.sparse.csr_matrix
        K and M_h over the elements inside the monitor radius (energy inside it).
    factorization : Factorization
        Of K_eff on the free dofs.
    correction : numpy.ndarray
        W = K_eff^-1 S (m/N), free dofs x candidates, column-major.
    lcp_matrix : numpy.ndarray
        (1 - a_f) (C + beta dt^2 / ((1 - a_m) M) 1 1^T) in m/N.
    material : ViscoelasticShear or None
        The body's Prony shear (its stiffness at G_eff is the K of K_eff); None: elastic.
    friction : float or None
        Coulomb coefficient mu >= 0 of the striker's surface (inf: bonded, no slip); None:
        frictionless (the LCP above).
    coupled : CoupledCompliance or None
        With ``friction``: A (m/N) on the candidates' u_z and u_r (module docstring).
    radial_correction : numpy.ndarray or None
        With ``friction``: K_eff^-1 at the radial dofs of ``coupled`` (m/N), free dofs x
        radial dofs, column-major.
    """

    system: ElasticSystem = field(repr=False)
    free: np.ndarray = field(repr=False)
    candidates: ContactCandidates
    striker: Striker
    scheme: TimeScheme
    body_mass: sp.csr_matrix = field(repr=False)
    damping: sp.csr_matrix = field(repr=False)
    inner_stiffness: sp.csr_matrix = field(repr=False)
    inner_mass: sp.csr_matrix = field(repr=False)
    factorization: Factorization = field(repr=False)
    correction: np.ndarray = field(repr=False)
    lcp_matrix: np.ndarray = field(repr=False)
    material: ViscoelasticShear | None = field(default=None, repr=False)
    friction: float | None = None
    coupled: CoupledCompliance | None = field(default=None, repr=False)
    radial_correction: np.ndarray | None = field(default=None, repr=False)

    @cached_property
    def radial_position(self) -> np.ndarray:
        """Index of the radial dofs of ``coupled`` among the free dofs."""
        assert self.coupled is not None
        return np.searchsorted(self.free, self.coupled.radial_dofs)

    @cached_property
    def massive(self) -> np.ndarray:
        """Dofs that carry mass (the others get no velocity or acceleration)."""
        return self.body_mass.diagonal() > 0

    @cached_property
    def massless(self) -> np.ndarray:
        """Indices of the dofs without mass."""
        return np.flatnonzero(~self.massive)

    @cached_property
    def damped(self) -> bool:
        """Whether there is a layer."""
        return self.damping.nnz > 0


@dataclass(frozen=True, eq=False)
class ImpactState:
    """The state after ``step`` time steps (SI units).

    Attributes
    ----------
    step : int
    x, v, a : numpy.ndarray
        Body displacement (m), velocity (m/s), acceleration (m/s^2); pressure dofs in Pa.
    stiffness_x : numpy.ndarray
        The internal force in N: K x (viscoelastic: with the shear's history force).
    striker_x, striker_v, striker_a : float
        Striker displacement X (m), velocity (m/s), acceleration (m/s^2), downward.
    forces, gap : numpy.ndarray
        Contact forces F (N) and gaps g (m) at the candidates.
    absorbed : float
        Work absorbed by the layer so far, J.
    contact_term : float
        Trapezoidal contact work so far, J.
    memory : ShearMemory or None
        The viscoelastic shear's internal variables (None: elastic body).
    contact : StickState or None
        A bonded or Coulomb striker's contact (stuck radii, slip, shear); None: frictionless.
    slip_heat : float
        Work dissipated by slip so far, J.
    """

    step: int
    x: np.ndarray = field(repr=False)
    v: np.ndarray = field(repr=False)
    a: np.ndarray = field(repr=False)
    stiffness_x: np.ndarray = field(repr=False)
    striker_x: float
    striker_v: float
    striker_a: float
    forces: np.ndarray = field(repr=False)
    gap: np.ndarray = field(repr=False)
    absorbed: float
    contact_term: float
    memory: ShearMemory | None = field(default=None, repr=False)
    contact: StickState | None = field(default=None, repr=False)
    slip_heat: float = 0.0

    @classmethod
    def first_touch(cls, problem: ImpactProblem) -> ImpactState:
        """At rest, the striker touching the surface at v0."""
        n = problem.system.n_dofs
        return cls(
            step=0,
            x=np.zeros(n),
            v=np.zeros(n),
            a=np.zeros(n),
            stiffness_x=np.zeros(n),
            striker_x=0.0,
            striker_v=problem.striker.velocity,
            striker_a=0.0,
            forces=np.zeros(problem.candidates.position.size),
            gap=problem.candidates.profile.copy(),
            absorbed=0.0,
            contact_term=0.0,
            memory=None if problem.material is None else problem.material.first_memory(),
            contact=None
            if problem.friction is None
            else StickState.untouched(problem.candidates.profile),
        )

    def time(self, scheme: TimeScheme) -> float:
        """t = step dt in s."""
        return self.step * scheme.dt


def _predictor(problem: ImpactProblem, state: ImpactState) -> tuple[np.ndarray, np.ndarray]:
    """x_hat (the explicit part, all dofs) and x_pred (the step without new contact forces)
    on the free dofs."""
    alpha_m, alpha_f = problem.scheme.alpha_m, problem.scheme.alpha_f
    beta, gamma, dt = problem.scheme.beta, problem.scheme.gamma, problem.scheme.dt
    x, v, a = state.x, state.v, state.a
    x_hat = x + dt * v + dt**2 * (0.5 - beta) * a
    rhs = np.zeros(x.size)
    if problem.body_mass.nnz:  # massless: none (1/dt^2 overflows where dt^2 underflows)
        rhs = problem.body_mass @ ((1.0 - alpha_m) / (beta * dt**2) * x_hat - alpha_m * a)
    if problem.damped:
        damping = problem.damping
        rhs += (1.0 - alpha_f) * (
            damping @ (gamma / (beta * dt) * x_hat - v - dt * (1 - gamma) * a)
        ) - alpha_f * (damping @ v)
    if state.memory is not None:  # the shear's history, a load of the step
        rhs -= (1.0 - alpha_f) * state.memory.force
    if alpha_f:
        load = state.stiffness_x.copy()  # K x_n
        load[problem.candidates.dofs] += state.forces
        if state.contact is not None and state.contact.shear is not None:
            load[problem.coupled.radial_dofs] -= state.contact.shear
        load *= alpha_f
        rhs -= load
    return x_hat, problem.factorization.solve(rhs[problem.free])


def _contact(
    problem: ImpactProblem, state: ImpactState, x_pred: np.ndarray, big_pred: float
) -> tuple[np.ndarray, np.ndarray]:
    """The new contact forces and x_new = x_pred - (1 - alpha_f) W F, both on the free dofs
    (``x_pred`` is corrected in place).

    Raises
    ------
    shtaerman.validation.InputError
        If the contact reaches the edge of the candidates.
    """
    candidates = problem.candidates
    clearance = candidates.profile - big_pred - x_pred[candidates.position]
    new_forces, _, _ = complementarity(problem.lcp_matrix, clearance)
    active = np.flatnonzero(new_forces > 0)
    x_new = x_pred
    if active.size:
        reach = active[-1] + 1  # contact is a disc: the candidates up to its edge
        weight = 1.0 - problem.scheme.alpha_f
        x_new -= weight * (problem.correction[:, :reach] @ new_forces[:reach])
        _check_edge(problem, state, active[-1])
    return new_forces, x_new


def _check_edge(problem: ImpactProblem, state: ImpactState, last: int) -> None:
    """Raise ContactEdgeReachedError if candidate ``last`` in contact is within EDGE_MARGIN
    of the edge of the refined zone."""
    r_c = problem.candidates.radius
    if last + EDGE_MARGIN >= r_c.size:
        t = (state.step + 1) * problem.scheme.dt
        raise ContactEdgeReachedError(
            f"the contact reached r = {r_c[last]:.4g} m at t = {t:.4g} s, the "
            f"edge of the refined zone ({r_c[-1]:.4g} m); increase the margin (mesh_margin=...)"
        )


def _stick_contact(
    problem: ImpactProblem, state: ImpactState, x_pred: np.ndarray, big_pred: float
) -> StickState:
    """The bonded or Coulomb contact of the step (``x_pred`` corrected in place to x_new on
    the free dofs, as :func:`_contact` does).

    Raises
    ------
    shtaerman.validation.NumericalFailureError
        If the stick and slip sets do not settle.
    """
    candidates, coupled = problem.candidates, problem.coupled
    assert coupled is not None and state.contact is not None
    reach = candidates.profile - big_pred - x_pred[candidates.position]
    offset = x_pred[problem.radial_position]
    contact = stick_slip_step(coupled, reach, offset, state.contact, problem.friction)
    if contact is None:
        t = (state.step + 1) * problem.scheme.dt
        raise NumericalFailureError(
            f"the contact's stick and slip did not settle at t = {t:.4g} s; take more time "
            "steps (time_steps=...) or a finer mesh (mesh_size=...)"
        )
    active = np.flatnonzero(contact.active)
    if active.size:
        reach_to = active[-1] + 1  # contact is a disc: the candidates up to its edge
        radial_to = int(np.searchsorted(coupled.radial_node, reach_to))
        weight = 1.0 - problem.scheme.alpha_f
        x_pred -= weight * (problem.correction[:, :reach_to] @ contact.forces[:reach_to])
        x_pred += weight * (problem.radial_correction[:, :radial_to] @ contact.shear[:radial_to])
        _check_edge(problem, state, active[-1])
    return contact


def _slip_heat(problem: ImpactProblem, state: ImpactState, contact: StickState | None) -> float:
    """The work dissipated by slip up to the new step, J: mu F |slip| of every node sliding at
    its end (the Coulomb law is imposed there), the slip counted from where the node was at
    the last step, or from where it touched in this one; a stuck node does no work."""
    if contact is None:
        return state.slip_heat
    node = problem.coupled.radial_node
    sliding = contact.slip[node] != 0
    start = np.where(state.contact.active, state.contact.radial, contact.held)[node]
    slip = (contact.radial[node] - start)[sliding]
    return state.slip_heat - float(contact.shear[sliding] @ slip)


def advance(problem: ImpactProblem, state: ImpactState) -> ImpactState:
    """One time step: predictor, contact LCP, correction, striker, layer and contact work.

    :func:`march` steps under one BLAS thread (``threadpoolctl.threadpool_limits``); stepping
    by hand under the same limit reproduces it to the last bit.

    Raises
    ------
    shtaerman.validation.InputError
        If the contact reaches the edge of the candidates (the refined zone).
    """
    alpha_m, alpha_f = problem.scheme.alpha_m, problem.scheme.alpha_f
    beta, gamma, dt = problem.scheme.beta, problem.scheme.gamma, problem.scheme.dt
    striker, forces = problem.striker.mass, state.forces
    big_x, big_v, big_a = state.striker_x, state.striker_v, state.striker_a
    x_hat, x_pred = _predictor(problem, state)
    big_hat = big_x + dt * big_v + dt**2 * (0.5 - beta) * big_a
    big_pred = big_hat - beta * dt**2 * (alpha_f * forces.sum() + alpha_m * striker * big_a) / (
        (1.0 - alpha_m) * striker
    )
    contact = None
    if problem.friction is None:
        new_forces, x_free = _contact(problem, state, x_pred, big_pred)
    else:
        contact = _stick_contact(problem, state, x_pred, big_pred)
        new_forces, x_free = contact.forces, x_pred
    x_new = np.zeros(problem.system.n_dofs)
    x_new[problem.free] = x_free
    total = float(new_forces.sum())
    big_a_new = -((1.0 - alpha_f) * total + alpha_f * forces.sum() + alpha_m * striker * big_a) / (
        (1.0 - alpha_m) * striker
    )
    big_new = big_hat + beta * dt**2 * big_a_new
    big_v_new = big_v + dt * ((1.0 - gamma) * big_a + gamma * big_a_new)
    a_new, massive = np.zeros(x_new.size), problem.massive  # the others have none
    a_new[massive] = (x_new[massive] - x_hat[massive]) / (beta * dt**2)
    v_new = state.v + dt * ((1.0 - gamma) * state.a + gamma * a_new)
    v_new[problem.massless] = 0.0
    absorbed = state.absorbed
    if problem.damped:  # midpoint velocity: exact for Newmark (dt/4 |v_n + v_n+1|_D^2)
        v_sum = state.v + v_new
        absorbed += 0.25 * dt * float(v_sum @ (problem.damping @ v_sum))
    candidates = problem.candidates
    new_gap = candidates.profile - big_new - x_free[candidates.position]
    contact_term = state.contact_term - 0.5 * float((forces + new_forces) @ (new_gap - state.gap))
    if problem.material is None:
        stiffness_x, memory = problem.system.matrix @ x_new, None
    else:
        stiffness_x, memory = problem.material.advance(state.memory, x_new)
    return ImpactState(
        step=state.step + 1,
        x=x_new,
        v=v_new,
        a=a_new,
        stiffness_x=stiffness_x,
        striker_x=big_new,
        striker_v=big_v_new,
        striker_a=big_a_new,
        forces=new_forces,
        gap=new_gap,
        absorbed=absorbed,
        contact_term=contact_term,
        memory=memory,
        contact=contact,
        slip_heat=_slip_heat(problem, state, contact),
    )


@dataclass(frozen=True, eq=False)
class ImpactHistory:
    """Per-step histories of a run (SI units), step 0 (first touch) included.

    Attributes
    ----------
    t, x, v, force, contact_radius, central_pressure : numpy.ndarray
        Time (s), striker displacement (m) and velocity (m/s, downward), contact force (N),
        contact radius (m, 0 without contact), pressure at the axis (Pa).
    energies : dict of str to numpy.ndarray
        :data:`ENERGY_NAMES` per step, J.
    snapshots : dict
        Requested time -> (actual time s, x, v).
    t_contact : float
        Separation time in s (nan if the striker never separated).
    memories : dict
        Requested time -> the viscoelastic shear's memory at that snapshot (None: elastic).
    """

    t: np.ndarray
    x: np.ndarray
    v: np.ndarray
    force: np.ndarray
    contact_radius: np.ndarray
    central_pressure: np.ndarray
    energies: dict[str, np.ndarray]
    snapshots: dict[float, tuple[float, np.ndarray, np.ndarray]]
    t_contact: float
    memories: dict[float, ShearMemory | None] = field(default_factory=dict)

    @property
    def separated(self) -> bool:
        """Whether the striker left the surface during the run."""
        return not math.isnan(self.t_contact)


def _observe(problem: ImpactProblem, state: ImpactState, inner: bool = True) -> tuple[tuple, tuple]:
    """(t, X, X', P, a, p0) and the energies (:data:`ENERGY_NAMES`) of a state; without
    ``inner``, those inside R_a (``inner``, ``inner_kinetic``) nan (:func:`_inner_energies`)."""
    r_c = problem.candidates.radius
    radius = pressure0 = 0.0
    if np.any(state.forces > 0):
        radius = edge_radius(r_c, state.forces, np.maximum(state.gap, 0.0))
        pressure = recover_pressure(problem.candidates.surface_factor, state.forces)
        pressure0 = central_pressure(r_c, pressure, radius)
    total = float(state.forces.sum())
    row = (state.time(problem.scheme), state.striker_x, state.striker_v, total, radius, pressure0)
    x, v = state.x, state.v
    kinetic = 0.5 * float(v @ (problem.body_mass @ v))
    strain = 0.5 * float(x @ state.stiffness_x)
    inner_energy, inner_kinetic = _inner_energies(problem, state) if inner else (math.nan,) * 2
    dissipated = 0.0
    if state.memory is not None:  # viscoelastic: the branches' springs store, their dashpots heat
        strain = problem.material.stored_energy(state.memory, x)
        dissipated = state.memory.dissipated
    striker_kinetic = 0.5 * problem.striker.mass * state.striker_v**2
    numerical = problem.striker.kinetic_energy - striker_kinetic - kinetic - strain - state.absorbed
    numerical -= dissipated
    numerical -= state.slip_heat
    energies = (striker_kinetic, kinetic, strain, state.absorbed, numerical, state.contact_term)
    return row, (*energies, inner_energy, dissipated, inner_kinetic, state.slip_heat)


def _inner_energies(problem: ImpactProblem, state: ImpactState) -> tuple[float, float]:
    """The body's energy inside R_a (J: kinetic and strain, less a viscoelastic body's relaxed
    part) and its kinetic part, of a state: two sparse products, ~8 % of a time step."""
    x, v = state.x, state.v
    inner_kinetic = 0.5 * float(v @ (problem.inner_mass @ v))
    inner = inner_kinetic + 0.5 * float(x @ (problem.inner_stiffness @ x))
    if state.memory is not None:
        inner -= problem.material.inner_relaxed(state.memory)
    return inner, inner_kinetic


def march(
    problem: ImpactProblem,
    *,
    duration: float,
    tail_time: float,
    force_exponent: float,
    snapshot_times: tuple[float, ...] = (),
    energy_series: bool = True,
    after_contact: bool = False,
) -> ImpactHistory:
    """Step from first touch until ``tail_time`` s after separation, or ``duration`` s.

    Parameters
    ----------
    problem : ImpactProblem
    duration : float
        Longest run in s (the steps are ceil(duration / dt)).
    tail_time : float
        Stepping after separation, s.
    force_exponent : float
        q of P ~ x^q, for the separation time between steps.
    snapshot_times : tuple of float
        Times in s at which to keep the state (nearest step; the last state beyond the run).
    energy_series : bool
        Whether the energies inside R_a (``inner``, ``inner_kinetic``) are computed at every
        step (a history's energies.csv) or at the last one only (nan before it: what the
        reflected energy and the loss split use).
    after_contact : bool
        Without the series, whether those energies are computed from the contact's end on
        too (what a layer's reflected energy uses).

    Raises
    ------
    ContactEdgeReachedError
        If the contact reaches the edge of the candidates with the energy balanced.
    shtaerman.validation.NumericalFailureError
        If it gets there after the energy balance drifted (the stepping became unstable).
    """
    dt, energy0 = problem.scheme.dt, problem.striker.kinetic_energy
    state, touched, numerical = ImpactState.first_touch(problem), False, 0.0
    left = False
    snapshots: dict[float, tuple[float, np.ndarray, np.ndarray]] = {}
    memories: dict[float, ShearMemory | None] = {}
    wanted = sorted(float(s) for s in snapshot_times)
    max_steps = math.ceil(duration / dt)

    def step() -> list[tuple[tuple, bool]]:
        nonlocal state, touched, numerical, left
        if state.step >= max_steps:
            return []
        try:
            state = advance(problem, state)
        except ContactEdgeReachedError as edge:
            _blame_the_stepping(numerical / energy0, state, problem, edge)
            raise
        t = state.time(problem.scheme)
        left = left or (after_contact and touched and not np.any(state.forces > 0))
        row, energies = _observe(problem, state, energy_series or left)
        numerical = energies[4]
        if not abs(numerical) <= RUNAWAY_BALANCE * energy0:  # NaN included
            raise NumericalFailureError(_runaway(numerical / energy0, state, problem))
        while wanted and wanted[0] <= t + 0.5 * dt:
            memories[wanted[0]] = state.memory
            snapshots[wanted.pop(0)] = (t, state.x.copy(), state.v.copy())
        touched = touched or bool(np.any(state.forces > 0))
        return [((*row, *energies), touched and row[3] == 0.0)]

    first = (0.0, 0.0, problem.striker.velocity, 0.0, 0.0, 0.0, energy0)
    first += (0.0,) * (len(ENERGY_NAMES) - 1)
    with threadpool_limits(limits=1, user_api="blas"):  # the products' rounding: one thread
        table, t_contact = march_steps(step, first, force_exponent, (tail_time, 1e-12 * dt))
        if not energy_series and state.step:  # the last row's, of the last state
            inner = ENERGY_NAMES.index("inner"), ENERGY_NAMES.index("inner_kinetic")
            table[-1, [6 + k for k in inner]] = _inner_energies(problem, state)
    for s in wanted:  # asked beyond the run: the last state
        snapshots[s], memories[s] = (
            (state.time(problem.scheme), state.x.copy(), state.v.copy()),
            state.memory,
        )
    return ImpactHistory(
        *(table[:, k] for k in range(6)),
        energies={name: table[:, 6 + k] for k, name in enumerate(ENERGY_NAMES)},
        snapshots=snapshots,
        t_contact=t_contact,
        memories=memories,
    )


def _blame_the_stepping(
    balance: float, state: ImpactState, problem: ImpactProblem, edge: ContactEdgeReachedError
) -> None:
    """Raise NumericalFailureError if the energy had drifted before the contact reached the edge."""
    if abs(balance) <= UNSTABLE_BALANCE:
        return
    where = " before the contact spread to the edge of the refined zone"
    raise NumericalFailureError(_unstable(balance, state, problem, where)) from edge


SMALL_STEP_CURE = (
    "use fewer time steps (time_steps=...) or a finer mesh with them (mesh_size=...): the "
    "contact stepping needs c_s dt not far below the surface element size"
)
"""What a message of an unstable contact stepping tells the user to change."""


def _runaway(balance: float, state: ImpactState, problem: ImpactProblem) -> str:
    """The one-line message of a run whose energy balance is off by the initial energy."""
    return (
        f"the energy balance is off by {abs(balance):.1e} of M v0^2/2 at t = "
        f"{state.time(problem.scheme):.4g} s: either the time stepping became unstable "
        f"(dt = {problem.scheme.dt:.3g} s is too small for this mesh: {SMALL_STEP_CURE}) or "
        "the mesh and time steps sized from the quasi-static impact do not resolve this impact"
    )


def _unstable(balance: float, state: ImpactState, problem: ImpactProblem, where: str) -> str:
    """The one-line message of an unstable run."""
    return (
        f"the time stepping became unstable at t = {state.time(problem.scheme):.4g} s (energy "
        f"balance off by {abs(balance):.1e} of M v0^2/2{where}): dt = {problem.scheme.dt:.3g} s "
        f"with this scheme does not keep the contact stable; {SMALL_STEP_CURE}"
    )


# --- the finite-strain body: massless, and with inertia (Bossak) ----------------------------------

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
"""Halvings of a time step of the finite-strain body whose Newton or secant failed."""
MAX_BACKTRACKS = 10
"""Halvings of a Newton update of the body with inertia that inverts an element (damped Newton)."""


@dataclass
class _State:
    """A converged static contact at depth X (m): solution, multipliers, force (N), stored
    energy and, for a relaxing body at a committed step, the dissipated energy (J); a Gent
    rubber's stretch (I1bar - 3) / Jm."""

    depth: float
    x: np.ndarray
    lam: np.ndarray
    force: float
    energy: float
    dissipated: float = 0.0
    stretch: float = 0.0


class QuasiStaticBody:
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
        self.cuts = 0  # time steps cut in halves (:func:`march_massless`)
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
        except GentLockError:  # the rubber's limit, an input: --gent-limit
            raise
        except NewtonError as error:  # the run's numerics, not its input
            last = self.history[-1]  # the undeformed start squeezes nothing
            squeezed = None
            if last is not self.zero:
                squeezed = squeeze_note(self.stepper.system, last.x, "more time_steps=...")
            remedy = "a lower velocity=... (on a pad: a thicker thickness=...)"
            raise NumericalFailureError(
                f"the finite-strain contact failed at depth {depth:g} m ({error}); "
                + (
                    f"{squeezed}: {remedy}"
                    if squeezed
                    else "the massless body follows the static contact curve, which does not "
                    "converge beyond it at these settings (more time_steps=... do not move "
                    f"it): {remedy}, or a finer mesh_size=... where the mesh is the cause"
                )
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

    def _newton(self, depth: float) -> tuple[np.ndarray, np.ndarray, int, list[float]]:
        """The stepper's solve at ``depth`` (m) from x and lambda extrapolated from the last two
        states; where it fails, from the last state itself. Near separation a relaxing body
        with friction turns, and the extrapolation past the turn can start the Newton from a
        folded surface (the audit30 Mooney-Rivlin pad at 100 steps: every cut of the step
        failed, 'an element inverted', until this start)."""
        states = [(state.depth, state.x, state.lam) for state in self.history]
        # a relaxing body's corrections measured on the deepest depth (it unloads to X <= 0)
        scale = max(depth, self.deepest) if self.relaxing else None
        try:
            return self.stepper.solve(depth, *extrapolate(states, depth), scale)
        except NewtonError:
            if len(states) < 2:  # its guess was the last state
                raise
        return self.stepper.solve(depth, states[-1][1], states[-1][2], scale)

    def _solve(self, depth: float, halvings: int) -> _State:
        try:
            x, lam, iterations, _ = self._newton(depth)
        except NewtonError as error:
            last = self.history[-1]
            step = (last.depth, depth)
            locked = gent_locks(error, self.stepper.system, last.x, step, last=halvings == 0)
            if locked is not None or halvings == 0:
                raise (locked or error) from None
            middle = 0.5 * (depth + last.depth)
            if middle <= 0.0 and not self.relaxing:
                raise
            self.accept(self._solve(middle, halvings - 1))
            return self._solve(depth, halvings - 1)
        self.iterations += iterations
        energy = self.stepper.system.energy(x)
        return _State(depth, x, lam, float(lam.sum()), energy, stretch=self.stepper.stretch)


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
    body: QuasiStaticBody,
    state: _State,
    striker: tuple[float, float],
    scales: tuple[float, float],
    gradient: Any = _discrete_gradient,
) -> tuple[_State, float]:
    """One step X_{n+1} - X_n = dt (V_n + V_{n+1}) / 2, M (V_{n+1} - V_n) = -dt G: the new
    state and velocity. ``striker``: V_n (m/s), M (kg) and v0 (m/s); ``scales``: dt (s) and
    the contact stiffness guess of the secant's first slope k (N/m); ``gradient``: G (N) of the
    states at the step's ends, the discrete gradient of the stored energy or the trapezoidal
    rule's mean force."""
    (v, mass, v0), (dt, k) = striker, scales

    def residual(depth: float) -> tuple[float, _State]:
        trial = body.at(depth)
        return 2.0 * mass * ((depth - state.depth) / dt - v) / dt + gradient(state, trial), trial

    scale = mass * v0 / dt  # not V_n: near the turning point it went to 0, and the tolerance
    # below the contact solves' noise (0.7 kg at 1e-14 m/s: 434 solves, steps cut; now 224)
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


def _stiffness(a: _State, b: _State, k: float) -> float:
    """The contact stiffness guess (N/m) of the next step's secant after the step a -> b
    (``k`` kept where a depth is 0 or the depths coincide)."""
    if b.depth > 0 and a.depth > 0 and b.depth != a.depth:
        return max((b.force - a.force) / (b.depth - a.depth), 0.0)
    return k


def _ended(piece: tuple) -> bool:
    """Whether the massless impact is over at ``piece`` = (state, V (m/s), ...): no force with
    the striker rebounding, or X back to 0."""
    state, v = piece[:2]
    return (state.force == 0.0 and v < 0.0) or state.depth <= 0.0


def _massless_step(
    body: QuasiStaticBody, striker: tuple[float, float], gradient: Any, start: tuple
) -> list[tuple[_State, float, float, float]]:
    """One time step of :func:`_step` of ``body.dt`` (s) from ``start`` = (state, V_n (m/s),
    k (N/m), ...) of the ``striker`` (M kg, v0 m/s), committed: [(state, V, k, dt)]. A failed
    step leaves the body as it was."""
    state, v, k = start[:3]
    kept, dt = body.history, body.dt
    try:
        new, speed = _step(body, state, (v, *striker), (dt, k), gradient)
    except NumericalFailureError:
        body.history = kept  # without the failed step's intermediate states
        if body.frictional:
            body.stepper.warm = {}  # solved for a step of another length
        raise
    new = body.commit(new)
    if new.depth > 0:
        body.accept(new)
    return [(new, speed, _stiffness(state, new, k), dt)]


def _in_halves(clock: Any, one: Callable[[Any], list], start: Any, ended: Callable) -> list:
    """``one(start)``: the states one time step of ``clock.dt`` (s) reaches, committed, or where
    it fails, in halves of dt / 2 (``clock.dt`` while they step; :func:`.constraints.in_halves`,
    at most :data:`MAX_STEP_CUTS` deep, the second skipped where the first ``ended`` the
    contact; a Gent rubber that locks is not cut). Each half is recorded as a step of its own,
    so the energy account holds at every recorded state. Near separation a relaxing massless
    body with friction lets many stuck nodes go in one step, and the Newton after that jump
    stalls (the surface folds at the axis): the smaller step lets them go fewer at a time."""

    def step(begin: Any, dt: float) -> list:
        kept, clock.dt = clock.dt, dt
        try:
            return one(begin)
        finally:
            clock.dt = kept

    def halves(_: Any, dt: float) -> tuple[float, float]:
        return 0.5 * dt, 0.5 * dt

    def locks(error: Exception, *_: Any) -> Exception | None:
        return error if isinstance(error, GentLockError) else None

    return in_halves(step, start, clock.dt, halves, locks, MAX_STEP_CUTS, ended)


def march_massless(
    body: QuasiStaticBody,
    mass: float,
    velocity: float,
    scales: tuple[float, float],
    observe: Callable[[float, np.ndarray], None] | None = None,
) -> tuple[tuple[np.ndarray, ...], float | None]:
    """Step from first touch until the striker leaves (or the longest run).

    An elastic frictionless body steps by the discrete gradient of its stored energy, until X
    is back to 0. A relaxing body, or a bonded or Coulomb contact, has no stored energy
    function of X: it steps by the trapezoidal rule on the contact force (second order, as
    Ting's quasi-static impact in :func:`shtaerman.theory.viscoelastic.viscoelastic_impact`),
    its history committed at every step, until the force vanishes with the striker
    rebounding. A step whose contact fails is cut in halves (:func:`_in_halves`; the steps
    cut are counted in ``body.cuts``). The steps are of ``body.dt`` (s); ``scales``: the
    longest run (s) and q of P ~ X^q; ``observe(t, x)`` is told each committed step's time (s)
    and solution. Returns the columns t, X, V, P, stored energy and, for a viscoelastic body or
    a contact with friction, the body's kinetic (0) and dissipated energies (SI); and the
    separation time (s; None for an elastic frictionless body, nan if the run ended first).
    Steps on one BLAS thread, as :func:`march_inertial`.
    """
    duration, exponent = scales
    state, v, t, k = body.zero, velocity, 0.0, 0.0
    extra = (0.0, 0.0) if body.viscous or body.frictional else ()
    gradient = _mean_force if body.history_dependent else _discrete_gradient
    one = partial(_massless_step, body, (mass, velocity), gradient)

    def step() -> list[tuple[tuple, bool]]:
        nonlocal state, v, t, k
        if not t < duration or (t > 0.0 and state.depth <= 0.0):  # the longest run; X back
            return []
        pieces = _in_halves(body, one, (state, v, k), _ended)
        rows, body.cuts = [], body.cuts + (len(pieces) > 1)
        for piece in pieces:
            state, v, k, interval = piece
            t += interval
            body.stepper.watch.accept(state.depth, state.stretch)
            if observe is not None:
                observe(t, state.x)
            row = (t, state.depth, v, state.force, state.energy)
            row += (0.0, state.dissipated) if extra else ()
            rows.append((row, body.history_dependent and _ended(piece)))
        return rows

    with threadpool_limits(limits=1, user_api="blas"):  # see march_inertial
        table, separation = march_steps(step, (0.0, 0.0, v, 0.0, 0.0, *extra), exponent)
    return tuple(table.T), (separation if body.history_dependent else None)


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
        self.cuts = 0  # the time steps cut in halves (:func:`march_inertial`)
        self.reached: _Dynamic | None = None  # the last state a step (or a cut half) reached
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
    step that led here; a Gent rubber's stretch (I1bar - 3) / Jm."""

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
    stretch: float = 0.0

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
    for X_{n+1} by a secant, each evaluation a body step, the first from x extrapolated in time
    (from the last state where that passes a Gent rubber's limit). ``scales``: the contact stiffness
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
    # a Gent rubber short of its lock (another: no state to check, 2.4 ms at 9.5k dofs; a
    # locked one is refused as before, in seconds, not after every cut)
    gent = stepper.watch.limit < math.inf and stepper.watch.crossed is None
    if gent and isinstance(stepper.admit(latest[0])[1], GentLimitError):  # past the limit
        latest = (state.x, state.lam, state.depth)

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
) -> tuple[list[_Dynamic], int]:
    """One time step of :func:`_dynamic_step`, or where it fails, in halves (:func:`_in_halves`:
    each half a Bossak step of dt / 2, same alpha_m, beta, gamma, started like any step from
    the state before it): the states reached (in time order) and the converged Newton
    iterations."""
    iterations = 0

    def step(start: _Dynamic) -> list[_Dynamic]:
        nonlocal iterations
        new, count = _dynamic_step(stepper, inertial, start, mass, scales)
        iterations += count
        inertial.reached = new  # where a later cut half fails, its squeeze is read here
        return [new]

    return _in_halves(inertial, step, state, _separated), iterations


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
        stretch=stepper.stretch,  # of the secant's last solve, at x
    )


def march_inertial(
    stepper: NewtonStepper,
    inertial: _InertialSystem,
    striker: tuple[float, float],
    scales: tuple[float, float, float],
    observe: Callable[[float, np.ndarray], None] | None = None,
) -> tuple[tuple[np.ndarray, ...], int, float, _Dynamic]:
    """Step from first touch until the contact force vanishes with the striker rebounding.

    ``striker``: mass M (kg) and v0 (m/s); ``scales``: the depth scale (m), the longest
    run (s) and q of P ~ X^q (for the separation time between steps); ``observe(t, x)`` is
    told each accepted step's time (s) and solution. Returns the columns
    t, X, V, P, Pi, body kinetic energy (SI), the Newton iterations and the separation time
    (s; nan if the run ended first) and the last state; the steps cut in halves are counted
    in ``inertial.cuts``. Steps on one BLAS thread (``threadpoolctl.threadpool_limits``).
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
            # a Gent rubber at its limit locks (rubber.gent_locks); else a numerical failure
            reached = state.depth + abs(state.speed) * inertial.dt  # the depth it went for
            step = (state.depth, reached)
            locked = gent_locks(error, stepper.system, state.x, step, last=True)
            last = inertial.reached or state  # the halves that passed went deeper
            at = (t, state.depth, max(deepest, last.depth))
            impact = (depth_scale, velocity, exponent)
            raise (locked or _step_failure(stepper, at, error, last.x, impact)) from None
        total, rows = total + iterations, []
        inertial.cuts += len(states) > 1
        for new in states:
            force, previous = float(new.lam.sum()), float(state.lam.sum())
            if new.depth != state.depth:
                k = max((force - previous) / (new.depth - state.depth), 0.0)
            _check_candidates(stepper, new.lam, new.depth)
            state, t, deepest = new, t + new.interval, max(deepest, new.depth)
            stepper.watch.accept(new.depth, new.stretch)
            if observe is not None:
                observe(t, new.x)
            body = 0.5 * float(state.v @ (inertial.mass @ state.v))
            row = (t, state.depth, state.speed, force, state.energy, body)
            rows.append(((*row, state.dissipated) if dissipative else row, _separated(state)))
            if rows[-1][1]:
                break
        return rows

    first = (0.0, 0.0, velocity, 0.0, 0.0, 0.0, *((0.0,) if dissipative else ()))
    # one BLAS thread: the factorizations' supernodes are small and the other thread spins
    # (the relaxing 12 mm pad with Coulomb friction: 35.6 -> 24.5 CPU s, the same numbers)
    with threadpool_limits(limits=1, user_api="blas"):
        table, separation = march_steps(step, first, exponent)
    return tuple(table.T), total, separation, state


def _step_failure(
    stepper: NewtonStepper,
    at: tuple[float, float, float],
    error: Exception,
    x: np.ndarray | None = None,
    impact: tuple[float, float, float] | None = None,
) -> NumericalFailureError:
    """The failure of a step from time ``at[0]`` (s) at striker depth ``at[1]`` (m), the run
    having reached ``at[2]`` (m), its last converged solution ``x`` (None: not read), of the
    ``impact`` (its quasi-static x_c m, velocity m/s and force exponent q; None: no velocity
    named) whose squeezed tip names the velocity that the reach limit names: with a
    bonded or Coulomb indenter beyond the validated x/a (:data:`.guards.MAX_DEPTH_RATIO`) that
    limit is named (near separation the last ring in contact slides back inward down the steep
    flank and folds the surface: the A = 8 pad, x/a 2.29); where ``x`` squeezes an element
    beside the tip (:func:`.contact.finite.squeeze_note`) a
    :class:`.contact.finite.SqueezedTipError` that names it and no time steps; else what may
    help (:func:`_other_remedy`)."""
    where = (
        f"the step from t = {at[0]:.4g} s (striker depth {at[1]:.4g} m): {error}, also in "
        f"steps cut {MAX_STEP_CUTS} times; "
    )
    ratio = depth_ratio(stepper.indenter, at[2]) if at[2] > 0 else 0.0  # failed at once: x 0
    if isinstance(stepper, HistoryStepper) and ratio > MAX_DEPTH_RATIO:
        return NumericalFailureError(
            where + f"the bonded indenter reached x/a = {ratio:.3g}, beyond the "
            f"finite-strain contact's validated {MAX_DEPTH_RATIO:g}, where its last ring in "
            "contact slides back along the steep striker as it leaves: a blunter striker "
            "(a smaller shape_coefficient=... or a slower velocity=...) or "
            "interface='frictionless' (run beyond x/a 1.2 with a warning)"
        )
    squeezed = None if x is None else squeeze_note(stepper.system, x, "more time_steps=...")
    if squeezed is not None:  # the elastic z = 8 r^1.3 pad: J 0.03 at the axis, x/a 1.45
        deep = ratio > MAX_DEPTH_RATIO  # else a thin pad's squeeze (x/H 0.9)
        slower = "" if impact is None else reach_velocity(stepper.indenter, *impact[:2])
        return SqueezedTipError(
            f"{where}{squeezed}; it had reached x/a = {ratio:.3g} (depth {at[2]:.4g} m)"
            + (f", beyond the {MAX_DEPTH_RATIO:g} up to which it is validated" if deep else "")
            + ": a slower velocity=..."
            + (
                f" (at most about {slower} m/s brings x_c within x/a {MAX_DEPTH_RATIO:g})"
                if slower
                else ""
            )
            + " or a smaller shape_coefficient=..."
            + ("" if deep else " (on a pad: a thicker thickness=...)")
        )
    return NumericalFailureError(
        where + "the body with inertia cannot follow this impact at these settings (other "
        "time_steps=... may help; a striker faster than the shear waves never converges): "
        + _other_remedy(stepper, ratio)
    )


def _other_remedy(stepper: NewtonStepper, ratio: float) -> str:
    """What a failed step with inertia names beside other time steps, the run having reached
    x/a ``ratio``: a larger gent_limit=... where the rubber passed :data:`.guards.LOCKED` of
    its limit (the massless impact may refuse it as locking: z = 5 r^1.3 at 0.2 m/s, Jm 0.1);
    else the massless impact (density2=0) within x/a :data:`.guards.MAX_DEPTH_RATIO` (it
    stops there: :func:`.guards.check_reach`), beyond it a slower or blunter striker."""
    if stepper.watch.crossed is not None:
        return (
            f"the Gent rubber passed {LOCKED:g} of its limit from depth "
            f"{stepper.watch.crossed:.4g} m on, where its stiffness runs away: a larger "
            "gent_limit=..."
        )
    if ratio <= MAX_DEPTH_RATIO:
        return "density2=0 gives the massless finite-strain impact"
    return (
        f"it had reached x/a = {ratio:.3g}, beyond the {MAX_DEPTH_RATIO:g} of the massless "
        "impact (density2=0): a slower velocity=... or a smaller shape_coefficient=..."
    )


def far_kinetic(inertial: _InertialSystem, v: np.ndarray) -> float:
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


def inertial_system(stepper: NewtonStepper, density: float, scheme: TimeScheme) -> _InertialSystem:
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
