"""Pydantic models at the arm boundary: poses, grasps, placements, locations, status.

Poses are metric, in the robot base frame, for a top-down gripper: position of the
tool centre point (between the fingertips) and a yaw about the vertical axis. A
parallel gripper is symmetric under a half turn, so yaw is kept in (-pi/2, pi/2].
"""

from __future__ import annotations

import math
from typing import Literal

from pydantic import BaseModel, ConfigDict, Field, computed_field, field_validator

from verigraph.arm.geometry import Point, wrap_angle

RunMode = Literal["dry-run", "sim", "real"]
AuditOutcome = Literal["sent", "done", "recorded", "refused", "declined", "failed", "timeout",
                       "cancelled"]


class Pose(BaseModel):
    """Tool centre point (metres) and yaw (radians) of a top-down gripper."""

    model_config = ConfigDict(extra="forbid", frozen=True, allow_inf_nan=False)

    x: float
    y: float
    z: float
    yaw: float = 0.0

    @field_validator("yaw")
    @classmethod
    def _half_turn(cls, v: float) -> float:
        v = wrap_angle(v)
        if v <= -math.pi / 2:
            v += math.pi
        elif v > math.pi / 2:
            v -= math.pi
        return v

    def point(self) -> Point:
        return (self.x, self.y, self.z)

    def text(self) -> str:
        return f"({self.x:.3f}, {self.y:.3f}, {self.z:.3f}) m, yaw {math.degrees(self.yaw):.0f} deg"


class Grasp(BaseModel):
    """How to pick one object: open, approach above, descend, close, lift."""

    model_config = ConfigDict(extra="forbid", frozen=True)

    object_id: str
    approach: Pose
    grasp: Pose
    lift: Pose
    open_width_m: float = Field(gt=0, description="finger opening before descending")
    object_width_m: float = Field(gt=0, description="object extent across the fingers")
    force_n: float = Field(gt=0, description="grip force")
    speed_m_s: float = Field(gt=0, description="tool speed for every segment")

    def waypoints(self) -> list[Pose]:
        return [self.approach, self.grasp, self.lift]


class Placement(BaseModel):
    """How to put the held object down: approach above, descend, open, retreat."""

    model_config = ConfigDict(extra="forbid", frozen=True)

    object_id: str
    relation: str
    target_id: str
    approach: Pose
    release: Pose
    retreat: Pose
    open_width_m: float = Field(gt=0)
    speed_m_s: float = Field(gt=0)

    def waypoints(self) -> list[Pose]:
        return [self.approach, self.release, self.retreat]


class ObjectLocation(BaseModel):
    """Where a locator saw an object: centre, size, yaw and when it looked."""

    model_config = ConfigDict(extra="forbid", frozen=True)

    object_id: str
    centre: Point = Field(description="centre of the object's bounding box, metres")
    size: Point = Field(description="extent along yaw, across yaw, and height, metres")
    yaw: float = Field(default=0.0, description="rotation of the footprint about z, radians")
    timestamp: float = Field(description="time.time() when the measurement was taken")
    source: str = Field(default="unknown", description="which locator measured it")

    @computed_field  # type: ignore[prop-decorator]
    @property
    def top_z(self) -> float:
        return self.centre[2] + self.size[2] / 2

    @property
    def bottom_z(self) -> float:
        return self.centre[2] - self.size[2] / 2

    def footprint_contains(self, x: float, y: float, margin: float = 0.0) -> bool:
        """True if (x, y) lies in the rotated footprint grown by `margin`."""
        dx, dy = x - self.centre[0], y - self.centre[1]
        c, s = math.cos(self.yaw), math.sin(self.yaw)
        along, across = c * dx + s * dy, -s * dx + c * dy
        return (abs(along) <= self.size[0] / 2 + margin
                and abs(across) <= self.size[1] / 2 + margin)

    def age(self, now: float) -> float:
        return now - self.timestamp


class DriverStatus(BaseModel):
    """What a driver reports about itself."""

    connected: bool
    tcp: Pose | None = None
    gripper_width_m: float | None = None
    moving: bool = False
    error: str | None = None


class ArmStatus(BaseModel):
    """The adapter's state, as the `arm_status` tool reports it."""

    driver: str
    mode: RunMode
    host: str | None
    connected: bool
    stop_latched: bool
    stop_reason: str | None = None
    busy: bool
    tcp: Pose | None = None
    last_outcome: str | None = Field(default=None, description="outcome of the last motion")
    last_error: str | None = None
    commands_sent: int = Field(description="commands sent to the driver so far")
    audit_log: str | None = Field(default=None, description="path of the JSON-lines audit log")

    def summary(self) -> str:
        state = "STOP LATCHED" + (f" ({self.stop_reason})" if self.stop_reason else "") \
            if self.stop_latched else ("busy" if self.busy else "idle")
        link = "connected" if self.connected else "not connected"
        return f"arm {self.driver} [{self.mode}] {link}, {state}; " \
               f"{self.commands_sent} commands sent"


class AuditRecord(BaseModel):
    """One line of the audit log: an event, what was asked, what came of it, and who.

    `seq`, `time`, `pid`, `prev` and `hash` are filled in by `AuditLog.record`.
    """

    seq: int = 0
    time: float = 0.0
    mode: RunMode
    driver: str
    command: str
    params: dict[str, object] = Field(default_factory=dict)
    outcome: AuditOutcome
    detail: str | None = None
    episode_id: str | None = None
    client: str | None = Field(default=None, description="the MCP client/session that asked")
    pid: int | None = None
    question: str | None = Field(default=None, description="the text shown to the human")
    prev: str | None = Field(default=None, description="hash of the previous record")
    hash: str | None = Field(default=None, description="SHA-256 of this record without it")


class ConfirmationRequest(BaseModel):
    """What a human is asked to approve before a real motion."""

    driver: str
    host: str | None
    motion: str = Field(description="what will happen, e.g. move(red, on, blue): pick ...")
    waypoints: list[Pose] = Field(description="every waypoint of the motion, in order")
    speed_m_s: float
    force_n: float | None = None

    def summary(self) -> str:
        where = f" at {self.host}" if self.host else ""
        grip = f", grip {self.force_n:.0f} N" if self.force_n is not None else ""
        return (f"Move the real arm ({self.driver}{where}): {self.motion}; "
                f"{len(self.waypoints)} waypoints at {self.speed_m_s:.2f} m/s{grip}. Approve?")
