"""Arm approval in one place: the validator's receipt, the human's yes, and the hooks
that ask for it.

* Receipts are the only way a graph action becomes something the arm controller
  accepts. `authorize` runs `validate_action` on the graph the arm currently observes
  and, only if it passes, issues a `ValidatedAction`; the controller redeems a receipt
  exactly once and only while it is fresh. Receipts cannot be constructed any other
  way, so an action that skipped the validator has no path to a driver.
* A real motion also needs a human's yes (`Approval`), asked through a synchronous
  `ConfirmHook`. Anything but a literal True (a decline, an exception, a late answer,
  an asynchronous hook, or no way to ask) means: do not move.
* MCP elicitation on protocol 2026-07-28 happens before a tool body runs (a server
  cannot push a question in the middle of a call), so the server previews the motions
  a call would make (`ArmWorld.preview`), asks the user once, and installs a
  `PreApproved` hook for the call (`confirm_scope`; context variables follow the call
  into its worker thread). Each real motion must then be the next approved one, within
  the approval tolerance (1 cm, 5 degrees); a motion that differs because the scene
  moved, or one that was never shown, is declined.
"""

from __future__ import annotations

import inspect
import math
import threading
import time
import weakref
from collections.abc import Iterator, Sequence
from contextlib import contextmanager
from contextvars import ContextVar
from dataclasses import dataclass

from verigraph.actions.feedback import Violation
from verigraph.actions.model import MoveAction
from verigraph.actions.validator import validate_action
from verigraph.arm.errors import UnauthorizedMotionError
from verigraph.arm.models import AuditOutcome, ConfirmationRequest, Pose
from verigraph.arm.protocols import ConfirmHook
from verigraph.graph.state import WorldState

APPROVAL_TOLERANCE_M = 0.01
APPROVAL_TOLERANCE_RAD = math.radians(5)

# -- receipts ---------------------------------------------------------------------------
_MINT = object()
_ISSUED: weakref.WeakSet[ValidatedAction] = weakref.WeakSet()
_ISSUED_LOCK = threading.Lock()


class ValidatedAction:
    """Proof that `action` passed the validator on the observed graph `fingerprint`."""

    __slots__ = ("__weakref__", "action", "fingerprint", "issued_at")

    def __init__(self, action: MoveAction, fingerprint: str, issued_at: float, *,
                 _mint: object = None) -> None:
        if _mint is not _MINT:
            raise UnauthorizedMotionError(
                "a ValidatedAction can only be issued by the validator", field="receipt",
                value=action.text(), fix="pass the action through execute_in_world (or "
                                         "ArmWorld.perform), which validates it first")
        self.action = action
        self.fingerprint = fingerprint
        self.issued_at = issued_at

    def __repr__(self) -> str:
        return f"ValidatedAction({self.action.text()}, graph {self.fingerprint[:8]})"


def graph_fingerprint(state: WorldState) -> str:
    """A stable text form of the support and contact edges of a state."""
    return ";".join(sorted(e.sentence() for e in state.edges()))


def authorize(state: WorldState, action: MoveAction) -> ValidatedAction | Violation:
    """Validate `action` on `state`; a receipt if it passes, the violation otherwise."""
    violation = validate_action(state, action)
    if violation is not None:
        return violation
    receipt = ValidatedAction(action, graph_fingerprint(state), time.time(), _mint=_MINT)
    with _ISSUED_LOCK:
        _ISSUED.add(receipt)
    return receipt


def redeem(receipt: object, *, max_age_s: float, now: float | None = None) -> MoveAction:
    """Consume a receipt (single use); raises UnauthorizedMotionError if it is not valid."""
    now = time.time() if now is None else now
    with _ISSUED_LOCK:
        issued = isinstance(receipt, ValidatedAction) and receipt in _ISSUED
        if issued:
            _ISSUED.discard(receipt)  # type: ignore[arg-type]
    if not issued:
        raise UnauthorizedMotionError(
            "motion refused: no unused receipt from the validator", field="receipt",
            value=repr(receipt), fix="validate the action on the current graph (through "
                                     "execute_in_world) and use its receipt once")
    assert isinstance(receipt, ValidatedAction)
    age = now - receipt.issued_at
    if age > max_age_s:
        raise UnauthorizedMotionError(
            f"motion refused: the validation is {age:.1f} s old (limit {max_age_s:.1f} s)",
            field="receipt", value=receipt.action.text(),
            fix="validate again on the current graph; the scene may have changed")
    return receipt.action


# -- the human's yes ---------------------------------------------------------------------
class Approval:
    """A human's yes to one set of waypoints; its controller accepts it once."""

    __slots__ = ("__weakref__", "approved_at", "waypoints")

    def __init__(self, waypoints: list[Pose]) -> None:
        self.waypoints = waypoints
        self.approved_at = time.time()

    def covers(self, waypoints: list[Pose]) -> bool:
        """True if `waypoints` are the approved ones (within 1 cm and 5 degrees)."""
        return len(waypoints) == len(self.waypoints) and all(
            math.dist(a.point(), b.point()) <= APPROVAL_TOLERANCE_M
            and abs(math.remainder(a.yaw - b.yaw, math.pi)) <= APPROVAL_TOLERANCE_RAD
            for a, b in zip(waypoints, self.waypoints, strict=True))


_SCOPED: ContextVar[ConfirmHook | None] = ContextVar("verigraph_arm_confirm", default=None)


class NoWayToAsk(Exception):
    """The current request installed no confirmation hook (its client cannot elicit)."""


class NotApproved(Exception):
    """A hook's reasoned no: the motion is not one the human approved."""


@contextmanager
def confirm_scope(hook: ConfirmHook | None) -> Iterator[None]:
    """Install `hook` for the current request; `scoped_confirm` delegates to it.

    The server opens one scope per tool call with an elicitation hook bound to that
    call's client. Context variables follow `anyio.to_thread.run_sync` into the
    worker thread, so the ArmWorld built once per episode asks the right client.
    """
    token = _SCOPED.set(hook)
    try:
        yield
    finally:
        _SCOPED.reset(token)


def scoped_confirm(request: ConfirmationRequest) -> bool:
    """A ConfirmHook that asks whichever hook the current `confirm_scope` installed."""
    hook = _SCOPED.get()
    if hook is None:
        raise NoWayToAsk("no confirmation hook in this request: the client cannot ask "
                         "the user")
    return hook(request)


@dataclass(frozen=True, slots=True)
class ConfirmationAnswer:
    approved: bool
    reason: str
    outcome: AuditOutcome = "declined"  # how the audit log files it


def ask_confirmation(hook: ConfirmHook | None, request: ConfirmationRequest,
                     timeout_s: float) -> ConfirmationAnswer:
    """Ask `hook` about `request`; approved only on a literal True within `timeout_s`.

    A hook is synchronous and cannot be interrupted, so its answer is timed: one that
    comes after `timeout_s` counts as no. (The server asks the user before the call runs
    and installs a `PreApproved` hook, so no hook ever waits on an event loop.)
    """
    if hook is None:
        return ConfirmationAnswer(False, "no confirmation hook: the client cannot ask the user",
                                  "refused")
    asked = time.monotonic()
    try:
        answer: object = hook(request)
    except (NoWayToAsk, NotApproved) as exc:
        return ConfirmationAnswer(False, str(exc))
    except Exception as exc:  # a failing hook must never let the arm move
        return ConfirmationAnswer(False, f"the confirmation hook failed: {exc!r}", "refused")
    late = time.monotonic() - asked
    if late > timeout_s:
        return ConfirmationAnswer(False, f"answered after {late:.1f} s, past the "
                                         f"{timeout_s:g} s deadline: counted as no", "timeout")
    if inspect.isawaitable(answer):
        if inspect.iscoroutine(answer):
            answer.close()  # never awaited: hooks are synchronous
        return ConfirmationAnswer(False, "the confirmation hook is asynchronous; hooks must "
                                         "answer True synchronously", "refused")
    if answer is True:
        return ConfirmationAnswer(True, "approved", "done")
    return ConfirmationAnswer(False, "declined" if answer is False
                              else f"the hook answered {answer!r}, not True")


# -- approval given before the call ----------------------------------------------------
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
