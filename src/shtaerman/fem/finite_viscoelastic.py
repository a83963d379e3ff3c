"""Viscoelastic rubber at finite strain: a Prony series on the isochoric stress (Simo 1987).

Abaqus' convention of :mod:`.viscoelastic` (E2, nu2 the instantaneous values, g_inf = 1 -
sum_i g_i): only the isochoric stress relaxes, the volumetric stress stays elastic. Each
quadrature point carries one reference-configuration stress H_i per term, updated exactly for
an isochoric stress S0 linear in time over each step; the step's stress is c P_iso + P_vol +
F T^n (T^n the branches' history, fixed in the step). Symmetric tensors: (RR, RZ, ZZ, TT);
A:B counts RZ twice. Energies in J. The recursion, the energy split and why:
benchmarks/FEM_NOTES.md, "Moved from the docstrings", fem/finite_viscoelastic.py."""

from __future__ import annotations

from dataclasses import dataclass, replace
from typing import Any

import numpy as np

from ..theory.viscoelastic import PronySeries
from .hyperelastic import HESSIAN_TERMS, HyperelasticSystem, Kinematics
from .viscoelastic import RelaxationStep

__all__ = [
    "ViscoelasticBody",
    "contract",
    "first_piola",
    "green_strain",
    "second_piola",
]


def second_piola(F: np.ndarray, P: np.ndarray) -> np.ndarray:
    """S = F^-1 P (Pa) as (RR, RZ, ZZ, TT) from the 5-vectors F and P (RZ: the mean of the two
    off-diagonal entries, equal for a symmetric S)."""
    a, b, c, d, h = F
    planar = a * d - b * c
    rr = (d * P[0] - b * P[2]) / planar
    rz = 0.5 * ((d * P[1] - b * P[3]) + (a * P[2] - c * P[0])) / planar
    zz = (a * P[3] - c * P[1]) / planar
    return np.stack([rr, rz, zz, P[4] / h])


def first_piola(F: np.ndarray, S: np.ndarray) -> np.ndarray:
    """P = F S as the 5-vector (Pa) of a symmetric reference tensor S = (RR, RZ, ZZ, TT)."""
    a, b, c, d, h = F
    rr, rz, zz, tt = S
    return np.stack([a * rr + b * rz, a * rz + b * zz, c * rr + d * rz, c * rz + d * zz, h * tt])


def green_strain(F: np.ndarray) -> np.ndarray:
    """E = (F^T F - I) / 2 as (RR, RZ, ZZ, TT) (dimensionless)."""
    a, b, c, d, h = F
    return 0.5 * np.stack([a * a + c * c - 1.0, a * b + c * d, b * b + d * d - 1.0, h * h - 1.0])


def contract(A: np.ndarray, B: np.ndarray) -> np.ndarray:
    """A:B of symmetric reference tensors (RR, RZ, ZZ, TT) over the leading axis."""
    return A[0] * B[0] + 2.0 * A[1] * B[1] + A[2] * B[2] + A[3] * B[3]


def _add_geometric(tangent: np.ndarray, S: np.ndarray) -> None:
    """tangent += d(F S)/dF for a fixed S (in place; (..., 5, 5), Pa)."""
    rr, rz, zz, tt = S
    for first in (0, 2):  # the rows (a, b) and (c, d) of F
        second = first + 1
        tangent[..., first, first] += rr
        tangent[..., first, second] += rz
        tangent[..., second, first] += rz
        tangent[..., second, second] += zz
    tangent[..., 4, 4] += tt


def _add_volume_hessian(tangent: np.ndarray, kin: Kinematics, scale: np.ndarray, log: bool) -> None:
    """tangent += scale d(g'(J) dJ/dF)/dF in place: scale H (g = J - 1) or scale (H / J -
    dJ/dF (x) dJ/dF / J^2) (g = ln J); ``scale`` per point (Pa)."""
    F = kin.F
    factor = scale / kin.J if log else scale
    for k, m, sign, f in HESSIAN_TERMS:
        term = sign * factor * F[f]
        tangent[..., k, m] += term
        tangent[..., m, k] += term
    if log:  # volume_gradient = dJ/dF / J
        Jg = kin.volume_gradient
        tangent -= (scale[..., None, None]) * np.einsum("k...,m...->...km", Jg, Jg)


@dataclass
class _Memory:
    """The committed state at the quadrature points (arrays (4, E, Q), branches (terms, 4, E,
    Q)): S0^n, H^n, the overstress V^n, the Green strain E^n; the overstress work W_V (J), the
    dissipated energy (J) and the stored energy's excess over Pi(x) (J)."""

    iso: np.ndarray
    branches: np.ndarray
    over: np.ndarray
    strain: np.ndarray
    work: float = 0.0
    dissipated: float = 0.0
    excess: float = 0.0


class ViscoelasticBody:
    """A :class:`.hyperelastic.HyperelasticSystem` whose isochoric stress relaxes by a Prony
    series; seen by the contact Newton as the system (state, residual, tangent, energy).

    ``clock`` is any object with the current time step ``dt`` (s) (the Bossak scheme, whose
    step may be cut); :meth:`commit` accepts a converged step and updates the history.
    """

    def __init__(self, system: HyperelasticSystem, prony: PronySeries, clock: Any = None) -> None:
        self.static = system
        self.prony = prony
        self.clock = clock
        q = system._quadrature
        shape = q.weight.shape
        terms = len(prony.weights)
        zero = np.zeros((4, *shape))
        self.memory = _Memory(zero, np.zeros((terms, *zero.shape)), zero, zero)
        self._steps: dict[float, RelaxationStep] = {}
        self._history: tuple[float, np.ndarray] | None = None
        self.logarithmic = getattr(system.material, "volumetric", "quadratic") == "logarithmic"

    def __getattr__(self, name: str) -> Any:
        return getattr(self.static, name)

    def step(self, dt: float | None = None) -> RelaxationStep:
        """The constants of the step ``dt`` (s; default the clock's)."""
        dt = float(self.clock.dt if dt is None else dt)
        if dt not in self._steps:
            self._steps[dt] = RelaxationStep.of(self.prony, dt)
        return self._steps[dt]

    def pressure(self, x: np.ndarray) -> np.ndarray:
        """p (Pa) at the quadrature points (E, Q)."""
        q = self.static._quadrature
        n_u = q.variation.shape[-1]
        return (q.pressure @ x[q.dofs][:, n_u:, None])[..., 0]

    def isochoric(self, kin: Kinematics, p: np.ndarray) -> np.ndarray:
        """S0 (Pa, (RR, RZ, ZZ, TT)): the instantaneous isochoric second Piola-Kirchhoff stress."""
        return second_piola(kin.F, kin.stress + p * kin.volume_gradient)

    def state(self, x: np.ndarray) -> Kinematics:
        """The kinematics of x with the relaxed stress and its consistent tangent."""
        kin = self.static.state(x)
        step = self.step()
        dt = float(self.clock.dt)
        if self._history is None or self._history[0] != dt:
            self._history = (dt, step.history(self.memory.branches, self.memory.iso))
        history = self._history[1]
        p = self.pressure(x)
        c = step.scale
        stress = c * kin.stress + (c - 1.0) * p * kin.volume_gradient
        stress += first_piola(kin.F, history)

        def tangent() -> np.ndarray:
            D = c * kin.tangent
            _add_volume_hessian(D, kin, (c - 1.0) * p, self.logarithmic)
            _add_geometric(D, history)
            return D

        return replace(kin, stress=stress, make_tangent=tangent)

    def residual(self, x: np.ndarray, state: Kinematics | None = None) -> np.ndarray:
        """Internal forces (N) with the relaxed stress, and the pressure equation (m^3)."""
        return self.static.residual(x, self.state(x) if state is None else state)

    def tangent_data(self, x: np.ndarray, state: Kinematics | None = None) -> np.ndarray:
        """The consistent tangent's data in the system's pattern."""
        return self.static.tangent_data(x, self.state(x) if state is None else state)

    def commit(self, x: np.ndarray) -> None:
        """Accept the converged ``x`` of the current step: H, S0, V, E, W_V and the energies."""
        kin = self.static.state(x)
        p = self.pressure(x)
        step, old = self.step(), self.memory
        iso = self.isochoric(kin, p)
        branches = step.advance(old.branches, old.iso, iso)
        over = branches.sum(axis=0) - float(step.gain.sum()) * iso
        strain = green_strain(kin.F)
        weight = self.static._quadrature.weight
        power = contract(0.5 * (old.over + over), strain - old.strain)
        work = old.work + float(np.sum(weight * power))
        excess = float(np.sum(weight * self._branch_excess(kin, p, iso, branches)))
        self.memory = _Memory(iso, branches, over, strain, work, work - excess, excess)
        self._history = None

    def _branch_excess(
        self, kin: Kinematics, p: np.ndarray, iso: np.ndarray, branches: np.ndarray
    ) -> np.ndarray:
        """sum_i [psi_i - g_i W0] (J/m^3) per point, psi_i = |H_i|^2 W0 / (g_i |S0|^2)."""
        material = self.static.material
        shear = material.shear_modulus
        isochoric_energy = kin.energy_density + p * kin.constraint
        isochoric_energy -= 0.5 * material.inverse_bulk * p * p
        square = contract(iso, iso)
        tiny = square <= (1e-12 * shear) ** 2  # at rest: the small-strain secant
        with np.errstate(divide="ignore", invalid="ignore"):
            secant = np.where(tiny, 0.25 / shear, isochoric_energy / np.where(tiny, 1.0, square))
        gains = np.asarray(self.prony.weights, dtype=float)
        excess = -float(gains.sum()) * isochoric_energy
        for i, g in enumerate(gains):
            if g > 0.0:
                excess += contract(branches[i], branches[i]) * secant / g
        return excess

    def energy(self, x: np.ndarray) -> float:
        """The stored energy (J) at the committed ``x``: Pi(x) + the branches' excess."""
        return self.static.energy(x) + self.memory.excess

    @property
    def dissipated(self) -> float:
        """Energy dissipated since first touch (J) at the committed state."""
        return self.memory.dissipated
