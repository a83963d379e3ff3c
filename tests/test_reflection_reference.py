"""One reference for the reflected energy on every route (session 67).

The linear body on the half-space states its reflected energy as a fraction of the radiated
energy 1 - e^2; a pad's (the rise after separation) and the rubber's (kinetic energy beyond half
its domain) are fractions of M v0^2/2. The API, the command line and the studies named and
checked them by the geometry alone, so a rubber on the half-space was read as "of the radiated",
and a study's pad likewise: a reflection of 0.03 of M v0^2/2 from a run that radiated 0.002 was
multiplied by 0.002, found below NEGLIGIBLE_REFLECTION (1e-4) and passed, where the CLI failed it.
"""

from types import SimpleNamespace

import shtaerman as sh
from shtaerman.api.dynamic_result import check_failures
from shtaerman.study.dynamic.loader import DynamicTolerances, reflection_reference
from shtaerman.study.dynamic.runner import _checks

PAPER = sh.PowerLawIndenter(shape_coefficient=5.0, exponent=1.5)
RUBBER = sh.Material(7.5e6, 0.5, 1100.0)
# 0.03 of M v0^2/2 back, 3x the default tolerance 1e-2; 0.002 radiated, so read as a share of
# the radiated it would be 6e-5 of M v0^2/2, below NEGLIGIBLE_REFLECTION (1e-4): counted as none
RUN = SimpleNamespace(
    energy_balance_error=0.0, reflected_energy_fraction=0.03, energy_radiated_fraction=0.002
)


def test_the_reference_follows_the_measure():
    assert reflection_reference(layered=False, finite=False) == "the radiated"
    assert reflection_reference(layered=True, finite=False) == "M v0^2/2"
    assert reflection_reference(layered=False, finite=True) == "M v0^2/2"


def test_a_rubber_on_the_half_space_is_checked_of_m_v0_squared():
    problem = sh.Problem.impact(PAPER, RUBBER, mass=0.7, velocity=3.0, model="neo-hookean")
    rubber_run = SimpleNamespace(**vars(RUN), mesh={}, rubber={"model": "neo-hookean"})
    (failure,) = check_failures(rubber_run, problem)
    assert "reflected energy 3.0e-02 of M v0^2/2 exceeds 0.01" in failure


def test_a_pad_study_checks_what_the_command_line_checks():
    study = SimpleNamespace(
        tolerances=DynamicTolerances(),
        finite=False,
        density=1100.0,
        prony=None,
        geometry=SimpleNamespace(thickness=0.02),
    )
    case = SimpleNamespace(velocity=3.0, result=RUN)
    reflected = [c for c in _checks(study, [case]) if c.name.startswith("reflected")]
    assert [c.passed for c in reflected] == [False]
