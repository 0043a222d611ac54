"""Motion blur: the shake's length and direction are estimated from the picture, the
picture is restored, and graphs come out as from a sharp camera; where no straight shake
explains the blur nothing is restored and the blur warning stands.

The benchmark's figures (more lengths and directions, 15+ scenes per family) are in
benchmarks/results/sgg_robustness.md; these seeds are apart from its seeds.
"""

from __future__ import annotations

import cv2
import numpy as np
import pytest

from verigraph.perception import perceive_image, score_graph
from verigraph.perception.correct.deblur import (
    MotionBlur,
    axis_kernel,
    estimate_motion,
    motion_kernel,
    restore,
)
from verigraph.perception.correct.noise import sharpness
from verigraph.sim2d import degrade_ops as ops
from verigraph.sim2d import palette
from verigraph.sim2d.generator import generate_scene

SEED = 36_000


def _angle_error(a: float, b: float) -> float:
    d = abs(a - b) % 180.0
    return min(d, 180.0 - d)


@pytest.mark.parametrize(("length", "degrees"), [(5, 0.0), (9, 35.0), (9, 90.0),
                                                 (13, 150.0)])
def test_the_shake_is_measured(length: int, degrees: float) -> None:
    image = generate_scene("kitchen", SEED).world.render()
    blur = estimate_motion(ops.motion_blur(image, length, degrees))
    assert blur is not None
    assert abs(blur.length - length) <= 1.0, blur
    assert _angle_error(blur.degrees, degrees) <= 5.0, blur


@pytest.mark.parametrize("family", ["kitchen", "tableware"])
def test_a_nine_pixel_shake_is_undone(family: str) -> None:
    """The families whose thin objects blur away (a spoon, a knife) come back exact;
    the result says what was undone, and a wrong graph would still be flagged."""
    exact = 0
    for i in range(4):
        scene = generate_scene(family, SEED + 10 + i)
        angle = float(np.random.default_rng(i).uniform(0, 180))
        shaken = ops.motion_blur(scene.world.render(), 9, angle)
        assert sharpness(shaken) < 240  # blurred enough to be warned about
        result = perceive_image(shaken, dictionary=family)
        assert "motion blur of" in result.restored and "Wiener" in result.restored
        right = score_graph(result.graph, scene.graph, family).exact
        exact += right
        assert right or not result.confident, result.warnings
    assert exact >= 3


def test_sharp_and_empty_pictures_are_left_alone() -> None:
    scene = generate_scene("tableware", SEED + 20)
    assert perceive_image(scene.world.render(), dictionary="tableware").restored == ""
    empty = np.empty((480, 640, 3), np.uint8)
    empty[:] = palette.BACKGROUND
    empty[440:] = palette.FLOOR
    assert restore(empty, sharpness(empty)) is None  # nothing to estimate a shake from
    result = perceive_image(empty, dictionary="kitchen")
    assert result.graph.nodes == [] and result.restored == ""


@pytest.mark.parametrize("sigma", [2.0, 3.0])
def test_a_blur_no_shake_explains_keeps_its_warning(sigma: float) -> None:
    """A strong Gaussian blur has no straight direction: the restoration would not
    sharpen the picture, so the image stays as it was and the warning says it is
    blurred."""
    scene = generate_scene("kitchen", SEED + 21)
    soft = np.asarray(cv2.GaussianBlur(scene.world.render(), (0, 0), sigmaX=sigma))
    level = sharpness(soft)
    assert level < 240
    assert restore(soft, level) is None
    result = perceive_image(soft, dictionary="kitchen")
    assert result.restored == ""
    assert any("blurred" in w for w in result.warnings)
    assert not result.confident


@pytest.mark.parametrize("degrees", [45.0, 135.0, 60.0])
def test_an_oblique_nine_pixel_shake_on_a_kitchen_is_restored_exactly(degrees: float) -> None:
    """Obliquely, the line kernel misses the smear between pixels: the restoration rings,
    and its bright echoes once made a silver pot's pocket read as wall. The oblique
    balance and the median check of restored pockets give the exact graph back."""
    exact = 0
    for i in range(3):
        scene = generate_scene("kitchen", SEED + 30 + i)
        shaken = ops.motion_blur(scene.world.render(), 9, degrees)
        result = perceive_image(shaken, dictionary="kitchen")
        assert "motion blur of" in result.restored
        right = score_graph(result.graph, scene.graph, "kitchen").exact
        assert right or not result.confident, result.warnings
        exact += right
    assert exact == 3


def test_a_vertical_shake_is_undone_with_a_column_of_whole_pixels() -> None:
    """Along a column the camera's smear is a box of whole pixels; the anti-aliased line
    spreads its ends and left ghosts of plates lying on books and desks (a plate split
    in two, or merged into its support). Oblique and horizontal shakes keep the line."""
    column = motion_kernel(MotionBlur(length=9.5, degrees=90.0))
    assert np.count_nonzero(column) == 9
    assert np.count_nonzero(column.sum(axis=0)) == 1  # one column, nothing spilt
    assert column.sum() == pytest.approx(1.0)
    assert axis_kernel(MotionBlur(length=9.5, degrees=0.0)) is None
    assert axis_kernel(MotionBlur(length=9.5, degrees=60.0)) is None
    exact = 0
    for i in range(20):
        scene = generate_scene("tableware", SEED + 40 + i)
        shaken = ops.motion_blur(scene.world.render(), 9, 90.0)
        result = perceive_image(shaken, dictionary="tableware")
        assert "motion blur of" in result.restored
        right = score_graph(result.graph, scene.graph, "tableware").exact
        assert right or not result.confident, result.warnings
        exact += right
    assert exact >= 18  # 14 of these 20 with the line kernel
