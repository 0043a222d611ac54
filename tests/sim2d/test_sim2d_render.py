"""Renderer: a pure function of the state, consistent class colours, degradations."""

from __future__ import annotations

import cv2
import numpy as np
import pytest

from verigraph.graph.builtin_scenes import cup_on_book, kitchen_pan, three_blocks
from verigraph.graph.dictionary import builtin_dictionary
from verigraph.sim2d import (
    Degradation,
    TabletopWorld,
    degrade,
    encode_png,
    generate_scene,
    side_by_side,
    world_for_graph,
)
from verigraph.sim2d.palette import COLORS, bgr

pytestmark = pytest.mark.fast


def centre_pixel(world: TabletopWorld, image: np.ndarray, obj: str, frac_y: float = 0.5
                 ) -> tuple[int, ...]:
    """Pixel at a point inside an object's solid part (found through the camera)."""
    from verigraph.sim2d.render import _Camera, tabletop_view

    cam = _Camera(tabletop_view(world), image.shape[1], image.shape[0], bottom=True)
    left, bottom, right, top = world.scene.things[obj].bounds()
    x, y = cam.pixel((left + right) / 2, bottom + frac_y * (top - bottom))
    return tuple(int(v) for v in image[y, x])


@pytest.mark.parametrize("size", [(640, 480), (320, 240), (200, 400)])
def test_render_has_the_requested_size_and_is_pure(size: tuple[int, int]) -> None:
    world = world_for_graph(cup_on_book())
    before = world.observe()
    a = world.render(*size)
    b = world.render(*size, labels=False)
    assert a.shape == (size[1], size[0], 3) and a.dtype == np.uint8
    assert (a == b).all()
    assert world.observe() == before
    assert len(np.unique(a.reshape(-1, 3), axis=0)) >= 5  # furniture, objects, floor, sky


def test_default_frame_takes_the_scene_shape_at_a_fixed_scale() -> None:
    """A wide kitchen is drawn wide, at 8 px per world unit, instead of shrinking into
    640x480; a narrow scene is at least 640 wide; tangram keeps 640x480."""
    from verigraph.sim2d.render import MAX_SIDE, MIN_WIDTH, PIXELS_PER_UNIT, tabletop_view

    for family in ("kitchen", "tableware", "blocks"):
        scene = generate_scene(family, 7)
        image = scene.world.render()
        x0, y0, x1, y1 = tabletop_view(scene.world)
        height, width = image.shape[:2]
        assert abs(width / height - (x1 - x0) / (y1 - y0)) < 0.02
        assert MIN_WIDTH <= width <= MAX_SIDE
        assert width / (x1 - x0) >= min(PIXELS_PER_UNIT, MAX_SIDE / (x1 - x0)) - 0.01
        assert scene.world.render(width=width).shape == image.shape
        assert scene.world.render(height=height).shape[0] == height
    assert generate_scene("tangram", 7).world.render().shape == (480, 640, 3)


def test_labels_are_light_on_dark_furniture_and_dark_elsewhere() -> None:
    """The stove's name is readable on the black stove, the counter's on the grey one."""
    from verigraph.sim2d.render import _Camera, tabletop_view

    world = world_for_graph(kitchen_pan())
    assert isinstance(world, TabletopWorld)
    plain, labelled = world.render(), world.render(labels=True)
    cam = _Camera(tabletop_view(world), plain.shape[1], plain.shape[0], bottom=True)
    for name, light in (("stove", True), ("counter", False)):
        left, bottom, right, top = world.scene.things[name].bounds()
        (x0, y0), (x1, y1) = cam.pixel(left, top), cam.pixel(right, bottom)
        changed = (plain[y0:y1, x0:x1] != labelled[y0:y1, x0:x1]).any(axis=2)
        assert changed.sum() > 20, name
        text = labelled[y0:y1, x0:x1][changed].mean()
        assert (text > 120) if light else (text < 120), (name, text)


def test_objects_are_drawn_in_their_class_colours() -> None:
    world = world_for_graph(cup_on_book())
    assert isinstance(world, TabletopWorld)
    image = world.render(640, 480)
    assert centre_pixel(world, image, "book") == bgr("green")
    assert centre_pixel(world, image, "cup", frac_y=0.03) == bgr("yellow")  # cup floor
    blocks = world_for_graph(three_blocks())
    assert isinstance(blocks, TabletopWorld)
    img = blocks.render(640, 480)
    for block in ("red_block", "blue_block", "green_block"):
        assert centre_pixel(blocks, img, block) == bgr(block.split("_")[0])


@pytest.mark.parametrize("family", ["kitchen", "tableware", "tangram"])
def test_classes_of_a_family_have_distinct_known_colours(family: str) -> None:
    d = builtin_dictionary(family)
    colours = [p.color for p in d.objects.values()]
    assert all(c in COLORS for c in colours), colours
    movable = [p.color for p in d.objects.values() if p.movable]
    assert len(set(movable)) == len(movable), movable


def test_tangram_render_shows_every_piece_colour() -> None:
    world = generate_scene("tangram", 0).world
    image = world.render(640, 480)
    present = {tuple(int(v) for v in px) for px in np.unique(image.reshape(-1, 3), axis=0)}
    for n in world.nodes:
        assert bgr(n.attrs["color"]) in present


def test_degradations_change_the_image_deterministically() -> None:
    image = world_for_graph(cup_on_book()).render(320, 240)
    assert (degrade(image, Degradation()) == image).all()
    for spec in (Degradation(noise=8), Degradation(blur=1.5), Degradation(lighting=0.6),
                 Degradation(jpeg=30), Degradation(noise=5, blur=1, lighting=0.3, jpeg=50)):
        out = degrade(image, spec, seed=3)
        assert out.shape == image.shape and out.dtype == np.uint8
        assert np.abs(out.astype(int) - image.astype(int)).mean() > 0.3, spec
        assert (degrade(image, spec, seed=3) == out).all()
    noisy = [degrade(image, Degradation(noise=8), seed=s) for s in (1, 2)]
    assert not (noisy[0] == noisy[1]).all()


def test_png_encoding_round_trips_and_side_by_side_stacks() -> None:
    image = world_for_graph(cup_on_book()).render(160, 120)
    decoded = cv2.imdecode(np.frombuffer(encode_png(image), np.uint8), cv2.IMREAD_COLOR)
    assert decoded is not None and np.array_equal(decoded, image)
    pair = side_by_side([image, image], ["start", "goal"])
    assert pair.shape[1] > 2 * 160 and pair.shape[0] > 120
