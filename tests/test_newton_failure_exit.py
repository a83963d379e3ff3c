"""A Newton that fails on valid input is a numerical failure (exit 1, one line naming what to
change), never bad input (exit 2); a Gent rubber locking is the user's gent_limit (exit 2)."""

from __future__ import annotations

from shtaerman.cli import main
from shtaerman.fem.hyperelastic import NewtonError
from shtaerman.fem.rubber import GentLockError
from shtaerman.validation import InputError, NumericalFailureError


def test_a_newton_failure_is_numerical_and_a_gent_lock_is_input():
    assert issubclass(NewtonError, NumericalFailureError)
    assert not issubclass(NewtonError, InputError)
    locked = GentLockError.locking(30.0, (5e-4, 1e-3), 0.9995)
    assert isinstance(locked, InputError) and isinstance(locked, NewtonError)
    assert locked.parameter == "gent_limit"


def test_the_frictionless_finite_curve_that_never_converges_exits_1(monkeypatch, capsys):
    """Every Newton of the curve fails: after its halvings the run stops with exit 1 (it was an
    InputError, exit 2, as if the user's input were wrong)."""
    import shtaerman.fem.contact.finite as finite

    def failing(self, *args, **kwargs):
        raise NewtonError("Newton did not converge in 30 iterations")

    monkeypatch.setattr(finite.NewtonStepper, "solve", failing)
    code = main(["contact", "--model", "neo-hookean", "--no-estimate", "--mesh-size", "0.1"])
    err = capsys.readouterr().err.strip().splitlines()
    assert code == 1, err
    assert len(err) == 1 and "did not converge" in err[0]
    assert "refine the mesh" in err[0] or "--mesh-size" in err[0]


def test_a_gent_rubber_that_locks_still_exits_2(capsys):
    """A Gent limit of 1e-6 locks in the first load step (the stretch of any indentation passes
    it): the user's input, exit 2, naming --gent-limit."""
    argv = ["contact", "--model", "gent", "--gent-limit", "1e-6", "--no-estimate"]
    code = main([*argv, "--mesh-size", "0.2"])
    err = capsys.readouterr().err.strip().splitlines()
    assert code == 2, err
    assert len(err) == 1
    assert err[0].startswith("shtaerman: error: --gent-limit: the Gent rubber locks")
