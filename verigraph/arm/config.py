"""The arm configuration file (YAML or JSON): driver, host, workspace, limits, mode.

Limits are validated when the file is read, so a configuration that could never move
safely (home outside the workspace, a speed above its own cap, `real` without an
audit log) is rejected up front with the field and the fix.
"""

from __future__ import annotations

import json
import os
from dataclasses import dataclass
from pathlib import Path
from typing import Any, Literal, get_args

import yaml
from pydantic import BaseModel, ConfigDict, Field, ValidationError, model_validator

from verigraph.arm.errors import ArmConfigError
from verigraph.arm.geometry import Box, KeepOutZone, Point
from verigraph.arm.locators import DeclaredObject
from verigraph.arm.models import Pose, RunMode

DriverName = Literal["pybullet", "rosbridge", "xarm"]
DRIVER_NAMES: tuple[str, ...] = get_args(DriverName)
PANDA_JOINTS = tuple(f"panda_joint{i}" for i in range(1, 8))
TABLE_Z_M = 0.0  # the arm's base stands on the table: its surface is z = 0


@dataclass(frozen=True)
class HardLimits:
    """What no configuration of a driver may exceed (see docs/arm.md for the sources)."""

    reach_m: float  # |x|, |y| of the workspace; its top is at most reach + base height
    base_height_m: float
    max_speed_m_s: float
    max_force_n: float


# Franka Panda: 855 mm reach, shoulder at 333 mm, Cartesian speed limit 1.7 m/s, hand
# continuous force 70 N. xArm family: the largest (xArm 850) reaches 850 mm, base
# 267 mm, TCP speed up to 1 m/s; the adapter allows its grippers at most 50 N.
HARD_LIMITS = {"pybullet": HardLimits(0.855, 0.333, 1.7, 70.0),
               "rosbridge": HardLimits(0.855, 0.333, 1.7, 70.0),
               "xarm": HardLimits(0.85, 0.267, 1.0, 50.0)}


class CameraView(BaseModel):
    """One simulated camera: where it is, where it looks, its image size."""

    model_config = ConfigDict(extra="forbid")

    eye: Point
    target: Point = (0.45, 0.0, 0.05)
    fov_deg: float = Field(default=50.0, gt=10, lt=120)
    width: int = Field(default=400, ge=64, le=1920)
    height: int = Field(default=300, ge=48, le=1080)


class PyBulletOptions(BaseModel):
    """The simulated Panda: physics pacing and the cameras that serve as locator.

    Two oblique cameras from either front corner: together they see three sides of
    every box, so even a covered block shows its whole footprint.
    """

    model_config = ConfigDict(extra="forbid")

    real_time_factor: float | None = Field(
        default=None, gt=0, description="None: as fast as possible; 1.0: wall-clock pace")
    time_step_s: float = Field(default=1 / 240, gt=0, le=0.01)
    cameras: list[CameraView] = Field(
        default_factory=lambda: [CameraView(eye=(1.1, 0.5, 0.75)),
                                 CameraView(eye=(1.1, -0.5, 0.75))], min_length=1)


class RosbridgeOptions(BaseModel):
    """ROS 2 through rosbridge: action names, joint names and the kinematic model for IK."""

    model_config = ConfigDict(extra="forbid")

    port: int = Field(default=9090, ge=1, le=65535)
    trajectory_action: str = "/panda_arm_controller/follow_joint_trajectory"
    trajectory_action_type: str = "control_msgs/action/FollowJointTrajectory"
    gripper_action: str = "/panda_hand_controller/gripper_cmd"
    gripper_action_type: str = "control_msgs/action/GripperCommand"
    joint_states_topic: str = "/joint_states"
    joint_names: tuple[str, ...] = PANDA_JOINTS
    urdf: str = Field(default="franka_panda/panda.urdf",
                      description="kinematic model for IK: a pybullet_data path or a file")
    tcp_link: str = "panda_grasptarget"
    waypoint_spacing_m: float = Field(default=0.01, gt=0, le=0.1)
    simulated_backend: bool = Field(
        default=False, description="true only if the ROS side is a simulator (mode sim)")


class XArmOptions(BaseModel):
    """UFACTORY xArm / Lite6 through xarm-python-sdk."""

    model_config = ConfigDict(extra="forbid")

    gripper: Literal["xarm", "lite6", "none"] = "xarm"
    gripper_open_pulse: int = Field(default=850, ge=0, le=1000)
    gripper_max_width_m: float = Field(default=0.086, gt=0)
    set_reduced_boundary: bool = Field(
        default=True, description="also program the workspace box as the controller's "
                                  "reduced-mode TCP boundary")
    roll_deg: float = 180.0
    pitch_deg: float = 0.0
    acceleration_mm_s2: float = Field(default=500.0, gt=0)


class ArmConfig(BaseModel):
    """Everything the adapter needs to drive one arm safely.

    Every number is finite and bounded: the workspace lies in the arm's reach and above
    the table, speed and force stay under the driver's hard maxima (HARD_LIMITS), ages
    and timeouts are bounded. Each rejection names the field and the allowed range.
    """

    model_config = ConfigDict(extra="forbid", allow_inf_nan=False)

    driver: DriverName
    mode: RunMode = Field(default="dry-run", description="dry-run moves nothing")
    host: str | None = Field(default=None, description="controller address (rosbridge, xarm)")
    connect_timeout_s: float = Field(default=5.0, gt=0, le=60)
    motion_timeout_s: float = Field(default=30.0, gt=0, le=600,
                                    description="per pick or place; on expiry stop + latch")
    confirm_timeout_s: float = Field(default=120.0, gt=0, le=600)
    max_location_age_s: float = Field(default=2.0, gt=0, le=10)
    workspace: Box = Box(min=(0.2, -0.45, 0.01), max=(0.8, 0.45, 0.65))
    keep_out: list[KeepOutZone] = Field(default_factory=list)
    speed_m_s: float = Field(default=0.2, gt=0)
    max_speed_m_s: float = Field(default=0.25, gt=0)
    grip_force_n: float = Field(default=20.0, gt=0)
    max_force_n: float = Field(default=40.0, gt=0)
    gripper_max_width_m: float = Field(default=0.08, gt=0, le=0.3)
    approach_height_m: float = Field(default=0.10, gt=0, le=0.5)
    clearance_m: float = Field(default=0.005, ge=0, le=0.05)
    max_grasp_depth_m: float = Field(default=0.03, gt=0, le=0.2,
                                     description="how far below an object's top to grasp")
    tool_margin_m: float = Field(default=0.01, ge=0, le=0.2,
                                 description="keep-out zones are grown by this much")
    home: Pose = Pose(x=0.35, y=0.0, z=0.45)
    agent_may_reset: bool = Field(
        default=False, description="sim/dry-run: let the agent's arm_reset clear a stop "
                                   "(real mode always asks the user)")
    deadman_s: float | None = Field(
        default=None, gt=0, le=60, description="stop a motion when no tool call arrives "
                                               "for this long (None: no heartbeat needed)")
    unsafe_disable_controller_fence: bool = Field(
        default=False, description="real mode: allow xarm.set_reduced_boundary: false, "
                                   "which leaves the controller's own fence off")
    audit_log: Path | None = Field(default=None, description="JSON-lines file, appended to")
    layout: dict[str, DeclaredObject] = Field(
        default_factory=dict,
        description="object id -> measured box, the locator for drivers without a camera "
                    "(rosbridge, xarm); a fixed layout never sees motion")
    pybullet: PyBulletOptions = Field(default_factory=PyBulletOptions)
    rosbridge: RosbridgeOptions = Field(default_factory=RosbridgeOptions)
    xarm: XArmOptions = Field(default_factory=XArmOptions)

    @model_validator(mode="after")
    def _consistent(self) -> ArmConfig:
        """Cross-field rules; each raises ArmConfigError naming the field and the range."""
        self._within_hard_limits()
        if self.speed_m_s > self.max_speed_m_s:
            _reject("speed_m_s", self.speed_m_s, f"speed_m_s ({self.speed_m_s}) exceeds "
                    f"max_speed_m_s ({self.max_speed_m_s})",
                    f"use 0 < speed_m_s <= max_speed_m_s ({self.max_speed_m_s})")
        if self.grip_force_n > self.max_force_n:
            _reject("grip_force_n", self.grip_force_n, f"grip_force_n ({self.grip_force_n}) "
                    f"exceeds max_force_n ({self.max_force_n})",
                    f"use 0 < grip_force_n <= max_force_n ({self.max_force_n})")
        if not self.workspace.contains(self.home.point()):
            _reject("home", self.home.point(), f"home {self.home.text()} is outside the "
                    "workspace", "put home inside the workspace box")
        for zone in self.keep_out:
            if zone.contains(self.home.point()):
                _reject("home", self.home.point(), f"home {self.home.text()} is inside "
                        f"keep-out zone '{zone.name}'", "move home out of the keep-out zones")
        if self.mode == "real":
            self._real_mode_rules()
        if self.mode == "sim" and self.driver == "xarm":
            _reject("mode", self.mode, "mode 'sim' with the xarm driver: it drives hardware",
                    "use mode real (with confirmation) or dry-run")
        if self.mode == "sim" and self.driver == "rosbridge" \
                and not self.rosbridge.simulated_backend:
            _reject("rosbridge.simulated_backend", False, "mode 'sim' with rosbridge needs "
                    "rosbridge.simulated_backend: true (the ROS side must be a simulator)",
                    "set it only if the ROS side is a simulator; else use mode real")
        if self.driver in ("rosbridge", "xarm") and self.mode != "dry-run" and not self.host:
            _reject("host", None, f"the {self.driver} driver needs a host",
                    "give the controller's address, e.g. host: 192.168.1.185")
        return self

    def _within_hard_limits(self) -> None:
        hard = HARD_LIMITS[self.driver]
        reach, top = hard.reach_m, hard.reach_m + hard.base_height_m
        ws = self.workspace
        for corner in (ws.min, ws.max):
            if abs(corner[0]) > reach or abs(corner[1]) > reach:
                _reject("workspace", list(corner), f"the workspace corner {list(corner)} is "
                        f"beyond the {self.driver} arm's reach", f"keep |x| and |y| <= {reach} m")
        if ws.min[2] < TABLE_Z_M:
            _reject("workspace.min", list(ws.min), f"the workspace reaches below the table "
                    f"surface (z {ws.min[2]} < {TABLE_Z_M})", f"use min z >= {TABLE_Z_M} m")
        if ws.max[2] > top:
            _reject("workspace.max", list(ws.max), f"the workspace top z {ws.max[2]} is "
                    f"beyond the {self.driver} arm's reach", f"use max z <= {top:.3f} m")
        if self.max_speed_m_s > hard.max_speed_m_s:
            _reject("max_speed_m_s", self.max_speed_m_s, f"max_speed_m_s {self.max_speed_m_s} "
                    f"is above the {self.driver} hard maximum",
                    f"use 0 < max_speed_m_s <= {hard.max_speed_m_s} m/s")
        if self.max_force_n > hard.max_force_n:
            _reject("max_force_n", self.max_force_n, f"max_force_n {self.max_force_n} is "
                    f"above the {self.driver} hard maximum",
                    f"use 0 < max_force_n <= {hard.max_force_n} N")

    def _real_mode_rules(self) -> None:
        if self.driver == "pybullet":
            _reject("mode", self.mode, "mode 'real' with the pybullet driver: it is a "
                    "simulator", "use mode sim or dry-run")
        if self.audit_log is None:
            _reject("audit_log", None, "mode 'real' needs an audit_log path",
                    "give a writable file path for the audit log")
        _writable_log(self.audit_log)
        if self.agent_may_reset:
            _reject("agent_may_reset", True, "agent_may_reset is for sim and dry-run: a real "
                    "arm's reset is always confirmed by the user", "remove agent_may_reset")
        if self.driver == "xarm" and not self.xarm.set_reduced_boundary \
                and not self.unsafe_disable_controller_fence:
            _reject("xarm.set_reduced_boundary", False, "mode 'real' with the controller's "
                    "own fence off", "keep xarm.set_reduced_boundary: true; only if you must, "
                    "also set unsafe_disable_controller_fence: true")

    def with_overrides(self, **changes: Any) -> ArmConfig:
        """A validated copy with some fields changed (CLI flags, tests)."""
        return parse_arm_config({**self.model_dump(), **changes})


def _reject(field: str, value: object, message: str, fix: str) -> None:
    raise ArmConfigError(f"bad arm config: {message}", field=field, value=value, fix=fix)


def _writable_log(path: Path | None) -> None:
    """A real arm's audit log must be a regular file this process can append to."""
    if path is None:
        return
    if path.exists():
        if not path.is_file():
            _reject("audit_log", str(path), f"the audit log {path} is not a regular file "
                    "(e.g. /dev/null keeps nothing)", "give a regular file path")
        if not os.access(path, os.W_OK):
            _reject("audit_log", str(path), f"the audit log {path} is not writable",
                    "fix its permissions or choose another path")
        return
    parent = path.parent
    while not parent.exists() and parent != parent.parent:
        parent = parent.parent
    if not parent.is_dir() or not os.access(parent, os.W_OK):
        _reject("audit_log", str(path), f"the audit log {path} cannot be created "
                f"({parent} is not a writable directory)", "choose a writable directory")


_FIXES = {
    "driver": f"use one of {', '.join(DRIVER_NAMES)}",
    "mode": "use dry-run (default, moves nothing), sim or real",
    "workspace": "give min and max corners as [x, y, z] in metres with min < max",
    "keep_out": "give each zone a name and min/max corners in metres",
    "host": "give the controller's address, e.g. host: 192.168.1.185",
    "layout": "give each object id a centre [x, y, z] and size [along, across, height] "
              "in metres",
}


def parse_arm_config(data: object) -> ArmConfig:
    """Validate a mapping into an ArmConfig; errors name the field and the fix."""
    try:
        return ArmConfig.model_validate(data)
    except ValidationError as exc:
        err = exc.errors()[0]
        loc = ".".join(str(p) for p in err["loc"]) or "config"
        top = str(err["loc"][0]) if err["loc"] else ""
        raise ArmConfigError(
            f"bad arm config: {err['msg']}", field=loc, value=err.get("input"),
            fix=_FIXES.get(top, "see the arm configuration reference in the README")
        ) from None


def load_arm_config(path: str | Path) -> ArmConfig:
    """Read an arm configuration from a .yaml/.yml or .json file."""
    p = Path(path)
    try:
        text = p.read_text(encoding="utf-8")
    except OSError as exc:
        raise ArmConfigError(f"cannot read arm config: {exc.strerror}", field="arm config",
                             value=str(p), fix="give the path of an existing YAML or JSON "
                                               "file") from None
    try:
        data = json.loads(text) if p.suffix == ".json" else yaml.safe_load(text)
    except (json.JSONDecodeError, yaml.YAMLError) as exc:
        raise ArmConfigError(f"arm config is not valid {p.suffix.lstrip('.') or 'YAML'}: "
                             f"{exc}", field="arm config", value=str(p),
                             fix="fix the syntax at the position shown") from None
    return parse_arm_config(data)


def driver_from_executor(executor: str) -> str:
    """`arm:pybullet` -> `pybullet`; anything else is an error naming the known drivers."""
    prefix, _, name = executor.partition(":")
    if prefix != "arm" or name not in DRIVER_NAMES:
        raise ArmConfigError(f"unknown arm executor '{executor}'", field="executor",
                             value=executor,
                             fix="use " + ", ".join(f"arm:{n}" for n in DRIVER_NAMES))
    return name
