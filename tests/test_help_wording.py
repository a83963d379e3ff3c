"""The --help of each command reads right for that command: shared options say nothing of
another command's time steps, study lists or sweeps, and each option states one default."""

import argparse
import re

import pytest

from shtaerman.cli import build_parser


def command_help(name: str) -> str:
    [commands] = [a for a in build_parser()._actions if isinstance(a, argparse._SubParsersAction)]
    return " ".join(commands.choices[name].format_help().split())


def test_contact_help_speaks_of_contact_only():
    text = command_help("contact")
    for foreign in ("time step", "dynamic", "sweep", "takes a list", "richardson"):
        assert foreign not in text, foreign
    mass = text.split("--mass KG", 2)[2].split("--velocity M/S")[0]
    assert "sets the impact whose x_c the default depths reach" in mass
    assert "not with --depths" in mass
    depths = text.split("--depths D1,D2,...", 2)[2].split("--json")[0]
    assert depths.count("(default:") == 1


@pytest.mark.parametrize("name", ["impact", "dynamic"])
def test_velocity_help_of_a_single_run_mentions_no_list(name):
    assert "takes a list" not in command_help(name)


def test_dynamic_help_says_refine_divides_the_time_step_too():
    text = command_help("dynamic")
    assert re.search(r"--refine K divide the whole mesh size field by K: the time step too", text)
    assert "error estimates by Richardson extrapolation" in text
