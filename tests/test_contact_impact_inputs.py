"""The contact JSON (and text) names the impact whose x_c its default depths reach."""

import shtaerman as sh
from shtaerman.cli.contact import contact_text

INDENTER = sh.PowerLawIndenter(12.0, 1.8)
RUBBER = sh.Material(4e6, 0.49)
COARSE = {"estimate": False, "mesh_size": 0.05, "domain_factor": 1e4}


def test_the_json_carries_the_mass_and_velocity_that_set_the_depths():
    c = sh.contact(INDENTER, RUBBER, mass=0.25, velocity=2.0, **COARSE)
    document = c.to_dict()
    keys = list(document)
    assert keys[keys.index("nu2") + 1 : keys.index("nu2") + 3] == ["mass", "velocity"]
    assert (document["mass"], document["velocity"]) == (0.25, 2.0) == (c.mass, c.velocity)
    assert "; depths up to the x_c of M = 0.25 kg at 2 m/s" in contact_text(document)


def test_given_depths_carry_no_impact():
    c = sh.contact(INDENTER, RUBBER, depths=[2e-3], **COARSE)
    assert c.mass is None and "mass" not in c.to_dict() and "velocity" not in c.to_dict()
    assert "x_c of M" not in contact_text(c.to_dict())
