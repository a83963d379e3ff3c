"""User-facing words found by session 64's new-user trials (task words65): each message speaks
the words of the route it is read on, names what it is about, and says it once."""

from shtaerman.cli.dynamic import ladder_rows


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
