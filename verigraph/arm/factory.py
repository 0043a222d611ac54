"""Building an ArmWorld from a configuration: the one call the server layer makes.

`open_arm_world(config, graph, confirm=...)` picks the driver by name, builds the
PyBullet cell from the episode graph when the driver is `pybullet`, connects (never
in dry-run) and returns the World to hand to `execute_in_world`.
"""

from __future__ import annotations

import socket
from collections.abc import Callable

import cv2
import numpy as np

from verigraph.arm.audit import AuditLog
from verigraph.arm.config import DRIVER_NAMES, ArmConfig
from verigraph.arm.controller import ArmController
from verigraph.arm.errors import ArmConfigError, ArmConnectionError
from verigraph.arm.locators import LayoutLocator
from verigraph.arm.protocols import ArmDriver, ConfirmHook, ObjectLocator, PathCheck
from verigraph.arm.world import ArmWorld
from verigraph.extras import EXTRAS, require
from verigraph.graph.model import SceneGraph


def open_arm_world(config: ArmConfig, graph: SceneGraph, *, confirm: ConfirmHook | None = None,
                   locator: ObjectLocator | None = None, driver: ArmDriver | None = None,
                   audit: AuditLog | None = None) -> ArmWorld:
    """An ArmWorld for the episode `graph`, connected unless the mode is dry-run.

    `confirm` is asked before every real motion; drivers without a camera of their own
    (rosbridge, xarm) need a `locator`, or a `layout` in the config; `driver` replaces
    the one named in the config (tests, custom hardware).
    """
    on_close: Callable[[], None] | None = None
    render: Callable[..., np.ndarray] | None = None
    if config.driver not in DRIVER_NAMES:
        raise ArmConfigError(f"unknown arm driver '{config.driver}'", field="driver",
                             value=config.driver, fix=f"use one of {', '.join(DRIVER_NAMES)}")
    if config.driver == "pybullet" and driver is None:
        require("arm", "pybullet")
        from verigraph.arm.drivers.pybullet_panda import PyBulletPandaDriver
        from verigraph.arm.sim.camera import PyBulletCameraLocator, capture
        from verigraph.arm.sim.panda_scene import PandaScene

        scene = PandaScene.from_graph(graph, config.pybullet)
        panda = PyBulletPandaDriver(scene)
        driver = panda
        locator = locator or PyBulletCameraLocator(scene)

        def release() -> None:
            """Disconnect every PyBullet client the cell opened (the scene and the IK)."""
            try:
                panda.close()
            finally:
                scene.close()

        on_close = release
        view = config.pybullet.cameras[0]

        def render(width: int | None = None, height: int | None = None) -> np.ndarray:
            """The scene camera's image; a side not given keeps the camera's aspect."""
            w = width or (round(height * view.width / view.height) if height else view.width)
            h = height or round(w * view.height / view.width)
            camera = view.model_copy(update={"width": w, "height": h})
            return cv2.cvtColor(capture(scene, camera).rgb, cv2.COLOR_RGB2BGR)

    elif driver is None:
        driver = make_driver(config)
    if locator is None and config.layout:
        locator = LayoutLocator(config.layout)
    if locator is None:
        raise ArmConfigError(f"the {config.driver} driver has no camera of its own",
                             field="locator", value=config.driver,
                             fix="pass an ObjectLocator (a camera pipeline), or give the "
                                 "config a layout: the measured box of every object")
    checker: PathCheck | None = None
    try:  # a failure here must not leave the cell's physics clients open
        checker = whole_arm_check(config)
        controller = ArmController(config, driver, confirm=confirm, audit=audit,
                                   whole_arm=checker)
    except BaseException:
        if checker is not None:
            checker.close()
        if on_close is not None:
            on_close()
        raise
    try:
        controller.connect()
    except BaseException:
        controller.close()
        if on_close is not None:
            on_close()
        raise
    return ArmWorld(graph, controller, locator, on_close=on_close, render=render)


def whole_arm_check(config: ArmConfig) -> PathCheck | None:
    """The whole-arm geometry check for `config`'s arm (PyBullet DIRECT with its URDF).

    Required to move anything (sim, real); a dry run without pybullet installed skips it.
    """
    try:
        from verigraph.arm.sim.whole_arm import WholeArmCheck
    except ImportError:
        if config.mode == "dry-run":
            return None
        raise ArmConfigError("the whole-arm geometry check needs pybullet", field="driver",
                             value=config.driver,
                             fix=f"install the arm extra: {EXTRAS['arm'].install}") from None
    return WholeArmCheck(config)


def make_driver(config: ArmConfig) -> ArmDriver:
    """The hardware driver named in the config (imports its SDK only now; a missing SDK
    is an ExtraMissingError naming the install command)."""
    if config.driver == "rosbridge":
        require("arm", "roslibpy")
        from verigraph.arm.drivers.rosbridge import RosbridgeDriver

        return RosbridgeDriver(config)
    if config.driver == "xarm":
        from verigraph.arm.drivers.xarm import XArmDriver

        return XArmDriver(config)
    raise ArmConfigError(f"the {config.driver} driver needs a scene, not only a config",
                         field="driver", value=config.driver,
                         fix="build it with open_arm_world, which creates the PyBullet cell")


# The TCP port each hardware driver talks to (xArm: the SDK's control port).
CONTROL_PORTS = {"xarm": 502}


def probe_arm(config: ArmConfig) -> None:
    """Check that the controller accepts a TCP connection, within connect_timeout_s.

    Side-effect free (nothing is sent), so `verigraph serve` can refuse to start
    against an unreachable arm before any client relies on it. Simulators and
    dry-run never contact a controller, so they are not probed.
    """
    if config.mode == "dry-run" or config.driver == "pybullet":
        return
    port = config.rosbridge.port if config.driver == "rosbridge" else CONTROL_PORTS["xarm"]
    host = config.host or ""
    try:
        with socket.create_connection((host, port), timeout=config.connect_timeout_s):
            pass
    except OSError as exc:
        why = "no answer" if isinstance(exc, TimeoutError) else (exc.strerror or str(exc))
        raise ArmConnectionError(
            f"cannot reach the {config.driver} controller at {host}:{port} within "
            f"{config.connect_timeout_s:g} s ({why})", field="host", value=host,
            fix="check the address, that the controller is on and reachable, and the port"
        ) from None
