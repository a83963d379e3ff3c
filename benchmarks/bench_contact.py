"""Benchmarks of the FEM contact test: speed, convergence, truncation, a parameter sweep.

Run ``python benchmarks/bench_contact.py`` (about 2.5 minutes on 2 idle cores) or with ``--quick``
(about 20 s: the default mesh only, coarse levels, fewer cases). Prints tables; nothing is
asserted (wall-clock times depend on the machine and on its load, printed beside them).

(a) SPEED. The issue's requirement: the whole contact curve of 8 depths must cost at most 3x one
    sparse factorization of the full stiffness matrix with the same solver. Per mesh: SuperLU
    factorization of the reduced stiffness with its own best ordering (``factorize(K,
    "superlu")``, MMD_AT_PLUS_A), the tail-ordered factorization that yields the compliance
    (``TailFactorization``), the contact phase (compliance + 8 LCPs), their ratio; the old
    approach (compliance by one multi-RHS solve of unit loads) and MKL PARDISO for contrast.
(b) ACCURACY / CONVERGENCE. The paper's case and Hertz on meshes refining the whole size field
    (:func:`shtaerman.fem.convergence.convergence_study`), errors and observed orders; (b') the
    bias of the far-field grading (~ growth^3) at a fixed surface mesh.
(c) TRUNCATION. Force and beta errors versus the domain radius at a fixed fine surface mesh.
(d) SWEEP. Shape coefficients, exponents and Poisson ratios not used above, at the default mesh,
    against the issue's acceptance limits.
(e) EDGE ALIGNMENT. The force error over many depths around the shallowest default one
    (a = a_c/3), per mesh: the nodal sum at each depth (a polygon in d, oscillating with the
    contact edge), the power-law interpolant between vertex-aligned contacts (the reported
    force, :func:`shtaerman.fem.contact.linear.aligned_force`) and, for contrast, between contacts
    aligned on P2 edge midpoints.
"""

from __future__ import annotations

import argparse
import dataclasses
import math
import os
import time
from collections.abc import Callable, Sequence

import numpy as np

from shtaerman.fem.contact.linear import (
    aligned_force,
    contact_step,
    factorize_stiffness,
    surface_compliance,
)
from shtaerman.fem.elasticity import ElasticSystem, assemble
from shtaerman.fem.mesh import MeshSettings
from shtaerman.fem.solver import available_backends, factorize
from shtaerman.study.contact.convergence import (
    convergence_study,
    fitted_order,
    observed_orders,
    refined_settings,
)
from shtaerman.study.contact.indentation import default_depths, run_indentation
from shtaerman.theory.contact import PowerLawContact
from shtaerman.theory.indenter import PowerLawIndenter
from shtaerman.theory.materials import Material

PAPER = (PowerLawIndenter(5.0, 1.5), Material(7.5e6, 0.5))
HERTZ = (PowerLawIndenter.sphere(0.1), Material(7.5e6, 0.5))  # A = 5 m^-1, n = 2
DEFAULT = MeshSettings()
REPEATS = 3
SAMPLE_LOADS = 128
LIMITS = {
    "force": 1e-3,
    "beta": 1e-3,
    "exponent": 1e-3,
    "contact_radius": 1e-2,
    "central_pressure": 1e-2,
}
"""The issue's acceptance limits on the largest relative errors."""
ERROR_KEYS = ("force", "beta", "exponent", "contact_radius", "central_pressure", "pressure_profile")
SHORT = {
    "force": "force",
    "beta": "beta",
    "exponent": "expon",
    "contact_radius": "radius",
    "central_pressure": "p(0)",
    "pressure_profile": "p(r) L2",
}


def _load() -> str:
    one, five, _ = os.getloadavg()
    return f"{os.cpu_count()} cores, load average {one:.1f} (1 min) {five:.1f} (5 min)"


def _timed(function: Callable, *args, **kwargs) -> tuple[object, float]:
    start = time.perf_counter()
    result = function(*args, **kwargs)
    return result, time.perf_counter() - start


# --- (a) speed -------------------------------------------------------------------------------


@dataclasses.dataclass
class _Problem:
    """An assembled indentation problem, as :func:`run_indentation` builds it."""

    indenter: PowerLawIndenter
    system: ElasticSystem
    free: np.ndarray
    refined: float
    depths: np.ndarray


def _problem(indenter: PowerLawIndenter, half_space: Material, mesh: MeshSettings) -> _Problem:
    depths = default_depths(indenter, half_space)
    a_g = (depths[-1] / indenter.shape_coefficient) ** (1.0 / indenter.exponent)
    refined = mesh.margin * a_g
    skfem_mesh = mesh.build(refined)
    system = assemble(skfem_mesh, half_space.youngs_modulus, half_space.poisson_ratio)
    return _Problem(indenter, system, system.free_dofs(), refined, depths)


def _contact_curve(problem: _Problem) -> dict:
    """Time the path of :func:`solve_contact`: tail factorization, compliance, 8 LCPs (s)."""
    start = time.perf_counter()
    factorization = factorize_stiffness(problem.system, problem.free, problem.refined)
    factorized = time.perf_counter()
    compliance = surface_compliance(problem.system, factorization, problem.free, problem.refined)
    complied = time.perf_counter()
    for depth in problem.depths:
        contact_step(compliance, problem.indenter.profile, float(depth))
    done = time.perf_counter()
    return {
        "factorization": factorized - start,
        "compliance": complied - factorized,
        "lcp": done - complied,
        "candidates": compliance.r.size,
    }


def _unit_load_seconds(factorization, problem: _Problem, columns: int | None) -> float:
    """Seconds of the old compliance: one multi-RHS solve of a unit load per candidate.

    With ``columns``, only that many unit loads are solved and the time is scaled to all the
    candidates (a triangular solve costs the same per right-hand side).
    """
    system = problem.system
    dofs = system.surface_dofs[system.surface_r <= problem.refined * (1 + 1e-12)]
    position = np.searchsorted(problem.free, dofs)
    count = position.size if columns is None else min(columns, position.size)
    loads = np.zeros((problem.free.size, count))
    loads[position[:count], np.arange(count)] = 1.0
    _, seconds = _timed(factorization.solve, loads)
    return seconds * position.size / count


def speed_row(label: str, mesh: MeshSettings, full: bool) -> str:
    """One line of table (a) for the paper's problem on ``mesh``.

    ``full``: the contrast columns (old approach, PARDISO) best of ``REPEATS`` with every unit
    load solved; else one run, unit-load solves extrapolated from ``SAMPLE_LOADS`` columns.
    """
    problem = _problem(*PAPER, mesh)
    matrix = problem.system.reduced_matrix(problem.free)
    plain_runs = [_timed(factorize, matrix, "superlu") for _ in range(REPEATS)]
    plain = min(seconds for _, seconds in plain_runs)
    superlu = plain_runs[-1][0]
    tail = min(
        (_contact_curve(problem) for _ in range(REPEATS)),
        key=lambda run: run["factorization"] + run["compliance"] + run["lcp"],
    )
    repeats, columns = (REPEATS, None) if full else (1, SAMPLE_LOADS)
    mark = " " if full else "~"
    old = min(_unit_load_seconds(superlu, problem, columns) for _ in range(repeats))
    ratio = (tail["factorization"] + tail["compliance"] + tail["lcp"]) / plain
    old_ratio = (plain + old + tail["lcp"]) / plain
    cells = [
        f"{label:>11}",
        f"{matrix.shape[0]:7d}",
        f"{tail['candidates']:5d}",
        f"{superlu.fill / 1e6:6.1f}",
        f"{plain:7.3f}",
        f"{tail['factorization']:7.3f}",
        f"{tail['compliance']:6.3f}",
        f"{tail['lcp']:6.3f}",
        f"{ratio:6.2f}",
        f"|{mark}{old:7.2f}",
        f"{old_ratio:6.1f}",
    ]
    del superlu, plain_runs
    if "pardiso" in available_backends():
        runs = [_timed(factorize, matrix, "pardiso") for _ in range(repeats)]
        pardiso = min(seconds for _, seconds in runs)
        solves = min(_unit_load_seconds(runs[-1][0], problem, columns) for _ in range(repeats))
        pardiso_ratio = (pardiso + solves + tail["lcp"]) / pardiso
        cells += [f"|{pardiso:7.3f}", f"{mark}{solves:6.2f}", f"{pardiso_ratio:6.1f}"]
        del runs
    return " ".join(cells)


def speed_table(quick: bool) -> None:
    """(a) Cost of the contact curve (8 depths) over one plain sparse factorization."""
    print("\n(a) SPEED: contact curve of 8 depths (paper: A = 5, n = 1.5, nu = 0.5) vs one")
    print(
        "    sparse factorization of the full stiffness with the same solver. Seconds, best of "
        f"{REPEATS}."
    )
    print(
        "    ratio = (tail LU + compliance + 8 LCPs) / SuperLU;  old = (SuperLU + unit-load "
        "solves + 8 LCPs) / SuperLU;"
    )
    print(
        "    PARDISO ratio = (PARDISO + its unit-load solves + 8 LCPs) / PARDISO. ~: one run, "
        f"{SAMPLE_LOADS} unit loads solved, scaled to all candidates."
    )
    print(
        "    The LCPs run with one BLAS thread (threadpoolctl); the compliance inversion uses"
        " all threads and is sensitive to a busy machine: " + _load()
    )
    header = [
        f"{'mesh':>11}",
        f"{'dofs':>7}",
        f"{'cand':>5}",
        f"{'LU 1e6':>6}",
        f"{'SuperLU':>7}",
        f"{'tail LU':>7}",
        f"{'compl':>6}",
        f"{'8 LCPs':>6}",
        f"{'ratio':>6}",
        f"|{'old sol':>8}",
        f"{'old':>6}",
    ]
    if "pardiso" in available_backends():
        header += [f"|{'PARDISO':>7}", f"{'solves':>7}", f"{'ratio':>6}"]
    print(" ".join(header))
    rows = [("default", DEFAULT, not quick)]
    if not quick:
        rows += [
            ("x 1/sqrt2", refined_settings(DEFAULT, DEFAULT.size / math.sqrt(2.0)), False),
            ("x 1/2", refined_settings(DEFAULT, DEFAULT.size / 2.0), False),
            ("size/4", dataclasses.replace(DEFAULT, size=DEFAULT.size / 4.0), False),
        ]
    for label, mesh, full in rows:
        print(speed_row(label, mesh, full), flush=True)
    print(
        "    mesh 'x t': the whole size field scaled by t (size, axis size, both growth rates);"
        " 'size/4': surface size 1/600 at the default growth (many candidates per dof)."
    )
    print(
        "    LU 1e6: nonzeros of the plain SuperLU factors in millions; cand: contact candidates"
        " (size of the dense compliance)."
    )


# --- (b) convergence -------------------------------------------------------------------------


def _format_size(size: float) -> str:
    return f"1/{1.0 / size:.0f}"


def convergence_table(
    name: str, case: tuple[PowerLawIndenter, Material], sizes: Sequence[float]
) -> list[dict]:
    """(b) Errors of one case on meshes refining the whole size field, and observed orders."""
    indenter, half_space = case
    base = dataclasses.replace(DEFAULT, domain=1e7)
    print(
        f"\n(b) {name}: A = {indenter.shape_coefficient:g}, n = {indenter.exponent:g}, "
        f"E2 = {half_space.youngs_modulus:g} Pa, nu = {half_space.poisson_ratio:g}, default "
        "depths (contact radii a_c/3 .. a_c);"
    )
    print(
        "    whole size field scaled with size (growth, axis size and axis growth prop. to size),"
        " domain 1e7 refined radii (truncation floor ~1.2e-7)"
    )
    study = convergence_study(indenter, half_space, sizes, base=base).levels
    header = (
        f"{'size':>7} {'growth':>6} {'dofs':>7} | "
        + " ".join(f"{SHORT[key]:>8}" for key in ERROR_KEYS)
        + f" | {'radius/size':>11} {'seconds':>7}"
    )
    print(header)
    for level in study:
        errors = level["errors"]
        print(
            f"{_format_size(level['size']):>7} {level['settings']['growth']:6.3f} "
            f"{level['dofs']:7d} | "
            + " ".join(f"{errors[key]:8.1e}" for key in ERROR_KEYS)
            + f" | {errors['contact_radius'] / level['size']:11.2f}"
            f" {level['timings']['total']:7.2f}"
        )
    for label, measure in (("order (size)", "size"), ("fit, size", "size"), ("fit, dofs", "dofs")):
        if label.startswith("order"):
            cells = [
                "/".join(f"{p:.1f}" for p in observed_orders(study, key, measure=measure))
                for key in ERROR_KEYS
            ]
        else:
            cells = [f"{fitted_order(study, key, measure=measure):.2f}" for key in ERROR_KEYS]
        print(f"{label:>22} | " + " ".join(f"{cell:>8}" for cell in cells))
    finest = study[-1]["errors"]
    verdict = "yes" if max(finest["force"], finest["beta"]) <= 1e-4 else "NO"
    print(
        f"    finest ({study[-1]['dofs']} dofs): force {finest['force']:.1e}, beta "
        f"{finest['beta']:.1e} (<= 1e-4: {verdict}), exponent {finest['exponent']:.1e}, "
        f"radius {finest['contact_radius']:.1e}, p(0) {finest['central_pressure']:.1e}"
    )
    return study


def growth_table() -> None:
    """(b') The growth-rate bias at a fixed surface size: beta error versus growth."""
    indenter, half_space = PAPER
    growths = (0.25, 0.177, 0.125)
    print(
        "\n(b') paper case, surface size a/300 (size 1/300), domain 1e7: the smooth bias of the"
        " far-field grading, error ~ growth^3"
    )
    print(f"{'growth':>7} {'dofs':>7} | {'force':>8} {'beta':>8} {'p(0)':>8} | beta/growth^3")
    for growth in growths:
        mesh = dataclasses.replace(DEFAULT, size=1 / 300, growth=growth, domain=1e7)
        result = run_indentation(indenter, half_space, mesh=mesh)
        errors = result.errors()
        print(
            f"{growth:7.4f} {result.mesh_stats['dofs']:7d} | {errors['force']:8.1e} "
            f"{errors['beta']:8.1e} {errors['central_pressure']:8.1e} | "
            f"{errors['beta'] / growth**3:8.2e}",
            flush=True,
        )


# --- (c) truncation --------------------------------------------------------------------------


def truncation_table(quick: bool) -> None:
    """(c) Force and beta errors versus the domain radius, fine fixed surface mesh."""
    indenter, half_space = PAPER
    size = DEFAULT.size if quick else DEFAULT.size / math.sqrt(2.0)
    surface = refined_settings(DEFAULT, size)
    domains = (1e2, 1e3, 1e4, 1e5) if quick else (1e2, 1e3, 1e4, 1e5, 1e6)
    reference_domain = 1e7  # gmsh slows down beyond: 1.8 s at 1e7, 12 s at 3e7, 120 s at 1e8
    print(
        f"\n(c) TRUNCATION: paper case, surface mesh size {_format_size(size)}, growth "
        f"{surface.growth:.3f}; 'vs ref': against domain {reference_domain:.0e} with the same "
        "mesh settings (isolates the truncation)"
    )
    print(
        "    P: force at the largest depth; c = (P vs ref) / (a/R), a its contact radius, R the "
        "domain radius (c constant: error ~ 1/domain)"
    )
    reference = run_indentation(
        indenter, half_space, mesh=dataclasses.replace(surface, domain=reference_domain)
    )
    p_ref, beta_ref = reference.steps[-1].force, reference.fit.beta_fixed_exponent
    print(
        f"{'domain':>7} {'dofs':>7} {'mesh s':>6} | {'force err':>9} {'beta err':>9} | "
        f"{'P vs ref':>9} {'c':>5} | {'beta vs ref':>11} {'x domain':>8}"
    )
    for domain in domains:
        result = run_indentation(
            indenter, half_space, mesh=dataclasses.replace(surface, domain=domain)
        )
        errors = result.errors()
        force = result.steps[-1].force / p_ref - 1.0
        a_over_r = result.steps[-1].contact_radius / result.mesh_stats["domain_radius"]
        beta = result.fit.beta_fixed_exponent / beta_ref - 1.0
        default = " <- default domain" if domain == DEFAULT.domain else ""
        print(
            f"{domain:7.0e} {result.mesh_stats['dofs']:7d} {result.timings['mesh']:6.2f} | "
            f"{errors['force']:9.2e} "
            f"{errors['beta']:9.2e} | {force:+9.2e} {force / a_over_r:5.2f} | {beta:+11.2e} "
            f"{beta * domain:8.2f}{default}",
            flush=True,
        )
    errors = reference.errors()
    print(
        f"{reference_domain:7.0e} {reference.mesh_stats['dofs']:7d} "
        f"{reference.timings['mesh']:6.2f} | {errors['force']:9.2e} {errors['beta']:9.2e} | "
        "(reference: discretisation error, truncation ~1e-7)"
    )


# --- (d) sweep -------------------------------------------------------------------------------


def _custom_depths(
    indenter: PowerLawIndenter, radii: tuple[float, float], count: int, spacing: str
) -> np.ndarray:
    """Depths (m) whose exact contact radii run from radii[0] to radii[1] (m)."""
    law = PowerLawContact(indenter, 1.0)  # the depth-radius relation does not involve E*
    low, high = law.depth(np.array(radii))
    if spacing == "geometric":
        return np.geomspace(low, high, count)
    return np.linspace(low, high, count)


SWEEP = [
    # (A m^(1-n), n, E2 Pa, nu, custom depths: (contact radii m, count, spacing) or None)
    (0.5, 1.5, 7.5e6, 0.5, None),
    (20.0, 1.5, 7.5e6, 0.5, None),
    (5.0, 1.2, 7.5e6, 0.5, None),
    (5.0, 1.35, 7.5e6, 0.25, None),
    (5.0, 1.8, 7.5e6, 0.0, None),
    (5.0, 2.0, 7.5e6, 0.4999, None),
    (0.5, 1.2, 7.5e6, 0.0, ((1e-3, 5e-3), 6, "geometric")),
    (20.0, 1.35, 7.5e6, 0.4999, ((5e-4, 2e-3), 10, "linear")),
    (0.5, 2.0, 7.5e6, 0.25, ((2e-3, 6e-3), 3, "geometric")),
    (20.0, 1.8, 2.1e11, 0.5, ((2e-4, 1e-3), 5, "geometric")),
]
QUICK_SWEEP = [SWEEP[0], SWEEP[2], SWEEP[6], SWEEP[7]]


def sweep_table(quick: bool) -> None:
    """(d) Worst errors at the default mesh over parameters not used above."""
    limits = ", ".join(f"{SHORT[key]} {value:g}" for key, value in LIMITS.items())
    print(f"\n(d) SWEEP at the default mesh; acceptance limits: {limits}")
    print(
        f"{'A':>5} {'n':>5} {'E2':>7} {'nu':>6} {'depths':>26} {'dofs':>6} | "
        + " ".join(f"{SHORT[key]:>8}" for key in LIMITS)
        + f" | {'worst/limit':>11} verdict"
    )
    failures = 0
    for shape, exponent, modulus, nu, custom in QUICK_SWEEP if quick else SWEEP:
        indenter, half_space = PowerLawIndenter(shape, exponent), Material(modulus, nu)
        if custom is None:
            depths, label = None, "default (a_c/3 .. a_c, 8)"
        else:
            radii, count, spacing = custom
            depths = _custom_depths(indenter, radii, count, spacing)
            label = f"a {radii[0] * 1e3:g}-{radii[1] * 1e3:g} mm, {count} {spacing[:3]}"
        result = run_indentation(indenter, half_space, depths)
        errors = result.errors()
        worst = max(errors[key] / limit for key, limit in LIMITS.items())
        verdict = "PASS" if worst <= 1.0 else "FAIL"
        failures += verdict == "FAIL"
        print(
            f"{shape:5g} {exponent:5g} {modulus:7.1e} {nu:6g} {label:>26} "
            f"{result.mesh_stats['dofs']:6d} | "
            + " ".join(f"{errors[key]:8.1e}" for key in LIMITS)
            + f" | {worst:11.2f} {verdict}",
            flush=True,
        )
    print(f"    {failures} failure(s)")


# --- (e) edge alignment ----------------------------------------------------------------------


def _alignment_errors(mesh: MeshSettings, samples: int) -> dict[str, np.ndarray]:
    """Relative force errors of the three recoveries at ``samples`` depths (one span 1.3).

    The deepest default depth is solved too, so the mesh is the default depths' mesh.
    """
    indenter, half_space = PAPER
    default = default_depths(indenter, half_space)
    depths = np.geomspace(default[0], 1.3 * default[0], samples)
    result = run_indentation(indenter, half_space, np.append(depths, default[-1]), mesh)
    steps = result.steps[:-1]
    compliance = result.curve.compliance
    midside = dataclasses.replace(compliance, vertex=~compliance.vertex)
    heights = indenter.profile(compliance.r)
    exact = result.exact.force(depths)
    forces = {
        "nodal sum": [step.discrete_force for step in steps],
        "vertex-aligned": [step.force for step in steps],
        "midside-aligned": [
            aligned_force(midside, heights, step.nodal_forces, step.depth) for step in steps
        ],
    }
    return {key: np.asarray(value) / exact - 1.0 for key, value in forces.items()}


def alignment_table(quick: bool) -> None:
    """(e) Force errors of the nodal sum and of the aligned interpolants around a_c/3."""
    samples = 12 if quick else 40
    refines = (1.0,) if quick else (1.0, math.sqrt(2.0), 2.0, 2.0 * math.sqrt(2.0))
    print(
        f"\n(e) EDGE ALIGNMENT: paper case, domain 1e6, {samples} depths from the shallowest "
        "default one (a = a_c/3) to 1.3x it; relative force error, min .. max over the depths"
    )
    print(f"{'refine':>6} | {'nodal sum':>21} | {'vertex-aligned':>21} | {'midside-aligned':>21}")
    for refine in refines:
        mesh = dataclasses.replace(DEFAULT, domain=1e6).refined(refine)
        errors = _alignment_errors(mesh, samples)
        cells = " | ".join(f"{e.min():+.2e} .. {e.max():+.2e}" for e in errors.values())
        print(f"{refine:6.3g} | {cells}", flush=True)


def _sizes(quick: bool) -> tuple[float, ...]:
    """Levels of (b): smallest size / refined radius, refined by sqrt(2) per level."""
    if quick:
        return (1 / 75, 1 / 106.066, 1 / 150)
    return (1 / 106.066, 1 / 150, 1 / 212.132, 1 / 300, 1 / 424.264)


def main(argv: list[str] | None = None) -> None:
    """Print the benchmark tables."""
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument(
        "--quick", action="store_true", help="default mesh and coarse levels only (< 1 min)"
    )
    args = parser.parse_args(argv)
    start = time.perf_counter()
    sections = [
        lambda: speed_table(args.quick),
        lambda: convergence_table("paper case", PAPER, _sizes(args.quick)),
        lambda: convergence_table("Hertz", HERTZ, _sizes(args.quick)),
        lambda: truncation_table(args.quick),
        lambda: sweep_table(args.quick),
        lambda: alignment_table(args.quick),
    ]
    if not args.quick:
        sections.insert(3, growth_table)
    for section in sections:
        _, seconds = _timed(section)
        print(f"    [{seconds:.0f} s]", flush=True)
    print(f"\ntotal {time.perf_counter() - start:.0f} s; " + _load())


if __name__ == "__main__":
    main()
