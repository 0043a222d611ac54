"""Safety checks run on a whole motion before its first command: reject, never clamp.

Every waypoint must lie in the workspace box; no segment may touch a keep-out zone,
which is grown by the tool margin and, while carrying, by the held object's extent
around the tool; speed and grip force must be within their caps.
"""

from __future__ import annotations

import math

from verigraph.arm.config import ArmConfig
from verigraph.arm.errors import UnsafeMotionError
from verigraph.arm.geometry import Box
from verigraph.arm.planning import PathSegment


def _fmt(box: Box) -> str:
    lo = ", ".join(f"{v:.3f}" for v in box.min)
    hi = ", ".join(f"{v:.3f}" for v in box.max)
    return f"[{lo}] .. [{hi}]"


def check_path(config: ArmConfig, segments: list[PathSegment]) -> None:
    """Raise UnsafeMotionError for the first waypoint or segment that breaks a limit."""
    for seg in segments:
        for pose in (seg.start, seg.end):
            if not config.workspace.contains(pose.point()):
                raise UnsafeMotionError(
                    f"waypoint '{seg.label}' at {pose.text()} is outside the workspace "
                    f"{_fmt(config.workspace)}", field="workspace", value=pose.point(),
                    fix="move the object or target inside the workspace; enlarge `workspace` "
                        "only if the cell is really clear there")
        grow, below, above = config.tool_margin_m, config.tool_margin_m, config.tool_margin_m
        if seg.carrying is not None:
            half_diagonal = math.hypot(seg.carrying.size[0], seg.carrying.size[1]) / 2
            grow += half_diagonal
            above += seg.hold_offset  # the object hangs below the tool: zones below reach up
            below += seg.carrying.size[2] - seg.hold_offset
        for zone in config.keep_out:
            if zone.expanded(grow, below, above).intersects_segment(seg.start.point(),
                                                                      seg.end.point()):
                what = f" carrying {seg.carrying.object_id}" if seg.carrying else ""
                raise UnsafeMotionError(
                    f"segment '{seg.label}'{what} from {seg.start.text()} to {seg.end.text()} "
                    f"enters keep-out zone '{zone.name}' {_fmt(zone)}", field="keep_out",
                    value=zone.name, fix="choose another target, or move the objects away "
                                         "from the keep-out zone")


def check_caps(config: ArmConfig, speed_m_s: float, force_n: float | None) -> None:
    """Refuse commands above the configured speed and force caps."""
    if speed_m_s > config.max_speed_m_s:
        raise UnsafeMotionError(f"speed {speed_m_s} m/s exceeds the cap "
                                f"{config.max_speed_m_s} m/s", field="speed_m_s",
                                value=speed_m_s, fix="lower speed_m_s in the arm config")
    if force_n is not None and force_n > config.max_force_n:
        raise UnsafeMotionError(f"grip force {force_n} N exceeds the cap {config.max_force_n} N",
                                field="grip_force_n", value=force_n,
                                fix="lower grip_force_n in the arm config")
