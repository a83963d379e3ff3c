"""The dynamic kind: the elastodynamic FE impact against the quasi-static impact."""
