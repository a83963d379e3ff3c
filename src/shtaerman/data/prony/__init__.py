"""Shipped rubbers' Prony series, one CSV file each (:mod:`shtaerman.theory.prony_sources`)."""
