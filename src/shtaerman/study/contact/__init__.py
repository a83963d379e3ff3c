"""The contact kind: linear FEM frictionless contact against Shtaerman's exact solution."""
