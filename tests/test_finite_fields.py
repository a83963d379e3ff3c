"""The fields of a rubber's impact (``dynamic --model ... --out``): the solution of the steps
nearest 0.5, 1 and 1.5 t_c as VTU files, the finite contact's fields (output/finite.py)."""

from __future__ import annotations

import csv
import re

import meshio
import numpy as np
import pytest

from shtaerman.fem.contact.finite import NEWTON_TOLERANCE
from shtaerman.fem.finite_dynamic import FiniteImpactSettings
from shtaerman.fem.impact import run_impact
from shtaerman.fem.mesh import MeshSettings
from shtaerman.output.finite import write_impact_fields
from shtaerman.theory.indenter import PowerLawIndenter
from shtaerman.theory.materials import Material

INDENTER = PowerLawIndenter(5.0, 1.5)
RUBBER = Material(7.5e6, 0.5)
MASS, VELOCITY = 0.7, 3.0
COARSE = MeshSettings(size=0.25, domain=1e3, growth=0.5, axis_size=1e-3, axis_growth=0.25)
POINT_DATA = {
    *("displacement [m]", "u_r [m]", "u_z [m]", "mean_pressure [Pa]", "von_mises [Pa]"),
    *("sigma_rr [Pa]", "sigma_zz [Pa]", "sigma_tt [Pa]", "sigma_rz [Pa]"),
}
"""The point data of the finite contact's field_max_depth.vtu (output/export.py)."""


def _axis_depth(path):
    """-u_z (m) of the surface point on the axis, and the point data of the VTU at ``path``."""
    mesh = meshio.read(path)
    top = int(np.argmin(np.hypot(mesh.points[:, 0], mesh.points[:, 1])))
    assert mesh.points[top, 0] == 0.0 and mesh.points[top, 1] == 0.0
    return -float(mesh.point_data["u_z [m]"][top]), mesh.point_data


def _check_fields(folder, t, x):
    """Each VTU of ``folder`` at a step of the history (t, x): the axis follows the striker."""
    paths = sorted(folder.glob("field_*_t*s.vtu"))
    assert len(paths) == 3  # 0.5, 1 and 1.5 t_c
    for index, path in enumerate(paths):
        actual = float(re.search(r"_t(.+)s\.vtu$", path.name).group(1))
        k = int(np.argmin(np.abs(t - actual)))
        assert t[k] == pytest.approx(actual, rel=1e-6)  # the name's 7 digits
        depth, data = _axis_depth(path)
        assert set(data) == POINT_DATA
        # gap f(u_r = 0) - X - u_z >= 0 on the axis to the Newton's correction tolerance
        # (NEWTON_TOLERANCE x depth): a surface that lags the leaving striker lies deeper
        assert depth >= x[k] * (1.0 - NEWTON_TOLERANCE)
        if index == 1:  # at maximum compression the axis is in contact: gap 0, linear in
            # u_z, so the last Newton update leaves it at the correction tolerance
            assert depth == pytest.approx(x[k], rel=NEWTON_TOLERANCE)
        for name in POINT_DATA:
            assert np.all(np.isfinite(data[name])), name
        assert np.max(data["von_mises [Pa]"]) > 0.1 * RUBBER.youngs_modulus  # strained


def test_api_massless_rubber_writes_its_fields(monkeypatch, tmp_path):
    import shtaerman as sh
    import shtaerman.fem.finite_dynamic as finite_dynamic

    monkeypatch.setattr(finite_dynamic, "IMPACT_MESH", COARSE)
    out = tmp_path / "run"
    sh.dynamic(
        INDENTER,
        RUBBER,
        mass=MASS,
        velocity=VELOCITY,
        model="neo-hookean",
        density=0.0,
        time_steps=50,
        estimate=False,
        out=out,
    )
    with open(out / "history.csv", newline="") as stream:
        rows = list(csv.DictReader(stream))
    t = np.array([float(row["t [s]"]) for row in rows])
    x = np.array([float(row["x [m]"]) for row in rows])
    _check_fields(out, t, x)
    # the second is at maximum compression: within half a step of t_c (50 steps per t_y)
    middle = sorted(out.glob("field_1_t*s.vtu"))[0]
    actual = float(re.search(r"_t(.+)s\.vtu$", middle.name).group(1))
    assert abs(actual - _quasi().t_c) <= 0.5 * _quasi().t_y / 50


def _quasi():
    import shtaerman as sh

    return sh.impact(INDENTER, RUBBER, mass=MASS, velocity=VELOCITY)


@pytest.mark.parametrize(("density", "friction"), [(1100.0, None), (0.0, 0.5)])
def test_rubber_with_inertia_or_friction_keeps_its_fields(tmp_path, density, friction):
    settings = FiniteImpactSettings(steps=20, mesh=COARSE)
    t_c = _quasi().t_c
    times = (0.5 * t_c, t_c, 1.5 * t_c)
    run = run_impact(
        INDENTER,
        RUBBER,
        density,
        MASS,
        VELOCITY,
        settings,
        friction=friction,
        snapshot_times=times,
    )
    assert run.kept is not None and sorted(run.kept.states) == list(times)
    write_impact_fields(run, INDENTER, RUBBER, "neo-hookean", tmp_path)
    _check_fields(tmp_path, run.t, run.x)
