# ---
# jupyter:
#   jupytext:
#     formats: py:percent
#     text_representation:
#       extension: .py
#       format_name: percent
# ---

# %% [markdown]
# # A sweep, locally or on a cluster
#
# A sweep is a grid of cases: every combination of the values in `[axes]` is one case, run in
# parallel on dask.distributed, each finished case saved as it arrives. Inputs are named as
# the command-line options, in snake_case. Here the exact quasi-static impact (kind `impact`,
# instantaneous per case) of the tutorial's own indenter over velocity and rubber modulus.

# %%
import csv
from pathlib import Path

import shtaerman as sh

Path("my-sweep.toml").write_text(
    """\
name = "my-sweep"
kind = "impact"            # impact | contact | dynamic | finite-strain

[parameters]               # fixed inputs
shape_coefficient = 12.0
exponent = 1.8
mass = 0.25
E1 = inf                   # rigid striker
nu2 = 0.49

[axes]                     # 3 x 2 = 6 cases, last axis fastest
velocity = [0.5, 1.0, 2.0]
E2 = [4e6, 8e6]
""",
    encoding="utf-8",
)

# %% [markdown]
# `workers=2` starts a local cluster of two single-threaded worker processes. The folder
# `my-sweep-run` gets one JSON file per case, `cases.csv`, `results.json` and figures.
#
# In a script, start the sweep under `if __name__ == "__main__":`: dask's worker processes
# import the main script, and must not start sweeps of their own (a notebook needs no guard).

# %%
if __name__ == "__main__":
    sh.sweep("my-sweep.toml", workers=2, out="my-sweep-run")
    with open("my-sweep-run/cases.csv", newline="", encoding="utf-8") as table:
        rows = list(csv.DictReader(table))
    for row in rows:
        print(
            f"v0 = {row['velocity [m/s]']:>4} m/s, E2 = {float(row['E2 [Pa]']):.0e} Pa: "
            f"x_c = {float(row['x_c [m]']) * 1e3:.4f} mm, P_c = {float(row['P_c [N]']):.1f} N"
        )

# %% [markdown]
# Each row is the same as a single `sh.impact` call with those inputs.
#
# ## On a cluster
#
# To use more machines, start a dask scheduler and workers where shtaerman (the same version)
# is installed, and point the sweep at the scheduler's address; workers need no shared disk:
#
# ```sh
# dask scheduler --port 8786                                   # on the head node
# dask worker tcp://head:8786 --nworkers 8 --nthreads 1        # on each compute node
# shtaerman sweep my-sweep.toml --scheduler tcp://head:8786 --out my-sweep-run
# ```
#
# or, from Python, `sh.sweep("my-sweep.toml", scheduler="tcp://head:8786", out="my-sweep-run")`.
# dask-jobqueue (SLURM, PBS) and dask-kubernetes users start their cluster as usual and pass
# its `scheduler_address`. An interrupted sweep keeps every finished case;
# `shtaerman sweep my-sweep.toml --out my-sweep-run --resume` completes it.
