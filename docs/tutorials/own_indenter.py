# ---
# jupyter:
#   jupytext:
#     formats: py:percent
#     text_representation:
#       extension: .py
#       format_name: percent
# ---

# %% [markdown]
# # Your own indenter, end to end
#
# A striker whose surface is z = 12 r^1.8 (shape coefficient A = 12 m^-0.8, exponent n = 1.8),
# 0.25 kg arriving at 2 m/s on a rubber of Young's modulus 4 MPa and Poisson's ratio 0.49. Three
# computations, each a single call of the public API:
#
# 1. the exact quasi-static impact (Shtaerman's force law and the Ateb solution),
# 2. the finite-element contact curve up to this impact's maximum approach x_c, every force
#    with its error estimate, against Shtaerman's P = beta x^q,
# 3. the dynamic finite-element impact, which keeps the energy the elastic waves carry away.
#
# The settings are coarse so that the tutorial runs in seconds (`refine=` below 1 coarsens the
# whole discretisation); drop `refine=` for the default accuracy.

# %%
import shtaerman as sh

indenter = sh.PowerLawIndenter(shape_coefficient=12.0, exponent=1.8)
rubber = sh.Material(youngs_modulus=4e6, poisson_ratio=0.49)  # density only for `dynamic`
mass, velocity = 0.25, 2.0  # kg, m/s

# %% [markdown]
# ## 1. The exact quasi-static impact
#
# The striker is rigid unless a `striker=` material is given. The result's attributes are the
# keys of `shtaerman impact --json`.

# %%
quasi_static = sh.impact(indenter, rubber, mass=mass, velocity=velocity)
x_c, P_c, t_c = quasi_static.x_c, quasi_static.P_c, quasi_static.t_c
print(f"x_c = {x_c * 1e3:.4f} mm, P_c = {P_c:.2f} N, t_c = {t_c * 1e3:.4f} ms")

# %% [markdown]
# The same number from the closed form,
# x_c = ((q+1) M v0^2 / (2 beta))^(1/(q+1)) with q = (n+1)/n and beta from `to_dict()`:

# %%
q = (indenter.exponent + 1) / indenter.exponent
beta = quasi_static.to_dict()["beta"]
x_c_formula = ((q + 1) * mass * velocity**2 / (2 * beta)) ** (1 / (q + 1))
print(f"beta = {beta:.6e} N/m^{q:.4f}, closed-form x_c / x_c - 1 = {x_c_formula / x_c - 1:.1e}")

# %% [markdown]
# ## 2. The FEM contact curve up to x_c
#
# With `mass=` and `velocity=`, `sh.contact` presses the indenter to this impact's x_c (or to
# the depths given by `depths=`). Every run is a ladder of three meshes; `error_estimate`
# holds the estimated relative error of each quantity (for the force, its worst depth).

# %%
curve = sh.contact(indenter, rubber, mass=mass, velocity=velocity, refine=0.6)
force_estimate = curve.error_estimate["force"]
print(f"deepest depth {curve.depth[-1] * 1e3:.4f} mm (x_c = {x_c * 1e3:.4f} mm)")
print(f"beta_fem / beta - 1 = {curve.beta_fem / beta - 1:+.1e}")
print(f"force estimate: {force_estimate:.1e} (relative, worst depth)")
print(" depth [mm]   force [N]   force / (beta x^q) - 1")
shtaerman_ratio = [
    float(force / (beta * depth**q) - 1)
    for depth, force in zip(curve.depth, curve.force, strict=True)
]
for depth, force, ratio in zip(curve.depth, curve.force, shtaerman_ratio, strict=True):
    print(f"{depth * 1e3:10.4f} {force:11.3f}   {ratio:+.1e}")

# %% [markdown]
# The FEM agrees with Shtaerman's law to within its own error estimate (the estimator's
# effectivity, estimate / true error, is measured at 0.55-2.5 on the contact ladders), and the
# contact radius and central pressure come with it: `curve.contact_radius`,
# `curve.central_pressure`.
#
# ## 3. The dynamic impact
#
# The half-space now has inertia, so it needs a density (1100 kg/m^3 is natural rubber). The
# quasi-static impact neglects the energy of elastic waves; the dynamic one measures it.

# %%
dense_rubber = sh.Material(youngs_modulus=4e6, poisson_ratio=0.49, density=1100.0)
impact = sh.dynamic(
    indenter,
    dense_rubber,
    mass=mass,
    velocity=velocity,
    refine=0.5,
    estimate=False,
)
print(f"restitution e = {impact.restitution:.4f}")
print(
    f"x_max = {impact.x_max * 1e3:.4f} mm, quasi-static x_c / x_max - 1 = "
    f"{x_c / impact.x_max - 1:+.2%}"
)
print(f"P_max = {impact.P_max:.2f} N, quasi-static P_c / P_max - 1 = {P_c / impact.P_max - 1:+.2%}")

# %% [markdown]
# The waves take part of the energy: the striker rebounds slower than it came (e < 1), and the
# quasi-static model overstates both the approach and the peak force. The
# [dynamic-impact tutorial](dynamic_impact.md) looks at this in detail.
