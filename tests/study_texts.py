"""Study-file texts the tests share (TOML)."""

DYNAMIC_STUDY = """\
kind = "dynamic"
[indenter]
shape_coefficient = 5.0
exponent = 1.5
[half_space]
E2 = 7.5e6
nu2 = 0.5
density2 = 1100.0
[impact]
mass = 0.7
velocity = [1.0, 3.0]
figure_velocity = 3.0
"""
"""The paper's striker on rubber at 1 and 3 m/s: the smallest complete dynamic study."""

PAPER_CASE = """\
[indenter]
shape_coefficient = 5.0
exponent = 1.5
[half_space]
E2 = 7.5e6
nu2 = 0.5
[impact]
mass = 0.7
velocity = 3.0
"""
"""The paper's striker, rubber and impact: a contact study without a ``kind`` line."""

FINITE_STUDY = 'kind = "finite-strain"\n' + PAPER_CASE
"""The paper's striker on neo-Hookean rubber: the smallest finite-strain study."""
