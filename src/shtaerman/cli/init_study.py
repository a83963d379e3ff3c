"""``shtaerman init-study FILE.toml``: write a commented template study to start from."""

from __future__ import annotations

import argparse
import os
from pathlib import Path

from ..output.files import staged_file
from ..validation import InputError
from .common import add_inputs, path_text

__all__ = ["STUDY_TEMPLATE", "TEMPLATES", "register", "run", "write_template"]

INDENTER = """\
[indenter]                  # the (rigid) striker's surface: z = A r^n
shape_coefficient = 5.0     # A, m^(1-n)
exponent = 1.5              # n > 1
#   sphere_radius = 0.01    # instead of the two above: an exact sphere of radius R (m), or
#   profile = "tip.csv"     # a tabulated tip z(r): a CSV with columns r, z (m), relative to
"""
"""The [indenter] table of a rigid striker, shared by the templates but the contact one."""

STUDY_TEMPLATE = """\
# A shtaerman cross-check study (TOML): the FEM contact against Shtaerman's exact solution, and
# the impact it implies. Run it with
#     shtaerman verify {file} --quick    # coarse meshes, seconds
#     shtaerman verify {file}            # the accurate meshes, a minute or so
# SI units everywhere. As written it is the paper's worked example (Ol'shanskii et al. 2019,
# section 5); edit the numbers to your case. The keys are the command line's options in
# snake_case (--E2 is E2, --mesh-size is mesh_size). Only the tables indenter, half_space
# and impact are required; an unknown key is an error naming file and key.
kind = "contact"

# name = "{name}"           # the study's name in reports and folders; default: the file name
description = "z = 5 r^(3/2) steel striker, 0.7 kg at 3 m/s, on rubber (edit me)"

[indenter]                  # the striker's surface near its first contact point: z = A r^n
shape_coefficient = 5.0     # A, m^(1-n)
exponent = 1.5              # n > 1 (n = 2, A = 1/(2R): Hertz's paraboloid)
#   sphere_radius = 0.01    # instead of the two above: an exact sphere of radius R (m), or
#   profile = "tip.csv"     # a tabulated tip z(r): a CSV with columns r, z (m), relative to
                            # this file

[striker]                   # scales the contact law through 1/E* = Q1 + Q2; omit it for a rigid
E1 = 2e11                   # striker (or write "inf"); Pa
nu1 = 0.25

[half_space]                # the body struck, meshed by the FEM
E2 = 7.5e6                  # Pa
nu2 = 0.5                   # in [0, 0.5]; 0.5 (incompressible) is exact: mixed u-p elements
#   density2 = 1100.0       # kg/m^3: only with [layer] dynamic = true (default 1100)
#   prony = "0.3:1e-3"      # a viscoelastic body (g1:tau1,...; with [contact] rate) is refused:
                            # its force depends on the pressing's history, so no impact follows
                            # from its curve; run shtaerman contact --prony --rate, or kind =
                            # "dynamic" with [half_space] prony for the impact

[impact]                    # quasi-static theory, stated valid below about 4-5 m/s
mass = 0.7                  # kg
velocity = 3.0              # m/s

[contact]
depths = "impact"           # 8 depths up to the impact's x_c (contact radii a_c/3 .. a_c),
                            # or a list of at least 2 increasing depths in m, e.g. [1e-3, 2e-3]
# interface = "bonded"      # the rubber sticks to the indenter (default "frictionless"); the
                            # force then departs from Shtaerman's by physics (nu2 < 0.5): the
                            # departures are reported, the checks are the exponent, the no-slip
                            # identity and the tabulated impact against the fitted one
#   friction = 0.5          # with "bonded": Coulomb's mu >= 0, a point slides where its shear
                            # exceeds mu x its pressure (default none: no slip)
#   rate = 0.1              # pressing speed (m/s) of a viscoelastic body: only with prony

[tolerances]                # relative errors that decide PASS or FAIL (these are the defaults)
force = 1e-3                # FEM force against Shtaerman's P(x), worst over the depths
beta = 1e-3                 # fitted beta (exponent held at the theory's)
exponent = 1e-3             # freely fitted exponent q = (n+1)/n
contact_radius = 1e-2
central_pressure = 1e-2
impact = 2e-3               # x_c, P_c, t_c of the two FEM-fed impacts against the exact one
identity = 3e-3             # bonded on nu2 < 0.5: P (n+1)/(2 E* a d n) against Mossakovskii's
                            # chi(nu2), plus the ladder's force and contact-radius estimates

# [numerics]                # mesh controls relative to the contact zone (defaults shown)
# refine = 1.0              # divide the whole mesh size field by K (dofs ~ K^2)
# mesh_size = 0.006667      # smallest element / refined radius (1/150)
# domain_factor = 1e5       # domain radius / refined radius, in [1e2, 1e7]
# growth = 0.25             # element growth away from the contact zone
# mesh_margin = 1.25        # refined radius / largest contact radius, > 1
# axis_size = 1e-6          # element size at the axis / refined radius, in (0, 1]
# axis_growth = 0.1         # element size growth away from the axis, in (0, 1]
# max_dofs = 400000         # refuse a mesh estimated above this many unknowns
# [quick]                   # 'verify --quick': takes the [numerics] keys

# [convergence]             # a mesh-convergence study: sizes refine the whole mesh, decreasing
# sizes = [0.01887, 0.01333, 0.00943]   # (--quick runs the coarsest three)

# [layer]                   # a pad of thickness H on a rigid base instead of the half-space
# thickness_ratio = 5.0     # H / a_c (a_c: the half-space contact radius at x_c), or
#                           # thickness = 0.02 (m)
# base = "bonded"           # or "lubricated" (free to slide on the base)
# dynamic = false           # true: also the dynamic impact on the pad, its restitution (~5 s)

# [sweep]                   # run the study once per value of ONE of these parameters (each
# velocity = [1.0, 2.0, 3.0]  # m/s; each run's name gets the value), or instead:
#   shape_coefficient = [2.0, 5.0]   # m^(1-n)
#   exponent = [1.5, 2.0]
#   sphere_radius = [0.01, 0.02]    # m (with [indenter] sphere_radius)
#   mass = [0.5, 1.0]               # kg
#   thickness = [0.01, 0.02]        # m (with [layer])
#   thickness_ratio = [2.0, 5.0]    # H / a_c (with [layer])
"""
"""The contact study template (the default kind)."""

DYNAMIC_TEMPLATE = """\
# A shtaerman dynamic study (TOML): the dynamic FE impact (inertia and elastic waves) against
# the quasi-static model, over the approach velocity. Run it with
#     shtaerman verify {file} --quick    # coarse settings, no error estimates, seconds
#     shtaerman verify {file}            # with the error estimates, a minute or so
# SI units everywhere. As written it is the paper's striker on rubber; edit the numbers to
# your case. The keys are the command line's options in snake_case (--density2 is density2,
# --time-steps is time_steps). Only the tables indenter, half_space and impact are required;
# an unknown key is an error naming file and key.
kind = "dynamic"

# name = "{name}"           # the study's name in reports and folders; default: the file name
description = "z = 5 r^(3/2) rigid striker, 0.7 kg, on rubber, over v0 (edit me)"

{indenter}
                            # this file (not with prony: the viscoelastic body is the power
                            # law's)

[half_space]                # the body struck, with its inertia
E2 = 7.5e6                  # Pa
nu2 = 0.5                   # in [0, 0.5]
density2 = 1100.0           # kg/m^3 (natural rubber; the quasi-static theory neglects it);
                            # 0: a massless body (no waves)
# prony = "0.3:1e-3"        # a viscoelastic body: shear relaxation g1:tau1,g2:tau2,... (tau
                            # in s; E2, nu2 its instantaneous values; default none: elastic);
                            # or "Einf;E1:tau1,..." (Pa), a .csv file, or a shipped rubber
                            # "zhermack-elite-double-32" (E2 = 2.912e6, nu2 = 0.45,
                            # density2 = 1134); check it: shtaerman prony-plot SERIES --out f.png

[impact]
mass = 0.7                  # kg
velocity = [1.0, 2.0, 3.0]  # m/s: one value or an increasing list
# figure_velocity = 2.0     # m/s: the velocity of the figures (default: the middle one)
# interface = "bonded"      # the rubber sticks to the striker (default "frictionless")
#   friction = 0.5          # with "bonded": Coulomb's mu >= 0 (default none: no slip)

# [rubber]                  # the body's material model
# model = "linear"          # the default: small strain; or a rubber at finite strain:
#   model = "neo-hookean"   # or "mooney-rivlin", "yeoh", "gent"
                            # (its [numerics] and [quick] take time_steps, mesh_size and
                            # refine only; defaults 100 steps, 50 massless, its own mesh)
#   mooney_ratio = 0.1      # mooney-rivlin: r = C01 / (C10 + C01), in [0, 1)
#   yeoh = [-0.101, 0.0127] # yeoh: C20/C10, C30/C10
#   gent_limit = 30.0       # gent: Jm, the limit of I1 - 3
#   volumetric = "quadratic"  # for nu2 < 0.5: K/2 (J-1)^2, or "logarithmic" K/2 (ln J)^2

# [layer]                   # a pad of thickness H on a rigid base instead of the half-space
# thickness = 0.02          # m, or instead
#   thickness_ratio = 5.0   # H / a_c (a_c: the half-space contact radius at the figure's x_c)
# base = "bonded"           # or "lubricated" (free to slide on the base; linear model only)
#   dynamic = false         # a contact study's key: refused here (a dynamic study is one)

# [numerics]                # the dynamic FEM's controls (defaults shown)
# refine = 1.0              # divide the mesh sizes and the time step by K after the others
# time_steps = 200          # time steps per quasi-static impact duration t_y
# mesh_size = 0.025         # smallest element / refined radius
# mesh_margin = 1.3         # refined radius / quasi-static contact radius
# domain_factor = 1e4       # domain radius / refined radius
# growth = 0.2              # element growth away from the contact zone
# axis_size = 0.00125       # element size at the axis / refined radius
# layer_rate = 0.0          # absorbing-layer damping rate x t_y (0: none on the half-space)
# layer_start = 0.75        # where the absorbing layer starts, R_a / (c_s t_y), > 1/2
# layer_width = 3.0         # width of its damping bump / (c_s t_y)
# layer_ramp = 1.0          # ramp length / (c_s t_y) of a layer without a width
# tail = 1.25               # stepping after separation, in R_a / c_R (0: no tail)
# spectral_radius = 0.9     # generalized-alpha rho_inf in [0, 1]

[quick]                     # 'verify --quick': takes the [numerics] keys, and velocity
time_steps = 60             # (default: the smallest and the figure's velocity, m/s)
mesh_size = 0.05
# velocity = [1.0, 2.0]

# [tolerances]              # pass or fail (these are the defaults)
# energy_balance = 1e-2     # |energy balance error| / (M v0^2 / 2), every step
# reflected = 1e-2          # energy reflected back to the contact / radiated energy
# estimate = 0.2            # |measured loss / first-order estimate - 1| ...
# estimate_below = 0.08     # ... where the first-order estimate is below this

# [sweep]                   # with a prony and density2 > 0: one study per loss, named
# loss = ["waves", "hysteresis", "both"]  # <name>-<loss> (waves: no prony; hysteresis:
                            # the massless body; both: as written)
"""
"""The dynamic study template."""

FINITE_TEMPLATE = """\
# A shtaerman finite-strain study (TOML): a neo-Hookean half-space at finite strain against
# Shtaerman's linear solution, and what it does to the impact. Run it with
#     shtaerman verify {file} --quick    # one coarse mesh, no error estimates, seconds
#     shtaerman verify {file}            # three meshes with error estimates, a few minutes
# SI units everywhere. As written it is the paper's striker on rubber; edit the numbers to
# your case. The keys are the command line's options in snake_case. Only the tables
# indenter, half_space and impact are required; an unknown key is an error naming file and key.
kind = "finite-strain"

# name = "{name}"           # the study's name in reports and folders; default: the file name
description = "z = 5 r^(3/2) rigid striker, 0.7 kg at 3 m/s, on neo-Hookean rubber (edit me)"

{indenter}
                            # this file

[half_space]                # the small-strain constants of the neo-Hookean solid
E2 = 7.5e6                  # Pa
nu2 = 0.5                   # in [0, 0.5]

[impact]
mass = 0.7                  # kg
velocity = 3.0              # m/s

[contact]                   # the depths: equal steps up to reach x_c after a few tiny ones
reach = 1.1                 # deepest depth / the linear impact's x_c, in [1, 3]
depth_steps = 12            # equal depth steps up to it
small_ratio = 0.01          # x/a of the first, tiny depth (the small-strain limit)
small_steps = 5             # geometric depths from it to the first equal step
# interface = "bonded"      # the rubber sticks to the striker (default "frictionless"); the
                            # same-mesh linear FEM takes it too
#   friction = 0.5          # with "bonded": Coulomb's mu >= 0 (default none: no slip)

# [layer]                   # a pad of thickness H on a bonded rigid base instead of the
# thickness = 0.02          # half-space: m, or instead
#   thickness_ratio = 5.0   # H / a_c (a_c: the linear contact radius at the impact's x_c)
#   base = "bonded"         # the only base at finite strain (u = 0 at z = -H)

# [numerics]                # the finest mesh of the error-estimate ladder (defaults shown)
# refine = 1.0              # divide the whole mesh size field by K
# mesh_size = 0.016667      # smallest element / refined radius (1/60)
# ladder = "nested"         # instead: one gmsh mesh at K/2 refined twice, K the middle level
                            # (estimates fall back far less often; about 4x the time)
# mesh_margin = 1.25        # refined radius / largest contact radius, > 1
# domain_factor = 1e5       # domain radius / refined radius, in [1e2, 1e7]
# growth = 0.3              # element growth away from the contact zone
# axis_size = 1e-6          # element size at the axis / refined radius
# axis_growth = 0.15        # element size growth away from the axis
# max_dofs = 400000         # refuse a mesh estimated above this many unknowns
# [quick]                   # 'verify --quick': takes the [numerics] keys (but ladder), and
# depth_steps = 6           # coarser depths
# small_steps = 2
# small_ratio = 0.02        # x/a of the first, tiny depth
# small_strain = 2e-2       # the small-strain tolerance on the quick mesh

# [tolerances]              # pass or fail (these are the defaults)
# small_strain = 5e-3       # |P / P_Shtaerman - 1| at the first, tiny depth
# small_strain_fem = 2e-3   # |P / P_linear-FEM - 1| there, on the same mesh
# identity = 3e-3           # bonded on nu2 < 0.5 (Shtaerman's is no reference there): the
                            # linear FEM's P (n+1)/(2 E* a d n) / chi(nu2) - 1, deepest depth
# conservation = 2e-3       # |integral of P dx / stored energy - 1|
# newton = 1e-6             # Newton's relative residual
# complementarity = 1e-6    # contact complementarity

# [rubber]                  # the rubber model (default "neo-hookean")
# model = "yeoh"            # or "mooney-rivlin", "gent"
# yeoh = [-0.101, 0.0127]   # C20/C10, C30/C10 (Treloar's natural rubber)
#   mooney_ratio = 0.1      # mooney-rivlin: r = C01 / (C10 + C01), in [0, 1)
#   gent_limit = 30.0       # gent: Jm, the limit of I1 - 3
#   volumetric = "quadratic"  # for nu2 < 0.5: K/2 (J-1)^2, or "logarithmic" K/2 (ln J)^2

# [corrections]             # dynamic impacts: do the wave and finite-strain corrections add?
# velocities = [1.0, 3.0]   # m/s (minutes per velocity)
# density2 = 1100.0         # kg/m^3, the rubber's

# [sweep]                   # run the study once per value of ONE of these parameters (each
# nu2 = [0.5, 0.3]          # run's name gets the value), or instead:
#   mass = [0.5, 1.0]       # kg
#   velocity = [1.0, 3.0]   # m/s
#   model = ["neo-hookean", "yeoh"]
#   volumetric = ["quadratic", "logarithmic"]
"""
"""The finite-strain study template."""

EFFECTS_TEMPLATE = """\
# A shtaerman effects study (TOML): the effect table of one impact, which effect (the pad, the
# waves, finite strain, viscoelasticity, friction) moves P_max, x_max, t_contact and e away
# from the paper's quasi-static values (as 'shtaerman effects --out' writes it). Run it with
#     shtaerman verify {file} --quick    # no error bars, seconds
#     shtaerman verify {file}            # each run with its error bar
# SI units everywhere; the keys are those of a dynamic study.
kind = "effects"

# name = "{name}"           # the study's name in reports and folders; default: the file name
description = "z = 5 r^(3/2) rigid striker, 0.7 kg at 3 m/s, on a rubber pad (edit me)"

{indenter}
                            # this file (a prony series is then dropped: its
                            # theory is the power law's)

[half_space]                # the body struck
E2 = 7.5e6                  # Pa
nu2 = 0.5                   # in [0, 0.5]
density2 = 1100.0           # kg/m^3; > 0: the waves are an effect (0: massless)
# prony = "0.3:1e-3"        # viscoelasticity: g1:tau1,... (tau in s; default none)

[impact]
mass = 0.7                  # kg
velocity = 3.0              # m/s
# interface = "bonded"      # friction as an effect (default "frictionless")
#   friction = 0.5          # with "bonded": Coulomb's mu >= 0 (default none: no slip)

# [rubber]                  # finite strain as an effect
# model = "linear"          # the default; or a rubber at finite strain:
#   model = "neo-hookean"   # or "mooney-rivlin", "yeoh", "gent"
#   mooney_ratio = 0.1      # mooney-rivlin: r = C01 / (C10 + C01), in [0, 1)
#   yeoh = [-0.101, 0.0127] # yeoh: C20/C10, C30/C10
#   gent_limit = 30.0       # gent: Jm, the limit of I1 - 3
#   volumetric = "quadratic"  # for nu2 < 0.5, or "logarithmic"

[layer]                     # the pad as an effect (leave the table out: the half-space)
thickness = 0.02            # m, or instead
#   thickness_ratio = 5.0   # H / a_c (a_c: the half-space contact radius at x_c)
# base = "bonded"           # or "lubricated"
#   dynamic = false         # a contact study's key: refused here

[numerics]                  # every run's numerics (defaults: each run's own)
mesh_size = 0.1             # smallest element / refined radius
time_steps = 100            # time steps per quasi-static impact duration t_y
# refine = 1.0              # divide the mesh sizes and the time step by K
# estimate = true           # each run's error bar (3-level ladder)
# mesh_margin = 1.3         # refined radius / quasi-static contact radius
# domain_factor = 1e4       # domain radius / refined radius
# growth = 0.2              # element growth away from the contact zone
# layer_rate = 0.0          # absorbing-layer damping rate x t_y

[quick]                     # 'verify --quick': takes the [numerics] keys (default: no estimate)
mesh_size = 0.2
time_steps = 50
"""
"""The effects study template."""

TEMPLATES = {
    kind: template.format(indenter=INDENTER.rstrip(), file="{file}", name="{name}")
    for kind, template in (
        ("contact", STUDY_TEMPLATE),
        ("dynamic", DYNAMIC_TEMPLATE),
        ("finite-strain", FINITE_TEMPLATE),
        ("effects", EFFECTS_TEMPLATE),
    )
}
"""Study kind -> its commented template (the rigid striker's [indenter] written once)."""


def register(commands: argparse._SubParsersAction) -> None:
    """Add the ``init-study`` subcommand."""
    p = commands.add_parser(
        "init-study",
        help="write a commented template study (TOML) to edit and verify",
        description=(
            "Write a commented template study of a kind: the paper's worked example with every\n"
            "key explained. Edit it, then run 'shtaerman verify FILE.toml --quick'."
        ),
    )
    p.add_argument("file", type=path_text, metavar="FILE.toml", help="the study file to write")
    p.add_argument(
        "--kind",
        default="contact",
        choices=tuple(TEMPLATES),
        help="the study's kind: the static FEM contact, the dynamic FE impact, the "
        "finite-strain contact, or the effect table of an impact",
    )
    add_inputs(p, ("force",), None)
    p.set_defaults(handler=run)


def write_template(path: Path, *, force: bool = False, kind: str = "contact") -> Path:
    """Write the template of study ``kind`` (:data:`TEMPLATES`) to ``path`` (a new file unless
    ``force``); returns it.

    The file appears whole or not at all: it is written beside ``path`` and renamed into place,
    so a write cut short (a full disk, a file-size limit) leaves the file there untouched.

    Raises
    ------
    shtaerman.validation.InputError
        If ``kind`` has no template, or ``path`` does not end in .toml, exists (without
        ``force``), is not a regular file, or cannot be written.
    """
    if kind not in TEMPLATES:
        raise InputError(f"kind must be one of {sorted(TEMPLATES)}, got {kind!r}")
    shown = display_path(path)
    if path.suffix != ".toml":
        raise InputError(f"FILE must end in .toml, got '{shown}'")
    if path.is_symlink() or (path.exists() and not path.is_file()):
        raise InputError(f"'{shown}' exists and is not a regular file; pick another FILE")
    text = TEMPLATES[kind].format(file=shown, name=display_path(Path(path.stem)))
    try:
        with staged_file(path, force=force, option="FILE") as stage:
            stage.write_text(text, encoding="utf-8")
    except OSError as error:
        raise InputError(f"cannot write '{shown}': {error.strerror or error}") from None
    return path


def display_path(path: Path) -> str:
    """``path`` as printable text: bytes that are not UTF-8 in its name shown as ``\\xff``."""
    return os.fsencode(path).decode("utf-8", "backslashreplace")


def run(args: argparse.Namespace) -> int:
    """Write the template and say how to run it."""
    path = display_path(write_template(Path(args.file), force=args.force, kind=args.kind))
    print(f"wrote {path}: edit it, then run 'shtaerman verify {path} --quick'")
    return 0
