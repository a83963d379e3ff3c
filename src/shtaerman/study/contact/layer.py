"""A contact study on a layer of thickness H on a rigid base: its force against Shtaerman's
half-space at the impact's maximum depth, and the impact on the layer's FE force-depth law.

The layer is given by H in m or by ``thickness_ratio`` = H / a_c (a_c the half-space contact
radius at the half-space impact's x_c). Its findings (:class:`LayerFindings`): the force ratio
P / P_Shtaerman at x_c with its error, the quasi-static impact on the layer's tabulated FE law,
and with ``dynamic = true`` the dynamic FE impact on it (benchmarks/FEM_NOTES.md, "Study error
estimates").
"""

from __future__ import annotations

import math
import warnings
from collections.abc import Callable
from dataclasses import dataclass, replace

import numpy as np

from ...fem.dynamic_contact import DynamicSettings
from ...fem.mesh import (
    Geometry,
    MeshSettings,
    check_thickness_range,
    resolved_depths,
)
from ...theory.materials import Material
from ...theory.sneddon import Indenter
from ..checks import Check
from .accuracy import AccuracyResult
from .contact_law import FemContactLaw

__all__ = [
    "LEVELS",
    "QUICK_DYNAMIC",
    "LayerFindings",
    "LayerSpec",
    "check_thickness",
    "layer_checks",
    "layer_depths",
    "layer_findings",
]

QUICK_DYNAMIC = DynamicSettings(steps=100, size=0.05)
"""Coarse dynamic settings of a layer study's dynamic impact in ``verify --quick``."""
LEVELS = (0.01, 0.05)
"""Departures P / P_Shtaerman - 1 the findings and the map mark: 1 % and 5 %."""
REFERENCE_EXPONENT = 1.5
"""The indenter exponent n of :data:`REFERENCE_MAP`."""
REFERENCE_THICKNESS = (0.1, 0.2, 0.5, 1.0, 2.0, 5.0, 10.0, 20.0, 50.0, 100.0, 200.0)
"""H / a_c of :data:`REFERENCE_MAP`."""
# fmt: off
REFERENCE_MAP = {
    ("bonded", 0.3): (30.0016, 14.9627, 5.93703, 3.00689, 1.73734, 1.21767, 1.09765, 1.04628,
                      1.01796, 1.00892, 1.00446),
    ("bonded", 0.45): (71.8964, 33.3697, 10.3979, 4.16324, 2.00426, 1.26928, 1.11775, 1.05519,
                       1.02129, 1.01055, 1.00526),
    ("bonded", 0.5): (1477.95, 204.155, 20.5443, 5.47300, 2.21019, 1.30190, 1.12988, 1.06046,
                      1.02324, 1.01150, 1.00574),
    ("lubricated", 0.5): (24.5172, 12.2619, 4.92951, 2.56747, 1.58010, 1.17847, 1.08146,
                          1.03894, 1.01520, 1.00757, 1.00379),
}
# fmt: on
"""P / P_Shtaerman at x_c over :data:`REFERENCE_THICKNESS` for n = 3/2 (any A and E2: the
ratio of a power-law indenter depends on H / a, n, nu2 and the base alone), measured by
``sweeps/layer.toml`` at the default mesh (estimated errors below 7e-4 of the ratio; a
lubricated layer's ratio is the same for nu2 = 0.3-0.5 to 1e-5). The layer map of a study with
n = 3/2 draws them as reference lines."""


@dataclass(frozen=True)
class LayerSpec:
    """A layer as a study gives it: thickness in m or H / a_c (one of them), and its base."""

    thickness: float | None = None
    """H in m."""
    thickness_ratio: float | None = None
    """H / a_c (a_c: the half-space contact radius at the half-space impact's x_c)."""
    base: str = "bonded"
    dynamic: bool = False
    """Also run the dynamic FE impact on the layer (its restitution)."""
    density: float = 1100.0
    """The layer's density in kg/m^3 (for ``dynamic``)."""

    def resolved(self, contact_radius: float) -> LayerSpec:
        """Both spellings filled in for the half-space contact radius a_c in m."""
        if self.thickness is not None:
            return replace(self, thickness_ratio=self.thickness / contact_radius)
        if self.thickness_ratio is None:
            raise ValueError("a layer needs its thickness or its thickness_ratio")
        return replace(self, thickness=self.thickness_ratio * contact_radius)

    @property
    def geometry(self) -> Geometry:
        """The body's shape: this (resolved) layer."""
        return Geometry(self.thickness, self.base)


def check_thickness(
    thickness: float,
    refined_at: Callable[[float | None], list[float]],
    velocity: float | None,
    exponent: float,
    where: str,
) -> None:
    """Refuse (:class:`~shtaerman.validation.LimitError` naming the thickness) a layer of
    ``thickness`` m that a mesh does not take at its refined radius, ``refined_at(velocity)``
    (m, one per mesh, of any profile: :func:`.indentation.refined_radius`, at the depths the
    impact at ``velocity`` m/s sets; None: depths given): the mesh's own bounds,
    :data:`~shtaerman.fem.mesh.MIN_THICKNESS` .. ``MAX_THICKNESS`` refined radii
    (``where`` names the depths), naming the velocity that fits it too
    (:func:`shtaerman.fem.mesh.fitting_velocity` of a tip z ~ r^``exponent``), checked at the
    radii it sets (none named where it does not). The one check of a contact curve's layer:
    the API's and a contact study's or sweep case's."""
    from ...fem.mesh import fitting_velocity
    from ...validation import InputError, LimitError

    for refined in refined_at(velocity):
        try:
            check_thickness_range(thickness, refined, where)
        except LimitError as error:
            fits = (
                None
                if velocity is None
                else fitting_velocity(thickness, refined, velocity, exponent)
            )
            if fits is None:  # depths given, or beyond the floats
                raise
            try:
                with warnings.catch_warnings():  # a slower or faster impact, only sized
                    warnings.simplefilter("ignore")
                    moved = refined_at(fits[0])
                for radius in moved:
                    check_thickness_range(thickness, radius, "")
            except InputError:  # not brought within
                raise error from None
            raise LimitError(str(error) + fits[1], "thickness") from None


def layer_depths(
    layer: Geometry, indenter: Indenter, *meshes: MeshSettings
) -> tuple[float, float, float] | None:
    """The thickness of ``layer`` and the shallowest and deepest depths of a power-law
    ``indenter`` at which each of ``meshes`` resolves it (all m; :func:`check_thickness`'s
    range: :func:`shtaerman.fem.mesh.resolved_depths` of their margins)."""
    return resolved_depths(layer, indenter, *(mesh.margin for mesh in meshes))


@dataclass(frozen=True)
class LayerFindings:
    """What a layer does to the paper's contact and impact (SI units; ratios dimensionless).

    Attributes
    ----------
    force_ratio : float
        P_layer / P_Shtaerman at the half-space impact's x_c.
    force_ratio_error : float
        Estimated relative error of ``force_ratio`` (FE estimate + interpolation); NaN when
        the ladder's estimate is missing.
    x_max, P_max : float
        Maxima of the quasi-static impact on the layer's tabulated FE law (m, N).
    x_max_ratio, P_max_ratio : float
        x_max / x_c and P_max / P_c of the half-space impact.
    curve : tuple of (float, float)
        (H / a, P / P_Shtaerman) at every depth of the study, a the half-space contact radius.
    restitution, x_max_dynamic, P_max_dynamic : float or None
        The dynamic FE impact on the layer: its restitution and maxima (m, N); None unless
        the study asks for it.
    dynamic_energy_balance : float or None
        Its energy balance error, of M v0^2/2.
    """

    thickness: float
    thickness_ratio: float
    base: str
    contact_radius: float
    force_ratio: float
    force_ratio_error: float
    x_max: float
    P_max: float
    x_max_ratio: float
    P_max_ratio: float
    curve: tuple[tuple[float, float], ...]
    restitution: float | None = None
    x_max_dynamic: float | None = None
    P_max_dynamic: float | None = None
    dynamic_energy_balance: float | None = None

    def to_dict(self) -> dict[str, object]:
        """Plain data for JSON (``curve`` as two lists)."""
        document: dict[str, object] = {
            key: getattr(self, key) for key in self.__dataclass_fields__ if key != "curve"
        }
        document["curve"] = {
            "thickness_ratio": [point[0] for point in self.curve],
            "force_ratio": [point[1] for point in self.curve],
        }
        return document


def _interpolation_error(law: FemContactLaw, depth: float) -> float:
    """|quadratic - linear| log-log interpolation of the force at ``depth``, relative."""
    log_x, log_p = np.log(law.depths), np.log(law.forces)
    nearest = np.sort(np.argsort(np.abs(log_x - math.log(depth)))[:3])
    if nearest.size < 3:
        return 0.0
    quadratic = np.polyval(np.polyfit(log_x[nearest], log_p[nearest], 2), math.log(depth))
    return abs(math.expm1(float(quadratic) - math.log(float(law.force(depth)))))


def _force_error(accuracy: AccuracyResult) -> float:
    """The ladder's estimated relative error of the force (NaN: its estimate is missing)."""
    estimate = accuracy.estimates.get("force")
    return math.nan if estimate is None else estimate.error


def layer_findings(
    layer: LayerSpec,
    accuracy: AccuracyResult,
    law: FemContactLaw,
    half_space: dict[str, float],
    layer_impact: dict[str, float],
) -> LayerFindings:
    """The findings of a layer study.

    Parameters
    ----------
    layer : LayerSpec
        The resolved layer.
    accuracy : AccuracyResult
        The mesh ladder of the layer's contact curve (its finest level made ``law``).
    law : FemContactLaw
        The layer's FE law, scaled to the pair's E*.
    half_space, layer_impact : dict
        Maxima (``x_c``, ``P_c``, ``a_c``) of the impact on the half-space (exact) and on the
        layer's tabulated law.
    """
    x_c, p_c, a_c = half_space["x_c"], half_space["P_c"], half_space["a_c"]
    curve = tuple(
        (
            layer.thickness / float(accuracy.finest.exact.contact_radius(step.depth)),
            step.force / float(accuracy.finest.exact.force(step.depth)),
        )
        for step in accuracy.finest.steps
    )
    return LayerFindings(
        thickness=float(layer.thickness),
        thickness_ratio=float(layer.thickness / a_c),
        base=layer.base,
        contact_radius=a_c,
        force_ratio=float(law.force(x_c)) / p_c,
        force_ratio_error=_force_error(accuracy) + _interpolation_error(law, x_c),
        x_max=layer_impact["x_c"],
        P_max=layer_impact["P_c"],
        x_max_ratio=layer_impact["x_c"] / x_c,
        P_max_ratio=layer_impact["P_c"] / p_c,
        curve=curve,
    )


def with_dynamic_impact(
    findings: LayerFindings,
    layer: LayerSpec,
    indenter: Indenter,
    half_space: Material,
    impact: tuple[float, float],
    quick: bool = False,
    friction: float | None = None,
) -> LayerFindings:
    """``findings`` with the dynamic FE impact (mass kg, velocity m/s) of a rigid striker on the
    resolved ``layer`` of ``half_space`` (density ``layer.density``): restitution, x_max (m),
    P_max (N) and its energy balance error; :data:`QUICK_DYNAMIC` settings if ``quick``;
    ``friction`` the striker's surface (None frictionless, inf bonded, else Coulomb's mu)."""
    from ...fem.impact import run_impact

    settings = QUICK_DYNAMIC if quick else DynamicSettings()
    physics = {"friction": friction, "geometry": layer.geometry}
    result = run_impact(indenter, half_space, layer.density, *impact, settings, **physics)
    return replace(
        findings,
        restitution=float(result.restitution),
        x_max_dynamic=float(result.x_max),
        P_max_dynamic=float(result.P_max),
        dynamic_energy_balance=float(result.energy_balance_error),
    )


def layer_checks(findings: LayerFindings, force: float, impact: float) -> list[Check]:
    """Pass or fail of a layer study: the FE error estimate of the force ratio within ``force``;
    the layer no softer than the half-space (within its error and ``force``); the impact on it
    no deeper and no softer than on the half-space (within ``impact``). Without the estimate
    (NaN: a ladder level failed, the report says why) its check is left out, not failed."""
    error = findings.force_ratio_error
    known = math.isfinite(error)
    checks = [Check("layer force ratio error estimate", error, force)] if known else []
    margin = error if known else 0.0
    checks += [
        Check("layer P / P_Shtaerman >= 1", min(0.0, findings.force_ratio - 1.0 + margin), force),
        Check("layer impact x_max <= x_c", max(0.0, findings.x_max_ratio - 1.0), impact),
        Check("layer impact P_max >= P_c", min(0.0, findings.P_max_ratio - 1.0), impact),
    ]
    if findings.dynamic_energy_balance is not None:  # the dynamic studies' own limit
        checks.append(Check("layer dynamic energy balance", findings.dynamic_energy_balance, 1e-2))
    return checks
