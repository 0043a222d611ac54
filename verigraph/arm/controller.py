"""The safety gate between plans and a driver: the only code that calls an ArmDriver.

It enforces, on every motion: run mode (dry-run records and moves nothing), the arm's
latched stop (verigraph.arm.latch, shared across episodes, processes and restarts)
cleared only by a reset someone may make, one motion at a time, a single-use validator
receipt, workspace / keep-out / speed / force checks and the whole-arm geometry on the
whole path before the first command, a human approval before `real` motions, a
per-command timeout and deadman that stop the arm and latch, and an audit record of
the intent before and the outcome after every command (a failed write stops and
latches). The stop path waits on nothing.
"""

from __future__ import annotations

import contextlib
import threading
import time
import weakref
from collections.abc import Callable, Iterator
from contextlib import contextmanager
from typing import Any, Literal

from pydantic import BaseModel

from verigraph.arm.approval import Approval, ConfirmationAnswer, ask_confirmation, redeem
from verigraph.arm.audit import AuditLog, AuditWriteError
from verigraph.arm.config import ArmConfig
from verigraph.arm.errors import (
    ArmBusyError,
    ArmConnectionError,
    ArmError,
    ArmRefusal,
    ArmStoppedError,
    ConfirmationError,
    MotionCancelledError,
    ResetNotAllowedError,
)
from verigraph.arm.latch import ArmLatch
from verigraph.arm.models import ArmStatus, AuditOutcome, AuditRecord, ConfirmationRequest, Pose
from verigraph.arm.planning import MotionPlan, PathSegment, describe
from verigraph.arm.protocols import ArmDriver, ConfirmHook, PathCheck
from verigraph.arm.safety import check_caps, check_path
from verigraph.arm.threads import StatusPoll, start

STOP_GRACE_S = 5.0  # how long a stopped driver may take to end its motion


class MotionOutcome(BaseModel):
    """What happened to a motion that passed every check."""

    status: Literal["done", "recorded", "timeout", "failed", "cancelled"]
    detail: str | None = None


class ArmController:
    """Owns one driver and lets a motion through only when every check passes."""

    def __init__(self, config: ArmConfig, driver: ArmDriver, *,
                 confirm: ConfirmHook | None = None, audit: AuditLog | None = None,
                 latch: ArmLatch | None = None, whole_arm: PathCheck | None = None) -> None:
        self.config = config
        self._whole_arm = whole_arm
        self._driver = driver
        self._confirm = confirm
        self.audit = audit if audit is not None else AuditLog(config.audit_log)
        self._latch = latch if latch is not None else ArmLatch.for_config(config)
        self._poll = StatusPoll(driver)
        self._motion_lock = threading.Lock()
        self._connected = False
        self._driver_stopped = False  # a stop was sent and no reset since
        self._worker: threading.Thread | None = None
        self._approvals: weakref.WeakSet[Approval] = weakref.WeakSet()
        self._dry_tcp = config.home
        self._last_outcome: str | None = None
        self._last_error: str | None = None
        self._heartbeat = time.monotonic()
        _LIVE.add(self)

    # -- state -----------------------------------------------------------------------------
    @property
    def mode(self) -> str:
        return self.config.mode

    @property
    def stop_latched(self) -> bool:
        return self._latch.reason() is not None

    @property
    def _stop_reason(self) -> str | None:
        return self._latch.reason()

    def touch(self) -> None:
        """A call from the client arrived: the deadman (`deadman_s`) starts again."""
        self._heartbeat = time.monotonic()

    def status(self, *, poll: bool = True) -> ArmStatus:
        """The adapter's state; the driver is asked only with `poll`, and never waited
        on for more than STATUS_WAIT_S."""
        tcp: Pose | None = self._dry_tcp if self.mode == "dry-run" else None
        error = self._last_error
        if self._connected and poll:
            try:
                st = self._poll()
                tcp, error = st.tcp, st.error or error
            except Exception as exc:  # status must answer even when the driver cannot
                error = f"driver status failed: {exc}"
        reason = self._stop_reason
        return ArmStatus(driver=self._driver.name, mode=self.config.mode, host=self.config.host,
                         connected=self._connected, stop_latched=reason is not None,
                         stop_reason=reason, busy=self._busy(), tcp=tcp,
                         last_outcome=self._last_outcome, last_error=error,
                         commands_sent=sum(r.outcome == "sent" for r in self.audit.records),
                         audit_log=str(self.audit.path) if self.audit.path else None)

    def _busy(self) -> bool:
        return self._motion_lock.locked() or (self._worker is not None
                                              and self._worker.is_alive())

    def _driver_fault(self) -> str | None:
        """What the connected driver reports as wrong (None: nothing, or not connected)."""
        if not self._connected:
            return None
        try:
            return self._poll().error
        except Exception as exc:
            return f"driver status failed: {exc}"

    # -- connection ------------------------------------------------------------------------
    def connect(self) -> None:
        """Connect the driver (never in dry-run), bounded by connect_timeout_s.

        Connecting never clears a stop or an error: a latched arm stays latched, and a
        controller that reports an error or a stop state latches the arm, so only a
        reset (which a human confirms) can clear it.
        """
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
        worker, errors = start("arm-connect", lambda: self._driver.connect(timeout))
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
        fault = self._driver_fault()
        if fault is not None:
            self._latch.set(f"the controller reported '{fault}' when connecting")
            self._driver_stopped = True
        self._log("connect", {}, "done",
                  None if fault is None else f"connected latched: the controller reports "
                                              f"'{fault}'; nothing was cleared")

    def close(self) -> None:
        """Disconnect the driver (a latched stop stays latched: it belongs to the arm)."""
        if self._whole_arm is not None:
            self._whole_arm.close()
        if self._connected:
            self._connected = False
            self._log("disconnect", {}, "sent")
            self._driver.disconnect()

    # -- stop and reset --------------------------------------------------------------------
    def stop(self, reason: str = "stop requested") -> ArmStatus:
        """Halt any motion now and latch; only a reset clears the latch.

        The driver's stop comes first and waits on nothing (no lock, no status poll, no
        file); the latch and the audit record follow.
        """
        sent, failure = self._halt(reason)
        if not self._connected:
            detail = "no driver connected"
        elif failure is not None:
            detail = f"driver stop failed: {failure}"
        else:
            detail = None
        with contextlib.suppress(AuditWriteError):  # latched already; nothing else to do
            self._log("stop", {"reason": reason}, "done" if sent else
                      ("failed" if failure else "recorded"), detail)
        return self.status(poll=False)

    def _halt(self, reason: str) -> tuple[bool, str | None]:
        """Send the driver's stop (if connected), then latch: (sent, failure)."""
        sent, failure = False, None
        if self._connected:
            try:
                self._driver.stop()
                sent = True
            except Exception as exc:  # the latch holds even if the driver cannot be told
                failure = str(exc)
                self._last_error = f"driver stop failed: {exc}"
            self._driver_stopped = True
        self._latch.set(reason)
        return sent, failure

    def reset_needed(self) -> str | None:
        """What a reset would clear: the latched stop or the controller's error (None:
        nothing)."""
        reason = self._stop_reason
        if reason is not None:
            return f"the latched stop ({reason})"
        self._rearm_if_released()
        fault = self._driver_fault()
        return None if fault is None else f"the controller's error state ({fault})"

    def reset_request(self) -> ConfirmationRequest | None:
        """What a human approves before a real arm is reset (None: nothing to ask).

        Clearing a stop or a controller error re-enables the motors, so on a real arm
        it is confirmed like a motion; nothing moves on a reset.
        """
        need = self.reset_needed() if self.mode == "real" else None
        if need is None:
            return None
        return self._request(f"reset: clear {need} and re-enable the motors; nothing moves "
                             "now", [], 0.0, None)

    def confirm_reset(self) -> None:
        """Ask the human about `reset_request()`; ConfirmationError unless approved."""
        request = self.reset_request()
        if request is None:
            return
        answer = ask_confirmation(self._confirm, request, self.config.confirm_timeout_s)
        self._log_answer(request, answer)
        if not answer.approved:
            raise _audited(ConfirmationError(
                f"reset not confirmed: {answer.reason}", field="confirm", value="reset",
                fix="approve the reset when asked, once the cell is safe"))

    def agent_reset(self) -> ArmStatus:
        """A reset asked for by the agent (the arm_reset tool).

        Real mode: a human confirms it. Sim and dry-run: refused unless the operator
        set `agent_may_reset: true`; the operator resets with `verigraph arm reset`.
        Resetting only permits a restart: it never starts a motion.
        """
        need = self.reset_needed()
        if need is None:
            self._log("reset", {"by": "agent"}, "recorded", "nothing to reset")
            return self.status()
        if self.mode == "real":
            self.confirm_reset()
            return self.reset(by="agent, confirmed by the user")
        if not self.config.agent_may_reset:
            self._log("reset", {"by": "agent"}, "refused",
                      "only the operator may reset this arm (agent_may_reset is false)")
            raise _audited(ResetNotAllowedError(
                f"the agent may not reset this arm: {need} stays until the operator resets "
                "it", field="agent_may_reset", value=False,
                fix="the operator runs `verigraph arm reset --config FILE` once the cell is "
                    "safe, or sets agent_may_reset: true in the arm config"))
        return self.reset(by="agent (agent_may_reset)")

    def reset(self, by: str = "operator") -> ArmStatus:
        """Clear the latch and the driver's stop/error state once no motion is running.

        The caller decided that `by` may do it (see `agent_reset`); nothing moves.
        """
        if self._worker is not None and self._worker.is_alive():
            raise ArmBusyError("the stopped motion has not ended yet", field="reset",
                               fix="wait for the driver to finish stopping, then reset")
        if self._connected:
            self._log("reset", {"by": by}, "sent")
            self._driver.reset()
        self._latch.clear()
        self._driver_stopped = False
        self._last_error = None
        self._log("reset", {"by": by}, "done")
        return self.status()

    def _rearm_if_released(self) -> None:
        """In sim, re-arm a stopped driver once the operator released the latch."""
        if self.mode == "sim" and self._driver_stopped and self._connected \
                and self._stop_reason is None:
            self._driver.reset()
            self._driver_stopped = False
            self._log("reset", {"by": "operator"}, "done",
                      "the simulator's stop cleared: the operator released the latch")

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
        self._log_answer(request, answer)
        if not answer.approved:
            raise _audited(ConfirmationError(
                f"real motion not confirmed: {answer.reason}", field="confirm",
                value=request.motion, fix="approve the motion when asked; use a client that "
                                          "supports elicitation, or mode sim / dry-run"))
        approval = Approval(request.waypoints)
        self._approvals.add(approval)
        return approval

    def _log_answer(self, request: ConfirmationRequest, answer: ConfirmationAnswer) -> None:
        self._log("confirm", {"motion": request.motion}, answer.outcome, answer.reason,
                  question=request.summary())

    def log_confirmation(self, question: str, outcome: AuditOutcome, detail: str) -> None:
        """Record an answer asked outside this controller (MCP elicitation)."""
        self._log("confirm", {}, outcome, detail, question=question)

    def log_refusal(self, what: str, detail: str) -> None:
        """Record a refusal decided outside the gate (validator, locator, planner)."""
        self._log("motion", {"what": what}, "refused", detail)

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
        self.touch()
        with self._exclusive():
            try:
                self._rearm_if_released()
                if redeem_first is not None:
                    redeem_first()
                segments = path(self._current_tcp())
                self._check(segments, speed, force)
                self._redeem_approval(approval, [s.end for s in segments])
                self._refuse_if_stopped()
            except ArmRefusal as exc:
                with contextlib.suppress(AuditWriteError):  # the write failure latched
                    self._log("motion", {"what": what}, "refused", str(exc))
                raise _audited(exc) from None
            if self.mode == "dry-run":
                try:
                    for name, params, _ in commands:
                        self._log(name, params, "recorded")
                except AuditWriteError as exc:
                    return self._finish(MotionOutcome(status="failed", detail=str(exc)))
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
        if self._whole_arm is not None:
            self._whole_arm.check(segments)

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
        try:
            tcp = self._poll().tcp
        except Exception as exc:
            raise ArmRefusal(f"the driver does not report the tool pose: {exc}", field="tcp",
                             fix="check the driver connection; the path cannot be checked "
                                 "without the start pose") from None
        if tcp is None:
            raise ArmRefusal("the driver does not report the tool pose", field="tcp",
                             fix="check the driver connection; the path cannot be checked "
                                 "without the start pose")
        return tcp

    def _run(self, command: str, params: dict[str, Any],
             call: Callable[[], None]) -> MotionOutcome | None:
        """Send one command under the motion timeout and the deadman; None if it completed.

        The intent is logged before the command and the outcome after it; if either
        write fails the arm is stopped and latched first. Nothing is sent once the stop
        is latched (a stop between a pick and its place keeps the place from going out).
        """
        if self.stop_latched:
            unsent = f"{command} not sent: the stop is latched ({self._stop_reason})"
            with contextlib.suppress(AuditWriteError):
                self._log(command, params, "cancelled", unsent)
            return MotionOutcome(status="cancelled", detail=unsent)
        try:
            self._log(command, params, "sent")
        except AuditWriteError as exc:
            return MotionOutcome(status="failed", detail=f"{command} not sent: {exc}")
        worker, errors = start(f"arm-{command}", call)
        self._worker = worker
        status, detail = self._wait(command, worker, errors)
        try:
            self._log(command, {}, status, detail)
        except AuditWriteError as exc:
            return MotionOutcome(status="failed", detail=f"after {command}: {exc}")
        return None if status == "done" else MotionOutcome(status=status, detail=detail)

    def _wait(self, command: str, worker: threading.Thread, errors: list[BaseException]
              ) -> tuple[Literal["done", "timeout", "failed", "cancelled"], str | None]:
        """Join the command's thread; stop it on the motion timeout or the deadman."""
        deadline = time.monotonic() + self.config.motion_timeout_s
        deadman = self.config.deadman_s
        while worker.is_alive() and not self.stop_latched:
            now = time.monotonic()
            if now >= deadline:
                reason = (f"{command} exceeded motion_timeout_s "
                          f"({self.config.motion_timeout_s} s)")
                self._halt(reason)
                worker.join(STOP_GRACE_S)
                return "timeout", reason if not worker.is_alive() else \
                    reason + "; the driver did not stop"
            wait = deadline - now
            if deadman is not None:
                silent = now - self._heartbeat
                if silent >= deadman:
                    self._halt(f"deadman: no call from the client for {deadman:g} s "
                               "during a motion")
                    break
                wait = min(wait, deadman - silent)
            worker.join(min(wait, 0.05))
        if worker.is_alive():  # latched here or by another process: make sure it stops
            self._halt(self._stop_reason or f"{command} stopped")
        worker.join(STOP_GRACE_S)
        if worker.is_alive():
            return "cancelled", f"the stop is latched ({self._stop_reason}); the driver " \
                                "did not end the motion"
        if not errors:
            return "done", None
        exc = errors[0]
        if isinstance(exc, MotionCancelledError) or self.stop_latched:
            self._latch.set(f"{command} cancelled")
            return "cancelled", str(exc)
        self._halt(f"{command} failed: {exc}")
        return "failed", str(exc)

    def _finish(self, outcome: MotionOutcome) -> MotionOutcome:
        self._last_outcome = outcome.status
        if outcome.status not in ("done", "recorded"):
            self._last_error = outcome.detail
        return outcome

    def _log(self, command: str, params: dict[str, Any], outcome: AuditOutcome,
             detail: str | None = None, *, question: str | None = None) -> None:
        """Write one audit record; if that fails, stop and latch, then raise."""
        try:
            self.audit.record(AuditRecord(mode=self.config.mode, driver=self._driver.name,
                                          command=command, params=params, outcome=outcome,
                                          detail=detail, question=question))
        except AuditWriteError as exc:
            self._halt(f"audit log write failed: {exc.message}")
            raise


_LIVE: weakref.WeakSet[ArmController] = weakref.WeakSet()


def stop_every_arm(reason: str) -> int:
    """Stop every controller of this process (shutdown, signals); how many were stopped."""
    controllers = list(_LIVE)
    for controller in controllers:
        controller.stop(reason)
    return len(controllers)


def _audited(exc: ArmError) -> ArmError:
    """Mark `exc` as already in the audit log (so the world does not log it twice)."""
    exc.audited = True
    return exc
