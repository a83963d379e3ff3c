"""User-facing words found by session 64's new-user trials (task words65): each message speaks
the words of the route it is read on, names what it is about, and says it once."""

import pytest

from shtaerman.cli.dynamic import ladder_rows
from shtaerman.theory.prony_sources import prony_from_csv
from shtaerman.validation import InputError


def test_the_cli_prints_a_retry_in_options_not_keywords():
    """The text on stdout printed 'time_steps=...' where stderr said '--time-steps'."""
    failure = "the contact did not converge; take more time steps (time_steps=...)"
    report = {
        "retried": f"refine 0.707: 113 steps failed ({failure}); passed with 226 steps",
        "mesh_ladder": [{"dofs": 10, "steps": 80}, {"dofs": None, "steps": 113}],
        "estimate_missing": f"a ladder level failed twice, refine 0.707: {failure}",
    }
    said = "the contact did not converge; take more time steps (--time-steps)"
    assert ladder_rows(report) == [
        f"  retried: refine 0.707: 113 steps failed ({said}); passed with 226 steps",
        f"  no error estimate (ladder 10 dofs/80 steps, failed): a ladder level failed twice, "
        f"refine 0.707: {said}",
    ]


def test_a_prony_files_sum_of_g_names_the_file_and_its_lines(tmp_path):
    """Every other fault of a Prony file named file, line and column; this one said only
    'prony weights must sum to less than 1'. 0.6 + 0.5 is 1.1 exactly in binary (fsum)."""
    path = tmp_path / "f.csv"
    path.write_text("tau [s],g [1]\n# two terms\n1e-3,0.6\n1e-2,0.5\n")
    with pytest.raises(InputError) as raised:
        prony_from_csv(path)
    assert str(raised.value) == (
        "prony: f.csv: column g must sum to less than 1 (relaxed modulus > 0), got "
        "sum g_i = 1.1 over lines 3 to 4"
    )
    assert raised.value.parameter == "prony"
