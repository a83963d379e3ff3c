"""Validity limits of a computed depth, declared once and applied on every route.

A run that ends outside a limit keeps its numbers and warns (:class:`ValidityWarning`, one
line): the command line prints it, the API issues it, a sweep records it in the case's
``warnings``. The limits concern the deepest approach x (m) the run reached:

- on a layer of thickness H: a contact curve's depth x >= H, a strain beyond 100 %, the linear
  model's own answer (its thin-layer foundation limit is verified so); an impact's approach
  x >= H is refused instead (:func:`check_within_layer`): the striker would pass through the
  pad;
- the depth ratio x/a (a: the exact contact radius at x, Shtaerman's or Sneddon's,
  :func:`depth_ratio`, which measures the strain under the indenter) beyond
  :data:`MAX_DEPTH_RATIO`, where the finite-strain contact has been validated: the linear
  model is then far outside small strain (at x/a = 0.88 a neo-Hookean rubber already carries
  4.9 % less force, docs/findings.md), and the finite-strain result is unverified;
- a Gent rubber's stretch (I1bar - 3) / Jm at :data:`LOCKED`, where it locks: each route
  tells its :class:`LockingWatch` every state it accepts, and the first at or beyond it warns
  with the depth the stretch crossed it, wherever the route's steps fall.

Refused before any work instead (:class:`~shtaerman.validation.LimitError`, an
:class:`~shtaerman.validation.InputError` a sweep records as its case's "refused" row): an FE
impact whose depth lies beyond the model's reach (:func:`check_reach`; a contact curve whose
depths an impact sets, on every route: :func:`check_profile_reach`), a sphere pressed past
its equator (:func:`check_equator`), and an FE impact with inertia (linear, or a rubber's:
:func:`shtaerman.fem.impact.check_impact_reach`) whose striker is too fast for the body's waves
(:func:`check_wave_speed`).

Both the impact drivers (:func:`shtaerman.study.dynamic.case.run_case`,
:func:`shtaerman.fem.impact.run_impact`) and the contact curve (the API, a
contact sweep case, a contact or layer study) call :func:`warn_outside_validity` with what
they reached.
"""

from __future__ import annotations

import functools
import itertools
import math
import warnings
from collections.abc import Callable, Iterator
from contextlib import contextmanager
from typing import Protocol

from .theory.indenter import PowerLawIndenter
from .theory.sneddon import Indenter, contact_law
from .validation import caller_stacklevel

__all__ = [
    "DEPTHS_INSTEAD",
    "LINEAR_REACH",
    "LOCKED",
    "MAX_DEPTH_RATIO",
    "MAX_RADIATED_ESTIMATE",
    "MIN_DEPTH_RATIO",
    "MIN_FINITE_DEPTH_RATIO",
    "REMEDY_SPAN",
    "RUBBER_POISSON",
    "RUBBER_WAVE_LIMITS",
    "WAVE_LIMITS",
    "FailedCheckWarning",
    "LadderWarnings",
    "LockingWatch",
    "ValidityWarning",
    "Waves",
    "check_equator",
    "check_profile_reach",
    "check_reach",
    "check_table_window",
    "check_wave_speed",
    "check_within_layer",
    "deepest_depth_remedy",
    "depth_ratio",
    "equator_energy_refusal",
    "on_rubber",
    "outside_validity",
    "passing_density",
    "reach_shape",
    "reach_velocity",
    "tip_exponents",
    "warn_outside_validity",
    "wave_limit",
]

MAX_DEPTH_RATIO = 1.2
"""Largest depth / contact radius x/a at which the finite-strain contact converges and was
checked against the linear one (beyond it Newton fails after minutes of halved load steps)."""
MIN_DEPTH_RATIO = 1e-6
"""Smallest x/a a linear FE impact is run at (a finite-strain one: :data:`MIN_FINITE_DEPTH_RATIO`):
the strains are of this order, and the linear FE's scales reach the floating-point range below
it (mass 1e-300 gave a singular matrix); the exact quasi-static impact is the answer there."""
MIN_FINITE_DEPTH_RATIO = 1e-3
"""Smallest x/a a finite-strain FE impact (or a contact curve an impact's x_c sets) is run at.
There the finite-strain correction (~5 % x/a) is below the FE's own error (~1e-4): the linear
model, exact there, is the answer (benchmarks/FEM_NOTES.md, "Stress without cancellation")."""
LOCKED = 0.999
"""(I1bar - 3) / Jm of a Gent rubber that locks: its tangent shear stiffness
mu / (1 - (I1bar - 3) / Jm) is a thousand times mu. A run's first state there warns
(:class:`LockingWatch`), and a failed load step from a state there is the rubber locking, not a
step too long (:func:`shtaerman.fem.rubber.gent_locks`; benchmarks/FEM_NOTES.md, "Gent
locking")."""
DEPTHS_INSTEAD = ", or, instead of mass=... and velocity=..., give depths=..."
"""The end of a reach refusal of a contact curve whose route takes depths: they replace the
impact that set the default ones ("or give depths" was read as "as well", and depths given
with a mass and velocity are refused)."""
LINEAR_REACH = 100.0
"""Largest x/a a linear FE impact is run at: a depth of a hundred contact radii is no
model's, and beyond it the mesh's scales overflow (mass 1e300 gave a singular matrix)."""
MAX_RADIATED_ESTIMATE = 0.7
"""Largest first-order radiated energy fraction lambda of the quasi-static impact
(:func:`shtaerman.theory.radiation.radiation_estimate`, ~ v0 / c_s: the striker's speed over
the body's shear wave speed c_s = sqrt(G / rho), times its mass and shape) at which an FE
impact with inertia is run, for a striker as sharp as the paper's or sharper (force exponent q
>= 5/3, n <= 3/2); a blunter one's is lower (:func:`wave_limit`). For one striker and nu2 the
linear FE's restitution and checks follow lambda alone, whatever v0 / c_s (session 59, default
mesh; n = 1.5, nu2 = 0.5: the same at 0.7 kg, v0 / c_s 0.52, and 7 kg, 0.77): its energy
balance fails (off by 2 to 4 of M v0^2/2, the contact chattering) from lambda 0.764, its
reflected-energy check from 0.75 (nu2 0; 0.78 at nu2 0.3, 0.83 at 0.5), and both pass at or
below 0.70 for n = 1.5 (n = 1.3, nu2 0.49: to 0.9; benchmarks/FEM_NOTES.md, "Wave speed
guard")."""
WAVE_LIMITS = (
    (1.1, 0.099),
    (1.2, 0.135),
    (1.25, 0.162),
    (9.0 / 7.0, 0.1845),
    (4.0 / 3.0, 0.22),
    (1.4, 0.28),
    (1.5, 0.45),
    (11.0 / 7.0, 0.57),
    (5.0 / 3.0, MAX_RADIATED_ESTIMATE),
)
"""(q, limit): the wave-speed limit (:func:`wave_limit`) at force exponents q = (n + 1)/n of
z = A r^n, n = 10, 5, 4, 3.5, 3, 2.5, 2, 1.75 and 1.5, each 0.9 of the lowest lambda at which
the linear FE impact with inertia failed a check at nu2 0, 0.3 or 0.5, for every nu2 but a
rubber's (:data:`RUBBER_POISSON`; default mesh;
benchmarks/bench_wave_limit.py, FEM_NOTES.md "Wave speed guard, session 60" and "The blunt
strikers' limits (session 67)"): its energy balance (nu2 0.5, the contact chattering) from
lambda 0.66, 0.52, 0.32, 0.25, 0.218, 0.18, 0.15 (n = 1.75, 2 and a sphere, 2.5, 3, 3.5, 4,
5), its reflected-energy check (nu2 0) from 0.64, 0.505 (n = 1.75, 2; measured before session
67's measure of what comes back); n = 3.5 and 10 at nu2 0.499's 0.205 and 0.11 (a table's tip
on a rubber, nu2 just below 0.5). n = 1.5 keeps session 59's 0.7."""
RUBBER_POISSON = (0.45, 0.499)
"""The Poisson's ratios nu2 of a rubber, whose FE impact with inertia is held to
:data:`RUBBER_WAVE_LIMITS` (measured at 0.45, 0.49 and 0.499). Below, the reflected-energy
check fails earlier (nu2 0, 0.3); above, the chatter does, falling to nu2 0.5's as nu2 -> 0.5
(z = 10 r^2's balance from lambda 0.65 at nu2 0.499, 0.55 at 0.4999, 0.52 at 0.5): both keep
:data:`WAVE_LIMITS`, within 0.9 of each failure at nu2 0.4999 too (n = 1.75 to 3.5)."""
RUBBER_WAVE_LIMITS = (
    (1.1, 0.099),
    (1.2, 0.135),
    (11.0 / 9.0, 0.1485),
    (1.25, 0.1647),
    (9.0 / 7.0, 0.1845),
    (4.0 / 3.0, 0.225),
    (1.4, 0.315),
    (1.5, 0.585),
    (11.0 / 7.0, 0.675),
    (5.0 / 3.0, MAX_RADIATED_ESTIMATE),
)
"""(q, limit): :data:`WAVE_LIMITS` of a rubber (nu2 in :data:`RUBBER_POISSON`) at n = 10, 5,
4.5, 4, 3.5, 3, 2.5, 2, 1.75 and 1.5, each 0.9 of the lowest lambda at which the linear FE
impact with inertia failed a check at nu2 0.45, 0.49 or 0.499 (default mesh, and the runs at
0.99 of each limit;
benchmarks/FEM_NOTES.md, "Wave-speed limit on rubber" and "The blunt strikers' limits
(session 67)"): its energy balance (nu2 0.499, the chatter) from 0.75, 0.65, 0.35, 0.25,
0.205, 0.183, 0.165, 0.15, 0.11 (n = 1.75, 2, 2.5, 3, 3.5, 4, 4.5, 5, 10)."""


def wave_limit(force_exponent: float, poisson: float, power_law: bool = False) -> float:
    """Largest first-order radiated fraction lambda at which an FE impact with inertia of a
    striker whose force goes as x^``force_exponent`` (q; a sphere's 3/2, a table's its tip's:
    :func:`tip_exponents`) on a body of Poisson's ratio ``poisson`` (nu2) is run:
    :data:`RUBBER_WAVE_LIMITS` for a ``power_law`` z = A r^n on a rubber (nu2 in
    :data:`RUBBER_POISSON`), else :data:`WAVE_LIMITS`, interpolated linearly in q, their first
    beyond n = 10 and :data:`MAX_RADIATED_ESTIMATE` from q = 5/3 up (n <= 3/2). Blunter
    strikers break down at a lower lambda; a sphere's fails where z = r^2 / (2 R) does on
    WAVE_LIMITS' bodies, however deep (q at its x_c 1.44), but earlier on a rubber pressed
    deep (R = 10 mm at x/a 1.17, q at x_c 1.39, nu2 0.49: its reflected check from lambda
    0.58, below z = 10 r^2's 0.70; benchmarks/FEM_NOTES.md)."""
    q = round(force_exponent, 9)  # 1 + 1/n and (n + 1)/n differ in the last digit
    table = RUBBER_WAVE_LIMITS if on_rubber(poisson, power_law) else WAVE_LIMITS
    for (first, low), (last, high) in itertools.pairwise(table):
        if q <= first:
            return low
        if q < last:
            return low + (high - low) * (q - first) / (last - first)
    return table[-1][1]


def on_rubber(poisson: float, power_law: bool) -> bool:
    """Whether a striker (a ``power_law``'s or not) on a body of Poisson's ratio ``poisson``
    is held to :data:`RUBBER_WAVE_LIMITS`."""
    return power_law and RUBBER_POISSON[0] <= poisson <= RUBBER_POISSON[1]


class Waves(Protocol):
    """The first-order radiated fraction lambda of an impact (mass kg, velocity m/s) on a
    body with mass (:class:`shtaerman.fem.dynamic_contact.RadiatedFraction`): its density
    ``rho`` (kg/m^3), whether the striker is a ``power_law`` (its lambda exact in the
    velocity), whether the body is held to a rubber's limits (``rubber``: :func:`on_rubber`)
    and the body's :func:`wave_limit` of a force exponent q (``limit``)."""

    rho: float

    @property
    def power_law(self) -> bool: ...

    @property
    def rubber(self) -> bool: ...

    def __call__(self, mass: float, velocity: float) -> float: ...

    def limit(self, force_exponent: float) -> float: ...


class ValidityWarning(UserWarning):
    """A run that reached beyond a validity limit of its model (its numbers are kept)."""


class FailedCheckWarning(ValidityWarning):
    """A dynamic run that fails the studies' own checks (its energy balance, the energy
    reflected back to the contact): the API warns, the command line exits 1, a study fails
    the check, a sweep records the case as failed."""


class LockingWatch:
    """The Gent stretch (I1bar - 3) / Jm of a run's accepted states, in order (:meth:`accept`):
    the first at or beyond :data:`LOCKED` issues one :class:`ValidityWarning` naming the depth
    where the stretch crossed :data:`LOCKED`, linear in the stretch between that state and the
    one accepted before it (the undeformed body at first), so that every route names about the
    same depth whatever its steps. ``limit``: Jm (inf for another rubber: never warns)."""

    def __init__(self, limit: float) -> None:
        self.limit = limit
        self.last = (0.0, 0.0)  # depth (m) and stretch of the last accepted state
        self.crossed: float | None = None  # the crossing depth (m), once warned

    def accept(self, depth: float, stretch: float) -> None:
        """An accepted (converged, committed) state at ``depth`` (m) with ``stretch``."""
        if self.crossed is None and stretch >= LOCKED:
            (before, below), span = self.last, stretch - self.last[1]
            self.crossed = before + (depth - before) * (LOCKED - below) / span
            from .validation import caller_stacklevel

            warnings.warn(self.sentence(depth, stretch), ValidityWarning, caller_stacklevel())
        self.last = (depth, stretch)

    def sentence(self, depth: float, stretch: float) -> str:
        """The warning of the crossing state at ``depth`` (m) with ``stretch``."""
        before, below = self.last
        return (
            f"the Gent rubber locks from depth {self.crossed:.4g} m on: its stretch I1bar - 3 "
            f"reaches {LOCKED:g} of its limit gent_limit={self.limit:g} there (interpolated "
            f"between {below:.6f} at {before:.6g} m and {stretch:.6f} at {depth:.6g} m), where "
            f"its shear stiffness is {1.0 / (1.0 - LOCKED):.0f} times the small-strain one: "
            "the results beyond depend on the load or time steps; a larger limit stays clear"
        )


class LadderWarnings:
    """The warnings of a mesh ladder's levels, said when the ladder ends (``with
    LadderWarnings() as said:`` around it, ``with said.level():`` around each level): the
    validity warnings of the level it reports only (a Gent rubber crosses :data:`LOCKED` at
    each mesh's own depth), the others of every level that passed. Each names the first
    line outside shtaerman that called the ladder."""

    def __init__(self) -> None:
        self.said: list[tuple[list[warnings.WarningMessage], bool]] = []

    def __enter__(self) -> LadderWarnings:
        return self

    def __exit__(self, kind: type[BaseException] | None, *_: object) -> None:
        self.say(raised=kind is not None)

    @contextmanager
    def level(self) -> Iterator[None]:
        """Hold the warnings of one level's run, and whether it passed."""
        with warnings.catch_warnings(record=True) as caught:
            warnings.simplefilter("always")
            try:
                yield
            except BaseException:
                self.said.append((caught, False))
                raise
        self.said.append((caught, True))

    def say(self, raised: bool = False) -> None:
        """Issue what the levels held: all of the reported level's (the last that passed;
        ``raised``: the ladder ends on the last level's error, which it reports), the other
        passed levels' but their validity warnings."""
        stacklevel = caller_stacklevel()
        passed = [number for number, (_, ok) in enumerate(self.said) if ok]
        reported = len(self.said) - 1 if raised else (passed or [None])[-1]
        for number, (caught, ok) in enumerate(self.said):
            for said in caught:
                validity = issubclass(said.category, ValidityWarning)
                if number == reported or (ok and not validity):
                    warnings.warn(said.message, stacklevel=stacklevel)


def tip_exponents(indenter: Indenter, depth: float) -> tuple[float, float]:
    """The striker's tip z ~ r^n at ``depth`` (m) as the reach and the waves' limit scale it:
    (n, q), q = (n + 1)/n its force exponent (P ~ x^q). A power law's own n; a sphere's 2; a
    table's n as its first rows give it
    (:attr:`~shtaerman.theory.profiles.TabulatedIndenter.tip_exponent`) once the contact
    passes its first row, else, or where they are sharper, 2: its interpolation in r^2 is a
    smooth tip (q at most 3/2). z = 50 r^3 tabulated took a sphere's wave limit 0.45 and
    failed its checks at lambda 0.45 (balance off by 4.6 of M v0^2/2)."""
    n = getattr(indenter, "exponent", 2.0)  # a power law's; a sphere's, a smooth tip's
    if indenter.kind == "tabulated" and depth > 0:
        beyond = depth > contact_law(indenter, 1.0).depth(indenter.radii[1])  # no root find
        n = max(indenter.tip_exponent, 2.0) if beyond else 2.0
    return n, (n + 1.0) / n


def depth_ratio(indenter: Indenter, depth: float) -> float:
    """x/a: ``depth`` (m) over the exact contact radius there (Shtaerman's, or Sneddon's for
    another profile; independent of the modulus)."""
    return float(depth / contact_law(indenter, 1.0).contact_radius(depth))


def outside_validity(
    indenter: Indenter,
    deepest: float,
    thickness: float | None,
    finite: bool,
    what: str = "the striker's approach",
) -> list[str]:
    """The limits the deepest approach ``deepest`` (m) passed, one sentence each ([] within
    them); ``thickness``: the layer's (m, None on the half-space), ``finite``: a rubber model
    at finite strain (False: linear elasticity); ``what`` names the depth in the sentences."""
    found = []
    if thickness is not None and deepest >= thickness:
        found.append(
            f"thickness: {what} {deepest:.6g} m reaches the layer's thickness "
            f"{thickness:.6g} m: a strain beyond 100 %, far outside "
            f"{'the validated range' if finite else 'linear elasticity'} (restitution and "
            "energies are not physical)"
        )
    ratio = depth_ratio(indenter, deepest)
    if ratio > MAX_DEPTH_RATIO:
        words = (
            "unverified: the finite-strain contact was validated up to"
            if finite
            else "far outside small strain, where the linear model's numbers are qualitative: "
            "the finite-strain models are validated up to"
        )
        whose = "Shtaerman's" if isinstance(indenter, PowerLawIndenter) else "Sneddon's"
        shown = _apart(ratio, (MAX_DEPTH_RATIO,))  # 1.2004 said "1.2 ..., validated up to 1.2"
        found.append(
            f"depth: {what} {deepest:.6g} m is {shown} contact radii (x/a, with {whose} "
            f"a), {words} x/a {MAX_DEPTH_RATIO:g}"
        )
    return found


def warn_outside_validity(
    indenter: Indenter,
    deepest: float,
    thickness: float | None,
    finite: bool,
    what: str = "the striker's approach",
) -> None:
    """Issue a :class:`ValidityWarning` for each limit of :func:`outside_validity` passed."""
    from .validation import caller_stacklevel

    for sentence in outside_validity(indenter, deepest, thickness, finite, what):
        warnings.warn(sentence, ValidityWarning, stacklevel=caller_stacklevel())


def check_within_layer(
    indenter: Indenter,
    reached: tuple[float, float | None],
    impact: tuple[float, float],
    x_c: float,
    g_inf: float = 1.0,
) -> None:
    """Refuse an impact's approach that reached a layer's thickness, ``reached`` = (depth,
    thickness; None on the half-space; m): the striker would pass through the pad, which no
    model describes. The refusal names the velocity and the mass at which the impact's
    (mass kg, velocity m/s) quasi-static depth on the half-space ``x_c`` (m), with a Prony
    series the fully relaxed body's, x_c g_inf^(-1/(q+1)), is below the thickness: it bounds
    the pad's depth from above (the pad is the stiffer body; at the deepest point the
    impact's energy is at least the static strain energy there); depth ~ (M v0^2)^(1/(q+1)),
    rounded down ("about", scaled from the depth reached, where a run went deeper than that
    bound). A contact curve's depths there are the linear model's own answer (the thin
    layer's foundation limit is checked so) and warn: :func:`outside_validity`."""
    from .validation import LimitError, bound_text

    deepest, thickness = reached
    if thickness is None or deepest < thickness:
        return
    (mass, velocity), q = impact, tip_exponents(indenter, x_c)[1]
    bound = x_c * g_inf ** (-1.0 / (q + 1.0))
    about = "about " if bound < deepest else ""
    share = (1.0 - 1e-12) * thickness / max(bound, deepest)  # below it, even if no digit is cut
    slower = bound_text(velocity * share ** ((q + 1.0) / 2.0), "high")
    lighter = bound_text(mass * share ** (q + 1.0), "high")
    raise LimitError(
        f"mass, velocity: {mass:g} kg at {velocity:g} m/s drive the striker to {deepest:.6g} "
        f"m, through the layer's thickness {thickness:.6g} m: the striker would pass through "
        f"the pad, which no model describes; lower velocity=... to at most {about}{slower} m/s "
        f"or mass=... to at most {about}{lighter} kg (there the half-space's quasi-static "
        "depth, which bounds the pad's, is within it)",
        "velocity",
    )


def check_reach(
    indenter: Indenter,
    depth: float,
    impact: tuple[float, float],
    finite: bool,
    note: str | None = "",
    layer: tuple[float, float, float] | None = None,
    waves: Waves | None = None,
    tight: tuple[float, float] | None = None,
) -> None:
    """Refuse, before any work, an FE impact (mass in kg, velocity in m/s) whose quasi-static
    depth (m) on the half-space has x/a outside the model's reach ([:data:`MIN_FINITE_DEPTH_RATIO`,
    :data:`MAX_DEPTH_RATIO`] at finite strain, [:data:`MIN_DEPTH_RATIO`, :data:`LINEAR_REACH`]
    linear; below the finite-strain floor the refusal says the linear model is exact); beyond it the
    message gives the velocity and the mass that reach the limit, below it likewise
    (depth ~ (M v^2)^(1/(q+1)), x/a ~ x^(1-1/n), n and q the tip's, :func:`tip_exponents`),
    each rounded to pass when tried.
    Both inputs set the depth: the message names both (or the shape coefficient, where the
    paper's striker would be within reach); ``note`` ends it (the route's other remedy;
    None: the route runs beyond the upper reach with a warning, the finite-strain frictionless
    pad with inertia, and only the floor is checked);
    ``layer``: a layer's thickness and the shallowest and deepest depths (m) its mesh resolves,
    which bound the remedy too (None: the half-space); ``waves``: the first-order radiated
    fraction of an impact (mass kg, velocity m/s) on the body of an FE impact with
    inertia (None: no waves), a remedy above :func:`wave_limit` is not named (1e-50
    kg at 3 m/s named 41.4 m/s and 1.9e-48 kg, both refused by :func:`check_wave_speed`): a
    heavier mass that passes both is named instead. The one refusal of an impact's depth
    beyond the reach, on every route: the contact curve whose depths an impact's x_c sets
    (:func:`shtaerman.fem.contact.finite.check_finite_depths`) says it in these words too.
    ``tight``: the mass (kg) and the velocity (m/s) named beyond the upper reach instead of
    those scaled from ``depth`` (a relaxing body's, whose depth is no power law in M v0^2)."""
    from .validation import LimitError

    (mass, velocity), (n, q) = impact, tip_exponents(indenter, depth)
    if not depth > 0:  # x_c underflows to 0: the exact impact refuses it in its own words
        return
    if n <= 1.0:  # a cone's x/a is the same at every depth:
        return  # no impact's remedy; every FE route refuses n <= 1 (validate_fem_inputs)
    ratio = depth_ratio(indenter, depth)
    low, high = _window(finite)
    if note is None:  # only the floor: the route warns beyond the upper reach
        high, note = math.inf, ""
    window = (low, high)
    check_equator(indenter, depth, impact, waves=waves)
    if low <= ratio <= high:  # within reach
        return
    check_table_window(indenter, finite)  # below the floor, as deep as the table reaches
    up = not ratio >= low  # x_c ~ (M v0^2)^(1/(q + 1)): the least of each
    blunt = _shape_remedy(indenter, depth, impact, (ratio, low if up else high), layer, waves)
    at_fault = _striker_at_fault(indenter, depth, q, window)
    remedies, blunt, (shown, passing) = _reach_remedies(
        indenter, (depth, impact), (ratio, window), (layer, waves), blunt, at_fault, tight
    )
    if at_fault:  # the impact's inputs head it too where their remedies are named
        words = (remedies, note, any(shown))
        raise _striker_refusal(indenter, impact, (ratio, window), finite, words)
    if blunt and "depths=" in (note or ""):
        note = ""  # depths as far off as x_c's remedy
    named, striker = ("mass, velocity", "")
    if blunt:
        named, striker = "shape_coefficient", f" {_striker_text(indenter)}"
    drive = f"{named}: {mass:g} kg at {velocity:g} m/s drive the striker{striker}"
    parameter = "shape_coefficient" if striker else ("mass" if up else "velocity")
    if up:
        raise LimitError(
            f"{drive} to {depth:.3g} m only, depth / contact radius "
            f"{_apart(ratio, (low,), 2)}, below the {low:g} "
            + (_FINITE_FLOOR if finite else _LINEAR_FLOOR)
            + f"; raise {remedies}"
            + (_waves_too(waves, q) if shown[0] and passing[1] and not passing[0] else ""),
            parameter,
        )
    raise LimitError(
        f"{drive} to about {depth:.3g} m, depth / contact radius {_apart(ratio, (high,))}, "
        f"beyond the {high:g} up to which {_reach_words(finite)}: lower {remedies}{note}",
        parameter,
    )


def _reach_remedies(
    indenter: Indenter,
    reached: tuple[float, tuple[float, float]],
    reach: tuple[float, tuple[float, float]],
    bounds: tuple,
    blunt: str,
    at_fault: bool,
    tight: tuple[float, float] | None = None,
) -> tuple[str, str, tuple[tuple[str, str], tuple[str, str]]]:
    """The remedies of :func:`check_reach`'s refusal of an impact (``reached`` = (its depth m,
    (mass kg, velocity m/s))) at x/a ``reach[0]`` outside the window ``reach[1]``, ``bounds``
    = its (layer, waves): the impact's velocity and mass, or the shape coefficient ``blunt``
    in their place (:func:`_spanned`); a striker ``at_fault`` (:func:`_striker_at_fault`) has
    ``blunt`` first and the impact's within :data:`REMEDY_SPAN` after it; ``tight``: as
    :func:`check_reach` takes it. Returns the words,
    ``blunt`` where named alone, and the velocity and mass (as shown) of the reach and of the
    waves' limit too."""
    from .validation import SQUARABLE_VELOCITY

    (depth, impact), (ratio, window), (layer, waves) = reached, reach, bounds
    (mass, velocity), (n, q) = impact, tip_exponents(indenter, depth)
    up = ratio < window[0]
    scale, on = _layer_bound(depth, _reach_scale(n, ratio, window), layer)
    (heavy, fast), log = (tight, 0.0) if tight else (impact, scale * (q + 1.0))  # x_c: M v0^2
    shown = (_shown(fast, log / 2.0, up=up), _shown(heavy, log, up=up))
    if up and shown[0] and float(shown[0]) < SQUARABLE_VELOCITY:  # v0^2 a float too
        shown = (_shown(SQUARABLE_VELOCITY, 0.0, up=True), shown[1])
    shape = getattr(indenter, "shape_coefficient", 1.0)
    if at_fault:  # the shape coefficient first, the impact's beside it where physical
        shown = (_near(shown[0], velocity), _near(shown[1], mass))
    else:
        shown, blunt = _spanned(shown, impact, blunt, shape, scale)
    passing = _within_waves(indenter, depth, impact, q, shown, waves, window)
    bound = "least" if up else "most"
    remedies = ""
    if any(shown):
        first, second = (
            ("velocity", passing[0], shown[0], "m/s"),
            ("mass", passing[1], shown[1], "kg"),
        )
        remedies = _remedies(first, second, on, bound, waves.limit(q) if waves else math.inf)
    if not at_fault:
        return _shape_named(remedies, blunt, bound, on), blunt, (shown, passing)
    shaped = f"shape_coefficient=... to at {bound} about {blunt}" if blunt else ""
    if shaped and remedies:  # which inputs each keeps
        shaped = _shape_named("", blunt, bound, on) + ", or " + remedies
    return shaped or remedies, "", (shown, passing)


def _spanned(
    shown: tuple[str, str], impact: tuple[float, float], blunt: str, shape: float, scale: float
) -> tuple[tuple[str, str], str]:
    """The velocity and mass remedies ``shown`` (m/s, kg, as shown) of ``impact`` (mass kg,
    velocity m/s) and the shape coefficient ``blunt`` (:func:`_shape_remedy`, now ``shape``)
    a reach refusal names: ``blunt`` only where it lies within :data:`REMEDY_SPAN` of
    ``shape``, the depth must move beyond it (``scale``: ln of its factor; x/a ~
    x^(1 - 1/n), a near-cone's) and each remedy of the impact is left out (:func:`_near`; or
    beyond the floats), which is then named alone (1e30 kg keeps its mass)."""
    mass, velocity = impact
    near = (_near(shown[0], velocity), _near(shown[1], mass))
    if not blunt or not _near(blunt.split()[0], shape) or abs(scale) <= math.log(REMEDY_SPAN):
        return shown, ""  # the impact's remedies are nearer (1e-300 m/s named A 8.52e92)
    return (near, "") if any(near) else (near, blunt)


def _shape_named(remedies: str, blunt: str, bound: str, on: str) -> str:
    """``remedies`` (the impact's), or the shape coefficient ``blunt`` in their place ("":
    not named); ``bound``: "least" or "most", ``on``: a layer's words."""
    if not blunt:
        return remedies
    return (
        f"shape_coefficient=... to at {bound} about {blunt} with this mass, velocity and body{on}"
    )


def _reach_words(finite: bool) -> str:
    """What the upper end of :func:`_window` is: where the model converges, or is run."""
    return "the finite-strain contact converges" if finite else "an FE impact is run"


def _striker_text(indenter: PowerLawIndenter) -> str:
    """``z = A r^n`` of a power law, as a refusal names it."""
    return f"z = {indenter.shape_coefficient:g} r^{indenter.exponent:g}"


def _striker_refusal(
    indenter: PowerLawIndenter,
    impact: tuple[float, float],
    reach: tuple[float, tuple[float, float]],
    finite: bool,
    words: tuple[str, str, bool],
) -> Exception:
    """The reach refusal of an impact (mass kg, velocity m/s) whose striker is at fault
    (:func:`_striker_at_fault`): its x/a and window ``reach``; ``words`` = the remedies
    (:func:`_reach_remedies`: the shape coefficient, then the impact's; "" none), the note
    and whether the impact's own remedies are among them."""
    from .validation import LimitError
    from .vocabulary import entry

    (mass, velocity), (ratio, (low, high)), (remedies, note, moved) = impact, reach, words
    paper = entry("shape_coefficient").default
    verb = "raise" if ratio < low else "lower"
    named = "shape_coefficient, mass, velocity" if moved else "shape_coefficient"
    return LimitError(
        f"{named}: the striker {_striker_text(indenter)} at {mass:g} kg and "
        f"{velocity:g} m/s reaches depth / contact radius {_apart(ratio, (low, high))}, "
        f"outside the [{low:g}, {high:g}] within which {_reach_words(finite)}, where the "
        f"paper's striker (shape_coefficient={paper:g}) would not (the exact quasi-static "
        f"impact, shtaerman impact, takes any striker)"
        + (f"; {verb} {remedies}" if remedies else "")
        + note,
        "shape_coefficient",
    )


REMEDY_SPAN = 1e6
"""Largest factor between a reach refusal's velocity or mass remedy (or a depth) and the value
given, beyond which it is not named where a shape coefficient is: a 1 m/s impact slowed a
million times moves at 1 um/s, slower than an indentation machine's crosshead (~1e-5 m/s), and
0.7 kg becomes 0.7 mg; near a cone (z = A r^1.01) x/a ~ x^(1 - 1/n) moves a hundredth as fast
as the depth, and 0.12 kg at 1.5 m/s (x/a 7.37) named 1.46e-119 m/s and 1.14e-239 kg."""


def deepest_depth_remedy(indenter: PowerLawIndenter, deep: float, ratio: float) -> str:
    """What brings a contact curve's deepest depth ``deep`` (m), at x/a ``ratio`` beyond
    :data:`MAX_DEPTH_RATIO`, within it: that depth lowered (x/a ~ x^(1 - 1/n)), or where it
    would move by more than :data:`REMEDY_SPAN` (near a cone), the shape coefficient at the
    same depth (:func:`reach_shape`), both rounded to pass."""
    if not isinstance(indenter, PowerLawIndenter):
        return "lower the deepest depth"
    n = indenter.exponent
    scale = _reach_scale(n, ratio, (0.0, MAX_DEPTH_RATIO)) if n > 1.0 else math.inf
    depth = _near(_shown(deep, scale, up=False), deep)  # "" beyond the floats or the span
    if depth:
        return f"lower the deepest depth to at most about {depth} m"
    log_shape = reach_shape(indenter, ratio, MAX_DEPTH_RATIO, impact=False)
    shape = _shown(1.0, log_shape, up=False)
    return f"lower shape_coefficient=... to at most about {shape} m^(1-n) at these depths"


def _near(shown: str, given: float) -> str:
    """``shown`` (a remedy as a message shows it), "" where it is more than
    :data:`REMEDY_SPAN` times ``given`` or less than its 1 / :data:`REMEDY_SPAN` and farther
    from 1 (SI) than ``given``: a remedy that brings 1e30 kg or 1e-21 m/s towards a physical
    size is kept, one that takes 1.5 m/s to 1.46e-119 is not."""
    if not shown:
        return ""
    value = float(shown)
    if abs(math.log(value / given)) <= math.log(REMEDY_SPAN):
        return shown
    return shown if abs(math.log(value)) <= abs(math.log(given)) else ""  # nearer SI's 1


def reach_shape(indenter: PowerLawIndenter, ratio: float, bound: float, impact: bool) -> float:
    """ln of the shape coefficient A (m^(1-n)) of z = A r^n that brings x/a, now ``ratio``,
    to ``bound``: at the same mass, velocity and body (``impact``; x/a = (kappa_n A)^(1/n)
    x^(1 - 1/n) and x_c ~ A^(1/(2n + 1)) give x/a ~ A^(3/(2n + 1))), else at the same depth
    (x/a ~ A^(1/n)). Exact for a power law: z = 5 r^1.01 at 0.12 kg and 1.5 m/s, x/a 7.37,
    reaches x/a 1.2 at A = 0.81 (a near-cone's x/a hardly moves with the depth)."""
    n = indenter.exponent
    power = 3.0 / (2.0 * n + 1.0) if impact else 1.0 / n
    return math.log(indenter.shape_coefficient) + math.log(bound / ratio) / power


def _shape_remedy(
    indenter: Indenter,
    depth: float,
    impact: tuple[float, float],
    target: tuple[float, float],
    layer: tuple[float, float, float] | None,
    waves: Waves | None,
) -> str:
    """The shape coefficient (m^(1-n), as shown, rounded inward) that brings a power law's
    ``impact`` (mass kg, velocity m/s) reaching ``depth`` m at x/a ``target[0]`` to x/a
    ``target[1]`` (:func:`reach_shape`), "" for another profile or where it leaves the FEM's
    range of A, the depths ``layer``'s mesh resolves (radii fixed: depths ~ A) or the waves'
    limit (``waves``: lambda ~ A^(-3/(2n + 1)), exact for a power law)."""
    from .vocabulary import entry

    if not isinstance(indenter, PowerLawIndenter):
        return ""
    (ratio, bound), given = target, indenter.shape_coefficient
    up = bound > ratio
    log_shape = reach_shape(indenter, ratio, bound, impact=True)
    shown = _shown(1.0, log_shape, up=up)
    if not shown or not entry("shape_coefficient").range_for("dynamic").contains(float(shown)):
        return ""
    factor, n = float(shown) / given, indenter.exponent
    moved = depth * factor ** (1.0 / (2.0 * n + 1.0))
    if layer is not None and not layer[1] * factor <= moved <= layer[2] * factor:
        return ""
    if waves is not None and not _fraction(waves, *impact) * factor ** (
        -3.0 / (2.0 * n + 1.0)
    ) <= waves.limit((n + 1.0) / n):
        return ""
    return f"{shown} m^(1-n)"


def check_table_window(indenter: Indenter, finite: bool) -> None:
    """Refuse, before any work, an FE impact (``finite``: a rubber's) of a table whose
    contact at its last radius reaches x/a below the model's floor (:func:`_window`): no mass
    or velocity runs (the depth goes as M v0^2 alone, and one deep enough for the floor drives
    the contact beyond the table), naming the radius a table of its last rows' z ~ r^n would
    reach for x/a ten times the floor at its end (x/a ~ a^(n - 1)), a decade of depths. z = 5
    r^10 to 4 cm (x/a 5.3e-12 at its end) refused each velocity for the other's remedy."""
    from .validation import LimitError, bound_text

    if indenter.kind != "tabulated":
        return
    low, law = _window(finite)[0], contact_law(indenter, 1.0)
    top = law.max_contact_radius
    end = float(law.depth(top))
    ratio = end / top
    if ratio >= low:
        return
    (r_before, r_last), (z_before, z_last) = indenter.radii[-2:], indenter.heights[-2:]
    n = math.log(z_last / z_before) / math.log(r_last / r_before)  # its last rows'
    further = ""
    if n > 1.0:
        radius = bound_text(top * (10.0 * low / ratio) ** (1.0 / (n - 1.0)), "low")
        further = (
            f"; a table reaching r = {radius} m (its last rows' z ~ r^{n:.3g} continued) "
            f"puts x/a {10.0 * low:g} at its end"
        )
    linear = finite and ratio >= MIN_DEPTH_RATIO
    raise LimitError(
        f"profile: the table's last radius {top:.6g} m is in contact from depth {end:.3g} m, "
        f"depth / contact radius {_apart(ratio, (low,), 2)}, below the {low:g} "
        + ("the finite-strain model is run at" if finite else "an FE impact resolves")
        + ": no mass or velocity runs (one that reaches the floor drives the contact beyond "
        f"the table){further}"
        + ("; the linear model (without model=...) runs it" if linear else "")
        + "; the exact quasi-static impact (shtaerman impact) takes any",
        "profile",
    )


def _window(finite: bool) -> tuple[float, float]:
    """The x/a an FE impact is run at: the finite-strain model's, or the linear one's."""
    return (MIN_FINITE_DEPTH_RATIO, MAX_DEPTH_RATIO) if finite else (MIN_DEPTH_RATIO, LINEAR_REACH)


_LINEAR_FLOOR = (
    "an FE impact resolves (strains of that order): the exact quasi-static impact (shtaerman "
    "impact) is the answer there"
)
_FINITE_FLOOR = (
    "the finite-strain model is run at (its correction, ~5 % of x/a, is below the FE's own "
    "error there): the linear model is exact there (shtaerman contact or shtaerman dynamic "
    "without model=...), and so is the exact quasi-static impact (shtaerman impact)"
)
"""The reasons of a refusal below the floor of x/a (:func:`_window`): linear, finite strain."""


def _apart(value: float, bounds: tuple[float, ...], digits: int = 3) -> str:
    """``value`` (a ratio outside a limit) to ``digits`` significant digits, or as many more
    as keep it from printing as one of ``bounds`` or on its other side (x/a 9.96e-07 printed
    "1e-06, below the 1e-06")."""
    for shown in range(digits, 18):
        text = f"{value:.{shown}g}"
        near = float(text)
        if all(near != bound and (near < bound) == (value < bound) for bound in bounds):
            return text
    return repr(value)


def _within_waves(
    indenter: Indenter,
    depth: float,
    impact: tuple[float, float],
    q: float,
    shown: tuple[str, str],
    waves: Waves | None,
    window: tuple[float, float],
) -> tuple[str, str]:
    """The velocity and the mass (m/s, kg, as shown) that bring ``impact`` (mass kg, velocity
    m/s; force exponent ``q``), now reaching ``depth`` m outside the reach ``window`` (the
    least and the largest x/a), within it (``shown``: the reach's, each "" beyond the floats)
    and within the waves' limit (``waves``, :func:`check_reach`'s, below :func:`wave_limit` of
    ``q``; None: ``shown``): a shallow impact's mass heavier where the waves ask it, a deep
    one's velocity lower; "" where none passes both."""
    if waves is None:
        return shown
    (mass, velocity), (speed, weight), (low, high) = impact, shown, window
    limit = waves.limit(q)
    if depth_ratio(indenter, depth) < low:  # faster radiates more, heavier less
        speed = _calm(speed, waves, (mass, None), limit)
        weight = _wave_mass(weight, velocity, q, waves)
        weight = _calm(weight, waves, (None, velocity), limit)
        moved = depth * (float(weight or mass) / mass) ** (1.0 / (q + 1.0))
        return speed, weight if depth_ratio(indenter, moved) <= high else ""
    speed = _calm(_wave_velocity(speed, mass, q, waves), waves, (mass, None), limit)
    moved = depth * (float(speed or velocity) / velocity) ** (2.0 / (q + 1.0))
    speed = speed if depth_ratio(indenter, moved) >= low else ""
    return speed, _calm(weight, waves, (None, velocity), limit)


def _remedies(
    first: tuple[str, str, str, str],
    second: tuple[str, str, str, str],
    on: str,
    bound: str,
    limit: float,
) -> str:
    """The reach refusal's remedies, each (parameter, value that passes the waves' limit too,
    value that passes the reach, unit: values as shown, "" beyond the floats): ``first``, then
    ``second`` after "or", with this striker and body (``on``: a layer's words). One the
    waves' limit (``limit``, the striker's :func:`wave_limit`) refuses ("") is left out; both:
    the reach's, on the massless body."""
    (name, value, bare, unit), (other, other_value, other_bare, other_unit) = first, second
    if not value and not other_value and (bare or other_bare):  # each radiates too much
        first, second = (name, bare, bare, unit), (other, other_bare, other_bare, other_unit)
        return _remedies(first, second, on, bound, limit) + _massless(limit)
    if not value:
        said = f"{other}=... to at {bound} about {other_value} {other_unit}"
        return f"{said} with this striker, {name} and body{on}"
    said = f"{name}=... to at {bound} about {value} {unit} with this striker, {other} and body{on}"
    if not other_value:  # beyond the floats, or refused by the waves' limit
        return said
    return said + f", or {other}=... to at {bound} about {other_value} {other_unit}"


def _waves_too(waves: Waves, q: float) -> str:
    """The end of a shallow impact's reach refusal (force exponent ``q``) whose velocity
    :func:`check_wave_speed` would refuse (``waves``' limit)."""
    return (
        f" (a faster striker radiates above {waves.limit(q):.3g} of its energy as waves, "
        "where the FE impact with inertia breaks down)"
    )


def _calm(
    shown: str,
    waves: Waves | None,
    impact: tuple[float | None, float | None],
    limit: float,
) -> str:
    """``shown``, a remedy's mass (kg) or velocity (m/s) as the message shows it, in place
    of the None of ``impact`` (mass, velocity), "" where ``waves`` puts that impact's
    first-order radiated fraction above ``limit`` (or cannot give it)."""
    if not shown or waves is None:
        return shown
    mass, velocity = impact
    impact = (float(shown), velocity) if mass is None else (mass, float(shown))
    return shown if _fraction(waves, *impact) <= limit else ""


def _fraction(waves: Waves, mass: float, velocity: float) -> float:
    """``waves``' first-order radiated fraction of an impact (mass kg, velocity m/s), NaN
    where it cannot give one (a refused input: the validation's InputError is a ValueError)."""
    try:
        return waves(mass, velocity)
    except (ValueError, ArithmeticError):
        return math.nan


def _reach_scale(n: float, ratio: float, window: tuple[float, float]) -> float:
    """ln of the depth that brings x/a, now ``ratio``, to the nearer end of ``window`` (the
    least and the largest x/a) over the depth now (x/a ~ x^(1 - 1/n), the tip's ``n``)."""
    return math.log(min(max(ratio, window[0]), window[1]) / ratio) / (1.0 - 1.0 / n)


def reach_velocity(indenter: Indenter, depth: float, velocity: float) -> str:
    """The velocity (m/s, three digits, rounded down) at which an impact now at ``velocity``
    reaching ``depth`` (m, its quasi-static x_c on the half-space)
    reaches :data:`MAX_DEPTH_RATIO`, the finite-strain reach: :func:`check_reach`'s remedy,
    for a run that failed beyond it ("" within it, beyond the floats or :data:`REMEDY_SPAN`)."""
    ratio = depth_ratio(indenter, depth) if depth > 0 else 0.0
    n, q = tip_exponents(indenter, depth)
    if not ratio > MAX_DEPTH_RATIO or n <= 1.0:
        return ""  # within reach, or a cone (its x/a moves with no depth)
    scale = _reach_scale(n, ratio, _window(True))  # a near-cone's: a millionth of it or less
    return _near(_shown(velocity, scale * (q + 1.0) / 2.0, up=False), velocity)


def _layer_bound(
    depth: float, scale: float, layer: tuple[float, float, float] | None
) -> tuple[float, str]:
    """``scale`` (ln of the depth a remedy aims at over ``depth``, m) moved within the depths
    ``layer`` = (a layer's thickness, the shallowest and the deepest depth its mesh resolves,
    all m; a velocity beyond them was refused by the thickness range in turn), and the words
    that say so ("" where they do not bind, or on the half-space, None)."""
    if layer is None:
        return scale, ""
    thickness, shallowest, deepest = layer
    bound = min(max(scale, math.log(shallowest / depth)), math.log(deepest / depth))
    if bound == scale:
        return scale, ""
    return bound, f" on this {thickness:.6g} m layer (the depths its mesh resolves)"


def _shown(value: float, log_factor: float, up: bool) -> str:
    """``value`` times e^``log_factor`` to three digits, rounded ``up`` (else down): a bound
    the message names that passes when tried ("" beyond the floating-point range)."""
    from .validation import bound_text

    log_value = math.log(value) + log_factor
    if not -700.0 < log_value < 700.0:
        return ""
    return bound_text(math.exp(log_value), "low" if up else "high")


def check_profile_reach(
    indenter: Indenter,
    modulus: float,
    depths: tuple[float, ...] | None,
    impact: tuple[float, float],
    overshoot: float = 1.0,
    finite: bool = False,
    note: str | None = DEPTHS_INSTEAD,
    layer: tuple[float, float, float] | None = None,
    waves: Waves | None = None,
) -> None:
    """Refuse, before any work, a sphere's or a table's deepest depth (the last of ``depths``
    m, or ``overshoot`` x_c of the ``impact``, mass kg at velocity m/s, on E* = ``modulus``
    Pa) beyond what its FE profile is: a sphere's radius (:func:`check_equator`) or a table's
    last row; a power law's depths set by the impact, outside the x/a an FE impact is run at
    (:func:`check_reach`; ``finite``: the finite-strain contact's; ``note`` ends its refusal:
    the route's other remedy, "" where it takes no depths; ``layer``: a layer's thickness and
    the depths, m, its mesh resolves, which its remedy keeps within; ``waves``: as
    :func:`check_reach`'s). The one check of every contact curve's route (the API, a contact or
    finite-strain study or sweep case) and of an FE impact's before its exact impact is solved
    (:func:`shtaerman.fem.impact.check_impact_reach`).

    Raises
    ------
    LimitError
        Naming ``depths`` where they were given, else ``sphere_radius`` or ``profile``; for a
        power law the mass and velocity, or the shape coefficient.
    """
    from .theory.profile_impact import lower_impact
    from .theory.viscoelastic import elastic_impact
    from .validation import InputError, LimitError

    if indenter.kind == "power-law":
        if depths is None:  # x_c = 3e110 m at 1e300 kg ran, overflowing (x/a 2.9e37)
            deepest = overshoot * _approach(indenter, modulus, impact)
            check_reach(indenter, deepest, impact, finite, note, layer, waves)
        return
    law = contact_law(indenter, modulus)
    if depths is not None:
        deepest, parameter = depths[-1], "depths"
        drive = f"depth {deepest:.6g} m"
    else:
        parameter = "sphere_radius" if indenter.kind == "sphere" else "profile"
        deepest = overshoot * elastic_impact(*impact, law).x_c  # a table's names profile
        drive = (
            f"{impact[0]:g} kg at {impact[1]:g} m/s drive the striker to about {deepest:.3g} m "
            f"({overshoot:g} x_c, the deepest depth)"
        )
    note = f" ({overshoot:g} x_c, the deepest depth)"
    check_equator(indenter, deepest, None if depths is not None else impact, note, overshoot, waves)
    try:
        law.contact_radius(deepest)  # a table's contact within its last row
    except InputError as error:
        text = str(error).removeprefix(f"{error.parameter}: ")
        said = depths is not None and text.startswith(f"depth {deepest:.6g} m ")  # the table's
        refusal = f"{parameter}: {'' if said else drive + ': '}{text}"
        if depths is None:  # overshoot x_c past the table's end, x_c within it
            end = float(law.depth(law.max_contact_radius))
            share = _end_share(indenter, end, deepest, overshoot)
            refusal += " or " + lower_impact(*impact, share)
        raise LimitError(refusal, parameter) from None  # beyond the table: its case's limit


def _approach(indenter: PowerLawIndenter, modulus: float, impact: tuple[float, float]) -> float:
    """x_c (m) of the exact ``impact`` (mass kg, velocity m/s) on E* = ``modulus`` Pa alone,
    in logarithms (0.7 kg at 1e-300 m/s, x_c 3.7e-228 m, was refused for its P_c = 0, naming
    four inputs); beyond the floating-point range, the exact impact's refusal."""
    from .theory.impact import QuasiStaticValidityWarning, log_approach
    from .theory.viscoelastic import elastic_impact

    law, (mass, velocity) = contact_law(indenter, modulus), impact
    if mass > 0 and velocity > 0:
        log_x_c = log_approach(mass, velocity, law.beta, law.force_exponent)
        if abs(log_x_c) < 700.0:  # a normal float
            return math.exp(log_x_c)
    with warnings.catch_warnings():  # the run warns of it; a refusal is one line
        warnings.simplefilter("ignore", QuasiStaticValidityWarning)
        return elastic_impact(mass, velocity, law).x_c


def check_wave_speed(
    impact: tuple[float, float],
    estimate: object,
    waves: Waves,
    force_exponent: float,
    reaches: Callable[[float, float], bool] | None = None,
) -> None:
    """Refuse, before any work, an FE impact with inertia (mass in kg, velocity in m/s)
    whose first-order radiated fraction ``estimate`` (a
    :class:`~shtaerman.theory.radiation.RadiationEstimate` on the body of ``waves``) exceeds
    the body's limit of its force exponent (``force_exponent`` q, the tip's:
    :func:`tip_exponents`; ``waves.limit``), naming the velocity and the density that pass:
    lambda goes as sqrt(density) and, for a power-law force P ~ x^q, as v0^((3q - 3)/(q + 1)).
    A sphere's or a table's force varies with depth: that velocity is a first guess, checked
    by ``waves`` (a power law's is exact), which a few rescalings bring below the limit (a
    12 g ball R = 50 mm at 60 m/s: q = 3/2 named 1.82 m/s, at lambda 0.837, above session
    59's 0.7). Where ``reaches`` (whether an impact, mass kg and velocity m/s, lies within
    :func:`check_reach`'s window; None: not checked) refuses that velocity, the refusal says
    so and names the density and the mass that pass instead; unchecked, a velocity beyond
    :data:`REMEDY_SPAN` is not named (the density is)."""
    from .validation import LimitError

    fraction, q, density = estimate.energy_fraction, force_exponent, waves.rho
    limit = waves.limit(q)
    if not fraction > limit:
        return
    mass, velocity = impact
    c_s, share = estimate.shear_wave_speed, limit / fraction
    slower = _slower(velocity, share, q)
    about = ""
    if not waves.power_law:
        power = (q + 1.0) / (3.0 * q - 3.0)
        at = functools.partial(waves, mass)
        slower, about = _passing_velocity(slower, power, at, limit)
    remedy, named = f" or velocity {about}{slower:.3g} m/s would pass", "velocity"
    if reaches is not None and not reaches(mass, float(f"{slower:.3g}")):
        remedy = _heavier_instead(impact, slower, q, share, reaches)
        named = "mass" if remedy.startswith(" or mass") else "density2"
    elif not _near(f"{slower:.3g}", velocity):  # a table's 0.0029 m/s named 3.7e-29
        remedy, named = " would pass", "density2"
    prefix = named if named == "density2" else f"{named}, density2"
    shown = _apart(fraction, (limit, float(f"{limit:.3g}")))  # 0.4502 said "0.45, above 0.45"
    lighter, massless = passing_density(density, share), "the quasi-static impact"
    lighter_text = f"density2 {lighter:g} kg/m^3"
    if not lighter:  # below the density's range (1e-300 kg at 1.34e154 m/s)
        lighter_text, massless = f"density2 0 ({massless} without waves)", ""
    raise LimitError(
        f"{prefix}: {mass:g} kg at {velocity:g} m/s is {velocity / c_s:.3g} of the body's "
        f"shear wave speed c_s = sqrt(G / density2) = {c_s:.3g} m/s and "
        f"{_radiates(fraction, shown)}, above "
        f"{_limit_text(q, limit, waves.rubber)}, where the FE impact with inertia breaks down "
        f"(measured: beyond it the linear one fails its energy balance or its reflected-energy "
        f"check): "
        f"{lighter_text}{remedy}"
        + (f" (density2 0: {massless} without waves)" if massless else ""),
        named,
    )


def _radiates(fraction: float, shown: str) -> str:
    """The first-order radiated ``fraction`` (printed as ``shown``) in words: a share of the
    striker's energy, or, from 1 up, a multiple of it that the first order (valid well below 1)
    cannot hold."""
    if fraction < 1.0:
        return f"radiates an estimated {shown} of its energy as waves (first order)"
    return f"would radiate {shown} times its energy as waves to first order (valid well below 1)"


def passing_density(density: float, share: float) -> float:
    """The density (kg/m^3, three digits) at which an impact radiating ``1 / share`` of the
    waves' limit on ``density`` passes it, with 1 % to spare (the first-order fraction goes as
    sqrt(density)); 0 where that lies below the density's range (only the massless body)."""
    from .theory.materials import DENSITY_RANGE

    lighter = float(f"{0.99 * density * share**2:.3g}")
    return lighter if lighter >= DENSITY_RANGE[0] else 0.0


def _limit_text(q: float, limit: float, rubber: bool) -> str:
    """The wave-speed ``limit`` of a striker whose force goes as x^``q`` as its refusal says
    it (with the exponent where it is a blunt striker's, below :data:`MAX_RADIATED_ESTIMATE`;
    the nu2 range where it is a ``rubber``'s: :func:`on_rubber`)."""
    if limit >= MAX_RADIATED_ESTIMATE:
        return f"{limit:.3g}"
    on = " on a rubber, nu2 {:g} to {:g}".format(*RUBBER_POISSON) if rubber else ""
    return f"{limit:.3g} (the limit of a force ~ x^{q:.3g}{on}, lower for blunter strikers)"


def _heavier_instead(
    impact: tuple[float, float],
    slower: float,
    q: float,
    share: float,
    reaches: Callable[[float, float], bool],
) -> str:
    """The end of the wave-speed refusal of ``impact`` (mass kg, velocity m/s) whose passing
    velocity ``slower`` (m/s) ``reaches`` refuses (too shallow for an FE impact: 1e-40 kg at 3
    m/s named 5.96e-06 m/s, below the reach's 4.14e-04): the heavier mass that passes the waves
    at the same velocity (lambda ~ M^((q - 2)/(q + 1)) of a force P ~ x^``q`` < 2, exact for a
    power law; the limit over its lambda ``share``), where ``reaches`` takes it; the words
    after the density's remedy."""
    mass, velocity = impact
    said = (
        f"; velocity {slower:.3g} m/s, which would pass the waves, drives the striker "
        "shallower than an FE impact resolves"
    )
    heavier = _heavier(mass, share, q)
    if heavier and reaches(float(heavier), velocity):
        return f" or mass {heavier} kg at {velocity:g} m/s would pass{said}"
    return f" would pass, no velocity with this mass{said}"


def _heavier(mass: float, share: float, q: float) -> str:
    """The mass (kg, three digits, rounded up) that brings the first-order radiated fraction of
    an impact of ``mass`` to 0.99 ``share`` of it (lambda ~ M^((q - 2)/(q + 1)) of a force P
    ~ x^``q``, exact for a power law; "" for q >= 2, where a heavier mass radiates no less)."""
    if q >= 2.0:
        return ""
    return _shown(mass, math.log(0.99 * share) * (q + 1.0) / (q - 2.0), up=True)


def _wave_mass(shown: str, velocity: float, q: float, waves: Waves) -> str:
    """``shown`` (a mass in kg as the message shows it), or the heavier one :func:`_heavier`
    names where ``waves`` puts its impact at ``velocity`` (m/s) above :func:`wave_limit` of
    the force exponent ``q`` ("" where it cannot say)."""
    fraction = _fraction(waves, float(shown), velocity) if shown else math.nan
    limit = waves.limit(q)
    if not fraction > limit:
        return shown if fraction == fraction else ""
    return _heavier(float(shown), limit / fraction, q)


def _wave_velocity(shown: str, mass: float, q: float, waves: Waves | None) -> str:
    """``shown`` (a velocity in m/s as the message shows it), or the lower one that brings
    the first-order radiated fraction ``waves`` gives of an impact of ``mass`` (kg) there
    below :func:`wave_limit` of the force exponent ``q`` (:func:`_passing_velocity`; ""
    unsettled)."""
    if not shown or waves is None:
        return shown
    fraction, limit = _fraction(waves, mass, float(shown)), waves.limit(q)
    if not fraction > limit:
        return shown if fraction == fraction else ""
    power = (q + 1.0) / (3.0 * q - 3.0)
    lower = _slower(float(shown), limit / fraction, q)
    lower, about = _passing_velocity(lower, power, lambda velocity: waves(mass, velocity), limit)
    return "" if about else f"{lower:.3g}"


def _slower(velocity: float, share: float, q: float) -> float:
    """The velocity (m/s) that brings an impact's first-order radiated fraction to 0.99
    ``share`` of its own at ``velocity`` (lambda ~ v0^((3q - 3)/(q + 1)) of a force P ~
    x^``q``, exact for a power law)."""
    return 0.99 * velocity * share ** ((q + 1.0) / (3.0 * q - 3.0))


def _passing_velocity(
    velocity: float,
    power: float,
    fraction_at: Callable[[float], float] | None,
    limit: float,
) -> tuple[float, str]:
    """``velocity`` (m/s) rescaled by (``limit`` / lambda)^``power`` until ``fraction_at``
    puts it, rounded as the message shows it, at or below ``limit`` (at most 8 times, each
    aiming 1 % below in velocity), and "" (checked); without ``fraction_at``, unsettled or
    out of its range, ``velocity`` and "about "."""
    if fraction_at is None:
        return velocity, "about "
    for _ in range(8):
        shown = float(f"{velocity:.3g}")
        try:
            fraction = fraction_at(shown)
        except (ValueError, ArithmeticError):  # a velocity beyond the quadrature's range
            break
        if not fraction > limit:
            return shown, ""
        velocity = 0.99 * shown * (limit / fraction) ** power
    return velocity, "about "


def check_equator(
    indenter: Indenter,
    deepest: float,
    impact: tuple[float, float] | None = None,
    note: str = "",
    overshoot: float = 1.0,
    waves: Waves | None = None,
) -> None:
    """Refuse, before any work, a sphere pressed to ``deepest`` >= its radius R (m): its
    equator at the surface, beyond which the FE's sphere is a flat rim (z = R for r > R)
    pressed into the body, not a ball (R = 5 mm at 0.7 kg and 3 m/s on the paper's rubber,
    x_c = 2 R: the contact ran onto the rim and failed at its edge). The one check of every
    route: the refusal names ``depths`` when they were given, else ``sphere_radius`` and the
    ``impact`` (mass kg, velocity m/s) that set the depth (``overshoot`` times its x_c) and
    the velocity and mass that pass (``waves``: as :func:`check_reach` takes it, within the
    waves' limit too: :func:`_equator_remedy`); ``note`` follows the depth."""

    radius = getattr(indenter, "radius", None)
    if getattr(indenter, "kind", "") != "sphere" or deepest < radius:
        return
    if impact is None:
        remedy = f"give smaller depths or a sphere_radius=... above {deepest:.6g} m"
        raise _equator_refusal("depths", f"depth {deepest:.6g} m,", radius, remedy)
    drive = f"{impact[0]:g} kg at {impact[1]:g} m/s drive the striker to about "
    remedy = _equator_remedy(indenter, deepest, impact, overshoot, waves)
    raise _equator_refusal("sphere_radius", f"{drive}{deepest:.3g} m{note},", radius, remedy)


def equator_energy_refusal(radius: float, impact: tuple[float, float], share: float) -> Exception:
    """The refusal of a sphere of ``radius`` m that the impact (mass kg, velocity m/s) drives
    to its equator, where the FE's sphere ends (:func:`check_equator`), when its depth is not
    known (the exact impact refused the contact past R): the velocity, the mass and the
    sphere whose energy is ``share`` of the impact's (<= 0: underflowed) stop short of it."""
    from .theory.profile_impact import larger_sphere, lower_inputs

    remedy = "take a larger sphere (sphere_radius=...)"
    if share > 0.0:
        log_share = math.log(share)
        remedy = _equator_words(*lower_inputs(*impact, log_share), larger_sphere(radius, log_share))
    drive = f"{impact[0]:g} kg at {impact[1]:g} m/s drive the striker"
    return _equator_refusal("sphere_radius", drive, radius, remedy)


def _equator_refusal(parameter: str, drive: str, radius: float, remedy: str) -> Exception:
    """The equator refusal's words: ``drive`` (what takes the striker there), the sphere's
    ``radius`` m and the ``remedy``, naming ``parameter``."""
    from .validation import LimitError

    return LimitError(
        f"{parameter}: {drive} beyond the sphere's radius {radius:.6g} m (its equator, past "
        f"which the FE profile is no sphere): the deepest depth must be below the radius; "
        f"{remedy}",
        parameter,
    )


def _equator_remedy(
    indenter: Indenter,
    deepest: float,
    impact: tuple[float, float],
    overshoot: float,
    waves: Waves | None,
) -> str:
    """The lower velocity and mass (m/s, kg) that bring ``overshoot`` times x_c of
    ``impact`` (mass kg, velocity m/s), now ``deepest`` m, below the sphere's radius, or a
    larger sphere. With ``waves`` (:func:`check_reach`'s) each is held to
    :func:`wave_limit` too: the velocity lowered further where the waves ask it
    (:func:`_wave_velocity`), the mass left out where it radiates above the limit (a lighter
    striker radiates more), and so the larger sphere where the impact of M times the energy's
    share does (a sphere of radius R' radiates as M (R / R')^3 on R, the quasi-static impact
    and lambda being self-similar in R; each R' past the equator's least, R share^(-1/3),
    radiates more): 0.039 kg at 10 m/s on 1000 kg/m^3 rubber, a 10 mm sphere's mass remedy,
    radiated 0.602, above 0.45."""
    from .theory.profile_impact import larger_sphere, lower_inputs

    (mass, velocity), q = impact, tip_exponents(indenter, deepest)[1]
    log_share = _end_share(indenter, math.nextafter(indenter.radius, 0.0), deepest, overshoot)
    slower, lighter = lower_inputs(mass, velocity, log_share)
    larger, left = larger_sphere(indenter.radius, log_share), []
    if waves is not None:
        limit = waves.limit(q)
        calm = (
            _wave_velocity(slower, mass, q, waves),
            _calm(lighter, waves, (None, velocity), limit),
            _fraction(waves, mass * math.exp(log_share), velocity) <= limit,
        )
        if not any(calm):  # the velocity's unsettled, the others radiate too much
            return _equator_words(slower, lighter, larger) + _massless(limit, "each")
        left = ["a lighter striker"] if lighter and not calm[1] else []
        left += [] if calm[2] else ["a larger sphere"]
        slower, lighter, larger = calm[0], calm[1], larger if calm[2] else ""
    if not left:
        return _equator_words(slower, lighter, larger)
    return _equator_words(slower, lighter, larger) + (
        f" ({' or '.join(left)} radiates above {limit:.3g} of its energy as waves on this "
        "density2, where the FE impact with inertia breaks down)"
    )


def _equator_words(slower: str, lighter: str, larger: str) -> str:
    """ "lower velocity=... to at most ``slower`` m/s or mass=... to at most ``lighter`` kg
    or ``larger``", each left out where ""."""
    named = [f"velocity=... to at most {slower} m/s"] if slower else []
    named += [f"mass=... to at most {lighter} kg"] if lighter else []
    lowered = [f"lower {' or '.join(named)}"] if named else []
    return " or ".join(lowered + ([larger] if larger else []))


def _massless(limit: float, each: str = "either") -> str:
    """The end of a remedy ``each`` of whose impacts radiates above ``limit``
    (:func:`wave_limit`): the massless body."""
    return (
        f", on the massless body, density2=0 (at this density2 {each} radiates above "
        f"{limit:.3g} of its energy as waves, where the FE impact with inertia breaks down)"
    )


def _end_share(indenter: Indenter, end: float, deepest: float, overshoot: float) -> float:
    """ln of the share of an impact's energy that brings ``overshoot`` times its x_c, now
    ``deepest`` m, to the depth ``end`` (m) of the profile: just below a sphere's radius, a
    table's last row. The quasi-static work to a contact radius is E* times the profile's,
    so their ratio needs no modulus."""
    from .theory.profile_impact import work_to

    law = contact_law(indenter, 1.0)
    below = law.contact_radius(end / overshoot)
    now = law.contact_radius(deepest / overshoot)
    return math.log(work_to(law, below)) - math.log(work_to(law, now))


def _striker_at_fault(
    indenter: Indenter, depth: float, q: float, window: tuple[float, float]
) -> bool:
    """Whether the paper's shape coefficient, at the same mass, velocity and body, would bring
    the depth ``depth`` (m) of this impact (force exponent ``q``) within the x/a ``window``
    (least, largest): then the striker's, not the impact's, is at fault
    (x_c ~ A^(1 / (n (q + 1))) as beta ~ A^(-1/n))."""
    from .vocabulary import entry

    if not isinstance(indenter, PowerLawIndenter):  # a sphere's or a table's size is its own
        return False
    paper = PowerLawIndenter(entry("shape_coefficient").default, indenter.exponent)
    scale = paper.shape_coefficient / indenter.shape_coefficient
    moved = depth * scale ** (1.0 / (indenter.exponent * (q + 1.0)))
    return window[0] <= depth_ratio(paper, moved) <= window[1]
