"""The `pybullet` driver: a simulated Franka Panda in a PandaScene.

Each pick or place is planned as straight tool lines (IK every centimetre) before
the first joint moves, then tracked by the physics with position control; the
gripper grasps by friction, so a bad grasp really drops the block.
"""

from __future__ import annotations

import threading

from verigraph.arm.errors import MotionCancelledError
from verigraph.arm.models import DriverStatus, Grasp, Placement, Pose
from verigraph.arm.sim.kinematics import JointTrajectory, Kinematics
from verigraph.arm.sim.panda_scene import PandaScene

OPEN_FORCE_N = 20.0  # opening needs no grip limit; the Panda finger motors allow 20 N


class PyBulletPandaDriver:
    """ArmDriver over a PandaScene (headless physics)."""

    name = "pybullet"
    simulated = True

    def __init__(self, scene: PandaScene, kinematics: Kinematics | None = None) -> None:
        self.scene = scene
        self._kinematics = kinematics or Kinematics()
        self._cancel = threading.Event()
        self._connected = False
        self._moving = False

    def connect(self, timeout_s: float) -> None:
        self._connected = True

    def status(self) -> DriverStatus:
        left, right = self.scene.finger_positions()
        return DriverStatus(connected=self._connected, tcp=self.scene.tcp_pose(),
                            gripper_width_m=left + right, moving=self._moving,
                            error="stopped" if self._cancel.is_set() else None)

    def home(self, pose: Pose, speed_m_s: float) -> None:
        self._run([self._lines([pose], speed_m_s)[0]])

    def pick(self, grasp: Grasp) -> None:
        to_approach, down, lift = self._lines(grasp.waypoints(), grasp.speed_m_s)
        self._run([("grip", grasp.open_width_m, grasp.force_n), to_approach, down,
                   ("grip", 0.0, grasp.force_n), lift])

    def place(self, placement: Placement) -> None:
        to_approach, down, retreat = self._lines(placement.waypoints(), placement.speed_m_s)
        self._run([to_approach, down, ("grip", placement.open_width_m, OPEN_FORCE_N), retreat])
        self.scene.settle(0.2)

    def stop(self) -> None:
        self._cancel.set()

    def reset(self) -> None:
        self._cancel.clear()

    def disconnect(self) -> None:
        self._connected = False
        self._kinematics.close()

    def _lines(self, waypoints: list[Pose], speed: float) -> list[JointTrajectory]:
        """Joint trajectories through `waypoints` from the current pose (all IK up front)."""
        q = self.scene.arm_positions()
        here = self._kinematics.fk(q)
        lines = []
        for target in waypoints:
            line = self._kinematics.line(q, here, target, speed)
            lines.append(line)
            q, here = line.final, target
        return lines

    def _run(self, steps: list[JointTrajectory | tuple[str, float, float]]) -> None:
        if self._cancel.is_set():
            raise MotionCancelledError("the pybullet driver is stopped; reset it first")
        self._moving = True
        try:
            for step in steps:
                if isinstance(step, JointTrajectory):
                    self.scene.follow(step, self._cancel)
                else:
                    _, width, force = step
                    self.scene.grip(width / 2, force, self._cancel)
        finally:
            self._moving = False
