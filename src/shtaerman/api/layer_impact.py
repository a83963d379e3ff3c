"""The quasi-static impact on a layer: the static FE force-depth law of the layer, integrated.

The reference of the dynamic impact on a layer (:mod:`shtaerman.fem.dynamic_layer`) in its
massless limit: the linear static FE (:func:`shtaerman.contact`) on the same layer gives
P(x) at a ladder of depths, interpolated monotonically in (ln x, ln P) and continued below
the first depth by the power law through the first two points (the contact is then small
against the thickness: the half-space's x^q); :func:`shtaerman.theory.impact_ode.integrate_impact`
integrates M x'' = -P(x).
"""

from __future__ import annotations

from collections.abc import Callable

import numpy as np
from scipy.interpolate import PchipInterpolator

from ..theory.impact_ode import NumericalImpact, integrate_impact
from ..theory.indenter import PowerLawIndenter
from ..theory.materials import Material
from .fem_contact import contact

__all__ = ["layer_force_law", "quasi_static_layer_impact"]


def layer_force_law(depths: np.ndarray, forces: np.ndarray) -> Callable[[np.ndarray], np.ndarray]:
    """P(x) in N from FE depths (m, increasing, > 0) and forces (N, increasing, > 0).

    Monotone cubic in (ln x, ln P) between the points, the power law of the first two points
    below them and of the last two beyond them; P(0) = 0.
    """
    log_x, log_p = np.log(depths), np.log(forces)
    spline = PchipInterpolator(log_x, log_p, extrapolate=False)
    low = (log_p[1] - log_p[0]) / (log_x[1] - log_x[0])
    high = (log_p[-1] - log_p[-2]) / (log_x[-1] - log_x[-2])

    def force(x: np.ndarray) -> np.ndarray:
        x = np.asarray(x, dtype=float)
        lx = np.log(np.maximum(x, 1e-300))
        inner = spline(np.clip(lx, log_x[0], log_x[-1]))
        below = log_p[0] + low * (lx - log_x[0])
        above = log_p[-1] + high * (lx - log_x[-1])
        out = np.where(lx < log_x[0], below, np.where(lx > log_x[-1], above, inner))
        return np.where(x > 0, np.exp(out), 0.0)

    return force


def quasi_static_layer_impact(
    indenter: PowerLawIndenter,
    body: Material,
    thickness: float,
    base: str,
    mass: float,
    velocity: float,
    depths: np.ndarray,
    **contact_options: object,
) -> tuple[NumericalImpact, object]:
    """The quasi-static impact (kg, m/s) on the static FE law of a layer (m, base).

    ``depths`` (m, increasing) must reach the maximum approach; ``contact_options`` go to
    :func:`shtaerman.contact` (e.g. ``estimate=False``). Returns the impact and the contact
    result.
    """
    result = contact(
        indenter, body, depths=depths, thickness=thickness, base=base, **contact_options
    )
    steps = result.steps
    force = layer_force_law(
        np.array([s["depth"] for s in steps]), np.array([s["force"] for s in steps])
    )
    return integrate_impact(mass, velocity, force, float(depths[-1])), result
