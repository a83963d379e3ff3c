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
