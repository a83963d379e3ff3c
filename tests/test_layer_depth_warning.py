"""A layer pressed deeper than its thickness: a contact curve is linear elasticity's answer and
warns that the strain is beyond 100 %; an impact through its pad is refused (an adversary found
restitution 1.0098 there, printed without comment)."""

import pytest

import shtaerman as sh
from shtaerman.validation import bound_text

PAPER = sh.PowerLawIndenter(5.0, 1.5)


def test_contact_deeper_than_the_layer_warns():
    body = sh.Material(7.5e6, 0.5)
    with pytest.warns(UserWarning, match="reaches the layer's thickness 2e-05 m"):
        sh.contact(PAPER, body, depths=[5e-5, 1e-4], thickness=2e-5, estimate=False, mesh_size=0.05)


@pytest.mark.filterwarnings("ignore::shtaerman.guards.FailedCheckWarning")  # mesh 0.2, 50 steps
def test_an_impact_through_the_layer_is_refused_naming_what_runs():
    """0.7 kg at 3 m/s onto a 0.13 mm pad went through it with a warning (task words65: a
    15 m/s pad study passed so); the striker would pass through the pad. The remedies bring the
    half-space's x_c (13.58 mm, sh.impact; an upper bound of the pad's approach, the pad being
    the stiffer body) below the thickness: v0 (H / x_c)^(4/3), M (H / x_c)^(8/3), q = 5/3."""
    body = sh.Material(7.5e6, 0.5, density=1100.0)
    case = dict(thickness=1.3e-4, estimate=False, mesh_size=0.2, time_steps=50)
    with pytest.raises(sh.LimitError) as refused:
        sh.dynamic(PAPER, body, mass=0.7, velocity=3.0, **case)
    said = str(refused.value)
    assert said.startswith("mass, velocity: 0.7 kg at 3 m/s drive the striker to 0.000"), said
    assert ", through the layer's thickness 0.00013 m: the striker would pass through" in said
    x_c = sh.impact(PAPER, sh.Material(7.5e6, 0.5), mass=0.7, velocity=3.0).x_c
    slower = bound_text(3.0 * (1.3e-4 / x_c) ** (4 / 3), "high")
    lighter = bound_text(0.7 * (1.3e-4 / x_c) ** (8 / 3), "high")
    assert said.endswith(
        f"lower velocity=... to at most {slower} m/s or mass=... to at most {lighter} kg (there "
        "the half-space's quasi-static depth, which bounds the pad's, is within it)"
    ), said
    result = sh.dynamic(PAPER, body, mass=0.7, velocity=float(slower), **case)
    assert result.x_max < 1.3e-4  # the velocity named runs within the pad
