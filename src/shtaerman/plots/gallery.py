"""The figures of a verification run: which files each study gets, and their captions.

Every function writes PNGs into a folder (created if missing) and returns ``{caption: path}``;
the report shows the captions under the pictures, so a caption says everything a reader needs
to read its figure. ``figure_format="svg"`` or ``"pdf"`` also writes each chart in that format
beside its PNG (same stem); the field pictures (pyvista renders) are PNG only
(:mod:`.formats`).
"""

from __future__ import annotations

from pathlib import Path
from typing import TYPE_CHECKING

from ..study.contact.layer import REFERENCE_EXPONENT, REFERENCE_MAP, REFERENCE_THICKNESS
from .curves import plot_convergence, plot_force_depth, plot_pressure
from .fields import SIGMA
from .impact import plot_impact_contact, plot_impact_motion
from .layer import LAYER_MAP_CAPTION, MapSeries, plot_layer_map
from .revolved import plot_revolved
from .sections import plot_each_field

NU = "\N{GREEK SMALL LETTER NU}"

if TYPE_CHECKING:
    from ..study.contact.indentation import IndentationResult
    from ..study.contact.runner import StudyOutcome

__all__ = ["FIELD_FIGURES", "contact_figures", "study_figures"]

FIELD_FIGURES = {
    "sigma_zz": f"Axial stress {SIGMA}zz under the indenter (r-z section, largest depth)",
    "sigma_rr": f"Radial stress {SIGMA}rr under the indenter (r-z section, largest depth)",
    "von_mises": "Von Mises stress under the indenter (r-z section, largest depth)",
    "u_z": "Axial displacement uz (r-z section, largest depth)",
}
"""Fields drawn by :func:`study_figures` and their captions."""
REVOLVED_CAPTION = (
    "Von Mises stress, the r-z section revolved through 270° (contact circle in green)"
)
MOTION_CAPTION = "Impact: approach x/x_c and force P/P_c against t/t_c (the paper's Fig. 3)"
IMPACT_CONTACT_CAPTION = (
    "Impact: contact radius a/a_c and central pressure p(0,t)/p_c (the paper's Fig. 4). The "
    "lower panel's scale is set away from t = 0 and t_y, where a ~ x^(1/n) and p(0) ~ "
    "x^(1-1/n) are infinitely steep and a tiny shift of t_y swamps the comparison; differences "
    "beyond it are marked by triangles on its edge and their extremes written in the panel"
)
FORCE_DEPTH_CAPTION = "Force against depth: FEM and Shtaerman's P = βx^q"
PRESSURE_CAPTION = "Contact pressure p(r)/p_avg: FEM nodal values and the exact profile"
CONVERGENCE_CAPTION = (
    "Mesh convergence: relative errors against the exact solution over the element size, "
    "each mesh's number of unknowns on the top axis"
)


def study_figures(
    outcome: StudyOutcome, folder: Path | str, figure_format: str = "png"
) -> dict[str, Path]:
    """Every figure of one contact study, written into ``folder``.

    At the largest depth, one picture per field of :data:`FIELD_FIGURES` (``field_<name>.png``)
    and the revolved von Mises cut-away (``field_revolved.png``), PNG only; on a layer
    ``layer_map.png``; ``force_depth.png`` and ``pressure.png`` (:func:`contact_figures`);
    ``impact_motion.png`` and ``impact_contact.png`` (the paper's Figs. 3 and 4, every impact
    variant of the study against its exact impact); ``convergence.png`` where the study has a
    convergence study.

    Parameters
    ----------
    outcome : shtaerman.study.contact.runner.StudyOutcome
        The study: its ``contact``, ``histories``, ``exact`` and ``convergence`` are drawn.
    folder, figure_format
        As every function here (the module's docstring).
    """
    folder, fmt = Path(folder), {"figure_format": figure_format}
    contact, histories, exact = outcome.contact, outcome.histories, outcome.exact
    paths = {name: folder / f"field_{name}.png" for name in FIELD_FIGURES}
    made = {FIELD_FIGURES[name]: path for name, path in plot_each_field(contact, paths).items()}
    made[REVOLVED_CAPTION] = plot_revolved(contact, folder / "field_revolved.png")
    made |= _layer_figures(outcome, folder, figure_format)
    made |= contact_figures(contact, folder, figure_format)
    made[MOTION_CAPTION] = plot_impact_motion(histories, exact, folder / "impact_motion.png", **fmt)
    made[IMPACT_CONTACT_CAPTION] = plot_impact_contact(
        histories, exact, folder / "impact_contact.png", **fmt
    )
    if outcome.convergence is not None:
        path = folder / "convergence.png"
        made[CONVERGENCE_CAPTION] = plot_convergence(outcome.convergence, path, **fmt)
    return made


def _layer_figures(outcome: StudyOutcome, folder: Path, figure_format: str) -> dict[str, Path]:
    """``layer_map.png`` of a study on a layer: its curve over the depths and its point at the
    half-space impact's x_c, over the measured map of n = 3/2 where the study's n is 3/2 ({} on
    the half-space)."""
    layer = outcome.layer
    if layer is None:
        return {}
    h, ratio = zip(*layer.curve, strict=True)
    nu2 = outcome.study.half_space.poisson_ratio
    series = {}
    if getattr(outcome.study.indenter, "exponent", None) == REFERENCE_EXPONENT:  # a power law
        series = {
            f"{base}, {NU}2 = {nu2:g} (sweeps/layer.toml)"
            if base == "bonded"
            else f"{base}, any {NU}2 (sweeps/layer.toml)": MapSeries(
                REFERENCE_THICKNESS, ratios, base=base, points=False, reference=True
            )
            for (base, nu2), ratios in REFERENCE_MAP.items()
        }
    series |= {
        f"this study ({layer.base}, {NU}2 = {nu2:g}), over the depths": MapSeries(
            h, ratio, base=layer.base, points=False
        ),
        f"at x_c (H / a_c = {layer.thickness_ratio:.3g})": MapSeries(
            (layer.thickness_ratio,),
            (layer.force_ratio,),
            (layer.force_ratio_error,),
            layer.base,
        ),
    }
    path = plot_layer_map(series, folder / "layer_map.png", figure_format=figure_format)
    return {LAYER_MAP_CAPTION: path}


def contact_figures(
    result: IndentationResult, folder: Path | str, figure_format: str = "png"
) -> dict[str, Path]:
    """The curve figures of one FEM contact curve (``contact --out``), written into ``folder``.

    ``force_depth.png`` and ``pressure.png`` (:func:`plot_force_depth`, :func:`plot_pressure`).
    """
    folder, fmt = Path(folder), {"figure_format": figure_format}
    return {
        FORCE_DEPTH_CAPTION: plot_force_depth(result, folder / "force_depth.png", **fmt),
        PRESSURE_CAPTION: plot_pressure(result, folder / "pressure.png", **fmt),
    }
