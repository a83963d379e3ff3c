"""Independent validation of the finite-strain contact by another code (SfePy).

Run ``PYTHONPATH=src python benchmarks/sfepy_crosscheck.py`` from the shared venv. SfePy lives
in its own venv (default /work/sfepy-venv, ``--sfepy-python``; install it with
``python -m venv /work/sfepy-venv && /work/sfepy-venv/bin/pip install sfepy``); this script
meshes with gmsh here and runs SfePy in a subprocess (the same file with ``--worker``), so
shtaerman never imports sfepy. Nothing is asserted; the table is printed. Three SfePy runs of
4-10 minutes each on 2 loaded cores (10k-19k unknowns; ``--cache DIR`` keeps them), then
shtaerman's two ladders (about 1.5 minutes).

The problem (both codes, SI units with R = 1 m, E = 1 Pa: the results are P / (E R^2)):
a rigid frictionless SPHERE of radius R pressed to depth delta into a compressible neo-Hookean
half-space, W = mu/2 (J^(-2/3) I1 - 3) + K/2 (J - 1)^2 with the small-strain E, nu = 0.45,
approximated by a ball of radius R_d (clamped on its spherical surface) of the same size in
both codes (R_d = the shtaerman default margin 1.25 x sqrt(2 R delta_max) x domain factor 100).

- SfePy: a 3D octant (symmetry planes x = 0, y = 0), quadratic tetrahedra, total-Lagrangian
  ``dw_tl_he_neohook`` + ``dw_tl_bulk_penalty``, the rigid sphere by the penalty term
  ``dw_contact_sphere`` (SfePy has no paraboloid and no axisymmetric hyperelastic terms). The
  force is 4 x the z-sum of the contact term's nodal forces. Error estimate of the finer mesh:
  |fine - coarse| over two graded meshes (``--sizes``, element sizes in ratio 1.43) plus the
  move of the coarse mesh's force when the penalty k grows 4-fold (a penalty under-presses).
- shtaerman: the axisymmetric P2-P1 finite-strain contact. Its indenter is a power law
  z = A r^n, so the paraboloid A = 1/(2R), n = 2 is run as is, and the sphere by replacing the
  gap function of the Newton stepper inside this script only (``_sphere_geometry``). Error
  estimate: Richardson on the 3-mesh ladder refine 1/2, 1/sqrt 2, 1.
"""

from __future__ import annotations

import argparse
import json
import math
import os
import subprocess
import sys
import tempfile
from pathlib import Path

import numpy as np

RADIUS = 1.0  # sphere radius R, m
YOUNG = 1.0  # small-strain E, Pa
NU = 0.45
DEPTHS = (0.05, 0.1, 0.2, 0.3)  # delta / R
FAR_GROWTH = 0.3  # SfePy mesh: element size growth per unit distance beyond d = R
MARGIN, DOMAIN = 1.25, 100.0  # shtaerman's refined zone / a_g and domain / refined zone
MAX_CUTS = 6  # SfePy: halvings of a failing load step before a depth is given up


def domain_radius(depths: tuple[float, ...] = DEPTHS) -> float:
    """Radius R_d (m) of the ball both codes mesh: as shtaerman's half-space mesh."""
    return DOMAIN * MARGIN * math.sqrt(2.0 * RADIUS * RADIUS * max(depths))


# ---------------------------------------------------------------- SfePy side (worker) ----


def octant_mesh(path: Path, size: float, growth: float, radius: float) -> None:
    """gmsh: the octant x, y >= 0, z <= 0 of a ball of ``radius`` (m), tetrahedra of size
    ``size`` (m) at the origin growing by ``growth`` per unit distance d up to d = R and by
    FAR_GROWTH beyond (a smooth switch); medit format."""
    import gmsh

    gmsh.initialize(["", "-nt", "1"])
    try:
        gmsh.option.setNumber("General.Terminal", 0)
        ball = gmsh.model.occ.addSphere(0, 0, 0, radius)
        box = gmsh.model.occ.addBox(0, 0, -radius, radius, radius, radius)
        gmsh.model.occ.intersect([(3, ball)], [(3, box)])
        gmsh.model.occ.synchronize()
        field = gmsh.model.mesh.field.add("MathEval")
        d = "Sqrt(x*x + y*y + z*z)"
        beyond = f"(({d} - {RADIUS}) + Sqrt(({d} - {RADIUS})^2 + 0.01)) / 2"
        expression = f"{size} + {growth} * {d} + {FAR_GROWTH - growth} * {beyond}"
        gmsh.model.mesh.field.setString(field, "F", expression)
        gmsh.model.mesh.field.setAsBackgroundMesh(field)
        for name in ("MeshSizeFromPoints", "MeshSizeFromCurvature", "MeshSizeExtendFromBoundary"):
            gmsh.option.setNumber(f"Mesh.{name}", 0)
        volumes = gmsh.model.getEntities(3)
        gmsh.model.addPhysicalGroup(3, [tag for _, tag in volumes], 1)
        gmsh.model.mesh.generate(3)
        gmsh.model.mesh.optimize("Netgen")
        gmsh.write(str(path))
    finally:
        gmsh.finalize()


def _norm(x: np.ndarray) -> np.ndarray:
    return np.sqrt(np.sum(x * x, axis=1))


def worker(args: argparse.Namespace) -> None:
    """Inside the SfePy venv: press the sphere into the octant mesh, print JSON forces."""
    from sfepy.base.base import IndexedStruct
    from sfepy.discrete import (
        Equation,
        Equations,
        FieldVariable,
        Function,
        Functions,
        Integral,
        Integrals,
        Material,
        Problem,
    )
    from sfepy.discrete.conditions import Conditions, EssentialBC
    from sfepy.discrete.fem import FEDomain, Field, Mesh
    from sfepy.solvers.ls import ScipyDirect
    from sfepy.solvers.nls import Newton
    from sfepy.terms import Term

    mesh = Mesh.from_file(args.mesh)
    domain = FEDomain("domain", mesh)
    eps, rd = 1e-8, args.domain
    omega = domain.create_region("Omega", "all")
    sym_x = domain.create_region("SymX", f"vertices in (x < {eps})", "facet")
    sym_y = domain.create_region("SymY", f"vertices in (y < {eps})", "facet")
    top = domain.create_region("Top", f"vertices in (z > -{eps})", "facet")
    on_ball = Function("on_ball", lambda x, domain=None: np.flatnonzero(_norm(x) > rd * 0.999999))
    functions = Functions([on_ball])
    far = domain.create_region("Far", "vertices by on_ball", "facet", functions=functions)
    field = Field.from_args("displacement", np.float64, "vector", omega, approx_order=2)
    u = FieldVariable("u", "unknown", field)
    v = FieldVariable("v", "test", field, primary_var_name="u")
    mu = YOUNG / (2 * (1 + NU))
    bulk = YOUNG / (3 * (1 - 2 * NU))
    solid = Material("solid", mu=mu, K=bulk)
    stiffness = args.penalty * YOUNG / RADIUS
    centre = np.array([0.0, 0.0, RADIUS])  # moved in place: the term keeps this array
    sphere = Material("cs", values={"f": [[stiffness, 0.0]], ".c": centre, ".r": RADIUS})
    volume, surface = Integral("i", order=4), Integral("is", order=4)
    terms = (
        Term.new("dw_tl_he_neohook(solid.mu, v, u)", volume, omega, solid=solid, v=v, u=u)
        + Term.new("dw_tl_bulk_penalty(solid.K, v, u)", volume, omega, solid=solid, v=v, u=u)
        + Term.new("dw_contact_sphere(cs.f, cs.c, cs.r, v, u)", surface, top, cs=sphere, v=v, u=u)
    )
    problem = Problem("indent", equations=Equations([Equation("balance", terms)]))
    problem.set_bcs(
        ebcs=Conditions(
            [
                EssentialBC("fix_x", sym_x, {"u.0": 0.0}),
                EssentialBC("fix_y", sym_y, {"u.1": 0.0}),
                EssentialBC("fix_far", far, {"u.all": 0.0}),
            ]
        )
    )
    options = {"i_max": 25, "eps_a": 1e-12, "eps_r": 1e-9, "ls_on": 0.99999, "ls_red": 0.5}
    nls_status = IndexedStruct()
    problem.set_solver(Newton(options, lin_solver=ScipyDirect({}), status=nls_status))
    saved, forces, reached = None, [], 0.0
    for depth in args.depths:
        step, cuts, converged = (depth - reached) / args.substeps, 0, True
        while reached < depth * (1 - 1e-12):
            trial = min(reached + step, depth)
            centre[2] = RADIUS - trial
            state = problem.solve(state0=saved, save_results=False)
            if nls_status.condition == 0:  # converged: keep it, try a longer step
                reached, saved, step = trial, state.get_state().copy(), 1.5 * step
                continue
            step, cuts = step / 2.0, cuts + 1  # failed: back to the last state, halve
            if cuts > MAX_CUTS:
                converged = False
                break
        centre[2] = RADIUS - reached
        problem.solve(state0=saved, save_results=False)  # the last converged state again
        vector = problem.evaluate(
            "dw_contact_sphere.is.Top(cs.f, cs.c, cs.r, v, u)",
            mode="weak",
            dw_mode="vector",
            integrals=Integrals([surface]),
            copy_materials=False,
            cs=sphere,
        )
        full = problem.equations.make_full_vec(vector, force_value=0.0)
        force_z = 4.0 * float(np.sum(full.reshape(-1, 3)[:, 2]))
        forces.append((reached if converged else depth, abs(force_z), converged))
        print(depth, abs(force_z), converged, file=sys.stderr, flush=True)
    json.dump({"dofs": int(field.n_nod * 3), "forces": forces}, sys.stdout)


def run_sfepy(
    python: str, size: float, growth: float, penalty: float, substeps: int, cache: str | None
) -> dict:
    """Mesh here, solve in the SfePy venv; returns the worker's JSON (kept in ``cache``, a
    folder, when given, and read back from there on a rerun with the same settings)."""
    name = f"sfepy_h{size:g}_g{growth:g}_k{penalty:g}_s{substeps}.json"
    if cache is not None and (Path(cache) / name).exists():
        return json.loads((Path(cache) / name).read_text())
    with tempfile.TemporaryDirectory() as folder:
        mesh = Path(folder) / "octant.mesh"
        octant_mesh(mesh, size, growth, domain_radius())
        command = [python, __file__, "--worker", "--mesh", str(mesh), "--penalty", str(penalty)]
        command += ["--domain", repr(domain_radius()), "--substeps", str(substeps)]
        command += ["--depths", ",".join(repr(d * RADIUS) for d in DEPTHS)]
        if not Path(python).exists():
            raise SystemExit(f"--sfepy-python: {python} not found; install SfePy in its own venv")
        done = subprocess.run(command, capture_output=True, text=True, check=False)
    if done.returncode != 0:
        raise RuntimeError(f"SfePy worker failed ({done.returncode}):\n{done.stderr[-3000:]}")
    result = json.loads(done.stdout.strip().splitlines()[-1])
    if cache is not None:
        Path(cache).mkdir(parents=True, exist_ok=True)
        (Path(cache) / name).write_text(json.dumps(result))
    return result


# ------------------------------------------------------------------- shtaerman side ----


def _sphere_geometry(self, x: np.ndarray, depth: float) -> tuple[np.ndarray, ...]:
    """The stepper's gap for the sphere f(r) = R - sqrt(R^2 - r^2) (R = 1 / (2 A))."""
    sphere = 1.0 / (2.0 * self.indenter.shape_coefficient)
    r = self.nodes.radius + x[self.nodes.ur]
    r = np.maximum(r, 0.0)
    s = np.sqrt(np.maximum(sphere**2 - np.minimum(r, 0.999 * sphere) ** 2, 0.0))
    gap = sphere - s - depth - x[self.nodes.uz]
    slope = r / s
    curvature = sphere**2 / s**3
    return r, gap, slope, curvature


def run_ours(profile: str, refine: float) -> list[float]:
    """shtaerman's force P / (E R^2) at DEPTHS on the default mesh refined by ``refine``."""
    from unittest import mock

    from shtaerman.fem.contact.finite import NewtonStepper, run_finite_indentation
    from shtaerman.fem.mesh import FINITE_MESH
    from shtaerman.study.contact.convergence import refined_settings
    from shtaerman.theory.indenter import PowerLawIndenter
    from shtaerman.theory.materials import Material

    indenter = PowerLawIndenter(1.0 / (2.0 * RADIUS), 2.0)
    settings = refined_settings(FINITE_MESH, FINITE_MESH.size / refine)
    settings = type(settings)(**{**settings.__dict__, "domain": DOMAIN, "margin": MARGIN})
    depths = np.asarray(DEPTHS) * RADIUS
    if profile == "sphere":
        with mock.patch.object(NewtonStepper, "geometry", _sphere_geometry):
            curve = run_finite_indentation(indenter, Material(YOUNG, NU), depths, settings)
    else:
        curve = run_finite_indentation(indenter, Material(YOUNG, NU), depths, settings)
    return [step.force / (YOUNG * RADIUS**2) for step in curve.steps]


def ours_with_estimate(profile: str) -> tuple[list[float], list[float], int]:
    """Forces on the finest of the ladder 1/2, 1/sqrt 2, 1 and their Richardson estimates."""
    from shtaerman.study.richardson import richardson

    ladder = [run_ours(profile, k) for k in (0.5, 1.0 / math.sqrt(2.0), 1.0)]
    estimates = [richardson(values, math.sqrt(2.0)) for values in zip(*ladder, strict=True)]
    fallbacks = sum(e.method != "richardson" for e in estimates)
    return ladder[-1], [e.error * abs(e.value) for e in estimates], fallbacks


def sfepy_with_estimate(args: argparse.Namespace) -> tuple[list[float], list[float], str]:
    """SfePy forces on the finer mesh and their estimate |fine - coarse| + |coarse at 4 k -
    coarse at k| (mesh and penalty), with a note of the unknowns and unconverged steps."""
    coarse_size, fine_size = (float(s) for s in args.sizes.split(","))
    growth = args.growth * fine_size / coarse_size
    python, k, steps, cache = args.sfepy_python, args.penalty, args.substeps, args.cache
    coarse = run_sfepy(python, coarse_size, args.growth, k, steps, cache)
    stiff = run_sfepy(python, coarse_size, args.growth, 4.0 * k, steps, cache)
    fine = run_sfepy(python, fine_size, growth, k, steps, cache)
    runs = (coarse, stiff, fine)
    forces = [[f for _, f, _ in run["forces"]] for run in runs]
    estimates = [abs(f - c) + abs(s - c) for c, s, f in zip(*forces, strict=True)]
    failed = sum(not ok for run in runs for _, _, ok in run["forces"])
    note = f"SfePy unknowns {coarse['dofs']} / {fine['dofs']}; unconverged steps {failed}"
    note += f"; penalty k R/E = {k:g} and {4 * k:g}"
    return forces[2], estimates, note


def report(args: argparse.Namespace) -> None:
    """Print the table: depth, P_sfepy +/- est, P_ours (sphere and paraboloid) +/- est."""
    print(f"sphere R = {RADIUS} m, E = {YOUNG} Pa, nu = {NU}, ball radius {domain_radius():.4g} m")
    print(f"load average {' '.join(f'{x:.1f}' for x in os.getloadavg())} on {os.cpu_count()}")
    theirs, their_err, note = sfepy_with_estimate(args)
    print(note)
    sphere, sphere_err, sphere_fb = ours_with_estimate("sphere")
    parab, parab_err, parab_fb = ours_with_estimate("paraboloid")
    fallbacks = f"sphere {sphere_fb}, paraboloid {parab_fb} of {len(DEPTHS)}"
    print(f"shtaerman Richardson fallbacks: {fallbacks}")
    print(
        "delta/R  P_sfepy/(E R^2)        P_ours sphere          sphere diff  "
        "P_ours paraboloid      parab/sphere-1"
    )
    for row in zip(DEPTHS, theirs, their_err, sphere, sphere_err, parab, parab_err, strict=True):
        depth, p_s, e_s, p_o, e_o, p_p, e_p = row
        print(
            f"{depth:6.3f}  {p_s:.5f} +/- {e_s:.1e}  {p_o:.5f} +/- {e_o:.1e}  "
            f"{p_s / p_o - 1:+8.2%}     {p_p:.5f} +/- {e_p:.1e}  {p_p / p_o - 1:+8.2%}"
        )


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--worker", action="store_true", help=argparse.SUPPRESS)
    parser.add_argument("--mesh", help=argparse.SUPPRESS)
    parser.add_argument("--domain", type=float, help=argparse.SUPPRESS)
    parser.add_argument("--depths", help=argparse.SUPPRESS)
    parser.add_argument("--penalty", type=float, default=1e3, help="penalty k R / E")
    parser.add_argument("--substeps", type=int, default=2, help="SfePy load steps per depth")
    parser.add_argument("--cache", help="folder keeping the SfePy runs' JSON (default: none)")
    parser.add_argument("--sfepy-python", default="/work/sfepy-venv/bin/python")
    parser.add_argument("--sizes", default="0.1,0.07", help="SfePy mesh sizes at the origin / R")
    parser.add_argument("--growth", type=float, default=0.2, help="SfePy size growth")
    args = parser.parse_args()
    if args.worker:
        args.depths = [float(d) for d in args.depths.split(",")]
        worker(args)
        return
    report(args)


if __name__ == "__main__":
    main()
