"""Motion needs a live client: a client that goes away, a silent client (deadman_s) and
a server told to stop (SIGTERM) all stop the arm, latch it, log it, and send nothing more.

The disconnect and the signal are tested with the PyBullet Panda moving at wall-clock
pace, through the real MCP client (in memory, and a stdio subprocess); the heartbeat
with a real-mode xArm whose SDK object is `BlockCellStandIn` (a stand-in).
"""

from __future__ import annotations

import contextlib
import json
import os
import signal
import sys
import threading
import time
from pathlib import Path
from typing import Any

import anyio
import anyio.to_thread
import pytest
from arm_deps import require
from arm_server_helpers import BlockCellStandIn, User, loose_blocks, xarm_toolbox
from mcp import Client, StdioServerParameters
from mcp.shared.exceptions import MCPError
from mcp_helpers import structured

from verigraph.arm import ArmWorld, PyBulletOptions, parse_arm_config
from verigraph.server import build_server
from verigraph.tools import Toolbox, ToolConfig
from verigraph.tools.executors import ArmSetup

require("pybullet")
require("xarm")

pytestmark = pytest.mark.anyio
STACK = ["move(green_block, on, red_block)"]


def audit(path: Path) -> list[dict[str, Any]]:
    return [json.loads(line) for line in path.read_text().splitlines()] if path.exists() else []


def sim_config(tmp_path: Path) -> dict[str, Any]:
    return {"driver": "pybullet", "mode": "sim", "audit_log": str(tmp_path / "audit.jsonl"),
            "pybullet": PyBulletOptions(real_time_factor=1.0).model_dump()}


def stdio_sim_server(tmp_path: Path) -> tuple[StdioServerParameters, Path]:
    """(how to start `verigraph serve` on the simulated arm in its own process, its audit log)."""
    config = tmp_path / "arm.json"
    config.write_text(json.dumps(sim_config(tmp_path)))
    params = StdioServerParameters(command=sys.executable, args=[
        "-m", "verigraph", "serve", "--arm-config", str(config)], env=dict(os.environ))
    return params, tmp_path / "audit.jsonl"


class StopClock:
    """Wraps a driver's stop to note when it was called; `moving` is set when the arm
    first follows a trajectory."""

    def __init__(self, world: ArmWorld) -> None:
        driver = world._controller._driver
        scene = driver.scene  # type: ignore[attr-defined]
        self.moving = threading.Event()
        self.stopped_at: float | None = None
        follow, stop = scene.follow, driver.stop

        def follow_and_signal(*args: Any, **kwargs: Any) -> Any:
            self.moving.set()
            return follow(*args, **kwargs)

        def timed_stop() -> None:
            if self.stopped_at is None:
                self.stopped_at = time.monotonic()
            stop()

        scene.follow = follow_and_signal
        driver.stop = timed_stop  # type: ignore[method-assign]


async def test_a_client_that_disconnects_mid_motion_stops_the_arm(tmp_path: Path) -> None:
    box = Toolbox(config=ToolConfig(executor="arm:pybullet", arm=ArmSetup(
        parse_arm_config(sim_config(tmp_path)))))
    ready = anyio.Event()
    found: dict[str, Any] = {}

    async def client_that_goes_away() -> None:
        async with Client(build_server(box)) as client:
            eid = structured(await client.call_tool("load_scene", {"graph": loose_blocks()}))[
                "episode_id"]
            world = box.context.store.peek(eid).world
            assert isinstance(world, ArmWorld)
            found.update(eid=eid, world=world, clock=StopClock(world))
            ready.set()
            await client.call_tool("execute_actions", {"episode_id": eid, "actions": STACK})

    with anyio.fail_after(60):
        async with anyio.create_task_group() as tg:
            tg.start_soon(client_that_goes_away)
            await ready.wait()
            clock: StopClock = found["clock"]
            assert await anyio.to_thread.run_sync(clock.moving.wait, 20)
            gone = time.monotonic()
            tg.cancel_scope.cancel()  # the client disconnects in the middle of the pick
    world: ArmWorld = found["world"]
    assert clock.stopped_at is not None and clock.stopped_at - gone < 0.1
    status = world.status()
    assert status.stop_latched and "client that asked for this motion is gone" in (
        status.stop_reason or "")
    records = audit(tmp_path / "audit.jsonl")
    sent = [r["command"] for r in records if r["outcome"] == "sent"]
    assert "pick" in sent and "place" not in sent  # the place never went out
    assert any(r["command"] == "stop" and "gone" in r["params"]["reason"] for r in records)
    world.close()


async def test_sigterm_stops_the_motion_before_the_server_exits(tmp_path: Path) -> None:
    params, log = stdio_sim_server(tmp_path)

    async def motion_started() -> dict[str, Any]:
        while True:  # the server is another process: watch its audit log
            pick = next((r for r in audit(log) if r["command"] == "pick"
                         and r["outcome"] == "sent"), None)
            if pick is not None:
                return pick
            await anyio.sleep(0.02)

    with anyio.fail_after(90):
        async with anyio.create_task_group() as tg, Client(params) as client:
            eid = structured(await client.call_tool("load_scene", {
                "graph": loose_blocks()}))["episode_id"]

            async def execute() -> None:
                # The server exits under this call: its connection closes (expected).
                with contextlib.suppress(MCPError):
                    await client.call_tool("execute_actions", {"episode_id": eid,
                                                               "actions": STACK})

            tg.start_soon(execute)
            pick = await motion_started()
            os.kill(pick["pid"], signal.SIGTERM)
            while _alive(pick["pid"]):
                await anyio.sleep(0.02)
            tg.cancel_scope.cancel()
    records = audit(log)
    stop = [r for r in records if r["command"] == "stop"]
    assert stop and stop[0]["params"]["reason"] == "the server received SIGTERM"
    assert stop[0]["outcome"] == "done" and stop[0]["seq"] > pick["seq"]
    assert not any(r["command"] == "place" and r["outcome"] == "sent" for r in records)


async def test_a_stdio_client_that_goes_away_mid_motion_stops_the_arm(tmp_path: Path) -> None:
    """The same over the real stdio transport: the client process's end closes the pipe."""
    params, log = stdio_sim_server(tmp_path)

    async def session() -> None:
        async with Client(params) as client:
            eid = structured(await client.call_tool("load_scene", {
                "graph": loose_blocks()}))["episode_id"]
            await client.call_tool("execute_actions", {"episode_id": eid, "actions": STACK})

    with anyio.fail_after(90):
        async with anyio.create_task_group() as tg:
            tg.start_soon(session)
            while not any(r["command"] == "pick" and r["outcome"] == "sent"
                          for r in audit(log)):  # another process: watch its audit log
                await anyio.sleep(0.02)
            tg.cancel_scope.cancel()  # the client goes away: its pipe to the server closes
        while not any(r["command"] == "stop" for r in audit(log)):
            await anyio.sleep(0.02)
    records = audit(log)
    stop = next(r for r in records if r["command"] == "stop")
    assert "client that asked for this motion is gone" in stop["params"]["reason"]
    assert not any(r["command"] == "place" and r["outcome"] == "sent" for r in records)


def _alive(pid: int) -> bool:
    try:
        os.kill(pid, 0)
    except ProcessLookupError:
        return False
    try:  # a child that exited but was not reaped yet is gone for our purpose
        with open(f"/proc/{pid}/stat") as f:
            return f.read().split(")")[-1].split()[0] != "Z"
    except OSError:
        return False


async def test_a_silent_client_trips_the_deadman(tmp_path: Path) -> None:
    api, user = BlockCellStandIn(), User()
    api.time_scale = 1.0  # linear moves take their real duration on the stand-in
    box = xarm_toolbox(tmp_path, api, deadman_s=0.3, speed_m_s=0.05)
    async with Client(build_server(box), elicitation_callback=user) as client:
        eid = structured(await client.call_tool("load_scene", {"graph": loose_blocks()}))[
            "episode_id"]
        started = time.monotonic()
        with anyio.fail_after(20):
            out = structured(await client.call_tool("execute_actions", {
                "episode_id": eid, "actions": STACK}))
        took = time.monotonic() - started
        status = structured(await client.call_tool("arm_status", {"episode_id": eid}))
    assert api.called("emergency_stop") and took < 5  # the pick alone takes > 8 s
    assert status["stop_latched"] and status["stop_reason"].startswith("deadman")
    assert out["violation"]["constraint"] == "execution_failed"
    assert "place" not in [r["command"] for r in audit(tmp_path / "audit.jsonl")
                           if r["outcome"] == "sent"]
