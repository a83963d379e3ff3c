"""A study file's refusals are the command line's checks in the file's words (user58's files).

Depths the FEM cannot take (a force beyond the floats, a span one mesh cannot resolve) are
refused in one line naming ``contact.depths`` and the depth at fault; an exponent or nu2
outside a study kind's range states that range whatever the bad value (the theory's own,
wider range used to reach the message first).
"""

import re

import pytest

from shtaerman.cli import main
from shtaerman.study.schema import StudyError, load_study

KINDS = ("contact", "dynamic", "finite-strain", "effects")


def template(tmp_path, kind, line, value):
    """The ``init-study --kind`` template with the first ``line = ...`` set to ``value``."""
    path = tmp_path / f"{kind}.toml"
    assert main(["init-study", "--kind", kind, "--force", str(path)]) == 0
    text = path.read_text()
    changed = re.sub(rf"(?m)^{line} = [^#\n]*", f"{line} = {value}  ", text, count=1)
    assert changed != text
    path.write_text(changed)
    return path


def refusal(capsys, *argv):
    """The one line of a refused command: exit 2, no other line of shtaerman's (no warning)
    on stderr and no traceback (a study's progress lines may come before it)."""
    code = main(list(argv))
    err = capsys.readouterr().err
    said = [line for line in err.splitlines() if line.startswith("shtaerman: ")]
    assert code == 2 and len(said) == 1 and "Traceback" not in err, (code, err)
    assert err.endswith(said[0] + "\n")
    return said[0]


def test_a_force_beyond_the_floats_is_refused_by_the_clis_check(tmp_path, capsys):
    path = template(tmp_path, "contact", "depths", "[1e-3, 1e300]")
    with pytest.raises(StudyError) as error:
        load_study(path)  # at load, before any mesh (was: SuperLU "exactly singular")
    said = str(error.value)
    assert "key 'contact.depths': 1e+300 m gives a contact force of inf N" in said
    assert said.endswith("give depths of a physical size")
    line = refusal(capsys, "verify", str(path), "--quick", "--out", str(tmp_path / "out"))
    assert "key 'contact.depths'" in line and "--depths" not in line
    # the command line's own refusal, without numpy's overflow warning before it
    line = refusal(capsys, "contact", "--depths", "1e-3,1e300")
    assert line.startswith("shtaerman: error: --depths: 1e+300 m gives a contact force of inf")


def test_depths_one_mesh_cannot_span_name_the_deepest_in_the_files_words(tmp_path, capsys):
    path = template(tmp_path, "contact", "depths", "[1e-3, 1e10]")
    line = refusal(capsys, "verify", str(path), "--quick", "--out", str(tmp_path / "out"))
    assert "key 'contact.depths': the smallest, 0.001 m, loads 1 surface node(s)" in line
    assert "on the mesh that the deepest, 1e+10 m, sizes (refined to r = " in line
    assert line.rstrip().endswith("([quick] mesh_size, [quick] refine)")  # not --mesh-size
    line = refusal(capsys, "contact", "--depths", "1e-3,1e10")
    assert "--depths: the smallest, 0.001 m" in line and "(--mesh-size, --refine)" in line


def said_of(tmp_path, kind, line, value):
    with pytest.raises(StudyError) as error:
        load_study(template(tmp_path, kind, line, value))
    return str(error.value).partition(": key ")[2]


@pytest.mark.parametrize("kind", KINDS)
def test_every_bad_exponent_states_the_kinds_range(tmp_path, kind):
    """The FEM's n in (1, 20] (bounded p(0)): 1e300 was "[0.25, 20] (force law ...)", the
    exact theory's, and an effects study's nan "[0.25, 20]"."""
    for value in ("0.5", "1e300", "nan"):
        said = said_of(tmp_path, kind, "exponent", value)
        assert said.startswith("'indenter.exponent': exponent must ") and "in (1, 20]" in said


@pytest.mark.parametrize("kind", KINDS)
def test_every_bad_nu2_states_the_kinds_range(tmp_path, kind):
    """The FEM's nu2 in [0, 0.5]: an effects study said "(-1, 0.5]" of nan and "half"."""
    for value in ("-0.3", "nan", '"half"'):
        said = said_of(tmp_path, kind, "nu2", value)
        assert said.startswith("'half_space.nu2': nu2 must ") and "in [0, 0.5]" in said, said
