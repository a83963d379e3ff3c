"""Session 57's words: refusals in the words of the route they came by, and the fit's
promise for an unknown that is not identifiable."""

import numpy as np
import pytest

import shtaerman as sh
from shtaerman.theory.contact import PowerLawContact
from shtaerman.validation import InputError

INDENTER = sh.PowerLawIndenter(shape_coefficient=5.0, exponent=1.5)
RUBBER = sh.Material(7.5e6, 0.5, density=1100.0)
DEPTHS = np.linspace(1e-4, 4e-3, 20)
INDENTATION = {"depth": DEPTHS, "force": PowerLawContact(INDENTER, 1e7).force(DEPTHS)}


def _refine_refusal(route, refine):
    """The refusal of ``refine`` by API entry point ``route``, refused before any mesh."""
    with pytest.raises(InputError) as caught:
        if route == "contact":
            sh.contact(INDENTER, RUBBER, depths=[1e-3, 2e-3], refine=refine)
        elif route == "dynamic":
            sh.dynamic(INDENTER, RUBBER, mass=0.7, velocity=3.0, refine=refine)
        else:
            case = sh.Problem.curve(INDENTER, sh.Material(7.5e6, 0.5))
            sh.fit("indentation", INDENTATION, case, refine=refine)
    assert caught.value.parameter == "refine"
    return str(caught.value)


@pytest.mark.parametrize("route", ["contact", "dynamic", "fit"])
def test_the_api_checks_refine_by_one_call(monkeypatch, route):
    """sh.contact, sh.dynamic and sh.fit each wrote entry("refine").check(validate_positive(
    "refine", ...)); now vocabulary.checked_positive, one call, in the words pinned before
    (a string 'not a string', test_probe56's range)."""
    import shtaerman.api.fem_contact
    import shtaerman.api.fem_dynamic
    import shtaerman.fitting.run
    from shtaerman.vocabulary import checked_positive

    module = {
        "contact": shtaerman.api.fem_contact,
        "dynamic": shtaerman.api.fem_dynamic,
        "fit": shtaerman.fitting.run,
    }[route]
    asked = []

    def spy(name, value):
        asked.append((name, value))
        return checked_positive(name, value)

    monkeypatch.setattr(module, "checked_positive", spy)
    said = _refine_refusal(route, "2")
    assert said == "refine must be a finite number > 0, not a string: got '2'"
    assert _refine_refusal(route, 1e308) == "refine must lie in (0, 1e6], got 1e+308"
    assert ("refine", "2") in asked and ("refine", 1e308) in asked


STEEL = sh.Material(2e11, 0.25)


def test_a_fit_with_no_unknown_identifiable_reports_the_starts():
    """Three resiliences the model cannot follow (test_left56) left E2 not identifiable, and
    it was reported where the search stopped, 9.82e6 Pa, where docs/fit.md promises the start:
    the problem's 7.5e6. Held, the model is drawn there too."""
    case = sh.Problem.impact(INDENTER, sh.Material(7.5e6, 0.5), mass=0.7, velocity=3.0,
                             striker=STEEL, prony="0.3:2e-3")  # fmt: skip
    data = {"velocity": [1.0, 2.0, 3.0], "resilience": [0.6, 0.62, 0.65]}
    result = sh.fit("resilience", data, case, unknowns="E2", steps=40)
    e2 = result.fitted["E2"]
    assert not e2["identifiable"]
    assert e2["value"] == pytest.approx(7.5e6, rel=1e-12)  # E2 -> E* -> E2: a few ulps
    vague = sh.fit("resilience", data, case, unknowns="E2", steps=40, noise=1.0).fitted["E2"]
    assert not vague["identifiable"] and vague["value"] == pytest.approx(7.5e6, rel=1e-12)
    # a 1 % noise makes the same search's point a fit: E2 [4.3, 22.7] MPa, kept where found
    sharp = sh.fit("resilience", data, case, unknowns="E2", steps=40, noise=0.01).fitted["E2"]
    assert sharp["identifiable"] and sharp["value"] == pytest.approx(9.824e6, rel=1e-3)


def _api_refusal(call):
    with pytest.raises(InputError) as caught:
        call()
    return caught.value


@pytest.mark.parametrize("given", ["keywords", "problem"])
def test_the_wave_speed_refusal_names_the_apis_density(capsys, given):
    """sh.dynamic of the paper's striker at 30 m/s (lambda 0.882 > 0.8) said "velocity,
    density2: ... density2 686 kg/m^3 or velocity 21.8 m/s would pass (density2 0: ...)",
    the study key, where the Python user gave sh.Material(density=1100): the API's entry points
    word their refusals once (problem.in_python_words). The command line keeps --density2."""
    from shtaerman.cli import main

    if given == "keywords":
        refused = _api_refusal(lambda: sh.dynamic(INDENTER, RUBBER, mass=0.7, velocity=30.0))
    else:
        case = sh.Problem.impact(INDENTER, RUBBER, mass=0.7, velocity=30.0)
        refused = _api_refusal(lambda: sh.dynamic(case))
    said = str(refused)
    assert said.startswith("velocity, density: 0.7 kg at 30 m/s"), said
    assert "density 686 kg/m^3 or velocity 21.8 m/s would pass (density 0: " in said, said
    assert "density2" not in said and refused.parameter == "velocity"
    assert main(["dynamic", "--velocity", "30"]) == 2
    typed = capsys.readouterr().err
    assert typed.startswith("shtaerman: error: --velocity, --density2: 0.7 kg"), typed


def test_a_fits_density_refusal_names_the_apis_density():
    """sh.fit of an indentation on a body with a density said "density2: ... (leave density2
    unset)", with parameter 'density2', of a keyword sh.fit has none of."""
    case = sh.Problem.curve(INDENTER, RUBBER)
    refused = _api_refusal(lambda: sh.fit("indentation", INDENTATION, case))
    assert str(refused).startswith("density: the FE correction of waves is fitted for"), refused
    assert str(refused).endswith("(leave density unset)") and refused.parameter == "density"


def test_a_fits_warning_still_names_the_callers_line():
    """sh.fit's velocity warning had stacklevel=3, one frame short of the caller once the
    entry point is worded by in_python_words: it names the caller's line
    (validation.caller_stacklevel), as sh.dynamic's failed check does."""
    import warnings

    from shtaerman.theory.impact import QuasiStaticValidityWarning

    case = sh.Problem.impact(INDENTER, sh.Material(7.5e6, 0.5), mass=0.7, velocity=3.0,
                             striker=STEEL, prony="0.3:2e-3")  # fmt: skip
    data = {"velocity": [1.0, 3.0, 6.0], "resilience": [0.6, 0.62, 0.65]}
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        sh.fit("resilience", data, case, unknowns="E2", steps=40)
    fast = [w for w in caught if issubclass(w.category, QuasiStaticValidityWarning)]
    assert fast and {w.filename for w in fast} == {__file__}, [str(w.message) for w in caught]
