"""Hunter (1957): the fraction of a sphere's impact energy radiated as elastic waves,
about 1.04 (V / c0)^(3/5), and its exponent 3 / (2 n + 1) for z = A r^n (docs/validation.md).

Each value is the dynamic FE of ``shtaerman dynamic`` (a rigid striker of the sphere's mass on
a steel half-space), fraction = 1 - e^2 over a decade of velocity.
"""

from __future__ import annotations

import math

import numpy as np

from ..api.fem_dynamic import dynamic
from ..theory.indenter import PowerLawIndenter
from ..theory.materials import Material
from .row import Row

__all__ = ["RIGID_TO_ELASTIC", "hunter_rows", "radiated_fractions"]

HUNTER = "Hunter 1957, J. Mech. Phys. Solids 5, 162-171; Johnson 1985, Contact Mechanics, 11.4"
RADIUS = 0.01
"""Sphere radius R, m."""
STEEL = Material(2.0e11, 0.3, density=7800.0)
"""The half-space and, for Hunter's constant, the sphere (one material)."""
VELOCITIES = (0.3, 1.0, 3.0)
"""Impact velocities, m/s: a decade."""
RIGID_TO_ELASTIC = 2.0 ** (6.0 / 5.0)
"""Fraction of a rigid sphere over that of an elastic one of the half-space's material: the
radiated fraction scales as E*^(6/5) at a given mass and velocity, and a rigid striker doubles
E* (docs/validation.md, eq. H4)."""


def radiated_fractions(
    exponent: float, velocities: tuple[float, ...] = VELOCITIES, refine: float = 1.0
) -> tuple[np.ndarray, np.ndarray]:
    """1 - e^2 of the dynamic FE and the first-order estimate at each velocity (dimensionless).

    The striker z = A r^n with A = 1 / (2 R) R^(2 - n) (the sphere's paraboloid at n = 2) and
    the mass of a steel sphere of radius R.
    """
    mass = 4.0 / 3.0 * math.pi * RADIUS**3 * STEEL.density
    indenter = PowerLawIndenter(0.5 * RADIUS ** (1.0 - exponent), exponent)
    fe, estimate = [], []
    for velocity in velocities:
        result = dynamic(
            indenter, STEEL, mass=mass, velocity=velocity, estimate=False, refine=refine
        ).to_dict()
        fe.append(1.0 - result["dynamic"]["restitution"] ** 2)
        estimate.append(result["radiation_estimate"]["energy_fraction"])
    return np.array(fe), np.array(estimate)


def _slope(velocities: tuple[float, ...], fractions: np.ndarray) -> tuple[float, float]:
    """Least-squares slope of log(fraction) against log(v), and its standard error."""
    x, y = np.log(velocities), np.log(fractions)
    slope, intercept = np.polyfit(x, y, 1)
    residual = y - (slope * x + intercept)
    spread = float(np.sqrt(np.sum(residual**2) / max(len(x) - 2, 1) / np.sum((x - x.mean()) ** 2)))
    return float(slope), spread


def hunter_rows(exponents: tuple[float, ...] = (2.0, 1.5), refine: float = 1.0) -> list[Row]:
    """The exponent rows (each n) and the constant row (n = 2)."""
    rows, constant = [], []
    for n in exponents:
        fe, estimate = radiated_fractions(n, refine=refine)
        slope, bar = _slope(VELOCITIES, fe)
        rows.append(
            Row(
                case="elastic waves, exponent",
                source=HUNTER if n == 2.0 else HUNTER + " (the argument at n = 3/2)",
                inputs=f"n = {n:g}, v = 0.3 .. 3 m/s, R = 10 mm, steel (nu 0.3)",
                quantity="d log(1 - e^2) / d log v",
                published=3.0 / (2.0 * n + 1.0),
                value=slope,
                error_bar=bar,
                tolerance=0.02 + 3.0 * bar,
                why="the point-force argument is exact to first order in a / (c t_c) ~ v / c; "
                "0.02 allows the second order over a decade (v / c < 1e-3; 0.007 at n = 2)",
                command=_command(n),
            )
        )
        if n == 2.0:
            constant.append(_constant_row(fe, estimate))
    return rows + constant


def _constant_row(fe: np.ndarray, estimate: np.ndarray) -> Row:
    """Hunter's constant from the FE at the decade's middle velocity, rigid -> elastic."""
    c0 = math.sqrt(STEEL.youngs_modulus / STEEL.density)
    scale = (VELOCITIES[1] / c0) ** 0.6 * RIGID_TO_ELASTIC
    return Row(
        case="elastic waves, constant",
        source=HUNTER,
        inputs="n = 2, v = 1 m/s, R = 10 mm, steel (nu 0.3), rigid striker scaled by 2^(6/5)",
        quantity="C in 1 - e^2 = C (V / c0)^(3/5)",
        published=1.04,
        value=float(fe[1] / scale),
        error_bar=float(abs(fe[1] - estimate[1]) / scale),
        tolerance=0.104 + 2.0 * float(abs(fe[1] - estimate[1]) / scale),
        why="Hunter's half-sine pulse is good to about 10 % (Johnson 11.4); error bar: FE against "
        "the first-order estimate (theory/radiation.py)",
        command=_command(2.0),
    )


def _command(exponent: float) -> str:
    """The reader's command of a velocity (repeat for 0.3, 1, 3 m/s)."""
    coefficient = 0.5 * RADIUS ** (1.0 - exponent)
    return (
        f"shtaerman dynamic --shape-coefficient {coefficient:.6g} --exponent {exponent:g} "
        "--E2 2e11 --nu2 0.3 --density2 7800 --mass 0.0326726 --velocity V --json"
    )
