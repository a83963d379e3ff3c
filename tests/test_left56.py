"""Session 56's leftovers of the adversary pass (issue 28): refusals in the command line's
words, a resilience curve's E2, the FE fits' default striker, sh.fit's data named in Python."""

import itertools

import numpy as np
import pytest

import shtaerman as sh
from shtaerman.cli import main
from shtaerman.theory.contact import PowerLawContact
from shtaerman.theory.materials import effective_modulus
from shtaerman.theory.viscoelastic import PronySeries, viscoelastic_impact
from shtaerman.validation import InputError

INDENTER = sh.PowerLawIndenter(shape_coefficient=5.0, exponent=1.5)
RUBBER = sh.Material(7.5e6, 0.5)
STEEL = sh.Material(2e11, 0.25)
STEPS = 40
"""Viscoelastic steps per t_c, of the data and the fit alike: the round trip is exact."""


def test_contact_names_refine_in_its_advice(capsys):
    """`contact --refine 0.1` advised "use refine >= 0.25", the keyword, not the option."""
    assert main(["contact", "--refine", "0.1"]) == 2
    assert capsys.readouterr().err == (
        "shtaerman: error: --refine 0.1 scales the mesh growth to 2.5 > 1; use --refine 0.25 "
        "or more with these settings\n"
    )
    with pytest.raises(InputError, match=r"; use refine=0.25 or more with these settings$"):
        sh.contact(INDENTER, RUBBER, depths=[1e-3], refine=0.1)


@pytest.mark.parametrize(
    ("argv", "said"),
    [
        (["contact", "--prony", "0.3:1e-3", "--rate", "0.01", "--accuracy", "1e-3"],
         "on a viscoelastic body use --refine, whose"),
        (["dynamic", "--sphere-radius", "0.001"],
         "lower --velocity to at most 0.118 m/s or --mass to at most 0.00108 kg or raise "
         "--sphere-radius to at least 0.00865 m"),
    ],
)  # fmt: skip
def test_other_advice_names_the_options(capsys, argv, said):
    """Both said the keywords (refine; mass or velocity) as plain words on the command line."""
    assert main(argv) == 2
    err = capsys.readouterr().err
    assert said in err and err.count("\n") == 1, err


def _resilience(velocities):
    law = PowerLawContact(INDENTER, effective_modulus(STEEL, RUBBER))
    series = PronySeries((0.3,), (2e-3,))
    runs = [viscoelastic_impact(0.7, v, law, series, steps=STEPS) for v in velocities]
    return {"velocity": velocities, "resilience": [r.restitution**2 for r in runs]}


def _case(E2=5e6, prony="0.3:2e-3"):
    return sh.Problem.impact(INDENTER, sh.Material(E2, 0.5), mass=0.7, velocity=3.0,
                             striker=STEEL, prony=prony)  # fmt: skip


def test_a_resilience_curve_gives_e2_only_with_the_relaxation_times_known():
    """The curve sees E2 through t_c / tau (t_c ~ (M / E*)^(n/(2n+1))): with tau known, E2
    comes back; with tau (or the mass) free as well, neither is identifiable, from measured
    (noisy) data and from exact ones: the model declares the trade (Model.trades), which the
    Jacobian's rank test alone missed on exact data (singular values 1.6e-8 apart, above its
    tolerance 1e-9: E2 5.60 MPa [5.57, 5.63] against the true 7.5, 'identifiable')."""
    data = _resilience([0.5, 1.0, 2.0, 3.0, 4.0])
    alone = sh.fit("resilience", data, _case(), unknowns="E2", steps=STEPS).fitted["E2"]
    assert alone["identifiable"] and alone["low"] < 7.5e6 < alone["high"]
    assert alone["value"] == pytest.approx(7.5e6, rel=1e-6)  # the same model both ways
    noise = 1.0 + 0.01 * np.random.default_rng(0).standard_normal(5)  # 1 %, as measured
    noisy = {**data, "resilience": np.asarray(data["resilience"]) * noise}
    for measured, other in itertools.product((noisy, data), ("tau1", "mass")):
        unknowns = "E2,tau" if other == "tau1" else "E2,mass"
        both = sh.fit("resilience", measured, _case(), unknowns=unknowns, steps=STEPS).fitted
        assert not both["E2"]["identifiable"] and not both[other]["identifiable"]


def test_a_fit_with_nothing_identifiable_reports_it_not_a_traceback():
    """Three resiliences the model cannot follow left E2 not identifiable, and the step-error
    refit then held every parameter: ValueError 'need at least one array to concatenate'."""
    data = {"velocity": [1.0, 2.0, 3.0], "resilience": [0.6, 0.62, 0.65]}
    result = sh.fit("resilience", data, _case(7.5e6), unknowns="E2", steps=STEPS)
    assert not result.fitted["E2"]["identifiable"]
    assert result.fitted["E2"]["high"] / result.fitted["E2"]["low"] > 1e7  # E*'s 1e4 span


def test_the_default_striker_of_an_fe_fit_is_rigid_a_given_one_is_refused(tmp_path, capsys):
    """A 500 MPa rubber on a 20 mm pad was refused by default: the FE curves press a rigid
    striker and the default steel one's compliance (0.0033 of the rubber's) exceeded their
    error (0.0012). Unset, E1 is now the FE runs' rigid striker, as in contact and dynamic;
    given, it is still refused where the FE runs would drop it."""
    depths = np.linspace(1e-4, 4e-3, 20)
    force = PowerLawContact(INDENTER, 1e9).force(depths)
    path = tmp_path / "ind.csv"
    rows = "\n".join(f"{x:.17g},{p:.17g}" for x, p in zip(depths, force, strict=True))
    path.write_text(f"depth [m],force [N]\n{rows}\n")
    argv = ["fit", "indentation", str(path), "--thickness", "0.02"]
    assert main([*argv, "--json"]) == 0
    assert main([*argv, "--E1", "2e11"]) == 1
    err = capsys.readouterr().err.splitlines()[-1]
    assert err.startswith("shtaerman: error: --E1 2e+11: the FE contact curves press a rigid")
    # without FE runs the exact model keeps the default steel striker: E* = 1e9 Pa exactly
    assert main(["fit", "indentation", str(path), "--json"]) == 0
    fitted = __import__("json").loads(capsys.readouterr().out)["fitted"]["E2"]["value"]
    assert effective_modulus(STEEL, sh.Material(fitted, 0.5)) == pytest.approx(1e9, rel=1e-9)


def test_sh_fit_names_its_data_keyword_and_index():
    """sh.fit said 'DATA: cannot read' (the CLI's argument) and named a mapping's first value
    'row 2' (a CSV file's numbering under its header)."""
    with pytest.raises(InputError, match=r"^data: cannot read 'nope\.csv'") as error:
        sh.fit("indentation", "nope.csv", sh.Problem.curve(INDENTER, RUBBER))
    assert error.value.parameter == "data"
    bad = {"depth": [np.nan, 1e-3, 2e-3], "force": [1.0, 2.0, 3.0]}
    with pytest.raises(InputError, match=r"^data: index 0: column 'depth' must be > 0, got nan"):
        sh.fit("indentation", bad, sh.Problem.curve(INDENTER, RUBBER))


def test_the_cli_still_names_its_data_argument(tmp_path, capsys):
    assert main(["fit", "indentation", str(tmp_path / "nope.csv")]) == 2
    assert capsys.readouterr().err.startswith("shtaerman: error: DATA: cannot read ")
