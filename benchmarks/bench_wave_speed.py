"""Where the linear FE impact with inertia breaks down against the striker's speed over the
body's shear wave speed (guards.wave_limit, lifted here to run past it).

Run ``python benchmarks/bench_wave_speed.py`` (about 2 minutes on 2 idle cores; ``--quick``:
mesh_size 0.1 and 60 steps per t_y, 20 s). The paper's impact (0.7 kg, 3 m/s, z = 5 r^1.5 on
7.5 MPa, nu = 0.5, 1100 kg/m^3) made faster three ways: a denser body (x/a fixed), a faster
striker, a 10x lighter striker on a denser body. Per case v0 / c_s, x/a, the first-order
radiated fraction lambda and restitution of the quasi-static impact, the FE's restitution,
radiated fraction, energy balance error and reflected fraction, and the exit code of
``shtaerman dynamic`` (1: a check failed). Prints a table; nothing is asserted.
"""

from __future__ import annotations

import contextlib
import io
import json
import math
import sys
import warnings

import shtaerman.guards
from shtaerman.cli import main as cli

CASES = [
    *(["--density2", f"{rho:g}"] for rho in (1100, 1e4, 3e4, 3.4e4, 3.5e4, 1e5, 1e6)),
    *(["--velocity", f"{v:g}"] for v in (16, 24, 26.5, 29, 31, 48)),
    *(["--mass", "0.07", "--density2", f"{rho:g}"] for rho in (1.5e4, 1.98e4, 2.2e4, 2.8e4)),
]


def run(argv: list[str]) -> tuple[int, dict]:
    """Exit code and JSON of ``shtaerman dynamic --json --no-estimate`` with ``argv``."""
    out = io.StringIO()
    with contextlib.redirect_stdout(out), contextlib.redirect_stderr(io.StringIO()):
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            code = cli(["dynamic", "--json", "--no-estimate", *argv])
    return code, json.loads(out.getvalue())


def main() -> None:
    shtaerman.guards.wave_limit = lambda *_: math.inf  # run past the guard
    coarse = ["--mesh-size", "0.1", "--time-steps", "60"] if "--quick" in sys.argv else []
    print(f"{'case':28} {'v0/c_s':>7} {'x/a':>5} {'lambda':>7} {'e_est':>6} {'e':>6} "
          f"{'radiated':>8} {'balance':>8} {'reflected':>9} exit")  # fmt: skip
    for argv in CASES:
        code, d = run([*argv, *coarse])
        p, dy, est, qs = d["parameters"], d["dynamic"], d["radiation_estimate"], d["quasi_static"]
        e_est = est["restitution"] if est["restitution"] is not None else math.nan
        print(
            f"{' '.join(argv):28} {p['velocity'] / p['shear_wave_speed']:7.3g} "
            f"{qs['x_c'] / qs['a_c']:5.3g} {est['energy_fraction']:7.3g} {e_est:6.3f} "
            f"{dy['restitution']:6.4f} {dy['energy_radiated_fraction']:8.4f} "
            f"{dy['energy_balance_error']:8.2g} {dy['reflected_energy_fraction']:9.3g} {code}"
        )


if __name__ == "__main__":
    main()
