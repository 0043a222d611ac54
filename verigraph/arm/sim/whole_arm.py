"""Whole-arm geometry: every link, the hand, the fingers and the held object, checked
along the planned path against the keep-out zones, the table and the workspace.

The tool-centre checks (verigraph.arm.safety) see a point; an elbow or a hand can still
reach into a zone the tool never touches. So before any motion, the path is sampled
every SAMPLE_SPACING_M along each straight tool segment, solved to joint positions with
the robot's URDF in a private PyBullet DIRECT client (IK seeded from the previous
sample, as the drivers do), and at every sample:

- every moving link (all but the base links) must keep `tool_margin_m` from every
  keep-out zone (exact convex distance, `getClosestPoints`) and stay above the table;
- the hand and the fingers must also stay within the workspace footprint in x and y
  (their axis-aligned bounding boxes; the tool centre alone is held under its top, as
  the gripper body stands above the tool);
- the held object (its box, yaw taken as the worst case) must keep the margin from
  every zone, stay above the table and within the workspace footprint.

This runs for every driver: the model is the Panda for pybullet and rosbridge (or the
rosbridge config's URDF) and the xArm 6 with its gripper for xarm. For an xArm the
controller's own inverse kinematics decides the real joint path of a linear move; the
model's solution from the same start is the check's estimate of it.
"""

from __future__ import annotations

import math
import threading
from dataclasses import dataclass

import pybullet as pb

from verigraph.arm.config import TABLE_Z_M, ArmConfig
from verigraph.arm.errors import UnsafeMotionError
from verigraph.arm.geometry import Box, lerp
from verigraph.arm.models import Pose
from verigraph.arm.planning import PathSegment
from verigraph.arm.sim.kinematics import PANDA_REST, Kinematics

SAMPLE_SPACING_M = 0.02
TABLE_TOLERANCE_M = 0.002


@dataclass(frozen=True)
class ArmModel:
    """The URDF the check solves, and which of its links play which part."""

    urdf: str
    ik_link: str  # solved for; sits `tcp_offset_m` above the tool centre (tool down)
    tcp_offset_m: float
    joints: tuple[str, ...]
    rest: tuple[float, ...]
    base_links: tuple[str, ...]  # fixed to the base: never checked
    hand_links: tuple[str, ...]  # also kept inside the workspace footprint


PANDA = ArmModel("franka_panda/panda.urdf", "panda_grasptarget", 0.0,
                 tuple(f"panda_joint{i}" for i in range(1, 8)), PANDA_REST,
                 ("panda_link0", "panda_link1"),
                 ("panda_hand", "panda_leftfinger", "panda_rightfinger"))
XARM6 = ArmModel("xarm/xarm6_with_gripper.urdf", "link6", 0.172,
                 tuple(f"joint{i}" for i in range(1, 7)), (0.0, -0.5, -0.5, 0.0, 1.0, 0.0),
                 ("link_base", "link1"),
                 ("xarm_gripper_base_link", "left_outer_knuckle", "left_finger",
                  "left_inner_knuckle", "right_outer_knuckle", "right_finger",
                  "right_inner_knuckle"))


def model_for(config: ArmConfig) -> ArmModel:
    if config.driver == "xarm":
        return XARM6
    if config.driver == "rosbridge":
        o = config.rosbridge
        return ArmModel(o.urdf, o.tcp_link, 0.0, o.joint_names, PANDA.rest[:len(o.joint_names)],
                        PANDA.base_links, PANDA.hand_links)
    return PANDA


class WholeArmCheck:
    """Checks planned tool paths with the whole arm; one private DIRECT client."""

    def __init__(self, config: ArmConfig, model: ArmModel | None = None) -> None:
        self.config = config
        self.model = model or model_for(config)
        self._kin = Kinematics(self.model.urdf, self.model.ik_link, self.model.joints)
        self._lock = threading.Lock()
        c, robot = self._kin.client, self._kin.robot
        try:
            names = {pb.getJointInfo(robot, j, physicsClientId=c)[12].decode(): j
                     for j in range(pb.getNumJoints(robot, physicsClientId=c))}
            self._links = {n: i for n, i in names.items() if n not in self.model.base_links
                           and pb.getCollisionShapeData(robot, i, physicsClientId=c)}
            self._hand = {n for n in self.model.hand_links if n in self._links}
            self._zones = {zone.name: (zone, _box_body(c, zone)) for zone in config.keep_out}
        except BaseException:
            self._kin.close()
            raise

    def close(self) -> None:
        self._kin.close()

    def check(self, segments: list[PathSegment]) -> None:
        """Raise UnsafeMotionError naming link, zone and waypoint for the first breach."""
        if not segments:
            return
        with self._lock:
            q = self._kin.ik(self._ik_pose(segments[0].start), self.model.rest)
            for seg in segments:
                steps = max(1, math.ceil(math.dist(seg.start.point(), seg.end.point())
                                         / SAMPLE_SPACING_M))
                turn = math.remainder(seg.end.yaw - seg.start.yaw, math.pi)
                for k in range(1, steps + 1):
                    t = k / steps
                    x, y, z = lerp(seg.start.point(), seg.end.point(), t)
                    tool = Pose(x=x, y=y, z=z, yaw=seg.start.yaw + turn * t)
                    q = self._kin.ik(self._ik_pose(tool), q)
                    self._kin.set_joints(q)
                    self._check_links(seg, tool, k, steps)
                    if seg.carrying is not None:
                        self._check_held(seg, tool, k, steps)

    def _ik_pose(self, tool: Pose) -> Pose:
        return tool.model_copy(update={"z": tool.z + self.model.tcp_offset_m})

    def _check_links(self, seg: PathSegment, tool: Pose, k: int, steps: int) -> None:
        c, robot, margin = self._kin.client, self._kin.robot, self.config.tool_margin_m
        ws = self.config.workspace
        for name, link in self._links.items():
            for zone, body in self._zones.values():
                if pb.getClosestPoints(robot, body, margin, linkIndexA=link,
                                       physicsClientId=c):
                    _refuse(f"the arm's {name} would come within {margin} m of keep-out "
                            f"zone '{zone.name}'", seg, tool, k, steps, "keep_out", zone.name)
            lo, hi = pb.getAABB(robot, link, physicsClientId=c)
            if lo[2] < TABLE_Z_M - TABLE_TOLERANCE_M and name not in self._hand:
                _refuse(f"the arm's {name} would go below the table (z {lo[2]:.3f} m)", seg,
                        tool, k, steps, "workspace", name)
            if name in self._hand and not _inside_footprint(ws, lo, hi):
                _refuse(f"the arm's {name} would leave the workspace "
                        f"(its box {_fmt(lo)} .. {_fmt(hi)})", seg, tool, k, steps,
                        "workspace", name)

    def _check_held(self, seg: PathSegment, tool: Pose, k: int, steps: int) -> None:
        held = seg.carrying
        assert held is not None
        half = math.hypot(held.size[0], held.size[1]) / 2
        bottom = tool.z - seg.hold_offset
        lo = (tool.x - half, tool.y - half, bottom)
        hi = (tool.x + half, tool.y + half, bottom + held.size[2])
        what = f"the held {held.object_id}"
        if bottom < TABLE_Z_M - TABLE_TOLERANCE_M:
            _refuse(f"{what} would go below the table", seg, tool, k, steps, "workspace",
                    held.object_id)
        if not _inside_footprint(self.config.workspace, lo, hi):
            _refuse(f"{what} would leave the workspace", seg, tool, k, steps, "workspace",
                    held.object_id)
        margin = self.config.tool_margin_m
        for zone, _ in self._zones.values():
            if _overlap(zone.expanded(margin, margin, margin), lo, hi):
                _refuse(f"{what} would come within {margin} m of keep-out zone "
                        f"'{zone.name}'", seg, tool, k, steps, "keep_out", zone.name)


def _box_body(client: int, box: Box) -> int:
    half = [(hi - lo) / 2 for lo, hi in zip(box.min, box.max, strict=True)]
    centre = [(hi + lo) / 2 for lo, hi in zip(box.min, box.max, strict=True)]
    shape = pb.createCollisionShape(pb.GEOM_BOX, halfExtents=half, physicsClientId=client)
    return int(pb.createMultiBody(0, shape, basePosition=centre, physicsClientId=client))


def _overlap(box: Box, lo: tuple[float, ...], hi: tuple[float, ...]) -> bool:
    return all(a <= box.max[i] and b >= box.min[i] for i, (a, b) in enumerate(zip(lo, hi,
                                                                                   strict=True)))


def _inside_footprint(ws: Box, lo: tuple[float, ...], hi: tuple[float, ...]) -> bool:
    return ws.min[0] <= lo[0] and hi[0] <= ws.max[0] and ws.min[1] <= lo[1] \
        and hi[1] <= ws.max[1]


def _fmt(v: tuple[float, ...]) -> str:
    return "[" + ", ".join(f"{x:.3f}" for x in v) + "]"


def _refuse(what: str, seg: PathSegment, tool: Pose, k: int, steps: int, field: str,
            value: str) -> None:
    raise UnsafeMotionError(
        f"{what} at waypoint {k}/{steps} of segment '{seg.label}' (tool at {tool.text()})",
        field=field, value=value,
        fix="choose another target or approach, or move the objects away from the zone; "
            "change the zones only if the cell is really clear there")
