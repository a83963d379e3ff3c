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
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from functools import cached_property
from typing import TYPE_CHECKING

import numpy as np
import scipy.sparse as sp
from threadpoolctl import threadpool_limits

from ..validation import InputError, NumericalFailureError
from .contact import EDGE_MARGIN, central_pressure, complementarity, edge_radius, recover_pressure
from .elasticity import ElasticSystem
from .impact_run import march_steps
from .solver import Factorization
from .stick import CoupledCompliance, StickState, stick_slip_step

if TYPE_CHECKING:
    from .viscoelastic import ShearMemory, ViscoelasticShear

__all__ = [
    "ContactCandidates",
    "ContactEdgeReachedError",
    "ImpactHistory",
    "ImpactProblem",
    "ImpactState",
    "Striker",
    "TimeScheme",
    "advance",
    "march",
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
            f"edge of the refined zone ({r_c[-1]:.4g} m); increase the margin (mesh_margin, "
            "--mesh-margin)"
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
            "steps (time_steps, --time-steps) or a finer mesh (mesh_size, --mesh-size)"
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
    a_new = (x_new - x_hat) / (beta * dt**2)
    v_new = state.v + dt * ((1.0 - gamma) * state.a + gamma * a_new)
    a_new[problem.massless], v_new[problem.massless] = 0.0, 0.0
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


def _observe(problem: ImpactProblem, state: ImpactState) -> tuple[tuple, tuple]:
    """(t, X, X', P, a, p0) and the energies (:data:`ENERGY_NAMES`) of a state."""
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
    inner_kinetic = 0.5 * float(v @ (problem.inner_mass @ v))
    inner = inner_kinetic + 0.5 * float(x @ (problem.inner_stiffness @ x))
    dissipated = 0.0
    if state.memory is not None:  # viscoelastic: the branches' springs store, their dashpots heat
        strain = problem.material.stored_energy(state.memory, x)
        inner -= problem.material.inner_relaxed(state.memory)
        dissipated = state.memory.dissipated
    striker_kinetic = 0.5 * problem.striker.mass * state.striker_v**2
    numerical = problem.striker.kinetic_energy - striker_kinetic - kinetic - strain - state.absorbed
    numerical -= dissipated
    numerical -= state.slip_heat
    energies = (striker_kinetic, kinetic, strain, state.absorbed, numerical, state.contact_term)
    return row, (*energies, inner, dissipated, inner_kinetic, state.slip_heat)


def march(
    problem: ImpactProblem,
    *,
    duration: float,
    tail_time: float,
    force_exponent: float,
    snapshot_times: tuple[float, ...] = (),
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

    Raises
    ------
    ContactEdgeReachedError
        If the contact reaches the edge of the candidates with the energy balanced.
    shtaerman.validation.NumericalFailureError
        If it gets there after the energy balance drifted (the stepping became unstable).
    """
    dt, energy0 = problem.scheme.dt, problem.striker.kinetic_energy
    state, touched, numerical = ImpactState.first_touch(problem), False, 0.0
    snapshots: dict[float, tuple[float, np.ndarray, np.ndarray]] = {}
    memories: dict[float, ShearMemory | None] = {}
    wanted = sorted(float(s) for s in snapshot_times)
    max_steps = math.ceil(duration / dt)

    def step() -> list[tuple[tuple, bool]]:
        nonlocal state, touched, numerical
        if state.step >= max_steps:
            return []
        try:
            state = advance(problem, state)
        except ContactEdgeReachedError as edge:
            _blame_the_stepping(numerical / energy0, state, problem, edge)
            raise
        t = state.time(problem.scheme)
        row, energies = _observe(problem, state)
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
    with threadpool_limits(limits=1, user_api="blas"):
        table, t_contact = march_steps(step, first, force_exponent, (tail_time, 1e-12 * dt))
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
    "use fewer time steps (time_steps, --time-steps) or a finer mesh with them (mesh_size, "
    "--mesh-size): the contact stepping needs c_s dt not far below the surface element size"
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
