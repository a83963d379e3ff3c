"""The bonded (no-slip) indenter of the linear FEM contact, against closed forms.

References:
- Mossakovskii (1954), Ufliand; Spence (1968, Proc. R. Soc. A 305): a rigid flat punch bonded
  to a half-space carries chi(nu) = (1 - nu) ln(3 - 4 nu) / (1 - 2 nu) times the frictionless
  force (chi = ln 3 = 1.0986 at nu = 0, 1.0286 at nu = 0.3, -> 1 at nu = 0.5, where the
  bonded force 4 G a d ln(3 - 4 nu) / (1 - 2 nu) tends to the frictionless 8 G a d).
- Under incremental no-slip loading each depth increment is such a bonded flat punch of the
  current radius a (the stuck points keep their displacement), so dP/dd = 2 E* chi a (Borodich
  and Keer, Proc. R. Soc. A 460, 2004: the factor is independent of the punch's shape); for the
  self-similar z = A r^n, P = 2 E* chi a d n / (n + 1) (frictionless: chi = 1, Shtaerman).
  Spence's (1975) Hertz no-slip tables were not at hand: this identity stands in for them.
- nu = 0.5: Dundurs' beta = 0, normal and tangential surface loads uncouple, so the bonded
  contact is the frictionless one.
Coarse meshes; the same mesh for both interfaces, so that the ratios cancel most of the FE
error (nodal sums on both sides).
"""

from __future__ import annotations

import functools
import math

import numpy as np
import pytest

import shtaerman as sh
from shtaerman.cli import main
from shtaerman.fem.contact.constraints import STEP_RATIO
from shtaerman.fem.contact.linear import solve_contact
from shtaerman.fem.contact.stick import solve_bonded_contact
from shtaerman.fem.elasticity import assemble
from shtaerman.fem.mesh import Geometry, MeshSettings
from shtaerman.study.contact.indentation import run_indentation
from shtaerman.theory.indenter import PowerLawIndenter
from shtaerman.theory.materials import Material
from shtaerman.validation import InputError

E2 = 1.0e6
RADIUS = 0.01
COARSE = MeshSettings(size=1.0 / 20.0)


def mossakovskii(nu: float) -> float:
    """Bonded / frictionless force of a rigid flat punch (Mossakovskii 1954, Spence 1968)."""
    return 1.0 if nu == 0.5 else (1.0 - nu) * np.log(3.0 - 4.0 * nu) / (1.0 - 2.0 * nu)


@functools.cache
def _pair(nu: float, exponent: float, step_ratio: float = STEP_RATIO):
    """Frictionless (nodal sums) and bonded curves of z = 5 r^n on one coarse mesh: computed
    once for the module (read, not changed, by its tests; the default step ratio's run of
    nu = 0, n = 2 serves two of them)."""
    indenter = PowerLawIndenter(5.0, exponent)
    depth = 5.0 * RADIUS**exponent
    refined = COARSE.margin * RADIUS
    system = assemble(COARSE.build(refined), E2, nu)
    depths = np.array([depth / 2.0**exponent, depth])
    free = solve_contact(system, indenter.profile, depths, refined, aligned=False)
    stuck = solve_bonded_contact(system, indenter.profile, depths, refined, step_ratio=step_ratio)
    return free, stuck


def test_mossakovskii_closed_form_tends_to_the_frictionless_punch():
    # 4 G a d ln(3 - 4 nu)/(1 - 2 nu) -> 8 G a d = 2 E* a d at nu = 0.5
    nu = 0.5 - 1e-9
    g = E2 / (2 * (1 + nu))
    bonded = 4 * g * np.log(3 - 4 * nu) / (1 - 2 * nu)
    assert bonded == pytest.approx(2 * E2 / (1 - nu**2), rel=1e-6)
    assert mossakovskii(0.0) == pytest.approx(np.log(3.0), rel=1e-15)


@pytest.mark.parametrize("nu", [0.0, 0.3])
def test_bonded_flat_punch_carries_mossakovskii_force(nu):
    refined = 1.5 * RADIUS
    settings = MeshSettings(size=1.0 / 30.0, margin=1.5)
    system = assemble(settings.build(refined), E2, nu)

    def punch(r):
        return np.where(r <= RADIUS * (1 + 1e-9), 0.0, 1.0)

    depths = np.array([1e-5])
    free = solve_contact(system, punch, depths, refined, aligned=False).steps[0].force
    stuck = solve_bonded_contact(system, punch, depths, refined).steps[0].force
    # measured 1.1001 (nu = 0) and 1.0294 (nu = 0.3) at this mesh
    assert stuck / free == pytest.approx(mossakovskii(nu), rel=3e-3)


def test_bonded_equals_frictionless_when_incompressible():
    free, stuck = _pair(0.5, 1.5)
    for f, b in zip(free.steps, stuck.steps, strict=True):
        assert b.force == pytest.approx(f.force, rel=2e-4)  # measured 5e-5
        assert b.contact_radius == pytest.approx(f.contact_radius, rel=5e-4)


def test_compressible_bonded_contact_is_stiffer_by_the_incremental_punch_law():
    nu, n = 0.3, 1.5
    free, stuck = _pair(nu, n)
    e_star = E2 / (1 - nu**2)
    for f, b in zip(free.steps, stuck.steps, strict=True):
        # measured P_b / P_f = 1.0157 (the old, frictionless code gives 1 exactly)
        assert 1.012 < b.force / f.force < 1.020
        assert b.contact_radius < f.contact_radius
        # P = 2 E* chi a d n/(n+1), as a ratio to the same identity of the frictionless FE
        identity = [
            s.force * (n + 1) / (2 * e_star * s.contact_radius * s.depth * n) for s in (f, b)
        ]
        assert identity[1] / identity[0] == pytest.approx(mossakovskii(nu), rel=5e-3)
        assert b.central_pressure > f.central_pressure
        # the shear carried: along +r on the body (outward: it holds the surface from sliding in)
        assert b.tangential_forces.sum() > 0


def test_force_converges_in_the_load_step():
    coarse = _pair(0.0, 2.0, step_ratio=1.2)[1].steps[-1].force
    fine = _pair(0.0, 2.0, step_ratio=1.02)[1].steps[-1].force
    assert coarse == pytest.approx(fine, rel=2e-3)


def test_bonded_fields_carry_the_tangential_load():
    _, stuck = _pair(0.3, 2.0)
    fields = stuck.field_solution(-1)
    step = stuck.steps[-1]
    # with the tangential nodal forces in the load, the surface carries no spurious reaction
    radial = stuck.compliance.radial_dofs
    reactions = stuck.system.matrix @ stuck.solutions[-1]
    assert np.allclose(reactions[radial], step.tangential_forces, atol=1e-9 * step.force)
    assert fields is not None


def test_api_and_cli_take_the_interface(capsys):
    indenter = PowerLawIndenter(5.0, 1.5)
    depth = 5.0 * RADIUS**1.5
    kwargs = dict(depths=[depth / 2, depth], estimate=False, mesh_size=1 / 20)
    bonded = sh.contact(indenter, Material(E2, 0.3), interface="bonded", **kwargs)
    free = sh.contact(indenter, Material(E2, 0.3), **kwargs)
    assert bonded.mesh["interface"] == "bonded" and "interface" not in free.mesh
    assert bonded.force[-1] > 1.01 * free.force[-1]
    sliding = sh.contact(indenter, Material(E2, 0.3), interface="bonded", friction=0.2, **kwargs)
    assert sliding.mesh["friction"] == 0.2 and "friction" not in bonded.mesh
    assert free.force[-1] < sliding.force[-1] < bonded.force[-1]
    argv = ["contact", "--nu2", "0.3", "--interface", "bonded", "--no-estimate"]
    argv += ["--mesh-size", "0.05", "--depths", f"{depth / 2},{depth}"]
    assert main(argv) == 0
    assert "bonded indenter" in capsys.readouterr().out


@pytest.mark.parametrize(
    ("argv", "words"),
    [
        (["--interface", "sticky"], "--interface"),
        (["--interface", "bonded", "--model", "yeoh", "--friction", "-0.3"], "[0, 1e2]"),
        (["--friction", "0.3"], "bonded indenter only"),
        (["--interface", "bonded", "--friction", "-1"], "[0, 1e2]"),
    ],
)
def test_bad_interface_is_one_line_and_exit_2(argv, words, capsys):
    assert main(["contact", *argv]) == 2
    err = capsys.readouterr().err.strip()
    assert words in err and "\n" not in err


def test_bad_interface_in_python():
    indenter = PowerLawIndenter(5.0, 1.5)
    with pytest.raises(InputError, match="interface"):
        sh.contact(indenter, Material(E2, 0.3), interface="sticky")
    with pytest.raises(InputError, match="interface"):
        sh.Interface("Bonded")
    system = _pair(0.3, 1.5)[1].system  # the module's (its run refused before it starts)
    with pytest.raises(InputError, match="step_ratio"):
        solve_bonded_contact(system, indenter.profile, [1e-5], RADIUS, step_ratio=1.0)


def test_bonded_indenter_on_a_layer():
    # a thin layer: the indenter's friction matters even at nu = 0.5 (beta = 0 is a
    # half-space result; a bonded top squeezes the film out less)
    indenter = PowerLawIndenter(5.0, 1.5)
    depth = np.array([5.0 * RADIUS**1.5])
    body = Material(E2, 0.5)
    mesh, layer = MeshSettings(size=1 / 20), Geometry(0.5 * RADIUS)
    forces = [
        run_indentation(indenter, body, depth, mesh, friction=friction, geometry=layer).steps[-1]
        for friction in (None, math.inf)  # frictionless, bonded
    ]
    assert forces[1].force > 1.05 * forces[0].force


STUDY = """
[indenter]
shape_coefficient = 5.0
exponent = 1.5
[half_space]
E2 = 1e6
nu2 = 0.3
[impact]
mass = 0.7
velocity = 3.0
[contact]
depths = [0.0002, 0.0005]
"""


def test_study_file_contact_interface(tmp_path):
    from shtaerman.study.schema import StudyError, load_study

    path = tmp_path / "stuck.toml"
    path.write_text(STUDY + 'interface = "bonded"\n')
    [study] = load_study(path)
    assert study.interface == sh.Interface("bonded")  # both meshes solve it (the runner's)
    path.write_text(STUDY)
    assert load_study(path)[0].interface.kind == "frictionless"
    path.write_text(STUDY + 'interface = "glued"\n')
    with pytest.raises(StudyError, match=r"contact\.interface.*frictionless"):
        load_study(path)
    path.write_text(STUDY + 'interface = "bonded"\nfriction = 0.4\n')
    assert load_study(path)[0].interface.coefficient == 0.4
    path.write_text(STUDY + "friction = 0.4\n")  # said "expected a number >= 0, got 0.4"
    with pytest.raises(StudyError, match=r"contact\.friction': applies to a bonded indenter"):
        load_study(path)
    for bad in ("friction = 0.4", 'interface = "bonded"\nfriction = -1'):
        path.write_text(STUDY + bad + "\n")
        with pytest.raises(StudyError, match="friction"):
            load_study(path)


def test_bonded_ladder_reports_no_true_error():
    # the departure from the frictionless solution is physics, not the FE error
    indenter = PowerLawIndenter(5.0, 1.5)
    depth = 5.0 * RADIUS**1.5
    result = sh.contact(
        indenter,
        Material(E2, 0.3),
        interface="bonded",
        depths=[depth / 2, depth],
        mesh_size=1 / 12,
    )
    assert result.error_estimate["force"] < 1e-2
    assert result.true_error is None and result.effectivity is None


def test_report_estimate_table_without_a_true_error():
    # a bonded study's ladder has no exact solution: the report leaves those cells empty
    from shtaerman.output.text_contact import _estimate_table

    accuracy = {
        "mesh_ladder": [{"dofs": 10}, {"dofs": 20}, {"dofs": 40}],
        "error_estimate": {"force": 1e-3},
        "estimate_details": {"force": {"value": 1.0, "method": "richardson", "reason": ""}},
    }
    [row] = _estimate_table({"accuracy": accuracy})["rows"]
    assert row[2:4] == ["-", "-"]


def test_coulomb_friction_spans_frictionless_to_bonded():
    # mu = 0: every contact node slides freely (the frictionless contact); mu -> inf: no slip
    free, stuck = _pair(0.0, 2.0)
    refined = COARSE.margin * RADIUS
    system, indenter = stuck.system, PowerLawIndenter(5.0, 2.0)
    depths = np.array([step.depth for step in stuck.steps])
    forces = []
    for mu in (0.0, 0.3):
        curve = solve_bonded_contact(system, indenter.profile, depths, refined, friction=mu)
        step = curve.steps[-1]
        # the shear never exceeds mu times the normal force at its node
        shear = np.zeros(step.nodal_forces.size)
        shear[
            np.searchsorted(
                curve.compliance.r,
                system.displacement_basis.doflocs[0, curve.compliance.radial_dofs],
            )
        ] = step.tangential_forces
        assert np.all(np.abs(shear) <= mu * step.nodal_forces * (1 + 1e-8) + 1e-12 * step.force)
        forces.append(step.force)
    assert forces[0] == pytest.approx(free.steps[-1].force, rel=1e-9)
    # measured (z = 5 r^2, nu 0, size 1/20): 1.0321 at mu = 0.3 and 1.0545 with no slip, times
    # the frictionless force
    assert forces[0] < forces[1] < stuck.steps[-1].force
    assert 1.025 < forces[1] / forces[0] < 1.04
    with pytest.raises(InputError, match="friction"):
        solve_bonded_contact(system, indenter.profile, depths, refined, friction=-0.1)
