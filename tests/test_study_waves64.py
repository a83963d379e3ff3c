"""A dynamic study of several velocities refused at load for the waves named the density that
passes its first velocity only (session 63's user: a z = 5 r^10 table at 0.0029 and 0.0045 m/s
named 4.79e-5 kg/m^3, which the 0.0045 m/s case refuses in turn). The faster impact radiates
the more (lambda ~ v0^((3q - 3)/(q + 1)), q > 1), so the loader checks it first, and the density
it names passes every velocity of the study."""

import re

import numpy as np
import pytest

from shtaerman.study.schema import StudyError, load_study


def _study(tmp_path, density: float, velocities: str):
    radius = np.linspace(0.0, 0.2, 200)
    table = "r,z\n" + "".join(f"{r:.8e},{5.0 * r**10:.8e}\n" for r in radius)
    (tmp_path / "tip10.csv").write_text(table)
    path = tmp_path / "s.toml"
    path.write_text(
        'kind = "dynamic"\n[indenter]\nprofile = "tip10.csv"\n'
        f"[half_space]\nE2 = 7.5e6\nnu2 = 0.5\ndensity2 = {density!r}\n"
        f"[impact]\nmass = 0.7\nvelocity = [{velocities}]\n"
    )
    return path


def _named_density(path) -> float:
    with pytest.raises(StudyError) as caught:
        load_study(path)
    said = str(caught.value)
    assert "key 'half_space.density2'" in said, said
    return float(re.search(r"density2 (\S+) kg/m\^3 would pass", said)[1])


def test_the_density_a_study_is_told_passes_every_velocity(tmp_path):
    both = _named_density(_study(tmp_path, 1100.0, "0.0029, 0.0045"))
    assert both == _named_density(_study(tmp_path, 1100.0, "0.0045"))  # the faster's remedy
    assert both < _named_density(_study(tmp_path, 1100.0, "0.0029"))  # the slower's is heavier
    load_study(_study(tmp_path, both, "0.0029, 0.0045"))  # and it loads: each passes


def test_a_tables_end_refusal_with_inertia_names_the_density_its_remedies_need(tmp_path):
    """The same table at 0.01 m/s on 1100 kg/m^3 rubber: beyond its last radius, the refusal
    named 0.00462 m/s or 0.149 kg, each of which the waves' limit then refused (their first-
    order radiated fractions 22.9 and 49.7, above 0.0045): it names the density that passes
    both, and each remedy passes the FE impact's checks there."""
    from shtaerman.fem.dynamic_contact import DynamicSettings, check_dynamic_impact
    from shtaerman.fem.impact import check_impact_reach
    from shtaerman.theory.materials import Material
    from shtaerman.theory.profiles import TabulatedIndenter
    from shtaerman.validation import InputError

    _study(tmp_path, 1100.0, "0.01")  # writes the table
    table, rubber = TabulatedIndenter.from_csv(tmp_path / "tip10.csv"), Material(7.5e6, 0.5)
    with pytest.raises(InputError) as caught:
        check_impact_reach(table, rubber, 1100.0, (0.7, 0.01), False)
    said = str(caught.value)
    slower = float(re.search(r"velocity=\.\.\. to at most (\S+) m/s", said)[1])
    lighter = float(re.search(r"mass=\.\.\. to at most (\S+) kg", said)[1])
    density = float(re.search(r"density2 at most about (\S+) kg/m\^3 passes both", said)[1])
    assert (slower, lighter) == (0.00462, 0.149), said  # the table's own remedies, as before
    for impact in ((0.7, slower), (lighter, 0.01)):  # at 1100 kg/m^3 the waves refuse each
        check_dynamic_impact(table, rubber, density, *impact, DynamicSettings())  # passes
