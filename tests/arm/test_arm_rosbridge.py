"""The rosbridge driver: the real roslibpy client over a real loopback WebSocket.

No rosbridge server can run here (it links ROS 2), so the tests start
`LoopbackRosbridgeServerForTests`, which speaks the rosbridge protocol and executes
the FollowJointTrajectory and GripperCommand goals on a PyBullet Panda. The camera
of that same simulated cell is the locator.
"""

from __future__ import annotations

import math
import socket
import threading
import time
from collections.abc import Iterator
from typing import Any

import pytest
from arm_deps import require

require("roslibpy")
require("websockets")
require("pybullet")

from loopback_rosbridge import LoopbackRosbridgeServerForTests  # noqa: E402

from verigraph.actions.execution import execute_in_world  # noqa: E402
from verigraph.actions.model import MoveAction  # noqa: E402
from verigraph.arm import (  # noqa: E402
    ArmConnectionError,
    ArmWorld,
    InfeasibleMotionError,
    PyBulletOptions,
    open_arm_world,
    parse_arm_config,
)
from verigraph.arm.sim.camera import PyBulletCameraLocator  # noqa: E402
from verigraph.arm.sim.panda_scene import PandaScene  # noqa: E402
from verigraph.graph.model import Edge, Node, SceneGraph  # noqa: E402
from verigraph.graph.state import WorldState  # noqa: E402

BLOCKS = ("red_block", "green_block", "blue_block")


def loose_blocks() -> SceneGraph:
    return SceneGraph(nodes=[Node(id="table", label="table")] + [
        Node(id=b, label="block") for b in BLOCKS],
        edges=[Edge(source=b, relation="on", target="table") for b in BLOCKS],
        dictionary="blocks")


class RosCell:
    """A PyBullet Panda behind a loopback rosbridge server, and an ArmWorld on it."""

    def __init__(self, options: PyBulletOptions | None = None, **config: object) -> None:
        self.scene = PandaScene.from_graph(loose_blocks(), options)
        self.server = LoopbackRosbridgeServerForTests(self.scene)
        port = self.server.start()
        self.config = parse_arm_config({
            "driver": "rosbridge", "mode": "sim", "host": "127.0.0.1",
            "rosbridge": {"port": port, "simulated_backend": True}, **config})
        self.world: ArmWorld | None = None

    def open(self) -> ArmWorld:
        self.world = open_arm_world(self.config, loose_blocks(),
                                    locator=PyBulletCameraLocator(self.scene))
        return self.world

    def close(self) -> None:
        if self.world is not None:
            self.world.close()
        self.server.stop()
        self.scene.close()


@pytest.fixture
def cell() -> Iterator[RosCell]:
    c = RosCell()
    yield c
    c.close()


def test_rosbridge_stacks_three_blocks_through_the_loopback_server(cell: RosCell) -> None:
    world = cell.open()
    state = WorldState.from_graph(loose_blocks())
    for step, (obj, target) in enumerate([("green_block", "red_block"),
                                          ("blue_block", "green_block")], start=1):
        _, _, violation, _, state = execute_in_world(
            state, [MoveAction(object=obj, target=target)], world, first_step=step)
        assert violation is None, violation.text()
        assert cell.scene.in_contact(obj, target)
        assert cell.scene.body_position(obj)[2] - cell.scene.body_position(target)[2] == \
            pytest.approx(0.06, abs=0.004)
    goals = cell.server.ops("send_action_goal")
    trajectories = [g for g in goals if g["action_type"] ==
                    "control_msgs/action/FollowJointTrajectory"]
    grips = [g for g in goals if g["action_type"] == "control_msgs/action/GripperCommand"]
    # each action: pick = 3 lines + open + close, place = 3 lines + open
    assert len(trajectories) == 12 and len(grips) == 6
    first = trajectories[0]["args"]["trajectory"]
    assert first["joint_names"] == [f"panda_joint{i}" for i in range(1, 8)]
    stamps = [p["time_from_start"]["sec"] + p["time_from_start"]["nanosec"] * 1e-9
              for p in first["points"]]
    assert stamps == sorted(stamps) and stamps[0] > 0
    assert grips[1]["args"]["command"] == {"position": 0.0, "max_effort": 20.0}
    assert cell.server.ops("subscribe")[0]["topic"] == "/joint_states"


def test_stop_cancels_the_active_goal() -> None:
    c = RosCell(PyBulletOptions(real_time_factor=1.0))
    try:
        world = c.open()
        moving = threading.Event()
        follow = c.scene.follow

        def follow_and_signal(*args: Any, **kwargs: Any) -> Any:
            moving.set()  # a trajectory goal is being executed: the arm moves
            return follow(*args, **kwargs)

        c.scene.follow = follow_and_signal  # type: ignore[method-assign]
        worker = threading.Thread(target=world.perform,
                                  args=(MoveAction(object="green_block", target="red_block"),))
        worker.start()
        assert moving.wait(10)
        world.stop("operator stop")
        worker.join(10)
        assert not worker.is_alive()
        cancels = c.server.ops("cancel_action_goal")
        assert cancels and cancels[0]["id"] == c.server.ops("send_action_goal")[-1]["id"]
        assert world.last_outcome is not None and world.last_outcome.status == "cancelled"
        halted = c.scene.arm_positions()
        c.scene.step(60)  # a quarter second of physics: a halted arm stays put
        assert max(abs(a - b) for a, b in zip(halted, c.scene.arm_positions(), strict=True)) \
            < 1e-3
        assert world.status().stop_latched
    finally:
        c.close()


def _free_port() -> int:
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return int(s.getsockname()[1])


def test_unreachable_rosbridge_is_a_clear_bounded_error() -> None:
    port = _free_port()
    config = parse_arm_config({"driver": "rosbridge", "mode": "sim", "host": "127.0.0.1",
                               "connect_timeout_s": 1.0,
                               "rosbridge": {"port": port, "simulated_backend": True}})
    scene = PandaScene.from_graph(loose_blocks())
    try:
        started = time.monotonic()
        with pytest.raises(ArmConnectionError) as err:
            open_arm_world(config, loose_blocks(), locator=PyBulletCameraLocator(scene))
        assert time.monotonic() - started < 3
        assert f"ws://127.0.0.1:{port}" in str(err.value) and "rosbridge_server" in str(err.value)
    finally:
        scene.close()


def test_joint_names_the_model_lacks_fail_at_connect(cell: RosCell) -> None:
    cell.config = cell.config.with_overrides(rosbridge={
        **cell.config.rosbridge.model_dump(), "joint_names": [f"arm_{i}" for i in range(7)]})
    with pytest.raises(InfeasibleMotionError, match="no joint arm_0") as err:
        cell.open()
    assert err.value.field == "rosbridge.joint_names"
    assert not cell.server.ops("send_action_goal")
    assert math.isfinite(cell.scene.arm_positions()[0])


def test_joint_states_without_the_configured_names_are_a_clear_error() -> None:
    scene = PandaScene.from_graph(loose_blocks())
    server = LoopbackRosbridgeServerForTests(scene, joint_names=tuple(
        f"fr3_joint{i}" for i in range(1, 8)))
    try:
        port = server.start()
        config = parse_arm_config({"driver": "rosbridge", "mode": "sim", "host": "127.0.0.1",
                                   "connect_timeout_s": 1.0,
                                   "rosbridge": {"port": port, "simulated_backend": True}})
        with pytest.raises(ArmConnectionError, match="fr3_joint1") as err:
            open_arm_world(config, loose_blocks(), locator=PyBulletCameraLocator(scene))
        assert err.value.field == "rosbridge.joint_names"
        assert not server.ops("send_action_goal")
    finally:
        server.stop()
        scene.close()
