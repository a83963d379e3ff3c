"""Dynamic impact of a rigid striker z = A r^n, a sphere or a tabulated z(r), on the elastic
half-space (elastodynamic FEM).

:func:`prepare_dynamic_impact` meshes, assembles (the normal mass taken off the contact
candidates, :func:`.elasticity.redistribute_normal_mass`; the optional absorbing layer,
:class:`.dynamic_layer.AbsorbingLayer`) and factorizes the effective matrix once;
:meth:`DynamicImpactSetup.march` steps the striker and the body with unilateral contact,
frictionless, bonded or Coulomb (:mod:`.stepper`: generalized-alpha, or Newmark with
``spectral_radius=None``), dt = t_y / ``steps``. The choice of scheme:
benchmarks/FEM_NOTES.md, "Moved from the docstrings", fem/dynamic_contact.py."""

from __future__ import annotations

import math
import sys
import time
import warnings
from collections.abc import Callable
from dataclasses import dataclass, replace

import numpy as np
import scipy.sparse as sp
from skfem import MeshTri
from threadpoolctl import threadpool_limits

from ..guards import check_reach, check_wave_speed, tip_exponents
from ..theory.contact import PowerLawContact
from ..theory.impact import duration_integral
from ..theory.indenter import PowerLawIndenter
from ..theory.materials import RIGID, Material, effective_modulus, validate_density
from ..theory.profile_impact import ProfileImpactResult, solve_profile_impact
from ..theory.radiation import (
    RadiationEstimate,
    impact_radiation,
    rayleigh_root,
)
from ..theory.sneddon import Indenter, SneddonContact, contact_law
from ..theory.viscoelastic import PronySeries
from ..validation import InputError, LimitError, validate_positive
from .contact.linear import mass_factor
from .contact.stick import CoupledCompliance, radial_dofs
from .dynamic_layer import (
    AbsorbingLayer,
    lateral_absorber,
    layer_dofs,
    layer_impact_mesh,
)
from .elasticity import (
    ElasticSystem,
    assemble,
    consistent_mass,
    mixed_matrix,
    redistribute_normal_mass,
    weighted_mass,
)
from .impact_limits import MAX_SIZE, MIN_STEPS
from .impact_run import (
    MAX_STEPS,
    ImpactRun,
    finished_run,
    fitted_peak,
    impact_parameters,
    mesh_counts,
    parabola_peak,
    refined_steps,
    validate_steps,
)
from .mesh import (
    HALF_SPACE,
    MAX_DOFS,
    Geometry,
    check_thickness_range,
    fitting_velocity,
    growth_error,
    halfspace_mesh,
)
from .solver import Factorization, factorize_scaled
from .stepper import (
    ContactCandidates,
    ImpactHistory,
    ImpactProblem,
    Striker,
    TimeScheme,
    march,
)
from .viscoelastic import ViscoelasticShear, sizing_impact, viscoelastic_shear

__all__ = [
    "MAX_DOFS",
    "DynamicImpactSetup",
    "DynamicSettings",
    "RadiatedFraction",
    "check_dynamic_impact",
    "estimate_dofs",
    "prepare_dynamic_impact",
]

MAX_DENSE_CORRECTION = 400e6
"""Largest dense W = K_eff^-1 S in bytes; a larger one is refused (InputError)."""
MAX_DOMAIN = 1e7
"""Largest domain radius in refined radii (the meshes' tested range)."""
RUN_DURATIONS = 3.0
"""The longest dynamic run in quasi-static impact durations t_y (a viscoelastic body's contact
time)."""
DYNAMIC_ACCURACY_CHECK = 1e-6
"""Largest accepted componentwise backward error of the scaled effective matrix before the
stricter fallbacks of :func:`.solver.factorize_scaled`."""


def validate_friction(friction: object) -> float | None:
    """Return the striker's Coulomb coefficient (None: frictionless, inf: bonded), or raise
    InputError naming ``friction``."""
    if friction is None:
        return None
    if isinstance(friction, bool) or not isinstance(friction, (int, float)) or not friction >= 0:
        raise InputError(
            f"friction: must be >= 0 (inf: bonded, no slip) or None (frictionless), got "
            f"{friction!r}",
            "friction",
        )
    return float(friction)


@dataclass(frozen=True)
class DynamicSettings:
    """Numerical controls of the dynamic impact, relative to the quasi-static impact.

    Attributes
    ----------
    steps : int
        Time steps per quasi-static impact duration t_y (dt = t_y / steps), >= 50.
    margin : float
        Refined (contact candidate) radius / quasi-static contact radius a_c, > 1.
    size : float
        Smallest element size / refined radius.
    axis_size : float
        Element size at the axis / refined radius.
    growth : float
        Element size growth per unit distance from the refined zone, in (0, 1].
    domain : float
        Domain radius / refined radius, in [1e2, 1e7]; the domain reaches at least as far as
        the fastest wave travels in the run (:func:`wave_reach`, up to ``MAX_DOMAIN``).
    layer_start : float
        R_a / (c_s t_y), > 1/2: where the absorbing layer starts, and the monitor radius of
        the reflected energy.
    layer_ramp : float
        Ramp length of the layer damping / (c_s t_y) (used when ``layer_width`` is None).
    layer_rate : float
        Peak damping rate zeta_max times t_y, >= 0. 0: no layer.
    tail : float
        Stepping after separation, in units of R_a / c_R, >= 0 (0: no reflection measured).
    layer_width : float or None
        Width of a sin^2 damping bump / (c_s t_y); None: a quadratic ramp over ``layer_ramp``
        to a plateau out to the far arc.
    spectral_radius : float or None
        rho_inf of generalized-alpha in [0, 1]; None: Newmark average acceleration.

    The body's geometry (:class:`.mesh.Geometry`) is taken beside these settings.
    """

    steps: int = 200
    margin: float = 1.3
    size: float = 1.0 / 40.0
    axis_size: float = 1.0 / 800.0
    growth: float = 0.2
    domain: float = 1.0e4
    layer_start: float = 0.75
    layer_ramp: float = 1.0
    layer_rate: float = 0.0
    tail: float = 1.25
    layer_width: float | None = 3.0
    spectral_radius: float | None = 0.9

    def __post_init__(self) -> None:
        validate_steps(self.steps, (MIN_STEPS, MAX_STEPS))
        for name in ("margin", "size", "axis_size", "growth", "domain", "layer_ramp"):
            validate_positive(f"mesh {name}", getattr(self, name))
        if self.margin <= 1.0:
            raise InputError(
                f"margin must be > 1 (contact inside the refined zone), got {self.margin!r}"
            )
        if self.size > MAX_SIZE * (1.0 + 1e-12):  # a ladder's size / (1/sqrt 2)^2 rounds up
            raise InputError(f"size must lie in (0, {MAX_SIZE:g}] refined radii, got {self.size!r}")
        if self.growth > 1.0:
            raise InputError(f"growth must lie in (0, 1], got {self.growth!r}")
        if not 1e2 <= self.domain <= MAX_DOMAIN:
            raise InputError(f"domain must lie in [1e2, 1e7] refined radii, got {self.domain!r}")
        if self.layer_start <= 0.5:
            raise InputError(
                f"layer_start must be > 0.5 (R_a beyond c_s t_y / 2), got {self.layer_start!r}"
            )
        if not (math.isfinite(self.layer_rate) and self.layer_rate >= 0):
            raise InputError(f"layer_rate must be >= 0, got {self.layer_rate!r}")
        rho_inf = self.spectral_radius
        if rho_inf is not None and not (
            isinstance(rho_inf, (int, float)) and 0.0 <= rho_inf <= 1.0
        ):
            raise InputError(
                f"spectral_radius must lie in [0, 1] or be None (Newmark), got {rho_inf!r}"
            )
        if not (math.isfinite(self.tail) and self.tail >= 0):
            raise InputError(f"tail must be >= 0, got {self.tail!r}")

    def refined(self, factor: float) -> DynamicSettings:
        """These settings with the mesh size field divided and the time steps multiplied by
        ``factor`` (> 1 refines): h and dt shrink together, so a ladder of refined settings
        converges in space and time at once (mesh dofs ~ factor^2, steps ~ factor).

        Raises
        ------
        shtaerman.validation.InputError
            If ``factor`` is not > 0 or the result leaves the settings' valid ranges.
        """
        steps = refined_steps(self.steps, factor, (MIN_STEPS, MAX_STEPS))
        return replace(
            self,
            size=self.size / factor,
            axis_size=self.axis_size / factor,
            growth=min(self.growth / factor, 1.0),
            steps=steps,
        )


def estimate_dofs(settings: DynamicSettings, domain: float | None = None) -> int:
    """Dofs of the graded mesh predicted before meshing (fitted to gmsh's output, within ~30 %),
    ``domain`` its radius in refined radii (None: ``settings.domain``); the largest int where
    the sizes underflow."""
    h0, g = settings.size, settings.growth
    domain = settings.domain if domain is None else domain
    try:
        strip = 1.0 / (h0 * g)
        fan = (math.pi / (g * g)) * math.log(max(domain * g / h0, 2.0))
    except ZeroDivisionError:  # a size or growth whose product underflows: no mesh
        return int(sys.float_info.max)
    axis = math.log(max(h0 / settings.axis_size, 1.0)) / 0.1 * 4.0
    return int(min(4.5 * 2.0 * (strip + fan + axis), sys.float_info.max))  # int: as before


@dataclass(frozen=True)
class _QuasiStatic:
    """The quasi-static impact of the rigid striker, the scales of the dynamic run (SI)."""

    beta: float
    force_exponent: float
    x_c: float
    t_y: float
    a_c: float


def profile_sizing_impact(
    indenter: Indenter, half_space: Material, mass: float, velocity: float
) -> ProfileImpactResult | None:
    """The quasi-static impact that sizes the FE runs of a sphere or a table (mass in kg,
    velocity in m/s): Sneddon's law at the rigid striker's E* (:func:`effective_modulus`, the
    case's exact impact's), by quadrature (seconds on a long table: a case solves it once and
    passes it to every run of its ladder as ``exact``); None for the power law, whose closed
    form costs nothing."""
    if isinstance(indenter, PowerLawIndenter):
        return None
    modulus = effective_modulus(RIGID, half_space)
    return solve_profile_impact(mass, velocity, SneddonContact(indenter, modulus))


def _quasi_static(
    indenter: Indenter,
    half_space: Material,
    striker: Striker,
    exact: ProfileImpactResult | None = None,
) -> _QuasiStatic:
    """x_c from the energy balance M v0^2 / 2 = beta x_c^(q+1) / (q+1), t_y = 2 I x_c / v0;
    another profile's from its :func:`profile_sizing_impact` (``exact`` when solved already;
    beta NaN, q its smooth tip's 3/2). The power law's x_c is taken in this power form: the
    refined radius follows from it, and gmsh's mesh depends on its last bit."""
    if not isinstance(indenter, PowerLawIndenter):
        if exact is None:
            exact = profile_sizing_impact(indenter, half_space, striker.mass, striker.velocity)
        return _QuasiStatic(math.nan, exact.force_exponent, exact.x_c, exact.t_y, exact.a_c)
    law = PowerLawContact(indenter, half_space.plane_strain_modulus)
    q, mass, velocity = law.force_exponent, striker.mass, striker.velocity
    x_c = ((q + 1.0) * mass * velocity**2 / (2.0 * law.beta)) ** (1.0 / (q + 1.0))
    return _QuasiStatic(
        beta=law.beta,
        force_exponent=q,
        x_c=x_c,
        t_y=2.0 * duration_integral(q) * x_c / velocity,
        a_c=float(law.contact_radius(x_c)),
    )


def _viscoelastic_extent(
    indenter: Indenter,
    half_space: Material,
    striker: Striker,
    prony: PronySeries,
    settings: DynamicSettings,
    glassy: float,
) -> tuple[float, float]:
    """Contact time (s) and largest contact radius (m) of the quasi-static viscoelastic impact
    (:func:`shtaerman.theory.viscoelastic.viscoelastic_impact`, coarse: for sizing only);
    ``glassy`` the elastic impact's t_y in s at the instantaneous modulus.

    Raises
    ------
    shtaerman.validation.InputError
        If the run would need more than ``MAX_STEPS`` time steps, or the contact lasts more
        than :data:`.viscoelastic.MAX_GLASSY_DURATIONS` glassy ones.
    """
    law = contact_law(indenter, half_space.plane_strain_modulus)
    slow = sizing_impact(striker.mass, striker.velocity, law, prony, glassy)
    steps = RUN_DURATIONS * slow.t_contact / glassy * settings.steps
    if steps > MAX_STEPS:
        raise InputError(
            f"prony: the viscoelastic impact lasts {slow.t_contact / glassy:.3g} glassy impact "
            f"durations, {steps:.3g} time steps at {settings.steps} per t_y (at most "
            f"{MAX_STEPS}); use fewer time steps or a series that relaxes less",
            "prony",
        )
    return slow.t_contact, float(law.contact_radius(slow.x_max))


@dataclass(frozen=True)
class _Scales:
    """Lengths, times and speeds of one impact, derived from the inputs and the settings."""

    quasi_static: _QuasiStatic
    shear_wave_speed: float
    rayleigh_wave_speed: float
    slowest_rayleigh_speed: float
    dt: float
    refined: float
    domain_radius: float
    layer: AbsorbingLayer
    has_layer: bool
    longest_t_y: float

    @property
    def t_y(self) -> float:
        """Quasi-static impact duration in s."""
        return self.quasi_static.t_y

    @property
    def inner_radius(self) -> float:
        """Monitor radius R_a of the reflected energy in m: where the layer starts, scaled by
        the slowest over the fastest wave speed (a viscoelastic body's relaxed over its glassy
        one; 1 for an elastic body), so that it is the same in the relaxed limit as for the
        elastic body at the relaxed modulus; within half the domain."""
        slowest = self.slowest_rayleigh_speed / self.rayleigh_wave_speed
        return min(self.layer.start * min(slowest, 1.0), 0.5 * self.domain_radius)


def _scales(
    indenter: Indenter,
    half_space: Material,
    rho: float,
    striker: Striker,
    settings: DynamicSettings,
    geometry: Geometry,
    prony: PronySeries | None = None,
    qs: _QuasiStatic | None = None,
) -> _Scales:
    """Quasi-static impact (``qs`` when already solved: a profile's quadrature is costly),
    wave speeds, time step, refined and domain radii, layer.

    With ``prony`` (a viscoelastic body) the refined zone, the layer and the run's length are
    sized for the quasi-static viscoelastic impact (Lee-Radok/Ting, its largest contact radius
    and its contact time); dt still follows the glassy impact.
    """
    qs = qs if qs is not None else _quasi_static(indenter, half_space, striker)
    nu = half_space.poisson_ratio
    shear = half_space.youngs_modulus / (2.0 * (1.0 + nu))
    c_s = math.sqrt(shear / rho) if rho > 0 else math.inf  # massless: no waves
    t_y, widest = qs.t_y, qs.a_c
    if prony is not None:
        t_y, widest = _viscoelastic_extent(indenter, half_space, striker, prony, settings, t_y)
    refined = settings.margin * widest
    reach = min(wave_reach(c_s, nu, t_y), MAX_DOMAIN * refined)  # capped: radiates ~nothing
    domain_radius = max(settings.domain * refined, reach)
    layer = AbsorbingLayer(
        start=settings.layer_start * c_s * t_y,
        ramp=settings.layer_ramp * c_s * t_y,
        rate=settings.layer_rate / qs.t_y,
        width=None if settings.layer_width is None else settings.layer_width * c_s * t_y,
    )
    has_layer = layer.start + layer.ramp < 0.5 * domain_radius and settings.layer_rate > 0
    if geometry.thickness is not None:  # a layer: its lateral edge and absorber
        layer, domain_radius, has_layer = lateral_absorber(
            settings, geometry.thickness, c_s, t_y, refined
        )
    return _Scales(
        quasi_static=qs,
        shear_wave_speed=c_s,
        rayleigh_wave_speed=c_s / rayleigh_root(nu),
        slowest_rayleigh_speed=_relaxed_rayleigh_speed(half_space, rho, prony),
        dt=qs.t_y / settings.steps,
        refined=refined,
        domain_radius=domain_radius,
        layer=layer,
        has_layer=has_layer,
        longest_t_y=t_y,
    )


def wave_reach(shear_wave_speed: float, poisson_ratio: float, t_y: float) -> float:
    """How far in m the fastest wave travels in the longest run (``RUN_DURATIONS`` t_y, t_y in
    s): c_p, or c_s (m/s) at nu = 0.5 (the pressure then is instantaneous, no wave); 0
    without waves (c_s inf: a massless body). No wave reaches a far arc this far out during
    the run: none comes back to the contact or inside R_a."""
    if not math.isfinite(shear_wave_speed):
        return 0.0
    ratio = 1.0
    if poisson_ratio < 0.5:
        ratio = math.sqrt(2.0 * (1.0 - poisson_ratio) / (1.0 - 2.0 * poisson_ratio))
    return RUN_DURATIONS * ratio * shear_wave_speed * t_y


def _relaxed_rayleigh_speed(half_space: Material, rho: float, prony: PronySeries | None) -> float:
    """Rayleigh wave speed c_R in m/s of the fully relaxed body (shear modulus G0 g_inf, the
    bulk modulus unchanged: nu rises toward 0.5): the slowest waves of a viscoelastic body,
    the speed of all of them in its relaxed limit; the elastic c_R without ``prony``."""
    if rho == 0:
        return math.inf
    nu, young = half_space.poisson_ratio, half_space.youngs_modulus
    shear = young / (2.0 * (1.0 + nu)) * (1.0 if prony is None else prony.g_inf)
    if nu < 0.5 and prony is not None:
        bulk = young / (3.0 * (1.0 - 2.0 * nu))
        nu = (3.0 * bulk - 2.0 * shear) / (2.0 * (3.0 * bulk + shear))
    return math.sqrt(shear / rho) / rayleigh_root(nu)


def _inner_energy_matrices(system: ElasticSystem, radius: float) -> tuple[sp.csr_matrix, ...]:
    """Stiffness and mass assembled over the elements with centroid inside ``radius``."""
    centroids = system.mesh.p[:, system.mesh.t].mean(axis=1)
    inner = np.flatnonzero(np.hypot(centroids[0], centroids[1]) < radius)
    ubasis = system.displacement_basis.with_elements(inner)
    pbasis = system.pressure_basis.with_elements(inner)
    stiffness = mixed_matrix(ubasis, pbasis, system.youngs_modulus, system.poisson_ratio)
    return stiffness, weighted_mass(system, lambda r, z: np.ones_like(r), ubasis)


@dataclass(frozen=True, eq=False)
class _Body:
    """The assembled body: dof layout, candidates and the matrices of the stepping."""

    system: ElasticSystem
    free: np.ndarray
    candidates: ContactCandidates
    body_mass: sp.csr_matrix
    damping: sp.csr_matrix
    inner_stiffness: sp.csr_matrix
    inner_mass: sp.csr_matrix


def _assemble_body(system: ElasticSystem, indenter: Indenter, rho: float, scales: _Scales) -> _Body:
    """Candidates r <= the refined radius, mass (normal mass redistributed), layer damping."""
    free = system.free_dofs()
    selected = np.flatnonzero(system.surface_r <= scales.refined * (1 + 1e-12))
    dofs = system.surface_dofs[selected]
    r_c = system.surface_r[selected]
    candidates = ContactCandidates(
        dofs=dofs,
        position=np.searchsorted(free, dofs),
        radius=r_c,
        profile=np.asarray(indenter.profile(r_c), dtype=float),
        surface_factor=mass_factor(system.surface_mass[selected][:, selected].toarray()),
    )
    n = system.n_dofs
    body_mass = (
        redistribute_normal_mass(consistent_mass(system, rho), dofs)
        if rho > 0
        else sp.csr_matrix((n, n))
    )
    damping = (
        weighted_mass(system, scales.layer.weight(rho))
        if scales.has_layer
        else sp.csr_matrix((n, n))
    )
    inner_stiffness, inner_unit_mass = _inner_energy_matrices(system, scales.inner_radius)
    return _Body(
        system, free, candidates, body_mass, damping, inner_stiffness, rho * inner_unit_mass
    )


def _factorized_problem(
    body: _Body,
    striker: Striker,
    scheme: TimeScheme,
    material: ViscoelasticShear | None = None,
    friction: float | None = None,
) -> ImpactProblem:
    """K_eff factorized once on the free dofs, W = K_eff^-1 S and the LCP matrix (K: the
    ``material``'s stiffness at its step's shear modulus when the body is viscoelastic);
    with ``friction`` also K_eff^-1 at the candidates' u_r and the coupled compliance.

    Raises
    ------
    shtaerman.validation.InputError
        If W would exceed ``MAX_DENSE_CORRECTION`` bytes.
    """
    alpha_m, alpha_f, beta, gamma = scheme.alpha_m, scheme.alpha_f, scheme.beta, scheme.gamma
    dt = scheme.dt
    free, position = body.free, body.candidates.position
    radial = None if friction is None else radial_dofs(body.system, body.candidates.radius)
    columns = position.size + (0 if radial is None else radial[0].size)
    stiffness = body.system.matrix if material is None else material.stiffness
    effective = (1.0 - alpha_f) * stiffness + ((1.0 - alpha_f) * gamma / (beta * dt)) * body.damping
    if body.body_mass.nnz:  # massless: none (1/dt^2 overflows where dt^2 underflows)
        effective = effective + ((1.0 - alpha_m) / (beta * dt**2)) * body.body_mass
    effective = effective.tocsr()
    reduced = effective[free][:, free].tocsc()
    if free.size * columns * 8 > MAX_DENSE_CORRECTION:
        raise InputError(
            f"{position.size} contact candidates on {free.size} dofs need more than "
            f"{MAX_DENSE_CORRECTION / 1e6:.0f} MB; reduce margin or size"
        )
    # one BLAS thread: SuperLU's supernodes are small, threads only contend
    with threadpool_limits(limits=1, user_api="blas"):
        groups = body.system.dof_nodes()[free]
        factorization = factorize_scaled(reduced, groups, DYNAMIC_ACCURACY_CHECK)
        unit = np.zeros((free.size, position.size))
        unit[position, np.arange(position.size)] = 1.0
        # W = K_eff^-1 S, free dofs x candidates; column-major so that W[:, :k] is a view
        correction = np.asfortranarray(factorization.solve(unit))
        stick = {}
        if radial is not None:
            stick = _stick_compliance(factorization, correction, position, radial, body.free)
    compliance = 0.5 * (correction[position] + correction[position].T)
    striker_term = beta * dt**2 / ((1.0 - alpha_m) * striker.mass)
    lcp_matrix = (1.0 - alpha_f) * (compliance + striker_term)
    if stick:
        stick["coupled"].matrix[: position.size, : position.size] += striker_term
        stick["coupled"].matrix[...] *= 1.0 - alpha_f
    return ImpactProblem(
        system=body.system,
        free=free,
        candidates=body.candidates,
        striker=striker,
        scheme=scheme,
        body_mass=body.body_mass,
        damping=body.damping,
        inner_stiffness=body.inner_stiffness,
        inner_mass=body.inner_mass,
        factorization=factorization,
        correction=correction,
        lcp_matrix=lcp_matrix,
        material=material,
        friction=friction,
        **stick,
    )


def _stick_compliance(
    factorization: Factorization,
    correction: np.ndarray,
    position: np.ndarray,
    radial: tuple[np.ndarray, np.ndarray],
    free: np.ndarray,
) -> dict[str, object]:
    """K_eff^-1 at the candidates' u_r dofs (``radial``: dofs and candidate of each) and
    S'^T K_eff^-1 S' on [u_z, u_r] (m/N, symmetrized; the caller adds the striker's term
    and the weight), as the ``coupled`` and ``radial_correction`` of an ImpactProblem."""
    dofs, node = radial
    at = np.searchsorted(free, dofs)
    unit = np.zeros((free.size, at.size))
    unit[at, np.arange(at.size)] = 1.0
    radial_correction = np.asfortranarray(factorization.solve(unit))
    tail = np.concatenate([position, at])
    both = np.hstack([correction[tail], radial_correction[tail]])
    coupled = CoupledCompliance(0.5 * (both + both.T), node, dofs)
    return {"coupled": coupled, "radial_correction": radial_correction}


def _checked_estimate(estimate: int, settings: DynamicSettings, layered: bool = False) -> int:
    """The estimated dofs of the mesh of ``settings`` (``layered``: a layer's), or InputError
    above ``MAX_DOFS``."""
    if estimate > MAX_DOFS:
        blamed = growth_error(settings, estimate_dofs, MAX_DOFS, MAX_SIZE)
        if blamed is not None:
            raise blamed
        mesh = "layer mesh" if layered else "mesh"
        raise InputError(
            f"the {mesh} would have about {estimate:.3g} dofs, above the limit {MAX_DOFS}; "
            f"lower --refine, or coarsen --mesh-size (now {settings.size!r}) or --growth (now "
            f"{settings.growth!r})"
        )
    return estimate


def _waves(
    indenter: Indenter,
    half_space: Material,
    rho: float,
    striker: Striker,
    exact: ProfileImpactResult | None,
) -> RadiationEstimate:
    """The first-order radiation estimate of the rigid striker's quasi-static impact (a
    sphere's or a table's ``exact``) on the body of density ``rho`` kg/m^3."""
    law = contact_law(indenter, effective_modulus(RIGID, half_space))
    return impact_radiation(striker.mass, striker.velocity, law, rho, half_space, exact)


@dataclass(frozen=True)
class RadiatedFraction:
    """The first-order radiated fraction of the quasi-static impact of a mass (kg) at a
    velocity (m/s) on ``half_space`` of density ``rho`` kg/m^3 (a sphere's or a table's: ms
    each): what :func:`shtaerman.guards.check_wave_speed` bounds, for the remedies of the
    limits it follows and precedes, held to the body's wave-speed limit (:meth:`limit`)."""

    indenter: Indenter
    half_space: Material
    rho: float

    def __call__(self, mass: float, velocity: float) -> float:
        """lambda of ``mass`` (kg) at ``velocity`` (m/s)."""
        with warnings.catch_warnings():  # another impact than the input's, only sized
            warnings.simplefilter("ignore")
            indenter, half_space = self.indenter, self.half_space
            exact = profile_sizing_impact(indenter, half_space, mass, velocity)
            striker = Striker(mass, velocity)
            return _waves(indenter, half_space, self.rho, striker, exact).energy_fraction

    @property
    def power_law(self) -> bool:
        """Whether the striker is z = A r^n (its lambda exact in the velocity)."""
        return self.indenter.kind == "power-law"

    @property
    def rubber(self) -> bool:
        """Whether the body is held to a rubber's limits (:func:`shtaerman.guards.on_rubber`)."""
        from ..guards import on_rubber

        return on_rubber(self.half_space.poisson_ratio, self.power_law)

    def limit(self, force_exponent: float) -> float:
        """:func:`shtaerman.guards.wave_limit` of a force ~ x^``force_exponent`` on this body."""
        from ..guards import wave_limit  # looked up here: a benchmark lifts it

        return wave_limit(force_exponent, self.half_space.poisson_ratio, self.power_law)


def _reaches(indenter: Indenter, half_space: Material) -> Callable[[float, float], bool]:
    """Whether a power law's impact (mass kg, velocity m/s) on the half-space ``half_space``
    lies within the linear FE impact's reach (:func:`shtaerman.guards.check_reach`)."""

    def reaches(mass: float, velocity: float) -> bool:
        try:
            with warnings.catch_warnings():  # a slower or heavier impact, only checked
                warnings.simplefilter("ignore")
                qs = _quasi_static(indenter, half_space, Striker(mass, velocity))
                if not qs.x_c > 0:  # underflows: check_reach leaves it to the exact impact
                    return False  # (1e-300 kg at 2.32e-49 m/s was named, then refused)
                check_reach(indenter, qs.x_c, (mass, velocity), False)
        except InputError:  # the reach's LimitError, or a depth beyond the floats
            return False
        return True

    return reaches


def check_dynamic_impact(
    indenter: Indenter,
    half_space: Material,
    density: float,
    mass: float,
    velocity: float,
    settings: DynamicSettings,
    prony: PronySeries | None = None,
    friction: float | None = None,
    exact: ProfileImpactResult | None = None,
    geometry: Geometry = HALF_SPACE,
) -> tuple[float, Striker, _Scales, int]:
    """Check every input of a dynamic impact (arguments of :func:`.impact.run_impact`) before
    anything is meshed, in well under a second: the density, mass and velocity, with inertia
    the striker's speed against the waves' (:func:`shtaerman.guards.check_wave_speed`), the
    depth's reach (x/a), the layer's thickness against the refined radius, the duration of a
    viscoelastic impact and the estimated mesh size.
    ``shtaerman dynamic`` and a dynamic sweep's load both refuse their inputs here.

    Returns
    -------
    tuple
        The density (kg/m^3), the striker, the impact's scales and the estimated dofs.

    Raises
    ------
    shtaerman.validation.InputError
        For an input out of range, naming it.
    """
    rho = validate_density("density2", density)
    validate_friction(friction)
    striker = Striker(
        validate_positive("mass", mass, "kg"), validate_positive("velocity", velocity, "m/s")
    )
    if exact is None:  # a sphere's or a table's, solved once for the sizing and the waves
        exact = profile_sizing_impact(indenter, half_space, striker.mass, striker.velocity)
    qs = _quasi_static(indenter, half_space, striker, exact)
    thickness, impact = geometry.thickness, (striker.mass, striker.velocity)
    fraction = RadiatedFraction(indenter, half_space, rho) if rho > 0 else None
    if thickness is None:  # a pad stops the striker short of x_c
        check_reach(indenter, qs.x_c, impact, False, waves=fraction)
        # before the viscoelastic sizing, which takes 0.06 s
        _checked_estimate(estimate_dofs(settings), settings)
    if fraction is not None:
        waves = _waves(indenter, half_space, rho, striker, exact)
        power_law = fraction.power_law  # a sphere's or a table's lambda is checked by calls
        reach = _reaches(indenter, half_space) if thickness is None and power_law else None
        check_wave_speed(impact, waves, fraction, tip_exponents(indenter, qs.x_c)[1], reach)
    scales = _scales(indenter, half_space, rho, striker, settings, geometry, prony, qs)
    if thickness is None:
        domain = scales.domain_radius / scales.refined  # at least the waves' reach
        return rho, striker, scales, _checked_estimate(estimate_dofs(settings, domain), settings)
    try:
        estimate = layer_dofs(settings, thickness, scales.refined, scales.domain_radius)
    except LimitError as error:  # the thickness range: the velocity that fits it too
        sized = (indenter, half_space, rho, settings, geometry, prony)
        remedy = _layer_velocity(sized, striker, scales)
        raise LimitError(str(error) + remedy, "thickness") from None
    return rho, striker, scales, _checked_estimate(estimate, settings, layered=True)


def _layer_velocity(sized: tuple, striker: Striker, scales: _Scales) -> str:
    """The end of the thickness range's refusal of an impact (``striker``, its ``scales``) on
    a layer of ``sized`` = (indenter, half-space, density kg/m^3, settings, geometry, Prony
    series: :func:`_scales`'s): the velocity that fits it (:func:`.mesh.fitting_velocity`),
    checked by sizing it ("" where it does not)."""
    indenter, half_space, rho, settings, geometry, prony = sized
    exponent = getattr(indenter, "exponent", 2.0)
    fits = fitting_velocity(geometry.thickness, scales.refined, striker.velocity, exponent)
    if fits is None:  # beyond the floats
        return ""
    try:
        with warnings.catch_warnings():  # a slower or faster impact, only sized
            warnings.simplefilter("ignore")
            moved = Striker(striker.mass, fits[0])
            refined = _scales(indenter, half_space, rho, moved, settings, geometry, prony).refined
        check_thickness_range(geometry.thickness, refined, "")
    except InputError:  # not brought within
        return ""
    return fits[1]


@dataclass(frozen=True, eq=False)
class DynamicImpactSetup:
    """A dynamic impact ready to step: the problem and how long to step it (SI units).

    Attributes
    ----------
    problem : ImpactProblem
        Matrices, factorization, contact candidates, striker and time scheme.
    duration : float
        Longest run in s (three quasi-static impact durations).
    tail_time : float
        Stepping after separation in s.
    force_exponent : float
        q of the quasi-static law P ~ x^q (separation time between steps).
    reflection_measured : bool
        Whether the energy inside R_a measures the reflections (a tail is stepped).
    mesh, parameters : dict
        As in :class:`.impact_run.ImpactRun`.
    timings : dict of str to float
        Seconds: ``mesh``, ``assembly``, ``factorization``.
    """

    problem: ImpactProblem
    duration: float
    tail_time: float
    force_exponent: float
    reflection_measured: bool
    mesh: dict[str, float]
    parameters: dict[str, float]
    timings: dict[str, float]

    def march(
        self, snapshot_times: tuple[float, ...] = (), energy_series: bool = True
    ) -> ImpactHistory:
        """Step the run (:func:`.stepper.march`), keeping the fields at ``snapshot_times`` (s);
        ``energy_series``: the energies inside R_a at every step, else from the contact's end on
        where the reflected energy is measured."""
        return march(
            self.problem,
            duration=self.duration,
            tail_time=self.tail_time,
            force_exponent=self.force_exponent,
            snapshot_times=snapshot_times,
            energy_series=energy_series,
            after_contact=self.reflection_measured,
        )

    def result(self, history: ImpactHistory, timings: dict[str, float]) -> ImpactRun:
        """The run of ``history`` (what :meth:`march` returned), ``timings`` its costs (s):
        maxima, rebound, energy fractions."""
        problem, parameters = self.problem, self.parameters
        t, dt = history.t, problem.scheme.dt
        energy0 = problem.striker.kinetic_energy
        x_max, t_x_max = parabola_peak(t, history.x)
        t_y = parameters["quasi_static_t_y"]
        force = history.force
        p_max = parabola_peak(t, force)[0]  # massless: no stiff-mode ripple to average out
        if parameters["density2"] > 0:  # the window (fixed in time: a bias that dt keeps) does
            p_max = fitted_peak(t, force, int(np.argmax(force)), max(2, round(0.05 * t_y / dt)))
        reflected = math.nan
        if history.separated:
            reflected = _reflected_fraction(
                history,
                energy0,
                self.reflection_measured,
                layered="thickness" in self.mesh,
                viscoelastic=problem.material is not None,
            )
            if parameters["density2"] == 0:  # massless: nothing radiates, nothing comes back
                reflected = 0.0
        run = finished_run(
            (t, history.x, history.v, force),
            history.energies,
            (x_max, p_max, t_x_max),
            history.t_contact,
            energy0,
            contact_radius=history.contact_radius,
            central_pressure=history.central_pressure,
            reflected_energy_fraction=reflected,
            mesh=self.mesh,
            timings=timings,
            parameters=parameters,
            system=problem.system,
            snapshots=history.snapshots,
            material=problem.material,
            memories=history.memories,
        )
        if problem.material is None:
            return run
        return replace(run, losses=_losses(problem, history, run.energy_radiated_fraction))


def prepare_dynamic_impact(
    indenter: Indenter,
    half_space: Material,
    density: float,
    mass: float,
    velocity: float,
    settings: DynamicSettings | None = None,
    prony: PronySeries | None = None,
    friction: float | None = None,
    exact: ProfileImpactResult | None = None,
    geometry: Geometry = HALF_SPACE,
) -> DynamicImpactSetup:
    """Mesh, assemble and factorize the dynamic impact (arguments of :func:`.impact.run_impact`).

    Step it with :func:`.stepper.advance` from :meth:`.stepper.ImpactState.first_touch`, or
    all at once with :func:`.stepper.march`.

    Raises
    ------
    shtaerman.validation.InputError
        For inputs out of range or a mesh above ``MAX_DOFS`` (estimated before meshing).
    """
    settings = DynamicSettings() if settings is None else settings
    rho, striker, scales, estimate = check_dynamic_impact(
        indenter, half_space, density, mass, velocity, settings, prony, friction, exact, geometry
    )
    clock = [time.perf_counter()]
    mesh = _mesh(settings, geometry, scales)
    clock.append(time.perf_counter())
    system = assemble(mesh, half_space.youngs_modulus, half_space.poisson_ratio)
    body = _assemble_body(system, indenter, rho, scales)
    clock.append(time.perf_counter())
    scheme = TimeScheme.generalized_alpha(settings.spectral_radius, scales.dt)
    material = (
        None if prony is None else viscoelastic_shear(system, prony, scales.dt, scales.inner_radius)
    )
    problem = _factorized_problem(body, striker, scheme, material, validate_friction(friction))
    clock.append(time.perf_counter())
    counts = mesh_counts(mesh, system.n_dofs, body.candidates.dofs.size, scales.refined, geometry)
    stats = {**counts, "estimated_dofs": estimate, "domain_radius": float(scales.domain_radius)}
    stats["smallest_size"] = settings.size * scales.refined  # sizes (counts) and geometry (m)
    return DynamicImpactSetup(
        problem=problem,
        duration=RUN_DURATIONS * scales.longest_t_y,
        tail_time=settings.tail * scales.inner_radius / scales.slowest_rayleigh_speed,
        force_exponent=scales.quasi_static.force_exponent,
        reflection_measured=settings.tail > 0
        and (geometry.thickness is not None or scales.layer.start < 0.5 * scales.domain_radius),
        mesh=stats,
        parameters=_parameters(indenter, half_space, rho, problem, scales),
        timings={
            name: clock[k + 1] - clock[k]
            for k, name in enumerate(("mesh", "assembly", "factorization"))
        },
    )


def _mesh(settings: DynamicSettings, geometry: Geometry, scales: _Scales) -> MeshTri:
    """The half-space mesh, or the layer's (:mod:`.dynamic_layer`) of ``geometry``."""
    if geometry.thickness is not None:
        return layer_impact_mesh(settings, geometry, scales.refined, scales.domain_radius)
    return halfspace_mesh(
        scales.refined,
        domain_radius=scales.domain_radius,
        smallest_size=settings.size * scales.refined,
        growth=settings.growth,
        axis_size=min(settings.axis_size, settings.size) * scales.refined,
        axis_growth=0.1,
    )


def _parameters(
    indenter: Indenter,
    half_space: Material,
    rho: float,
    problem: ImpactProblem,
    scales: _Scales,
) -> dict[str, float]:
    """Inputs and derived scales, SI units."""
    qs, layer, has_layer = scales.quasi_static, scales.layer, scales.has_layer
    striker = (problem.striker.mass, problem.striker.velocity, rho)
    parameters = impact_parameters(indenter, half_space, striker, scales.dt, problem.friction)
    return {
        **parameters,
        "shear_wave_speed": scales.shear_wave_speed,
        "rayleigh_wave_speed": scales.rayleigh_wave_speed,
        "layer_start": layer.start if has_layer else math.nan,
        "layer_ramp": layer.ramp if has_layer else math.nan,
        "layer_rate": layer.rate if has_layer else 0.0,
        "quasi_static_x_c": qs.x_c,
        "quasi_static_t_y": scales.t_y,
        "quasi_static_a_c": qs.a_c,
        "beta": qs.beta,
        "solver_backward_error": problem.factorization.backward_error,
    }


def _losses(problem: ImpactProblem, history: ImpactHistory, radiated: float) -> dict[str, float]:
    """The loss 1 - e^2 split into waves (body energy beyond R_a and the layer's) and
    hysteresis (the rest: dissipated, or still inside R_a to be dissipated)."""
    energies = {key: float(values[-1]) for key, values in history.energies.items()}
    energy0 = problem.striker.kinetic_energy
    body = energies["body_kinetic"] + energies["strain"] - energies["inner"]
    waves = (body + energies["absorbed"]) / energy0
    return {
        "energy_dissipated_fraction": energies["dissipated"] / energy0,
        "energy_hysteresis_fraction": radiated - waves,
        "energy_wave_fraction": waves if not math.isnan(radiated) else math.nan,
    }


def _reflected_fraction(
    history: ImpactHistory,
    energy0: float,
    measured: bool,
    *,
    layered: bool = False,
    viscoelastic: bool = False,
) -> float:
    """What came back inside R_a: the largest rise of the body energy there above its running
    minimum after separation (:func:`_returned`, J), over the radiated energy, or over
    ``energy0`` (J) on a layer. nan if not measured; a viscoelastic body's counts twice its
    kinetic energy there."""
    scale = 2.0 if viscoelastic else 1.0
    inner = history.energies["inner_kinetic" if viscoelastic else "inner"] * scale
    returned = _returned(inner[history.t > history.t_contact]) if measured else math.nan
    if layered:
        return returned / energy0
    radiated_energy = energy0 - history.energies["striker_kinetic"][-1]
    if radiated_energy > 0:
        return returned / radiated_energy
    return math.nan


def _returned(energies: np.ndarray) -> float:
    """The largest rise of ``energies`` (a series, nan before the monitoring began) above
    their running minimum: what came back, in their unit (0 for energy only leaving)."""
    series = energies[~np.isnan(energies)]
    if series.size == 0:
        return math.nan
    return float(np.max(series - np.minimum.accumulate(series)))
