"""Axis-aligned boxes and straight segments: the geometry the safety checks run on.

Everything is metric, in the robot base frame. A segment is checked against a box
exactly (slab method), so a straight move that cuts the corner of a keep-out zone is
caught even when both of its end points lie outside.
"""

from __future__ import annotations

import math

from pydantic import BaseModel, ConfigDict, Field, model_validator

Point = tuple[float, float, float]


class Box(BaseModel):
    """An axis-aligned box given by its minimum and maximum corners (metres, finite)."""

    model_config = ConfigDict(extra="forbid", frozen=True, allow_inf_nan=False)

    min: Point = Field(description="(x, y, z) of the lower corner, metres, robot base frame")
    max: Point = Field(description="(x, y, z) of the upper corner, metres, robot base frame")

    @model_validator(mode="after")
    def _ordered(self) -> Box:
        for axis, lo, hi in zip("xyz", self.min, self.max, strict=True):
            if not lo < hi:
                raise ValueError(f"min.{axis} ({lo}) must be below max.{axis} ({hi})")
        return self

    def contains(self, p: Point, tolerance: float = 1e-9) -> bool:
        """True if `p` lies inside or on the boundary."""
        return all(lo - tolerance <= v <= hi + tolerance
                   for v, lo, hi in zip(p, self.min, self.max, strict=True))

    def expanded(self, xy: float = 0.0, below: float = 0.0, above: float = 0.0) -> Box:
        """The box grown by `xy` sideways, `below` downwards and `above` upwards."""
        return Box(min=(self.min[0] - xy, self.min[1] - xy, self.min[2] - below),
                   max=(self.max[0] + xy, self.max[1] + xy, self.max[2] + above))

    def intersects_segment(self, a: Point, b: Point) -> bool:
        """True if the straight segment a->b touches the box (slab method)."""
        t0, t1 = 0.0, 1.0
        for axis in range(3):
            d = b[axis] - a[axis]
            lo, hi = self.min[axis], self.max[axis]
            if abs(d) < 1e-12:
                if not lo <= a[axis] <= hi:
                    return False
                continue
            ta, tb = (lo - a[axis]) / d, (hi - a[axis]) / d
            if ta > tb:
                ta, tb = tb, ta
            t0, t1 = max(t0, ta), min(t1, tb)
            if t0 > t1:
                return False
        return True


class KeepOutZone(Box):
    """A named box no part of the tool (or what it carries) may enter."""

    name: str = Field(min_length=1, max_length=64, description="shown in refusals")


def lerp(a: Point, b: Point, t: float) -> Point:
    return (a[0] + (b[0] - a[0]) * t, a[1] + (b[1] - a[1]) * t, a[2] + (b[2] - a[2]) * t)


def wrap_angle(angle: float) -> float:
    """Angle in (-pi, pi]."""
    wrapped = math.remainder(angle, 2 * math.pi)
    return math.pi if wrapped == -math.pi else wrapped
