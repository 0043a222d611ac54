"""The `pybullet` driver: a simulated Franka Panda in a PandaScene.

Each pick or place is planned as straight tool lines (IK every centimetre) before
the first joint moves, then tracked by the physics with position control; the
gripper grasps by friction, so a bad grasp really drops the block.
"""

from __future__ import annotations

import threading

from verigraph.arm.drivers.sequence import GripStep, Step, home_steps, pick_steps, place_steps
from verigraph.arm.errors import MotionCancelledError
from verigraph.arm.models import DriverStatus, Grasp, Placement, Pose
from verigraph.arm.sim.kinematics import Kinematics
from verigraph.arm.sim.panda_scene import PandaScene


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
        self._run(home_steps(self._kinematics, self.scene.arm_positions(), pose, speed_m_s))

    def pick(self, grasp: Grasp) -> None:
        self._run(pick_steps(self._kinematics, self.scene.arm_positions(), grasp))

    def place(self, placement: Placement) -> None:
        self._run(place_steps(self._kinematics, self.scene.arm_positions(), placement))
        self.scene.settle(0.2)

    def stop(self) -> None:
        self._cancel.set()

    def reset(self) -> None:
        self._cancel.clear()

    def disconnect(self) -> None:
        self._connected = False
        self.close()

    def close(self) -> None:
        """Release the driver's own IK client (idempotent).

        Called when the world closes whether or not the driver was ever connected: a
        dry run never connects, and its IK client would otherwise stay in the process.
        """
        self._kinematics.close()

    def _run(self, steps: list[Step]) -> None:
        if self._cancel.is_set():
            raise MotionCancelledError("the pybullet driver is stopped; reset it first")
        self._moving = True
        try:
            for step in steps:
                if isinstance(step, GripStep):
                    self.scene.grip(step.width_m / 2, step.force_n, self._cancel)
                else:
                    self.scene.follow(step, self._cancel)
        finally:
            self._moving = False
