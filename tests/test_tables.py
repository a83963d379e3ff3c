"""The paper's tables regenerated: which printed entries hold, and which do not (and why)."""

import pytest

from shtaerman.paper.comparison import compare_tables


@pytest.fixture(scope="module")
def tables():
    return {table.name: table for table in compare_tables()}


def test_every_printed_ateb_value_is_the_exact_one_rounded(tables):
    # Tables 1 and 2: every printed 10 Sa, 10 Ca is the exact value to two decimals
    for name, column in (("table1", "sine"), ("table2", "cosine")):
        cells = [c for _, cells in tables[name].rows for c in cells if c.column == column]
        assert len(cells) == 30
        assert not [c for c in cells if c.flagged]


def test_only_the_bracket_at_eta_08_misses_its_formula(tables):
    # the paper's formula puts eta = 0.8 in its last branch (7.43); it printed the quadratic
    # branch's 7.42: the one approximation entry off by more than half a unit
    flagged = tables["table1"].flagged
    assert [(key, cell.column) for key, cell in flagged] == [(8.0, "sine_approximation")]
    assert flagged[0][1].exact == pytest.approx(7.4268918, abs=1e-6)
    assert not tables["table2"].flagged


def test_approximation_error_claim_is_measured(tables):
    # "error less than one percent": measured 0.654 % (sine) and 0.645 % (cosine)
    assert "max 0.654 %" in tables["table1"].summary[1]
    assert "max 0.645 %" in tables["table2"].summary[1]


def test_table3_numerical_column_agrees_with_exact(tables):
    numerical = [
        c for _, cells in tables["table3"].rows for c in cells if c.column.endswith("numerical")
    ]
    # Maple's column: within 6e-5 of the exact Sa (its 0.9149 should round to 0.9150)
    assert max(abs(c.printed - c.exact) for c in numerical) < 6e-5
    formulae = [
        c for _, cells in tables["table3"].rows for c in cells if c.column.endswith("formulae")
    ]
    # the paper's linear interpolation in its 2-digit tables: off by up to 4.5e-4
    assert max(abs(c.printed - c.exact) for c in formulae) == pytest.approx(4.5e-4, abs=1e-5)


def test_impact_tables_agree_to_four_digits(tables):
    for name in ("table4", "table5", "table6"):
        cells = [c for _, cells in tables[name].rows for c in cells]
        # printed to 4-6 significant digits; the worst is p_c at A = 4 (3.5e-4, Table 4)
        assert max(abs(c.relative_difference) for c in cells) < 4e-4


def test_example_misprint_is_caught(tables):
    rows = dict(tables["example"].rows)
    [coefficient] = rows["x_c_coefficient"]
    assert coefficient.flagged and coefficient.exact == pytest.approx(0.0037365, rel=2e-5)
    [duration] = rows["duration_coefficient"]
    # 2.891854 is twice the rounded I; 2 I = 2.8918549
    assert duration.exact == pytest.approx(2.8918549444511, rel=1e-12)
