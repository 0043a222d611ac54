"""The PyBullet Panda: real physics, the camera as locator, the whole adapter on top.

This is the honest end-to-end test of the adapter: each validated action moves a
simulated arm, and the result is checked in the physics itself (contacts and
heights), not only through the camera.
"""

from __future__ import annotations

import math
import threading
from collections.abc import Iterator
from pathlib import Path

import pytest
from arm_deps import require
from panda_helpers import arm_moving

pb = require("pybullet")

from verigraph.actions.execution import execute_in_world  # noqa: E402
from verigraph.actions.model import MoveAction  # noqa: E402
from verigraph.arm import ArmWorld, PyBulletOptions, open_arm_world, parse_arm_config  # noqa: E402
from verigraph.arm.sim.camera import PyBulletCameraLocator, capture  # noqa: E402
from verigraph.arm.sim.panda_scene import FINGER_JOINTS, PandaScene  # noqa: E402
from verigraph.graph.builtin_scenes import three_blocks  # noqa: E402
from verigraph.graph.model import Edge, Node, SceneGraph  # noqa: E402
from verigraph.graph.state import WorldState  # noqa: E402

BLOCKS = ("red_block", "green_block", "blue_block")
BLOCK_M = 0.06  # the blocks dictionary's 6 cm


def loose_blocks() -> SceneGraph:
    return SceneGraph(nodes=[Node(id="table", label="table")] + [
        Node(id=b, label="block") for b in BLOCKS],
        edges=[Edge(source=b, relation="on", target="table") for b in BLOCKS],
        dictionary="blocks")


def open_panda(graph: SceneGraph, **config: object) -> ArmWorld:
    return open_arm_world(parse_arm_config({"driver": "pybullet", "mode": "sim", **config}),
                          graph)


def scene_of(world: ArmWorld) -> PandaScene:
    scene = world._controller._driver.scene  # type: ignore[attr-defined]
    assert isinstance(scene, PandaScene)
    return scene


def positions(scene: PandaScene) -> dict[str, tuple[float, float, float]]:
    return {b: scene.body_position(b) for b in BLOCKS}


@pytest.fixture
def world() -> Iterator[ArmWorld]:
    w = open_panda(loose_blocks())
    yield w
    w.close()


def test_camera_locates_every_block_within_a_centimetre() -> None:
    scene = PandaScene.from_graph(three_blocks())
    try:
        found = PyBulletCameraLocator(scene).locate([*BLOCKS, "table"])
        assert set(found) == {*BLOCKS, "table"}
        for block in BLOCKS:
            truth = scene.body_position(block)
            seen = found[block]
            assert math.dist(seen.centre[:2], truth[:2]) < 0.01, block
            assert seen.top_z == pytest.approx(truth[2] + BLOCK_M / 2, abs=0.005)
            assert sorted(seen.size) == pytest.approx([BLOCK_M] * 3, abs=0.006)
        # blue is covered by red: its top is hidden, yet its footprint is still whole
        assert found["blue_block"].size[:2] == pytest.approx((BLOCK_M, BLOCK_M), abs=0.006)
        assert found["table"].top_z == pytest.approx(0.0, abs=0.005)
    finally:
        scene.close()


def test_observed_graph_matches_the_scene_it_was_built_from() -> None:
    w = open_panda(three_blocks())
    try:
        assert w.verify_scene(three_blocks()).satisfied
    finally:
        w.close()


def test_panda_stacks_three_blocks_and_the_physics_confirms_each_on(world: ArmWorld) -> None:
    scene = scene_of(world)
    state = WorldState.from_graph(loose_blocks())
    for step, (obj, target) in enumerate([("green_block", "red_block"),
                                          ("blue_block", "green_block")], start=1):
        action = MoveAction(object=obj, target=target)
        _, _, violation, _, state = execute_in_world(state, [action], world, first_step=step)
        assert violation is None, violation.text()
        assert world.last_check is not None and world.last_check.holds
        # the physics, not the camera: resting on the target, one block higher, centred
        assert scene.in_contact(obj, target)
        (ox, oy, oz), (tx, ty, tz) = scene.body_position(obj), scene.body_position(target)
        assert oz - tz == pytest.approx(BLOCK_M, abs=0.004)
        assert math.dist((ox, oy), (tx, ty)) < 0.015
    assert {e.sentence() for e in state.edges()} == {
        "red_block on table", "green_block on red_block", "blue_block on green_block"}
    assert not scene.in_contact("blue_block", "table")
    assert world.status().commands_sent == 5  # connect + 2 x (pick, place)


def test_dry_run_moves_nothing_in_the_physics() -> None:
    w = open_arm_world(parse_arm_config({"driver": "pybullet"}), loose_blocks())
    try:
        scene = scene_of(w)
        before, joints = positions(scene), scene.arm_positions()
        state = WorldState.from_graph(loose_blocks())
        _, _, violation, _, state = execute_in_world(
            state, [MoveAction(object="green_block", target="red_block"),
                    MoveAction(object="blue_block", target="green_block")], w)
        assert violation is None  # the dry run predicts the stack ...
        assert "blue_block on green_block" in {e.sentence() for e in state.edges()}
        assert positions(scene) == before and scene.arm_positions() == joints  # ... moves none
        assert w.status().commands_sent == 0
    finally:
        w.close()


def test_failed_grasp_is_observed_and_becomes_the_graph(world: ArmWorld) -> None:
    """Closed loop: fingers without friction drop the block; the episode learns it."""
    scene = scene_of(world)
    for finger in FINGER_JOINTS:
        pb.changeDynamics(scene.robot, finger, lateralFriction=0.0,
                          physicsClientId=scene.client)
    state = WorldState.from_graph(loose_blocks())
    _, _, violation, _, after = execute_in_world(
        state, [MoveAction(object="green_block", target="red_block")], world)
    assert violation is not None and violation.constraint == "execution_failed"
    assert violation.blocking == ["green_block"]
    assert world.last_check is not None and not world.last_check.holds
    assert not scene.in_contact("green_block", "red_block")
    assert "green_block on red_block" not in {e.sentence() for e in after.edges()}


def test_target_outside_the_workspace_moves_nothing() -> None:
    w = open_panda(loose_blocks(), workspace={"min": [0.2, -0.45, 0.01],
                                              "max": [0.8, 0.05, 0.65]})
    try:
        scene = scene_of(w)
        before = positions(scene)
        state = WorldState.from_graph(loose_blocks())
        _, _, violation, _, after = execute_in_world(
            state, [MoveAction(object="red_block", target="blue_block")], w)
        assert violation is not None and "outside the workspace" in violation.message
        assert after.to_graph().edge_keys() == loose_blocks().edge_keys()
        assert positions(scene) == before
    finally:
        w.close()


def test_timeout_halts_the_arm_and_latches_the_stop(tmp_path: Path) -> None:
    w = open_panda(loose_blocks(), motion_timeout_s=0.3, agent_may_reset=True,
                   audit_log=str(tmp_path / "audit.jsonl"),
                   pybullet=PyBulletOptions(real_time_factor=1.0).model_dump())
    try:
        scene = scene_of(w)
        state = WorldState.from_graph(loose_blocks())
        _, _, violation, _, after = execute_in_world(
            state, [MoveAction(object="green_block", target="red_block")], w)
        assert w.last_outcome is not None and w.last_outcome.status == "timeout"
        assert w.status().stop_latched
        assert violation is not None and violation.constraint == "execution_failed"
        halted = scene.arm_positions()
        scene.step(60)
        assert max(abs(a - b) for a, b in zip(halted, scene.arm_positions(), strict=True)) < 0.01
        refused = w.perform(MoveAction(object="green_block", target="red_block"))
        assert refused is not None and "stop is latched" in refused.message
        w.reset()
        assert not w.status().stop_latched
    finally:
        w.close()


def test_stop_during_a_motion_cancels_it(tmp_path: Path) -> None:
    w = open_panda(loose_blocks(), audit_log=str(tmp_path / "audit.jsonl"),
                   pybullet=PyBulletOptions(real_time_factor=1.0).model_dump())
    try:
        moving = arm_moving(scene_of(w))
        worker = threading.Thread(target=w.perform,
                                  args=(MoveAction(object="green_block", target="red_block"),))
        worker.start()
        assert moving.wait(10)  # the arm is moving, not merely about to
        status = w.stop("test stop")
        worker.join(10)
        assert not worker.is_alive()
        assert status.stop_latched and status.stop_reason == "test stop"
        assert w.last_outcome is not None and w.last_outcome.status == "cancelled"
        assert not scene_of(w).in_contact("green_block", "red_block")
    finally:
        w.close()


def test_camera_frames_are_written_as_png(tmp_path: Path) -> None:
    scene = PandaScene.from_graph(three_blocks())
    try:
        frame = capture(scene)
        path = frame.save_png(tmp_path / "frame.png")
        assert path.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
        assert frame.rgb.shape == (300, 400, 3) and frame.rgb.std() > 10
    finally:
        scene.close()


def test_render_and_home(world: ArmWorld) -> None:
    assert world.render is not None
    image = world.render(width=160, height=120)
    assert image.shape == (120, 160, 3) and image.std() > 10
    world.perform(MoveAction(object="green_block", target="red_block"))
    assert world.home().status == "done"
    tcp = world.status().tcp
    home = world._controller.config.home
    assert tcp is not None and math.dist(tcp.point(), home.point()) < 0.01


def test_in_places_the_cup_inside_the_bowl() -> None:
    graph = SceneGraph(nodes=[Node(id="table", label="table"), Node(id="bowl", label="bowl"),
                              Node(id="cup", label="cup")],
                       edges=[Edge(source="bowl", relation="on", target="table"),
                              Edge(source="cup", relation="on", target="table")],
                       dictionary="tableware")
    w = open_panda(graph)
    try:
        scene = scene_of(w)
        _, _, violation, _, state = execute_in_world(
            WorldState.from_graph(graph), [MoveAction(object="cup", relation="in",
                                                      target="bowl")], w)
        assert violation is None, violation.text()
        assert "cup in bowl" in {e.sentence() for e in state.edges()}
        (cx, cy, cz), (bx, by, bz) = scene.body_position("cup"), scene.body_position("bowl")
        assert math.dist((cx, cy), (bx, by)) < 0.03  # inside the 12 cm bowl's walls
        assert cz - 0.04 < bz  # the cup's bottom is below the bowl's centre: inside
        assert scene.in_contact("cup", "bowl") and not scene.in_contact("cup", "table")
    finally:
        w.close()
