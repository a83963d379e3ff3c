"""Session 56's adversary pass over ``shtaerman fit`` / ``sh.fit`` (main c2e2086): what it
found, fixed. Every case is refused before any fit is run."""

import numpy as np
import pytest

import shtaerman as sh
from shtaerman.cli import main
from shtaerman.theory.contact import PowerLawContact
from shtaerman.validation import InputError

INDENTER = sh.PowerLawIndenter(shape_coefficient=5.0, exponent=1.5)
CASE = sh.Problem.curve(INDENTER, sh.Material(7.5e6, 0.5))
DEPTHS = np.linspace(1e-4, 4e-3, 20)
DATA = {"depth": DEPTHS, "force": PowerLawContact(INDENTER, 1e7).force(DEPTHS)}


def _csv(tmp_path):
    path = tmp_path / "ind.csv"
    rows = "\n".join(f"{x:.17g},{p:.17g}" for x, p in zip(*DATA.values(), strict=True))
    path.write_text(f"depth [m],force [N]\n{rows}\n")
    return str(path)


@pytest.mark.parametrize("noise", ["1e200", "1e308"])
def test_a_huge_noise_is_one_line_not_an_overflow(tmp_path, capsys, noise):
    """`fit indentation ind.csv --noise 1e200` ended in an OverflowError traceback (noise**2
    in the covariance, exit 1); the noise now has a range, (0, 1e100], like the moduli."""
    assert main(["fit", "indentation", _csv(tmp_path), "--noise", noise]) == 2
    err = capsys.readouterr().err
    assert f"--noise must lie in (0, 1e100], got '{noise}'" in err and err.count("\n") == 1


def test_python_refuses_a_huge_noise_by_its_keyword():
    with pytest.raises(InputError, match=r"^noise must lie in \(0, 1e100\]") as e:
        sh.fit("indentation", DATA, CASE, noise=1e308)
    assert e.value.parameter == "noise"


@pytest.mark.parametrize(
    ("keywords", "parameter"),
    [({"figure_format": "svg"}, "figure_format"), ({"force": "yes", "out": "x"}, "force")],
)
def test_sh_fit_refuses_output_keywords_as_the_other_routes(tmp_path, keywords, parameter):
    """`sh.fit(figure_format="svg")` without out ran and drew nothing, where `fit
    --figure-format svg` without --out, and sh.contact / sh.dynamic, refuse it; `force="yes"`
    was taken as true where they refuse anything but a bool."""
    if "out" in keywords:
        keywords = {**keywords, "out": tmp_path / "fit"}
    with pytest.raises(InputError, match=rf"^{parameter}") as e:
        sh.fit("indentation", DATA, CASE, **keywords)
    assert e.value.parameter == parameter and not (tmp_path / "fit").exists()


def test_units_beside_a_mapping_are_refused_not_dropped():
    """`sh.fit(..., {"depth": x_mm, ...}, units={"depth": "mm"})` fitted the millimetres as
    metres: a mapping's columns are SI and the units were silently ignored."""
    with pytest.raises(InputError, match=r"^units: applies to a CSV file's header") as e:
        sh.fit("indentation", DATA, CASE, units={"depth": "mm"})
    assert e.value.parameter == "units"


@pytest.mark.parametrize(
    ("column", "said"),
    [
        (["a"] * DEPTHS.size, "of <U1"),  # was a bare ValueError from numpy
        ([True] * DEPTHS.size, "of bool"),  # was read as depths of 1 m: E2 = 1.7 kPa
        (DEPTHS.reshape(4, 5), "shape (4, 5)"),  # was "the columns must have equal lengths"
    ],
)
def test_a_mapping_column_of_no_numbers_is_one_line_naming_it(column, said):
    with pytest.raises(InputError, match=r"^data: column 'depth' must be a one-dimensional") as e:
        sh.fit("indentation", {**DATA, "depth": column}, CASE)
    assert said in str(e.value) and e.value.parameter == "data"


@pytest.mark.parametrize(("data", "problem"), [(5, CASE), (DATA, {"E2": 7.5e6}), (DATA, None)])
def test_sh_fit_refuses_what_is_no_data_or_no_problem(data, problem):
    """An int as data ended in TypeError from list(); a dict or None as the problem in
    AttributeError on problem.body."""
    with pytest.raises(InputError, match=r"^(data|problem)( must be|: give) ") as e:
        sh.fit("indentation", data, problem)
    assert e.value.parameter == ("data" if data == 5 else "problem")


@pytest.mark.parametrize("unknowns", ["E2", "E2,nu2"])
def test_a_fitted_e2_outside_its_range_is_refused(tmp_path, capsys, unknowns):
    """`fit indentation ind.csv --shape-coefficient 1e-100` printed E2 = 5.5e-61 Pa with exit
    0 (a force history at A = 1e-30: 2.6e-14 Pa): no E2 in [1e-3, 1e100] Pa, the range every
    route takes, reproduces the data under that profile."""
    argv = ["fit", "indentation", _csv(tmp_path), "--shape-coefficient", "1e-100"]
    assert main([*argv, "--fit", unknowns]) == 1
    err = capsys.readouterr().err
    assert "needs E2 = 5.526e-61 Pa, outside [1e-3, 1e100] Pa" in err and err.count("\n") == 1


def test_a_soft_striker_beside_fe_curves_is_refused_not_dropped(tmp_path, capsys):
    """`fit indentation ind.csv --thickness 0.02 --E1 1e9` (or 1e-3) gave E2 = 5.24 MPa, the
    rigid striker's value to every digit: the FE curves press a rigid striker and dropped the
    given one. Its compliance, 0.0066 of the rubber's, is 5 times the curves' force error."""
    argv = ["fit", "indentation", _csv(tmp_path), "--thickness", "0.02", "--E1", "1e9"]
    assert main(argv) == 1
    err = capsys.readouterr().err.splitlines()[-1]
    assert err.startswith("shtaerman: error: --E1 1e+09: the FE contact curves press a rigid")
    assert main([*argv[:-1], "inf"]) == 0  # the same curve with a rigid striker runs


def test_a_soft_striker_beside_fe_impacts_is_refused_not_dropped():
    """A force history on a 20 mm pad gave E2 = 2.405 MPa with E1 = 3e7 and 2.406 MPa with a
    rigid striker (the FE impacts press a rigid one), where its compliance is 0.45 of the
    rubber's: refused after the first FE impact, naming E1."""
    from shtaerman.theory.impact import solve_impact
    from shtaerman.validation import NumericalFailureError

    impact = solve_impact(0.7, 3.0, PowerLawContact(INDENTER, 1e7))
    t = np.linspace(0.0, 1.2 * impact.t_y, 120)
    force = np.zeros_like(t)
    inside = (t > 0) & (t < impact.t_y)
    force[inside] = impact.history(times=t[inside]).P
    soft = sh.Problem.impact(INDENTER, sh.Material(7.5e6, 0.5), mass=0.7, velocity=3.0,
                             striker=sh.Material(3e7, 0.25), thickness=0.02)  # fmt: skip
    with pytest.raises(NumericalFailureError, match=r"^E1=3e\+07: the FE impacts press a rigid"):
        sh.fit("force-history", {"time": t, "force": force}, soft, unknowns="E2")


@pytest.mark.parametrize("command", [["contact", "--depths", "1e-3,2e-3"], ["dynamic"]])
def test_a_huge_refine_is_refused_by_its_option(capsys, command):
    """`contact --refine 1e308` said "size must be > 0 and at least 2.226e-308 ..., got
    6.67e-311", naming a mesh size the user never gave; `dynamic` named refine but half of it
    (its ladder's coarsest level). refine now has a range, (0, 1e6], far past any max_dofs."""
    assert main([*command, "--refine", "1e308"]) == 2
    err = capsys.readouterr().err
    assert err == "shtaerman: error: --refine must lie in (0, 1e6], got '1e308'\n"


@pytest.mark.parametrize("route", ["contact", "dynamic"])
def test_python_refuses_a_huge_refine_by_its_keyword(route):
    """sh.dynamic(refine=1e308) said "the error-estimate ladder's coarsest level ... got
    4.999999999999999e+307", with no parameter; sh.contact named an internal 'size'."""
    rubber = sh.Material(7.5e6, 0.5, density=1100.0)
    with pytest.raises(InputError, match=r"^refine must lie in \(0, 1e6\], got 1e\+308$") as e:
        if route == "contact":
            sh.contact(INDENTER, rubber, depths=[1e-3, 2e-3], refine=1e308)
        else:
            sh.dynamic(sh.Problem.impact(INDENTER, rubber, mass=0.7, velocity=3.0), refine=1e308)
    assert e.value.parameter == "refine"


def test_convergence_sizes_keep_their_own_refusal_not_refines_range():
    """The refine range is the input's: a [convergence] size of 1e-10 (a refinement 6.7e7 of
    the base mesh) is still refused by its unknowns, naming the size, not by refine's range."""
    from shtaerman.fem.mesh import MeshSettings

    finer = MeshSettings().refined(6.7e7)  # no range here: the mesh's own checks follow
    assert finer.size == pytest.approx(MeshSettings().size / 6.7e7, rel=1e-12)


def test_dynamic_names_the_refine_given_not_its_ladders_half(capsys):
    """`dynamic --refine 1e5` said "the error-estimate ladder's coarsest level ... refine must
    lie in [0.25, 500] ..., got 49999.999999999985": the finest level is checked first now."""
    assert main(["dynamic", "--refine", "1e5"]) == 2
    err = capsys.readouterr().err
    assert err.startswith("shtaerman: error: --refine must lie in [0.25, 500] with 200 steps")
    assert err.endswith("got 100000.0\n") and "coarsest" not in err
