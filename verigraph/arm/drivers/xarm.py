"""The `xarm` driver: UFACTORY xArm / Lite6 through xarm-python-sdk.

Straight tool moves are the controller's own linear `set_position` (mm, degrees, the
tool pointing down: roll 180, pitch 0); the gripper is the xArm gripper (pulses) or
the Lite6 gripper (open/close). On connect the workspace box is also programmed as
the controller's reduced-mode TCP boundary with fence mode on, so the controller
itself refuses to leave it even if this software misbehaves. `stop` is the SDK's
emergency stop. The standard xArm gripper takes no force, so the force cap is checked
by the gate but cannot be enforced by this gripper.
"""

from __future__ import annotations

import contextlib
import math
import sys
import threading
from collections.abc import Callable
from typing import Any

from verigraph.arm.config import ArmConfig
from verigraph.arm.errors import ArmConnectionError, ArmMotionError, MotionCancelledError
from verigraph.arm.models import DriverStatus, Grasp, Placement, Pose
from verigraph.extras import require

ApiFactory = Callable[[str], Any]


def sdk_api(host: str) -> Any:
    """A real XArmAPI for `host`, not yet connected."""
    require("arm", "xarm")
    # The SDK prints its version to stdout on import; over MCP stdio, stdout is the wire.
    with contextlib.redirect_stdout(sys.stderr):
        from xarm.wrapper import XArmAPI

    return XArmAPI(host, is_radian=False, do_not_open=True)


class XArmDriver:
    """ArmDriver over an XArmAPI object (or a stand-in with the same methods)."""

    name = "xarm"
    simulated = False

    def __init__(self, config: ArmConfig, api_factory: ApiFactory | None = None) -> None:
        self.config = config
        self.options = config.xarm
        self._factory = api_factory or sdk_api
        self._api: Any = None
        self._cancel = threading.Event()
        self._moving = False
        self._fault: str | None = None

    # -- connection ------------------------------------------------------------------------
    def connect(self, timeout_s: float) -> None:
        host = self.config.host or ""
        api = self._factory(host)
        try:
            api.connect()
        except Exception as exc:
            raise ArmConnectionError(f"cannot connect to the xArm controller at {host}: {exc}",
                                     field="host", value=host,
                                     fix="check the controller's IP address, power and "
                                         "network cable") from None
        if not api.connected:
            raise ArmConnectionError(f"the xArm controller at {host} did not accept the "
                                     "connection", field="host", value=host,
                                     fix="check the controller's IP address and power")
        self._api = api
        # Never clear what the controller reports: an error or a stop (state 4) stays
        # until a reset that a human confirms; only a clean controller is enabled.
        self._fault = _fault_of(api)
        if self._fault is None:
            self._enable()
        if self.options.set_reduced_boundary:
            lo, hi = self.config.workspace.min, self.config.workspace.max
            mm = [hi[0], lo[0], hi[1], lo[1], hi[2], lo[2]]
            self._call("set_reduced_tcp_boundary", [round(v * 1000, 1) for v in mm])
            self._call("set_reduced_max_tcp_speed", round(self.config.max_speed_m_s * 1000, 1))
            self._call("set_fence_mode", True)
            self._call("set_reduced_mode", True)
        if self.options.gripper == "xarm":
            self._call("set_gripper_mode", 0)
            self._call("set_gripper_enable", True)

    def disconnect(self) -> None:
        if self._api is not None:
            self._api.disconnect()
            self._api = None

    # -- ArmDriver -------------------------------------------------------------------------
    def status(self) -> DriverStatus:
        api = self._api
        if api is None:
            return DriverStatus(connected=False)
        code, pos = api.get_position(is_radian=False)
        tcp = None if code != 0 else Pose(x=pos[0] / 1000, y=pos[1] / 1000, z=pos[2] / 1000,
                                           yaw=math.radians(pos[5]))
        error = _fault_of(api) or self._fault
        return DriverStatus(connected=bool(api.connected), tcp=tcp, moving=self._moving,
                            error=error or ("stopped" if self._cancel.is_set() else None))

    def home(self, pose: Pose, speed_m_s: float) -> None:
        self._sequence([lambda: self._move(pose, speed_m_s)])

    def pick(self, grasp: Grasp) -> None:
        speed = grasp.speed_m_s
        self._sequence([lambda: self._grip(grasp.open_width_m),
                        lambda: self._move(grasp.approach, speed),
                        lambda: self._move(grasp.grasp, speed),
                        lambda: self._grip(0.0),
                        lambda: self._move(grasp.lift, speed)])

    def place(self, placement: Placement) -> None:
        speed = placement.speed_m_s
        self._sequence([lambda: self._move(placement.approach, speed),
                        lambda: self._move(placement.release, speed),
                        lambda: self._grip(placement.open_width_m),
                        lambda: self._move(placement.retreat, speed)])

    def stop(self) -> None:
        self._cancel.set()
        if self._api is not None:
            self._api.emergency_stop()

    def reset(self) -> None:
        """Clear the controller's error and stop state and enable it (nothing moves).

        Only the controller calls it, on a reset the user confirmed.
        """
        self._cancel.clear()
        if self._api is not None:
            self._call("clean_error")
            self._call("clean_warn")
            self._enable()
            self._fault = None

    def _enable(self) -> None:
        self._call("motion_enable", enable=True)
        self._call("set_mode", 0)
        self._call("set_state", 0)

    # -- internals -------------------------------------------------------------------------
    def _sequence(self, steps: list[Callable[[], None]]) -> None:
        self._moving = True
        try:
            for step in steps:
                if self._cancel.is_set():
                    raise MotionCancelledError("the xArm is stopped; reset it first")
                step()
        finally:
            self._moving = False

    def _move(self, pose: Pose, speed_m_s: float) -> None:
        self._call("set_position", x=pose.x * 1000, y=pose.y * 1000, z=pose.z * 1000,
                   roll=self.options.roll_deg, pitch=self.options.pitch_deg,
                   yaw=math.degrees(pose.yaw), speed=speed_m_s * 1000,
                   mvacc=self.options.acceleration_mm_s2, wait=True,
                   timeout=self.config.motion_timeout_s)

    def _grip(self, width_m: float) -> None:
        kind = self.options.gripper
        if kind == "xarm":
            ratio = max(0.0, min(1.0, width_m / self.options.gripper_max_width_m))
            self._call("set_gripper_position", round(ratio * self.options.gripper_open_pulse),
                       wait=True)
        elif kind == "lite6":
            self._call("open_lite6_gripper" if width_m > 0 else "close_lite6_gripper")

    def _call(self, method: str, *args: Any, **kwargs: Any) -> Any:
        """Call the SDK and turn a non-zero return code into an error."""
        if self._api is None:
            raise ArmMotionError("the xArm is not connected", field="connected",
                                 fix="connect first")
        result = getattr(self._api, method)(*args, **kwargs)
        code = result[0] if isinstance(result, tuple) else result
        if self._cancel.is_set() and method in ("set_position", "set_gripper_position"):
            raise MotionCancelledError(f"{method} was interrupted by the stop")
        if code not in (0, None):
            raise ArmMotionError(f"xArm {method} returned code {code} (controller error "
                                 f"{getattr(self._api, 'error_code', '?')})", field=method,
                                 value=code, fix="see the xArm API code table; clear the "
                                                 "error on the controller, then reset")
        return result


STOPPED_STATE = 4  # the SDK's "stop" state: after an emergency stop or an error


def _fault_of(api: Any) -> str | None:
    """What the controller reports as wrong: an error code, or the stop state."""
    if getattr(api, "error_code", 0):
        return f"controller error {api.error_code}"
    if getattr(api, "state", 0) == STOPPED_STATE:
        return "controller in the stop state (4)"
    return None
