"""The file formats a figure can be written in (no plotting library imported here).

Charts (matplotlib) are always written as PNG at 200 dpi, the picture the reports embed; with
``figure_format="svg"`` or ``"pdf"`` also as vector graphics beside the PNG, same stem, text
kept as text. The field pictures (pyvista renders of the FEM fields) are PNG only: VTK's vector
export embeds the rendered bitmap anyway and re-sets the text in another font.
"""

from __future__ import annotations

import argparse

from .. import vocabulary
from ..validation import InputError

__all__ = ["FIGURE_FORMATS", "FORMAT_HELP", "add_figure_format", "check_figure_format"]

FIGURE_FORMATS = vocabulary.entry("figure_format").choices
"""What ``figure_format`` may be: PNG only, or PNG and an SVG or PDF beside it."""
FORMAT_HELP = (
    "figure files: png (200 dpi), or svg / pdf (vector, text kept as text) written beside each "
    "chart's PNG; field renders (pyvista) stay PNG only"
)


def check_figure_format(figure_format: str) -> str:
    """``figure_format`` if it is one of :data:`FIGURE_FORMATS`, else :class:`InputError`."""
    if figure_format not in FIGURE_FORMATS:
        raise InputError(
            f"figure_format must be one of {', '.join(FIGURE_FORMATS)}, got {figure_format!r}",
            "figure_format",
        )
    return figure_format


def add_figure_format(parser: argparse.ArgumentParser) -> None:
    """--figure-format png|svg|pdf of a subcommand that writes figures (``args.figure_format``).

    The one definition of the option: :mod:`shtaerman.cli.common` re-exports it for the
    subcommands, and the sweep's parser (which may not import the CLI) takes it from here.
    """
    parser.add_argument(
        "--figure-format", default="png", choices=FIGURE_FORMATS, metavar="FORMAT", help=FORMAT_HELP
    )
