"""The FE impact driver: a rigid striker on a body, linear or at finite strain.

:func:`run_impact` takes the problem's parts (the striker's profile, mass and velocity; the
body's small-strain material, density, rubber model and Prony series; its geometry; the
interface) and the numerical settings, whose kind chooses the body:

- :class:`.dynamic_contact.DynamicSettings` (or none): the linear body, its fast path one
  factorization and the generalized-alpha march with the condensed contact compliance
  (:mod:`.stepper`);
- :class:`.finite_dynamic.FiniteImpactSettings`, or a ``rubber`` model: the rubber at finite
  strain, Newton every step (massless: the discrete-gradient march; with inertia: Bossak).

Either prepares a :class:`PreparedImpact` (checked inputs, mesh, assembled body), which marches
in the one loop of :func:`.impact_run.march_steps` and ends in one
:class:`.impact_run.ImpactRun` (:func:`.impact_run.finished_run`).
"""

from __future__ import annotations

import math
import time
from collections.abc import Callable
from typing import Any, Protocol

from ..guards import (
    Waves,
    check_equator,
    check_profile_reach,
    check_wave_speed,
    equator_energy_refusal,
    tip_exponents,
)
from ..theory.materials import Material
from ..theory.profile_impact import ProfileImpactResult
from ..theory.sneddon import Indenter
from ..theory.viscoelastic import PronySeries
from .dynamic_contact import DynamicSettings, prepare_dynamic_impact
from .finite_dynamic import IMPACT_MARGIN, FiniteImpactSettings, prepare_finite_impact
from .impact_run import ImpactRun
from .mesh import HALF_SPACE, Geometry, resolved_depths
from .rubber import RubberModel

__all__ = ["PreparedImpact", "check_impact_reach", "run_impact"]


class PreparedImpact(Protocol):
    """A body ready to be struck: what :func:`run_impact` asks of it."""

    timings: dict[str, float]
    """Seconds spent preparing it, by phase."""

    def march(self, snapshot_times: tuple[float, ...] = (), energy_series: bool = True) -> Any:
        """Step from first touch to the end of the run."""

    def result(self, marched: Any, timings: dict[str, float]) -> ImpactRun:
        """The run of what :meth:`march` returned, with its costs ``timings`` (s)."""


def check_impact_reach(
    indenter: Indenter,
    half_space: Material,
    density: float,
    impact: tuple[float, float],
    finite: bool,
    friction: float | None = None,
    geometry: Geometry = HALF_SPACE,
    prony: PronySeries | None = None,
    exact: Callable[[], Any] | None = None,
) -> None:
    """Refuse, before its exact impact is solved, a power law's FE impact (mass kg, velocity
    m/s) on ``half_space`` (density kg/m^3; ``finite``: a rubber at finite strain) whose depth
    lies beyond its model's reach where its run checks it (the linear body on the half-space,
    its remedies within the waves' limit; a rubber where :func:`.finite_dynamic.pad_reach_note`
    has a note): x_c in logarithms, :func:`shtaerman.guards.check_profile_reach`, the contact
    curve's check (0.7 kg at 1e-300 m/s was refused for the exact impact's P_c = 0, naming
    four inputs and no value). A table whose end lies below the floor is refused first
    (:func:`shtaerman.guards.check_table_window`); a sphere's or a table's reach is checked by
    its run, and so is
    a v0^2 beyond the largest float: its refusal (a velocity of a physical size) passes where
    the reach's might not (1e-300 kg at 1e200 m/s: 4.13e158 m/s, whose v0^2 overflows too).
    A rubber with inertia (``density`` > 0) is then held to the linear body's wave-speed
    limit (:func:`shtaerman.guards.check_wave_speed`; its remedies within the finite-strain
    reach), any profile: 1e-40 kg at 3 m/s failed numerically after a minute. A rubber with a
    ``prony`` series beyond the reach is refused as its run refuses it
    (:func:`.finite_dynamic.check_fully_relaxed`). A sphere's or a table's exact impact is
    ``exact()`` (:func:`shtaerman.theory.viscoelastic.rigid_impact`: the caller's, solved
    once for its checks and its run; None: solved here), its refusal beyond the profile's
    end the first."""
    from ..guards import check_table_window
    from ..theory.materials import RIGID, effective_modulus
    from ..theory.sneddon import contact_law
    from ..theory.viscoelastic import rigid_impact
    from ..validation import LimitError
    from .dynamic_contact import RadiatedFraction
    from .finite_dynamic import check_fully_relaxed, pad_reach_note

    check_table_window(indenter, finite)  # a table with no window: before its exact impact
    if math.isinf(impact[1] * impact[1]):
        return
    pad = geometry.thickness is not None  # a pad stops the striker short of x_c
    note = pad_reach_note(pad, friction, density) if finite else (None if pad else "")
    waves = RadiatedFraction(indenter, half_space, density) if density > 0 else None
    modulus = effective_modulus(RIGID, half_space)
    exact = rigid_impact(indenter, half_space, *impact) if exact is None else exact
    if indenter.kind != "power-law":  # its end, with inertia with the waves' remedy
        _check_profile_end(indenter, half_space, density, impact, exact)
    if indenter.kind == "power-law" and (note is not None or finite):  # a rubber: its floor
        # a pad's remedy within the depths its mesh resolves (adv60: 4.95e-12 m/s was named
        # for 1e-16 on a 12 mm pad, whose thickness that impact then refused)
        layer = resolved_depths(geometry, indenter, IMPACT_MARGIN) if finite else None
        try:
            check_profile_reach(
                indenter, modulus, None, impact, finite=finite, note=note, layer=layer, waves=waves
            )
        except LimitError:  # a relaxing rubber: in the fully relaxed body's words
            if finite:
                reach = (indenter, contact_law(indenter, modulus), impact, prony)
                check_fully_relaxed(reach, note, layer, waves)
            raise
    if finite and waves is not None:
        _check_finite_waves(indenter, half_space, density, impact, waves, exact)


def _check_profile_end(
    indenter: Indenter,
    half_space: Material,
    density: float,
    impact: tuple[float, float],
    exact: Callable[[], ProfileImpactResult],
) -> None:
    """The refusal of a sphere's or a table's impact (mass kg, velocity m/s) beyond the
    profile's end, that of its exact impact ``exact()``, which with inertia also names, where
    its remedies (the slower or the lighter impact that stays within the profile) radiate
    above the body's :func:`shtaerman.guards.wave_limit`, the density (kg/m^3, 0.99 of the
    limit's: lambda ~ sqrt(density)) at which both pass."""
    from ..guards import passing_density
    from ..theory.materials import RIGID, effective_modulus
    from ..theory.profile_impact import work_to
    from ..theory.sneddon import SneddonContact
    from ..validation import LimitError
    from .dynamic_contact import RadiatedFraction

    try:
        exact()
    except LimitError as refusal:
        law = SneddonContact(indenter, effective_modulus(RIGID, half_space))
        (mass, velocity), top = impact, law.max_contact_radius
        if law.sphere:  # the FE's sphere ends where the depth reaches R, at a < R
            top = float(law.contact_radius(math.nextafter(top, 0.0)))
        # 0 where the work or the radius (its root, R = 1e-300 m) underflows
        share = 0.999 * work_to(law, top) / (0.5 * mass * velocity * velocity) if top else 0.0
        error = equator_energy_refusal(indenter.radius, impact, share) if law.sphere else refusal
        if not (share > 0.0 and density > 0.0):
            raise error from None
        fraction = RadiatedFraction(indenter, half_space, density)
        worst = max(fraction(mass, velocity * math.sqrt(share)), fraction(mass * share, velocity))
        limit = fraction.limit(tip_exponents(indenter, float(law.depth(top)))[1])
        if not worst > limit:
            raise error from None
        lighter = passing_density(density, limit / worst)
        passing = (
            f"density2 at most about {lighter:g} kg/m^3 passes both (density2 0: "
            if lighter
            else "only density2 0 passes ("
        )
        raise LimitError(
            f"{error}; with inertia either radiates above {limit:.3g} of its energy as waves "
            f"on this density2, where the FE impact with inertia breaks down: {passing}the "
            "quasi-static impact without waves)",
            error.parameter,
        ) from None


def _check_finite_waves(
    indenter: Indenter,
    half_space: Material,
    density: float,
    impact: tuple[float, float],
    waves: Waves,
    exact: Callable[[], Any],
) -> None:
    """The wave-speed limit of a rubber's impact (mass kg, velocity m/s) with inertia on
    ``half_space`` of ``density`` kg/m^3 (``waves``: the radiated fraction of an impact), as
    the linear body's (:func:`.dynamic_contact.check_dynamic_impact`): a power law's remedy
    within the finite-strain reach, a sphere's or a table's velocity checked by ``waves``
    (its exact impact ``exact()``); first a sphere's equator
    (:func:`shtaerman.guards.check_equator`), its remedies within the waves' limit, as the
    linear body's reach check names them."""
    import warnings

    from ..theory.materials import RIGID, effective_modulus
    from ..theory.radiation import impact_radiation
    from ..theory.sneddon import contact_law
    from ..validation import InputError

    modulus = effective_modulus(RIGID, half_space)
    with warnings.catch_warnings():  # the run warns of it beside its results
        warnings.simplefilter("ignore")
        exact = None if indenter.kind == "power-law" else exact()
        estimate = impact_radiation(
            *impact, contact_law(indenter, modulus), density, half_space, exact
        )

    def reaches(mass: float, velocity: float) -> bool:
        try:
            with warnings.catch_warnings():  # a slower or heavier impact, only checked
                warnings.simplefilter("ignore")
                check_profile_reach(indenter, modulus, None, (mass, velocity), finite=True)
        except (InputError, ArithmeticError):
            return False
        return True

    if exact is not None:  # a sphere's equator first, its remedies within the waves' limit
        check_equator(indenter, exact.x_c, impact, waves=waves)
    q = tip_exponents(indenter, math.nan if exact is None else exact.x_c)[1]
    check_wave_speed(impact, estimate, waves, q, reaches if exact is None else None)


def run_impact(
    indenter: Indenter,
    half_space: Material,
    density: float,
    mass: float,
    velocity: float,
    settings: DynamicSettings | FiniteImpactSettings | None = None,
    rubber: RubberModel | None = None,
    prony: PronySeries | None = None,
    friction: float | None = None,
    *,
    geometry: Geometry = HALF_SPACE,
    snapshot_times: tuple[float, ...] = (),
    exact: ProfileImpactResult | None = None,
    energy_series: bool = True,
) -> ImpactRun:
    """Strike the body with a rigid striker and follow it until the striker leaves.

    Parameters
    ----------
    indenter : PowerLawIndenter, SphereIndenter or TabulatedIndenter
        The striker's profile: z = A r^n (n > 1), the exact sphere or a tabulated z(r).
    half_space : Material
        E2 in Pa and nu2 in [0, 0.5] (the small-strain, instantaneous values).
    density : float
        The body's density in kg/m^3: 0 (massless) or within ``DENSITY_RANGE``.
    mass, velocity : float
        Striker mass M in kg and impact velocity v0 in m/s, > 0.
    settings : DynamicSettings or FiniteImpactSettings, optional
        The numerics, and by their kind the body (module docstring); None: the linear body's
        defaults.
    rubber : RubberModel, optional
        The rubber at finite strain (None: neo-Hookean where the settings ask finite strain).
    prony : PronySeries, optional
        Shear relaxation of the body; None: elastic.
    friction : float, optional
        The striker's surface: None frictionless, ``math.inf`` bonded (no slip), mu >= 0
        Coulomb (the finite-strain body takes 0 as frictionless).
    geometry : Geometry
        The body's shape: the half-space (default) or a layer of a thickness on its base.
    snapshot_times : tuple of float
        Times in s at which to keep the fields (the linear body; nearest step).
    exact : ProfileImpactResult, optional
        A sphere's or a table's quasi-static impact that sizes the run, when solved already
        (:func:`.dynamic_contact.profile_sizing_impact`, the same for every level of a
        ladder); None: solved here (a power law's needs none).
    energy_series : bool
        The linear body's energies inside R_a at every step (the run's energies, as a
        history writes them), else at the last step only (nan before it: a study's run).

    Returns
    -------
    ImpactRun

    Raises
    ------
    TypeError
        For a ``rubber`` with the linear body's settings.
    shtaerman.validation.InputError
        For inputs out of range, naming them, or a contact that outgrows the refined zone.
    shtaerman.validation.NumericalFailureError
        When the stepping fails, saying what to change.
    """
    inputs = (indenter, half_space, density, mass, velocity, settings)
    if rubber is not None and isinstance(settings, DynamicSettings):
        raise TypeError("run_impact: a rubber takes FiniteImpactSettings, not DynamicSettings")
    if rubber is not None or isinstance(settings, FiniteImpactSettings):
        physics = (rubber, prony, friction, exact, geometry)
        prepared: PreparedImpact = prepare_finite_impact(*inputs, *physics)
    else:
        prepared = prepare_dynamic_impact(*inputs, prony, friction, exact, geometry)
    start = time.perf_counter()
    marched = prepared.march(snapshot_times, energy_series)
    timings = {**prepared.timings, "stepping": time.perf_counter() - start}
    timings["total"] = sum(timings.values())
    return prepared.result(marched, timings)
