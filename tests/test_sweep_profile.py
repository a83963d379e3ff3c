"""A sphere and a tabulated profile in the dynamic and contact sweeps (issue 29):
``sphere_radius`` (m, an axis or fixed) or ``profile`` (a CSV relative to the sweep file,
fixed) in place of shape_coefficient and exponent, one profile per case, checked at load.

The runs use the coarse dynamic settings of tests/test_profile_study.py (time_steps 60,
mesh_size 0.05: 1-3 s a case) and a coarse contact mesh (mesh_size 0.05, about 3 s)."""

from __future__ import annotations

import re
from pathlib import Path

import numpy as np
import pytest

import shtaerman as sh
from shtaerman.sweep.engine import execute_case
from shtaerman.sweep.kinds import KINDS, _indenter
from shtaerman.sweep.spec import SweepError, load_sweep, parse_sweep

SWEEP = """name = "ball"
kind = "{kind}"
[parameters]
{parameters}
[axes]
{axes}
"""
BODY = sh.Material(7.5e6, 0.5, 1100.0)  # the dynamic kind's defaults


def _sweep(parameters: str, axes: str, kind: str = "dynamic", path: Path | None = None):
    text = SWEEP.format(kind=kind, parameters=parameters, axes=axes)
    if path is None:
        return parse_sweep(text)
    path.write_text(text)
    return load_sweep(path)


def test_a_sphere_sweep_of_the_dynamic_kind_is_sh_dynamic_on_each_case():
    spec = _sweep("time_steps = 60\nmesh_size = 0.05", "sphere_radius = [0.01, 0.02]")
    for case in spec.cases():
        # one profile per case: the power law's default keys are not the case's striker
        assert case.params["shape_coefficient"] is None and case.params["exponent"] is None
        row = execute_case(KINDS["dynamic"].case, case.index, case.params)
        assert row["status"] == "ok", row["error"]
        ball = sh.SphereIndenter(case.axis_values["sphere_radius"])
        result = sh.dynamic(
            ball, BODY, mass=0.7, velocity=3.0, time_steps=60, mesh_size=0.05, estimate=False
        )
        out = row["outputs"]
        # the same deterministic FE run and the same Sneddon quadrature: equal to round-off
        for key in ("x_max", "P_max", "t_x_max", "t_contact", "restitution"):
            assert out[key] == pytest.approx(result.dynamic[key], rel=1e-12), key
        for key in ("energy_radiated_fraction", "energy_balance_error"):
            assert out[key] == pytest.approx(result.dynamic[key], rel=1e-12), key
        for key in ("x_c", "P_c", "t_c"):
            assert out[key] == pytest.approx(result.quasi_static[key], rel=1e-12), key
            short = key[0]
            expected = result.differences[key]
            assert out[f"difference_{short}"] == pytest.approx(expected, rel=1e-12), key
        estimate = result.radiation_estimate["energy_fraction"]  # the sphere's estimate
        assert out["estimate_energy_fraction"] == pytest.approx(estimate, rel=1e-12)
        assert out["dofs"] == result.mesh["dofs"]


def test_a_sphere_case_of_the_contact_kind_is_sh_contact():
    spec = _sweep("mesh_size = 0.05", "sphere_radius = [0.01]", kind="contact")
    (case,) = spec.cases()
    row = execute_case(KINDS["contact"].case, case.index, case.params)
    assert row["status"] == "ok", row["error"]
    curve = sh.contact(sh.SphereIndenter(0.01), sh.Material(7.5e6, 0.5), mesh_size=0.05)
    document = curve.to_dict()
    out = row["outputs"]
    # the same FE curve; a sphere's analytic beta is Sneddon's exact forces fitted as the
    # FEM's are, as the contact command reports it (a sphere has no closed-form beta)
    for key in ("beta_fem", "exponent_fem", "beta_analytic"):
        assert out[key] == pytest.approx(document[key], rel=1e-12), key
    for key in ("force", "beta", "exponent", "contact_radius", "central_pressure"):
        assert out[f"error_{key}"] == pytest.approx(document["errors"][key], rel=1e-12), key


def test_a_profile_csv_is_read_beside_the_sweep_file(tmp_path, monkeypatch):
    r = np.linspace(0.0, 0.05, 201)
    (tmp_path / "tips").mkdir()
    (tmp_path / "sweeps").mkdir()
    tip = np.c_[r, r**2 / 0.02]
    np.savetxt(tmp_path / "tips" / "tip.csv", tip, delimiter=",", header="r,z", comments="")
    monkeypatch.chdir(tmp_path / "tips")  # not the sweep file's folder
    path = tmp_path / "sweeps" / "s.toml"
    spec = _sweep('profile = "../tips/tip.csv"', "mass = [0.7, 1.0]", path=path)
    # the path is made absolute at load, so a worker in another folder finds the same file
    assert spec.parameters["profile"] == str((tmp_path / "tips" / "tip.csv").resolve())
    for case in spec.cases():
        indenter = _indenter(case.params)
        assert indenter.kind == "tabulated"
        np.testing.assert_array_equal(indenter.radii, r)


@pytest.mark.parametrize(
    ("parameters", "axes", "says"),
    [
        ("exponent = 2.0", "sphere_radius = [0.01]", "axes.sphere_radius: one striker profile"),
        ("", "sphere_radius = [0.01]\nexponent = [2.0]", "axes.sphere_radius: one striker"),
        (
            'sphere_radius = 0.01\nprofile = "tip.csv"',
            "mass = [0.7]",
            "parameters.sphere_radius: one striker profile per case",
        ),
        ('profile = "no.csv"', "mass = [0.7]", "parameters.profile: cannot read"),
        ("", 'profile = ["tip.csv"]', "axes.profile: a tabulated profile is fixed"),
        ("", "sphere_radius = [0.01, -1.0]", "axes.sphere_radius[1] must lie in (0, 1e6] m"),
        ("sphere_radius = 2e6", "mass = [0.7]", "parameters.sphere_radius must lie in"),
        ("profile = 3.0", "mass = [0.7]", "parameters.profile must be a file path"),
    ],
)
def test_a_bad_striker_profile_is_refused_at_load_naming_its_key(parameters, axes, says):
    with pytest.raises(SweepError, match=r"^<sweep>: ") as error:
        _sweep(parameters, axes)
    assert says in str(error.value)


def test_the_contact_kind_refuses_two_profiles_too():
    with pytest.raises(SweepError, match=r"parameters\.sphere_radius: one striker profile"):
        _sweep("sphere_radius = 0.01\nshape_coefficient = 3.0", "nu2 = [0.5]", kind="contact")


def test_a_sphere_driven_past_its_radius_is_refused_before_any_run():
    """R = 5 mm at 0.7 kg and 3 m/s on the paper's rubber: Sneddon's x_c = 9.88 mm = 2 R. The
    FE's ball ends at its equator (a flat rim beyond): the run reached the rim and failed at
    the refined zone's edge after the work; now refused at load and before the FE run: the
    case is recorded refused (a validity limit, issue 28 item 4; the whole sweep was refused
    until session 57), and a sweep of that case alone is refused whole."""
    from shtaerman.validation import InputError

    says = "sphere_radius: 0.7 kg at 3 m/s drive the striker to about 0.00988 m, beyond the"
    spec = _sweep("", "sphere_radius = [0.005, 0.01]")
    assert list(spec.refused) == [0] and says in spec.refused[0]
    with pytest.raises(SweepError, match=re.escape("case 0 (sphere_radius = 0.005): ")) as error:
        _sweep("", "sphere_radius = [0.005]")
    assert says in str(error.value)
    api = says.replace("sphere_radius:", "SphereIndenter(radius=...):")  # the API's field
    with pytest.raises(InputError, match=re.escape(api)):
        sh.dynamic(sh.SphereIndenter(0.005), BODY, mass=0.7, velocity=3.0, estimate=False)
