"""A sweep axis value that is no number names the valid range, as one out of range does
(polish49: ``mass = ["heavy"]`` said "must be a number in kg" without "> 0")."""

from __future__ import annotations

import pytest

from shtaerman.sweep.kinds import KINDS, get_kind
from shtaerman.sweep.spec import RANGES_OF, SweepError, parse_sweep
from shtaerman.vocabulary import VOCABULARY

ENTRIES = {item.name: item for item in VOCABULARY}


def _ranged():
    """(kind, parameter, the range in words) of every number parameter of a sweepable kind
    that the vocabulary gives a range for that kind."""
    found = []
    for name, kind in sorted(KINDS.items()):
        if not kind.case:
            continue
        ranges = RANGES_OF.get(name, name)
        for key, parameter in get_kind(name).parameters.items():
            item = ENTRIES.get(key)
            if parameter.type in ("float", "int") and item and ranges in item.kinds:
                text = item.range_text(ranges)
                if text:
                    found.append((name, key, text))
    return found


RANGED = _ranged()


def test_the_check_covers_the_axes_of_the_issue():
    assert ("impact", "mass", "> 0") in RANGED  # the issue's axis
    assert len({kind for kind, _, _ in RANGED}) >= 3  # every sweepable kind's numbers


@pytest.mark.parametrize(("kind", "key", "text"), RANGED)
def test_a_non_number_on_an_axis_names_its_range(kind, key, text):
    toml = f'name = "words"\nkind = "{kind}"\n[axes]\n{key} = ["heavy"]\n'
    with pytest.raises(SweepError) as caught:
        parse_sweep(toml)
    said = str(caught.value)
    assert f"axes.{key}[0] must be " in said and said.endswith("got 'heavy'"), said
    assert text.removesuffix(", or inf (rigid)") in said, said
