"""The wave-speed limit of a rubber (nu2 0.45 to 0.499; session 66): its own column,
RUBBER_WAVE_LIMITS, measured (benchmarks/FEM_NOTES.md, "Wave-speed limit on rubber"). z = 8
r^2, 0.12 kg at 1.5 m/s on a 12 mm pad of 3 MPa rubber, nu2 0.49, 1000 kg/m^3 (lambda
0.539) was refused above WAVE_LIMITS' 0.45, which holds for nu2 0 to 0.5, although it runs
cleanly (balance 6.7e-4 of M v0^2/2 on the default mesh)."""

from __future__ import annotations

import json
import re

import pytest

from shtaerman.cli import main
from shtaerman.guards import RUBBER_WAVE_LIMITS, WAVE_LIMITS, wave_limit

USER = ["--exponent", "2", "--shape-coefficient", "8", "--E2", "3e6", "--nu2", "0.49"]
USER += ["--mass", "0.12", "--density2", "1000"]
"""The researcher's striker and rubber (its 12 mm pad: --thickness 0.012)."""
COARSE = ["--mesh-size", "0.1", "--time-steps", "60", "--no-estimate", "--json"]


def _passes(capsys, *argv: str) -> dict:
    """The dynamic results of ``shtaerman dynamic`` with ``argv`` on a coarse mesh, which
    exits 0: both checks passed."""
    code = main(["dynamic", *argv, *COARSE])
    result = json.loads(capsys.readouterr().out)["dynamic"]
    assert code == 0, result  # 2: refused, 1: a check failed
    # a run past the limit is off by 2 to 6 of M v0^2/2 (the chatter): the check's 1e-2
    assert result["energy_balance_error"] < 1e-2, result
    return result


def test_the_rubber_column_is_0_9_of_the_first_failure_measured():
    """FEM_NOTES' table (default mesh, steps of 0.05 in lambda): z = 10 r^2 first failed at
    lambda 0.70, 0.70, 0.65 (nu2 0.45, 0.49, 0.499), z = 20 r^2.5 at 0.55, 0.50, 0.35, z = 50
    r^3 at 0.40, 0.35, 0.25, z = 100 r^3.5 at 0.205 (nu2 0.499, by 0.005 from 0.20). Outside
    nu2 0.45 to 0.499, and for a sphere or a table, the other column (z = 10 r^2 failed from
    0.55 at nu2 0.4999, 0.52 at 0.5, 0.505 at nu2 0; a 10 mm ball pressed to x/a 1.17 on nu2
    0.49 from 0.58)."""
    for nu in (0.45, 0.49, 0.499):
        assert wave_limit(1.5, nu, True) == pytest.approx(0.9 * 0.65, rel=1e-12)
        assert wave_limit(1.4, nu, True) == pytest.approx(0.9 * 0.35, rel=1e-12)
        assert wave_limit(4.0 / 3.0, nu, True) == pytest.approx(0.9 * 0.25, rel=1e-8)  # q rounded
        assert wave_limit(9.0 / 7.0, nu, True) == pytest.approx(0.9 * 0.205, rel=1e-8)
        assert wave_limit(1.5, nu) == 0.45  # a sphere's
    for nu in (0.0, 0.3, 0.449, 0.4999, 0.5):
        assert wave_limit(1.5, nu, True) == 0.45
    qs = [q for q, _ in RUBBER_WAVE_LIMITS]
    assert qs == sorted(qs) and qs[0] == WAVE_LIMITS[0][0]
    for k in range(201):  # the rubber's never below the other's, and monotone in q
        q, after = 1.0 + k / 200, 1.0 + (k + 1) / 200
        assert wave_limit(q, 0.49, True) >= wave_limit(q, 0.49), q
        assert wave_limit(q, 0.49, True) <= wave_limit(after, 0.49, True), q


@pytest.mark.filterwarnings("ignore::UserWarning")
def test_the_researchers_rubber_pad_runs_and_its_faster_impact_names_rubbers_limit(capsys):
    """The 12 mm pad at 1.5 m/s (refused on main, above 0.45) runs with both checks passed;
    at 3 m/s (lambda 0.818: 0.539 (3 / 1.5)^0.6, lambda ~ v0^((3q - 3)/(q + 1)), q = 3/2)
    the refusal quotes the rubber's 0.585 and names a velocity that runs."""
    pad = [*USER, "--thickness", "0.012"]
    result = _passes(capsys, *pad, "--velocity", "1.5")
    # the pad stops the striker before it radiates much: e = 0.998 on the default mesh
    assert result["restitution"] > 0.99, result
    assert main(["dynamic", *pad, "--velocity", "3"]) == 2
    said = capsys.readouterr().err
    assert "estimated 0.818 of its energy as waves (first order), above 0.585 (the limit " in said
    assert "of a force ~ x^1.5 on a rubber, nu2 0.45 to 0.499, lower for blunter" in said
    slower = re.search(r" or velocity (\S+) m/s would pass", said)[1]
    _passes(capsys, *pad, "--velocity", slower)
