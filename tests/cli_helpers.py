"""Helpers of the command-line tests (imported by name, like figure_helpers)."""

from shtaerman.cli import main


def error_line(capsys, *argv):
    """The one error line of a refused command (exit code 2, nothing on stdout)."""
    code = main([str(arg) for arg in argv])
    out, err = capsys.readouterr()
    assert code == 2 and out == "" and err.count("\n") == 1, (code, out, err)
    return err.removeprefix("shtaerman: error: ").strip()
