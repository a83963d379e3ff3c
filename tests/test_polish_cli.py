"""Options that would change nothing are refused (exit 2, one line) or, where the help says they
have no effect, warned about; an option typed with its default value counts as given; a layer's
contact text names the half-space it is compared with."""

import pytest

import shtaerman as sh
from shtaerman.cli import main
from shtaerman.cli.contact import _model_words, contact_text
from shtaerman.theory.indenter import PowerLawIndenter
from shtaerman.theory.layer import half_space_limit
from shtaerman.theory.materials import Material


class ReachedError(Exception):
    """Raised by a stand-in where the command would start computing."""


def _stop(*args, **kwargs):
    raise ReachedError


def _one_line_error(capsys, argv, words):
    assert main(argv) == 2
    out, err = capsys.readouterr()
    assert out == "" and err.count("\n") == 1 and words in err, err


def test_max_time_without_accuracy_is_refused(capsys, monkeypatch):
    monkeypatch.setattr("shtaerman.api.fem_contact._solve", _stop)  # the old code ran the curve
    words = "--max-time: applies with --accuracy only"  # the API's, by the table
    _one_line_error(capsys, ["contact", "--max-time", "30"], words)
    # with --accuracy it reaches the computation
    with pytest.raises(ReachedError):
        main(["contact", "--max-time", "30", "--accuracy", "1e-3"])


def test_verify_extended_with_named_studies_is_refused(capsys, monkeypatch):
    monkeypatch.setattr("shtaerman.study.schema.find_study", _stop)  # the old code loaded it
    _one_line_error(capsys, ["verify", "paper", "--extended"], "--extended: applies to the shipped")


def test_layer_rate_on_a_massless_body_is_refused(capsys, monkeypatch):
    monkeypatch.setattr("shtaerman.study.dynamic.case.run_case", _stop)  # the old code ran it
    argv = ["dynamic", "--density2", "0", "--layer-rate", "5", "--no-estimate"]
    _one_line_error(capsys, argv, "--layer-rate: applies to a body with mass only")
    body = Material(7.5e6, 0.5, density=0.0)
    with pytest.raises(sh.InputError, match=r"^layer_rate: applies to a body with mass only"):
        sh.dynamic(PowerLawIndenter(5.0, 1.5), body, mass=0.7, velocity=3.0, layer_rate=5.0)
    with pytest.raises(ReachedError):  # not given: the massless run goes on
        main(["dynamic", "--density2", "0", "--no-estimate"])


def test_volumetric_at_nu2_one_half_warns_and_leaves_the_header(capsys, monkeypatch):
    class Finished:
        def to_dict(self):
            return {"model": "neo-hookean"}

    monkeypatch.setattr("shtaerman.cli.contact.contact", lambda *a, **k: Finished())
    argv = ["contact", "--model", "neo-hookean", "--volumetric", "logarithmic", "--json"]
    assert main(argv) == 0  # the run goes on
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "--volumetric has no effect at --nu2 0.5" in err
    assert main([*argv, "--nu2", "0.45"]) == 0
    assert capsys.readouterr().err == ""
    report = {"model": "neo-hookean", "volumetric": "logarithmic", "nu2": 0.5}
    assert _model_words(report) == "Neo-Hookean"  # it named the logarithmic energy
    report["nu2"] = 0.45
    assert _model_words(report) == "Neo-Hookean (logarithmic volumetric energy)"


@pytest.mark.parametrize(
    ("typed", "field", "value"),
    [(["--time-steps", "200"], "time_steps", 200), (["--mesh-size", "0.025"], "mesh_size", 0.025)],
)
def test_a_typed_default_reaches_the_finite_strain_impact(monkeypatch, typed, field, value):
    # 200 steps and 0.025 are the linear impact's defaults: the value typed was replaced by
    # the finite-strain impact's own default (50 steps) without a word
    seen = {}

    def route(problem, **numerics):
        seen.update(numerics)
        raise ReachedError

    monkeypatch.setattr("shtaerman.study.dynamic.case.finite_settings", route)
    with pytest.raises(ReachedError):
        main(["dynamic", "--model", "neo-hookean", "--density2", "0", *typed])
    assert seen[field] == value
    with pytest.raises(ReachedError):
        main(["dynamic", "--model", "neo-hookean", "--density2", "0"])
    assert seen["time_steps"] is None and seen["mesh_size"] is None  # not given


def test_a_linear_option_typed_with_its_default_is_refused_with_a_model(capsys):
    argv = ["dynamic", "--model", "neo-hookean", "--density2", "0", "--growth", "0.2"]
    _one_line_error(capsys, argv, "growth: not supported with model 'neo-hookean'")


def test_the_layer_contact_text_compares_with_the_half_space():
    indenter, body = PowerLawIndenter(5.0, 1.5), Material(7.5e6, 0.5)
    depth = float(half_space_limit(indenter, body).depth(0.01))
    result = sh.contact(
        indenter, body, depths=[depth], thickness=0.02, mesh_size=1 / 60, estimate=False
    )
    text = contact_text(result.to_dict())
    assert "vs half-space" in text and "p0/pavg half-space" in text
    assert "pressure profile L2 departure from the half-space" in text
    assert "exact" not in text and "L2 error" not in text


def test_the_finite_strain_layer_text_names_the_layer_and_the_half_space_reference():
    from shtaerman.cli.contact import finite_contact_text

    result = sh.contact(
        PowerLawIndenter(5.0, 1.5),
        Material(7.5e6, 0.5),
        depths=[1e-3],
        thickness=0.1,
        model="neo-hookean",
        mesh_size=0.1,
        estimate=False,
    )
    rows = finite_contact_text(result.to_dict()).splitlines()
    # the layer went unmentioned: its /lin columns read as the layer's own linear solution
    assert rows[1] == (
        "  layer H = 0.1 m on a bonded rigid base: /lin = against the linear half-space, not "
        "the layer"
    )


@pytest.mark.parametrize(("keyword", "value"), [("mesh_size", 0.5), ("mesh_size", 0.9)])
def test_the_finite_strain_api_states_the_command_lines_ranges(keyword, value):
    # sh.dynamic(model=...) took mesh_size 0.5, which the CLI refuses
    from shtaerman.validation import InputError

    with pytest.raises(InputError, match=rf"^{keyword} must (be|lie in)"):
        sh.dynamic(
            PowerLawIndenter(5.0, 1.5),
            Material(7.5e6, 0.5),
            mass=0.7,
            velocity=3.0,
            model="neo-hookean",
            density=0.0,
            **{keyword: value},
        )
