"""The FE impact's time-step and mesh-size limits and defaults.

Plain numbers in a module of their own: the command line's ``dynamic --help`` states them
without loading the FEM (:mod:`.dynamic_contact` and :mod:`.finite_dynamic` enforce them).
"""

MIN_STEPS = 50
"""Fewest time steps per quasi-static impact duration t_y accepted (the linear body)."""
MAX_SIZE = 0.2
"""Largest smallest-element size of the dynamic mesh, in refined radii."""
FINITE_MIN_STEPS = 20
"""Fewest time steps of a finite-strain impact level."""
MASSLESS_STEPS = 50
"""Default time steps of a massless finite-strain impact."""
INERTIA_STEPS = 100
"""Default time steps of a finite-strain impact with inertia."""
