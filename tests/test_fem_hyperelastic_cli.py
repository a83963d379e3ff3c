"""``shtaerman contact --model linear|neo-hookean``: the finite-strain model on the command line."""

import json

import pytest
from figure_helpers import svg_text
from PIL import Image

from shtaerman.cli import main
from shtaerman.theory.contact import PowerLawContact
from shtaerman.theory.indenter import PowerLawIndenter

COARSE = ["--mesh-size", "0.1", "--domain-factor", "1e4"]
DEPTHS = [1e-3, 2e-3]
PAPER = PowerLawContact(PowerLawIndenter(5.0, 1.5), 7.5e6 / 0.75)


def run(capsys, *argv):
    code = main(list(argv))
    out, err = capsys.readouterr()
    return code, out, err


def exact_energy(depth: float) -> float:
    """Int_0^d beta x^q dx = beta d^(q+1)/(q+1) in J (the linear law)."""
    q = PAPER.force_exponent
    return PAPER.beta * depth ** (q + 1) / (q + 1)


def test_neo_hookean_json(capsys):
    code, out, err = run(
        capsys,
        "contact",
        "--model",
        "neo-hookean",
        "--json",
        "--depths",
        ",".join(map(str, DEPTHS)),
        *COARSE,
    )
    assert code == 0 and err == ""
    report = json.loads(out)
    assert report["model"] == "neo-hookean"
    steps = report["steps"]
    assert [s["depth"] for s in steps] == DEPTHS
    for step in steps:
        # finite strain softens the paper's contact: P / P_lin = 0.974, 0.968 here (coarse
        # mesh error ~1e-3); the linear values are reported beside
        assert 0.95 < step["force"] / step["force_analytic"] < 0.99
        # the stored energy is close to the linear one (it is Int P dx of a softer law)
        assert step["strain_energy"] == pytest.approx(exact_energy(step["depth"]), rel=0.05)
        assert step["newton_iterations"] >= 1
    assert set(report["departures_from_linear"]) == {"force", "contact_radius", "central_pressure"}
    assert report["mesh"]["dofs"] > 0 and report["timings"]["total"] > 0
    # the 3-mesh ladder, as for the linear model: K/2, K/sqrt(2), K, the finest answering
    ladder = report["mesh_ladder"]
    assert [level["refine"] for level in ladder] == pytest.approx([0.5, 2**-0.5, 1.0])
    assert ladder[0]["dofs"] < ladder[1]["dofs"] < ladder[2]["dofs"] == report["mesh"]["dofs"]
    keys = {"force", "beta", "exponent", "contact_radius", "central_pressure"}
    assert set(report["error_estimate"]) == set(report["extrapolated"]) == keys
    # coarse mesh: force and beta estimated at 3.5e-3 here; a missing ladder would give 0 or
    # NaN, a broken one O(1)
    assert all(1e-6 < report["error_estimate"][key] < 0.05 for key in ("force", "beta"))
    extrapolated = report["extrapolated"]["beta"] / report["beta_fem"] - 1
    assert abs(extrapolated) <= report["error_estimate"]["beta"] * 1.01
    assert "true_error" not in report and "effectivity" not in report  # no exact solution


def test_neo_hookean_no_estimate_runs_one_mesh(capsys):
    argv = ["contact", "--model", "neo-hookean", "--json", "--no-estimate", "--depths", "2e-3"]
    code, out, _ = run(capsys, *argv, *COARSE, "--refine", "0.8")
    report = json.loads(out)
    assert code == 0 and "error_estimate" not in report and "mesh_ladder" not in report
    # --refine scales the one mesh: fewer dofs than the default 12457 of COARSE at 2e-3 m
    assert report["mesh"]["dofs"] < 12457 * 0.8


def test_linear_json_gains_model_and_strain_energy(capsys):
    # mesh-size 0.1 is too coarse for the linear code's Schur-tail factorization (it pivots)
    linear_mesh = ["--mesh-size", "0.05", "--domain-factor", "1e4"]
    depths = ",".join(map(str, DEPTHS))
    code, out, _ = run(capsys, "contact", "--json", "--depths", depths, *linear_mesh)
    assert code == 0
    report = json.loads(out)
    assert report["model"] == "linear"
    for step in report["steps"]:
        # W = 1/2 sum F_i (d - f(r_i)) against Int_0^d beta x^q dx (observed 1.6e-4, 1.9e-4:
        # the mesh's own error; a wrong factor 1/2 or sign would be O(1))
        assert step["strain_energy"] == pytest.approx(exact_energy(step["depth"]), rel=5e-4)


def test_linear_no_estimate_runs_one_mesh(capsys):
    linear_mesh = ["--mesh-size", "0.05", "--domain-factor", "1e4", "--depths", "2e-3"]
    code, out, _ = run(capsys, "contact", "--json", *linear_mesh)
    full = json.loads(out)
    code, out, _ = run(capsys, "contact", "--json", "--no-estimate", *linear_mesh)
    alone = json.loads(out)
    assert code == 0 and "error_estimate" in full and "error_estimate" not in alone
    assert alone["mesh"]["dofs"] == full["mesh_ladder"][-1]["dofs"]  # the finest level alone


def test_neo_hookean_text_and_out(capsys, tmp_path):
    """--out writes the files and the force-depth figure, with --figure-format svg also in SVG
    beside the PNG, as the linear model does (it wrote no figure, the SVG format was ignored)."""
    folder = tmp_path / "run"
    argv = ["contact", "--model", "neo-hookean", "--depths", "1e-3,2e-3", "--out", str(folder)]
    code, out, _ = run(capsys, *argv, "--figure-format", "svg", *COARSE)
    assert code == 0
    assert "Neo-Hookean contact" in out and "energy (J)" in out and "Newton" in out
    saved = json.loads((folder / "contact.json").read_text())
    assert saved["model"] == "neo-hookean" and saved["steps"][0]["strain_energy"] > 0
    assert sorted(p.name for p in folder.iterdir() if not p.name.startswith(".")) == [
        "contact.json",
        "field_max_depth.vtu",
        "finite_curve.csv",
        "force_depth.png",
        "force_depth.svg",
    ]
    assert (folder / "finite_curve.csv").read_text().startswith("depth [m],force [N],")
    assert Image.open(folder / "force_depth.png").format == "PNG"
    svg = svg_text(folder / "force_depth.svg")
    # the rubber's points against Shtaerman's linear curve, and their departure from it
    assert "FEM, neo-Hookean" in svg and "Shtaerman" in svg and "Depth" in svg


def test_neo_hookean_force_replaces_a_used_folder(capsys, tmp_path):
    # --force was not passed on to the staging of the neo-Hookean path: the run computed,
    # then refused its own folder (QA)
    from shtaerman.output.files import FOLDER_MARKER

    folder = tmp_path / "run"
    folder.mkdir()
    (folder / FOLDER_MARKER).write_text("{}")  # a folder this tool wrote
    (folder / "old").write_text("old")
    argv = ["contact", "--model", "neo-hookean", "--no-estimate", "--depths", "1e-3"]
    code, _, err = run(capsys, *argv, "--out", str(folder), "--force", *COARSE)
    assert code == 0, err
    assert sorted(p.name for p in folder.iterdir()) == [
        FOLDER_MARKER,
        "contact.json",
        "field_max_depth.vtu",
        "finite_curve.csv",
        "force_depth.png",
    ]


@pytest.mark.parametrize(
    ("argv", "names"),
    [
        (["--model", "hyperelastic"], "--model"),
        (["--model", "neo-hookean", "--mesh-size", "2"], "mesh-size"),
        (["--model", "neo-hookean", "--nu2", "-0.2"], "nu2"),
        (["--model", "neo-hookean", "--exponent", "1"], "exponent"),
        (["--model", "neo-hookean", "--accuracy", "1e-3"], "accuracy"),
        (["--no-estimate", "--accuracy", "1e-3"], "accuracy"),
        (["--model", "neo-hookean", "--refine", "0.5"], "refine must be >= 0.6 with these"),
    ],
)
def test_bad_input_is_one_line(capsys, argv, names):
    code, out, err = run(capsys, "contact", *argv)
    assert code == 2 and out == ""
    assert names in err and err.count("\n") == 1


@pytest.mark.parametrize(
    ("depths", "message"),
    [
        # Newton failed after 109 s of halved load steps (as it does from d/a ~ 1.27)
        ("0.05,0.1", "0.1 m gives depth / contact radius 2.01, beyond the neo-hookean"),
        # 'refine the mesh' after 19 s: strains of 4e-10 have no digits left in F = I + grad u
        ("1e-30,1e-29", "1e-30 m gives depth / contact radius 4.3e-10, below the neo-hookean"),
    ],
)
def test_depths_the_finite_strain_contact_cannot_resolve_are_refused_at_once(
    capsys, monkeypatch, depths, message
):
    import shtaerman.fem.contact.finite as finite

    def never(*args, **kwargs):
        raise AssertionError("the FEM ran")

    monkeypatch.setattr(finite, "assemble_hyperelastic", never)
    code, out, err = run(capsys, "contact", "--model", "neo-hookean", "--depths", depths)
    assert code == 2 and out == "" and err.count("\n") == 1
    assert message in err and "[1e-06, 1.2]" in err


def test_the_studies_depths_pass_the_finite_strain_check():
    """Finite-strain study depths (x/a from 0.01 up to 2 x_c of the paper's impact) lie inside
    the range the check allows."""
    from shtaerman.fem.contact.finite import check_finite_depths

    x_c = 0.008517340195359727
    depths = [float(PAPER.depth(1e-6)), 2 * x_c]  # d/a 0.009 and 1.11
    check_finite_depths(PowerLawIndenter(5.0, 1.5), depths)


def test_a_fold_beyond_the_contact_edge_is_a_failure_not_a_numpy_warning():
    """Free surface nodes lying on the indenter (zero gap past the last loaded node) made the
    edge extrapolation divide 0 by 0: 'invalid value encountered in scalar divide' reached the
    user and the contact radius was NaN. It is now one NumericalFailureError."""
    import warnings

    import numpy as np

    from shtaerman.fem.contact.finite import finite_step
    from shtaerman.validation import NumericalFailureError

    radius = np.linspace(0.0, 1e-2, 41)
    loaded = np.where(radius < 3e-3, 1.0, 0.0)

    class Folded:
        def geometry(self, x, depth):
            return radius, np.zeros_like(radius), None, None

    with warnings.catch_warnings():
        warnings.simplefilter("error")
        with pytest.raises(NumericalFailureError, match="zero gap"):
            finite_step(Folded(), PAPER, 1e-3, np.zeros(3), loaded, 1, 1, [])


def test_a_smallest_depth_the_mesh_cannot_resolve_is_refused_before_newton():
    """A smallest depth whose contact covers no surface node is refused before any Newton
    step (from Shtaerman's contact radius); it ran and returned the numbers of no contact."""
    from shtaerman.fem.contact.finite import run_finite_indentation
    from shtaerman.fem.mesh import MeshSettings
    from shtaerman.theory.materials import Material
    from shtaerman.validation import InputError

    coarse = MeshSettings(size=0.1, growth=0.3, domain=1e3, axis_size=0.1)  # no axis grading
    depths = [1e-3 * 0.03**1.5, 1e-3]  # contact radii 7e-5 and 2.3e-3 m; elements 4.4e-4 m
    with pytest.raises(InputError, match="covers no surface node besides the axis"):
        run_finite_indentation(PowerLawIndenter(5.0, 1.5), Material(7.5e6, 0.5), depths, coarse)
