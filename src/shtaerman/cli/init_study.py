"""``shtaerman init-study FILE.toml``: write a commented template study to start from."""

from __future__ import annotations

import argparse
import os
from pathlib import Path

from ..validation import InputError

__all__ = ["STUDY_TEMPLATE", "register", "run", "write_template"]

STUDY_TEMPLATE = """\
# A shtaerman cross-check study (TOML). Run it with
#     shtaerman verify {file} --quick    # coarse meshes, seconds
#     shtaerman verify {file}            # the accurate meshes, a minute or so
# SI units everywhere. As written it is the paper's worked example (Ol'shanskii et al. 2019,
# section 5); edit the numbers to your case. Every key below except [indenter], [half_space]
# and [impact] is optional; a misspelt or unknown key is an error naming file and key.

# name = "{name}"           # the study's name in reports and folders; default: the file name
description = "z = 5 r^(3/2) steel striker, 0.7 kg at 3 m/s, on rubber (edit me)"

[indenter]                  # the striker's surface near its first contact point: z = A r^n
shape_coefficient = 5.0     # A, m^(1-n)
exponent = 1.5              # n > 1 (n = 2, A = 1/(2R): a sphere of radius R, Hertz)

[striker]                   # scales the contact law through 1/E* = Q1 + Q2; omit it for a rigid
youngs_modulus = 2e11       # striker (or write "inf"); Pa
poisson_ratio = 0.25

[half_space]                # the body struck, meshed by the FEM
youngs_modulus = 7.5e6      # Pa
poisson_ratio = 0.5         # in [0, 0.5]; 0.5 (incompressible) is exact: mixed u-p elements

[impact]                    # quasi-static theory, stated valid below about 4-5 m/s
mass = 0.7                  # kg
velocity = 3.0              # m/s

[contact]
depths = "impact"           # 8 depths up to the impact's x_c (contact radii a_c/3 .. a_c),
                            # or a list of at least 2 increasing depths in m, e.g. [1e-3, 2e-3]

[tolerances]                # relative errors that decide PASS or FAIL (these are the defaults)
force = 1e-3                # FEM force against Shtaerman's P(x), worst over the depths
beta = 1e-3                 # fitted beta (exponent held at the theory's)
exponent = 1e-3             # freely fitted exponent q = (n+1)/n
contact_radius = 1e-2
central_pressure = 1e-2
impact = 2e-3               # x_c, P_c, t_c of the two FEM-fed impacts against the exact one

# [mesh]                    # mesh controls relative to the contact zone (defaults shown)
# size = 0.006667           # smallest element / refined radius (1/150)
# domain = 1e5              # domain radius / refined radius, in [1e2, 1e7]
# growth = 0.25             # element growth away from the contact zone
# [quick_mesh]              # the same keys, for 'verify --quick'

# [convergence]             # a mesh-convergence study: sizes refine the whole mesh, decreasing
# sizes = [0.01887, 0.01333, 0.00943]   # (--quick runs the coarsest three)

# [sweep]                   # run the study once per value of ONE parameter: shape_coefficient,
# velocity = [1.0, 2.0, 3.0]  # exponent, mass or velocity (each run's name gets the value)
"""


def register(commands: argparse._SubParsersAction) -> None:
    """Add the ``init-study`` subcommand."""
    p = commands.add_parser(
        "init-study",
        help="write a commented template study (TOML) to edit and verify",
        description=(
            "Write a commented template study: the paper's worked example with every key\n"
            "explained. Edit it, then run 'shtaerman verify FILE.toml --quick'."
        ),
    )
    p.add_argument("file", metavar="FILE.toml", help="the study file to write")
    p.add_argument("--force", action="store_true", help="replace an existing FILE.toml")
    p.set_defaults(handler=run)


def write_template(path: Path, *, force: bool = False) -> Path:
    """Write :data:`STUDY_TEMPLATE` to ``path`` (a new file unless ``force``); returns it.

    Raises
    ------
    shtaerman.validation.InputError
        If ``path`` does not end in .toml, exists (without ``force``), is not a regular file,
        or cannot be written.
    """
    if path.suffix != ".toml":
        raise InputError(f"FILE must end in .toml, got '{path}'")
    if path.is_symlink() or (path.exists() and not path.is_file()):
        raise InputError(f"'{path}' exists and is not a regular file; pick another FILE")
    text = STUDY_TEMPLATE.format(file=path, name=path.stem)
    mode = "w" if force else "x"
    try:
        with path.open(mode, encoding="utf-8") as stream:
            stream.write(text)
    except FileExistsError:
        raise InputError(f"'{path}' exists; use --force to replace it") from None
    except OSError as error:
        raise InputError(f"cannot write '{path}': {error.strerror or error}") from None
    return path


def run(args: argparse.Namespace) -> int:
    """Write the template and say how to run it."""
    path = write_template(Path(os.fspath(args.file)), force=args.force)
    print(f"wrote {path}: edit it, then run 'shtaerman verify {path} --quick'")
    return 0
