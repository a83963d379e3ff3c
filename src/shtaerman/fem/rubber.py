"""Rubber models beyond neo-Hookean: Mooney-Rivlin, Yeoh, Gent, and the volumetric energy.

Every model is an isochoric energy W(I1bar, I2bar) plus a volumetric energy U(J) = K/2 g(J)^2
in the mixed form of :mod:`.hyperelastic`, Psi(F, p) = W - p g(J) - p^2 / (2 K). Volumetric
(``volumetric``): ``quadratic`` g = J - 1 (the default), ``logarithmic`` g = ln J. Isochoric,
all with the small-strain shear modulus mu = E / (2 (1 + nu)):

- ``neo-hookean``:   W = mu/2 (I1bar - 3);
- ``mooney-rivlin``: W = C10 (I1bar - 3) + C01 (I2bar - 3), C10 + C01 = mu/2,
  r = C01 / (C10 + C01) in [0, 1) (``mooney_ratio``);
- ``yeoh``:          W = C10 (x + c2 x^2 + c3 x^3), x = I1bar - 3, C10 = mu/2,
  (c2, c3) = (C20, C30) / C10 (``yeoh``);
- ``gent``:          W = -mu/2 Jm ln(1 - x / Jm), Jm > 0 (``gent_limit``).

Stress and tangent are shared by all models (:func:`energy_derivatives`); their formulas:
benchmarks/FEM_NOTES.md, "Moved from the docstrings", fem/rubber.py."""

from __future__ import annotations

import math
import numbers
from dataclasses import astuple, dataclass
from typing import Any

import numpy as np

from ..guards import LOCKED
from ..validation import InputError, plain_float
from .hyperelastic import (
    HESSIAN_TERMS,
    N_COMPONENTS,
    Kinematics,
    NeoHookean,
    NewtonError,
    deformation,
    deviatoric_direction,
    invariant_excess,
    power_excess,
)

__all__ = [
    "MODELS",
    "VOLUMETRIC",
    "GentLimitError",
    "GentLockError",
    "Rubber",
    "RubberModel",
    "energy_derivatives",
    "gent_locks",
    "gent_stretch",
    "invariant_kinematics",
    "rubber_model",
]

MODELS = ("neo-hookean", "mooney-rivlin", "yeoh", "gent")
"""The finite-strain models (``--model``)."""
VOLUMETRIC = ("quadratic", "logarithmic")
"""The volumetric energies (``--volumetric``): K/2 (J - 1)^2 and K/2 (ln J)^2."""
YEOH_BOUND = 10.0
"""|c2| and c3 at most this (C20, C30 up to ten times C10: far beyond published fits)."""


@dataclass(frozen=True)
class RubberModel:
    """The constitutive choice of a finite-strain run, apart from E and nu.

    Attributes
    ----------
    name : str
        One of :data:`MODELS`.
    mooney_ratio : float
        r = C01 / (C10 + C01) in [0, 1) (Mooney-Rivlin only).
    yeoh : tuple of float
        (c2, c3) = (C20 / C10, C30 / C10) (Yeoh only).
    gent_limit : float
        Jm > 0 (Gent only; the limit of I1bar - 3).
    volumetric : str
        One of :data:`VOLUMETRIC`.
    """

    name: str = "neo-hookean"
    mooney_ratio: float = 0.0
    yeoh: tuple[float, float] = (0.0, 0.0)
    gent_limit: float = math.inf
    volumetric: str = "quadratic"

    def material(self, youngs_modulus: float, poisson_ratio: float) -> Rubber:
        """The :class:`Rubber` with small-strain constants E (Pa) and nu."""
        return Rubber(youngs_modulus, poisson_ratio, *astuple(self))  # name, mooney_ratio, ...

    def to_dict(self) -> dict[str, Any]:
        """The model's keys for a JSON report (only those that apply)."""
        out: dict[str, Any] = {"model": self.name}
        if self.name == "mooney-rivlin":
            out["mooney_ratio"] = self.mooney_ratio
        if self.name == "yeoh":
            out["yeoh"] = list(self.yeoh)
        if self.name == "gent":
            out["gent_limit"] = self.gent_limit
        out["volumetric"] = self.volumetric
        return out


def _yeoh_pair(value: Any) -> tuple[float, float]:
    """(c2, c3) from "c2,c3" or a pair of numbers; InputError naming ``yeoh`` otherwise."""
    items = value.split(",") if isinstance(value, str) else value
    try:
        c2, c3 = (plain_float(item) if isinstance(item, str) else float(item) for item in items)
    except (TypeError, ValueError):
        raise InputError(
            f"yeoh must be two numbers c2,c3 (C20/C10, C30/C10), got {value!r}", "yeoh"
        ) from None
    typed = [str(item).strip() for item in items]  # as written: 1e999, not inf
    if not abs(c2) <= YEOH_BOUND:  # nan and inf too
        raise InputError(f"yeoh: c2 must lie in [-10, 10], got {typed[0]}", "yeoh")
    if not 0.0 <= c3 <= YEOH_BOUND:
        raise InputError(f"yeoh: c3 must lie in [0, 10], got {typed[1]}", "yeoh")
    if c2 < 0.0 and c2 * c2 >= 3.0 * c3:
        raise InputError(
            f"yeoh: c2 = {c2:g}, c3 = {c3:g} soften without bound (dW/dI1 = C10 (1 + 2 c2 x + "
            f"3 c3 x^2) reaches 0 at x = I1bar - 3 >= 0); a negative c2 needs c2^2 < 3 c3",
            "yeoh",
        )
    return c2, c3


def rubber_model(
    model: str = "neo-hookean",
    mooney_ratio: float | None = None,
    yeoh: Any = None,
    gent_limit: float | None = None,
    volumetric: str | None = None,
) -> RubberModel:
    """Check the rubber options together and return the :class:`RubberModel`.

    A shape option of another model (e.g. ``mooney_ratio`` with ``yeoh``) is refused where
    the input enters, by :class:`shtaerman.problem.Body` (its map
    :data:`shtaerman.problem.RUBBER_SHAPES`). None means "not given" (the defaults: r = 0,
    (c2, c3) = (0, 0), Jm required for Gent, ``quadratic``).

    Raises
    ------
    shtaerman.validation.InputError
        One line naming the option and its valid range.
    """
    if model not in MODELS:
        raise InputError(
            f"model: unknown finite-strain model {model!r}; pick one of {', '.join(MODELS)}",
            "model",
        )
    if volumetric is not None and volumetric not in VOLUMETRIC:
        raise InputError(
            f"volumetric must be one of {', '.join(VOLUMETRIC)}, got {volumetric!r}", "volumetric"
        )
    ratio = 0.0 if mooney_ratio is None else mooney_ratio
    if not _real(ratio) or not 0.0 <= ratio < 1.0:
        raise InputError(f"mooney_ratio must lie in [0, 1), got {mooney_ratio!r}", "mooney_ratio")
    limit = math.inf
    if model == "gent":
        if gent_limit is None:
            raise InputError("gent_limit: the gent model needs Jm > 0 (e.g. 97.2)", "gent_limit")
        if not _real(gent_limit) or not 0.0 < gent_limit < math.inf:
            raise InputError(
                f"gent_limit must be a finite number > 0, got {gent_limit!r}", "gent_limit"
            )
        limit = float(gent_limit)
    pair = (0.0, 0.0) if yeoh is None else _yeoh_pair(yeoh)
    return RubberModel(model, float(ratio), pair, limit, volumetric or "quadratic")


def _real(value: Any) -> bool:
    """Whether ``value`` is a real number (a NumPy scalar too, as for mass=...), not a bool."""
    return isinstance(value, numbers.Real) and not isinstance(value, bool | np.bool_)


@dataclass(frozen=True)
class Rubber(NeoHookean):
    """A rubber model with small-strain constants E (Pa) and nu, see :class:`RubberModel`.

    With the defaults (neo-Hookean, quadratic) it is :class:`.hyperelastic.NeoHookean` and runs
    its kinematics; any other choice runs :func:`invariant_kinematics`.
    """

    model: str = "neo-hookean"
    mooney_ratio: float = 0.0
    yeoh: tuple[float, float] = (0.0, 0.0)
    gent_limit: float = math.inf
    volumetric: str = "quadratic"

    def __post_init__(self) -> None:
        super().__post_init__()
        rubber_model(
            self.model,
            self.mooney_ratio if self.model == "mooney-rivlin" else None,
            self.yeoh if self.model == "yeoh" else None,
            self.gent_limit if self.model == "gent" else None,
            self.volumetric,
        )

    @property
    def uses_invariants(self) -> bool:
        """Whether :func:`invariant_kinematics` evaluates it (all but the default)."""
        return self.model != "neo-hookean" or self.volumetric != "quadratic"

    def kinematics(
        self, grad: np.ndarray, u_r: np.ndarray, radius: np.ndarray, p: np.ndarray
    ) -> Kinematics:
        """:func:`invariant_kinematics` of this rubber (the arguments of
        :func:`.hyperelastic.kinematics`)."""
        return invariant_kinematics(self, grad, u_r, radius, p)


def energy_derivatives(material: Rubber, x1: np.ndarray, x2: np.ndarray) -> tuple:
    """W (J/m^3) and its derivatives in the invariants, at x1 = I1bar - 3, x2 = I2bar - 3.

    Returns
    -------
    tuple
        (W, psi1, psi2, psi11, psi12, psi22) in Pa; a derivative that vanishes identically is
        the float 0.0.

    Raises
    ------
    GentLimitError
        Where a Gent solid reaches its limit x1 >= Jm (the update is then halved).
    """
    half = 0.5 * material.shear_modulus
    model = material.model
    if model == "neo-hookean":
        return half * x1, half, 0.0, 0.0, 0.0, 0.0
    if model == "mooney-rivlin":
        c10, c01 = (1.0 - material.mooney_ratio) * half, material.mooney_ratio * half
        return c10 * x1 + c01 * x2, c10, c01, 0.0, 0.0, 0.0
    if model == "yeoh":
        c2, c3 = material.yeoh
        energy = half * x1 * (1.0 + x1 * (c2 + c3 * x1))
        first = half * (1.0 + x1 * (2.0 * c2 + 3.0 * c3 * x1))
        return energy, first, 0.0, half * (2.0 * c2 + 6.0 * c3 * x1), 0.0, 0.0
    limit = material.gent_limit
    slack = 1.0 - x1 / limit
    if np.any(slack <= 0):  # NaN (an inverted element) passes to the caller's J check
        raise GentLimitError(f"an iterate passed the gent limit I1bar - 3 = Jm = {limit:g}")
    with np.errstate(invalid="ignore"):
        energy = -half * limit * np.log1p(-x1 / limit)
    return energy, half / slack, 0.0, half / (limit * slack**2), 0.0, 0.0


class GentLimitError(NewtonError):
    """A Newton iterate passed a Gent rubber's limit I1bar - 3 = Jm: outside the rubber's
    states, so the update is halved or the step cut (a numerical failure where they run out,
    unless :func:`gent_locks` finds the rubber locking)."""


class GentLockError(NewtonError, InputError):
    """A Gent rubber locks: its stretch reached its limit I1bar - 3 = Jm where a route gave up
    (:func:`gent_locks`). Unlike other Newton failures it is an InputError: the limit is the
    user's gent_limit (the CLI: exit 2)."""

    def __init__(self, message: str, parameter: str | None = None) -> None:
        InputError.__init__(self, message, parameter)

    @staticmethod
    def locking(limit: float, step: tuple[float, float], stretch: float) -> GentLockError:
        """The one-line diagnosis of a rubber that locks in the failed load ``step`` (from,
        to: m) from a converged state at ``stretch`` (I1bar - 3) / Jm, naming gent_limit; a
        first step (from the undeformed body, ``stretch`` 0) bounds the depth from above."""
        done, depth = step
        if stretch > 0.0:
            where = (
                f"at depth {done:.6g} m: its stretch I1bar - 3 is {stretch:.6f} of its limit "
                f"Jm = {limit:g} there, and the load step on to {depth:.6g} m fails"
            )
        else:
            where = (
                f"before depth {depth:.6g} m: its first load step, from the undeformed body, "
                f"passes its limit I1bar - 3 = Jm = {limit:g}"
            )
        return GentLockError(
            f"gent_limit: the Gent rubber locks {where}; give a larger limit (a finer mesh, "
            "more depths or shorter steps do not pass the limit)",
            "gent_limit",
        )


def gent_stretch(material: Rubber, state: Kinematics) -> float:
    """Largest (I1bar - 3) / Jm of a converged ``state`` of a Gent ``material`` over its
    quadrature points (0 for any other model): 1 is the rubber's stretch limit."""
    if material.model != "gent":
        return 0.0
    a, b, c, d, h = state.F
    first = (a * a + b * b + c * c + d * d + h * h) * np.abs(state.J) ** (-2.0 / 3.0)
    return float(np.max(first - 3.0)) / material.gent_limit


def gent_locks(
    error: Exception, system: Any, x: np.ndarray, step: tuple[float, float], *, last: bool
) -> GentLockError | None:
    """The diagnosis of a load ``step`` (from the depth of ``x`` to a depth, m) that failed
    with ``error``: the Gent rubber locking where the last converged state ``x`` of ``system``
    (a hyperelastic system of the rubber) is at :data:`~shtaerman.guards.LOCKED` of its
    limit, or where, ``last`` (no cut left), ``x`` is undeformed and ``error`` is the limit
    (the first step passes it at every cut); None otherwise (no Gent rubber, or a step to cut
    or a numerical failure)."""
    material = system.material
    if material.model != "gent":
        return None
    undeformed = last and isinstance(error, GentLimitError) and not np.any(x)
    stretch = gent_stretch(material, system.state(x))
    if undeformed or stretch >= LOCKED:
        return GentLockError.locking(material.gent_limit, step, stretch)
    return None


def _volumetric(name: str, j_m1: np.ndarray, J: np.ndarray) -> tuple:
    """g(J), g'(J), g''(J) of the volumetric energy K/2 g^2 (J - 1 given without cancellation)."""
    if name == "quadratic":
        return j_m1, 1.0, 0.0
    return np.log1p(j_m1), 1.0 / J, -1.0 / J**2


def _zero(value: object) -> bool:
    """Whether ``value`` is the float 0.0 of a derivative that vanishes identically."""
    return isinstance(value, float) and value == 0.0


def _outer(x: np.ndarray, y: np.ndarray) -> np.ndarray:
    """(..., 5, 5) x_k y_m of two (5, ...) arrays."""
    return np.einsum("k...,m...->...km", x, y)


def _symmetric(x: np.ndarray, y: np.ndarray) -> np.ndarray:
    """(..., 5, 5) x y^T + y x^T."""
    product = _outer(x, y)
    return product + np.swapaxes(product, -1, -2)


def _hessian_J(F: np.ndarray) -> np.ndarray:
    """(..., 5, 5) d2J/dF2."""
    H = np.zeros((*F.shape[1:], N_COMPONENTS, N_COMPONENTS))
    for k, m, sign, f in HESSIAN_TERMS:
        H[..., k, m] = H[..., m, k] = sign * F[f]
    return H


def _hessian_I2(F: np.ndarray, planar: np.ndarray, dP: np.ndarray, q4: np.ndarray) -> np.ndarray:
    """(..., 5, 5) d2I2/dF2 with I2 = P^2 + h^2 q4, q4 = a^2 + b^2 + c^2 + d^2."""
    h = F[4]
    H = np.zeros((*F.shape[1:], N_COMPONENTS, N_COMPONENTS))
    H[..., :4, :4] = 2.0 * _outer(dP, dP)
    for k in range(4):
        H[..., k, k] += 2.0 * h**2
        H[..., k, 4] = H[..., 4, k] = 4.0 * h * F[k]
    H[..., 0, 3] += 2.0 * planar
    H[..., 3, 0] += 2.0 * planar
    H[..., 1, 2] -= 2.0 * planar
    H[..., 2, 1] -= 2.0 * planar
    H[..., 4, 4] = 2.0 * q4
    return H


def invariant_kinematics(
    material: Rubber, grad: np.ndarray, u_r: np.ndarray, radius: np.ndarray, p: np.ndarray
) -> Kinematics:
    """F, J, the stress and the consistent tangent (made when asked) of any :class:`Rubber`,
    pointwise.

    Same arguments and result as :func:`.hyperelastic.kinematics` (grad dimensionless, u_r and
    radius in m, p in Pa; stress and tangent in Pa); ``volume_gradient`` is g'(J) dJ/dF and
    ``constraint`` g(J) + p/K.
    """
    F, J, Jg, eta, planar_m1, J_m1 = deformation(grad, u_r, radius)
    a, b, c, d, h = F
    alpha, delta = grad[0, 0], grad[1, 1]
    planar, dP = Jg[4], np.stack([d, -c, -b, a])
    q4 = a**2 + b**2 + c**2 + d**2
    dI2 = np.concatenate([2.0 * planar * dP + 2.0 * h**2 * F[:4], (2.0 * h * q4)[None]])
    # I1bar - 3 and I2bar - 3 without cancellation (see hyperelastic.kinematics)
    q4_m2 = 2.0 * (alpha + delta) + alpha**2 + b**2 + c**2 + delta**2
    hoop = 2.0 * eta + eta**2
    with np.errstate(divide="ignore", invalid="ignore"):  # J <= 0 is caught by the caller
        log_J = np.log1p(J_m1)
        j23_m1, j43_m1 = np.expm1(-(2.0 / 3.0) * log_J), np.expm1(-(4.0 / 3.0) * log_J)
    j23, j43 = 1.0 + j23_m1, 1.0 + j43_m1
    x1 = j23 * invariant_excess(grad, eta, J_m1)  # I1bar - 3 (second order)
    bar1 = x1 + 3.0
    # dIbar/dF, their O(1) parts cancelled by hand (hyperelastic.deviatoric_direction)
    J_excess = 3.0 * J_m1
    d_bar1 = 2.0 * j23 * deviatoric_direction(grad, eta, planar_m1, q4_m2 + hoop - J_excess, J, Jg)
    x2, d_bar2 = 0.0, 0.0  # I2bar - 3 and its gradient: only Mooney-Rivlin's W has them
    if material.model == "mooney-rivlin":
        x2 = j43 * _i2_invariant_excess(grad, eta, planar_m1, J_m1)
        I2_m3 = 2.0 * planar_m1 + planar_m1**2 + q4_m2 + hoop * (2.0 + q4_m2)
        d_bar2 = j43 * (
            _i2_excess(grad, eta, planar_m1) - (4.0 / 3.0) * (I2_m3 - J_excess) / J * Jg
        )
    bar2 = x2 + 3.0
    energy, psi1, psi2, psi11, psi12, psi22 = energy_derivatives(material, x1, x2)
    with np.errstate(divide="ignore", invalid="ignore"):
        g, dg, ddg = _volumetric(material.volumetric, J_m1, J)
    stress = psi1 * d_bar1 + psi2 * d_bar2 - p * dg * Jg

    def tangent() -> np.ndarray:
        D = _invariant_tangent(
            F, Jg, (bar1, bar2, J, j23, j43), (psi1, psi2, psi11, psi12, psi22), (d_bar1, d_bar2)
        )
        D += (-p * ddg)[..., None, None] * _outer(Jg, Jg) if not _zero(ddg) else 0.0
        D += (-p * dg)[..., None, None] * _hessian_J(F)
        if not _zero(psi2):
            D += (psi2 * j43)[..., None, None] * _hessian_I2(F, planar, dP, q4)
            D += (-(4.0 / 3.0) * psi2 * j43 / J)[..., None, None] * _symmetric(dI2, Jg)
        return D

    return Kinematics(
        F=F,
        J=J,
        stress=stress,
        make_tangent=tangent,
        volume_gradient=dg * Jg,
        constraint=g + material.inverse_bulk * p,
        make_energy=lambda: energy - p * g - 0.5 * material.inverse_bulk * p**2,
    )


def _i2_invariant_excess(
    grad: np.ndarray, eta: np.ndarray, planar_m1: np.ndarray, J_m1: np.ndarray
) -> np.ndarray:
    """I2 - 3 J^(4/3) (second order in the strain) without cancellation, as
    :func:`.hyperelastic.invariant_excess` does I1's."""
    alpha, b, c, delta = grad[0, 0], grad[0, 1], grad[1, 0], grad[1, 1]
    planar_2 = alpha * delta - b * c
    squares = alpha**2 + b**2 + c**2 + delta**2
    hoop = eta * (2.0 + eta)
    poly = (
        -2.0 * planar_2
        + planar_m1**2
        + squares
        + 2.0 * eta**2
        + hoop * (2.0 * (alpha + delta) + squares)
        - 4.0 * eta * planar_m1
    )
    return poly - 3.0 * power_excess(J_m1, 4.0 / 3.0)


def _i2_excess(grad: np.ndarray, eta: np.ndarray, planar_m1: np.ndarray) -> np.ndarray:
    """dI2/dF - 4 dJ/dF (5-vector, O(strain)) from the displacement gradient, without the
    cancellation of the identity's 4 (1, 0, 0, 1, 1) in each (arguments as in
    :func:`.hyperelastic.deviatoric_direction`)."""
    alpha, b, c, delta = grad[0, 0], grad[0, 1], grad[1, 0], grad[1, 1]
    hoop = eta * (2.0 + eta)  # h^2 - 1
    h2 = 1.0 + hoop
    q4_m2 = 2.0 * (alpha + delta) + alpha**2 + b**2 + c**2 + delta**2
    return 2.0 * np.stack(
        [
            (1.0 + delta) * planar_m1 + alpha - delta + eta**2 - 2.0 * eta * delta + hoop * alpha,
            -c * planar_m1 + c + 2.0 * eta * c + h2 * b,
            -b * planar_m1 + b + 2.0 * eta * b + h2 * c,
            (1.0 + alpha) * planar_m1 + delta - alpha + eta**2 - 2.0 * eta * alpha + hoop * delta,
            2.0 * eta + eta * q4_m2 + (alpha - delta) ** 2 + (b + c) ** 2,
        ]
    )


def _invariant_tangent(
    F: np.ndarray, Jg: np.ndarray, scalars: tuple, psi: tuple, gradients: tuple
) -> np.ndarray:
    """The parts of D that every model has: psi1 d2I1bar/dF2, the J-terms of psi2 d2I2bar/dF2
    and the second derivatives' outer products (Pa, (..., 5, 5))."""
    bar1, bar2, J, j23, _ = scalars
    psi1, psi2, psi11, psi12, psi22 = psi
    d_bar1, d_bar2 = gradients
    ones = np.ones_like(J)
    outer_coefficient = (10.0 / 9.0) * psi1 * bar1 / J**2 + (28.0 / 9.0) * psi2 * bar2 / J**2
    hessian = -(2.0 / 3.0) * psi1 * bar1 / J - (4.0 / 3.0) * psi2 * bar2 / J
    tangent = outer_coefficient[..., None, None] * _outer(Jg, Jg)
    tangent += (-(4.0 / 3.0) * psi1 * j23 / J)[..., None, None] * _symmetric(F, Jg)
    tangent += hessian[..., None, None] * _hessian_J(F)
    tangent += (2.0 * psi1 * j23 * ones)[..., None, None] * np.eye(N_COMPONENTS)
    if not _zero(psi11):
        tangent += (psi11 * ones)[..., None, None] * _outer(d_bar1, d_bar1)
    if not _zero(psi12):
        tangent += (psi12 * ones)[..., None, None] * _symmetric(d_bar1, d_bar2)
    if not _zero(psi22):
        tangent += (psi22 * ones)[..., None, None] * _outer(d_bar2, d_bar2)
    return tangent
