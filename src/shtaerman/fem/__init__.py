"""Finite-element contact on an axisymmetric elastic half-space."""
