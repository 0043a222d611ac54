"""The arm adapter: the only way a graph action reaches a robot arm.

The server builds an `ArmWorld` with `open_arm_world(config, graph, confirm=...)` and
passes it to `verigraph.actions.execution.execute_in_world`, which validates each action
before `ArmWorld.perform`; the world validates again on the graph it observes, and
the `ArmController` gate checks, confirms, times and logs every command.
"""

from verigraph.arm.approval import (
    Approval,
    NotApproved,
    NoWayToAsk,
    PreApproved,
    ValidatedAction,
    authorize,
    confirm_scope,
    scoped_confirm,
)
from verigraph.arm.audit import AuditLog
from verigraph.arm.config import (
    DRIVER_NAMES,
    ArmConfig,
    CameraView,
    PyBulletOptions,
    RosbridgeOptions,
    XArmOptions,
    driver_from_executor,
    load_arm_config,
    parse_arm_config,
)
from verigraph.arm.controller import ArmController, MotionOutcome
from verigraph.arm.errors import (
    ArmBusyError,
    ArmConfigError,
    ArmConnectionError,
    ArmError,
    ArmMotionError,
    ArmRefusal,
    ArmStoppedError,
    ConfirmationError,
    InfeasibleMotionError,
    MotionCancelledError,
    ObjectNotFoundError,
    StaleLocationError,
    UnauthorizedMotionError,
    UnsafeMotionError,
)
from verigraph.arm.factory import make_driver, open_arm_world, probe_arm
from verigraph.arm.geometry import Box, KeepOutZone
from verigraph.arm.locators import DeclaredObject, DryRunLocator, LayoutLocator
from verigraph.arm.models import (
    ArmStatus,
    AuditRecord,
    ConfirmationRequest,
    DriverStatus,
    Grasp,
    ObjectLocation,
    Placement,
    Pose,
)
from verigraph.arm.protocols import ArmDriver, ConfirmHook, ObjectLocator
from verigraph.arm.world import ArmWorld, RelationCheck

__all__ = [
    "DRIVER_NAMES", "Approval", "ArmBusyError", "ArmConfig", "ArmConfigError",
    "ArmConnectionError", "ArmController", "ArmDriver", "ArmError", "ArmMotionError",
    "ArmRefusal", "ArmStatus", "ArmStoppedError", "ArmWorld", "AuditLog", "AuditRecord", "Box",
    "CameraView", "ConfirmHook", "ConfirmationError", "ConfirmationRequest", "DeclaredObject",
    "DriverStatus", "DryRunLocator", "Grasp", "InfeasibleMotionError", "KeepOutZone",
    "LayoutLocator", "MotionCancelledError", "MotionOutcome", "NoWayToAsk", "NotApproved",
    "ObjectLocation", "ObjectLocator", "ObjectNotFoundError", "Placement", "Pose",
    "PreApproved", "PyBulletOptions",
    "RelationCheck", "RosbridgeOptions", "StaleLocationError", "UnauthorizedMotionError",
    "UnsafeMotionError", "ValidatedAction", "XArmOptions", "authorize", "confirm_scope",
    "driver_from_executor", "load_arm_config", "make_driver", "open_arm_world",
    "parse_arm_config", "probe_arm", "scoped_confirm",
]
