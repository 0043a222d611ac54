"""The two seams of the arm adapter: motion (ArmDriver) and perception (ObjectLocator).

They are separate so a camera pipeline and an arm can change independently: the
PyBullet camera, a fixed layout, or a real depth camera can each feed any driver.
"""

from __future__ import annotations

from collections.abc import Callable, Collection
from typing import TYPE_CHECKING, Protocol, runtime_checkable

from verigraph.arm.models import (
    ConfirmationRequest,
    DriverStatus,
    Grasp,
    ObjectLocation,
    Placement,
    Pose,
)

if TYPE_CHECKING:
    from verigraph.arm.planning import PathSegment


@runtime_checkable
class ArmDriver(Protocol):
    """Low-level motion. Only the ArmController calls it, after every safety check.

    Poses are metric in the robot base frame. `pick` and `place` follow exactly the
    waypoints of their argument with straight tool-centre moves (the controller checked
    those segments). `stop` may be called from another thread while a motion runs: the
    motion must end promptly (raising MotionCancelledError) and stay stopped until
    `reset`.
    """

    name: str
    simulated: bool

    def connect(self, timeout_s: float) -> None: ...

    def status(self) -> DriverStatus: ...

    def home(self, pose: Pose, speed_m_s: float) -> None: ...

    def pick(self, grasp: Grasp) -> None: ...

    def place(self, placement: Placement) -> None: ...

    def stop(self) -> None: ...

    def reset(self) -> None: ...

    def disconnect(self) -> None: ...


@runtime_checkable
class ObjectLocator(Protocol):
    """Object id -> where it is now (centre, top height, size, timestamp).

    Returns an entry for every requested id it can see, and none for the others.
    """

    def locate(self, object_ids: Collection[str]) -> dict[str, ObjectLocation]: ...


class PathCheck(Protocol):
    """A check of a whole planned tool path before motion (the whole-arm geometry)."""

    def check(self, segments: list[PathSegment]) -> None: ...

    def close(self) -> None: ...


ConfirmHook = Callable[[ConfirmationRequest], bool]
"""Asked before every `real` motion, synchronously; only a literal True lets the arm move."""
