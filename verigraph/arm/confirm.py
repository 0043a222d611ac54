"""Asking a human before a real motion, through a sync or async hook.

The server implements the hook with MCP elicitation (async). `execute_in_world` is
synchronous, so the server runs it in an AnyIO worker thread; from there an async hook
is awaited on the server's event loop. Anything but a literal True (a decline, an
exception, a timeout, or no way to wait for the answer) means: do not move.
"""

from __future__ import annotations

import asyncio
import inspect
import time
from collections.abc import Awaitable, Iterator
from contextlib import contextmanager
from contextvars import ContextVar
from dataclasses import dataclass

import anyio
import anyio.from_thread

from verigraph.arm.models import AuditOutcome, ConfirmationRequest
from verigraph.arm.protocols import ConfirmHook

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


def scoped_confirm(request: ConfirmationRequest) -> bool | Awaitable[bool]:
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

    A synchronous hook cannot be interrupted, so its answer is timed: one that comes
    after `timeout_s` counts as no.
    """
    if hook is None:
        return ConfirmationAnswer(False, "no confirmation hook: the client cannot ask the user",
                                  "refused")
    asked = time.monotonic()
    try:
        reply = hook(request)
        answer = _wait(reply, timeout_s) if inspect.isawaitable(reply) else reply
    except TimeoutError:
        return ConfirmationAnswer(False, f"no answer within {timeout_s:.0f} s", "timeout")
    except (NoWayToAsk, NotApproved) as exc:
        return ConfirmationAnswer(False, str(exc))
    except Exception as exc:  # a failing hook must never let the arm move
        return ConfirmationAnswer(False, f"the confirmation hook failed: {exc!r}", "refused")
    late = time.monotonic() - asked
    if late > timeout_s:
        return ConfirmationAnswer(False, f"answered after {late:.1f} s, past the "
                                         f"{timeout_s:g} s deadline: counted as no", "timeout")
    if answer is True:
        return ConfirmationAnswer(True, "approved", "done")
    return ConfirmationAnswer(False, "declined" if answer is False
                              else f"the hook answered {answer!r}, not True")


def _wait(awaitable: Awaitable[object], timeout_s: float) -> object:
    async def bounded() -> object:
        with anyio.fail_after(timeout_s):
            return await awaitable

    try:
        asyncio.get_running_loop()
    except RuntimeError:
        pass
    else:
        if inspect.iscoroutine(awaitable):
            awaitable.close()
        raise RuntimeError("an async confirmation hook cannot be awaited from inside a "
                           "running event loop; run execute_in_world in a worker thread "
                           "(anyio.to_thread.run_sync)")
    try:
        return anyio.from_thread.run(bounded)  # in an AnyIO worker thread: the server's loop
    except anyio.NoEventLoopError:
        return anyio.run(bounded)  # plain synchronous caller: a private loop
