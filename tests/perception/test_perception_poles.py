"""A plain bar hanging from the top edge in front of the scene (a pole, a cable, an arm
link), in any colour of the palette, and readings the dictionary says cannot be: never a
wrong graph without a warning, never an occluder reported as an object."""

from __future__ import annotations

import cv2
import numpy as np
import pytest

from verigraph.graph.dictionary import builtin_dictionary
from verigraph.graph.model import SceneGraph
from verigraph.perception import perceive_image, score_graph
from verigraph.perception.detect.occlusion import find_poles
from verigraph.perception.robustness import FAMILIES, POLE_COLOURS, pole_spec
from verigraph.sim2d import palette
from verigraph.sim2d.degrade import Degradation, degrade
from verigraph.sim2d.generator import generate_scene

pytestmark = pytest.mark.fast

SAMPLE_SEED = 37_100  # one scene per palette colour and family
GREY = palette.COLORS["gray"]  # the counter's colour


def _edges(graph: SceneGraph) -> set[str]:
    return {f"{e.source} {e.relation} {e.target}" for e in graph.edges}


@pytest.mark.parametrize("family", FAMILIES)
def test_a_pole_of_every_colour_never_gives_a_silent_wrong_graph(family: str) -> None:
    """One scene per palette colour, widths and lengths cycling: no wrong graph comes
    without a warning, and no wrong edge is given as sure."""
    silent, sure_wrong = [], []
    for k in range(len(POLE_COLOURS)):
        name, spec = pole_spec(k + len(POLE_COLOURS) * (k % 12))
        scene = generate_scene(family, SAMPLE_SEED + k)
        result = perceive_image(degrade(scene.world.render(), spec, seed=scene.seed),
                                dictionary=family)
        exact = score_graph(result.graph, scene.graph, family).exact
        if not exact and result.confident:
            silent.append((scene.seed, name))
        unsure = {u.item for u in result.uncertain}
        if family != "tangram":
            wrong = _edges(result.graph) - _edges(scene.graph) - unsure
            if wrong:
                sure_wrong.append((scene.seed, name, sorted(wrong)))
    assert not silent, silent
    assert not sure_wrong, sure_wrong


@pytest.mark.parametrize(("length", "width"), [(0.35, 0.02), (0.6, 0.01), (0.85, 0.04),
                                               (1.0, 0.02)])
def test_a_grey_pole_on_a_kitchen_is_never_read_as_a_counter(length: float,
                                                              width: float) -> None:
    d = builtin_dictionary("kitchen")
    for k, at in enumerate((0.2, 0.5, 0.8)):
        scene = generate_scene("kitchen", SAMPLE_SEED + 40 + k)
        spec = Degradation(pole=width, pole_length=length, pole_colour=GREY, pole_at=at)
        result = perceive_image(degrade(scene.world.render(), spec, seed=scene.seed),
                                dictionary="kitchen")
        fixed = sorted(n.label for n in result.graph.nodes if not d.objects[n.label].movable)
        truth = sorted(n.label for n in scene.graph.nodes if not d.objects[n.label].movable)
        assert fixed == truth, (scene.seed, at, fixed)
        assert not any(o.box[1] <= 1 for o in result.objects), result.objects
        assert not result.confident
        assert [b.kind for b in result.blocked if b.kind == "pole"] == ["pole"]
        assert any("hanging from the top edge" in w for w in result.warnings)


def test_what_a_pole_covers_is_uncertain_and_named() -> None:
    """The objects a pole crosses are named in `blocked` and `occluded`, and their
    edges are uncertain with the reason."""
    scene = generate_scene("blocks", SAMPLE_SEED + 50)
    image = scene.world.render()
    clean = perceive_image(image, dictionary="blocks")
    block = next(o for o in clean.objects if o.label == "block")
    x = (block.box[0] + block.box[2]) // 2 - 6
    spoilt = image.copy()
    spoilt[:, x:x + 12] = palette.COLORS["red"]  # a red pole down across the block
    result = perceive_image(spoilt, dictionary="blocks")
    assert any(b.kind == "pole" and block.id in b.touches for b in result.blocked), \
        result.blocked
    assert block.id in result.occluded
    reasons = {u.item: u.reason for u in result.uncertain}
    assert block.id in reasons and "hanging from the top edge" in reasons[block.id]


def test_no_pole_in_clean_pictures() -> None:
    for family in FAMILIES:
        for k in range(3):
            scene = generate_scene(family, SAMPLE_SEED + 60 + k)
            assert find_poles(scene.world.render()) == []


def _kitchen_with(label: str) -> tuple[np.ndarray, dict[str, tuple[int, int, int, int]]]:
    for seed in range(SAMPLE_SEED + 70, SAMPLE_SEED + 120):
        scene = generate_scene("kitchen", seed)
        image = scene.world.render()
        result = perceive_image(image, dictionary="kitchen")
        boxes = {o.label: o.box for o in result.objects}
        if label in boxes and result.confident:
            return image, boxes
    raise AssertionError(f"no kitchen with a {label} among the seeds")


def test_furniture_standing_on_an_object_is_not_emitted() -> None:
    """A counter-grey slab standing on the stove (no counter does) is something in
    front of the scene: it is not reported as a second counter, and it is said so."""
    image, boxes = _kitchen_with("stove")
    x0, y0, x1, _ = boxes["stove"]
    slab = image.copy()
    cv2.rectangle(slab, (x0 + 4, y0 - 60), (x1 - 4, y0 - 1), GREY, -1)
    cv2.rectangle(slab, (x0 + 4, y0 - 60), (x1 - 4, y0 - 1), palette.OUTLINE, 1)
    result = perceive_image(slab, dictionary="kitchen")
    assert [n.id for n in result.graph.nodes if n.label == "counter"] == ["counter"], \
        result.graph.nodes
    assert any("stands on stove" in w and "not reported as an object" in w
               for w in result.warnings), result.warnings
    assert not result.confident


def test_an_object_on_nothing_is_uncertain() -> None:
    scene = generate_scene("blocks", SAMPLE_SEED + 51)
    image = scene.world.render()
    h, w = image.shape[:2]
    floating = image.copy()
    cx, cy = w // 2, h // 6
    cv2.rectangle(floating, (cx - 20, cy - 20), (cx + 20, cy + 20), palette.COLORS["lime"], -1)
    cv2.rectangle(floating, (cx - 20, cy - 20), (cx + 20, cy + 20), palette.OUTLINE, 1)
    result = perceive_image(floating, dictionary="blocks")
    reasons = {u.item: u.reason for u in result.uncertain}
    assert "lime_block" in reasons and "stands on nothing" in reasons["lime_block"], reasons


def test_a_region_running_into_the_border_is_uncertain() -> None:
    scene = generate_scene("blocks", SAMPLE_SEED + 52)
    image = scene.world.render()
    clean = perceive_image(image, dictionary="blocks")
    left = min((o for o in clean.objects if o.label == "block"), key=lambda o: o.box[0])
    cut = image[:, left.box[0] + 8:].copy()
    result = perceive_image(cut, dictionary="blocks")
    reasons = [u.reason for u in result.uncertain if " " not in u.item]
    assert any("runs into the image's left border" in r for r in reasons), reasons
    assert not result.confident
