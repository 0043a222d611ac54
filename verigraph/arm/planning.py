"""Graph action -> motion: a grasp at the located object, a placement on or in the target.

`on` releases the held object `clearance_m` above the target's top (the tool sits at
the object's grasp height above its bottom, so for a centre grasp that is the
object's half height); `in` lowers it into the container's opening. The arm only
moves sideways at one transit height that clears the tallest located object with the
held one under the tool, and goes straight up and down above the object and target.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from pydantic import BaseModel, ConfigDict, Field

from verigraph.arm.approval import ValidatedAction
from verigraph.arm.config import ArmConfig
from verigraph.arm.errors import InfeasibleMotionError, StaleLocationError
from verigraph.arm.geometry import wrap_angle
from verigraph.arm.models import Grasp, ObjectLocation, Placement, Pose


@dataclass(frozen=True, slots=True)
class PathSegment:
    """One straight tool move; `carrying` is the held object (for keep-out growth)."""

    label: str
    start: Pose
    end: Pose
    carrying: ObjectLocation | None = None
    hold_offset: float = 0.0  # tool height above the held object's bottom


class MotionPlan(BaseModel):
    """A receipt plus the grasp and placement derived from fresh locations."""

    model_config = ConfigDict(frozen=True, arbitrary_types_allowed=True)

    receipt: ValidatedAction
    grasp: Grasp
    placement: Placement
    held: ObjectLocation
    target: ObjectLocation
    rest_z: float = Field(description="height the held object's bottom comes to rest at")

    @property
    def hold_offset(self) -> float:
        return self.grasp.grasp.z - self.held.bottom_z

    def path(self, start: Pose) -> list[PathSegment]:
        """Every straight segment from the current tool pose to the retreat."""
        g, p = self.grasp, self.placement
        held, off = self.held, self.hold_offset
        return [PathSegment("to pick approach", start, g.approach),
                PathSegment("descend to grasp", g.approach, g.grasp),
                PathSegment("lift", g.grasp, g.lift, held, off),
                PathSegment("transit", g.lift, p.approach, held, off),
                PathSegment("descend to release", p.approach, p.release, held, off),
                PathSegment("retreat", p.release, p.retreat)]

    def predicted_location(self, now: float) -> ObjectLocation:
        """Where the held object ends if the placement goes exactly as commanded."""
        r = self.placement.release
        turn = r.yaw - self.grasp.grasp.yaw
        return ObjectLocation(object_id=self.held.object_id,
                              centre=(r.x, r.y, self.rest_z + self.held.size[2] / 2),
                              size=self.held.size, yaw=wrap_angle(self.held.yaw + turn),
                              timestamp=now, source="commanded (dry-run)")


def check_fresh(locations: list[ObjectLocation], now: float, max_age_s: float) -> None:
    """Refuse to plan from a measurement older than `max_age_s`."""
    for loc in locations:
        age = loc.age(now)
        if age > max_age_s:
            raise StaleLocationError(
                f"the location of {loc.object_id} is {age:.1f} s old (limit {max_age_s:.1f} "
                f"s, source {loc.source})", field="max_location_age_s", value=round(age, 2),
                fix="locate the objects again just before moving, or raise "
                    "max_location_age_s if the locator is slow")


def plan_motion(receipt: ValidatedAction, held: ObjectLocation, target: ObjectLocation,
                others: list[ObjectLocation], config: ArmConfig, now: float) -> MotionPlan:
    """The grasp and placement for a validated move, from fresh locations."""
    action = receipt.action
    check_fresh([held, target], now, config.max_location_age_s)
    # Close the fingers across a side that fits, turning the wrist as little as possible.
    sides = [(held.yaw, held.size[1]), (held.yaw + math.pi / 2, held.size[0])]
    graspable = [(yaw, width) for yaw, width in sides
                 if width <= config.gripper_max_width_m - 0.005]
    if not graspable:
        width = min(held.size[0], held.size[1])
        raise InfeasibleMotionError(
            f"{held.object_id} is {width * 100:.1f} cm across, the gripper opens "
            f"{config.gripper_max_width_m * 100:.1f} cm", field="object", value=held.object_id,
            fix="move a narrower object, or use a gripper that opens wider")
    yaw, width = min(graspable, key=lambda side: abs(math.remainder(side[0], math.pi)))
    height = held.size[2]
    grasp_z = held.top_z - min(height / 2, config.max_grasp_depth_m)
    hold_offset = grasp_z - held.bottom_z
    tallest = max([o.top_z for o in others if o.object_id != held.object_id]
                  + [target.top_z], default=target.top_z)
    transit_z = max(held.top_z, tallest + height) + config.approach_height_m

    if action.relation == "in":
        fit = min(target.size[0], target.size[1]) - 0.01
        if max(held.size[0], held.size[1]) > fit:
            raise InfeasibleMotionError(
                f"{held.object_id} ({max(held.size[:2]) * 100:.1f} cm) does not fit the "
                f"opening of {target.object_id} ({fit * 100:.1f} cm)", field="target",
                value=target.object_id, fix="choose a larger container or put it on "
                                            "something instead")
        floor = target.top_z - min(height, target.size[2]) / 2
    else:
        floor = target.top_z
    release_z = floor + config.clearance_m + hold_offset
    # Turn the held object onto the target's axes by the smallest quarter turn.
    turn = math.remainder(target.yaw - held.yaw, math.pi / 2)
    cx, cy = held.centre[0], held.centre[1]
    tx, ty = target.centre[0], target.centre[1]
    speed = config.speed_m_s
    grasp = Grasp(object_id=held.object_id,
                  approach=Pose(x=cx, y=cy, z=transit_z, yaw=yaw),
                  grasp=Pose(x=cx, y=cy, z=grasp_z, yaw=yaw),
                  lift=Pose(x=cx, y=cy, z=transit_z, yaw=yaw),
                  open_width_m=min(config.gripper_max_width_m, width + 0.03),
                  object_width_m=width, force_n=config.grip_force_n, speed_m_s=speed)
    placement = Placement(object_id=held.object_id, relation=action.relation,
                          target_id=target.object_id,
                          approach=Pose(x=tx, y=ty, z=transit_z, yaw=yaw + turn),
                          release=Pose(x=tx, y=ty, z=release_z, yaw=yaw + turn),
                          retreat=Pose(x=tx, y=ty, z=transit_z, yaw=yaw + turn),
                          open_width_m=min(config.gripper_max_width_m, width + 0.03),
                          speed_m_s=speed)
    return MotionPlan(receipt=receipt, grasp=grasp, placement=placement, held=held,
                      target=target, rest_z=floor)


def describe(plan: MotionPlan) -> str:
    """One line for humans: the action and where the arm will pick and place."""
    g, p = plan.grasp, plan.placement
    return (f"{plan.receipt.action.text()}: pick {g.object_id} at {g.grasp.text()}, "
            f"release it {p.relation} {p.target_id} at {p.release.text()}")
