"""The effects a :class:`~shtaerman.problem.Problem` adds to the paper's impact, and the variants
of it that switch them off.

The paper's impact (Ol'shanskii et al. 2019; :func:`shtaerman.impact`) is quasi-static on a
linear, elastic, frictionless half-space without mass. A problem departs from it by up to five
effects, each a part (or a field of one) that the idealisation sets otherwise:

- ``pad``: a layer on a rigid base (:class:`~shtaerman.problem.Geometry`) instead of the
  half-space;
- ``waves``: a body density > 0 (inertia) instead of 0 (massless);
- ``finite strain``: a rubber ``model`` instead of ``linear``;
- ``viscoelasticity``: a Prony series instead of none;
- ``friction``: a bonded or Coulomb :class:`~shtaerman.problem.Interface` instead of
  frictionless.

Each effect is a function that switches it off (``parts -> parts``); every variant of the
effect table is the full problem with some of them applied.
"""

from __future__ import annotations

from collections.abc import Callable, Mapping
from dataclasses import dataclass, fields, replace
from typing import Any

from ...problem import RUBBER_OPTIONS, Geometry, Interface, Problem
from ...validation import InputError

__all__ = ["EFFECTS", "Effect", "Variant", "parts_of", "variants"]

Parts = Mapping[str, Any]
"""A problem's parts by field name (``striker``, ``body``, ``geometry``, ``interface``,
``loading``): :func:`shtaerman.problem.parts`, or a :class:`Problem`'s fields."""


def _body(parts: Parts, **changes: Any) -> dict[str, Any]:
    return {**parts, "body": replace(parts["body"], **changes)}


@dataclass(frozen=True)
class Effect:
    """One effect: its ``name``, and ``off``, which returns the parts with it switched off
    (the paper's idealisation of that part)."""

    name: str
    off: Callable[[Parts], dict[str, Any]]

    def present(self, parts: Parts) -> bool:
        """Whether ``parts`` have this effect switched on."""
        return self.off(parts) != dict(parts)


EFFECTS = (
    Effect("pad", lambda parts: {**parts, "geometry": Geometry()}),
    Effect("waves", lambda p: _body(p, material=replace(p["body"].material, density=0.0))),
    Effect("finite strain", lambda p: _body(p, model="linear", **dict.fromkeys(RUBBER_OPTIONS))),
    Effect("viscoelasticity", lambda parts: _body(parts, prony=None)),
    Effect("friction", lambda parts: {**parts, "interface": Interface()}),
)
"""The effects, in the table's order."""


@dataclass(frozen=True)
class Variant:
    """One run of the table: ``label`` (``none``, ``pad alone``, ``full``, ``without pad``),
    ``role`` (``none``, ``alone``, ``full``, ``without``), its ``effect`` (None for ``none``
    and ``full``) and its parts (not yet checked to combine)."""

    label: str
    role: str
    effect: str | None
    parts: dict[str, Any]


def parts_of(problem: Problem | Parts) -> dict[str, Any]:
    """The parts of ``problem`` (a :class:`Problem`, or its parts as a mapping: checked first,
    a missing part or an unknown key refused naming ``problem``, a part refused); an
    impact's only (InputError, as :func:`shtaerman.dynamic` refuses a curve or no problem)."""
    if not isinstance(problem, Problem | Mapping):
        raise InputError(
            "problem must be a Problem (Problem.impact) or its parts (a mapping), got "
            f"{type(problem).__name__}",
            "problem",
        )
    problem = problem if isinstance(problem, Problem) else Problem(**_parts(problem))
    problem.alone("effects", "impact")
    return {part.name: getattr(problem, part.name) for part in fields(problem)}


def _parts(given: Mapping[str, Any]) -> Mapping[str, Any]:
    """``given`` if its keys are a problem's parts (striker and body at least), else an
    InputError naming ``problem`` (a mapping of flat keywords is no problem's parts)."""
    names = [part.name for part in fields(Problem)]
    unknown = sorted(str(key) for key in given if key not in names)
    missing = [name for name in names[:2] if name not in given]
    if unknown or missing:
        wrong = f"unknown keys {unknown}" if unknown else f"no {' and no '.join(missing)}"
        raise InputError(
            f"problem: a mapping holds a problem's parts {names} ({wrong}); build the impact "
            "with sh.Problem.impact(indenter, body, mass=..., velocity=..., ...)",
            "problem",
        )
    return given


def _without(parts: Parts, effects: tuple[Effect, ...]) -> dict[str, Any]:
    out = dict(parts)
    for effect in effects:
        out = effect.off(out)
    return out


def variants(parts: Parts) -> tuple[tuple[Variant, ...], tuple[str, ...]]:
    """The table's variants of the full problem ``parts`` and the names of the effects it
    does not have: ``none`` (every effect off: the paper's problem, by FE), each present effect
    alone, ``full`` and the full problem without each present effect. With one effect, its
    ``alone`` is the full problem and ``without`` it is ``none`` (the runs are shared)."""
    present = tuple(effect for effect in EFFECTS if effect.present(parts))
    absent = tuple(effect.name for effect in EFFECTS if effect not in present)
    rows = [Variant("none", "none", None, _without(parts, present))]
    for effect in present:
        others = tuple(other for other in present if other is not effect)
        rows.append(Variant(f"{effect.name} alone", "alone", effect.name, _without(parts, others)))
    rows.append(Variant("full", "full", None, dict(parts)))
    for effect in present:
        rows.append(Variant(f"without {effect.name}", "without", effect.name, effect.off(parts)))
    return tuple(rows), absent
