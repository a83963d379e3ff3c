"""Figures for a paper: --figure-format, readable labels, per cent, and unresolved points.

Vector files are checked by their magic bytes and their text (matplotlib keeps SVG text as
text: the readable label is searchable in the file); PNGs as images (resolution, colours).
Drawing details are checked on the matplotlib Figure a function would save (saving replaced by
capturing), so each test reads what a reader sees: axis data, labels, marker fill.
"""

import json
import math
from pathlib import Path
from types import SimpleNamespace

import numpy as np
import pytest
from figure_helpers import capture, svg_text
from PIL import Image

from shtaerman.cli import main
from shtaerman.fem.mesh import HALF_SPACE
from shtaerman.plots import curves, dynamic, finite, labels, style
from shtaerman.study.contact.convergence import ConvergenceStudy
from shtaerman.sweep import figures as sweep_figures_module
from shtaerman.sweep.figures import sweep_figures
from shtaerman.validation import InputError

LEVELS = [
    {"size": h, "dofs": int(2000 / h**1.2), "errors": {"force": 3e-2 * h**2, "beta": 2e-2 * h}}
    for h in (0.1, 0.05, 0.025)
]


# --- labels -------------------------------------------------------------------------------------


def test_labels_name_quantities_with_units_and_percent():
    minus = labels.MINUS
    assert labels.axis_label("velocity") == "Approach velocity v0 (m/s)"
    assert labels.axis_label("energy_radiated_fraction") == (
        f"Energy left in the body 1 {minus} e² (%)"  # a pad or a half-space alike
    )
    assert labels.scale("difference_worst") == 100.0 and labels.scale("restitution") == 1.0
    # errors are fractions, shown in per cent, named after their quantity
    error = labels.describe("error_difference_x")
    assert error.percent and error.text.startswith("Error of maximum approach")
    assert labels.describe("force_ratio_xa25").text == "P / P of the linear FEM at x/a = 0.25"
    # a key the table does not know keeps its name and the unit it comes with
    assert labels.axis_label("my_output", "J") == "my_output (J)"
    assert labels.axis_label("my_output") == "my_output"


def test_every_sweep_key_has_a_readable_label():
    from shtaerman.sweep.kinds import KINDS
    from shtaerman.vocabulary import KIND_NAMES

    keys = set()
    for kind in (KINDS[name] for name in KIND_NAMES):  # shipped kinds, not the tests' probes
        keys |= {*kind.parameters, *kind.outputs}
        keys |= {key for outputs in kind.optional_outputs.values() for key in outputs}
    assert sorted(key for key in keys if labels.describe(key).text == key) == []
    # every difference and error a sweep reports is a fraction: shown in per cent
    assert all(labels.is_percent(k) for k in keys if k.startswith(("difference_", "error_")))


# --- formats ------------------------------------------------------------------------------------


@pytest.mark.parametrize("figure_format", ["svg", "pdf"])
def test_vector_figure_beside_the_png(tmp_path, figure_format):
    study = ConvergenceStudy.from_levels(LEVELS)
    path = curves.plot_convergence(study, tmp_path / "convergence.png", figure_format=figure_format)
    assert path == tmp_path / "convergence.png"
    assert Image.open(path).format == "PNG"
    twin = tmp_path / f"convergence.{figure_format}"
    if figure_format == "pdf":
        assert twin.read_bytes()[:5] == b"%PDF-"
    else:
        text = svg_text(twin)
        assert "Relative error (%)" in text and "Element size" in text
    assert sorted(p.name for p in tmp_path.iterdir()) == sorted([path.name, twin.name])


def test_a_vector_path_writes_that_format_alone(tmp_path):
    path = curves.plot_convergence(ConvergenceStudy.from_levels(LEVELS), tmp_path / "c.svg")
    svg_text(path)
    assert [p.name for p in tmp_path.iterdir()] == ["c.svg"]


def test_bad_figure_format_is_one_line(tmp_path):
    study = ConvergenceStudy.from_levels(LEVELS)
    with pytest.raises(InputError, match=r"^figure_format must be one of png, svg, pdf, got 'jpg'"):
        curves.plot_convergence(study, tmp_path / "c.png", figure_format="jpg")
    with pytest.raises(InputError, match=r"must end in \.png, \.svg or \.pdf"):
        curves.plot_convergence(study, tmp_path / "c.gif")
    with pytest.raises(InputError, match="figure_format"):  # the keyword (guards55)
        sweep_figures(tmp_path / "results.json", tmp_path, figure_format="eps")
    assert list(tmp_path.iterdir()) == []


def test_field_pictures_refuse_a_vector_path(tmp_path):
    from shtaerman.plots import render

    with render.picture() as plotter, pytest.raises(InputError, match="PNG only"):
        render.save(plotter, tmp_path / "field.svg")
    assert list(tmp_path.iterdir()) == []


@pytest.mark.parametrize("command", ["contact", "dynamic", "verify", "sweep"])
def test_every_figure_command_takes_figure_format(command, capsys):
    with pytest.raises(SystemExit):
        main([command, "--help"])
    help_text = " ".join(capsys.readouterr().out.split())
    assert "--figure-format FORMAT" in help_text
    assert "field renders (pyvista) stay PNG only" in help_text
    assert main([command, "--figure-format", "gif"]) == 2
    assert "--figure-format: invalid choice: 'gif'" in capsys.readouterr().err


# --- the convergence plot -----------------------------------------------------------------------


def test_convergence_is_drawn_against_the_element_size(tmp_path, monkeypatch):
    # the legend states the order p of error ~ h^p: the axis is h, not the number of unknowns
    study = ConvergenceStudy.from_levels(LEVELS)
    figure = capture(
        monkeypatch, curves, lambda: curves.plot_convergence(study, tmp_path / "c.png")
    )
    axes = figure.axes[0]
    force = axes.get_lines()[0]
    assert list(force.get_xdata()) == [0.1, 0.05, 0.025]
    assert force.get_ydata() == pytest.approx([100 * 3e-2 * h**2 for h in (0.1, 0.05, 0.025)])
    assert "Element size" in axes.get_xlabel() and axes.get_ylabel() == "Relative error (%)"
    assert r"h^p" in figure.legends[0].get_title().get_text()
    assert force.get_label().startswith("Force P (order 2.00")
    [top] = axes.child_axes  # the number of unknowns of each mesh, at its size
    ticks = top.xaxis.get_ticklabels()
    assert [t.get_text() for t in ticks] == [f"{row['dofs']:,}" for row in LEVELS]
    assert list(top.get_xticks()) == [0.1, 0.05, 0.025]


# --- sweep heat maps and curves -----------------------------------------------------------------


def difference_results(tmp_path, axes, values, errors):
    results = {
        "spec": {"name": "validity", "kind": "dynamic", "axes": axes},
        "kind": {
            "outputs": {"difference_worst": "", "error_difference_worst": ""},
            "levels": {"difference_worst": [0.01, 0.05]},
            "parameter_units": {"velocity": "m/s", "density2": "kg/m^3"},
        },
        "cases": [
            {
                "index": i,
                "status": "ok",
                "outputs": {"difference_worst": v, "error_difference_worst": e},
            }
            for i, (v, e) in enumerate(zip(values, errors, strict=True))
        ],
    }
    path = tmp_path / "results.json"
    path.write_text(json.dumps(results))
    return path


HEAT = {"density2": [900.0, 1100.0], "velocity": [1.0, 2.0, 3.0]}
VALUES = [0.005, 0.02, 0.06, 0.0008, 0.03, 0.07]
ERRORS = [0.001, 0.004, 0.002, 0.002, 0.001, 0.003]  # the fourth case: error > |value|


def test_heat_map_has_readable_title_percent_and_200_dpi(tmp_path):
    results = difference_results(tmp_path, HEAT, VALUES, ERRORS)
    paths = sweep_figures(results, tmp_path / "fig", figure_format="svg")
    png = tmp_path / "fig" / "difference_worst.png"
    assert png in paths
    assert Image.open(png).info["dpi"][0] == pytest.approx(200, abs=0.5)
    text = svg_text(png.with_suffix(".svg"))
    assert "Largest |quasi-static / dynamic" in text and "validity sweep (dynamic)" in text
    assert ">difference_worst<" not in text  # the raw key is no title or label any more
    assert "Approach velocity v0 (m/s)" in text and "Half-space density" in text
    for cell in ("0.5 %", "2 %", "6 %", "3 %", "7 %", "± 0.1 %"):  # fractions in per cent
        assert f">{cell}<" in text
    assert text.count(">unresolved<") == 1  # the 0.08 % ± 0.2 % case is no data


def test_heat_map_hatches_the_unresolved_cell(tmp_path, monkeypatch):
    results = difference_results(tmp_path, HEAT, VALUES, ERRORS)
    figure = capture(
        monkeypatch, sweep_figures_module, lambda: sweep_figures(results, tmp_path / "fig")
    )  # the first output's figure: the difference (then the error's, not captured)
    axes = figure.axes[0]
    shown = axes.get_images()[0].get_array()
    assert shown.mask[1, 0] and not shown.mask[0, 0]  # no colour for the unresolved cell
    assert shown[0, 2] == pytest.approx(6.0)  # per cent
    hatched = [p for p in axes.patches if p.get_hatch()]
    assert len(hatched) == 1 and hatched[0].get_xy() == (-0.5, 0.5)


def test_sweep_curve_draws_unresolved_points_open(tmp_path, monkeypatch):
    results = difference_results(tmp_path, {"velocity": [1, 2, 3, 4, 5, 6]}, VALUES, ERRORS)
    figure = capture(
        monkeypatch, sweep_figures_module, lambda: sweep_figures(results, tmp_path / "fig")
    )
    axes = figure.axes[0]
    data, unresolved = axes.get_lines()[0], axes.get_lines()[-1]
    assert np.isnan(data.get_ydata()[3]) and data.get_ydata()[2] == pytest.approx(6.0)
    assert list(unresolved.get_xdata()) == [4] and unresolved.get_markerfacecolor() == "white"
    assert axes.get_ylabel().endswith("(%)")


def test_heat_map_shows_si_values_with_a_prefix(tmp_path):
    # p_c in Pa and E2 in Pa over the axis: MPa, as a reader writes them (values 5.4e6 ...)
    results = {
        "spec": {"name": "grid", "kind": "impact", "axes": {"E2": [5e6, 7.5e6], "nu2": [0.3, 0.5]}},
        "kind": {"outputs": {"p_c": "Pa"}, "parameter_units": {"E2": "Pa", "nu2": ""}},
        "cases": [
            {"index": i, "status": "ok", "outputs": {"p_c": v}}
            for i, v in enumerate([5.41e6, 6.4e6, 7.12e6, 8.43e6])
        ],
    }
    path = tmp_path / "results.json"
    path.write_text(json.dumps(results))
    sweep_figures(path, tmp_path / "fig", figure_format="svg")
    text = svg_text(tmp_path / "fig" / "p_c.svg")
    assert "Quasi-static maximum central pressure p_c (MPa)" in text
    assert "modulus E2 (MPa)" in text
    for shown in (">5.41<", ">8.43<", ">7.5<", ">5<"):
        assert shown in text


# --- unresolved points of the study figures -----------------------------------------------------


def test_points_open_where_unresolved():
    assert list(style.unresolved([0.1, 0.01, -0.05], [0.02, 0.02, math.nan])) == [
        False,
        True,
        True,
    ]
    assert not style.unresolved([0.0], None).any()


def fake_finite(estimated: bool):
    """A finite-strain outcome's shape: at x/a < 0.4 the linear FEM's p(0)/p_avg is 2.25-2.33
    against the exact 2.5 (the mesh's error, 7-10 %), above the finite-strain effect there."""
    x_a = np.array([0.1, 0.2, 0.3, 0.5, 0.8, 1.0])
    linear_centre = np.array([2.25, 2.3, 2.33, 2.47, 2.49, 2.5])
    finite_centre = linear_centre * (1 + 0.2 * x_a**2)  # the effect: 0.2 % .. 20 %
    rows = [
        {
            "depth_to_radius": r,
            "force_ratio": 1 + 0.1 * r**2,
            "force_linear_fem": 1.001,
            "force_linear": 1.0,
            "central_to_mean": c,
        }
        for r, c in zip(x_a, finite_centre, strict=True)
    ]
    steps = [
        SimpleNamespace(central_pressure=c, contact_radius=1 / math.sqrt(math.pi), force=1.0)
        for c in linear_centre
    ]
    estimates = None
    if estimated:
        error = SimpleNamespace(error=1e-3)
        estimates = SimpleNamespace(
            steps=[{"force_ratio": error, "central_to_mean": error} for _ in rows]
        )
    return SimpleNamespace(
        rows=lambda: rows,
        linear_fem=SimpleNamespace(steps=steps),
        finite=SimpleNamespace(exact=SimpleNamespace(central_to_mean_ratio=2.5)),
        at_maximum=lambda: {"depth_to_radius": 0.8},
        estimates=estimates,
        study=SimpleNamespace(rubber=SimpleNamespace(name="neo-hookean")),  # the legend's
    )


@pytest.mark.parametrize("estimated", [False, True])
def test_finite_ratios_draw_unresolved_depths_open(tmp_path, monkeypatch, estimated):
    outcome = fake_finite(estimated)
    figure = capture(
        monkeypatch, finite, lambda: finite.plot_finite_ratios(outcome, tmp_path / "f.png")
    )
    bottom = figure.axes[1]
    by_label = {line.get_label(): line for line in bottom.get_lines()}
    # x/a = 0.1, 0.2, 0.3: effect 0.2-1.8 % < the linear FEM's 7-10 % error: no data there
    for label in ("neo-Hookean FEM", "linear FEM, same mesh"):
        assert np.isnan(by_label[label].get_ydata()[:3]).all()
        assert np.isfinite(by_label[label].get_ydata()[3:]).all()
        opened = by_label[f"{label}, unresolved"]
        assert list(opened.get_xdata()) == [0.1, 0.2, 0.3]
        assert opened.get_markerfacecolor() == "white"
    bars = [c for c in bottom.containers if c.has_yerr]
    assert bool(bars) == estimated  # error bars from the mesh ladder's estimates
    # the scale is the resolved values' (2.47 .. 3.0); the six unresolved ones are below it
    assert 2.4 < bottom.get_ylim()[0] < 2.47
    assert [t.get_text() for t in bottom.texts] == ["6 unresolved points off scale"]


def fake_dynamic(errors):
    cases = [
        SimpleNamespace(
            result=SimpleNamespace(restitution=0.95, energy_radiated_fraction=0.1 * v),
            differences=lambda v=v: {"x": 0.01 * v, "P": 0.02 * v, "t": -0.001},
        )
        for v in (1.0, 2.0, 3.0)
    ]
    return SimpleNamespace(
        velocities=[1.0, 2.0, 3.0],
        cases=cases,
        study=SimpleNamespace(geometry=HALF_SPACE),  # the half-space: its estimate is drawn
        estimate_curve=lambda: {
            "velocity": [1.0, 3.0],
            "restitution": [0.97, 0.9],
            "energy_fraction": [0.05, 0.2],
        },
        difference_errors=lambda: errors,
    )


def test_dynamic_over_velocity_in_percent_with_unresolved_open(tmp_path, monkeypatch):
    errors = {"x": [0.002] * 3, "P": [0.002] * 3, "t": [0.004] * 3}
    outcome = fake_dynamic(errors)
    figure = capture(
        monkeypatch,
        dynamic,
        lambda: dynamic.plot_dynamic_over_velocity(outcome, tmp_path / "d.png"),
    )
    _, loss, ratio, time = figure.axes
    assert loss.get_ylabel().endswith("(%)")
    assert list(loss.get_lines()[0].get_ydata()) == pytest.approx([10.0, 20.0, 30.0])
    lines = {line.get_label(): line for line in ratio.get_lines()}
    assert list(lines["$P_c/P_{max} - 1$"].get_ydata()) == pytest.approx([2.0, 4.0, 6.0])
    # t: -0.1 % against an estimated error of 0.4 %: every point unresolved, open
    time_lines = {line.get_label(): line for line in time.get_lines()}
    assert np.isnan(time_lines["$t_y/t_{contact} - 1$"].get_ydata()).all()
    assert time_lines["$t_y/t_{contact} - 1$, unresolved"].get_markerfacecolor() == "white"
    assert ratio.get_xlabel() == "Approach velocity v0 (m/s)"


# --- every command that writes figures ----------------------------------------------------------


def test_sweep_cli_writes_vector_heat_maps(tmp_path):
    sweep = tmp_path / "grid.toml"
    sweep.write_text(
        'name = "grid"\nkind = "impact"\n[axes]\nvelocity = [1.0, 2.0]\nnu2 = [0.3, 0.5]\n'
    )
    out = tmp_path / "out"
    argv = ["sweep", str(sweep), "--out", str(out), "--workers", "1", "--figure-format", "pdf"]
    assert main(argv) == 0
    figures = out / "figures"
    assert (figures / "x_c.png").is_file()
    assert (figures / "x_c.pdf").read_bytes()[:5] == b"%PDF-"
    assert {p.suffix for p in figures.iterdir()} == {".png", ".pdf"}


def test_contact_out_writes_its_charts_in_the_format(tmp_path):
    out = tmp_path / "out"
    argv = ["contact", "--no-estimate", "--out", str(out), "--figure-format", "svg"]
    assert main([*argv, "--mesh-size", "0.02", "--domain-factor", "1e4"]) == 0
    for stem in ("force_depth", "pressure"):
        assert Image.open(out / f"{stem}.png").format == "PNG"
    assert "Depth" in svg_text(out / "force_depth.svg")
    assert "Contact pressure" in svg_text(out / "pressure.svg")


def test_dynamic_out_writes_history_chart_and_wave_fields(tmp_path):
    out = tmp_path / "out"
    argv = ["dynamic", "--no-estimate", "--out", str(out), "--figure-format", "pdf"]
    assert main([*argv, "--steps", "100", "--mesh-size", "0.05"]) == 0
    assert (out / "dynamic_history.pdf").read_bytes()[:5] == b"%PDF-"
    assert Image.open(out / "dynamic_history.png").format == "PNG"
    waves = sorted(out.glob("wave_field_*"))
    assert [p.suffix for p in waves] == [".png"] * 3  # the kept times; field renders stay PNG
    assert np.asarray(Image.open(waves[1]).convert("L")).std() > 10  # not blank


def test_verify_writes_vector_charts_and_keeps_pngs_for_the_report(
    quick_outcomes, tmp_path, monkeypatch
):
    from conftest import quick_study_files

    import shtaerman.output.folder

    def cached(study, *, quick=False, progress=None):
        assert quick and quick_outcomes[study.name].study == study
        return quick_outcomes[study.name]

    monkeypatch.setattr(shtaerman.output.folder, "run_study", cached)
    out = tmp_path / "run"
    paper = [path for path in quick_study_files() if Path(path).stem == "paper"]
    argv = ["verify", "--quick", "--workers", "1", "--figure-format", "pdf", "--out", str(out)]
    main([*argv, *paper])
    results = json.loads((out / "results.json").read_text())
    named = list(results["studies"]["paper"]["figures"].values())
    assert named and all(name.endswith(".png") for name in named)  # the reports show PNGs
    for chart in ("paper/force_depth", "paper/impact_motion", "paper/convergence", "ateb"):
        assert (out / f"{chart}.pdf").read_bytes()[:5] == b"%PDF-", chart
    assert (out / "paper/field_von_mises.png").is_file()
    assert not list(out.glob("paper/field_*.pdf"))
    assert "data:image/png;base64," in (out / "report.html").read_text()


def test_dynamic_over_velocity_says_when_it_has_no_estimates(tmp_path, monkeypatch):
    figure = capture(
        monkeypatch,
        dynamic,
        lambda: dynamic.plot_dynamic_over_velocity(fake_dynamic(None), tmp_path / "d.png"),
    )
    ratio = figure.axes[2]
    assert [t.get_text() for t in ratio.texts] == ["no error estimates (quick run)"]
    assert not [line for line in ratio.get_lines() if "unresolved" in line.get_label()]
