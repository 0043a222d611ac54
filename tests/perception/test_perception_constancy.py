"""Colour constancy on images with known transforms: a tone curve and a colour cast are
undone, a repainted wall is taken back as background, a gain measured on the floor
alone is not extrapolated up the wall, and what no tone map can undo is reported."""

from __future__ import annotations

import numpy as np
import pytest

from verigraph.perception import perceive_image, score_graph
from verigraph.perception.correct.constancy import estimate_tone, repaint_wall, wall_colour
from verigraph.perception.correct.lighting import estimate_gain
from verigraph.perception.correct.photometry import correct_colours
from verigraph.sim2d import degrade_ops as ops
from verigraph.sim2d import palette
from verigraph.sim2d.generator import generate_scene

PALETTE = [palette.BACKGROUND, palette.FLOOR, palette.OUTLINE, *palette.COLORS.values()]


def render(family: str = "kitchen", seed: int = 30_001) -> np.ndarray:
    return np.asarray(generate_scene(family, seed).world.render())


def anchors(image: np.ndarray) -> list[tuple[np.ndarray, tuple[int, int, int]]]:
    """The wall at the top border and the floor at the bottom, as photometry passes them."""
    top, floor = wall_colour(image), wall_colour(image, bottom=True)
    assert top is not None and floor is not None
    return [(np.array(top, dtype=np.float64), palette.BACKGROUND),
            (np.array(floor, dtype=np.float64), palette.FLOOR)]


def difference(a: np.ndarray, b: np.ndarray) -> float:
    return float(np.abs(a.astype(int) - b.astype(int)).mean())


@pytest.mark.parametrize("spoil", [
    lambda im: ops.gamma(im, 1.6),
    lambda im: ops.gamma(im, 0.7),
    lambda im: ops.white_balance(im, (0.8, 1.0, 1.2)),
    lambda im: ops.white_balance(ops.gamma(im, 1.3), (1.1, 0.95, 0.85)),
], ids=["gamma 1.6", "gamma 0.7", "warm cast", "cool cast and gamma"])
def test_a_tone_curve_and_a_colour_cast_are_undone(spoil: object) -> None:
    clean = render()
    spoilt = spoil(clean)  # type: ignore[operator]
    tone = estimate_tone(spoilt, PALETTE, anchors(spoilt))
    restored = tone.apply(spoilt)
    assert difference(spoilt, clean) > 8
    assert difference(restored, clean) < 3, tone
    assert tone.residual < 5


def test_an_untouched_render_gets_the_identity() -> None:
    clean = render("tableware", 30_002)
    tone = estimate_tone(clean, PALETTE)
    assert tone.is_identity and tone.residual < 2


def test_a_wall_of_another_colour_is_repainted_as_background() -> None:
    clean = render()
    green = ops.recolour(clean, palette.BACKGROUND, (170, 215, 175))
    repainted, wall = repaint_wall(green, palette.BACKGROUND)
    assert wall is not None and abs(wall[0] - 170) < 4 and abs(wall[1] - 215) < 4
    was_wall = (clean == palette.BACKGROUND).all(axis=2)
    assert np.abs(repainted[was_wall].astype(int) - palette.BACKGROUND).max() <= 2
    assert difference(repainted, clean) < 1.5
    unchanged, none = repaint_wall(clean, palette.BACKGROUND)
    assert none is None and unchanged is clean


def test_a_gain_seen_on_the_floor_alone_is_not_extrapolated_up_the_wall() -> None:
    """The wall's hue is not the background's, so only the floor band gives samples: a
    plane through them has no height to measure a slope over."""
    clean = ops.recolour(render("blocks"), palette.BACKGROUND, (150, 200, 230))
    h, w = clean.shape[:2]
    ramp = np.linspace(0.8, 1.0, h, dtype=np.float32)[:, None, None]
    spoilt = np.clip(clean * ramp, 0, 255).astype(np.uint8)
    gain = estimate_gain(spoilt, [palette.BACKGROUND, palette.FLOOR])
    field = gain.image(h, w)
    assert gain.c == 0.0
    assert field.min() >= gain.low and field.max() <= gain.high
    assert 0.85 < float(field.mean()) < 1.1  # what the floor showed, not 0.34


def test_a_hue_rotation_no_tone_map_undoes_is_reported() -> None:
    spoilt = ops.hue_shift(render("blocks", 30_003), 30.0)
    photo = correct_colours(spoilt, PALETTE, palette.BACKGROUND,
                            [palette.BACKGROUND, palette.FLOOR])
    assert photo.doubtful and any("palette poorly" in n for n in photo.notes)


@pytest.mark.parametrize("spoil", [
    lambda im: ops.gamma(im, 1.8),
    lambda im: ops.white_balance(im, (0.8, 1.0, 1.2)),
    lambda im: ops.recolour(im, palette.BACKGROUND, (170, 215, 175)),
], ids=["gamma 1.8", "warm cast", "pale green wall"])
@pytest.mark.parametrize("family", ["blocks", "kitchen", "tableware"])
def test_graphs_survive_known_colour_transforms(family: str, spoil: object) -> None:
    scene = generate_scene(family, 30_010)
    result = perceive_image(spoil(scene.world.render()), dictionary=family)  # type: ignore[operator]
    assert score_graph(result.graph, scene.graph, family).exact, result.warnings
