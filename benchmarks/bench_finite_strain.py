"""Finite-strain (neo-Hookean) contact: the acceptance figures of issue 9, printed.

Run ``PYTHONPATH=src python benchmarks/bench_finite_strain.py`` (about 10 minutes on 2 loaded
cores) or with ``--quick`` (the paper's curve and the small-strain limit only). Nothing is
asserted; wall-clock times depend on the machine and its load (printed beside them).

(a) SMALL-STRAIN LIMIT. Blunt indenters (n = 1.5 and 2) at x/a = 1e-3 and 2e-3 (contact radius
    1 mm), nu2 = 0.3 and 0.5: finite-strain force against Shtaerman, and against the linear FEM
    on the same mesh (which isolates the finite-strain effect from the discretization error).
(b) THE PAPER'S CURVE. A = 5 m^-1/2, n = 1.5, E2 = 7.5 MPa, nu2 = 0.5, rigid striker, 12 depths
    up to 1.01 x_c at the default mesh: time, P / (beta x^(5/3)), a / a_lin, p(0)/p_avg; the
    finite-strain impact (0.7 kg at 3 m/s) from M x'' = -P(x) on the tabulated curve.
(c) CONSERVATION. 16 equal depth steps to x_c: Simpson's Int P dx against the stored energy.
(d) MESH CONVERGENCE of P at x/a = 0.5 and 0.9 (x/a of the linear solution), smallest size
    refined by 2 each level: differences, observed orders, Richardson estimate, and the error
    of the default mesh.
(e) HERTZ (n = 2, A = 1/(2R)) at finite strain against published neo-Hookean sphere results.
(f) THE STUDY'S ERROR ESTIMATES (fem/finite_strain.toml, nu2 = 0.5 and 0.3): CPU time of the
    3-mesh ladder against one run on today's default mesh (FINITE_MESH, refine 1); every
    estimate of the finest level against its "true" error, the difference from a reference run
    on the finest mesh refined by 2 (the reference refined by sqrt 2 beside, to show how far
    the reference itself is converged); effectivity = estimate / true (``--sections f``, about
    5 minutes of CPU time per study).
(g) COST OF A NEWTON ITERATION on the paper's curve of (b): CPU time per iteration of the
    assembly (state, residual and tangent) and of SuperLU's factorization, and their ratio.
"""

from __future__ import annotations

import argparse
import math
import os
import time
from collections.abc import Callable
from dataclasses import replace
from unittest import mock

import numpy as np
import scipy.sparse.linalg as spla
from scipy.integrate import simpson
from scipy.interpolate import PchipInterpolator

from shtaerman.fem.contact.finite import NewtonStepper, run_finite_indentation
from shtaerman.fem.hyperelastic import HyperelasticSystem
from shtaerman.fem.mesh import FINITE_MESH
from shtaerman.study.contact.convergence import refined_settings
from shtaerman.study.contact.indentation import run_indentation
from shtaerman.study.finite.accuracy import reported_values
from shtaerman.study.finite.runner import run_finite_strain_study
from shtaerman.study.schema import load_study, shipped_studies
from shtaerman.theory.contact import PowerLawContact
from shtaerman.theory.impact_ode import integrate_impact
from shtaerman.theory.indenter import PowerLawIndenter
from shtaerman.theory.materials import Material

E2 = 7.5e6
PAPER = PowerLawIndenter(5.0, 1.5)
RUBBER = Material(E2, 0.5)
MASS, VELOCITY = 0.7, 3.0
X_C = 8.5175e-3  # linear quasi-static impact, m


def load() -> str:
    one, five, fifteen = os.getloadavg()
    return f"load average {one:.1f} {five:.1f} {fifteen:.1f} on {os.cpu_count()} cores"


def blunt(exponent: float, ratio: float, radius: float = 1e-3) -> tuple[PowerLawIndenter, float]:
    """Indenter whose linear contact at radius ``radius`` has depth/radius = ``ratio``."""
    kappa = PowerLawIndenter(1.0, exponent).kappa
    indenter = PowerLawIndenter(ratio / (kappa * radius ** (exponent - 1)), exponent)
    return indenter, kappa * indenter.shape_coefficient * radius**exponent


def small_strain() -> None:
    print("\n(a) small-strain limit, default mesh (P_fem: finite strain; P_lin: linear FEM)")
    print("  n    nu   x/a     P/P_Shtaerman-1  P/P_lin-1   a/a_lin-1")
    for exponent in (1.5, 2.0):
        for nu in (0.3, 0.5):
            indenter, depth = blunt(exponent, 2e-3)
            depths = [depth * 0.5**exponent, depth]  # x/a = 1e-3 and 2e-3
            finite = run_finite_indentation(indenter, Material(E2, nu), depths)
            linear = run_indentation(indenter, Material(E2, nu), depths, FINITE_MESH)
            for step, ref in zip(finite.steps, linear.steps, strict=True):
                print(
                    f"  {exponent:<4} {nu:<4} {step.depth / step.contact_radius_linear:.1e}"
                    f"  {step.force / step.force_linear - 1:+.2e}        "
                    f"{step.force / ref.force - 1:+.2e}   "
                    f"{step.contact_radius / ref.contact_radius - 1:+.2e}"
                )


def paper_curve() -> None:
    exact = PowerLawContact(PAPER, RUBBER.youngs_modulus / (1 - RUBBER.poisson_ratio**2))
    depths = 1.01 * X_C * np.arange(1, 13) / 12
    start, cpu = time.perf_counter(), time.process_time()
    curve = run_finite_indentation(PAPER, RUBBER, depths)
    elapsed, cpu = time.perf_counter() - start, time.process_time() - cpu
    print(f"\n(b) the paper's curve, 12 depths to 1.01 x_c, default mesh {curve.mesh_stats}")
    print(
        f"  wall time {elapsed:.1f} s ({ {k: round(v, 2) for k, v in curve.timings.items()} }), "
        f"{load()}; cpu time {cpu:.1f} s (one process: about what an idle machine takes)"
    )
    print("  depth (m)   x/a_lin  P/(beta x^5/3)  a/a_lin  p0/p_avg  p0/p0_lin  energy (J)  Newton")
    for s in curve.steps:
        ratio_x = s.depth / s.contact_radius_linear
        ratio_a = s.contact_radius / s.contact_radius_linear
        ratio_p = s.central_pressure / s.central_pressure_linear
        print(
            f"  {s.depth:.4e}  {ratio_x:.3f}    {s.force / s.force_linear:.4f}          "
            f"{ratio_a:.4f}   {s.central_pressure / s.mean_pressure:.3f}     {ratio_p:.4f}"
            f"     {s.strain_energy:.4e}  {s.newton_iterations}"
        )
    # the finite-strain force law: P = beta x^(5/3) * ratio(x), ratio -> 1 as x -> 0
    x = np.array([0.0] + [s.depth for s in curve.steps])
    ratio = np.array([1.0] + [s.force / s.force_linear for s in curve.steps])
    smooth = PchipInterpolator(x, ratio)

    def force(depth):
        # beyond the last depth the ratio is extrapolated (PCHIP's end cubic): the
        # finite-strain x_c lies ~0.7 % beyond 1.01 x_c, where the ratio changes by ~1e-4
        depth = np.asarray(depth, dtype=float)
        return exact.force(depth) * smooth(depth)

    finite = integrate_impact(MASS, VELOCITY, force, X_C)
    linear = integrate_impact(MASS, VELOCITY, exact.force, X_C)
    at_xc = smooth(finite.x_c)
    print(
        f"  at the finite-strain x_c: P/(beta x^5/3) = {at_xc:.4f} (x_c is "
        f"{finite.x_c / x[-1] - 1:+.2%} beyond the last tabulated depth: extrapolated)"
    )
    print("  impact 0.7 kg at 3 m/s      x_c (m)      P_c (N)     t_c (s)")
    print(f"    linear (Shtaerman)    {linear.x_c:.5e}  {linear.P_c:.5e}  {linear.t_c:.5e}")
    print(f"    finite strain         {finite.x_c:.5e}  {finite.P_c:.5e}  {finite.t_c:.5e}")
    print(
        f"    ratio                 {finite.x_c / linear.x_c:.4f}       "
        f"{finite.P_c / linear.P_c:.4f}       {finite.t_c / linear.t_c:.4f}"
    )


def conservation() -> None:
    depths = X_C * np.arange(1, 17) / 16
    curve = run_finite_indentation(PAPER, RUBBER, depths)
    d = np.concatenate([[0.0], depths])
    p = np.concatenate([[0.0], [s.force for s in curve.steps]])
    work = simpson(p, x=d)
    energy = curve.steps[-1].strain_energy
    print("\n(c) conservation, 16 equal steps to x_c, default mesh")
    print(
        f"  Simpson Int P dx = {work:.6e} J, stored energy = {energy:.6e} J, "
        f"relative difference {work / energy - 1:+.2e}"
    )
    half = simpson(p[::2], x=d[::2])
    print(
        f"  (8 steps: {half / energy - 1:+.2e}: the difference is Simpson's error, "
        f"converging with the step)"
    )


def depth_at_ratio(ratio: float) -> float:
    """Depth where the linear x/a equals ``ratio`` for the paper's indenter."""
    scale = PAPER.kappa * PAPER.shape_coefficient  # x = scale a^1.5, x/a = scale a^0.5
    a = (ratio / scale) ** 2
    return scale * a**1.5


def mesh_convergence(factors: list[float]) -> None:
    """Whole size field scaled by t (size, axis size and both growth rates;
    study.contact.convergence)."""
    depths = [depth_at_ratio(0.5), depth_at_ratio(0.9)]
    print(
        f"\n(d) mesh convergence of P at x/a = 0.5, 0.9 (depths {depths[0]:.4e}, "
        f"{depths[1]:.4e} m); the whole size field of the default mesh scaled by t"
    )
    forces, sizes = [], []
    for t in factors:
        mesh = refined_settings(FINITE_MESH, FINITE_MESH.size * t)
        start, cpu = time.perf_counter(), time.process_time()
        curve = run_finite_indentation(PAPER, RUBBER, depths, mesh)
        forces.append([s.force for s in curve.steps])
        sizes.append(t)
        print(
            f"  t = {t:.3f}: dofs {curve.mesh_stats['dofs']}, P = {forces[-1][0]:.7e}, "
            f"{forces[-1][1]:.7e} N ({time.perf_counter() - start:.0f} s wall, "
            f"{time.process_time() - cpu:.0f} s cpu)"
        )
    forces = np.array(forces)
    ratio_t = factors[0] / factors[1]
    default = factors.index(1.0)
    for k, ratio in enumerate((0.5, 0.9)):
        column = forces[:, k]
        diffs = np.diff(column)
        orders = np.log(np.abs(diffs[:-1] / diffs[1:])) / np.log(ratio_t)
        order = orders[-1]
        limit = column[-1] + diffs[-1] / (ratio_t**order - 1)
        overall = np.polyfit(np.log(factors[1:]), np.log(np.abs(diffs)), 1)[0]
        print(
            f"  x/a = {ratio}: least-squares order over all levels {overall:.2f}; default "
            f"against the finest mesh {column[default] / column[-1] - 1:+.2e}"
        )
        print(
            f"  x/a = {ratio}: successive differences "
            f"{', '.join(f'{d:+.2e}' for d in diffs)} N; observed orders "
            f"{', '.join(f'{o:.2f}' for o in orders)} (in h); Richardson P = {limit:.7e}; "
            f"default mesh error {column[default] / limit - 1:+.2e}, "
            f"finest {column[-1] / limit - 1:+.2e}"
        )


def sneddon_sphere(radius: float, modulus: float, depth: float) -> tuple[float, float]:
    """Exact linear force (N) and contact radius of a rigid *sphere* (Sneddon 1965)."""
    from scipy.optimize import brentq

    def excess(a):
        return 0.5 * a * math.log((radius + a) / (radius - a)) - depth

    a = brentq(excess, 1e-12 * radius, radius * (1 - 1e-12))
    force = modulus * (
        0.5 * (radius**2 + a**2) * math.log((radius + a) / (radius - a)) - a * radius
    )
    return force, a


def hertz() -> None:
    radius = 0.01
    indenter = PowerLawIndenter.sphere(radius)
    star = E2 / 0.75
    ratios = np.array([0.005, 0.01, 0.025, 0.05, 0.1, 0.2])
    depths = ratios * radius
    start = time.perf_counter()
    # one run per depth, each with the default mesh sized to its own contact (one run for all
    # sizes the mesh to the deepest: the shallowest force then carries ~1.5e-3 more error)
    steps = [run_finite_indentation(indenter, RUBBER, [d]).steps[0] for d in depths]
    print(
        f"\n(e) Hertz paraboloid z = r^2/(2R), R = {radius} m, incompressible neo-Hookean "
        f"({time.perf_counter() - start:.0f} s)"
    )
    print(
        "  sphere est. = FE paraboloid x (Sneddon sphere / Hertz): profile and finite-strain\n"
        "  effects composed to first order. Lin09 shape: (1 - e + e^2/3)/(1 - e)^2, e = 0.2 a/R,\n"
        "  the neo-Hookean uniaxial law at Lin et al.'s representative strain, normalised to\n"
        "  Hertz at small strain (our reconstruction; their printed prefactor 40/3 C10 vs Hertz's\n"
        "  32/3 C10 not verified here)."
    )
    print(
        "  d/R    P/P_Hertz (FE, paraboloid)  a/a_Hertz  Sneddon sphere/Hertz  sphere est."
        "  Lin09 shape"
    )
    for step, ratio in zip(steps, ratios, strict=True):
        sphere, _ = sneddon_sphere(radius, star, step.depth)
        profile = sphere / step.force_linear
        eps = 0.2 * math.sqrt(ratio)  # Lin et al.'s strain 0.2 a/R, a = sqrt(R d)
        lin = (1 - eps + eps**2 / 3) / (1 - eps) ** 2
        slope = (1 - step.force / step.force_linear) / math.sqrt(ratio)
        print(
            f"  {ratio:<5}  {step.force / step.force_linear:.4f} (1 - {slope:.3f} a/R)      "
            f"{step.contact_radius / step.contact_radius_linear:.4f}     {profile:.4f}"
            f"                {step.force / step.force_linear * profile:.4f}       {lin:.4f}"
        )


def _timed(study, **options):
    cpu = time.process_time()
    outcome = run_finite_strain_study(study, **options)
    return outcome, time.process_time() - cpu


def _crossings(outcome) -> dict[str, float]:
    return {f"x/a at {e['level']:.0%}": e["depth_to_radius"] for e in outcome.validity()}


def _row(name: str, value: float, estimate: float, method: str, refs: list[float]) -> str:
    true = abs(value / refs[-1] - 1.0)
    reference = abs(refs[0] / refs[-1] - 1.0)
    ratio = estimate / true if true > 0 else math.inf
    return (
        f"  {name:26s} {value:12.6g}  {estimate:8.1e}  {true:8.1e}  {ratio:7.2f}  "
        f"{reference:8.1e}  {method}"
    )


def study_estimates(which: int) -> None:
    study = load_study(next(p for p in shipped_studies() if p.stem == "finite_strain"))[which]
    _, today = _timed(replace(study, mesh=FINITE_MESH), estimate=False)
    ladder, cost = _timed(study)
    estimates = ladder.estimates
    references = [
        _timed(replace(study, mesh=study.mesh.refined(f)), estimate=False)[0]
        for f in (math.sqrt(2.0), 2.0)
    ]
    print(
        f"\n(f) {study.name}: ladder {'/'.join(map(str, estimates.dofs))} dofs, CPU "
        f"{' + '.join(f'{c:.1f}' for c in estimates.cpu_seconds)} = {cost:.1f} s against "
        f"{today:.1f} s for one run on today's default mesh ({cost / today:.2f}x); references "
        f"{'/'.join(str(r.finite.curve.mesh_stats['dofs']) for r in references)} dofs; {load()}"
    )
    print("  quantity                          value  estimate      true  effect.  ref-ref  method")
    values = [reported_values(r) for r in (ladder, *references)]
    for key, estimate in estimates.scalars.items():
        if key == "force_ratio_worst":
            continue
        method = estimate.method + (f" ({estimate.reason})" if estimate.reason else "")
        print(_row(key, values[0][key], estimate.error, method, [v[key] for v in values[1:]]))
    worst = estimates.worst_step()
    rows = [r.rows()[worst]["force_ratio"] for r in references]
    estimate = estimates.steps[worst]["force_ratio"]
    name = f"P/(b x^q) worst, x/a {ladder.rows()[worst]['depth_to_radius']:.2g}"
    print(_row(name, ladder.rows()[worst]["force_ratio"], estimate.error, estimate.method, rows))
    crossings = [_crossings(r) for r in (ladder, *references)]
    for entry, (key, value) in zip(ladder.limits(), crossings[0].items(), strict=True):
        refs = [c[key] for c in crossings[1:]]
        error = entry["errors"]["depth_to_radius"]
        print(_row(key, value, error, f"departure error {entry['departure_error']:.1e}", refs))
    effectivities = []
    for k, step in enumerate(estimates.steps):
        for key in ("force_ratio", "force_ratio_fem"):
            true = abs(ladder.rows()[k][key] / references[-1].rows()[k][key] - 1.0)
            effectivities.append(step[key].error / true if true > 0 else math.inf)
    inside = np.mean([1 / 3 <= e <= 3 for e in effectivities])
    print(
        f"  per depth, P/P_lin and P/P_linFEM ({len(effectivities)} estimates): effectivity "
        f"median {np.median(effectivities):.2f}, quartiles "
        f"{np.percentile(effectivities, 25):.2f}-{np.percentile(effectivities, 75):.2f}, "
        f"{inside:.0%} within [1/3, 3], {np.mean(np.array(effectivities) < 1):.0%} below 1"
    )


def _clocked(function: Callable, spent: dict[str, float], key: str) -> Callable:
    """``function`` adding its CPU time to spent[key] and counting its calls in spent[key + 'n']."""

    def clocked(*args, **kwargs):
        start = time.process_time()
        try:
            return function(*args, **kwargs)
        finally:
            spent[key] += time.process_time() - start
            spent[key + "n"] += 1

    return clocked


def iteration_cost() -> None:
    keys = ("assembly", "factorization", "newton")
    spent = {key + suffix: 0.0 for key in keys for suffix in ("", "n")}
    patches = [
        mock.patch.object(HyperelasticSystem, name, _clocked(method, spent, "assembly"))
        for name, method in (
            ("state", HyperelasticSystem.state),
            ("residual", HyperelasticSystem.residual),
            ("tangent_data", HyperelasticSystem.tangent_data),
        )
    ]
    patches.append(mock.patch.object(spla, "splu", _clocked(spla.splu, spent, "factorization")))
    patches.append(
        mock.patch.object(NewtonStepper, "solve", _clocked(NewtonStepper.solve, spent, "newton"))
    )
    depths = 1.01 * X_C * np.arange(1, 13) / 12
    for patch in patches:
        patch.start()
    try:
        curve = run_finite_indentation(PAPER, RUBBER, depths)
    finally:
        for patch in patches:
            patch.stop()
    iterations = int(spent["factorizationn"])
    assembly, factorization, newton = (spent[key] / iterations for key in keys)
    print(
        f"\n(g) cost of a Newton iteration, the paper's curve of (b) "
        f"({curve.mesh_stats['dofs']} dofs, {iterations} iterations, {spent['newton']:.1f} s CPU "
        f"in Newton; {load()})"
    )
    print(
        f"  per iteration (CPU): assembly (state, residual, tangent) {assembly * 1e3:.1f} ms, "
        f"factorization {factorization * 1e3:.1f} ms, assembly / factorization = "
        f"{assembly / factorization:.2f}; the rest (constraint elimination, scaling, solve, "
        f"checks) {(newton - assembly - factorization) * 1e3:.1f} ms"
    )


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--quick", action="store_true", help="sections (b) and (a) only")
    parser.add_argument("--sections", default="bacdefg", help="which sections to run, e.g. 'd'")
    args = parser.parse_args()
    sections = "ba" if args.quick else args.sections
    print(f"machine: {load()}")
    run = {
        "b": paper_curve,
        "a": small_strain,
        "c": conservation,
        "e": hertz,
        "d": lambda: mesh_convergence([2.0, 2**0.5, 1.0, 2**-0.5, 0.5]),
        "f": lambda: [study_estimates(which) for which in (0, 1)],
        "g": iteration_cost,
    }
    for section in sections:
        run[section]()


if __name__ == "__main__":
    main()
