"""shtaerman: FEM cross-check of Shtaerman's power-law contact and the impact it implies."""

__version__ = "0.1.0"
