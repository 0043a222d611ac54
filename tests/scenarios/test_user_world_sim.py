"""simulate=true on a user's own labels: generic bodies from roles, labelled renders,
the verifier's predictions carried out, and `no_room` (never a crash) where nothing fits."""

from __future__ import annotations

import random
from typing import Any

import numpy as np
import pytest
from user_worlds import inline_scene

from verigraph.actions.execution import execute_in_world
from verigraph.errors import VeriGraphError
from verigraph.graph import SceneGraph, WorldState
from verigraph.sim2d import TabletopWorld, generate_scene, world_for_graph
from verigraph.sim2d.generator import valid_moves
from verigraph.sim2d.room import room_violation
from verigraph.tools import Toolbox
from verigraph.tools.scenes import ImageResult


def test_generic_bodies_follow_the_role_and_the_declared_size() -> None:
    world = world_for_graph(SceneGraph.model_validate(inline_scene()))
    assert isinstance(world, TabletopWorld)
    things = world.scene.things
    assert things["laptop"].spec.kind == "box"  # a slab: 14 wide, 2 high
    assert (things["laptop"].spec.width, things["laptop"].spec.height) == (14.0, 2.0)
    assert things["pens"].spec.kind == "container" and things["pens"].spec.cavity is not None
    assert things["drawers"].spec.kind == "furniture"
    assert things["drawers"].spec.cavity is not None  # a fixed bin, things go in it
    assert world.observe().edge_keys() == SceneGraph.model_validate(inline_scene()).edge_keys()


def test_default_sizes_apply_without_width_and_height() -> None:
    scene = inline_scene()
    scene["nodes"].append({"id": "gadget", "label": "gadget", "attrs": {"movable": True}})
    scene["edges"].append({"source": "gadget", "relation": "on", "target": "desk"})
    world = world_for_graph(SceneGraph.model_validate(scene))
    assert isinstance(world, TabletopWorld)
    spec = world.scene.things["gadget"].spec
    assert (spec.kind, spec.width, spec.height) == ("box", 6.0, 4.0)


def test_a_simulated_user_world_renders_with_its_labels() -> None:
    box = Toolbox()
    ep = box.call("load_scene", {"graph": inline_scene(), "simulate": True}).episode_id
    labelled = box.call("render_scene", {"episode_id": ep, "width": 480, "height": 320})
    assert isinstance(labelled, ImageResult)
    with box.context.store.use(ep) as episode:
        world = episode.world
        assert isinstance(world, TabletopWorld)
        bare = world.render(width=480, height=320)
    import cv2
    picture = cv2.imdecode(np.frombuffer(labelled.png, np.uint8), cv2.IMREAD_COLOR)
    assert picture.shape == (320, 480, 3)
    # The labels are drawn on top of the same scene: some pixels differ, most do not.
    changed = np.any(picture != bare, axis=2).mean()
    assert 0.001 < changed < 0.2
    silver = np.array([192, 192, 192])  # the laptop's colour (BGR of silver)
    assert np.any(np.all(np.abs(bare.astype(int) - silver) < 30, axis=2))


def test_random_valid_moves_end_in_the_predicted_graph() -> None:
    executed = refused = 0
    failures: list[str] = []
    for seed in range(6):
        scene = generate_scene("user", seed)
        world, state = scene.world, WorldState.from_graph(scene.graph)
        assert state.dictionary.user_labels
        rng = random.Random(seed)
        for _ in range(10):
            action = rng.choice(valid_moves(state))
            roomy = room_violation(state, action) is None
            _, _, violation, _, new_state = execute_in_world(state, [action], world)
            if violation is None:
                executed += 1
                assert world.observe().edge_keys() == new_state.to_graph().edge_keys()
                state = new_state
            elif violation.constraint == "no_room" and not roomy:
                refused += 1
            else:
                failures.append(f"user:{seed} {action.text()}: {violation.message}")
                state = WorldState.from_graph(world.observe(), state.dictionary, partial=True)
    assert failures == []
    assert executed >= 40


def test_a_move_with_no_room_is_refused_and_changes_nothing() -> None:
    box = Toolbox()
    scene = inline_scene()
    scene["dictionary"]["objects"]["rug"] = {"surface": True, "capacity": 1, "width": 400,
                                             "height": 1}
    scene["nodes"].append({"id": "rug", "label": "rug"})
    scene["edges"].append({"source": "rug", "relation": "on", "target": "desk"})
    ep = box.call("load_scene", {"graph": scene, "simulate": True}).episode_id
    before = box.call("get_state", {"episode_id": ep}).graph
    out: Any = box.call("execute_actions", {"episode_id": ep,
                                            "actions": ["move(rug, on, book_2)"]})
    assert not out.ok and out.violation.constraint == "no_room"
    assert "no free place" in out.violation.message
    assert box.call("get_state", {"episode_id": ep}).graph == before


def test_a_scene_that_cannot_be_laid_out_is_a_clear_no_room() -> None:
    box = Toolbox()
    scene = inline_scene()
    scene["dictionary"]["objects"]["pinboard"] = {"surface": True, "capacity": 3,
                                                  "width": 10, "height": 1}
    scene["dictionary"]["objects"]["poster"] = {"width": 300, "height": 1}
    scene["nodes"] += [{"id": "pinboard", "label": "pinboard"},
                       {"id": "poster_1", "label": "poster"},
                       {"id": "poster_2", "label": "poster"}]
    scene["edges"] += [{"source": "pinboard", "relation": "on", "target": "desk"},
                       {"source": "poster_1", "relation": "on", "target": "pinboard"},
                       {"source": "poster_2", "relation": "on", "target": "pinboard"}]
    with pytest.raises(VeriGraphError) as caught:
        box.call("load_scene", {"graph": scene, "simulate": True})
    assert caught.value.message.startswith("no_room:")
    assert caught.value.field == "edges" and caught.value.fix
    assert len(box.context.store) == 0
    # The same scene verifies without the simulator: only its layout is impossible.
    assert box.call("load_scene", {"graph": scene}).graph is not None
