"""A sim2d world survives JSON: same render bytes, same graph, same behaviour after."""

from __future__ import annotations

import json

import numpy as np
import pytest

from verigraph.actions.model import MoveAction
from verigraph.sim2d import generate_scene
from verigraph.sim2d.persist import world_from_state, world_state

pytestmark = pytest.mark.fast


@pytest.mark.parametrize("family", ["blocks", "kitchen", "tableware", "tangram"])
def test_world_round_trips_exactly(family: str) -> None:
    world = generate_scene(family, 5).world
    restored = world_from_state(json.loads(json.dumps(world_state(world))))
    assert np.array_equal(world.render(), restored.render())
    assert world.observe() == restored.observe()
    assert world_state(restored) == world_state(world)


def test_a_restored_world_moves_like_the_original() -> None:
    world = generate_scene("blocks", 2, 4).world
    restored = world_from_state(json.loads(json.dumps(world_state(world))))
    graph = world.observe()
    mover = next(n.id for n in graph.nodes if n.label == "block"
                 and not any(e.target == n.id for e in graph.edges))
    target = next(n.id for n in graph.nodes if n.id != mover and n.label != "block")
    move = MoveAction(object=mover, relation="on", target=target)
    assert world.perform(move) == restored.perform(move)
    assert world.observe() == restored.observe()
    assert np.array_equal(world.render(), restored.render())


def test_unknown_format_is_refused() -> None:
    with pytest.raises(ValueError, match="format"):
        world_from_state({"format": 99})
