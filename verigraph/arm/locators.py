"""Locators that need no camera: a declared fixed layout, and the dry-run overlay.

`LayoutLocator` reports positions an operator measured once (a fixture plate, a test
cell). It never sees motion, so in `sim` or `real` mode the closed-loop check will
report that nothing moved: use a camera locator there. `DryRunLocator` wraps any
locator and overlays where dry-run motions *would* have put objects, so a dry run of
a whole plan stays consistent; its entries say so in `source`.
"""

from __future__ import annotations

import time
from collections.abc import Collection, Mapping

from pydantic import BaseModel, ConfigDict, Field

from verigraph.arm.geometry import Point
from verigraph.arm.models import ObjectLocation
from verigraph.arm.protocols import ObjectLocator


class DeclaredObject(BaseModel):
    """An object's measured box in a fixed layout (metres, robot base frame)."""

    model_config = ConfigDict(extra="forbid")

    centre: Point
    size: Point = Field(description="extent along yaw, across yaw, height")
    yaw: float = 0.0


class LayoutLocator:
    """Reports a fixed, declared layout; timestamps are the time of each call."""

    def __init__(self, layout: Mapping[str, DeclaredObject]) -> None:
        self._layout = dict(layout)

    def locate(self, object_ids: Collection[str]) -> dict[str, ObjectLocation]:
        now = time.time()
        return {i: ObjectLocation(object_id=i, centre=d.centre, size=d.size, yaw=d.yaw,
                                  timestamp=now, source="declared layout")
                for i in object_ids if (d := self._layout.get(i)) is not None}


class DryRunLocator:
    """A locator with the predicted effects of dry-run motions laid over it."""

    def __init__(self, base: ObjectLocator) -> None:
        self.base = base
        self._moved: dict[str, ObjectLocation] = {}

    def record(self, location: ObjectLocation) -> None:
        self._moved[location.object_id] = location

    def locate(self, object_ids: Collection[str]) -> dict[str, ObjectLocation]:
        found = self.base.locate([i for i in object_ids if i not in self._moved])
        now = time.time()
        for i in object_ids:
            if i in self._moved:
                found[i] = self._moved[i].model_copy(update={"timestamp": now})
        return found
