"""A layer pressed deeper than its thickness: linear elasticity answers, but the run says that
the strain is beyond 100 % (an adversary found restitution 1.0098 there, printed without
comment)."""

import pytest

import shtaerman as sh

PAPER = sh.PowerLawIndenter(5.0, 1.5)


def test_contact_deeper_than_the_layer_warns():
    body = sh.Material(7.5e6, 0.5)
    with pytest.warns(UserWarning, match="reaches the layer's thickness 2e-05 m"):
        sh.contact(PAPER, body, depths=[5e-5, 1e-4], thickness=2e-5, estimate=False, mesh_size=0.05)


def test_dynamic_approach_beyond_the_layer_warns():
    body = sh.Material(7.5e6, 0.5, density=1100.0)
    with pytest.warns(UserWarning, match="reaches the layer's thickness 0.00013 m"):
        sh.dynamic(
            PAPER,
            body,
            mass=0.7,
            velocity=3.0,
            thickness=1.3e-4,
            estimate=False,
            mesh_size=0.2,
            time_steps=50,
        )
