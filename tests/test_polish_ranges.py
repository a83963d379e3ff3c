"""Printed valid ranges never mislead: a number typed as printed inside a range is accepted,
and a refused number is never printed as inside it (range ends are rounded inward)."""

import re
import sys

import pytest

from shtaerman.fem.mesh import MAX_THICKNESS, MIN_THICKNESS, check_thickness_range
from shtaerman.validation import InputError, bound_text, validate_positive
from shtaerman.vocabulary import Range

# 0.0125 (1 + 2^-52): the dynamic impact's refined radius, whose 0.01 x is a hair above
# 0.000125 m; nearest rounding printed [0.000125, 12.5] and refused 0.000125
REFINED = [0.0125000000000000003, 0.0125 * (1 + 2**-52), 0.026123456789, 1.0 / 3.0, 7.77777e-3]


def _printed_bounds(refined: float) -> tuple[str, str]:
    with pytest.raises(InputError) as error:
        check_thickness_range(1e-300, refined, "here")
    match = re.search(r"must lie in \[([^,]+), ([^\]]+)\] m", str(error.value))
    assert match, str(error.value)
    return match[1], match[2]


@pytest.mark.parametrize("refined", REFINED)
def test_the_printed_thickness_ends_are_accepted(refined):
    low, high = _printed_bounds(refined)
    check_thickness_range(float(low), refined, "here")  # no InputError: inside, as printed
    check_thickness_range(float(high), refined, "here")


def test_a_refused_thickness_is_printed_outside_the_range():
    refined = 0.0125 * (1 + 2**-52)
    assert MIN_THICKNESS * refined > 0.000125  # the case of the finding
    with pytest.raises(InputError, match=r"must lie in \[0\.000126, 12\.5\] m.*got 0\.000125$"):
        check_thickness_range(0.000125, refined, "here")
    assert MAX_THICKNESS * refined >= 12.5


@pytest.mark.parametrize(
    ("value", "side", "digits", "text"),
    [
        (0.1, "low", 3, "0.1"),  # float("0.1") is the bound itself: no step
        (0.1, "high", 3, "0.1"),
        (0.00012500000000000003, "low", 3, "0.000126"),
        (0.00012500000000000003, "high", 3, "0.000125"),
        (12.500000000000002, "high", 3, "12.5"),
        (12.500000000000002, "low", 3, "12.6"),
        (1.0 / 3.0, "low", 6, "0.333334"),
        (1.0 / 3.0, "high", 6, "0.333333"),
        (9.996, "low", 3, "10"),
        (0.0, "low", 3, "0"),
    ],
)
def test_bound_text_rounds_inward(value, side, digits, text):
    assert bound_text(value, side, digits) == text
    printed = float(text)
    assert printed >= value if side == "low" else printed <= value


def test_the_smallest_normal_float_is_printed_rounded_up():
    # 2.225e-308 < sys.float_info.min (a subnormal): it was refused as "at least 2.225e-308"
    assert 2.225e-308 < sys.float_info.min
    with pytest.raises(InputError, match=r"at least 2\.226e-308 .*got 2\.225e-308$"):
        validate_positive("mass", 2.225e-308, "kg")
    assert validate_positive("mass", 2.226e-308, "kg") == 2.226e-308


def test_a_vocabulary_range_with_more_digits_is_printed_inward():
    valid = Range(1.0 / 3.0, 2.0 / 3.0, low_open=False)
    assert valid.text() == "[0.333334, 0.666666]"
    assert valid.contains(0.333334) and valid.contains(0.666666)
    assert Range(0.05, 500.0, low_open=False).text() == "[0.05, 500]"  # exact ends unchanged


def test_the_printed_end_of_the_history_times_is_accepted():
    import shtaerman as sh

    # t_y = 0.010805367889682317 s at 1 m/s: the nearest 6 digits, 0.0108054, lie beyond it
    solution = sh.impact(
        sh.PowerLawIndenter(5.0, 1.5), sh.Material(7.5e6, 0.5), mass=0.7, velocity=1.0
    ).solution
    with pytest.raises(InputError, match=r"\[0, t_y\] = \[0, 0\.0108053\] s") as error:
        solution.history(times=[1.0])
    end = float(str(error.value).rsplit("[0, ", 1)[1].split("]")[0])
    assert end <= solution.t_y
    solution.history(times=[0.0, end])  # the printed end is accepted


def test_half_the_largest_dynamic_mesh_size_passes_the_estimate_ladder():
    # 0.1 doubled by the ladder (1/sqrt(2)^2) is 0.20000000000000007 in floats: the top of
    # (0, 0.2] must still be accepted, and a size the ladder cannot double names mesh_size
    from shtaerman.fem.dynamic_contact import DynamicSettings
    from shtaerman.study.dynamic.accuracy import check_ladder

    check_ladder(DynamicSettings(size=0.1, steps=100))
    with pytest.raises(InputError, match=r"mesh_size: .*\(0, 0\.1\].*got 0\.15"):
        check_ladder(DynamicSettings(size=0.15, steps=100))


def test_a_growth_refused_after_refinement_says_it_is_the_refined_mesh(capsys):
    """--growth 0.001 at --refine 50 is refused on the refined mesh's growth (2e-05): the line
    says so, and that the remedy is a lower --refine, not the growth range printed."""
    from cli_helpers import error_line

    line = error_line(capsys, "dynamic", "--refine", 50, "--growth", 0.001)
    assert line.startswith("--growth: must lie in [") and "got 2e-05" in line
    assert "the mesh's, after --refine divides --growth" in line
    assert line.endswith("raise --growth or lower --refine)")
