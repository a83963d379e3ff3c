"""The researcher's case as one value: striker, body, geometry, interface and loading.

A :class:`Problem` is built and checked once, where input enters (the command line, the Python
API, a study file, a sweep case); the layers below trust it. Each part's values are checked by
the vocabulary (:mod:`shtaerman.vocabulary`, ranges and units); which parts combine is declared
once, in :data:`SUPPORT`, and which numerical and output options each combination takes, in
:data:`OPTION_SUPPORT`. The command line's and the API's refusals, and the documentation's
table of combinations, come from these two tables.

A combination is a :class:`Cell`: the body's model (``linear`` or a ``rubber`` at finite
strain), whether it relaxes (a Prony series), the geometry (``half-space``, ``layer bonded``,
``layer lubricated``), the interface (``frictionless``, ``bonded``, ``coulomb``) and the
loading (``curve``: pressed to given depths; ``massless``: the impact on a body without
inertia, the quasi-static impact; ``inertia``: the impact with waves).
"""

from __future__ import annotations

import functools
import math
import re
from collections.abc import Callable, Iterable, Mapping, Sequence
from dataclasses import dataclass, field, fields
from typing import TYPE_CHECKING, Any, NamedTuple, TypeVar, cast

from .fem.mesh import Geometry
from .theory.materials import RIGID, Material
from .validation import InputError, NumericalFailureError, caller_stacklevel, validate_positive
from .vocabulary import VOCABULARY, entry

if TYPE_CHECKING:
    from .fem.rubber import RubberModel
    from .theory.sneddon import Indenter
    from .theory.viscoelastic import PronySeries

__all__ = [
    "LOADING_KEYWORDS",
    "MODELS",
    "OPTION_SUPPORT",
    "SUPPORT",
    "Body",
    "Cell",
    "Geometry",
    "Interface",
    "Loading",
    "Problem",
    "Striker",
    "Unsupported",
    "check_keywords",
    "check_options",
    "check_outputs",
    "in_python_words",
    "parts",
    "support_table",
    "worded",
]

MODELS = ("linear", "neo-hookean", "mooney-rivlin", "yeoh", "gent")
"""The body's material models: linear elasticity (the default), then the rubbers at finite
strain (:mod:`shtaerman.fem.rubber`)."""
_Function = TypeVar("_Function", bound=Callable[..., Any])
RUBBER_OPTIONS = ("mooney_ratio", "yeoh", "gent_limit", "volumetric")
"""The rubber models' shape options (:func:`shtaerman.fem.rubber.rubber_model`)."""
RUBBER_SHAPES = {"mooney_ratio": "mooney-rivlin", "yeoh": "yeoh", "gent_limit": "gent"}
"""A rubber's shape option -> the model it applies to (``volumetric``: every rubber)."""


def check_bodies(indenter: object, body: object, striker: object = RIGID) -> None:
    """Raise InputError unless the arguments are an indenter (PowerLawIndenter, SphereIndenter
    or TabulatedIndenter) and two Materials whose finite moduli lie in E2's and E1's range."""
    from .theory.sneddon import INDENTERS

    if not isinstance(indenter, INDENTERS):
        raise InputError(
            f"indenter must be a PowerLawIndenter(shape_coefficient, exponent), a "
            f"SphereIndenter(radius) or a TabulatedIndenter, got {type(indenter).__name__}",
            "indenter",
        )
    for name, value in (("body", body), ("striker", striker)):
        if not isinstance(value, Material):
            raise InputError(
                f"{name} must be a Material(youngs_modulus, poisson_ratio, density=None), got "
                f"{type(value).__name__}",
                name,
            )
    if math.isinf(body.youngs_modulus) and math.isinf(striker.youngs_modulus):
        raise InputError("body: a rigid body under a rigid striker has no contact law", "body")
    for name, material in (("E2", body), ("E1", striker)):  # every route's range (inf: rigid)
        if math.isfinite(material.youngs_modulus):
            entry(name).check(material.youngs_modulus)


@dataclass(frozen=True)
class Striker:
    """The striker: its profile, and for an impact its mass and approach velocity.

    Parameters
    ----------
    indenter : PowerLawIndenter, SphereIndenter or TabulatedIndenter
        The profile of its tip: z = A r^n, the exact sphere, or a tabulated z(r).
    mass : float, optional
        Mass in kg (an impact, or the impact whose x_c a contact curve's default depths reach).
    velocity : float, optional
        Approach velocity in m/s.
    material : Material
        Its elasticity (E1, nu1; default rigid).
    """

    indenter: Indenter
    mass: float | None = None
    velocity: float | None = None
    material: Material = RIGID

    def __post_init__(self) -> None:
        for name, unit in (("mass", "kg"), ("velocity", "m/s")):
            value = getattr(self, name)
            if value is not None:
                object.__setattr__(self, name, validate_positive(name, value, unit))


@dataclass(frozen=True)
class Body:
    """The struck body: its small-strain elasticity and density, its material model, and an
    optional shear relaxation.

    Parameters
    ----------
    material : Material
        E2 (Pa; with ``prony`` the instantaneous value), nu2 and the density in kg/m^3
        (0: massless, None: not given).
    model : str
        One of :data:`MODELS`.
    mooney_ratio, yeoh, gent_limit, volumetric : optional
        The rubber's shape (:func:`shtaerman.fem.rubber.rubber_model`); rubber models only.
    prony : PronySeries or str, optional
        Shear relaxation ``g1:tau1,...`` (tau in s); None: elastic.
    """

    material: Material
    model: str = "linear"
    mooney_ratio: float | None = None
    yeoh: Any = None
    gent_limit: float | None = None
    volumetric: str | None = None
    prony: PronySeries | None = None

    def __post_init__(self) -> None:
        from .theory.prony_sources import prony_input

        if self.model not in MODELS:
            raise InputError(
                f"model: unknown model {self.model!r}. Pick one of {list(MODELS)}", "model"
            )
        modulus = getattr(self.material, "youngs_modulus", None)  # a non-Material: Problem's
        object.__setattr__(self, "prony", prony_input(self.prony, youngs_modulus=modulus))
        if not self.finite:
            for name in RUBBER_OPTIONS:
                if getattr(self, name) is not None:
                    raise InputError(f"{name}: applies to the finite-strain models only", name)
        else:
            for name, owner in RUBBER_SHAPES.items():
                if getattr(self, name) is not None and self.model != owner:
                    raise InputError(f"{name}: applies to the {owner} model only", name)
            self.rubber()  # checks the shape options' values now, each naming itself

    @property
    def finite(self) -> bool:
        """Whether the body is a rubber at finite strain."""
        return self.model != "linear"

    def rubber(self) -> RubberModel | None:
        """The rubber model (None for the linear body)."""
        from .fem.rubber import rubber_model

        if not self.finite:
            return None
        return rubber_model(self.model, *(getattr(self, name) for name in RUBBER_OPTIONS))


@dataclass(frozen=True)
class Interface:
    """The striker's surface: ``frictionless``, or ``bonded`` (a point that touches it sticks)
    with an optional Coulomb coefficient ``friction`` >= 0 (a point slides where its shear
    exceeds friction x its pressure)."""

    kind: str = "frictionless"
    friction: float | None = None

    def __post_init__(self) -> None:
        object.__setattr__(self, "kind", entry("interface").check(self.kind))
        if self.friction is None:
            return
        if self.kind != "bonded":
            raise InputError(
                "friction: applies to a bonded indenter only; give interface='bonded' too",
                "friction",
            )
        object.__setattr__(self, "friction", float(entry("friction").check(self.friction)))

    @property
    def name(self) -> str:
        """``frictionless``, ``bonded`` (no slip) or ``coulomb``."""
        return "coulomb" if self.friction is not None else self.kind

    @property
    def coefficient(self) -> float | None:
        """The solvers' friction: None frictionless, ``math.inf`` bonded (no slip), else
        Coulomb's mu."""
        if self.kind == "frictionless":
            return None
        return math.inf if self.friction is None else self.friction


@dataclass(frozen=True)
class Loading:
    """How the striker loads the body: ``curve`` (pressed to ``depths`` in m, increasing; None:
    the default depths, up to the x_c of the striker's impact; at ``rate`` m/s on a viscoelastic
    body) or ``impact`` (the striker's mass strikes at its velocity)."""

    kind: str = "impact"
    depths: tuple[float, ...] | None = None
    rate: float | None = None

    def __post_init__(self) -> None:
        if self.kind not in ("curve", "impact"):
            raise InputError(f"loading must be 'curve' or 'impact', got {self.kind!r}", "loading")
        if self.rate is not None:
            if self.kind != "curve":
                raise InputError("rate: applies to a contact curve only", "rate")
            object.__setattr__(self, "rate", float(entry("rate").check(self.rate, "contact")))
        if self.depths is not None:
            if self.kind != "curve":
                raise InputError("depths: applies to a contact curve only", "depths")
            object.__setattr__(self, "depths", _depths(self.depths))


def _depths(values: Any) -> tuple[float, ...]:
    """``values`` as depths in m, each checked by the vocabulary; a sequence (a list, a tuple
    or a 1-D array) is required, not a number or a string."""
    import numpy as np

    one_dimensional = isinstance(values, np.ndarray) and values.ndim == 1
    if not (isinstance(values, list | tuple) or one_dimensional):
        got = (
            f"an array of shape {values.shape}" if isinstance(values, np.ndarray) else repr(values)
        )
        raise InputError(
            f"depths must be a sequence of depths in m (a list, increasing), got {got}",
            "depths",
        )
    return tuple(float(d) for d in entry("depths").check(list(values), "contact"))


class Cell(NamedTuple):
    """A combination of the problem's parts: one cell of the support matrix."""

    model: str  # "linear" | "rubber"
    relaxing: bool
    geometry: str  # "half-space" | "layer bonded" | "layer lubricated"
    interface: str  # "frictionless" | "bonded" | "coulomb"
    loading: str  # "curve" | "massless" | "inertia"

    def __str__(self) -> str:
        """The parts in words: ``linear, Prony, layer bonded, coulomb, inertia``."""
        relaxing = "Prony" if self.relaxing else "elastic"
        return ", ".join((self.model, relaxing, self.geometry, self.interface, self.loading))


@dataclass(frozen=True)
class Unsupported:
    """A combination that is refused, and why.

    ``when`` selects the cells (a predicate on :class:`Cell`); ``parameter`` is the input the
    refusal names (the one that adds the unsupported part); ``reason`` says why, in words that
    fit the command line and Python alike.
    """

    when: Callable[[Cell], bool]
    parameter: str
    reason: str


def in_python_words(function: _Function) -> _Function:
    """The API's entry point ``function`` with its refusal or numerical failure, raised to a
    caller outside the package, in Python's words (:func:`worded`: ``density``, not the
    study key ``density2``): the one place that words them for the API. The package's own
    callers (the command line, study files, sweeps, the effect table) get the message as
    written, for their routes word it theirs."""

    @functools.wraps(function)
    def entry_point(*args: Any, **kwargs: Any) -> Any:
        inside = caller_stacklevel() > 2  # 2: this frame's caller is outside the package
        try:
            return function(*args, **kwargs)
        except (InputError, NumericalFailureError) as error:
            if not inside:
                error.args = (worded(str(error), "python"), *error.args[1:])
                if isinstance(error, InputError) and error.parameter in _KEYWORDS:
                    error.parameter = _KEYWORDS[error.parameter]
            raise

    return cast("_Function", entry_point)


LINEAR_BODY = ", or take model='linear'"
"""The end of a refusal that the linear body lifts, on the routes that choose the model (a
finite-strain study or sweep, always a rubber, words its own: :mod:`shtaerman.sweep.spec`)."""

SUPPORT: tuple[Unsupported, ...] = (
    Unsupported(
        lambda c: c.model == "rubber" and c.geometry == "layer lubricated",
        "base",
        "a layer at finite strain is bonded only (the lubricated base's exterior stiffness "
        "beyond the lateral edge is linear): take base='bonded' or model='linear'",
    ),
    Unsupported(
        lambda c: c.relaxing and c.loading == "curve" and c.model == "rubber",
        "prony",
        "a contact curve at finite strain is elastic (the finite-strain contact solver has no "
        "time): a viscoelastic rubber is pressed by an impact (give mass=... and velocity=... "
        f"to the dynamic impact, with density2=0 for the quasi-static one){LINEAR_BODY}",
    ),
    Unsupported(
        lambda c: c.relaxing and c.loading == "curve" and c.interface != "frictionless",
        "interface",
        "a viscoelastic contact curve is frictionless: the bonded and Coulomb indenters are "
        "solved on an elastic body only",
    ),
)
"""Every refused combination of the problem's parts, each with its reason: the one place that
decides what combines (everything not refused here runs)."""


def refusal(cell: Cell) -> Unsupported | None:
    """The first limit that refuses ``cell``, or None: it runs (for every striker profile:
    a power law, a sphere, a tabulated z(r))."""
    return next((limit for limit in SUPPORT if limit.when(cell)), None)


@dataclass(frozen=True)
class OptionLimit:
    """Numerical or output options that a set of combinations does not take; ``{model}`` in
    the reason is the body's model, ``{value}`` the option's value. ``allows`` (of the value
    and every option given) exempts what the combinations do take (default: nothing)."""

    when: Callable[[Cell], bool]
    options: tuple[str, ...]
    reason: str
    allows: Callable[[Any, Mapping[str, Any]], bool] = lambda value, given: False


OPTION_SUPPORT: tuple[OptionLimit, ...] = (
    OptionLimit(
        lambda c: c.model == "rubber" and c.loading != "curve",
        (
            "mesh_margin",
            "domain_factor",
            "growth",
            "layer_rate",
            *("axis_size", "layer_start", "layer_ramp", "tail", "layer_width", "spectral_radius"),
            "settings",  # a DynamicSettings: the linear body's (it was ignored)
        ),
        "not supported with model {model!r} in the impact (it takes mass=..., velocity=..., "
        "density2=..., time_steps=..., mesh_size=..., refine=..., estimate=..., thickness=..., "
        "base='bonded', interface=..., friction=..., prony=..., the rubber options and the "
        "outputs)",
    ),
    OptionLimit(
        lambda c: c.loading == "massless",
        ("layer_rate",),
        "applies to a body with mass only: a massless body (density2=0) radiates no waves for "
        "the absorbing layer to damp",
    ),
    OptionLimit(
        lambda c: c.relaxing and c.loading == "curve",
        ("accuracy",),
        "applies to the elastic contact curve only; on a viscoelastic body use refine=..., whose "
        "estimates come with every run",
    ),
    OptionLimit(
        lambda c: c.model == "rubber" and c.loading == "curve",
        ("accuracy",),
        "applies to the linear model only; for a finite-strain model use refine=..., whose "
        "estimates come with every run",
    ),
    OptionLimit(
        lambda c: c.model == "rubber",
        ("solver",),
        "the {model} model uses superlu only, got {value!r}",
        lambda value, given: value != "pardiso",
    ),
    OptionLimit(
        lambda c: c.loading == "curve",
        ("accuracy",),
        "needs the error estimates, which estimate=False switches off",
        lambda value, given: given.get("estimate", True) is not False,
    ),
    OptionLimit(
        lambda c: c.loading == "curve",
        ("refine",),
        "accuracy=... chooses the refinement itself (its ladder starts at refine=1), got "
        "refine={value:g}; give one of them",
        lambda value, given: value == 1.0 or given.get("accuracy") is None,
    ),
    OptionLimit(
        lambda c: c.loading == "curve",
        ("max_time",),
        "applies with accuracy=... only: it is the time budget of its refinement; "
        "give accuracy=... too",
        lambda value, given: given.get("accuracy") is not None,
    ),
)
"""Numerical and output options that some combinations do not take."""


@dataclass(frozen=True)
class Problem:
    """The whole case: striker, body, geometry, interface and loading, checked once.

    Build one with :meth:`impact` or :meth:`curve` (or from its parts); each part checks its
    own values on construction, and the problem checks that its parts combine
    (:data:`SUPPORT`). Every entry point builds one; the numerics (mesh, steps, ladder) and the
    outputs stay outside it.
    """

    striker: Striker
    body: Body
    geometry: Geometry = field(default_factory=Geometry)
    interface: Interface = field(default_factory=Interface)
    loading: Loading = field(default_factory=Loading)

    def __post_init__(self) -> None:
        for part in fields(self):
            expected = {"striker": Striker, "body": Body, "geometry": Geometry}.get(part.name)
            expected = expected or {"interface": Interface, "loading": Loading}[part.name]
            if not isinstance(getattr(self, part.name), expected):
                got = type(getattr(self, part.name)).__name__
                raise InputError(
                    f"{part.name} must be a shtaerman.{expected.__name__}, got {got}", part.name
                )
        check_bodies(self.striker.indenter, self.body.material, self.striker.material)
        if self.loading.depths is not None:
            for name in ("mass", "velocity"):
                if getattr(self.striker, name) is not None:
                    raise InputError(
                        f"{name}: sets the default depths (up to that impact's x_c); give "
                        "either depths=... or mass=... and velocity=...",
                        name,
                    )
            if math.isfinite(self.striker.material.youngs_modulus):  # the FE striker is rigid
                raise InputError(
                    "striker: its E1 enters only the impact whose x_c sets the default depths "
                    "(the FE striker is rigid); give either depths=... or striker=...",
                    "striker",
                )
        if self.loading.kind == "impact":
            for name in ("mass", "velocity"):
                if getattr(self.striker, name) is None:
                    raise InputError(f"{name}: an impact needs the striker's {name}", name)
        limit = refusal(self.cell)
        if limit is not None:
            raise InputError(f"{limit.parameter}: {limit.reason}", limit.parameter)
        self._check_rate()

    def _check_rate(self) -> None:
        """A contact curve on a viscoelastic body needs its pressing speed; no other does."""
        relaxing, rate = self.body.prony is not None, self.loading.rate
        if relaxing and self.loading.kind == "curve" and rate is None:
            raise InputError(
                "rate: a contact curve on a viscoelastic body (prony) is pressed at a speed: "
                f"give rate=... {entry('rate').range_text('contact')} m/s",
                "rate",
            )
        if rate is not None and not relaxing:
            viscoelastic = refusal(self.cell._replace(relaxing=True))
            remedy = "give prony=... too" if viscoelastic is None else viscoelastic.reason
            raise InputError(
                "rate: applies to a viscoelastic body only (an elastic curve does not depend "
                f"on it); {remedy}",
                "rate",
            )

    def alone(self, caller: str, loading: str, **beside: Any) -> Problem:
        """This problem as ``caller`` ("contact") takes it: a TypeError naming the parts
        ``beside`` it that are given (other than None and :data:`DEFAULTS`), an InputError
        unless its loading is ``loading`` ("curve" or "impact")."""
        given = [
            key
            for key, value in beside.items()
            if value is not None and not (isinstance(value, str) and value == DEFAULTS.get(key))
        ]
        if given:
            raise TypeError(f"{caller}(problem) takes numerics only; the problem holds {given}")
        if self.loading.kind != loading:
            does = {
                "curve": "presses a contact curve (Problem.curve)",
                "impact": "runs an impact (Problem.impact), not a curve",
            }[loading]
            raise InputError(f"problem: {caller}() {does}")
        return self

    @property
    def cell(self) -> Cell:
        """This problem's combination of parts."""
        loading = self.loading.kind
        if loading == "impact":
            loading = "massless" if self.body.material.density == 0 else "inertia"
        return Cell(
            "rubber" if self.body.finite else "linear",
            self.body.prony is not None,
            self.geometry.name,
            self.interface.name,
            loading,
        )

    @classmethod
    @in_python_words
    def impact(
        cls,
        indenter: Indenter,
        body: Material,
        *,
        mass: float,
        velocity: float,
        **parts: Any,
    ) -> Problem:
        """The impact of a striker of ``mass`` kg at ``velocity`` m/s on ``body``.

        ``parts`` are the keywords of :func:`parts` (model, rubber options, prony, thickness,
        base, interface, friction, striker material).
        """
        check_keywords(parts, "Problem.impact()", without=LOADING_KEYWORDS)
        return cls.from_keywords(indenter, body, mass=mass, velocity=velocity, **parts)

    @classmethod
    @in_python_words
    def curve(
        cls,
        indenter: Indenter,
        body: Material,
        *,
        depths: Sequence[float] | None = None,
        **parts: Any,
    ) -> Problem:
        """The contact curve of ``indenter`` pressed into ``body`` to ``depths`` (m; None:
        eight up to the x_c of the impact of ``mass`` at ``velocity`` by an elastic ``striker``,
        which given depths do not take: the FE striker is rigid)."""
        return cls.from_keywords(indenter, body, loading="curve", depths=depths, **parts)

    @classmethod
    @in_python_words
    def from_keywords(cls, indenter: Indenter, body: Material, **keywords: Any) -> Problem:
        """A problem from the API's flat keywords (None: not given), each checked."""
        return cls(**parts(indenter, body, **keywords))


LOADING_KEYWORDS = ("loading", "depths", "rate")
"""The keywords that make a contact curve: an impact (mass and velocity) takes none."""


def check_keywords(
    keywords: Mapping[str, Any], caller: str = "", extra: tuple = (), without: tuple = ()
) -> None:
    """TypeError naming the ``keywords`` that are neither a part's (:data:`KEYWORDS`, less
    ``without``) nor in ``extra``, as Python names an unexpected keyword (``caller``:
    "dynamic()")."""
    unknown = sorted(set(keywords) - ({*KEYWORDS, *extra} - set(without)))
    if unknown:
        said = f"{caller} got unexpected" if caller else "unexpected"
        raise TypeError(f"{said} keyword arguments {unknown}")


def parts(indenter: Indenter, body: Material, **keywords: Any) -> dict[str, Any]:
    """The parts of a problem (``striker``, ``body``, ``geometry``, ``interface``,
    ``loading``) from the API's flat keywords (None: not given), each checked on its own but
    not whether they combine: ``Problem(**parts(...))`` checks that (:data:`SUPPORT`)."""
    check_keywords(keywords)
    given = DEFAULTS | {key: value for key, value in keywords.items() if value is not None}
    return dict(
        striker=Striker(
            indenter, given.get("mass"), given.get("velocity"), given.get("striker", RIGID)
        ),
        body=Body(
            body,
            given["model"],
            *(given.get(name) for name in RUBBER_OPTIONS),
            prony=given.get("prony"),
        ),
        geometry=Geometry(given.get("thickness"), given.get("base")),
        interface=Interface(given["interface"], given.get("friction")),
        loading=Loading(given["loading"], given.get("depths"), given.get("rate")),
    )


KEYWORDS = (
    "mass",
    "velocity",
    "striker",
    "model",
    *RUBBER_OPTIONS,
    "prony",
    "thickness",
    "base",
    "interface",
    "friction",
    *LOADING_KEYWORDS,
)
"""The flat keywords of :meth:`Problem.from_keywords`."""
DEFAULTS = {"model": "linear", "interface": "frictionless", "loading": "impact"}
"""The flat keywords' defaults other than None (not given)."""


def check_options(problem: Problem, given: Mapping[str, Any] | Iterable[str]) -> None:
    """Refuse, in one line naming it, a numerical or output option (its key) that the problem's
    combination does not take (:data:`OPTION_SUPPORT`); ``given`` holds the options set (a
    mapping: with their values, which a limit's ``allows`` reads; else their names alone)."""
    cell, values = problem.cell, given if isinstance(given, Mapping) else dict.fromkeys(given)
    for limit in OPTION_SUPPORT:
        if not limit.when(cell):
            continue
        for name, value in values.items():
            if name in limit.options and not limit.allows(value, values):
                reason = limit.reason.format(model=problem.body.model, value=value)
                raise InputError(f"{name}: {reason}", name)


def support_table() -> list[tuple[Cell, str]]:
    """Every cell of the support matrix with ``runs`` or its refusal (``parameter: reason``,
    in the API's words as :class:`Problem` refuses it), for every striker profile."""
    from itertools import product

    rows = []
    for cell in product(
        ("linear", "rubber"),
        (False, True),
        ("half-space", "layer bonded", "layer lubricated"),
        ("frictionless", "bonded", "coulomb"),
        ("curve", "massless", "inertia"),
    ):
        cell = Cell(*cell)
        limit = refusal(cell)
        said = "runs" if limit is None else f"{limit.parameter}: {worded(limit.reason, 'python')}"
        rows.append((cell, said))
    return rows


def check_outputs(out: Any, *, force: Any, estimate: Any, figure_format: str) -> None:
    """Refuse, in one line naming it, an output keyword of the API that would be read wrong:
    ``force`` and ``estimate`` other than True or False (``force="False"`` counted as true),
    and a figure format other than png without ``out`` (nothing is drawn; the command line
    refuses it too)."""
    for name, value in (("force", force), ("estimate", estimate)):
        if not isinstance(value, bool):
            raise InputError(f"{name} must be True or False, got {value!r}", name)
    if out is None and figure_format != entry("figure_format").default:
        raise InputError(
            "figure_format: applies with out=... only (the format of the figures written "
            "there); give out=... too",
            "figure_format",
        )


_NAMES = frozenset(item.name for item in VOCABULARY)
_KEYWORDS = {item.name: item.keyword for item in VOCABULARY if item.keyword}
"""Input -> the API's name of it, where that differs (density2: ``Material(density=...)``)."""
_NAMED = re.compile(rf"(?<![\w-])({'|'.join(_KEYWORDS)})(?!\w)")
_REFERENCE = re.compile(r"(?<![^\s(])([A-Za-z]\w*)=('[^']*'|\.\.\.|[\w+-]+(?:\.\w+)*)")
_LEADING = re.compile(r"(\w+(?:, \w+)*)(?=: )")
_FIELDS = {
    "shape_coefficient": "PowerLawIndenter(shape_coefficient={})",
    "exponent": "PowerLawIndenter(exponent={})",
    "sphere_radius": "SphereIndenter(radius={})",
}
"""Input -> the API's striker field that holds it (no keyword of sh.dynamic and the like)."""
_COMMAND = re.compile(r"\bshtaerman (impact|contact|dynamic)\b")
"""A command a message names, which the API calls sh.impact, sh.contact, sh.dynamic."""


def _fields_at_head(message: str) -> str:
    """``message`` whose head names a striker's field in the API's words:
    ``sphere_radius, mass: ...`` is ``SphereIndenter(radius=...), mass: ...``."""
    leading = _LEADING.match(message)
    if leading is None:
        return message
    names = leading[1].split(", ")
    spelled = [_FIELDS[name].format("...") if name in _FIELDS else name for name in names]
    return ", ".join(spelled) + message[leading.end() :]


def worded(
    message: str, route: str, keys: Mapping[str, str] | None = None, parameter: str | None = None
) -> str:
    """``message`` in the words of the ``route`` its input came by: the one place that spells
    an input per route. A refusal is written in Python's: it begins with the keyword at fault
    (``friction: ...``) and names another input ``name=value`` or, alone, ``name=...``.
    ``"cli"`` spells options (``--friction: ... --interface bonded``, ``--no-estimate``),
    ``"file"`` the keys of a study or sweep file (``[impact] interface = "bonded"``; ``keys``
    maps an input to its ``table.key``), ``"python"`` keeps it but for the inputs the API
    names otherwise (``density2`` is the body's ``density``, ``shape_coefficient=...`` and a
    head ``shape_coefficient:`` ``PowerLawIndenter(shape_coefficient=...)``) and the commands
    (``shtaerman impact`` is ``sh.impact``). On the command line the message's head becomes
    options only when it names the refusal's declared ``parameter``, a keyword of the
    vocabulary (``friction: ...``, ``mass, velocity: ...``, ``solver 'pardiso' ...``): a head
    that names none (a numerical failure's step, ``fit: ...``, ``level 2: ...``) is left as
    written."""
    if route == "python":
        message = _REFERENCE.sub(
            lambda match: _FIELDS[match[1]].format(match[2]) if match[1] in _FIELDS else match[0],
            _COMMAND.sub(r"sh.\1", message),
        )
        return _NAMED.sub(lambda match: _KEYWORDS[match[1]], _fields_at_head(message))

    def spoken(match: re.Match) -> str:
        name, value = match[1], match[2]
        if name not in _NAMES:
            return match[0]
        if route == "cli":
            return _option(name, value)
        table, _, key = (keys or {}).get(name, name).rpartition(".")
        place = f"[{table}] {key}" if table else key
        value = {"True": "true", "False": "false"}.get(value, value).replace("'", '"')
        return place if value == "..." else f"{place} = {value}"

    message = _REFERENCE.sub(spoken, message)
    if route != "cli" or parameter not in _NAMES:
        return message
    leading = _LEADING.match(message)
    names = leading[1].split(", ") if leading else []
    if parameter in names and all(name in _NAMES for name in names):
        options = ", ".join(entry(name).cli_option for name in names)
        return options + message[leading.end() :]
    if re.match(rf"{parameter}\b(?![-=:,])", message):
        return entry(parameter).cli_option + message[len(parameter) :]
    return message


def _option(name: str, value: str) -> str:
    """Input ``name`` set to ``value`` (a Python literal, or ``...``) as an option."""
    item = entry(name)
    option = item.cli_option
    if item.type in ("bool", "flag"):  # --no-estimate is estimate=False, --json json=True
        on = value == ("False" if option.startswith("--no-") else "True")
        return option if on or value == "..." else f"without {option}"
    return option if value == "..." else f"{option} {value.strip(chr(39))}"
