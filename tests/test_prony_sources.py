"""A Prony series in either convention (weights g_i or moduli E_i), from a CSV file or a shipped
rubber's name (:mod:`shtaerman.theory.prony_sources`), and the FE impact on the shipped silicone."""

import contextlib
import importlib.util
import io
from fractions import Fraction
from pathlib import Path

import pytest

from shtaerman.cli import main
from shtaerman.fem.dynamic_contact import DynamicSettings
from shtaerman.fem.impact import run_impact
from shtaerman.study.schema import find_study, load_study
from shtaerman.theory.contact import PowerLawContact
from shtaerman.theory.indenter import PowerLawIndenter
from shtaerman.theory.materials import RIGID, Material, effective_modulus
from shtaerman.theory.prony_sources import (
    prony_from_csv,
    prony_from_moduli,
    prony_input,
    shipped_rubber,
)
from shtaerman.theory.viscoelastic import PronySeries, viscoelastic_impact
from shtaerman.validation import InputError

NAME = "zhermack-elite-double-32"
E_INF = "1.196"  # MPa, the source's values (as decimal strings, for exact fractions)
E_I = ("0.477", "0.328", "0.221", "0.157", "0.113", "0.127", "0.114", "0.077", "0.059", "0.043")
TAU = (4.99e-8, 4.83e-7, 3.55e-6, 1.72e-5, 6.04e-5, 2.28e-4, 1.33e-3, 9.07e-3, 6.42e-2, 4.89e-1)


def test_shipped_silicone_is_the_sources_series():
    """E0 = 1.196 + 1.716 = 2.912 MPa and g_i = E_i/E0, to the last bit of the exact fractions."""
    rubber = shipped_rubber(NAME)
    e0 = Fraction(E_INF) + sum(Fraction(e) for e in E_I)
    assert e0 == Fraction("2.912")
    assert rubber.youngs_modulus == pytest.approx(2.912e6, rel=1e-15)  # fsum of decimals in Pa
    for g, e in zip(rubber.series.weights, E_I, strict=True):
        assert g == pytest.approx(float(Fraction(e) / e0), rel=1e-15)  # one rounding each
    assert rubber.series.times == TAU
    assert rubber.series.g_inf == pytest.approx(1.196 / 2.912, rel=1e-14)  # 1 - sum: cancellation
    assert (rubber.poisson_ratio, rubber.density) == (0.45, 1134.0)
    assert "NOT verified" in rubber.provenance and "Albertini" in rubber.provenance
    assert shipped_rubber(NAME).series == rubber.series == prony_input(NAME)


def test_moduli_and_weights_convert_both_ways():
    """g -> E -> g and E -> g -> E return the input (rounding only)."""
    series, e0 = prony_from_moduli(1.196e6, tuple(float(e) * 1e6 for e in E_I), TAU)
    relaxed, moduli = series.g_inf * e0, tuple(g * e0 for g in series.weights)
    assert relaxed == pytest.approx(1.196e6, rel=1e-14)  # via 1 - sum g_i: a few roundings
    assert moduli == pytest.approx([float(e) * 1e6 for e in E_I], rel=1e-15)
    again, e0_again = prony_from_moduli(relaxed, moduli, TAU)
    assert e0_again == pytest.approx(e0, rel=1e-15)
    assert again.weights == pytest.approx(series.weights, rel=1e-14)


def test_moduli_text_and_csv_give_the_shipped_series(tmp_path):
    """The three user forms of the same rubber: ``Einf;E1:tau1,...``, a CSV of E, a CSV of g."""
    shipped = shipped_rubber(NAME).series
    text = "1.196e6;" + ",".join(f"{e}e6:{t}" for e, t in zip(E_I, TAU, strict=True))
    assert prony_input(text).weights == pytest.approx(shipped.weights, rel=1e-15)
    moduli = tmp_path / "e.csv"
    rows = "".join(f"{t},{e}e6\n" for e, t in zip(E_I, TAU, strict=True))
    moduli.write_text("# a comment\ntau [s], E [Pa]\ninf,1.196e6\n" + rows)
    assert prony_from_csv(moduli)[0].weights == pytest.approx(shipped.weights, rel=1e-15)
    weights = tmp_path / "g.csv"
    rows = "".join(f"{t!r},{g!r}\n" for g, t in zip(shipped.weights, TAU, strict=True))
    weights.write_text("tau,g\n" + rows)
    assert prony_input(str(weights)) == shipped


@pytest.mark.parametrize(
    ("text", "message"),
    [
        ("tau,G\n1e-3,0.5\n", "header must be 'tau [s],E [Pa]' or 'tau [s],g [1]'"),
        ("tau,g\n1e-3,half\n", "f.csv: line 2, column g must be a number, got 'half'"),
        ("tau,E\ninf,1e6\nsoon,1e6\n", "f.csv: line 3, column tau must be a number"),
        ("tau,E\n1e-3,1e6\n", "an E column needs exactly one row with tau = inf (E_inf), got 0"),
        ("tau,g\ninf,0.5\n", "a g column takes no tau = inf row"),
        ("tau,g\n1e-3,0.5,1\n", "f.csv: line 2: 3 cells where the header has 2"),
        ("tau,g\n1e-3\n", "f.csv: line 2: 1 cell where the header has 2"),
        ("tau,g\n-1e-3,0.5\n", "f.csv: line 2, column tau: must be > 0 s, got -0.001"),
        ("tau,E\ninf,1e6\n1e-3,-5\n", "f.csv: line 3, column E: must be a finite number >= 0 Pa"),
    ],
)
def test_csv_errors_name_row_and_column(tmp_path, text, message):
    path = tmp_path / "f.csv"
    path.write_text(text)
    with pytest.raises(InputError, match=r"^prony") as raised:
        prony_input(str(path))
    assert message in str(raised.value) and "\n" not in str(raised.value)


def test_cli_refuses_an_unknown_rubber_in_one_line():
    err = io.StringIO()
    with contextlib.redirect_stderr(err), contextlib.redirect_stdout(io.StringIO()):
        code = main(["dynamic", "--prony", "zhermack-elite-double-23"])
    assert code == 2
    lines = err.getvalue().strip().splitlines()
    assert len(lines) == 1 and "--prony" in lines[0] and NAME in lines[0]


def test_fe_impact_on_the_silicone_is_tings():
    """The massless FE (100 steps per t_y, size 1/20) with all ten terms against Ting's exact
    impact. Five terms relax within one FE step (tau_1..5 <= 6e-5 s, the step ~1.5e-4 s): the
    recursive convolution integrates each exactly for a strain linear over the step, so no
    term is lumped or dropped, and the FE meets Ting as closely as with slow terms only."""
    indenter, rubber = PowerLawIndenter(5.0, 1.5), Material(2.912e6, 0.5)
    series = shipped_rubber(NAME).series
    fe = run_impact(
        indenter, rubber, 0.0, 0.7, 3.0, DynamicSettings(steps=100, size=0.05), prony=series
    )
    law = PowerLawContact(indenter, effective_modulus(RIGID, rubber))
    exact = viscoelastic_impact(0.7, 3.0, law, series)
    # measured 4e-5 (e) and 3e-4 (P_max); dropping the five fast terms into the relaxed
    # modulus moves e by 2.6e-3, so 5e-4 tells a lumped or mishandled fast term apart
    assert fe.restitution == pytest.approx(exact.restitution, abs=5e-4)
    assert fe.P_max == pytest.approx(exact.P_max, rel=2e-3)
    assert fe.x_max == pytest.approx(exact.x_max, rel=1e-3)


def test_silicone_study_runs_the_shipped_rubber():
    """fem/extended/silicone.toml: the shipped series with its own E0, nu and density."""
    rubber = shipped_rubber(NAME)
    waves, hysteresis, both_ = load_study(find_study("silicone"))
    assert (waves.prony, hysteresis.density) == (None, 0.0)
    assert hysteresis.prony == both_.prony == rubber.series
    assert both_.half_space.youngs_modulus == rubber.youngs_modulus
    assert (both_.half_space.poisson_ratio, both_.density) == (0.45, rubber.density)
    assert both_.prony_text == NAME


def _silicone_map():
    path = Path(__file__).parents[1] / "benchmarks" / "silicone_map.py"
    spec = importlib.util.spec_from_file_location("silicone_map", path)
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def test_silicone_map_crosses_between_half_and_one_metre_per_second():
    """benchmarks/silicone_map.py, steel ball R = 10 mm: hysteresis (exact, Ting) outweighs the
    first-order waves at 0.464 m/s (ratio 0.81), the waves outweigh it at 1 m/s (1.26); the
    quick FE study (fem/extended/silicone.toml) agrees in order: 0.085 waves against 0.137
    hysteresis at 0.3 m/s, 0.166 against 0.142 at 1 m/s."""
    module = _silicone_map()
    slow, fast = (module.row(0.01, v, steps=100) for v in (0.464, 1.0))
    # the ratio's step-halving error is ~3e-6 / 0.15 at 400 steps, 16 times that at 100
    assert slow["ratio"] == pytest.approx(0.81, abs=0.01)
    assert fast["ratio"] == pytest.approx(1.26, abs=0.01)
    assert module.crossing([slow, fast]) == pytest.approx(0.672, rel=0.01)


def test_study_reads_a_csv_beside_it(tmp_path, monkeypatch):
    """A study's relative ``prony = "rubber.csv"`` is the file beside the study, wherever the
    command runs."""
    folder = tmp_path / "studies"
    folder.mkdir()
    (folder / "rubber.csv").write_text("tau [s],g [1]\n2e-3,0.5\n")
    text = find_study("silicone").read_text()
    text = text.replace('prony = "zhermack-elite-double-32"', 'prony = "rubber.csv"')
    (folder / "mine.toml").write_text(text.replace('name = "silicone"', 'name = "mine"'))
    monkeypatch.chdir(tmp_path)
    *_, both_ = load_study(folder / "mine.toml")
    assert both_.prony == PronySeries((0.5,), (2e-3,)) and both_.prony_text == "rubber.csv"


@pytest.mark.parametrize("text", [",".join(["0.06:1e-3"] * 21), "1e6;" + ",".join(["1e5:1"] * 21)])
def test_a_series_of_too_many_terms_is_refused_by_its_count_first(text):
    # 21 terms of g 0.06 also break sum g < 1 (1.26): the count is named, before any parsing
    with pytest.raises(InputError, match=r"^prony: 21 terms is too many \("):
        prony_input(text)


def test_a_csv_of_too_many_rows_is_refused_before_the_rest_is_parsed(tmp_path, monkeypatch):
    # user62b: a million-row file was parsed whole (10.5 CPU s) before its count was refused;
    # now only the first MAX_PRONY_TERMS + 3 rows are read. The 22 rows of an E column with
    # 20 terms and its tau = inf row pass
    import shtaerman.theory.prony_sources as sources

    many = tmp_path / "many.csv"
    many.write_text("tau,g\n" + "".join(f"{1e-3 * (1 + k)},1e-8\n" for k in range(10_000)))
    parsed = []
    number = sources._number
    monkeypatch.setattr(sources, "_number", lambda *a: parsed.append(a) or number(*a))
    with pytest.raises(InputError, match=r"^prony: many\.csv: more than 20 terms \("):
        prony_input(str(many))
    assert len(parsed) <= 2 * 22  # two cells of at most 22 rows parsed, not 20,000
    twenty = tmp_path / "twenty.csv"
    twenty.write_text("tau,E\ninf,1e6\n" + "".join(f"{1e-3 * (1 + k)},1e4\n" for k in range(20)))
    assert len(prony_input(str(twenty)).weights) == 20
