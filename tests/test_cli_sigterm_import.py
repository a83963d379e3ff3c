"""SIGTERM while VTK imports a module lazily: VTK's loader turns the Terminated into an
ImportError, which printed a traceback and exit 1 (an adversary's kill at 4.2 s of
``verify --quick layer``); it is a termination, exit 143 and the usual line."""

import os
import signal
import time

import pytest

import shtaerman.cli as cli


def _killed_inside_an_import(argv):
    try:
        os.kill(os.getpid(), signal.SIGTERM)
        time.sleep(5)
    except BaseException:
        raise ImportError("Failed to load vtkViewsContext2D") from None
    return 0


def test_a_sigterm_hidden_in_an_import_error_is_a_termination(monkeypatch, capsys):
    monkeypatch.setattr(cli, "_run", _killed_inside_an_import)
    assert cli.main(["verify"]) == 143
    assert capsys.readouterr().err.startswith("shtaerman: terminated;")


def test_an_import_error_without_a_sigterm_is_not_hidden(monkeypatch):
    def broken(argv):
        raise ImportError("no module named x")

    monkeypatch.setattr(cli, "_run", broken)
    with pytest.raises(ImportError, match="no module named x"):
        cli.main(["verify"])
