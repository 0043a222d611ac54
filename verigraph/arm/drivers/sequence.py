"""Pick and place as joint-level step lists, shared by the joint-space drivers.

A pick is: open, line to approach, line down, close, line up; a place is: line to
approach, line down, open, line up. All lines are solved before the first step runs,
so an unreachable waypoint fails before anything moves.
"""

from __future__ import annotations

from dataclasses import dataclass

from verigraph.arm.models import Grasp, Placement, Pose
from verigraph.arm.sim.kinematics import JointTrajectory, Kinematics

OPEN_FORCE_N = 20.0  # opening needs no grip limit; the Panda finger motors allow 20 N


@dataclass(frozen=True, slots=True)
class GripStep:
    """Move the fingers to a total opening `width_m` with at most `force_n`."""

    width_m: float
    force_n: float


Step = JointTrajectory | GripStep


def lines_through(kinematics: Kinematics, start_q: tuple[float, ...], waypoints: list[Pose],
                  speed_m_s: float, spacing_m: float = 0.01) -> list[JointTrajectory]:
    """Straight tool lines from the pose at `start_q` through every waypoint."""
    q, here = start_q, kinematics.fk(start_q)
    lines = []
    for target in waypoints:
        line = kinematics.line(q, here, target, speed_m_s, spacing_m)
        lines.append(line)
        q, here = line.final, target
    return lines


def pick_steps(kinematics: Kinematics, start_q: tuple[float, ...], grasp: Grasp,
               spacing_m: float = 0.01) -> list[Step]:
    to_approach, down, lift = lines_through(kinematics, start_q, grasp.waypoints(),
                                            grasp.speed_m_s, spacing_m)
    return [GripStep(grasp.open_width_m, grasp.force_n), to_approach, down,
            GripStep(0.0, grasp.force_n), lift]


def place_steps(kinematics: Kinematics, start_q: tuple[float, ...], placement: Placement,
                spacing_m: float = 0.01) -> list[Step]:
    to_approach, down, retreat = lines_through(kinematics, start_q, placement.waypoints(),
                                               placement.speed_m_s, spacing_m)
    return [to_approach, down, GripStep(placement.open_width_m, OPEN_FORCE_N), retreat]


def home_steps(kinematics: Kinematics, start_q: tuple[float, ...], pose: Pose,
               speed_m_s: float, spacing_m: float = 0.01) -> list[Step]:
    return list(lines_through(kinematics, start_q, [pose], speed_m_s, spacing_m))
