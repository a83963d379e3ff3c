# ---
# jupyter:
#   jupytext:
#     formats: py:percent
#     text_representation:
#       extension: .py
#       format_name: percent
# ---

# %% [markdown]
# # Finite strain: is rubber linear at these depths?
#
# Shtaerman's solution is linear elasticity. At the paper's maximum approach the depth is 0.89
# of the contact radius and the surface slope at the contact edge 36 degrees: far from small
# strain. `sh.contact(..., model="neo-hookean")` computes the same contact for a neo-Hookean
# half-space with the same small-strain modulus and Poisson's ratio (exactly incompressible at
# 0.5), frictionless against the rigid surface in the deformed configuration.
#
# The paper's striker, z = 5 r^(3/2), 0.7 kg at 3 m/s, on rubber of 7.5 MPa. Coarse meshes
# (`refine=0.6`) keep it short.

# %%
import numpy as np

import shtaerman as sh

indenter = sh.PowerLawIndenter(shape_coefficient=5.0, exponent=1.5)
q = (indenter.exponent + 1) / indenter.exponent

# %% [markdown]
# Four depths up to this impact's x_c. For each Poisson's ratio the table gives the
# neo-Hookean force over Shtaerman's linear beta x^q and the central pressure over the mean
# pressure (2.5 in the linear theory for n = 3/2).

# %%
ratio_at_x_c = {}
for poisson_ratio in (0.5, 0.3):
    rubber = sh.Material(youngs_modulus=7.5e6, poisson_ratio=poisson_ratio)
    exact = sh.impact(indenter, rubber, mass=0.7, velocity=3.0)
    beta = exact.to_dict()["beta"]
    depths = exact.x_c * np.array([0.25, 0.5, 0.75, 1.0])
    curve = sh.contact(indenter, rubber, depths=depths, model="neo-hookean", refine=0.6)
    ratio = curve.force / (beta * curve.depth**q)
    central_to_mean = curve.central_pressure / (curve.force / (np.pi * curve.contact_radius**2))
    ratio_at_x_c[poisson_ratio] = float(ratio[-1])
    print(f"nu2 = {poisson_ratio}: force estimate {curve.error_estimate['force']:.1e}")
    print("   x / x_c   P / (beta x^q)   p(0) / p_avg")
    for depth, r, c in zip(curve.depth, ratio, central_to_mean, strict=True):
        print(f"   {depth / exact.x_c:7.2f}   {r:14.4f}   {c:12.3f}")

# %% [markdown]
# Incompressible rubber softens (the force falls below beta x^q, by about 5 % at x_c on fine
# meshes); the compressible neo-Hookean stiffens, and its central pressure grows far beyond
# 2.5 p_avg; both depart further the deeper the striker goes. (Shallow depths need a finer
# mesh than this coarse one, which is refined for the contact at x_c: the shipped study checks
# the small-strain limit at x/a = 0.01.)
#
# The shipped study `fem/finite_strain.toml` (`shtaerman verify finite_strain`, or
# `sh.run_study("finite_strain")`) does this properly: 17 depths on a nested three-mesh ladder, the
# linear FEM on the same meshes, the impact integrated on the finite-strain curve, and the
# depths up to which the linear law holds to 1 % and 5 %, each with its error estimate (see
# [Findings](../findings.md#finite-strain-real-rubber-is-not-linear-at-these-depths)).
