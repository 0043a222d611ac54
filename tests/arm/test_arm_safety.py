"""Motion planning and the safety checks on its path: reject, never clamp."""

from __future__ import annotations

import math
import time

import pytest

from verigraph.actions.model import MoveAction
from verigraph.arm import (
    ArmConfig,
    Box,
    InfeasibleMotionError,
    KeepOutZone,
    ObjectLocation,
    Pose,
    StaleLocationError,
    UnsafeMotionError,
)
from verigraph.arm.approval import ValidatedAction, authorize
from verigraph.arm.planning import MotionPlan, plan_motion
from verigraph.arm.safety import check_caps, check_path
from verigraph.graph.model import Edge, Node, SceneGraph
from verigraph.graph.state import WorldState

BLOCK = (0.05, 0.05, 0.05)


def two_objects(held: str = "block", target: str = "block",
                dictionary: str = "blocks") -> WorldState:
    return WorldState.from_graph(SceneGraph(
        nodes=[Node(id="table", label="table"), Node(id="a", label=held),
               Node(id="b", label=target)],
        edges=[Edge(source="a", relation="on", target="table"),
               Edge(source="b", relation="on", target="table")], dictionary=dictionary))


def loc(object_id: str, x: float, y: float, z: float, size: tuple[float, float, float] = BLOCK,
        age: float = 0.0, yaw: float = 0.0) -> ObjectLocation:
    return ObjectLocation(object_id=object_id, centre=(x, y, z), size=size, yaw=yaw,
                          timestamp=time.time() - age, source="test")


def plan(config: ArmConfig, held: ObjectLocation, target: ObjectLocation,
         relation: str = "on") -> MotionPlan:
    """Plan move(a, relation, b): blocks for `on`, a cup into a bowl for `in`."""
    state = two_objects() if relation == "on" else two_objects("cup", "bowl", "tableware")
    issued = authorize(state, MoveAction(object="a", relation=relation, target="b"))
    assert isinstance(issued, ValidatedAction)
    return plan_motion(issued, held, target, [held, target], config, time.time())


def test_segment_that_cuts_a_corner_intersects_the_box() -> None:
    box = Box(min=(0.0, 0.0, 0.0), max=(1.0, 1.0, 1.0))
    assert box.intersects_segment((-0.5, 0.5, 0.5), (0.5, -0.5, 0.5)) is True  # ends outside
    assert box.intersects_segment((-1.0, 2.0, 0.5), (2.0, 2.0, 0.5)) is False
    assert box.intersects_segment((0.2, 0.2, 0.2), (0.3, 0.3, 0.3)) is True  # inside
    assert box.intersects_segment((1.5, 0.5, 0.5), (1.5, 0.5, 0.5)) is False  # a point


def test_on_releases_just_above_the_target_top() -> None:
    config = ArmConfig(driver="pybullet", clearance_m=0.005)
    p = plan(config, loc("a", 0.5, -0.1, 0.025), loc("b", 0.5, 0.1, 0.025))
    # Grasped at its centre (half height 2.5 cm above its bottom), released with the
    # object's bottom 5 mm above b's top at 5 cm.
    assert p.grasp.grasp.z == pytest.approx(0.025)
    assert p.placement.release.z == pytest.approx(0.05 + 0.005 + 0.025)
    assert (p.placement.release.x, p.placement.release.y) == pytest.approx((0.5, 0.1))
    assert p.rest_z == pytest.approx(0.05)
    # one transit height clearing the target with the held block under the tool
    assert p.grasp.lift.z == p.placement.approach.z >= 0.05 + 0.05 + config.approach_height_m


def test_in_lowers_into_the_opening() -> None:
    config = ArmConfig(driver="pybullet")
    bowl = loc("b", 0.5, 0.1, 0.03, size=(0.12, 0.12, 0.06))
    p = plan(config, loc("a", 0.5, -0.1, 0.025), bowl, relation="in")
    assert p.rest_z == pytest.approx(0.06 - 0.025)  # half the block below the rim
    assert p.placement.release.z < bowl.top_z + 0.025 + config.clearance_m


def test_object_too_wide_for_the_gripper_is_refused() -> None:
    config = ArmConfig(driver="pybullet", gripper_max_width_m=0.08)
    with pytest.raises(InfeasibleMotionError, match="gripper opens"):
        plan(config, loc("a", 0.5, -0.1, 0.02, size=(0.14, 0.14, 0.04)),
             loc("b", 0.5, 0.1, 0.025))


def test_narrow_side_is_grasped_with_the_least_wrist_turn() -> None:
    config = ArmConfig(driver="pybullet")
    p = plan(config, loc("a", 0.5, -0.1, 0.02, size=(0.03, 0.12, 0.04)),
             loc("b", 0.5, 0.1, 0.025))
    assert p.grasp.object_width_m == pytest.approx(0.03)
    assert abs(p.grasp.grasp.yaw) == pytest.approx(math.pi / 2)


def test_object_that_does_not_fit_the_container_is_refused() -> None:
    config = ArmConfig(driver="pybullet")
    with pytest.raises(InfeasibleMotionError, match="does not fit"):
        plan(config, loc("a", 0.5, -0.1, 0.025), loc("b", 0.5, 0.1, 0.03,
                                                       size=(0.055, 0.055, 0.06)), "in")


def test_stale_location_is_refused() -> None:
    config = ArmConfig(driver="pybullet", max_location_age_s=1.0)
    with pytest.raises(StaleLocationError) as err:
        plan(config, loc("a", 0.5, -0.1, 0.025, age=3.0), loc("b", 0.5, 0.1, 0.025))
    assert err.value.field == "max_location_age_s"


def test_target_outside_the_workspace_is_rejected_not_clamped() -> None:
    config = ArmConfig(driver="pybullet")
    p = plan(config, loc("a", 0.5, -0.1, 0.025), loc("b", 0.95, 0.1, 0.025))
    with pytest.raises(UnsafeMotionError, match="outside the workspace") as err:
        check_path(config, p.path(config.home))
    assert err.value.field == "workspace"
    assert "0.950" in str(err.value)


def test_transit_through_a_keep_out_zone_is_rejected() -> None:
    post = KeepOutZone(name="post", min=(0.45, -0.02, 0.0), max=(0.55, 0.02, 0.4))
    config = ArmConfig(driver="pybullet", keep_out=[post])
    p = plan(config, loc("a", 0.5, -0.15, 0.025), loc("b", 0.5, 0.15, 0.025))
    with pytest.raises(UnsafeMotionError, match="enters keep-out zone 'post'") as err:
        check_path(config, p.path(config.home))
    assert "transit" in str(err.value) and "carrying a" in str(err.value)


def test_a_zone_only_the_held_object_would_touch_is_rejected() -> None:
    # A low obstacle 2 cm under the transit line: clear for the bare tool, hit by the
    # block held at its centre, whose bottom hangs 2.5 cm below the tool.
    config = ArmConfig(driver="pybullet", tool_margin_m=0.0)
    p = plan(config, loc("a", 0.5, -0.15, 0.025), loc("b", 0.5, 0.15, 0.025))
    top = p.grasp.lift.z - 0.02
    low = KeepOutZone(name="low", min=(0.45, -0.02, top - 0.1), max=(0.55, 0.02, top))
    bare = ArmConfig(driver="pybullet", tool_margin_m=0.0, keep_out=[low])
    with pytest.raises(UnsafeMotionError, match="carrying a"):
        check_path(bare, p.path(config.home))
    empty = [s for s in p.path(config.home) if s.carrying is None]
    check_path(bare, empty)  # the same zone is no obstacle without the block


def test_speed_and_force_caps() -> None:
    config = ArmConfig(driver="pybullet", max_speed_m_s=0.25, max_force_n=40)
    check_caps(config, 0.25, 40)
    with pytest.raises(UnsafeMotionError, match="speed"):
        check_caps(config, 0.3, 10)
    with pytest.raises(UnsafeMotionError, match="grip force"):
        check_caps(config, 0.1, 41)


def test_pose_yaw_is_a_half_turn() -> None:
    assert Pose(x=0, y=0, z=0, yaw=math.pi).yaw == pytest.approx(0.0, abs=1e-9)
    assert Pose(x=0, y=0, z=0, yaw=-3 * math.pi / 4).yaw == pytest.approx(math.pi / 4)
