"""``shtaerman prony-plot``: a Prony series' E(t), E', E'' and tan delta, drawn and summarized."""

from __future__ import annotations

import argparse
from pathlib import Path

import numpy as np

from ..output.files import check_output_file, naming_output
from ..theory.prony_sources import PRONY_FORM, prony_input, prony_with_modulus
from ..validation import InputError
from ..vocabulary import Entry
from .common import Input, path_text

INSTANTANEOUS = Entry("E0", "Pa", "the instantaneous modulus", "E0", option="--E0")
"""``--E0``: read and checked as every numeric option is (:class:`~.common.Input`)."""


def register(commands: argparse._SubParsersAction) -> None:
    """Add the ``prony-plot`` subcommand."""
    p = commands.add_parser(
        "prony-plot",
        help="draw a Prony series' E(t), E', E'' and tan delta (check it before a run)",
        description=(
            "Draw the relaxation E(t) and the storage and loss moduli E'(f), E''(f) with tan "
            "delta of a Prony series, and print E0, E_inf and the loss peak. SERIES takes the "
            f"dynamic command's prony forms: {PRONY_FORM}. The moduli are in MPa when the series "
            "carries E0 (moduli, a CSV of E, a shipped rubber) or --E0 is given, else ratios to "
            "E0."
        ),
    )
    p.add_argument("series", metavar="SERIES", help="the Prony series (as dynamic's prony)")
    p.add_argument(
        "--out",
        type=path_text,
        required=True,
        metavar="FILE.png",
        help="the figure (.png/.svg/.pdf)",
    )
    p.add_argument(
        "--E0",
        action=Input,
        item=INSTANTANEOUS,
        kind=None,
        metavar="PA",
        help="the instantaneous modulus, in Pa, > 0",
    )
    p.add_argument("--force", action="store_true", help="replace --out if it exists")
    p.set_defaults(handler=run)


def run(args: argparse.Namespace) -> int:
    """Draw the figure and print the summary."""
    from ..plots.prony import prony_curves, prony_figure  # matplotlib only when it draws

    if Path(args.out).suffix.lower() not in (".png", ".svg", ".pdf"):
        raise InputError(f"--out: the figure must end in .png, .svg or .pdf, got {args.out!r}")
    check_output_file(args.out, force=args.force, option="--out")  # an existing file is kept
    series = prony_input(args.series, "SERIES")
    carried = prony_with_modulus(args.series)[1]  # read again: prony_input has checked it
    modulus = carried if args.E0 is None else args.E0
    with naming_output("--out", Path(args.out)):
        path = prony_figure(series, args.out, modulus, args.series)
    data = prony_curves(series, modulus)
    peak = int(np.argmax(data["tan_delta"]))
    scale, unit = (1.0, "E0") if modulus is None else (1e-6, "MPa")
    e0 = 1.0 if modulus is None else modulus
    low, high = f"{min(series.times):.3g}", f"{max(series.times):.3g}"
    count = len(series.weights)
    taus = low if low == high else f"{low} to {high}"
    print(f"Prony series, {count} term{'s' * (count != 1)} (tau {taus} s)")
    if modulus is None:
        print("  E0    = 1 (the moduli are ratios to E0; --E0 gives them in MPa)")
    else:
        print(f"  E0    = {scale * e0:.6g} {unit} (instantaneous)")
    print(f"  E_inf = {scale * e0 * series.g_inf:.6g} {unit} (g_inf = {series.g_inf:.6g})")
    print(
        f"  tan delta peaks at {data['tan_delta'][peak]:.4g}, f = {data['frequency'][peak]:.3g} Hz"
    )
    print(f"  figure: {path}")
    return 0
