"""A client that goes away cancels its heavy call: the worker stops at its next budget
checkpoint. A real uvicorn server on loopback, a real HTTP client that disconnects;
one plan step is instrumented to hold until the disconnect (events, no sleeps)."""

from __future__ import annotations

import functools
import threading
from types import SimpleNamespace
from typing import Any

import anyio
import anyio.to_thread
import httpx2
import pytest
import uvicorn
from mcp import Client
from mcp_helpers import JSON_HEADERS, free_port, rpc, text

from verigraph.actions import execution
from verigraph.budget import BudgetExceeded, CallBudget, checkpoint
from verigraph.server import build_server
from verigraph.server.heavy import HeavyLimits
from verigraph.server.http import HttpOptions, uvicorn_config
from verigraph.tools import Toolbox

pytestmark = pytest.mark.anyio
SAFETY_S = 60  # only so that a broken server fails instead of hanging


class HeldStep:
    """Wraps the plan checker's per-move step (the move row's compiled check and edit):
    the first move waits until cancelled."""

    def __init__(self) -> None:
        self.started = threading.Event()
        self.outcome: list[BaseException | str] = []
        self.finished = threading.Event()
        self.real = execution.MOVE.step

    def __call__(self, *args: Any, **kwargs: Any) -> Any:
        if not self.started.is_set():
            self.started.set()
            try:
                give_up = threading.Event()
                while not give_up.wait(0.005):  # a long computation with checkpoints
                    checkpoint()
            except BudgetExceeded as exc:
                self.outcome.append(exc)
                raise
            finally:
                self.finished.set()
        return self.real(*args, **kwargs)

    def row(self) -> SimpleNamespace:
        """The move row with this check in place of its own."""
        move = execution.MOVE
        return SimpleNamespace(name=move.name, args=move.args, accepted=move.accepted,
                               apply=move.apply, step=self)


async def test_a_vanished_clients_call_is_cancelled(monkeypatch: pytest.MonkeyPatch) -> None:
    held = HeldStep()
    monkeypatch.setattr(execution, "MOVE", held.row())
    options = HttpOptions(port=free_port())
    server = uvicorn.Server(uvicorn_config(build_server(Toolbox()), options))
    plan = "move(cup, on, desk)   \n" * 1000  # long enough to run as a heavy call
    body = rpc("tools/call", {"name": "validate_plan", "arguments": {
        "scene_id": "cup_on_book", "plan": plan}})
    async with anyio.create_task_group() as tg:
        tg.start_soon(server.serve)
        with anyio.fail_after(SAFETY_S):
            while not server.started:
                await anyio.sleep(0.01)
        async with httpx2.AsyncClient(timeout=SAFETY_S) as http, \
                anyio.create_task_group() as client:
            client.start_soon(functools.partial(http.post, options.url(), content=body,
                                                headers=JSON_HEADERS))
            await anyio.to_thread.run_sync(held.started.wait, SAFETY_S)
            client.cancel_scope.cancel()  # the client goes away mid-call
        assert await anyio.to_thread.run_sync(held.finished.wait, SAFETY_S)
        assert held.outcome and "cancelled" in str(held.outcome[0])
        async with httpx2.AsyncClient(timeout=SAFETY_S) as http:  # still serving
            reply = await http.post(options.url(), content=rpc("ping"), headers=JSON_HEADERS)
            assert reply.status_code == 200 and reply.json()["result"] == {}
        server.should_exit = True


async def test_a_call_over_its_wall_clock_budget_gets_a_tool_error(
        monkeypatch: pytest.MonkeyPatch) -> None:
    held = HeldStep()
    monkeypatch.setattr(execution, "MOVE", held.row())
    server = build_server(Toolbox(), heavy=HeavyLimits(budget=CallBudget(wall_s=0.2)))
    async with Client(server) as client:
        result = await client.call_tool("validate_plan", {
            "scene_id": "cup_on_book", "plan": "move(cup, on, desk)   \n" * 1000})
    assert result.is_error
    assert "validate_plan ran longer than its 0.2 s budget" in text(result)
    assert "--tool-seconds" in text(result)
