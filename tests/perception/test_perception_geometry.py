"""Geometry on images with known transforms: camera roll is measured on the floor line
and undone; furniture cut in two by an occluder is joined and the occlusion reported."""

from __future__ import annotations

import numpy as np
import pytest

from verigraph.graph.dictionary import load_dictionary
from verigraph.perception import perceive_image, score_graph
from verigraph.perception.correct.roll import estimate_roll
from verigraph.perception.detect import colors
from verigraph.perception.label.catalogue import models_by_colour
from verigraph.sim2d import degrade_ops as ops
from verigraph.sim2d.degrade import Degradation, degrade
from verigraph.sim2d.generator import generate_scene


def classes_of(image: np.ndarray, family: str) -> np.ndarray:
    models = models_by_colour(load_dictionary(family))
    return colors.classify(image, colors.colour_table(tuple(sorted(models)), tangram=False))


@pytest.mark.parametrize("degrees", [-6.0, -2.0, 0.0, 2.5, 8.0])
def test_roll_is_read_off_the_floor_line(degrees: float) -> None:
    image = generate_scene("tableware", 32_000).world.render()
    rolled = ops.rotate(image, degrees) if degrees else image
    found = estimate_roll(classes_of(rolled, "tableware"))
    assert found is not None and found == pytest.approx(degrees, abs=0.3)


@pytest.mark.parametrize("family", ["kitchen", "tableware", "blocks"])
@pytest.mark.parametrize("degrees", [-8.0, 8.0])
def test_a_rolled_camera_gives_the_graph_with_a_note(family: str, degrees: float) -> None:
    for seed in (32_001, 32_002):
        scene = generate_scene(family, seed)
        result = perceive_image(degrade(scene.world.render(), Degradation(rotation=degrees)),
                                dictionary=family)
        assert score_graph(result.graph, scene.graph, family).exact, result.warnings
        assert any("rolled" in w for w in result.warnings)


def test_a_table_split_by_a_bar_is_one_table_and_the_occlusion_is_reported() -> None:
    scene = generate_scene("blocks", 20_000)
    image = scene.world.render()
    rng = np.random.default_rng(0)
    barred = ops.occlude(image, 0.01, (300, 0, 340, image.shape[0]), rng)
    result = perceive_image(barred, dictionary="blocks")
    assert [n.label for n in result.graph.nodes].count("table") == 1
    assert score_graph(result.graph, scene.graph, "blocks").exact
    assert result.occluded == ["table"]
    assert any("something in front hides part of the scene" in w and "touches table" in w
               for w in result.warnings)
    assert not result.confident


@pytest.mark.parametrize("family", ["blocks", "kitchen", "tableware", "tangram"])
def test_family_detection_says_which_and_why(family: str) -> None:
    for seed in (32_010, 32_011, 32_012):
        scene = generate_scene(family, seed)
        result = perceive_image(scene.world.render())
        assert result.family == family, result.family_reason
        assert result.family_reason.startswith(f"{family}:")
        assert score_graph(result.graph, scene.graph, family).exact


def test_a_picture_two_families_fit_alike_is_refused() -> None:
    """Bare furniture: a table with nothing on it is blocks' and tableware's alike."""
    from verigraph.graph.model import Node, SceneGraph
    from verigraph.sim2d import world_for_graph

    graph = SceneGraph(nodes=[Node(id="table", label="table")], dictionary="blocks")
    result = perceive_image(world_for_graph(graph).render())
    assert result.family is None and not result.graph.nodes
    assert result.family_reason.startswith("refused")
    assert any("about equally" in w for w in result.warnings)
