"""Approval given before a call runs: a hook that says yes only to what was shown.

MCP elicitation on protocol 2026-07-28 happens before a tool body runs (a server
cannot push a question in the middle of a call), so the server previews the motions
a call would make (`ArmWorld.preview`), asks the user once, and installs a
`PreApproved` hook for the call. Each real motion must then be the next approved one,
within the controller's own approval tolerance (1 cm, 5 degrees); a motion that
differs because the scene moved, or one that was never shown, is declined.
"""

from __future__ import annotations

import math
import threading
from collections.abc import Sequence

from verigraph.arm.confirm import NotApproved
from verigraph.arm.controller import Approval
from verigraph.arm.models import ConfirmationRequest


def same_request(approved: ConfirmationRequest, asked: ConfirmationRequest) -> bool:
    """True if `asked` is the motion the human saw as `approved` (within tolerance)."""
    if (approved.driver, approved.host, approved.force_n) != (asked.driver, asked.host,
                                                              asked.force_n):
        return False
    if not math.isclose(approved.speed_m_s, asked.speed_m_s, abs_tol=1e-9):
        return False
    if not approved.waypoints:  # not a motion (a reset): the words are what was approved
        return not asked.waypoints and approved.motion == asked.motion
    return Approval(approved.waypoints).covers(asked.waypoints)


class PreApproved:
    """A ConfirmHook approving exactly the given requests, once each, in order."""

    def __init__(self, approved: Sequence[ConfirmationRequest]) -> None:
        self._pending = list(approved)
        self._lock = threading.Lock()

    @property
    def remaining(self) -> int:
        return len(self._pending)

    def __call__(self, request: ConfirmationRequest) -> bool:
        with self._lock:
            expected = self._pending.pop(0) if self._pending else None
        if expected is None:
            raise NotApproved("the user was not asked about this motion in this call; "
                              "send the action again to be asked")
        if not same_request(expected, request):
            raise NotApproved("the scene changed since the user approved: the motion now "
                              f"differs from the approved one ({request.motion}); send the "
                              "action again to be asked about the new motion")
        return True
