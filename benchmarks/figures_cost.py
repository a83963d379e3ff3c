"""CPU time of the figures `shtaerman verify` draws, per study and per figure kind.

Run: python benchmarks/figures_cost.py [--quick] [--repeat N] [--kinds contact finite-strain
dynamic] [--profile KIND]. Every shipped study of the chosen kinds is computed once (not
timed); then each of its figures is drawn ``--repeat`` times (default 3) into a temporary
folder, with the same calls as the study's writer; printed are the CPU time of the first
drawing (in the first study of a kind it carries the process's one-off costs: fonts, the
mathtext parser, the OpenGL context) and the least of the repeats (``time.process_time``:
this process and its threads, which VTK's software renderer uses; wall time is left out, other
jobs share the machine). The figures that depend on no study (the Ateb functions, one per
indenter exponent) are timed once per exponent.
``--profile KIND`` prints a cProfile of one more drawing of that figure kind (first study).
Beside each least time is its ratio to a reference measured in the same run (the least of
``--repeat``, at least 3, savefigs of one empty axes at the figures' size and dpi: matplotlib
alone), which compares runs at different loads better than seconds; the load average is
printed at the start and the end. Asserts nothing about time.
"""

import argparse
import cProfile
import os
import pstats
import tempfile
import time
from collections.abc import Callable
from pathlib import Path
from typing import Any

from matplotlib.figure import Figure

from shtaerman.output.dynamic import SEPARATION_SNAPSHOT
from shtaerman.plots import ateb, curves, dynamic, finite, gallery, impact, revolved, sections
from shtaerman.plots.style import DPI, WIDTH
from shtaerman.study.run import run_study
from shtaerman.study.schema import load_study, shipped_studies

Figures = dict[str, Callable[[Path], Any]]


def contact_figures(outcome: Any) -> Figures:
    """A contact study's figures as :func:`shtaerman.output.folder.study_entry` draws them."""
    result, histories, exact = outcome.contact, outcome.histories, outcome.exact
    paths = {name: f"field_{name}.png" for name in gallery.FIELD_FIGURES}
    made: Figures = {
        "field sections (4)": lambda out: sections.plot_each_field(
            result, {name: out / path for name, path in paths.items()}
        ),
        "field revolved": lambda out: revolved.plot_revolved(result, out / "field_revolved.png"),
        "force_depth": lambda out: curves.plot_force_depth(result, out / "force_depth.png"),
        "pressure": lambda out: curves.plot_pressure(result, out / "pressure.png"),
        "impact_motion": lambda out: impact.plot_impact_motion(
            histories, exact, out / "impact_motion.png"
        ),
        "impact_contact": lambda out: impact.plot_impact_contact(
            histories, exact, out / "impact_contact.png"
        ),
    }
    if outcome.convergence is not None:
        made["convergence"] = lambda out: curves.plot_convergence(
            outcome.convergence, out / "convergence.png"
        )
    return made


def finite_figures(outcome: Any) -> Figures:
    """A finite-strain study's figures as :mod:`shtaerman.output.finite` draws them."""
    return {
        "finite_ratios": lambda out: finite.plot_finite_ratios(outcome, out / "ratios.png"),
        "finite_section": lambda out: finite.plot_finite_section(outcome, out / "section.png"),
        "finite_impact": lambda out: finite.plot_finite_impact(outcome, out / "impact.png"),
    }


def dynamic_figures(outcome: Any) -> Figures:
    """A dynamic study's figures as :mod:`shtaerman.output.dynamic` draws them."""
    example = outcome.example
    made: Figures = {
        "dynamic_history": lambda out: dynamic.plot_dynamic_histories(example, out / "history.png"),
        "dynamic_over_velocity": lambda out: dynamic.plot_dynamic_over_velocity(
            outcome, out / "over_velocity.png"
        ),
    }
    quasi, snapshots = example.quasi, example.result.snapshots
    for stem, key in (("tc", quasi.t_c), ("separation", SEPARATION_SNAPSHOT * quasi.t_y)):
        if key in snapshots:
            made[f"wave_field_{stem}"] = lambda out, key=key, stem=stem: dynamic.plot_wave_field(
                example, key, out / f"wave_{stem}.png"
            )
    return made


KINDS = {"contact": contact_figures, "finite-strain": finite_figures, "dynamic": dynamic_figures}


def cpu_seconds(draw: Callable[[Path], Any], repeat: int) -> tuple[float, float]:
    """CPU time of the first of ``repeat`` drawings and the least, each into a fresh folder."""
    seconds = []
    for _ in range(repeat):
        with tempfile.TemporaryDirectory() as folder:
            start = time.process_time()
            draw(Path(folder))
            seconds.append(time.process_time() - start)
    return seconds[0], min(seconds)


def empty_savefig(out: Path) -> None:
    """The reference: one empty axes saved as PNG by matplotlib's savefig (two draws)."""
    figure = Figure(figsize=(WIDTH, 4.0), layout="constrained")
    figure.add_subplot()
    figure.savefig(out / "reference.png", dpi=DPI)


def load() -> str:
    return "load average " + " ".join(f"{value:.2f}" for value in os.getloadavg())


def row(study: str, name: str, seconds: Any, reference: float) -> None:
    """One line: first and least CPU s, and the least over the reference."""
    ratio = seconds[1] / reference
    print(f"{study:<20} {name:<24} {seconds[0]:7.2f} {seconds[1]:7.2f} {ratio:6.1f}")


def added(total: list[float], seconds: tuple[float, float]) -> list[float]:
    return [total[0] + seconds[0], total[1] + seconds[1]]


def profile(draw: Callable[[Path], Any]) -> None:
    with tempfile.TemporaryDirectory() as folder:
        profiler = cProfile.Profile(time.process_time)
        profiler.runcall(draw, Path(folder))
    pstats.Stats(profiler).sort_stats("cumulative").print_stats(40)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--quick", action="store_true", help="verify --quick's coarse runs")
    parser.add_argument("--repeat", type=int, default=3)
    parser.add_argument("--kinds", nargs="+", choices=list(KINDS), default=list(KINDS))
    parser.add_argument("--profile", metavar="KIND", help="a figure kind to profile")
    args = parser.parse_args()
    studies = [study for path in shipped_studies() for study in load_study(path)]
    totals: dict[str, list[float]] = {}
    exponents = set()
    print(load())
    reference = cpu_seconds(empty_savefig, max(args.repeat, 3))[1]
    print(f"reference (empty savefig): {reference:.4f} CPU s")
    print(f"{'study':<20} {'figure':<24} {'first s':>7} {'least s':>7} {'/ ref':>6}")
    for study in studies:
        kind = getattr(study, "kind", "contact")
        if kind not in args.kinds:
            continue
        outcome = run_study(study, quick=args.quick)
        if kind == "contact":
            _ = outcome.contact.deepest_field  # the verify run computes it for the VTU file
            exponents.add(study.indenter.exponent)
        figures = KINDS[kind](outcome)
        study_total = [0.0, 0.0]
        for name, draw in figures.items():
            seconds = cpu_seconds(draw, args.repeat)
            row(study.name, name, seconds, reference)
            totals[name] = added(totals.get(name, [0.0, 0.0]), seconds)
            study_total = added(study_total, seconds)
            if args.profile == name:
                profile(draw)
                args.profile = None
        row(study.name, "all", study_total, reference)
    for exponent in sorted(exponents):
        draw = lambda out, n=exponent: ateb.paper_figures(out, [n])  # noqa: E731
        totals[f"ateb (n = {exponent:g})"] = list(cpu_seconds(draw, args.repeat))
    print("\nper figure kind, summed over the studies:")
    everything = [sum(seconds[i] for seconds in totals.values()) for i in (0, 1)]
    for name, seconds in [*totals.items(), ("all figures", everything)]:
        print(f"  {name:<42} {seconds[0]:7.2f} {seconds[1]:7.2f} {seconds[1] / reference:6.1f}")
    print(load())


if __name__ == "__main__":
    main()
