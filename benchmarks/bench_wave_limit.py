"""At which first-order radiated fraction lambda the linear FE impact with inertia fails its
checks, per striker, and whether it passes at the limit guards.wave_limit sets (lifted here to
run past it).

Run ``python benchmarks/bench_wave_limit.py [STRIKER ...] [--lambdas 0.2,0.3,...]
[--at-limit] [--estimate] [--quick]`` (default: every striker at lambda 0.05 to 0.9 by 0.05,
the default mesh, ``--no-estimate``; ~2 CPU s a run, ~500 runs; ``--at-limit``: each at 0.99
of guards.wave_limit of its tip's force exponent and nu2, where the guard's remedies land;
``--estimate``: the estimate ladder's three meshes; ``--quick``: mesh_size 0.1 and 60 steps
per t_y). For each striker the velocity (or, where the striker's options give one, the
density2) that puts lambda (:class:`shtaerman.fem.dynamic_contact.RadiatedFraction`) at each
target is run with ``shtaerman dynamic --json``: per run the force exponent q at x_c (2 E* a_c
x_c / P_c), nu2, the option set, v0 / c_s, x/a, lambda, the FE's restitution, energy balance
error and reflected fraction, the exit code (1: a check failed, the balance or the reflected
energy beyond 1e-2, the latter once it is 1e-4 of M v0^2/2) and the CPU time. Then per
striker the largest lambda below which every run passed and the first that failed. Prints
tables; nothing is asserted.
"""

from __future__ import annotations

import contextlib
import io
import json
import math
import sys
import time
import warnings

import shtaerman.guards
from shtaerman.cli import main as cli
from shtaerman.fem.dynamic_contact import RadiatedFraction
from shtaerman.theory.indenter import PowerLawIndenter
from shtaerman.theory.materials import Material
from shtaerman.theory.profiles import SphereIndenter

LIMIT = shtaerman.guards.wave_limit
"""The guard's limit, kept before :func:`main` lifts it."""
SOFT = ["--E2", "1e7", "--density2", "1000", "--mass", "0.1"]
"""The body and mass of session 59's blunt strikers (z = 10 r^2 failed from lambda 0.52)."""
SHAPES = {
    1.5: 5.0,
    1.75: 7.0,
    2.0: 10.0,
    2.5: 20.0,
    3.0: 50.0,
    3.25: 70.0,
    3.5: 100.0,
    4.0: 200.0,
    4.5: 400.0,
}
"""A of z = A r^n on :data:`SOFT` (x/a 1e-6 to 1 over the scans)."""
BALL = ["--sphere-radius", "0.05", "--mass", "0.012", "--E2", "3e6", "--density2", "1000"]
"""user56's 12 g ball R = 50 mm on 3 MPa (refused at 60 m/s; its remedies failed)."""


def _power(n: float, *more: str) -> list[str]:
    return ["--exponent", f"{n:g}", "--shape-coefficient", f"{SHAPES[n]:g}", *SOFT, *more]


def _blunt(n: float, shape: float, nu: str) -> list[str]:
    """z = ``shape`` r^``n``, 0.7 kg at 1 m/s on 7.5 MPa, nu2 ``nu``: scanned by density2."""
    return ["--exponent", f"{n:g}", "--shape-coefficient", f"{shape:g}", "--velocity", "1",
            "--nu2", nu]  # fmt: skip


BLUNT_NU = ("0", "0.3", "0.45", "0.49", "0.499", "0.5")
"""The nu2 of the scans of n = 5 and 10: WAVE_LIMITS' and a rubber's."""
STRIKER_28 = ["--E2", "3e6", "--nu2", "0.49", "--mass", "0.12", "--density2", "1000"]
"""Issue 28's body and mass (its striker z = 8 r^1.3 at 1.5 m/s; its pad 12 mm)."""


def _pad(n: float, thickness_mm: float, *more: str) -> list[str]:
    """z = 8 r^``n``, issue 28's body and mass, on a bonded pad ``thickness_mm`` thick."""
    return ["--exponent", f"{n:g}", "--shape-coefficient", "8", *STRIKER_28[:6],
            "--thickness", f"{thickness_mm / 1e3:g}", *more]  # fmt: skip


STRIKERS = {
    "n1.3": ["--exponent", "1.3", "--shape-coefficient", "8", *STRIKER_28],  # issue 28's
    "n1.5": ["--exponent", "1.5", "--shape-coefficient", "5"],  # the paper's, 0.7 kg, 7.5 MPa
    "n1.5-soft": _power(1.5),
    **{f"n{n:g}": _power(n) for n in (1.75, 2.0, 2.5, 3.0, 3.25, 3.5, 4.0)},
    **{f"n{n:g}-nu0": _power(n, "--nu2", "0") for n in (1.75, 2.0, 2.5, 3.0, 3.25, 3.5)},
    **{f"n{n:g}-nu0.3": _power(n, "--nu2", "0.3") for n in (1.75, 2.0, 2.5, 3.0, 3.25, 3.5)},
    **{f"n{n:g}-nu{nu}": _power(n, "--nu2", nu)
       for n in (1.75, 2.0, 2.5, 3.0, 3.5) for nu in ("0.45", "0.49", "0.499")},
    **{f"n{n:g}-nu0.4999": _power(n, "--nu2", "0.4999") for n in (1.75, 2.0, 2.5, 3.0, 3.5)},
    "n2-heavy": [*_power(2.0), "--mass", "1"],
    **{f"n4-density{nu}": [*_power(4.0, "--velocity", "0.1"), "--nu2", nu]
       for nu in ("0", "0.3", "0.45", "0.49", "0.499", "0.5")},
    **{f"n4.5-density{nu}": [*_power(4.5, "--velocity", "0.1"), "--nu2", nu]
       for nu in ("0.45", "0.49", "0.499")},
    "n5": ["--exponent", "5", "--shape-coefficient", "1000"],  # 0.7 kg, 7.5 MPa
    **{f"n5-density{nu}": _blunt(5.0, 1e3, nu) for nu in BLUNT_NU},
    **{f"n10-density{nu}": _blunt(10.0, 1e6, nu) for nu in BLUNT_NU},
    "ball": BALL,
    "ball-nu0.3": [*BALL, "--nu2", "0.3"],
    "ball-nu0": [*BALL, "--nu2", "0"],
    **{f"ball-nu{nu}": [*BALL, "--nu2", nu] for nu in ("0.45", "0.49", "0.499")},
    "ball-equator": ["--sphere-radius", "0.01", *STRIKER_28, "--velocity", "5.5"],  # user64b
    "ball-deep": ["--sphere-radius", "0.005", *SOFT[:2], "--density2", "3.3e4", *SOFT[4:]],
    **{f"pad-n{n:g}-H{h:g}": _pad(n, h, "--velocity", "1.5")
       for n in (1.3, 1.5, 2.0, 3.0) for h in (3, 12, 48)},
    **{f"pad-n{n:g}-H12-v": _pad(n, 12, "--density2", "1000") for n in (1.3, 2.0)},
    **{f"half-n{n:g}": [*_pad(n, 0)[:-2], "--velocity", "1.5"] for n in (1.5, 2.0, 3.0)},
}  # fmt: skip
"""Each striker's options; one that gives --velocity is scanned by density2 (lambda ~
sqrt(density2) at a fixed x/a: z = A r^n, n >= 5, reaches lambda 0.01 below 1e-6 m/s)."""
LAMBDAS = [round(0.05 + 0.05 * k, 2) for k in range(18)]


def option(argv: list[str], name: str, default: float) -> float:
    """The value of ``--name`` in ``argv`` (its last), else ``default``."""
    values = [float(argv[k + 1]) for k, word in enumerate(argv) if word == f"--{name}"]
    return values[-1] if values else default


def tip_exponent(argv: list[str]) -> float:
    """q = (n + 1)/n of the striker ``argv`` describes (a sphere's tip: 3/2)."""
    return 1.5 if "--sphere-radius" in argv else 1.0 + 1.0 / option(argv, "exponent", 1.5)


def fraction_of(argv: list[str]):
    """lambda(velocity m/s, density2 kg/m^3) of the striker ``argv`` describes."""
    if "--sphere-radius" in argv:
        indenter = SphereIndenter(option(argv, "sphere-radius", 0.05))
    else:
        shape = option(argv, "shape-coefficient", 5.0)
        indenter = PowerLawIndenter(shape, option(argv, "exponent", 1.5))
    body, mass = (
        Material(option(argv, "E2", 7.5e6), option(argv, "nu2", 0.5)),
        option(argv, "mass", 0.7),
    )
    return lambda velocity, density: RadiatedFraction(indenter, body, density)(mass, velocity)


def setting(argv: list[str], target: float) -> list[str]:
    """The options that put the striker ``argv`` describes at lambda ``target``: its
    density2 where ``argv`` gives a velocity (lambda ~ sqrt(density2)), else its velocity (a
    secant in log-log, exact in one step for a power law: lambda ~ v0^((3q - 3)/(q + 1)))."""
    fraction, density = fraction_of(argv), option(argv, "density2", 1100.0)
    if "--velocity" in argv:
        here = fraction(option(argv, "velocity", 3.0), density)
        return ["--density2", f"{density * (target / here) ** 2:.4g}"]
    log_v, slope = 0.0, 0.3
    for _ in range(30):
        here = math.log(fraction(math.exp(log_v), density))
        if abs(math.log(target) - here) < 1e-6:
            break
        slope = (math.log(fraction(math.exp(log_v + 1e-3), density)) - here) / 1e-3
        log_v += (math.log(target) - here) / slope
    return ["--velocity", f"{math.exp(log_v):.4g}"]


def run(argv: list[str]) -> tuple[int, dict]:
    """Exit code and JSON of ``shtaerman dynamic --json`` with ``argv``."""
    out = io.StringIO()
    with contextlib.redirect_stdout(out), contextlib.redirect_stderr(io.StringIO()):
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            code = cli(["dynamic", "--json", *argv])
    try:
        return code, json.loads(out.getvalue())
    except json.JSONDecodeError:  # refused (exit 2), or a run stopped with no result
        return code, {}


def scan(name: str, lambdas: list[float], extra: list[str]) -> tuple[float, float]:
    """Print the runs of striker ``name`` at ``lambdas``; the largest lambda below which every
    run passed and the first that failed (NaN: none)."""
    argv = STRIKERS[name]
    passed, failed = math.nan, math.nan
    for target in lambdas:
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            knob = setting(argv, target)
        start = time.process_time()
        code, d = run([*argv, *knob, *extra])
        cpu = time.process_time() - start
        if not d:
            print(f"{name:11} {' '.join(knob):>20} refused (exit {code})")
            continue
        p, dy, qs = d["parameters"], d["dynamic"], d["quasi_static"]
        modulus = p["E2"] / (1.0 - p["nu2"] ** 2)  # the rigid striker's E*
        q = 2.0 * modulus * qs["a_c"] * qs["x_c"] / qs["P_c"]  # d ln P / d ln x at x_c
        estimate = d["radiation_estimate"]  # None on a pad: the half-space's, as the guard
        est = estimate["energy_fraction"] if estimate else target
        dy = {key: math.nan if value is None else value for key, value in dy.items()}
        print(
            f"{name:11} {q:5.3f} {p['nu2']:4.2f} {' '.join(knob):>20} "
            f"{p['velocity'] / p['shear_wave_speed']:8.3g} {qs['x_c'] / qs['a_c']:8.3g} "
            f"{est:6.3f} {dy['restitution']:6.4f} {dy['energy_balance_error']:8.2g} "
            f"{dy['reflected_energy_fraction']:8.3g} {code:4d} {cpu:5.1f}",
            flush=True,
        )
        if code == 0 and math.isnan(failed):
            passed = est
        elif code != 0 and math.isnan(failed):
            failed = est
    return passed, failed


def main() -> None:
    shtaerman.guards.wave_limit = lambda *_: math.inf  # run past the guard
    args = sys.argv[1:]
    lambdas = LAMBDAS
    if "--lambdas" in args:
        lambdas = [float(x) for x in args[args.index("--lambdas") + 1].split(",")]
    extra = [] if "--estimate" in args else ["--no-estimate"]
    if "--quick" in args:
        extra += ["--mesh-size", "0.1", "--time-steps", "60"]
    names = [name for name in args if name in STRIKERS] or list(STRIKERS)
    print(f"{'striker':11} {'q':>5} {'nu2':>4} {'set':>20} {'v0/c_s':>8} {'x/a':>8} "
          f"{'lambda':>6} {'e':>6} {'balance':>8} {'reflect':>8} exit {'CPU s':>5}")  # fmt: skip
    summary = []
    for name in names:
        if "--at-limit" in args:  # where the guard's remedies land
            argv = STRIKERS[name]
            power_law = "--sphere-radius" not in argv  # the bench's tables: none
            limit = LIMIT(tip_exponent(argv), option(argv, "nu2", 0.5), power_law)
            lambdas = [round(0.99 * limit, 5)]
        summary.append((name, *scan(name, lambdas, extra)))
    print(f"\n{'striker':11} {'passes to':>9} {'fails at':>8}")
    for name, passed, failed in summary:
        print(f"{name:11} {passed:9.3f} {failed:8.3f}")


if __name__ == "__main__":
    main()
