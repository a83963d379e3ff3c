"""The case a study computed, in words: its body (a half-space or a pad on its base), the
material model with its constants, the Prony series and the interface.

Every finding of a report is prefixed with these words (:func:`.entry.stored_findings`), so a
finding never reads as the paper's elastic, frictionless half-space when the study was not.
"""

from __future__ import annotations

from collections.abc import Mapping
from typing import TYPE_CHECKING, Any

from ..plots.labels import model_label

if TYPE_CHECKING:
    from ..fem.rubber import RubberModel
    from ..theory.viscoelastic import PronySeries

__all__ = [
    "body_words",
    "case_words",
    "interface_words",
    "prefixed",
    "prony_words",
    "rubber_constants",
    "rubber_words",
]

VOLUMETRIC = {"quadratic": "K/2 (J-1)^2", "logarithmic": "K/2 (ln J)^2"}
"""A compressible rubber's volumetric energy in words."""


def rubber_constants(rubber: RubberModel) -> str:
    """The constants the model's shape depends on, "r = C01/(C10 + C01) = 0.085" ("" for the
    neo-Hookean: none)."""
    return {
        "mooney-rivlin": f"r = C01/(C10 + C01) = {rubber.mooney_ratio:g}",
        "yeoh": "c2, c3 = C20/C10, C30/C10 = {:g}, {:g}".format(*rubber.yeoh),
        "gent": f"Jm = {rubber.gent_limit:g}",
    }.get(rubber.name, "")


def rubber_words(rubber: RubberModel, poisson_ratio: float) -> str:
    """The rubber model and the constants it depends on: "Mooney-Rivlin rubber,
    r = C01/(C10 + C01) = 0.085"; the volumetric energy where nu2 < 0.5 makes it count."""
    words = [f"{model_label(rubber.name)} rubber"]
    if rubber_constants(rubber):
        words.append(rubber_constants(rubber))
    if poisson_ratio < 0.5:
        words.append(f"volumetric energy {VOLUMETRIC[rubber.volumetric]}")
    return ", ".join(words)


def prony_words(prony: PronySeries | None) -> str:
    """ "Prony series g:tau = 0.5:0.0020526 s" ("" for an elastic body)."""
    if prony is None:
        return ""
    return f"Prony series g:tau = {prony.text()} s"


def body_words(thickness: float | None, base: str | None = None) -> str:
    """ "half-space", or "20 mm pad on a bonded rigid base" (``thickness`` in m)."""
    if thickness is None:
        return "half-space"
    return f"{1e3 * thickness:.3g} mm pad on a {base or 'bonded'} rigid base"


def interface_words(interface: str = "frictionless", friction: float | None = None) -> str:
    """ "frictionless indenter", "bonded indenter (no slip)" or "bonded indenter with Coulomb
    friction mu = 0.3"."""
    if interface != "bonded":
        return f"{interface} indenter"
    if friction is None:
        return "bonded indenter (no slip)"
    return f"bonded indenter with Coulomb friction mu = {friction:g}"


def case_words(
    *,
    material: str = "linear elastic",
    prony: PronySeries | None = None,
    thickness: float | None = None,
    base: str | None = None,
    interface: str = "frictionless",
    friction: float | None = None,
) -> str:
    """The whole case: "20 mm pad on a bonded rigid base; linear viscoelastic, Prony series
    g:tau = 0.3:0.002 s; bonded indenter with Coulomb friction mu = 0.3".

    ``material``: the model in words (:func:`rubber_words` for a rubber); ``thickness`` in m
    (None: the half-space); ``friction``: Coulomb's mu of a bonded indenter (None: no slip).
    """
    if prony is not None:
        relaxing = "linear viscoelastic" if material == "linear elastic" else material
        material = f"{relaxing}, {prony_words(prony)}"
    return "; ".join((body_words(thickness, base), material, interface_words(interface, friction)))


def prefixed(name: str, study: Mapping[str, Any], sentence: str) -> str:
    """ "name (case): sentence" of a results.json entry; "name: sentence" for an entry
    without its case (written by an earlier release)."""
    case = study.get("case")
    return f"{name} ({case}): {sentence}" if case else f"{name}: {sentence}"
