"""The `rosbridge` driver: ROS 2 through rosbridge, with roslibpy (pure Python).

Motions become `control_msgs/action/FollowJointTrajectory` goals (straight tool lines
turned into joint trajectories by a local kinematic model of the arm, before the first
goal is sent) and `control_msgs/action/GripperCommand` goals; `stop` cancels every
active goal. Current joints come from `sensor_msgs/msg/JointState`.
"""

from __future__ import annotations

import math
import threading
from typing import Any

import roslibpy

from verigraph.arm.config import ArmConfig
from verigraph.arm.drivers.sequence import GripStep, Step, home_steps, pick_steps, place_steps
from verigraph.arm.errors import ArmConnectionError, ArmMotionError, MotionCancelledError
from verigraph.arm.models import DriverStatus, Grasp, Placement, Pose
from verigraph.arm.sim.kinematics import JointTrajectory, Kinematics

SUCCEEDED, ABORTED = 4, 6
CANCEL_GRACE_S = 2.0


def _duration(seconds: float) -> dict[str, int]:
    whole = math.floor(seconds)
    return {"sec": whole, "nanosec": round((seconds - whole) * 1e9)}


class RosbridgeDriver:
    """ArmDriver over rosbridge: trajectory and gripper action goals, cancel on stop."""

    name = "rosbridge"

    def __init__(self, config: ArmConfig) -> None:
        self.options = config.rosbridge
        self.host = config.host or "127.0.0.1"
        self.simulated = config.rosbridge.simulated_backend
        self._ros: Any = None
        self._kinematics: Kinematics | None = None
        self._joint_state: dict[str, float] = {}
        self._first_state = threading.Event()
        self._cancel = threading.Event()
        self._lock = threading.Lock()
        self._active: dict[str, Any] = {}  # goal id -> its ActionClient
        self._moving = False

    # -- connection ------------------------------------------------------------------------
    def connect(self, timeout_s: float) -> None:
        o = self.options
        # The kinematic model first: a joint name it lacks is a config error, found now.
        self._kinematics = Kinematics(o.urdf, o.tcp_link, o.joint_names)
        ros = roslibpy.Ros(host=self.host, port=o.port)
        try:
            ros.run(timeout=timeout_s)
        except Exception:
            self._abandon(ros)
            self.disconnect()
            raise ArmConnectionError(
                f"no rosbridge server answered at ws://{self.host}:{o.port} within "
                f"{timeout_s} s", field="host", value=f"{self.host}:{o.port}",
                fix="start rosbridge_server (ros2 launch rosbridge_server "
                    "rosbridge_websocket_launch.xml) and check host and rosbridge.port") from None
        self._ros = ros
        self._topic = roslibpy.Topic(ros, o.joint_states_topic, "sensor_msgs/msg/JointState")
        self._topic.subscribe(self._on_joint_state)
        if not self._first_state.wait(timeout_s):
            seen = sorted(self._joint_state)
            self.disconnect()
            if seen:
                raise ArmConnectionError(
                    f"joint states on {o.joint_states_topic} name {seen}, not all of "
                    f"{list(o.joint_names)}", field="rosbridge.joint_names",
                    value=list(o.joint_names), fix="set rosbridge.joint_names to the robot's")
            raise ArmConnectionError(
                f"no joint states on {o.joint_states_topic} within {timeout_s} s",
                field="rosbridge.joint_states_topic", value=o.joint_states_topic,
                fix="check that the robot's joint_state_broadcaster runs and the topic name")
        self._trajectory = roslibpy.ActionClient(ros, o.trajectory_action,
                                                 o.trajectory_action_type)
        self._gripper = roslibpy.ActionClient(ros, o.gripper_action, o.gripper_action_type)

    @staticmethod
    def _abandon(ros: Any) -> None:
        """Stop roslibpy from retrying a connection that failed."""
        stop_trying = getattr(ros.factory, "stopTrying", None)
        if stop_trying is not None:
            ros.call_later(0, stop_trying)

    def disconnect(self) -> None:
        if self._ros is not None:
            self._topic.unsubscribe()
            self._ros.close()
            self._ros = None
        if self._kinematics is not None:
            self._kinematics.close()
            self._kinematics = None

    def _on_joint_state(self, message: dict[str, Any]) -> None:
        self._joint_state = dict(zip(message.get("name", []), message.get("position", []),
                                     strict=False))
        if all(n in self._joint_state for n in self.options.joint_names):
            self._first_state.set()

    def _arm_positions(self) -> tuple[float, ...]:
        state = self._joint_state
        return tuple(state[n] for n in self.options.joint_names)

    # -- ArmDriver -------------------------------------------------------------------------
    def status(self) -> DriverStatus:
        connected = self._ros is not None and bool(self._ros.is_connected)
        tcp = None
        if connected and self._kinematics is not None and self._first_state.is_set():
            tcp = self._kinematics.fk(self._arm_positions())
        fingers = [v for k, v in self._joint_state.items() if "finger" in k]
        return DriverStatus(connected=connected, tcp=tcp, moving=self._moving,
                            gripper_width_m=sum(fingers) if fingers else None,
                            error="stopped" if self._cancel.is_set() else None)

    def home(self, pose: Pose, speed_m_s: float) -> None:
        self._run(home_steps(self._model(), self._arm_positions(), pose, speed_m_s,
                             self.options.waypoint_spacing_m))

    def pick(self, grasp: Grasp) -> None:
        self._run(pick_steps(self._model(), self._arm_positions(), grasp,
                             self.options.waypoint_spacing_m))

    def place(self, placement: Placement) -> None:
        self._run(place_steps(self._model(), self._arm_positions(), placement,
                              self.options.waypoint_spacing_m))

    def stop(self) -> None:
        self._cancel.set()
        with self._lock:
            active = list(self._active.items())
        for goal_id, client in active:
            client.cancel_goal(goal_id)

    def reset(self) -> None:
        self._cancel.clear()

    # -- internals -------------------------------------------------------------------------
    def _model(self) -> Kinematics:
        if self._kinematics is None:
            raise ArmMotionError("the rosbridge driver is not connected", field="connected",
                                 fix="connect first")
        return self._kinematics

    def _run(self, steps: list[Step]) -> None:
        self._moving = True
        try:
            for step in steps:
                if isinstance(step, GripStep):
                    # GripperCommand.position is the finger joint's position: half the gap.
                    self._send(self._gripper, {"command": {"position": step.width_m / 2,
                                                           "max_effort": step.force_n}},
                               "gripper")
                else:
                    self._send(self._trajectory, self._trajectory_goal(step), "trajectory")
        finally:
            self._moving = False

    def _trajectory_goal(self, trajectory: JointTrajectory) -> dict[str, Any]:
        points = [{"positions": list(q), "velocities": [], "accelerations": [], "effort": [],
                   "time_from_start": _duration(t)}
                  for t, q in zip(trajectory.times, trajectory.positions, strict=True) if t > 0]
        return {"trajectory": {"header": {"stamp": {"sec": 0, "nanosec": 0}, "frame_id": ""},
                               "joint_names": list(self.options.joint_names), "points": points},
                "goal_time_tolerance": _duration(0.5)}

    def _send(self, client: Any, goal: dict[str, Any], what: str) -> None:
        """Send one action goal and wait for its result; cancel it if the stop comes."""
        if self._cancel.is_set():
            raise MotionCancelledError(f"the {what} goal was not sent: the driver is stopped")
        done = threading.Event()
        outcome: dict[str, Any] = {}

        def finished(result: Any) -> None:
            outcome.update(dict(result))
            done.set()

        goal_id = client.send_goal(roslibpy.Goal(goal), finished, lambda _fb: None, finished)
        with self._lock:
            self._active[goal_id] = client
        try:
            while not done.wait(0.02):
                if self._cancel.is_set():
                    client.cancel_goal(goal_id)
                    done.wait(CANCEL_GRACE_S)
                    raise MotionCancelledError(f"the {what} goal was cancelled")
                if self._ros is None or not self._ros.is_connected:
                    raise ArmMotionError(f"rosbridge connection lost during the {what} goal",
                                         field="host", value=self.host,
                                         fix="check the network and the rosbridge server")
        finally:
            with self._lock:
                self._active.pop(goal_id, None)
        status = getattr(outcome.get("status"), "value", outcome.get("status"))
        values = outcome.get("values") or {}
        if self._cancel.is_set():
            raise MotionCancelledError(f"the {what} goal was cancelled")
        stalled_grip = what == "gripper" and status == ABORTED and values.get("stalled")
        if status != SUCCEEDED and not stalled_grip:
            raise ArmMotionError(f"the {what} goal ended with status {status}: {values}",
                                 field=what, value=status,
                                 fix="check the controller's log; the arm stopped here")
