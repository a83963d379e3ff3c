"""Error estimates, ``accuracy`` and the size guard on a layer, as on the half-space.

The truth on a layer is the Hankel-transform reference
(:class:`shtaerman.theory.layer_reference.LayerReference`); the half-space's exact solution is
not (a layer's departure from it is physics, not error).
"""

from __future__ import annotations

import numpy as np
import pytest

import shtaerman as sh
from shtaerman.fem.mesh import Geometry, MeshSettings
from shtaerman.study.contact.accuracy import LAYER_TRUNCATION, run_ladder
from shtaerman.study.contact.indentation import refined_radius
from shtaerman.study.ladder import check_ladder
from shtaerman.theory.indenter import PowerLawIndenter
from shtaerman.theory.layer import half_space_limit
from shtaerman.theory.layer_reference import LayerReference
from shtaerman.theory.materials import Material
from shtaerman.validation import InputError

RADIUS = 0.01
COARSE = 1.0 / 60.0
INDENTER = PowerLawIndenter(5e-3 / RADIUS**1.8, 1.8)
BODY = Material(7.5e6, 0.4)
DEPTH = float(half_space_limit(INDENTER, BODY).depth(RADIUS))


def test_layer_force_estimate_brackets_the_reference_error():
    depths = np.array([0.4 * DEPTH, DEPTH])
    settings = MeshSettings(size=COARSE)
    result = run_ladder(INDENTER, BODY, depths, settings, geometry=Geometry(RADIUS, "bonded"))
    reference = LayerReference(INDENTER, BODY, RADIUS, "bonded")
    true = max(
        abs(step.force / reference.force(depth) - 1.0)
        for step, depth in zip(result.finest.steps, depths, strict=True)
    )
    estimate = result.estimates["force"].error
    # measured: estimate 6.9e-5 (with the 1e-5 edge term), true 5.7e-5, effectivity 1.21
    assert true < estimate < 10.0 * true
    assert estimate > LAYER_TRUNCATION  # the lateral edge is in the estimate


def test_accuracy_reaches_its_target_on_a_layer():
    progress: list[str] = []
    result = sh.contact(
        INDENTER,
        BODY,
        depths=[DEPTH],
        thickness=0.5 * RADIUS,
        base="lubricated",
        accuracy=2e-3,
        mesh_size=COARSE,
        progress=progress.append,
    )
    assert result.error_estimate["force"] <= 2e-3
    assert len(progress) == 3  # the first three levels meet it
    force = result.steps[-1]["force"]
    reference = LayerReference(INDENTER, BODY, 0.5 * RADIUS, "lubricated").force(DEPTH)
    assert abs(force / reference - 1.0) <= 2e-3


def test_accuracy_below_the_layer_edge_is_refused():
    with pytest.raises(InputError, match="accuracy must be >= 2e-05 on a layer"):
        sh.contact(INDENTER, BODY, depths=[DEPTH], thickness=RADIUS, accuracy=1e-5)


def test_layer_size_guard_uses_the_layer_estimate_before_the_ladder():
    settings, geometry = MeshSettings(), Geometry(1.5 * RADIUS)
    refined = refined_radius(INDENTER, np.array([DEPTH]), settings, geometry)
    layer = settings.layer_dofs(1.5 * RADIUS / refined)
    assert layer < settings.estimated_dofs  # the half-space estimate was checked before
    between = MeshSettings(max_dofs=0.5 * (layer + settings.estimated_dofs))
    check_ladder(between, 1.0, refined, geometry)  # the layer fits
    below = MeshSettings(max_dofs=0.8 * layer)
    with pytest.raises(InputError, match="this layer mesh would have about"):
        check_ladder(below, 1.0, refined, geometry)


def test_api_refuses_a_too_large_layer_before_any_level():
    progress: list[str] = []
    with pytest.raises(InputError, match="this layer mesh would have about"):
        sh.contact(
            INDENTER,
            BODY,
            depths=[DEPTH],
            thickness=RADIUS,
            max_dofs=5000,
            progress=progress.append,
        )
    assert progress == []


def test_cli_refuses_an_unresolved_layer_without_a_misleading_hint(capsys):
    """The thickness is checked before the ladder; running without it would not help."""
    from shtaerman.cli import main

    assert main(["contact", "--thickness", "1e-300"]) == 2
    err = capsys.readouterr().err
    assert err.startswith("shtaerman: error: --thickness: must lie in [")
    assert "--no-estimate" not in err
