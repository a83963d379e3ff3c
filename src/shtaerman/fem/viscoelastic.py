"""Linear viscoelastic shear of the half-space: a Prony series by recursive convolution.

The body relaxes in shear by G(t) = G0 [g_inf + sum_i g_i exp(-t/tau_i)] (Abaqus' convention:
E2 and nu2 are the instantaneous values, :class:`shtaerman.theory.viscoelastic.PronySeries`);
its bulk response stays elastic. The branch strains update exactly for a deviatoric strain
linear over each step, so a step's stiffness is the elastic one at the constant G_eff and the
history enters as a nodal force; energies in J. The recursion and the energies:
benchmarks/FEM_NOTES.md, "Moved from the docstrings", fem/viscoelastic.py."""

from __future__ import annotations

import dataclasses
import warnings
from dataclasses import dataclass, field

import numpy as np
import scipy.sparse as sp
from skfem import asm

from ..theory.contact import PowerLawContact
from ..theory.impact import QuasiStaticValidityWarning
from ..theory.viscoelastic import PronySeries, ViscoelasticImpact, viscoelastic_impact
from ..validation import InputError, NumericalFailureError
from ..vocabulary import MAX_GLASSY_DURATIONS
from .elasticity import TWO_PI, ElasticSystem, deviatoric_stiffness

__all__ = [
    "MAX_GLASSY_DURATIONS",
    "RelaxationStep",
    "ShearMemory",
    "ViscoelasticShear",
    "effective_shear_modulus",
    "sizing_impact",
    "strain_operator",
    "viscoelastic_shear",
]

ROOT2 = np.sqrt(2.0)


@dataclass(frozen=True, eq=False)
class ShearMemory:
    """The internal variables after a step (SI units).

    Tensors are stored as (rr, tt, zz, sqrt(2) rz), so that a:b is the plain dot product.

    Attributes
    ----------
    deviator : numpy.ndarray
        d^n, shape (4 points,): the deviatoric strain at the quadrature points (component-major).
    branches : numpy.ndarray
        h_i^n, shape (terms, 4 points): the strain of each Maxwell branch's spring.
    force : numpy.ndarray
        B^T W s_hist^n in N on all dofs: the history's nodal force for the next step.
    dissipated : float
        Energy dissipated by the branches since first touch, J.
    shear_energy : float
        G0 Int [g_inf d:d + sum_i g_i h_i:h_i] 2 pi r dA, J: stored in shear.
    inner_relaxed : float
        G0 Int sum_i g_i (d:d - h_i:h_i) 2 pi r dA inside the monitor radius, J: what the
        elastic energy at G0 there exceeds the stored one by.
    """

    deviator: np.ndarray = field(repr=False)
    branches: np.ndarray = field(repr=False)
    force: np.ndarray = field(repr=False)
    dissipated: float
    shear_energy: float
    inner_relaxed: float


def strain_operator(system: ElasticSystem) -> tuple[sp.csr_matrix, np.ndarray, np.ndarray]:
    """The strains at the displacement basis' quadrature points.

    Returns
    -------
    matrix : scipy.sparse.csr_matrix
        B, shape (4 points, dofs): x (m, Pa) -> e_rr, e_tt, e_zz, sqrt(2) e_rz (stacked by
        component, points element-major); zero on the pressure dofs.
    weights : numpy.ndarray
        2 pi r dA in m^3 per point.
    radius : numpy.ndarray
        Distance of each point's element centroid from the origin, m.
    """
    ubasis = system.displacement_basis
    r = np.array(ubasis.global_coordinates())[0]  # (elements, points per element)
    elements, per = r.shape
    points = elements * per
    rows, cols, values = [], [], []
    index = np.arange(points).reshape(elements, per)
    for local in range(ubasis.element_dofs.shape[0]):
        phi = ubasis.basis[local][0]
        dofs = np.broadcast_to(ubasis.element_dofs[local][:, None], (elements, per))
        parts = (
            phi.grad[0, 0],
            np.array(phi)[0] / r,
            phi.grad[1, 1],
            (0.5 * ROOT2) * (phi.grad[0, 1] + phi.grad[1, 0]),
        )
        for component, part in enumerate(parts):
            rows.append((component * points + index).ravel())
            cols.append(dofs.ravel())
            values.append(np.asarray(part).ravel())
    matrix = sp.csr_matrix(
        (np.concatenate(values), (np.concatenate(rows), np.concatenate(cols))),
        shape=(4 * points, system.n_dofs),
    )
    matrix.eliminate_zeros()
    centroids = system.mesh.p[:, system.mesh.t].mean(axis=1)
    distance = np.repeat(np.hypot(centroids[0], centroids[1]), per)
    return matrix, (TWO_PI * r * ubasis.dx).ravel(), distance


def _deviator(strain: np.ndarray) -> np.ndarray:
    """Strains (4 points,) -> their deviator (the rz part unchanged)."""
    deviator = strain.reshape(4, -1).copy()
    deviator[:3] -= deviator[:3].sum(axis=0) / 3.0
    return deviator.ravel()


def _excess(x: np.ndarray) -> np.ndarray:
    """x - 2 tanh(x/2) >= 0 without cancellation (series below 0.1)."""
    small = x < 0.1
    xs = np.where(small, x, 0.0)
    series = xs**3 / 12.0 - xs**5 / 120.0 + 17.0 * xs**7 / 20160.0
    return np.where(small, series, x - 2.0 * np.tanh(0.5 * x))


@dataclass(frozen=True)
class RelaxationStep:
    """The per-term constants of a step dt (arrays over the terms), at small and finite strain.

    Attributes
    ----------
    gain, decay, ramp : numpy.ndarray
        g_i, exp(-dt/tau_i) and r_i = (tau_i/dt)(1 - exp(-dt/tau_i)).
    scale : float
        c = g_inf + sum_i g_i r_i: the instantaneous isochoric stress' factor over the step.
    """

    gain: np.ndarray
    decay: np.ndarray
    ramp: np.ndarray
    scale: float

    @classmethod
    def of(cls, prony: PronySeries, dt: float) -> RelaxationStep:
        """The constants of ``prony`` for a step of ``dt`` s."""
        gain, tau = np.asarray(prony.weights, dtype=float), np.asarray(prony.times, dtype=float)
        with np.errstate(over="ignore", divide="ignore", invalid="ignore"):  # x -> inf or 0
            x = dt / tau
            ramp = -np.expm1(-x) / x
        return cls(gain, np.exp(-x), ramp, prony.g_inf + float(gain @ ramp))

    def history(self, branches: np.ndarray, iso: np.ndarray) -> np.ndarray:
        """T^n = sum_i [exp(-dt/tau_i) H_i^n - g_i r_i S0^n] (Pa) from H^n (terms, 4, ...) and
        S0^n (4, ...)."""
        return np.tensordot(self.decay, branches, axes=1) - float(self.gain @ self.ramp) * iso

    def advance(self, branches: np.ndarray, iso: np.ndarray, new_iso: np.ndarray) -> np.ndarray:
        """H^{n+1} (terms, 4, ...) from H^n, S0^n and S0^{n+1} (Pa)."""
        change = new_iso - iso
        weights = self.gain * self.ramp
        return (
            self.decay.reshape(-1, *[1] * iso.ndim) * branches
            + weights.reshape(-1, *[1] * iso.ndim) * change
        )


@dataclass(frozen=True)
class _Step(RelaxationStep):
    """:class:`RelaxationStep` with the dissipation's constants (arrays over the terms; x =
    dt / tau_i).

    Branch i dissipates, over the step, 2 G0 g_i / tau_i Int |A e^{-s/tau_i} + C|^2 ds with
    C = tau_i (d^{n+1} - d^n) / dt and A = h_i^n - C; that is
    ``square`` |h_i^n + ``mix`` (d^{n+1} - d^n)|^2 + ``steady`` |d^{n+1} - d^n|^2 (per unit
    volume), tau_i cancelled so that any tau_i > 0 stays finite.
    """

    mix: np.ndarray = field(default=None)  # tanh(x/2) / x
    square: np.ndarray = field(default=None)  # G0 g_i (1 - exp(-2x)), Pa
    steady: np.ndarray = field(default=None)  # 2 G0 g_i (x - 2 tanh(x/2)) / x^2, Pa

    @classmethod
    def dissipating(cls, prony: PronySeries, shear_modulus: float, dt: float) -> _Step:
        """The constants of ``prony`` on the glassy ``shear_modulus`` (Pa) for ``dt`` s."""
        base = RelaxationStep.of(prony, dt)
        gain = base.gain
        with np.errstate(over="ignore", divide="ignore", invalid="ignore"):  # x -> inf or 0
            x = dt / np.asarray(prony.times, dtype=float)
            excess = np.where(x > 1e3, 1.0 / x - 2.0 / (x * x), _excess(x) / (x * x))
            return cls(
                gain,
                base.decay,
                base.ramp,
                base.scale,
                mix=np.tanh(0.5 * x) / x,
                square=-shear_modulus * gain * np.expm1(-2.0 * x),
                steady=2.0 * shear_modulus * gain * np.nan_to_num(excess, nan=0.0),
            )


@dataclass(frozen=True, eq=False)
class ViscoelasticShear:
    """The body's Prony shear for a fixed time step: effective stiffness and history update.

    Attributes
    ----------
    prony : PronySeries
    shear_modulus : float
        Instantaneous (glassy) G0 in Pa.
    time_step : float
        dt in s.
    stiffness : scipy.sparse.csr_matrix
        The elastic matrix with the deviatoric part at G_eff (all dofs; N/m, m^2).
    strain : scipy.sparse.csr_matrix
        B of :func:`strain_operator`.
    weights : numpy.ndarray
        2 pi r dA per quadrature point, m^3.
    inner : numpy.ndarray
        Weights of the points inside the monitor radius (0 elsewhere), m^3.
    pressure_block : scipy.sparse.csr_matrix
        The matrix' pressure block -C (bulk compliance, m^3/Pa; empty when incompressible).
    strain_shape : tuple of int
        (elements, points per element) of the quadrature.
    """

    prony: PronySeries
    shear_modulus: float
    time_step: float
    stiffness: sp.csr_matrix = field(repr=False)
    strain: sp.csr_matrix = field(repr=False)
    weights: np.ndarray = field(repr=False)
    inner: np.ndarray = field(repr=False)
    pressure_block: sp.csr_matrix = field(repr=False)
    strain_shape: tuple[int, int] = (0, 0)

    def __post_init__(self) -> None:
        step = _Step.dissipating(self.prony, self.shear_modulus, self.time_step)
        weights = np.tile(self.weights, 4)
        object.__setattr__(self, "_step", step)
        object.__setattr__(self, "_weights", weights)
        object.__setattr__(self, "_both", np.column_stack([weights, np.tile(self.inner, 4)]))
        object.__setattr__(self, "_transpose", self.strain.T.tocsr())

    def first_memory(self) -> ShearMemory:
        """At rest: no strain, no history, nothing dissipated."""
        size = 4 * self.weights.size
        terms = len(self.prony.weights)
        force = np.zeros(self.stiffness.shape[0])
        return ShearMemory(np.zeros(size), np.zeros((terms, size)), force, 0.0, 0.0, 0.0)

    def advance(self, memory: ShearMemory, x: np.ndarray) -> tuple[np.ndarray, ShearMemory]:
        """The internal force (N, all dofs) at the new displacement ``x`` and the new memory."""
        step, g0, weights = self._step, self.shear_modulus, self._weights
        force = self.stiffness @ x
        force += memory.force
        deviator = _deviator(self.strain @ x)
        change = deviator - memory.deviator
        # dissipation over the step, from the branches' strains before the update
        mixed = step.mix[:, None] * change
        mixed += memory.branches
        heat = step.square @ ((mixed * mixed) @ weights)
        heat += float(np.sum(step.steady)) * float((change * change) @ weights)
        branches = step.ramp[:, None] * change
        branches += step.decay[:, None] * memory.branches
        next_force = self._history_force(branches, deviator)
        squares = (deviator * deviator) @ self._both  # everywhere, inside the monitor radius
        branch_squares = step.gain @ ((branches * branches) @ self._both)
        stored = g0 * (self.prony.g_inf * squares[0] + branch_squares[0])
        relaxed = g0 * (float(np.sum(step.gain)) * squares[1] - branch_squares[1])
        memory = ShearMemory(
            deviator, branches, next_force, memory.dissipated + float(heat), stored, relaxed
        )
        return force, memory

    def _history_force(self, branches: np.ndarray, deviator: np.ndarray) -> np.ndarray:
        """B^T W s_hist in N: the history's nodal force for the next step of this dt."""
        step = self._step
        history = (step.gain * step.decay) @ branches
        history -= float(step.gain @ step.ramp) * deviator
        history *= self._weights
        force = self._transpose @ history
        force *= 2.0 * self.shear_modulus
        return force

    def resume(self, memory: ShearMemory) -> ShearMemory:
        """``memory`` (left by a step of another dt) with the history force for a step of this
        one: the strains carry over, the force depends on the step."""
        force = self._history_force(memory.branches, memory.deviator)
        return dataclasses.replace(memory, force=force)

    def deviatoric_stress(self, memory: ShearMemory) -> np.ndarray:
        """s = 2 G0 [g_inf d + sum_i g_i h_i] in Pa, (rr, tt, zz, rz) x (elements, points)."""
        stress = self.prony.g_inf * memory.deviator + self._step.gain @ memory.branches
        stress = (2.0 * self.shear_modulus * stress).reshape(4, -1)
        stress[3] /= ROOT2
        return stress.reshape(4, *self.strain_shape)

    def stored_energy(self, memory: ShearMemory, x: np.ndarray) -> float:
        """Energy stored in the body (bulk and the springs of every branch), J."""
        n_p = self.pressure_block.shape[0]
        p = x[x.size - n_p :]
        return memory.shear_energy - 0.5 * float(p @ (self.pressure_block @ p))

    def inner_relaxed(self, memory: ShearMemory) -> float:
        """What the elastic energy at G0 inside the monitor radius exceeds the stored one by, J."""
        return memory.inner_relaxed


def effective_shear_modulus(prony: PronySeries, shear_modulus: float, time_step: float) -> float:
    """G_eff = G0 [g_inf + sum_i g_i (tau_i/dt)(1 - exp(-dt/tau_i))] in Pa: the shear modulus of
    one step of ``time_step`` s on the glassy ``shear_modulus`` G0 (Pa)."""
    return shear_modulus * RelaxationStep.of(prony, time_step).scale


def viscoelastic_shear(
    system: ElasticSystem, prony: PronySeries, time_step: float, inner_radius: float
) -> ViscoelasticShear:
    """Assemble the Prony shear of ``system`` (E2, nu2 its instantaneous moduli) for steps of
    ``time_step`` s; ``inner_radius`` (m) bounds the monitored energy (element centroids)."""
    strain, weights, distance = strain_operator(system)
    glassy = system.shear_modulus
    change = effective_shear_modulus(prony, glassy, time_step) - glassy
    deviatoric = asm(deviatoric_stiffness(change), system.displacement_basis)
    n_p = system.n_dofs - system.n_displacement
    update = sp.block_diag([deviatoric, sp.csr_matrix((n_p, n_p))], format="csr")
    return ViscoelasticShear(
        prony=prony,
        shear_modulus=glassy,
        time_step=float(time_step),
        stiffness=(system.matrix + update).tocsr(),
        strain=strain,
        weights=weights,
        inner=np.where(distance < inner_radius, weights, 0.0),
        pressure_block=system.matrix[system.n_displacement :, system.n_displacement :].tocsr(),
        strain_shape=system.displacement_basis.dx.shape,
    )


def sizing_impact(
    mass: float, velocity: float, law: PowerLawContact, prony: PronySeries, glassy: float
) -> ViscoelasticImpact:
    """The coarse quasi-static viscoelastic impact (100 steps per t_c) that sizes a run.

    ``law`` is the elastic contact at the glassy modulus and ``glassy`` its impact duration t_y
    in s (its t_c = t_y / 2 is not solved again); SI units. The integration stops at
    :data:`MAX_GLASSY_DURATIONS` t_y, so its cost is bounded whatever the series.

    Raises
    ------
    shtaerman.validation.InputError
        Naming ``prony`` when the contact would last longer than that.
    """
    longest = MAX_GLASSY_DURATIONS * glassy
    try:
        with warnings.catch_warnings():  # of a fast impact: its run's caller warns, once
            warnings.simplefilter("ignore", QuasiStaticValidityWarning)
            return viscoelastic_impact(
                mass, velocity, law, prony, steps=100, longest=longest, t_c=0.5 * glassy
            )
    except NumericalFailureError:
        pass
    smallest = MAX_GLASSY_DURATIONS ** -(law.force_exponent + 1.0)  # the relaxed impact's g_inf
    raise InputError(
        f"prony: the viscoelastic impact lasts more than {MAX_GLASSY_DURATIONS:g} glassy impact "
        f"durations (at most {MAX_GLASSY_DURATIONS:g} are run): the series relaxes too far "
        f"within the impact; 1 - sum g_i >= {smallest:.2g} (the relaxed impact, at "
        f"E2 (1 - sum g_i), within the bound) or slower terms keep it shorter",
        "prony",
    ) from None
