"""Asking a human before a real motion, through a sync or async hook.

The server implements the hook with MCP elicitation (async). `execute_in_world` is
synchronous, so the server runs it in an AnyIO worker thread; from there an async hook
is awaited on the server's event loop. Anything but a literal True (a decline, an
exception, a timeout, or no way to wait for the answer) means: do not move.
"""

from __future__ import annotations

import asyncio
import inspect
from collections.abc import Awaitable
from dataclasses import dataclass

import anyio
import anyio.from_thread

from verigraph.arm.models import ConfirmationRequest
from verigraph.arm.protocols import ConfirmHook


@dataclass(frozen=True, slots=True)
class ConfirmationAnswer:
    approved: bool
    reason: str


def ask_confirmation(hook: ConfirmHook | None, request: ConfirmationRequest,
                     timeout_s: float) -> ConfirmationAnswer:
    """Ask `hook` about `request`; approved only on a literal True within `timeout_s`."""
    if hook is None:
        return ConfirmationAnswer(False, "no confirmation hook: the client cannot ask the user")
    try:
        reply = hook(request)
        answer = _wait(reply, timeout_s) if inspect.isawaitable(reply) else reply
    except TimeoutError:
        return ConfirmationAnswer(False, f"no answer within {timeout_s:.0f} s")
    except Exception as exc:  # a failing hook must never let the arm move
        return ConfirmationAnswer(False, f"the confirmation hook failed: {exc!r}")
    if answer is True:
        return ConfirmationAnswer(True, "approved")
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
