"""Session 67's small fixes found by the adversary's trial (adv67)."""

from shtaerman.sweep.cli import _cases


def test_one_case_is_not_cases():
    # adv67: a one-case sweep reported "sweep s (impact): 1 cases, 1 ok, ..."
    assert [_cases(n) for n in (0, 1, 2)] == ["0 cases", "1 case", "2 cases"]


def test_the_api_names_a_striker_field_at_the_head_of_a_refusal():
    # adv67: sh.impact's equator refusal began "sphere_radius: ...", a name the API has not
    # (the field is SphereIndenter(radius=...)); the parameter attribute keeps the input's name
    import pytest

    import shtaerman as sh

    with pytest.raises(sh.InputError) as refused:
        sh.impact(sh.SphereIndenter(radius=1e-4), sh.Material(7.5e6, 0.5), mass=0.7, velocity=3.0)
    said = str(refused.value)
    assert said.startswith("SphereIndenter(radius=...): the striker's energy"), said
    assert "raise SphereIndenter(radius=...) to at least" in said
    assert refused.value.parameter == "sphere_radius"
