"""Rubber models beyond neo-Hookean (Mooney-Rivlin, Yeoh, Gent) and the volumetric energy.

Pointwise: the stress against closed-form homogeneous deformations, the tangent against finite
differences, the neo-Hookean special cases. Contact (coarse mesh): the special cases equal the
neo-Hookean contact, Mooney-Rivlin departs, the small-strain limit. Options: one-line errors.
"""

from __future__ import annotations

import json
import math
import re

import numpy as np
import pytest

from shtaerman.fem.contact.finite import run_finite_indentation
from shtaerman.fem.hyperelastic import NeoHookean, NewtonError, kinematics
from shtaerman.fem.mesh import MeshSettings
from shtaerman.fem.rubber import (
    Rubber,
    RubberModel,
    energy_derivatives,
    invariant_kinematics,
    rubber_model,
)
from shtaerman.study.contact.indentation import run_indentation
from shtaerman.theory.indenter import PowerLawIndenter
from shtaerman.theory.materials import Material
from shtaerman.validation import InputError

E2 = 7.5e6
MU = E2 / 3.0
MATERIALS = {
    "mooney-rivlin": dict(model="mooney-rivlin", mooney_ratio=0.3),
    "yeoh": dict(model="yeoh", yeoh=(-0.05, 0.01)),
    "gent": dict(model="gent", gent_limit=20.0),
    "neo-hookean-log": dict(model="neo-hookean", volumetric="logarithmic"),
    "yeoh-log": dict(model="yeoh", yeoh=(0.2, 0.03), volumetric="logarithmic"),
}


def _psi(name: str, nu: float, x1: float) -> tuple[float, float]:
    """dW/dI1bar and dW/dI2bar of each model, written from its energy (Pa)."""
    mu = E2 / (2 * (1 + nu))
    spec = MATERIALS[name]
    if spec["model"] == "mooney-rivlin":
        r = spec["mooney_ratio"]
        return (1 - r) * mu / 2, r * mu / 2
    if spec["model"] == "yeoh":
        c2, c3 = spec["yeoh"]
        return mu / 2 * (1 + 2 * c2 * x1 + 3 * c3 * x1**2), 0.0
    if spec["model"] == "gent":
        return mu / 2 / (1 - x1 / spec["gent_limit"]), 0.0
    return mu / 2, 0.0


def _principal(stretches):
    """grad, u_r, radius of the homogeneous deformation diag(l_r, l_theta, l_z) (R = 1 m)."""
    lr, lt, lz = stretches
    grad = np.array([[lr - 1.0, 0.0], [0.0, lz - 1.0]])[..., None]
    return grad, np.array([lt - 1.0]), np.array([1.0])


def _closed_form(name: str, nu: float, stretches, p: float) -> np.ndarray:
    """Cauchy (rr, tt, zz) of a principal stretch state: (2/J) dev[(psi1 + I1bar psi2) Bbar -
    psi2 Bbar^2] - p g'(J), g' = 1 (J - 1) or 1/J (ln J)."""
    lam = np.asarray(stretches, dtype=float)
    J = float(np.prod(lam))
    bbar = J ** (-2 / 3) * lam**2
    i1, i2 = bbar.sum(), 0.5 * (bbar.sum() ** 2 - (bbar**2).sum())
    psi1, psi2 = _psi(name, nu, i1 - 3)
    tensor = (psi1 + i1 * psi2) * bbar - psi2 * bbar**2
    trace = psi1 * i1 + 2 * psi2 * i2
    slope = 1 / J if MATERIALS[name].get("volumetric") == "logarithmic" else 1.0
    return 2 / J * (tensor - trace / 3) - p * slope


def _material(name: str, nu: float) -> Rubber:
    return Rubber(E2, nu, **MATERIALS[name])


HOMOGENEOUS = {
    "uniaxial": (1.5**-0.5, 1.5**-0.5, 1.5),
    "equibiaxial": (1.3, 1.3, 1.3**-2),
    "hoop": (1.2, 0.85, 1 / (1.2 * 0.85)),
    "compressible": (1.1, 0.95, 0.8),
}


@pytest.mark.parametrize("name", MATERIALS)
@pytest.mark.parametrize("state", HOMOGENEOUS)
@pytest.mark.parametrize("nu", [0.5, 0.3])
def test_stress_of_homogeneous_deformations_is_the_closed_form(name, state, nu):
    stretches, p = HOMOGENEOUS[state], 0.37 * MU
    grad, u_r, radius = _principal(stretches)
    k = kinematics(_material(name, nu), grad, u_r, radius, np.array([p]))
    S, F = k.stress[:, 0], k.F[:, 0]
    cauchy = np.array([S[0] * F[0], S[4] * F[4], S[3] * F[3]]) / k.J[0]
    assert np.max(np.abs(cauchy - _closed_form(name, nu, stretches, p))) <= 1e-10 * MU
    assert abs(S[1]) + abs(S[2]) <= 1e-10 * MU  # no shear in a principal state


def _random_state(seed: int, size: int = 6):
    rng = np.random.default_rng(seed)
    grad = 0.25 * rng.standard_normal((2, 2, size))
    u_r = 0.2 * rng.standard_normal(size)
    return grad, u_r, np.ones(size), 0.3 * MU * rng.standard_normal(size)


def _from_F(F: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    grad = np.array([[F[0] - 1.0, F[1]], [F[2], F[3] - 1.0]])
    return grad, F[4] - 1.0


@pytest.mark.parametrize("name", MATERIALS)
@pytest.mark.parametrize("nu", [0.5, 0.3])
def test_tangent_is_the_derivative_of_the_stress(name, nu):
    material = _material(name, nu)
    grad, u_r, radius, p = _random_state(1)
    k = kinematics(material, grad, u_r, radius, p)
    eps = 1e-6
    for m in range(5):
        step = np.zeros((5, 1))
        step[m] = eps
        plus = kinematics(material, *_from_F(k.F + step), radius, p)
        minus = kinematics(material, *_from_F(k.F - step), radius, p)
        fd = (plus.stress - minus.stress) / (2 * eps)
        scale = np.abs(k.tangent).max()
        # central differences: O(eps^2) truncation ~1e-12 relative; a wrong term is O(1e-2)
        assert np.abs(fd.T - k.tangent[:, :, m]).max() <= 1e-7 * scale
        fd_energy = (plus.energy_density - minus.energy_density) / (2 * eps)
        assert np.abs(fd_energy - k.stress[m]).max() <= 1e-7 * np.abs(k.stress).max()
    assert np.abs(k.tangent - np.swapaxes(k.tangent, -1, -2)).max() <= 1e-12 * scale


@pytest.mark.parametrize(
    "spec",
    [
        dict(model="neo-hookean"),
        dict(model="mooney-rivlin", mooney_ratio=0.0),
        dict(model="yeoh", yeoh=(0.0, 0.0)),
    ],
)
@pytest.mark.parametrize("nu", [0.5, 0.3])
def test_special_cases_are_neo_hookean_pointwise(spec, nu):
    grad, u_r, radius, p = _random_state(2)
    fast = kinematics(NeoHookean(E2, nu), grad, u_r, radius, p)
    general = invariant_kinematics(Rubber(E2, nu, **spec), grad, u_r, radius, p)
    for key in ("stress", "tangent", "volume_gradient", "constraint", "energy_density"):
        a, b = getattr(fast, key), getattr(general, key)
        assert np.abs(a - b).max() <= 1e-12 * max(np.abs(a).max(), MU), key


def test_the_default_rubber_runs_the_neo_hookean_code_bitwise():
    grad, u_r, radius, p = _random_state(3)
    fast = kinematics(NeoHookean(E2, 0.3), grad, u_r, radius, p)
    default = kinematics(Rubber(E2, 0.3), grad, u_r, radius, p)
    assert np.array_equal(fast.tangent, default.tangent)
    assert np.array_equal(fast.energy_density, default.energy_density)


def test_small_strain_energy_is_linear_elasticity_for_every_model():
    """The second derivative at F = I (the small-strain modulus) equals the neo-Hookean one."""
    zero = (np.zeros((2, 2, 1)), np.zeros(1), np.ones(1), np.zeros(1))
    reference = kinematics(NeoHookean(E2, 0.3), *zero).tangent
    for name in MATERIALS:
        tangent = kinematics(_material(name, 0.3), *zero).tangent
        assert np.abs(tangent - reference).max() <= 1e-12 * MU, name


def test_gent_limit_stops_the_step():
    grad = np.array([[3.0, 0.0], [0.0, 1 / 16 - 1]])[..., None]  # I1bar - 3 ~ 13
    material = Rubber(E2, 0.5, model="gent", gent_limit=5.0)
    with pytest.raises(NewtonError, match="gent limit"):
        kinematics(material, grad, np.zeros(1), np.ones(1), np.zeros(1))


def test_yeoh_energy_derivatives():
    material = Rubber(E2, 0.5, model="yeoh", yeoh=(-0.05, 0.01))
    x = np.array([0.0, 0.7, 4.0])
    w, psi1, _, psi11, _, _ = energy_derivatives(material, x, x)
    C10 = MU / 2
    assert np.allclose(w, C10 * (x - 0.05 * x**2 + 0.01 * x**3), rtol=1e-14)
    assert np.allclose(psi1, C10 * (1 - 0.1 * x + 0.03 * x**2), rtol=1e-14)
    assert np.allclose(psi11, C10 * (-0.1 + 0.06 * x), rtol=1e-14)


@pytest.mark.parametrize(
    "options, word",
    [
        (dict(model="mooney-rivlin", mooney_ratio=1.0), "mooney_ratio"),
        (dict(model="mooney-rivlin", mooney_ratio=-0.1), "mooney_ratio"),
        (dict(model="mooney-rivlin", mooney_ratio=math.nan), "mooney_ratio"),
        (dict(model="yeoh", yeoh="0.1"), "yeoh"),
        (dict(model="yeoh", yeoh="a,b"), "yeoh"),
        (dict(model="yeoh", yeoh=(-0.5, 0.0)), "yeoh"),
        (dict(model="yeoh", yeoh=(-0.5, 0.08)), "yeoh"),
        (dict(model="yeoh", yeoh=(0.1, -0.01)), "yeoh"),
        (dict(model="yeoh", yeoh=(0.1, math.inf)), "yeoh"),
        (dict(model="gent"), "gent_limit"),
        (dict(model="gent", gent_limit=0.0), "gent_limit"),
        (dict(model="neo-hookean", volumetric="cubic"), "volumetric"),
        (dict(model="ogden"), "model"),
    ],
)
def test_bad_rubber_options_are_one_line_naming_the_option(options, word):
    with pytest.raises(InputError) as error:
        rubber_model(**options)
    assert word in str(error.value) and "\n" not in str(error.value)


def test_numpy_scalars_are_rubber_constants_as_they_are_masses():
    """adv50: np.float32(0.2) as gent_limit was refused as 'gent_limit must be a finite
    number > 0, got np.float32(0.2)' (np.int64 and mooney_ratio alike) where mass=np.float32
    is taken; a NumPy bool stays refused."""
    gent = rubber_model("gent", gent_limit=np.float32(0.2))
    assert gent.gent_limit == float(np.float32(0.2)) and type(gent.gent_limit) is float
    assert rubber_model("gent", gent_limit=np.int64(30)).gent_limit == 30.0
    assert rubber_model("mooney-rivlin", mooney_ratio=np.float32(0.25)).mooney_ratio == 0.25
    for bad in (np.bool_(True), np.float64(np.nan), np.float32(-1.0)):
        with pytest.raises(InputError, match="gent_limit must be a finite number > 0"):
            rubber_model("gent", gent_limit=bad)


@pytest.mark.parametrize(
    ("options", "word"),
    [
        (dict(model="neo-hookean", mooney_ratio=0.2), "mooney_ratio"),
        (dict(model="mooney-rivlin", yeoh=(0.1, 0.0)), "yeoh"),
    ],
)
def test_a_shape_option_of_another_model_is_refused_by_the_body(options, word):
    """Where the input enters (problem.Body, by problem.RUBBER_SHAPES), not in fem."""
    from shtaerman.problem import Body

    with pytest.raises(InputError) as error:
        Body(Material(7.5e6, 0.5), **options)
    owner = "mooney-rivlin" if word == "mooney_ratio" else "yeoh"
    assert str(error.value) == f"{word}: applies to the {owner} model only"


def test_stable_negative_c2_is_allowed():
    assert rubber_model("yeoh", yeoh="-0.1,0.004").yeoh == (-0.1, 0.004)


# --- the contact -------------------------------------------------------------------------------
COARSE = MeshSettings(size=0.1, domain=1e4, growth=0.3, axis_size=1e-4, axis_growth=0.2)
"""~5.5k dofs (as in test_fem_hyperelastic)."""
PAPER = PowerLawIndenter(5.0, 1.5)


@pytest.fixture(scope="module")
def neo_hookean_curve():
    """The paper's rubber to x/a = 0.6 (linear a), coarse mesh, neo-Hookean."""
    return run_finite_indentation(PAPER, Material(E2, 0.5), _DEPTHS, COARSE)


_DEPTHS = np.array([0.25, 0.5, 0.75, 1.0]) * 6e-3 * (0.6 / 0.78541) ** 3
"""Up to x/a = 0.6 on the linear solution (x/a ~ x^(1/3))."""


@pytest.mark.parametrize(
    "model", [rubber_model("mooney-rivlin", 0.0), rubber_model("yeoh", yeoh=(0.0, 0.0))]
)
def test_special_cases_equal_the_neo_hookean_contact(neo_hookean_curve, model):
    curve = run_finite_indentation(PAPER, Material(E2, 0.5), _DEPTHS, COARSE, model)
    for step, reference in zip(curve.steps, neo_hookean_curve.steps, strict=True):
        assert step.force == pytest.approx(reference.force, rel=1e-8)
        assert step.contact_radius == pytest.approx(reference.contact_radius, rel=1e-8)


def test_mooney_rivlin_departs_measurably_at_x_over_a_0_6(neo_hookean_curve):
    curve = run_finite_indentation(
        PAPER, Material(E2, 0.5), _DEPTHS, COARSE, rubber_model("mooney-rivlin", 0.3)
    )
    step, reference = curve.steps[-1], neo_hookean_curve.steps[-1]
    assert 0.55 < step.depth / step.contact_radius_linear < 0.65
    # the I2 term stiffens: observed +2.3 % on the force (the mesh's own error ~1e-3)
    assert step.force / reference.force - 1 > 1e-2


@pytest.mark.parametrize(
    "model",
    [
        rubber_model("mooney-rivlin", 0.3),
        rubber_model("yeoh", yeoh=(-0.05, 0.01)),
        rubber_model("gent", gent_limit=20.0),
        rubber_model("neo-hookean", volumetric="logarithmic"),
    ],
)
@pytest.mark.parametrize("nu", [0.5, 0.3])
def test_small_strain_limit_of_every_model(model, nu):
    ratio, radius = 2e-3, 0.01
    kappa = PowerLawIndenter(1.0, 1.5).kappa
    indenter = PowerLawIndenter(ratio / (kappa * radius**0.5), 1.5)
    depth = kappa * indenter.shape_coefficient * radius**1.5
    finite = run_finite_indentation(indenter, Material(E2, nu), [depth], COARSE, model)
    linear = run_indentation(indenter, Material(E2, nu), [depth], COARSE, aligned=False)
    assert finite.steps[0].force == pytest.approx(linear.steps[0].force, rel=3e-3)


# --- the command line and the API ---------------------------------------------------------------
def _cli(capsys, *argv):
    from shtaerman.cli import main

    code = main(["contact", *argv])
    out, err = capsys.readouterr()
    return code, out, err


@pytest.mark.parametrize(
    ("argv", "name"),
    [
        (["--model", "mooney-rivlin", "--mooney-ratio", "1"], "--mooney-ratio"),
        (["--model", "mooney-rivlin", "--mooney-ratio", "x"], "--mooney-ratio"),
        (["--model", "yeoh", "--yeoh=-0.5,0"], "--yeoh"),
        (["--model", "yeoh", "--yeoh", "0.1"], "--yeoh"),
        (["--model", "yeoh", "--yeoh", "0.1,,2"], "--yeoh"),
        (["--model", "yeoh", "--mooney-ratio", "0.2"], "--mooney-ratio"),
        (["--model", "gent"], "--gent-limit"),
        (["--model", "gent", "--gent-limit", "-1"], "--gent-limit"),
        (["--mooney-ratio", "0.2"], "--mooney-ratio"),
        (["--volumetric", "logarithmic"], "--volumetric"),
        (["--model", "yeoh", "--volumetric", "ln"], "--volumetric"),
        (["--model", "mooney-rivlin", "--solver", "pardiso"], "--solver"),
        (["--model", "yeoh", "--accuracy", "1e-3"], "--accuracy"),
        (["--model", "yeoh", "--thickness", "0.1", "--base", "lubricated"], "--base"),
    ],
)
def test_bad_rubber_options_exit_2_with_one_line(capsys, argv, name):
    code, out, err = _cli(capsys, *argv, "--depths", "1e-3")
    assert code == 2 and out == ""
    assert name in err and err.count("\n") == 1


def test_mooney_rivlin_json_names_the_model(capsys):
    argv = ["--model", "mooney-rivlin", "--mooney-ratio", "0.3", "--nu2", "0.4"]
    argv += ["--volumetric", "logarithmic", "--json", "--no-estimate", "--depths", "2e-3"]
    code, out, _ = _cli(capsys, *argv, "--mesh-size", "0.1", "--domain-factor", "1e4")
    report = json.loads(out)
    assert code == 0
    assert (report["model"], report["mooney_ratio"], report["volumetric"]) == (
        "mooney-rivlin",
        0.3,
        "logarithmic",
    )
    mesh = ["--mesh-size", "0.1", "--domain-factor", "1e4"]
    code, out, _ = _cli(capsys, *argv[:-4], "--no-estimate", "--depths", "2e-3", *mesh)
    assert code == 0 and out.startswith("Mooney-Rivlin (r = 0.3, logarithmic volumetric energy)")


def test_the_api_takes_the_rubber_keywords():
    import shtaerman as sh

    result = sh.contact(
        PAPER,
        Material(E2, 0.5),
        model="yeoh",
        yeoh=(-0.05, 0.01),
        depths=[2e-3],
        estimate=False,
        mesh_size=0.1,
        domain_factor=1e4,
    )
    assert result.model == "yeoh" and result.to_dict()["yeoh"] == [-0.05, 0.01]


@pytest.mark.parametrize(
    ("pressure", "radius", "words"),
    [
        (0.942, 1.033, ("5.8 % below", "3.3 % larger")),
        (1.02, 0.99, ("2.0 % above", "1.0 % smaller")),
    ],
)
def test_central_pressure_wording_follows_the_numbers(pressure, radius, words):
    from shtaerman.output.text_finite import central_pressure_words

    sentence = central_pressure_words(pressure, radius)
    assert all(word in sentence for word in words)


# --- the study files ----------------------------------------------------------------------------
def _study_file(tmp_path, rubber: str, sweep: str = "") -> str:
    path = tmp_path / "rubber.toml"
    path.write_text(
        'kind = "finite-strain"\n[indenter]\nshape_coefficient = 5.0\nexponent = 1.5\n'
        "[half_space]\nE2 = 7.5e6\nnu2 = 0.3\n[impact]\nmass = 0.7\nvelocity = 3.0\n"
        f"[rubber]\n{rubber}\n" + (f"[sweep]\n{sweep}\n" if sweep else "")
    )
    return str(path)


def test_study_file_sweeps_the_model_with_each_models_shape(tmp_path):
    from shtaerman.study.schema import load_study

    text = "mooney_ratio = 0.1\nyeoh = [-0.1, 0.01]"
    studies = load_study(_study_file(tmp_path, text, 'model = ["neo-hookean", "yeoh"]'))
    assert [s.name for s in studies] == ["rubber-neo-hookean", "rubber-yeoh"]
    assert studies[0].rubber == rubber_model("neo-hookean")
    assert studies[1].rubber == rubber_model("yeoh", yeoh=(-0.1, 0.01))
    [study] = load_study(_study_file(tmp_path, 'volumetric = "logarithmic"'))
    assert study.rubber.volumetric == "logarithmic"


def test_a_gent_study_file_loads_with_its_limit(tmp_path):
    """adv50: every finite-strain study file of model "gent" (not swept) was refused as "key
    'rubber.gent_limit': the gent model needs Jm > 0", its gent_limit given: the check of its
    contact curve built the problem's body from the model's name alone."""
    from shtaerman.study.schema import load_study

    [study] = load_study(_study_file(tmp_path, 'model = "gent"\ngent_limit = 0.01'))
    assert study.rubber == rubber_model("gent", gent_limit=0.01)


@pytest.mark.parametrize(
    "rubber",
    [
        'model = "yeoh"\nmooney_ratio = 0.1',
        'model = "yeoh"\nyeoh = [-1.0, 0.0]',
        'volumetric = "x"',
    ],
)
def test_bad_rubber_table_names_the_file_and_key(tmp_path, rubber):
    from shtaerman.study.schema import StudyError, load_study

    with pytest.raises(StudyError, match=r"rubber\.toml: key 'rubber\.\w+': "):  # the Body's words
        load_study(_study_file(tmp_path, rubber))


def test_shipped_rubber_studies_carry_the_treloar_fit():
    from shtaerman.study.schema import load_study, shipped_studies

    paths = {p.stem: p for p in shipped_studies(extended=True)}
    models = {s.name: s.rubber for s in load_study(paths["rubber_models"])}
    assert models["rubber-mooney-rivlin"].mooney_ratio == 0.085
    assert models["rubber-yeoh"].yeoh == (-0.101, 0.0127)
    assert "Treloar" in paths["rubber_models"].read_text()
    [volumetric] = load_study(paths["rubber_volumetric"])
    assert volumetric.rubber.volumetric == "logarithmic"


def test_findings_name_the_model_and_flag_the_volumetric_energy():
    from types import SimpleNamespace

    from shtaerman.output.text_finite import rubber_finding

    def finding(nu: float, model: RubberModel) -> list[str]:
        study = SimpleNamespace(rubber=model, half_space=Material(E2, nu))
        return rubber_finding(SimpleNamespace(study=study))

    assert finding(0.5, RubberModel()) == []
    [flag] = finding(0.3, RubberModel())
    assert "depend on the volumetric energy" in flag and "K/2 (J-1)^2" in flag
    [named, flag] = finding(0.3, rubber_model("yeoh", yeoh=(-0.1, 0.01), volumetric="logarithmic"))
    assert "Yeoh with c2, c3 = C20/C10, C30/C10 = -0.1, 0.01" in named and "(ln J)^2" in flag


# --- a Gent rubber that locks is told so (issue 31 items 13-14), and one that does not runs ---

LOCKS = "--gent-limit: the Gent rubber locks "


def _locking_depth(err: str) -> float:
    """The depth of the refusal, the last line of ``err`` (after the warning of the first
    state at LOCKED, where one was accepted: tests/test_gent_locking_warning.py)."""
    *warned, refused = err.splitlines()
    assert refused.startswith(f"shtaerman: error: {LOCKS}") and len(warned) <= 1, err
    assert all(line.startswith("shtaerman: warning: the Gent rubber locks from") for line in warned)
    assert "refine the mesh" not in err and "finer --mesh-size" not in err
    # "at depth D m" (a state near the limit) or "before depth D m" (the first step)
    return float(refused.removeprefix(f"shtaerman: error: {LOCKS}").split(" m:")[0].split()[-1])


@pytest.mark.parametrize("limit", ["1e-6", "0.01"])
def test_a_gent_rubber_that_locks_names_the_gent_limit(capsys, limit):
    code, out, err = _cli(capsys, "--model", "gent", "--gent-limit", limit, "--mesh-size", "0.2")
    assert code == 2 and out == ""
    # at 0.01 the stretch is 0.9985 Jm at 7.7e-5 m and 0.99984 Jm at 1.02e-4 m, and the step
    # from there to 1.54e-4 m fails: the run stops there (a state at LOCKED = 0.999). Before
    # issue 31 it crawled on in halved steps to 3.9e-3 m and blamed the mesh (85 s)
    assert _locking_depth(err) < 2e-4
    if limit == "0.01":  # a lock from a converged state: its stretch is past LOCKED
        from shtaerman.guards import LOCKED

        stretch = float(re.search(r"its stretch I1bar - 3 is (\S+) of its limit", err)[1])
        assert LOCKED <= stretch < 1.0, err
        # that state warned first, with the depth where the stretch crossed LOCKED: 8.6e-5 m,
        # between 7.7e-5 m (0.9985) and that state's 1.02e-4 m
        crossed = float(re.search(r"locks from depth (\S+) m on", err)[1])
        assert 7.6e-5 < crossed < _locking_depth(err), err
    else:  # the first step locks: no state accepted near the limit, no warning
        assert "warning" not in err, err


def test_a_gent_rubber_near_its_limit_is_not_refused_while_its_steps_converge(capsys):
    """adv49: Jm 0.2 was refused as locking at 3.32 mm (the stretch past 0.9 Jm and a Newton
    iterate past the limit), while 60 depths reached 4.95 mm and the massless impact of the
    same rubber x_max 7.79 mm. An iterate past the limit is now halved (GENT_BACKTRACKS), and
    the curve reaches the paper's x_c, 8.517 mm (the stretch is 0.99984 Jm there, past LOCKED:
    a state near the limit is no lock while the steps converge)."""
    code, out, err = _cli(
        capsys,
        "--model",
        "gent",
        "--gent-limit",
        "0.2",
        "--mesh-size",
        "0.2",
        "--no-estimate",
        "--json",
    )
    # not refused; warned once, from 5.33 mm on (0.99899 at 5.32 mm, 0.99967 at 6.73 mm)
    assert code == 0 and err.count("\n") == 1 and "error" not in err, err
    assert err.startswith("shtaerman: warning: the Gent rubber locks from depth 0.005"), err
    assert json.loads(out)["steps"][-1]["depth"] == pytest.approx(8.517e-3, rel=1e-3)


def test_a_massless_gent_impact_that_locks_names_the_gent_limit(capsys):
    from shtaerman.cli import main

    code = main(["dynamic", "--model", "gent", "--gent-limit", "1e-6", "--density2", "0"])
    out, err = capsys.readouterr()
    assert code == 2 and out == ""
    assert _locking_depth(err) < 1e-4


def test_a_failed_gent_step_is_a_lock_only_near_the_limit_or_at_once():
    from shtaerman.fem.hyperelastic import assemble_hyperelastic
    from shtaerman.fem.rubber import GentLimitError, gent_locks, gent_stretch
    from shtaerman.guards import LOCKED

    mesh = MeshSettings(size=0.2).build(1e-2)
    system = assemble_hyperelastic(mesh, Rubber(E2, 0.5, model="gent", gent_limit=0.01))
    rest = np.zeros(system.n_dofs)
    assert gent_stretch(system.material, system.state(rest)) == 0.0
    overshoot = GentLimitError("an iterate passed the gent limit I1bar - 3 = Jm = 0.01")
    step = (0.0, 1e-4)  # from the undeformed body to 0.1 mm
    assert gent_locks(overshoot, system, rest, step, last=False) is None  # 0 < LOCKED: cut
    assert gent_locks(NewtonError("no convergence"), system, rest, step, last=True) is None
    locked = gent_locks(overshoot, system, rest, step, last=True)  # the first step, no cut left
    # adv50: it said "locks at depth 0.0001 m", the step's end, where the first step locks
    # anywhere before it: the contact curve said 6.4e-6 m, the massless impact 7.7e-6 m, the
    # impact with inertia 4.9e-4 m and the finite-strain study 6.0e-10 m for Jm 1e-6
    said = "locks before depth 0.0001 m: its first load step, from the undeformed body"
    assert locked.parameter == "gent_limit" and said in str(locked)
    assert 0.99 < LOCKED < 1.0  # the stiffness mu / (1 - LOCKED) is over 100 mu


def test_a_gent_rubber_locking_at_once_with_inertia_is_refused_as_on_the_other_routes():
    """adv50: Jm 1e-6 with inertia failed as a numerical failure (exit 1, 132 s: 'Newton did
    not converge in 30 iterations, also in steps cut 4 times'), where the contact curve and
    the massless impact of the same rubber are refused as locking at 6.4e-6 and 7.7e-6 m
    (exit 2). Every Newton of the first step had its iterates past the limit (1,208 of them
    halved): that non-convergence is the limit's, so the first step is the lock."""
    import shtaerman as sh
    from shtaerman.fem.rubber import GentLockError

    with pytest.raises(GentLockError, match="locks before depth") as caught:
        sh.dynamic(
            PAPER,
            Material(E2, 0.5, 1100.0),
            mass=0.7,
            velocity=3.0,
            model="gent",
            gent_limit=1e-6,
            estimate=False,
            time_steps=50,
            mesh_size=0.2,
        )
    assert caught.value.parameter == "gent_limit"


def test_a_gent_lock_in_the_first_step_with_inertia_names_a_depth_reached(capsys):
    """It said 'locks at depth 0 m': the depth before the step, not the one it went for.
    Any limit the first step passes says it (GentLockError.locking, stretch 0): Jm 1e-6, as
    the test above, gives up in 16 CPU s where 0.01 took 57 s (the same line and depth)."""
    import re

    from shtaerman.cli import main

    argv = ["dynamic", "--model", "gent", "--gent-limit", "1e-6", "--mesh-size", "0.2"]
    assert main([*argv, "--time-steps", "50", "--no-estimate"]) == 2
    err = capsys.readouterr().err
    depth = float(re.search(r"locks before depth (\S+) m", err)[1])
    assert 0.0 < depth < 1e-3 and err.count("\n") == 1, err  # within the first steps of 8.5 mm
