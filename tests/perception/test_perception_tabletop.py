"""Tabletop detector on real sim2d renders: exact graphs over many seeds, clean and spoilt.

Seeds 500+ are not the ones the detector was developed on. Each family's scenes are
generated once per module (generation dominates the cost).
"""

from __future__ import annotations

from functools import cache

import cv2
import numpy as np
import pytest

from verigraph.graph.builtin_scenes import cup_on_book
from verigraph.graph.dictionary import builtin_dictionary
from verigraph.graph.model import SceneGraph
from verigraph.graph.wellformed import check_well_formed
from verigraph.perception import perceive, perceive_image
from verigraph.perception.metrics import score_graph
from verigraph.sim2d import Degradation, degrade, world_for_graph
from verigraph.sim2d.generator import GeneratedScene, generate_scene

SEEDS = range(500, 520)
LEVELS = {
    "clean": Degradation(),
    "noise": Degradation(noise=8.0),
    "lighting": Degradation(lighting=0.4),
    "blur": Degradation(blur=1.0),
    "jpeg": Degradation(jpeg=50),
}
# Exact-graph rate each level must reach over the 20 seeds, in the simulator's default
# frame (the scene's shape at 8 px per world unit): the targets.
REQUIRED = {"clean": 1.0, "noise": 0.95, "lighting": 0.95, "blur": 0.95, "jpeg": 0.95}
# A wide kitchen forced into 640x480 gets 3-5 px per world unit: clean and noisy renders
# still read exactly, blur and JPEG erase the thinnest walls (benchmarks/results/sgg.md).
FIXED_FRAME_REQUIRED = {"clean": 1.0, "noise": 0.9}


@cache
def scenes(family: str) -> tuple[GeneratedScene, ...]:
    return tuple(generate_scene(family, seed) for seed in SEEDS)


@cache
def render(family: str, index: int, size: tuple[int, int] | None = None) -> np.ndarray:
    world = scenes(family)[index].world
    return world.render() if size is None else world.render(*size)


def exact_rate(family: str, level: str, size: tuple[int, int] | None = None
               ) -> tuple[float, list[str]]:
    hits, misses = 0, []
    for i, scene in enumerate(scenes(family)):
        image = degrade(render(family, i, size), LEVELS[level], seed=scene.seed)
        result = perceive_image(image, dictionary=family)
        score = score_graph(result.graph, scene.graph, family)
        hits += score.exact
        if not score.exact:
            missing = set(scene.graph.sentences()) - set(result.graph.sentences())
            extra = set(result.graph.sentences()) - set(scene.graph.sentences())
            misses.append(f"seed {scene.seed}: missing {sorted(missing)}, extra {sorted(extra)}")
    return hits / len(SEEDS), misses


@pytest.mark.parametrize("family", ["blocks", "kitchen", "tableware"])
@pytest.mark.parametrize("level", list(LEVELS))
def test_exact_graphs_over_many_seeds(family: str, level: str) -> None:
    rate, misses = exact_rate(family, level)
    assert rate >= REQUIRED[level], f"{family}/{level}: {rate:.2f}\n" + "\n".join(misses)


@pytest.mark.parametrize("family", ["kitchen", "tableware"])
@pytest.mark.parametrize("level", list(FIXED_FRAME_REQUIRED))
def test_a_wide_scene_in_a_640x480_frame(family: str, level: str) -> None:
    rate, misses = exact_rate(family, level, (640, 480))
    assert rate >= FIXED_FRAME_REQUIRED[level], f"{family}/{level} at 640x480: {rate:.2f}\n" \
        + "\n".join(misses)


@pytest.mark.parametrize("family", ["blocks", "kitchen", "tableware"])
def test_goal_layouts_are_perceived(family: str) -> None:
    """Reference-image goals show the goal graph laid out afresh by world_for_graph."""
    hits = 0
    for scene in scenes(family)[:10]:
        goal = scene.goal.graph
        assert goal is not None
        image = world_for_graph(goal, seed=scene.seed + 1).render()
        hits += score_graph(perceive(image, dictionary=family), goal, family).exact
    assert hits >= 9


def test_cup_on_book_is_a_well_formed_graph_with_the_papers_ids() -> None:
    image = world_for_graph(cup_on_book()).render(640, 480)
    result = perceive_image(image, dictionary="tableware")
    graph = result.graph
    assert graph.edge_keys() == cup_on_book().edge_keys()
    assert sorted(graph.node_ids()) == ["book", "cup", "desk", "shelf"]
    assert graph.dictionary == "tableware" and result.view == "tabletop"
    assert check_well_formed(graph, builtin_dictionary("tableware")) == []
    assert not result.warnings
    boxes = {o.id: o.box for o in result.objects}
    assert boxes["cup"][3] <= boxes["book"][1] + 6  # the cup's bottom meets the book's top


def test_blocks_get_colour_ids_and_attrs() -> None:
    scene = scenes("blocks")[0]
    graph = perceive(render("blocks", 0), dictionary="blocks")
    blocks = [n for n in graph.nodes if n.label == "block"]
    assert blocks and all(n.id == f"{n.attrs['color']}_block" for n in blocks)
    assert sorted(graph.node_ids()) == sorted(scene.graph.node_ids())


@pytest.mark.parametrize("family", ["blocks", "kitchen", "tableware"])
def test_union_dictionary_finds_the_family(family: str) -> None:
    """With no dictionary named, the union of the built-ins applies and the family is
    inferred from what is seen."""
    for i, scene in enumerate(scenes(family)[:5]):
        result = perceive_image(render(family, i))
        assert result.family == family and result.graph.dictionary == family
        assert score_graph(result.graph, scene.graph, family).exact, scene.seed


def test_duplicate_labels_are_numbered_left_to_right() -> None:
    scene = generate_scene("tableware", 3, n_objects=11)
    truth = scene.graph
    graph = perceive(scene.world.render(640, 480), dictionary="tableware")
    assert score_graph(graph, truth, "tableware").exact
    labels = [n.label for n in truth.nodes]
    repeated = {lab for lab in labels if labels.count(lab) > 1}
    assert repeated, "the scene should repeat a label for this test to mean anything"
    for label in repeated:
        assert label in graph.node_ids() and f"{label}_2" in graph.node_ids()


def test_empty_scene_gives_an_empty_graph_with_a_warning() -> None:
    from verigraph.sim2d import palette

    image = np.empty((480, 640, 3), np.uint8)
    image[:] = palette.BACKGROUND
    image[440:] = palette.FLOOR
    result = perceive_image(image, dictionary="kitchen")
    assert result.graph.nodes == [] and result.graph.edges == []
    assert any("no objects" in w for w in result.warnings)


def test_objects_outside_the_dictionary_are_left_out_with_a_warning() -> None:
    """A big magenta blob is nothing the kitchen dictionary knows."""
    image = render("kitchen", 0).copy()
    cv2.rectangle(image, (300, 60), (380, 140), (200, 40, 200), -1)
    cv2.rectangle(image, (300, 60), (380, 140), (25, 25, 25), 3)
    result = perceive_image(image, dictionary="kitchen")
    assert score_graph(result.graph, scenes("kitchen")[0].graph, "kitchen").exact
    assert any("colours no dictionary object" in w for w in result.warnings)


def test_a_named_dictionary_limits_the_labels() -> None:
    """Tableware objects seen through the kitchen dictionary: only kitchen labels come
    out (knife and spoon look the same in both), the rest is reported."""
    image = world_for_graph(cup_on_book()).render(640, 480)
    result = perceive_image(image, dictionary="kitchen")
    known = set(builtin_dictionary("kitchen").objects)
    assert all(n.label in known for n in result.graph.nodes)
    assert result.warnings


def test_perceive_is_what_the_tools_layer_calls() -> None:
    """The tools (load_scene, set_goal, generate_scene_graph) all call one wrapper of
    `perceive_image`, which keeps the graph and turns warnings into doubts."""
    from verigraph.graph.dictionary import load_dictionary
    from verigraph.tools import goals, loading, perceived
    from verigraph.tools import scenes as scene_tools

    assert (loading.perceive_photo is goals.perceive_photo is scene_tools.perceive_photo
            is perceived.perceive_photo)
    seen = perceived.perceive_photo(render("kitchen", 1), load_dictionary("kitchen"))
    assert isinstance(seen.graph, SceneGraph) and seen.confident
    assert score_graph(seen.graph, scenes("kitchen")[1].graph, "kitchen").exact
    assert seen.graph == perceive(render("kitchen", 1), dictionary=load_dictionary("kitchen"))
