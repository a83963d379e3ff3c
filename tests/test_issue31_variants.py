"""Variants of issue 31's attacks (other names, values and orders) that found a defect."""

from pathlib import Path

from shtaerman.cli import main

ROOT = Path(__file__).resolve().parents[1]


def run(capsys, *argv):
    code = main([str(arg) for arg in argv])
    out, err = capsys.readouterr()
    return code, out, err


def test_contact_with_a_huge_mass_names_the_mass(capsys):
    # the depths come from the impact's x_c: the mass, not E2, makes the contact zone huge
    code, _, err = run(capsys, "contact", "--mass", "1e300")
    assert code == 2
    assert err.count("\n") == 1 and err.startswith("shtaerman: error: --mass, --velocity: ")
    assert "lower the mass" in err and "check E2" not in err


def test_a_contact_study_with_a_huge_mass_names_the_mass(capsys, tmp_path):
    text = (ROOT / "fem" / "hertz.toml").read_text()
    lines = ["mass = 1e300" if line.startswith("mass =") else line for line in text.splitlines()]
    study = tmp_path / "big.toml"
    study.write_text("\n".join(lines) + "\n")
    code, _, err = run(
        capsys, "verify", study, "--quick", "--workers", "1", "--out", tmp_path / "o"
    )
    assert code == 2
    last = err.strip().splitlines()[-1]
    assert "mass, velocity: 1e+300 kg" in last and "check E2" not in last
