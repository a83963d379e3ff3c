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
    rows = "\n".join(f"{x!r},{p!r}" for x, p in zip(*DATA.values(), strict=True))
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
