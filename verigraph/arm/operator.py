"""What only the operator may do to an arm, from the command line: release its latch.

In sim and dry-run the agent may not reset a stop (unless the config sets
`agent_may_reset: true`), so the operator, at the machine, runs
`verigraph arm reset --config FILE`. It releases the latch persisted next to the
audit log; a running server sees it on its next check. A real arm's stop is reset
through `arm_reset`, which the user confirms; the controller's own error or stop
state is only ever cleared there. Nothing moves on a reset.
"""

from __future__ import annotations

from verigraph.arm.audit import AuditLog, verify_audit_file
from verigraph.arm.config import ArmConfig
from verigraph.arm.errors import ArmConfigError
from verigraph.arm.latch import ArmLatch
from verigraph.arm.models import AuditRecord

__all__ = ["operator_reset", "verify_audit_file"]


def operator_reset(config: ArmConfig) -> str | None:
    """Release the latched stop of `config`'s arm; the reason it was latched, or None."""
    if config.mode == "real":
        raise ArmConfigError(
            "a real arm's stop is reset through arm_reset, which the user confirms",
            field="mode", value=config.mode,
            fix="call arm_reset from the MCP client and approve it once the cell is safe")
    latch = ArmLatch.for_config(config)
    if latch.path is None or config.audit_log is None:
        raise ArmConfigError(
            "this arm's latch lives in the server's memory: the config has no audit_log",
            field="audit_log", value=None,
            fix="give the config an audit_log (the latch is kept next to it), or set "
                "agent_may_reset: true to let the agent's arm_reset clear it")
    reason = latch.reason()
    if reason is None:
        return None
    latch.clear()
    AuditLog(config.audit_log).record(AuditRecord(
        mode=config.mode, driver=config.driver, command="reset",
        params={"by": "operator", "arm": latch.key}, outcome="done",
        detail=f"the operator released the latched stop ({reason}) from the command line"))
    return reason
