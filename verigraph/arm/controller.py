"""The safety gate between plans and a driver: the only code that calls an ArmDriver.

It enforces, on every motion: run mode (dry-run records and moves nothing), a latched
stop cleared only by `reset`, one motion at a time, a single-use validator receipt,
workspace / keep-out / speed / force checks on the whole path before the first
command, a human approval before `real` motions, a per-command timeout that stops the
arm and latches, and an append-only audit record of every command.
"""

from __future__ import annotations

import math
import threading
import time
import weakref
from collections.abc import Callable, Iterator
from contextlib import contextmanager
from typing import Any, Literal

from pydantic import BaseModel

from verigraph.arm.audit import AuditLog
from verigraph.arm.config import ArmConfig
from verigraph.arm.confirm import ask_confirmation
from verigraph.arm.errors import (
    ArmBusyError,
    ArmConnectionError,
    ArmError,
    ArmRefusal,
    ArmStoppedError,
    ConfirmationError,
    MotionCancelledError,
)
from verigraph.arm.models import ArmStatus, AuditRecord, ConfirmationRequest, Pose
from verigraph.arm.planning import MotionPlan, PathSegment, describe
from verigraph.arm.protocols import ArmDriver, ConfirmHook
from verigraph.arm.receipt import redeem
from verigraph.arm.safety import check_caps, check_path

STOP_GRACE_S = 5.0  # how long a stopped driver may take to end its motion
APPROVAL_TOLERANCE_M = 0.01
APPROVAL_TOLERANCE_RAD = math.radians(5)


class MotionOutcome(BaseModel):
    """What happened to a motion that passed every check."""

    status: Literal["done", "recorded", "timeout", "failed", "cancelled"]
    detail: str | None = None


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


class ArmController:
    """Owns one driver and lets a motion through only when every check passes."""

    def __init__(self, config: ArmConfig, driver: ArmDriver, *,
                 confirm: ConfirmHook | None = None, audit: AuditLog | None = None) -> None:
        self.config = config
        self._driver = driver
        self._confirm = confirm
        self.audit = audit if audit is not None else AuditLog(config.audit_log)
        self._motion_lock = threading.Lock()
        self._stop_lock = threading.Lock()
        self._stop_reason: str | None = None
        self._connected = False
        self._worker: threading.Thread | None = None
        self._approvals: weakref.WeakSet[Approval] = weakref.WeakSet()
        self._dry_tcp = config.home
        self._last_outcome: str | None = None
        self._last_error: str | None = None

    # -- state -----------------------------------------------------------------------------
    @property
    def mode(self) -> str:
        return self.config.mode

    @property
    def stop_latched(self) -> bool:
        return self._stop_reason is not None

    def status(self) -> ArmStatus:
        tcp: Pose | None = self._dry_tcp if self.mode == "dry-run" else None
        error = self._last_error
        if self._connected:
            try:
                st = self._driver.status()
                tcp, error = st.tcp, st.error or error
            except Exception as exc:  # status must answer even when the driver cannot
                error = f"driver status failed: {exc}"
        return ArmStatus(driver=self._driver.name, mode=self.config.mode, host=self.config.host,
                         connected=self._connected, stop_latched=self.stop_latched,
                         stop_reason=self._stop_reason, busy=self._busy(), tcp=tcp,
                         last_outcome=self._last_outcome, last_error=error,
                         commands_sent=sum(r.outcome == "sent" for r in self.audit.records),
                         audit_log=str(self.audit.path) if self.audit.path else None)

    def _busy(self) -> bool:
        return self._motion_lock.locked() or (self._worker is not None
                                              and self._worker.is_alive())

    # -- connection ------------------------------------------------------------------------
    def connect(self) -> None:
        """Connect the driver (never in dry-run), bounded by connect_timeout_s."""
        if self._connected:
            return
        if self.mode == "dry-run":
            self._log("connect", {}, "recorded", "dry-run: the driver is not contacted")
            return
        want_sim = self.mode == "sim"
        if self._driver.simulated != want_sim:
            kind = "a simulator" if self._driver.simulated else "hardware"
            raise ArmConnectionError(
                f"mode '{self.mode}' does not match the {self._driver.name} driver, which "
                f"drives {kind}", field="mode", value=self.mode,
                fix="use mode sim for simulators and mode real (with confirmation) for hardware")
        timeout = self.config.connect_timeout_s
        self._log("connect", {"host": self.config.host, "timeout_s": timeout}, "sent")
        worker, errors = _start("arm-connect", lambda: self._driver.connect(timeout))
        worker.join(timeout + 1.0)
        if worker.is_alive() or errors:
            why = f"no answer within {timeout} s" if worker.is_alive() else str(errors[0])
            self._log("connect", {}, "failed", why)
            if errors and isinstance(errors[0], ArmError):
                raise errors[0]
            raise ArmConnectionError(
                f"cannot reach the {self._driver.name} controller at {self.config.host}: {why}",
                field="host", value=self.config.host,
                fix="check the address, that the controller is on and reachable, and the port")
        self._connected = True
        self._log("connect", {}, "done")

    def close(self) -> None:
        """Disconnect the driver (a latched stop stays latched in the audit trail)."""
        if self._connected:
            self._connected = False
            self._log("disconnect", {}, "sent")
            self._driver.disconnect()

    # -- stop and reset --------------------------------------------------------------------
    def stop(self, reason: str = "stop requested") -> ArmStatus:
        """Latch the stop and halt any motion now; only `reset` clears the latch."""
        self._latch(reason)
        if self._connected:
            self._send_stop()
        else:
            self._log("stop", {"reason": reason}, "recorded", "no driver connected")
        return self.status()

    def reset_request(self) -> ConfirmationRequest | None:
        """What a human approves before a real arm's latched stop is cleared (else None).

        Clearing the latch re-enables the motors, so on a real arm it is confirmed like
        a motion; with no stop latched, or not in real mode, there is nothing to ask.
        """
        if self.mode != "real" or self._stop_reason is None:
            return None
        return self._request(f"reset: clear the latched stop ({self._stop_reason}) and "
                             "re-enable the motors; nothing moves now", [], 0.0, None)

    def confirm_reset(self) -> None:
        """Ask the human about `reset_request()`; ConfirmationError unless approved."""
        request = self.reset_request()
        if request is None:
            return
        answer = ask_confirmation(self._confirm, request, self.config.confirm_timeout_s)
        self._log("confirm", {"motion": request.motion},
                  "done" if answer.approved else "refused", answer.reason)
        if not answer.approved:
            raise ConfirmationError(f"reset not confirmed: {answer.reason}", field="confirm",
                                    value="reset", fix="approve the reset when asked, once "
                                                       "the cell is safe")

    def reset(self) -> ArmStatus:
        """Clear the latched stop once no motion is running (explicit operator action)."""
        if self._worker is not None and self._worker.is_alive():
            raise ArmBusyError("the stopped motion has not ended yet", field="reset",
                               fix="wait for the driver to finish stopping, then reset")
        if self._connected:
            self._log("reset", {}, "sent")
            self._driver.reset()
        else:
            self._log("reset", {}, "recorded")
        with self._stop_lock:
            self._stop_reason = None
        self._last_error = None
        return self.status()

    def _latch(self, reason: str) -> None:
        with self._stop_lock:
            if self._stop_reason is None:
                self._stop_reason = reason

    def _send_stop(self) -> None:
        self._log("stop", {"reason": self._stop_reason}, "sent")
        try:
            self._driver.stop()
        except Exception as exc:  # the latch holds even if the driver cannot be told
            self._last_error = f"driver stop failed: {exc}"
            self._log("stop", {}, "failed", str(exc))

    # -- confirmation ----------------------------------------------------------------------
    def confirm_plan(self, plan: MotionPlan) -> Approval:
        """Check the plan, then ask the human; an Approval to pass to `execute`."""
        request, _ = self.preview(plan)
        return self._ask(request)

    def preview(self, plan: MotionPlan, start: Pose | None = None
                ) -> tuple[ConfirmationRequest, Pose]:
        """The request `confirm_plan` would put to the human: checked, not asked.

        `start` is where the tool will be when the motion begins (default: now), so a
        sequence of motions can be previewed in order; returns the request and the pose
        the motion ends at. Raises the refusal `confirm_plan` would raise.
        """
        segments = plan.path(start if start is not None else self._current_tcp())
        self._check(segments, plan.grasp.speed_m_s, plan.grasp.force_n)
        self._refuse_if_stopped()
        request = self._request(describe(plan), [s.end for s in segments],
                                plan.grasp.speed_m_s, plan.grasp.force_n)
        return request, segments[-1].end

    def confirm_home(self) -> Approval:
        segment = PathSegment("to home", self._current_tcp(), self.config.home)
        self._check([segment], self.config.speed_m_s, None)
        self._refuse_if_stopped()
        return self._ask(self._request(f"go home to {self.config.home.text()}", [segment.end],
                                       self.config.speed_m_s, None))

    def _request(self, motion: str, waypoints: list[Pose], speed: float,
                 force: float | None) -> ConfirmationRequest:
        return ConfirmationRequest(driver=self._driver.name, host=self.config.host,
                                   motion=motion, waypoints=waypoints, speed_m_s=speed,
                                   force_n=force)

    def _ask(self, request: ConfirmationRequest) -> Approval:
        self._refuse_if_stopped()
        answer = ask_confirmation(self._confirm, request, self.config.confirm_timeout_s)
        self._log("confirm", {"motion": request.motion},
                  "done" if answer.approved else "refused", answer.reason)
        if not answer.approved:
            raise ConfirmationError(f"real motion not confirmed: {answer.reason}",
                                    field="confirm", value=request.motion,
                                    fix="approve the motion when asked; use a client that "
                                        "supports elicitation, or mode sim / dry-run")
        approval = Approval(request.waypoints)
        self._approvals.add(approval)
        return approval

    def _redeem_approval(self, approval: Approval | None, waypoints: list[Pose]) -> None:
        if self.mode != "real":
            return
        ok = (approval is not None and approval in self._approvals
              and approval.covers(waypoints)
              and time.time() - approval.approved_at <= self.config.confirm_timeout_s)
        if approval is not None:
            self._approvals.discard(approval)
        if not ok:
            raise ConfirmationError(
                "real motion without a matching approval (missing, used, expired, or the "
                "scene changed since it was given)", field="confirm",
                fix="ask again with confirm_plan on the current plan")

    # -- motions ---------------------------------------------------------------------------
    def execute(self, plan: MotionPlan, *, approval: Approval | None = None) -> MotionOutcome:
        """Pick and place per `plan`, or raise an ArmRefusal before anything is sent."""
        return self._gated(
            plan.receipt.action.text(), plan.path,
            max(plan.grasp.speed_m_s, plan.placement.speed_m_s), plan.grasp.force_n, approval,
            [("pick", {**plan.grasp.model_dump(), "validated_on": plan.receipt.fingerprint},
              lambda: self._driver.pick(plan.grasp)),
             ("place", plan.placement.model_dump(), lambda: self._driver.place(plan.placement))],
            redeem_first=lambda: redeem(plan.receipt, max_age_s=self.config.max_location_age_s))

    def home(self, *, approval: Approval | None = None) -> MotionOutcome:
        """Move to the configured home pose through the same checks."""
        home, speed = self.config.home, self.config.speed_m_s
        return self._gated(
            "home", lambda start: [PathSegment("to home", start, home)], speed, None, approval,
            [("home", {"pose": home.model_dump(), "speed_m_s": speed},
              lambda: self._driver.home(home, speed))])

    def _gated(self, what: str, path: Callable[[Pose], list[PathSegment]], speed: float,
               force: float | None, approval: Approval | None,
               commands: list[tuple[str, dict[str, Any], Callable[[], None]]], *,
               redeem_first: Callable[[], object] | None = None) -> MotionOutcome:
        """Every check, then the commands in order (recorded only, in dry-run)."""
        with self._exclusive():
            try:
                if redeem_first is not None:
                    redeem_first()
                segments = path(self._current_tcp())
                self._check(segments, speed, force)
                self._redeem_approval(approval, [s.end for s in segments])
                self._refuse_if_stopped()
            except ArmRefusal as exc:
                self._log("motion", {"what": what}, "refused", str(exc))
                raise
            if self.mode == "dry-run":
                for name, params, _ in commands:
                    self._log(name, params, "recorded")
                self._dry_tcp = segments[-1].end
                return self._finish(MotionOutcome(status="recorded"))
            for name, params, call in commands:
                outcome = self._run(name, params, call)
                if outcome is not None:
                    return self._finish(outcome)
            return self._finish(MotionOutcome(status="done"))

    @contextmanager
    def _exclusive(self) -> Iterator[None]:
        """One motion at a time: a non-blocking hold on the motion lock."""
        if not self._motion_lock.acquire(blocking=False):
            raise ArmBusyError("another motion is in progress", field="busy",
                               fix="wait for it to finish (arm_status) or stop it (arm_stop)")
        try:
            if self._worker is not None and self._worker.is_alive():
                raise ArmBusyError("the previous motion has not ended", field="busy",
                                   fix="wait, or stop it with arm_stop")
            yield
        finally:
            self._motion_lock.release()

    def _check(self, segments: list[PathSegment], speed: float, force: float | None) -> None:
        check_caps(self.config, speed, force)
        check_path(self.config, segments)

    def _refuse_if_stopped(self) -> None:
        if self._stop_reason is not None:
            raise ArmStoppedError(f"the stop is latched ({self._stop_reason})", field="stop",
                                  value=self._stop_reason,
                                  fix="make the cell safe, then call arm_reset")
        if self.mode != "dry-run" and not self._connected:
            raise ArmRefusal("the arm is not connected", field="connected",
                             fix="connect the arm controller first")

    def _current_tcp(self) -> Pose:
        if self.mode == "dry-run" or not self._connected:
            return self._dry_tcp
        tcp = self._driver.status().tcp
        if tcp is None:
            raise ArmRefusal("the driver does not report the tool pose", field="tcp",
                             fix="check the driver connection; the path cannot be checked "
                                 "without the start pose")
        return tcp

    def _run(self, command: str, params: dict[str, Any],
             call: Callable[[], None]) -> MotionOutcome | None:
        """Send one command under the motion timeout; None if it completed."""
        self._log(command, params, "sent")
        worker, errors = _start(f"arm-{command}", call)
        self._worker = worker
        worker.join(self.config.motion_timeout_s)
        if worker.is_alive():
            reason = f"{command} exceeded motion_timeout_s ({self.config.motion_timeout_s} s)"
            self._latch(reason)
            self._send_stop()
            worker.join(STOP_GRACE_S)
            detail = reason if not worker.is_alive() else reason + "; the driver did not stop"
            self._log(command, {}, "timeout", detail)
            return MotionOutcome(status="timeout", detail=detail)
        if not errors:
            self._log(command, {}, "done")
            return None
        exc = errors[0]
        if isinstance(exc, MotionCancelledError) or self.stop_latched:
            self._latch(f"{command} cancelled")
            self._log(command, {}, "cancelled", str(exc))
            return MotionOutcome(status="cancelled", detail=str(exc))
        self._latch(f"{command} failed: {exc}")
        self._log(command, {}, "failed", str(exc))
        return MotionOutcome(status="failed", detail=str(exc))

    def _finish(self, outcome: MotionOutcome) -> MotionOutcome:
        self._last_outcome = outcome.status
        if outcome.status not in ("done", "recorded"):
            self._last_error = outcome.detail
        return outcome

    def _log(self, command: str, params: dict[str, Any],
             outcome: Literal["sent", "done", "recorded", "refused", "failed", "timeout",
                              "cancelled"], detail: str | None = None) -> None:
        self.audit.record(AuditRecord(seq=0, time=0.0, mode=self.config.mode,
                                      driver=self._driver.name, command=command,
                                      params=params, outcome=outcome, detail=detail))


def _start(name: str, call: Callable[[], None]) -> tuple[threading.Thread, list[BaseException]]:
    """Run `call` in a daemon thread; the list receives what it raised, if anything."""
    errors: list[BaseException] = []

    def body() -> None:
        try:
            call()
        except BaseException as exc:
            errors.append(exc)

    worker = threading.Thread(target=body, name=name, daemon=True)
    worker.start()
    return worker, errors
