"""Inverse kinematics and straight-line joint trajectories for a URDF arm.

Runs on a private headless PyBullet client holding only the robot model, so any
driver can use it (the simulated Panda, or a real Panda behind ROS 2) without
touching a physics scene. A whole pick or place is turned into joint trajectories
*before* the first joint moves, so an unreachable pose fails without motion.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
import pybullet as pb
import pybullet_data

from verigraph.arm.errors import InfeasibleMotionError
from verigraph.arm.geometry import lerp
from verigraph.arm.models import Pose

PANDA_REST = (0.0, -0.785, 0.0, -2.356, 0.0, 1.571, 0.785)
MAX_YAW_RATE = 1.0  # rad/s, so pure wrist turns take time too
IK_TOLERANCE_M = 0.002


@dataclass(frozen=True, slots=True)
class JointTrajectory:
    """Joint positions at times from the trajectory's start (seconds)."""

    times: tuple[float, ...]
    positions: tuple[tuple[float, ...], ...]

    @property
    def duration(self) -> float:
        return self.times[-1] if self.times else 0.0

    @property
    def final(self) -> tuple[float, ...]:
        return self.positions[-1]


def down_orientation(yaw: float) -> tuple[float, float, float, float]:
    """Quaternion of a top-down tool: z axis pointing down, x axis at `yaw`."""
    x, y, z, w = pb.getQuaternionFromEuler([math.pi, 0.0, yaw])
    return (x, y, z, w)


class Kinematics:
    """IK / FK for one arm model on its own DIRECT client."""

    def __init__(self, urdf: str = "franka_panda/panda.urdf", tcp_link: str = "panda_grasptarget",
                 joint_names: tuple[str, ...] | None = None) -> None:
        self._client = pb.connect(pb.DIRECT)
        try:
            self._load(urdf, tcp_link, joint_names)
        except BaseException:
            pb.disconnect(self._client)  # a refused model keeps no client open
            raise

    def _load(self, urdf: str, tcp_link: str, joint_names: tuple[str, ...] | None) -> None:
        pb.setAdditionalSearchPath(pybullet_data.getDataPath(), physicsClientId=self._client)
        try:
            self._robot = pb.loadURDF(urdf, useFixedBase=True, physicsClientId=self._client)
        except pb.error:
            raise InfeasibleMotionError(f"cannot load the arm model '{urdf}'",
                                        field="rosbridge.urdf", value=urdf,
                                        fix="give a pybullet_data path or a URDF file") from None
        info = [pb.getJointInfo(self._robot, j, physicsClientId=self._client)
                for j in range(pb.getNumJoints(self._robot, physicsClientId=self._client))]
        links = {i[12].decode(): i[0] for i in info}
        if tcp_link not in links:
            raise InfeasibleMotionError(f"the arm model has no link '{tcp_link}'",
                                        field="rosbridge.tcp_link", value=tcp_link,
                                        fix=f"use one of {', '.join(links)}")
        self.tcp = links[tcp_link]
        movable = [i for i in info if i[2] != pb.JOINT_FIXED]
        by_name = {i[1].decode(): i for i in movable}
        names = joint_names or tuple(i[1].decode() for i in movable[:len(PANDA_REST)])
        missing = [n for n in names if n not in by_name]
        if missing:
            raise InfeasibleMotionError(f"the arm model has no joint {missing[0]}",
                                        field="rosbridge.joint_names", value=missing[0],
                                        fix=f"use joint names of the model: {', '.join(by_name)}")
        self.joint_names = names
        self._movable = [i[0] for i in movable]
        self._arm = [by_name[n][0] for n in names]
        self._lower = [i[8] for i in movable]
        self._upper = [i[9] for i in movable]

    @property
    def client(self) -> int:
        """The private PyBullet client holding the model (for geometry queries)."""
        return self._client

    @property
    def robot(self) -> int:
        return self._robot

    def set_joints(self, q: tuple[float, ...] | list[float]) -> None:
        """Put the model at joint positions `q` (arm joints in `joint_names` order)."""
        self._set(q)

    def close(self) -> None:
        if pb.isConnected(self._client):
            pb.disconnect(self._client)

    def _set(self, q: tuple[float, ...] | list[float]) -> None:
        for j, v in zip(self._arm, q, strict=True):
            pb.resetJointState(self._robot, j, v, physicsClientId=self._client)

    def _tcp(self, q: tuple[float, ...] | list[float]) -> tuple[tuple[float, float, float],
                                                                float]:
        """Tool position and full-turn yaw for joint positions `q`."""
        self._set(q)
        state = pb.getLinkState(self._robot, self.tcp, computeForwardKinematics=True,
                                physicsClientId=self._client)
        m = pb.getMatrixFromQuaternion(state[5])
        return state[4], math.atan2(m[3], m[0])

    def fk(self, q: tuple[float, ...] | list[float]) -> Pose:
        """Tool pose for joint positions `q` (arm joints in `joint_names` order)."""
        (x, y, z), yaw = self._tcp(q)
        return Pose(x=x, y=y, z=z, yaw=yaw)

    def ik(self, pose: Pose, seed: tuple[float, ...] | list[float]) -> tuple[float, ...]:
        """Joint positions that put the tool at `pose`, near `seed`; raises if unreachable.

        The gripper is symmetric under a half turn, so the yaw nearest the wrist's
        current one is tried first and the other one only if that fails.
        """
        _, seed_yaw = self._tcp(seed)
        nearest = seed_yaw + math.remainder(pose.yaw - seed_yaw, math.pi)
        best: tuple[float, tuple[float, ...]] | None = None
        for yaw in (nearest, nearest + math.pi):
            q, error = self._solve(pose.point(), yaw, seed)
            if error == 0.0:
                return q
            if best is None or error < best[0]:
                best = (error, q)
        assert best is not None
        raise InfeasibleMotionError(f"the arm cannot reach {pose.text()} (IK error "
                                    f"{best[0] * 1000:.1f} mm)", field="pose",
                                    value=pose.point(),
                                    fix="move the object or target closer to the arm")

    def _solve(self, point: tuple[float, float, float], yaw: float,
               seed: tuple[float, ...] | list[float]) -> tuple[tuple[float, ...], float]:
        """Damped IK from `seed`, clamped to the joint limits; (q, 0.0) on success."""
        q = list(seed)
        orientation = down_orientation(yaw)
        limits = [(self._lower[self._movable.index(j)], self._upper[self._movable.index(j)])
                  for j in self._arm]
        error = math.inf
        for _ in range(30):
            self._set(q)
            full = pb.calculateInverseKinematics(
                self._robot, self.tcp, point, orientation, jointDamping=[0.01] * len(
                    self._movable), maxNumIterations=200, residualThreshold=1e-6,
                physicsClientId=self._client)
            by_joint = dict(zip(self._movable, full, strict=True))
            q = [min(max(by_joint[j], lo + 1e-4), hi - 1e-4)
                 for j, (lo, hi) in zip(self._arm, limits, strict=True)]
            reached, reached_yaw = self._tcp(q)
            error = math.dist(reached, point)
            if error < IK_TOLERANCE_M / 4:
                break
        if error < IK_TOLERANCE_M and abs(math.remainder(reached_yaw - yaw, math.pi)) < 0.05:
            return tuple(q), 0.0
        return tuple(q), max(error, 1e-6)

    def line(self, start_q: tuple[float, ...], start: Pose, end: Pose, speed_m_s: float,
             spacing_m: float = 0.01) -> JointTrajectory:
        """A straight tool line start->end at `speed_m_s`, sampled every `spacing_m`."""
        length = math.dist(start.point(), end.point())
        turn = math.remainder(end.yaw - start.yaw, math.pi)
        n = max(1, math.ceil(length / spacing_m), math.ceil(abs(turn) / 0.05))
        duration = max(length / speed_m_s, abs(turn) / MAX_YAW_RATE, 0.05)
        times, positions = [0.0], [tuple(start_q)]
        q = start_q
        for k in range(1, n + 1):
            t = k / n
            x, y, z = lerp(start.point(), end.point(), t)
            q = self.ik(Pose(x=x, y=y, z=z, yaw=start.yaw + turn * t), q)
            times.append(duration * t)
            positions.append(q)
        return JointTrajectory(tuple(times), tuple(positions))


def sample(trajectory: JointTrajectory, t: float) -> np.ndarray:
    """Joint positions at time `t`, linearly interpolated (clamped at the ends)."""
    times = trajectory.times
    if t <= times[0]:
        return np.asarray(trajectory.positions[0])
    if t >= times[-1]:
        return np.asarray(trajectory.positions[-1])
    k = int(np.searchsorted(times, t))
    a, b = np.asarray(trajectory.positions[k - 1]), np.asarray(trajectory.positions[k])
    w = (t - times[k - 1]) / (times[k] - times[k - 1])
    return np.asarray(a + (b - a) * w)
