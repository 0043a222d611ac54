"""XArmAPIStandIn: a stand-in for xarm-python-sdk's XArmAPI object, for tests only.

No xArm controller or simulator can run on a development machine, so this object has
the methods the `xarm` driver calls, with the SDK's signatures and return codes, and
records every call. It tracks the commanded TCP and, like the controller in reduced
mode with fence mode on, refuses positions outside the programmed boundary
(TCP_LIMIT). Linear moves take distance / speed times `time_scale` seconds and end
early with EMERGENCY_STOP when `emergency_stop` is called. It moves nothing physical.
"""

from __future__ import annotations

import math
import threading
from typing import Any

from xarm.x3.code import APIState


class XArmAPIStandIn:
    """Records calls and mimics an XArmAPI's state; never connects anywhere."""

    def __init__(self, host: str = "192.168.1.185", *, time_scale: float = 0.0,
                 accept_connection: bool = True) -> None:
        self.host = host
        self.time_scale = time_scale
        self.accept_connection = accept_connection
        self.calls: list[tuple[str, tuple[Any, ...], dict[str, Any]]] = []
        self.connected = False
        self.error_code = 0
        self.warn_code = 0
        self.state = 0
        self.mode = 0
        self.position = [307.0, 0.0, 485.0, 180.0, 0.0, 0.0]  # mm, degrees
        self.gripper_position = 850
        self.reduced_mode = False
        self.fence_mode = False
        self.reduced_tcp_boundary: list[float] | None = None
        self.reduced_max_tcp_speed: float | None = None
        self._stopped = threading.Event()

    def _record(self, name: str, *args: Any, **kwargs: Any) -> None:
        self.calls.append((name, args, kwargs))

    def called(self, name: str) -> list[tuple[tuple[Any, ...], dict[str, Any]]]:
        return [(a, k) for n, a, k in self.calls if n == name]

    # -- connection and state ----------------------------------------------------------------
    def connect(self, port: Any = None, **kwargs: Any) -> None:
        self._record("connect")
        if not self.accept_connection:
            raise Exception("connect socket failed")  # what the SDK raises
        self.connected = True

    def disconnect(self) -> None:
        self._record("disconnect")
        self.connected = False

    def _ok(self, name: str, *args: Any, **kwargs: Any) -> int:
        self._record(name, *args, **kwargs)
        return APIState.NOT_CONNECTED if not self.connected else 0

    def clean_error(self) -> int:
        self.error_code = 0
        return self._ok("clean_error")

    def clean_warn(self) -> int:
        self.warn_code = 0
        return self._ok("clean_warn")

    def motion_enable(self, enable: bool = True, servo_id: Any = None) -> int:
        return self._ok("motion_enable", enable=enable)

    def set_mode(self, mode: int = 0, detection_param: int = 0) -> int:
        self.mode = mode
        return self._ok("set_mode", mode)

    def set_state(self, state: int = 0) -> int:
        self.state = state
        self._stopped.clear()
        return self._ok("set_state", state)

    def set_reduced_tcp_boundary(self, boundary: list[float]) -> int:
        self.reduced_tcp_boundary = list(boundary)
        return self._ok("set_reduced_tcp_boundary", boundary)

    def set_reduced_max_tcp_speed(self, speed: float) -> int:
        self.reduced_max_tcp_speed = speed
        return self._ok("set_reduced_max_tcp_speed", speed)

    def set_reduced_mode(self, on: bool) -> int:
        self.reduced_mode = on
        return self._ok("set_reduced_mode", on)

    def set_fence_mode(self, on: bool) -> int:
        self.fence_mode = on
        return self._ok("set_fence_mode", on)

    def get_position(self, is_radian: bool | None = None) -> tuple[int, list[float]]:
        self._record("get_position")
        return (0 if self.connected else APIState.NOT_CONNECTED), list(self.position)

    # -- motion --------------------------------------------------------------------------------
    def set_position(self, x: float | None = None, y: float | None = None,
                     z: float | None = None, roll: float | None = None,
                     pitch: float | None = None, yaw: float | None = None,
                     speed: float | None = None, wait: bool = False, **kwargs: Any) -> int:
        self._record("set_position", x=x, y=y, z=z, roll=roll, pitch=pitch, yaw=yaw,
                     speed=speed, wait=wait, **kwargs)
        if not self.connected:
            return APIState.NOT_CONNECTED
        if self.state == 4:
            return APIState.EMERGENCY_STOP
        target = [v if v is not None else cur
                  for v, cur in zip((x, y, z, roll, pitch, yaw), self.position, strict=True)]
        if self._outside_fence(target):
            return APIState.TCP_LIMIT
        if self.reduced_mode and self.reduced_max_tcp_speed is not None and speed is not None \
                and speed > self.reduced_max_tcp_speed:
            speed = self.reduced_max_tcp_speed  # the controller caps speed in reduced mode
        duration = math.dist(target[:3], self.position[:3]) / max(speed or 100.0, 1e-6)
        if wait and self._stopped.wait(duration * self.time_scale):
            return APIState.EMERGENCY_STOP
        self.position = target
        return 0

    def _outside_fence(self, target: list[float]) -> bool:
        if not (self.fence_mode and self.reduced_mode and self.reduced_tcp_boundary):
            return False
        x_max, x_min, y_max, y_min, z_max, z_min = self.reduced_tcp_boundary
        x, y, z = target[:3]
        return not (x_min <= x <= x_max and y_min <= y <= y_max and z_min <= z <= z_max)

    def emergency_stop(self) -> None:
        self._record("emergency_stop")
        self.state = 4
        self._stopped.set()

    # -- grippers ------------------------------------------------------------------------------
    def set_gripper_mode(self, mode: int, **kwargs: Any) -> int:
        return self._ok("set_gripper_mode", mode)

    def set_gripper_enable(self, enable: bool, **kwargs: Any) -> int:
        return self._ok("set_gripper_enable", enable)

    def set_gripper_position(self, pos: float, wait: bool = False, speed: Any = None,
                             auto_enable: bool = False, timeout: Any = None,
                             **kwargs: Any) -> int:
        self.gripper_position = int(pos)
        return self._ok("set_gripper_position", pos, wait=wait)

    def open_lite6_gripper(self, sync: bool = True) -> int:
        return self._ok("open_lite6_gripper")

    def close_lite6_gripper(self, sync: bool = True) -> int:
        return self._ok("close_lite6_gripper")
