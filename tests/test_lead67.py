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


def test_a_first_order_fraction_above_one_is_not_called_a_share_of_the_energy():
    # adv67: "radiates an estimated 10.7 of its energy as waves": z = 8 r^4, 0.12 kg at 1.5 m/s
    # on 3 MPa rubber (nu2 0.49, 1000 kg/m^3) has lambda 10.7, beyond what first order holds
    import pytest

    import shtaerman as sh

    striker = sh.PowerLawIndenter(shape_coefficient=8.0, exponent=4.0)
    rubber = sh.Material(youngs_modulus=3e6, poisson_ratio=0.49, density=1000.0)
    with pytest.raises(sh.LimitError) as refused:
        sh.dynamic(striker, rubber, mass=0.12, velocity=1.5, estimate=False)
    said = str(refused.value)
    assert "would radiate 10.7 times its energy as waves to first order" in said, said
    assert "radiates an estimated" not in said
