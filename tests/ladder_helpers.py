"""A contact-ladder level made to fail, for the tests of what a failed level leaves."""


def failing_level(monkeypatch, failing: int) -> None:
    """Make the ``failing``-th level run (1 = the coarsest) of the contact ladder fail as an
    unsettled load step does."""
    from shtaerman.fem.contact.constraints import unsettled
    from shtaerman.study.contact import accuracy

    real, calls = accuracy.run_indentation, []

    def run(*args, **kwargs):
        calls.append(1)
        if len(calls) == failing:
            raise unsettled(0.005, 16)
        return real(*args, **kwargs)

    monkeypatch.setattr(accuracy, "run_indentation", run)
