"""The words of a bad Prony input (session 63's adversary), the same on every route: the
command line (``dynamic --prony``), the API (:func:`shtaerman.theory.prony_sources.prony_input`,
which :class:`shtaerman.Body` calls) and a study file's ``[half_space] prony``."""

from pathlib import Path

import pytest
from study_texts import DYNAMIC_STUDY

from shtaerman.cli import main
from shtaerman.study.schema import StudyError, load_study
from shtaerman.theory.prony_sources import PRONY_FORM, prony_input
from shtaerman.theory.viscoelastic import PronySeries
from shtaerman.validation import InputError

FORM = PRONY_FORM.removeprefix("write ")


def _reasons(tmp_path: Path, prony: str, capsys) -> list[str]:
    """The reason each route gives for ``prony``, its own prefix (the parameter) taken off."""
    assert main(["dynamic", f"--prony={prony}", "--no-estimate"]) == 2
    said = capsys.readouterr().err
    assert said.count("\n") == 1, said  # one line
    with pytest.raises(InputError) as api:
        prony_input(prony)
    study = tmp_path / "visco.toml"
    study.write_text(
        DYNAMIC_STUDY.replace("density2 = 1100.0", f'density2 = 1100.0\nprony = "{prony}"')
    )
    with pytest.raises(StudyError) as loaded:
        load_study(study)
    return [
        said.removeprefix("shtaerman: error: --prony: ").rstrip("\n"),
        str(api.value).removeprefix("prony: "),
        str(loaded.value).removeprefix(f"{study}: key 'half_space.prony': "),
    ]


def test_a_garbage_row_past_the_term_limit_is_named_as_an_earlier_one(tmp_path, capsys):
    # 21 good terms on lines 2-22 and garbage on line 23: main read "more than 20 terms", as if
    # the row were a term; line 23 is among the rows read, so it is named as line 7 would be
    rows = tmp_path / "rows.csv"
    good = "".join(f"{1e-3 * (1 + k)},0.01\n" for k in range(21))
    rows.write_text(f"tau,g\n{good}garbage,xx\n")
    said = f"rows.csv: line 23, column tau must be a number, got 'garbage' ({PRONY_FORM})"
    assert _reasons(tmp_path, str(rows), capsys) == [said] * 3
    rows.write_text(f"tau,g\n{good}")  # the same 21 good terms alone: too many
    assert (
        _reasons(tmp_path, str(rows), capsys)
        == [f"rows.csv: more than 20 terms ({PRONY_FORM})"] * 3
    )


def test_a_prony_header_of_three_columns_is_refused_as_the_header(tmp_path, capsys):
    # main told the 2-cell rows under 'tau,g,x' to take the header's 3 columns, which the
    # header check then refuses: the header, on line 1, is at fault
    three = tmp_path / "three.csv"
    three.write_text("# relaxation\ntau,g,x\n0.001,0.1\n")
    said = (
        "three.csv: line 2: the header must be 'tau [s],E [Pa]' or 'tau [s],g [1]', got "
        f"'tau,g,x' ({PRONY_FORM})"
    )
    assert _reasons(tmp_path, str(three), capsys) == [said] * 3
    three.write_text("tau,g\n0.001,0.1\n0.01,0.2,7\n")  # a row of 3 cells under a right header
    said = "three.csv: line 3: 3 cells where the header has 2; give every row the header's columns"
    assert _reasons(tmp_path, str(three), capsys) == [f"{said} ({PRONY_FORM})"] * 3


def test_a_csv_of_old_mac_line_ends_is_read(tmp_path):
    # CR alone ends a line in old Mac files (valid CSV); main showed Python's csv.Error about
    # "universal-newline mode". The series read is the one written
    mac = tmp_path / "mac.csv"
    mac.write_bytes(b"tau [s],g [1]\r0.001,0.1\r0.01,0.2\r")
    assert prony_input(str(mac)) == PronySeries((0.1, 0.2), (1e-3, 1e-2))
    mac.write_bytes(b"tau,g\r0.001,0.1\r0.01,\xe9\r")  # a Latin-1 e acute: line 3, column 6
    with pytest.raises(InputError, match=r"': line 3, column 6: byte 0xe9 is not UTF-8"):
        prony_input(str(mac))


@pytest.mark.parametrize(
    ("text", "empty"),
    [("," * 10**6, 1), ("0.1:1e-3,,0.2:1e-2", 2), ("1e6;1e5:1,", 2), ("1e6;,1e5:1", 1)],
)
def test_a_series_text_of_empty_terms_names_the_first(tmp_path, capsys, text, empty):
    # a million bare commas read "1000001 terms is too many"; they are empty terms, the first
    # named (in the moduli form the terms after 'Einf;' are counted)
    said = f"must be written {FORM}; term {empty} is empty (a doubled, leading or trailing comma)"
    assert _reasons(tmp_path, text, capsys) == [said] * 3
