"""Lighting correction: the gain plane is measured on the wall and floor, not on a grey
counter that has the wall's hue at two thirds of its brightness."""

from __future__ import annotations

import numpy as np
import pytest

from verigraph.perception.correct.lighting import GainField, correct, estimate_gain
from verigraph.sim2d import palette
from verigraph.sim2d.generator import generate_scene

KITCHEN = 10020  # a long grey counter under a short wall


def lit(image: np.ndarray, gain: GainField) -> np.ndarray:
    field = gain.image(*image.shape[:2])[:, :, None]
    return np.clip(image.astype(np.float32) * field, 0, 255).astype(np.uint8)


@pytest.mark.parametrize("truth", [GainField(0.8, 0.3, -0.2), GainField(1.1, 0.19, 0.15),
                                   GainField(1.05, -0.1, -0.22)])
def test_gain_is_read_off_the_wall_and_floor_of_a_tight_side_view(truth: GainField) -> None:
    """Brighter lighting clips much of the wall, so the unclipped counter outnumbers it
    among the wall-coloured samples; the wall is still the surface that reaches the
    border."""
    clean = generate_scene("kitchen", KITCHEN).world.render()
    counter = (clean == palette.bgr("gray")).all(axis=2).mean()
    wall = (clean == palette.BACKGROUND).all(axis=2).mean()
    assert counter > 0.25 and wall < 0.6  # the case the border rule is for
    found = estimate_gain(lit(clean, truth), [palette.BACKGROUND, palette.FLOOR])
    for u, v in [(0.1, 0.1), (0.5, 0.5), (0.9, 0.9), (0.1, 0.9)]:
        assert found.at(np.float32(u), np.float32(v)) == pytest.approx(
            truth.at(np.float32(u), np.float32(v)), abs=0.03)
    spoilt = lit(clean, truth)
    restored = correct(spoilt, found)
    unclipped = spoilt.max(axis=2) < 248  # a clipped pixel is kept as it is
    assert np.abs(restored.astype(int) - clean.astype(int))[unclipped].mean() < 3


def test_an_evenly_lit_render_is_left_alone() -> None:
    clean = generate_scene("kitchen", KITCHEN).world.render()
    found = estimate_gain(clean, [palette.BACKGROUND, palette.FLOOR])
    assert found.is_identity
    assert correct(clean, found) is clean
