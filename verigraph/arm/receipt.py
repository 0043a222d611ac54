"""Receipts: the only way a graph action becomes something the arm controller accepts.

`authorize` runs `validate_action` on the graph the arm currently observes and, only
if it passes, issues a `ValidatedAction`. The controller redeems a receipt exactly
once and only while it is fresh; receipts cannot be constructed any other way, so an
action that skipped the validator has no path to a driver.
"""

from __future__ import annotations

import threading
import time
import weakref

from verigraph.actions.feedback import Violation
from verigraph.actions.model import MoveAction
from verigraph.actions.validator import validate_action
from verigraph.arm.errors import UnauthorizedMotionError
from verigraph.graph.state import WorldState

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
