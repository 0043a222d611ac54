"""LoopbackRosbridgeServerForTests: a rosbridge-protocol server on 127.0.0.1 for tests.

No real rosbridge server can run here (it links ROS 2), so this speaks the subset of
the rosbridge v2 JSON protocol the `rosbridge` driver uses, over a real WebSocket:
`subscribe` (joint states are published at a fixed rate), `send_action_goal` for
FollowJointTrajectory and GripperCommand (executed on a PyBullet Panda, with
`action_feedback` and `action_result`), and `cancel_action_goal`. Every received
message is kept in `received` so tests can assert what the client really sent.
"""

from __future__ import annotations

import asyncio
import contextlib
import json
import queue
import threading
from collections.abc import Callable
from typing import Any

from websockets.asyncio.server import Server, ServerConnection, serve

from verigraph.arm.config import PANDA_JOINTS
from verigraph.arm.errors import MotionCancelledError
from verigraph.arm.sim.kinematics import JointTrajectory
from verigraph.arm.sim.panda_scene import PandaScene

SUCCEEDED, CANCELED, ABORTED = 4, 5, 6
FINGER_NAMES = ("panda_finger_joint1", "panda_finger_joint2")


class _Goal:
    def __init__(self, message: dict[str, Any], connection: ServerConnection) -> None:
        self.id = str(message.get("id"))
        self.action = str(message["action"])
        self.args: dict[str, Any] = message.get("args") or {}
        self.connection = connection
        self.cancel = threading.Event()


class LoopbackRosbridgeServerForTests:
    """Rosbridge protocol on loopback, with a PandaScene executing the goals."""

    def __init__(self, scene: PandaScene, *,
                 trajectory_action: str = "/panda_arm_controller/follow_joint_trajectory",
                 gripper_action: str = "/panda_hand_controller/gripper_cmd",
                 joint_states_topic: str = "/joint_states",
                 joint_names: tuple[str, ...] = PANDA_JOINTS, publish_hz: float = 25.0) -> None:
        self.scene = scene
        self.trajectory_action = trajectory_action
        self.gripper_action = gripper_action
        self.joint_states_topic = joint_states_topic
        self.joint_names = joint_names
        self.publish_hz = publish_hz
        self.received: list[dict[str, Any]] = []
        self.port = 0
        self._loop: asyncio.AbstractEventLoop | None = None
        self._server: Server | None = None
        self._subscribers: set[ServerConnection] = set()
        self._goals: queue.Queue[_Goal | None] = queue.Queue()
        self._active: dict[str, _Goal] = {}
        self._ready = threading.Event()
        self._thread = threading.Thread(target=self._serve, name="loopback-rosbridge",
                                        daemon=True)
        self._executor = threading.Thread(target=self._execute_goals,
                                          name="loopback-rosbridge-goals", daemon=True)

    # -- lifecycle -------------------------------------------------------------------------
    def start(self) -> int:
        """Start serving on an ephemeral loopback port; returns the port."""
        self._thread.start()
        self._executor.start()
        if not self._ready.wait(10):
            raise RuntimeError("the loopback rosbridge server did not start")
        return self.port

    def stop(self) -> None:
        self._goals.put(None)
        for goal in list(self._active.values()):
            goal.cancel.set()
        if self._loop is not None and self._server is not None:
            self._loop.call_soon_threadsafe(self._server.close)
        self._thread.join(5)
        self._executor.join(5)

    def __enter__(self) -> LoopbackRosbridgeServerForTests:
        self.start()
        return self

    def __exit__(self, *exc: object) -> None:
        self.stop()

    def ops(self, op: str) -> list[dict[str, Any]]:
        """Received messages with this `op`, in order."""
        return [m for m in self.received if m.get("op") == op]

    # -- the WebSocket side (event-loop thread) ----------------------------------------------
    def _serve(self) -> None:
        asyncio.run(self._main())

    async def _main(self) -> None:
        self._loop = asyncio.get_running_loop()
        async with serve(self._handle, "127.0.0.1", 0) as server:
            self._server = server
            self.port = server.sockets[0].getsockname()[1]
            publisher = asyncio.create_task(self._publish_joint_states())
            self._ready.set()
            await server.wait_closed()
            publisher.cancel()

    async def _handle(self, connection: ServerConnection) -> None:
        try:
            async for raw in connection:
                message = json.loads(raw)
                self.received.append(message)
                op = message.get("op")
                if op == "subscribe" and message.get("topic") == self.joint_states_topic:
                    self._subscribers.add(connection)
                elif op == "unsubscribe":
                    self._subscribers.discard(connection)
                elif op == "send_action_goal":
                    goal = _Goal(message, connection)
                    self._active[goal.id] = goal
                    self._goals.put(goal)
                elif op == "cancel_action_goal":
                    cancelled = self._active.get(str(message.get("id")))
                    if cancelled is not None:
                        cancelled.cancel.set()
        finally:
            self._subscribers.discard(connection)

    async def _publish_joint_states(self) -> None:
        while True:
            if self._subscribers:
                arm = self.scene.arm_positions()
                fingers = self.scene.finger_positions()
                text = json.dumps({"op": "publish", "topic": self.joint_states_topic, "msg": {
                    "header": {"stamp": {"sec": 0, "nanosec": 0}, "frame_id": ""},
                    "name": list(self.joint_names) + list(FINGER_NAMES),
                    "position": list(arm) + list(fingers), "velocity": [], "effort": []}})
                for connection in list(self._subscribers):
                    try:
                        await connection.send(text)
                    except Exception:
                        self._subscribers.discard(connection)
            await asyncio.sleep(1 / self.publish_hz)

    def _reply(self, goal: _Goal, message: dict[str, Any]) -> None:
        """Send from the executor thread through the event loop."""
        loop = self._loop
        if loop is None:
            return
        future = asyncio.run_coroutine_threadsafe(goal.connection.send(json.dumps(message)),
                                                  loop)
        with contextlib.suppress(Exception):  # the client went away: nobody to tell
            future.result(5)

    # -- goal execution (executor thread: the only one stepping the physics) --------------
    def _execute_goals(self) -> None:
        while (goal := self._goals.get()) is not None:
            handlers: dict[str, Callable[[_Goal], tuple[int, dict[str, Any]]]] = {
                self.trajectory_action: self._follow, self.gripper_action: self._grip}
            handler = handlers.get(goal.action)
            status: int
            values: dict[str, Any]
            if handler is None:
                status, values = ABORTED, {"error_string": f"no action server {goal.action}"}
            else:
                self._reply(goal, {"op": "action_feedback", "id": goal.id,
                                   "action": goal.action,
                                   "values": {"joint_names": list(self.joint_names),
                                              "actual": {"positions": list(
                                                  self.scene.arm_positions())}}})
                try:
                    status, values = handler(goal)
                except MotionCancelledError:
                    status, values = CANCELED, {"error_code": 0, "error_string": "canceled"}
            self._active.pop(goal.id, None)
            self._reply(goal, {"op": "action_result", "id": goal.id, "action": goal.action,
                               "values": values, "status": status,
                               "result": status == SUCCEEDED})

    def _follow(self, goal: _Goal) -> tuple[int, dict[str, Any]]:
        trajectory = goal.args.get("trajectory", {})
        names = list(trajectory.get("joint_names", []))
        if sorted(names) != sorted(self.joint_names):
            return ABORTED, {"error_code": -2, "error_string": f"joint names {names} do not "
                                                               f"match {list(self.joint_names)}"}
        order = [names.index(n) for n in self.joint_names]
        times, positions = [0.0], [self.scene.arm_positions()]
        for point in trajectory.get("points", []):
            stamp = point["time_from_start"]
            times.append(stamp["sec"] + stamp["nanosec"] * 1e-9)
            positions.append(tuple(point["positions"][k] for k in order))
        self.scene.follow(JointTrajectory(tuple(times), tuple(positions)), goal.cancel)
        return SUCCEEDED, {"error_code": 0, "error_string": ""}

    def _grip(self, goal: _Goal) -> tuple[int, dict[str, Any]]:
        command = goal.args.get("command", {})
        target = float(command.get("position", 0.0))
        self.scene.grip(target, float(command.get("max_effort", 20.0)), goal.cancel)
        reached = self.scene.finger_positions()[0]
        stalled = abs(reached - target) > 0.002
        return (ABORTED if stalled else SUCCEEDED), {
            "position": reached, "effort": 0.0, "stalled": stalled,
            "reached_goal": not stalled}
