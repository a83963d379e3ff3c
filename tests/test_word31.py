"""Two one-line refusals of a study file said something else than the file can take."""

from pathlib import Path

import pytest
from study_texts import DYNAMIC_STUDY

from shtaerman.cli import main
from shtaerman.study.schema import StudyError, load_study


def test_a_lubricated_finite_strain_pad_suggests_only_what_the_kind_takes(tmp_path: Path):
    """The finite-strain study refuses [rubber] model = "linear": its refusal of a lubricated
    base may not offer it (the Problem's wording does, where a linear model runs)."""
    path = tmp_path / "pad.toml"
    assert main(["init-study", str(path), "--kind", "finite-strain"]) == 0
    text = path.read_text().replace("# [layer]", "[layer]")
    text = text.replace("# thickness = 0.02", "thickness = 0.02")
    path.write_text(text.replace('#   base = "bonded"', 'base = "lubricated"'))
    with pytest.raises(StudyError) as refused:
        load_study(path)
    message = str(refused.value)
    assert "key 'layer.base': a layer at finite strain is bonded only" in message, message
    assert 'take [layer] base = "bonded", or a study of kind "contact"' in message, message
    assert 'linear"' not in message and "[rubber]" not in message and "\n" not in message


def test_a_prony_refusal_names_its_key_once(tmp_path: Path):
    path = tmp_path / "visco.toml"
    path.write_text(DYNAMIC_STUDY.replace("density2 = 1100.0", 'density2 = 0\nprony = "1.5:2e-3"'))
    with pytest.raises(StudyError) as refused:
        load_study(path)
    message = str(refused.value)
    assert message.startswith(f"{path}: key 'half_space.prony': weight g1"), message
    reason = message.removeprefix(f"{path}: key 'half_space.prony': ")
    assert "prony" not in reason and "\n" not in message
