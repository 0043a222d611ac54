"""Arm errors: each names the field, the value and the fix, like every VeriGraph error.

`ArmRefusal` and its subclasses are raised *before* anything is sent to a driver, so
the caller may treat the episode as unchanged; `ArmMotionError` means a command was
already sent and the world may have changed (observe it before trusting any graph).
"""

from __future__ import annotations

from verigraph.errors import VeriGraphError


class ArmError(VeriGraphError):
    """Base class of every arm adapter error."""

    audited = False  # set once the error is in the audit log


class ArmConfigError(ArmError):
    """A bad arm configuration: unknown driver, bad mode, inconsistent limits."""


class ArmConnectionError(ArmError):
    """The driver could not reach its controller within the connect timeout."""


class ArmRefusal(ArmError):
    """The adapter refused before sending any command; nothing moved."""


class UnsafeMotionError(ArmRefusal):
    """A waypoint or segment leaves the workspace, enters a keep-out zone or breaks a cap."""


class ArmStoppedError(ArmRefusal):
    """The stop is latched; only an explicit reset clears it."""


class ResetNotAllowedError(ArmRefusal):
    """The caller may not reset this arm (the agent, unless the operator allowed it)."""


class ArmBusyError(ArmRefusal):
    """Another motion is in progress; the adapter runs one motion at a time."""


class ObjectNotFoundError(ArmRefusal):
    """The locator cannot see an object the action needs."""


class StaleLocationError(ArmRefusal):
    """An object location is older than the configured maximum age."""


class ConfirmationError(ArmRefusal):
    """A real motion was not confirmed (declined, no way to ask, or the hook failed)."""


class UnauthorizedMotionError(ArmRefusal):
    """A motion without a fresh, unused receipt from the validator."""


class ArmMotionError(ArmError):
    """A command was sent and then failed (driver error or timeout); the world may differ."""


class InfeasibleMotionError(ArmRefusal):
    """The motion cannot work physically: object too wide to grasp, does not fit the target."""


class MotionCancelledError(ArmMotionError):
    """A driver gave up a motion because the stop was triggered."""
