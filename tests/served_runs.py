"""FE impact runs served by their inputs: each computed once where a test (or module) runs
the same problem again, on another route or with a level made to fail."""


def served_impacts(patch, runs: dict | None = None):
    """Make ``case.run_impact`` (through ``patch``, a monkeypatch) compute each set of inputs
    once, kept in ``runs``, and return it. Its runs are read, not changed, by the routes; the
    warnings a run gives are given when it is computed, not when it is served."""
    from shtaerman.study.dynamic import case

    runs, real = ({} if runs is None else runs), case.run_impact

    def once(*args, **kwargs):
        key = repr((args, sorted(kwargs.items())))
        if key not in runs:
            runs[key] = real(*args, **kwargs)
        return runs[key]

    patch.setattr(case, "run_impact", once)
    return once
