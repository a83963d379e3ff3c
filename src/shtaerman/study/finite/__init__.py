"""The finite-strain kind: neo-Hookean contact against Shtaerman, and the impact on it."""
