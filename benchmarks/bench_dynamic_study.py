"""The dynamic study (fem/dynamic.toml): its cost, and the error of its settings vs a finer run.

Run: python benchmarks/bench_dynamic_study.py [--quick]. Prints the study's wall and CPU time
at its default and quick settings, and at 3 m/s the relative differences of x_max, P_max,
t_contact, e and 1 - e^2 between the study's settings and a run 4x finer in time and 3x in
space (800 steps per t_y, smallest element 1/120 of the refined radius), beside the study's own
ladder estimates of them (their ratio: the estimator's effectivity against that finer run).
Asserts nothing about time.

Measured on 2 shared cores (load average 3.5-5 from other jobs), 2026-11-22:
study, 6 velocities: 14.3-14.7 s CPU, 22-29 s wall; quick (1 and 3 m/s): 1.9-2.1 s CPU, 3 s wall.
3 m/s, study settings (200 steps, size 1/40; 11.7k dofs): 2.4-2.7 s CPU; the finer run (15.3k
dofs) 12.3 s CPU; differences x_max 1.9e-5, P_max 1.6e-4, t_contact 3.2e-5, e 3.9e-5.
Quick settings (60 steps, size 1/20): x_max 2.4e-4, P_max 1.5e-3, t_contact 6.8e-4, e 1.8e-5.
The quasi-static / dynamic differences the study reports (1-7 %) are 100x larger than these.

Since the study runs its error-estimate ladder (2026-11-22, load 2.6-4.8): study 34.1 s CPU,
40.9 s wall (24.8 s CPU, 36.9 s wall in another run at load 5.5; 14.1 s CPU without the
ladder); quick 2.9 s CPU (no ladder). At 3 m/s, difference to the finer run / ladder estimate
(effectivity): x_max 1.9e-5 / 4.3e-5 (2.3, Richardson), P_max 1.6e-4 / 5.1e-5 (0.31,
Richardson), t_contact 3.2e-5 / 6.7e-4 (21, two-level), e 3.9e-5 / 5.3e-6 (0.13, two-level),
1 - e^2 4.8e-4 / 6.4e-5 (0.13, two-level): the estimates of P_max and e are 3-8x below the
difference to this finer run (which also refines in other directions than the ladder).
"""

import argparse
import os
import time
from dataclasses import replace

from shtaerman.study.dynamic import run_case
from shtaerman.study.run import run_study
from shtaerman.study.schema import find_study, load_study

KEYS = ("x_max", "P_max", "t_contact", "restitution", "energy_radiated_fraction")


def timed(function, *args, **kwargs):
    wall, cpu = time.perf_counter(), time.process_time()
    value = function(*args, **kwargs)
    return value, time.perf_counter() - wall, time.process_time() - cpu


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--quick", action="store_true", help="skip the full study and fine run")
    quick = parser.parse_args().quick
    [study] = load_study(find_study("dynamic"))
    print("load average {:.1f} {:.1f} {:.1f}".format(*os.getloadavg()))
    for mode in (True,) if quick else (True, False):
        outcome, wall, cpu = timed(run_study, study, quick=mode)
        print(f"study quick={mode}: {cpu:.1f} s CPU, {wall:.1f} s wall, passed {outcome.passed}")
    if quick:
        return
    inputs = (study.indenter, study.half_space, study.density, study.mass, 3.0)
    fine_settings = replace(study.settings, steps=800, size=1.0 / 120.0)
    fine, wall, cpu = timed(run_case, *inputs, fine_settings)
    print(f"fine run: {fine.result.mesh['dofs']} dofs, {cpu:.1f} s CPU, {wall:.1f} s wall")

    def against_fine(case) -> dict[str, float]:
        return {key: abs(getattr(case.result, key) / getattr(fine.result, key) - 1) for key in KEYS}

    study_case = next(case for case in outcome.cases if case.velocity == 3.0)
    estimates = study_case.estimates()
    print(
        "study settings (the study's own 3 m/s run): against the fine run / its ladder estimate"
        " (effectivity): "
        + ", ".join(
            f"{key} {difference:.1e} / {estimates[key].error:.1e} "
            f"({estimates[key].error / difference:.2g}, {estimates[key].method})"
            for key, difference in against_fine(study_case).items()
        )
    )
    case, wall, cpu = timed(run_case, *inputs, study.quick_settings)
    errors = ", ".join(f"{key} {value:.1e}" for key, value in against_fine(case).items())
    print(f"quick settings ({case.result.mesh['dofs']} dofs, {cpu:.1f} s CPU): {errors}")


if __name__ == "__main__":
    main()
