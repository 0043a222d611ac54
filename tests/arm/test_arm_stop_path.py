"""The stop path waits on nothing: a driver whose status() hangs does not delay the stop.

The xArm's SDK object is a stand-in (no controller can run here) whose
`get_position` blocks until the test releases it, like a stalled controller socket.
"""

from __future__ import annotations

import threading
import time
from pathlib import Path

import anyio
import pytest
from arm_deps import require
from arm_server_helpers import BlockCellStandIn, User, loose_blocks, xarm_toolbox
from mcp import Client
from mcp_helpers import structured

from verigraph.arm import ArmWorld
from verigraph.server import build_server
from verigraph.server.heavy import HeavyLimits

require("xarm")

pytestmark = pytest.mark.anyio


class HangingStatusStandIn(BlockCellStandIn):
    """The SDK stand-in whose position query hangs while `hang` is set."""

    def __init__(self) -> None:
        super().__init__()
        self.hang = threading.Event()
        self.release = threading.Event()
        self.hanging = threading.Event()  # a status query is stuck right now
        self.stopped_at: float | None = None

    def get_position(self, is_radian: bool | None = None) -> tuple[int, list[float]]:
        if self.hang.is_set():
            self.hanging.set()
            self.release.wait(30)
        return super().get_position(is_radian)

    def emergency_stop(self) -> None:
        self.stopped_at = time.monotonic()
        super().emergency_stop()


async def test_arm_stop_reaches_the_emergency_stop_while_status_hangs(tmp_path: Path) -> None:
    api = HangingStatusStandIn()
    box = xarm_toolbox(tmp_path, api)
    try:
        async with Client(build_server(box), elicitation_callback=User()) as client:
            eid = structured(await client.call_tool("load_scene", {"graph": loose_blocks()}))[
                "episode_id"]
            api.hang.set()
            with anyio.fail_after(5):
                status = structured(await client.call_tool("arm_status", {"episode_id": eid}))
            assert api.hanging.is_set() and not api.release.is_set()
            assert "driver status failed: no answer within" in status["last_error"]
            with anyio.fail_after(5):  # answers although the status query is still stuck
                stopped = structured(await client.call_tool("arm_stop", {
                    "episode_id": eid, "reason": "hung controller"}))
            assert not api.release.is_set() and api.called("emergency_stop")
            assert stopped["stop_latched"] and stopped["stop_reason"] == "hung controller"
            # directly on the world: the emergency stop goes out within 50 ms
            world = box.context.store.peek(eid).world
            assert isinstance(world, ArmWorld)
            started = time.monotonic()
            world.stop("again")
            assert api.stopped_at is not None and api.stopped_at - started < 0.05
    finally:
        api.release.set()


async def test_arm_stop_does_not_queue_behind_busy_worker_threads(tmp_path: Path) -> None:
    """Every heavy-call slot is taken (a motion; a call waiting behind it); the stop
    still goes out at once."""
    api = BlockCellStandIn()
    api.time_scale = 1.0  # linear moves take their real duration on the stand-in
    box = xarm_toolbox(tmp_path, api, speed_m_s=0.05)
    anyio.to_thread.current_default_thread_limiter().total_tokens = 2
    one_worker = HeavyLimits(workers=1)  # the motion takes the server's only heavy slot
    async with Client(build_server(box, heavy=one_worker), elicitation_callback=User()) as client:
        eid = structured(await client.call_tool("load_scene", {"graph": loose_blocks()}))[
            "episode_id"]
        async with anyio.create_task_group() as tg:
            tg.start_soon(client.call_tool, "execute_actions", {
                "episode_id": eid, "actions": ["move(green_block, on, red_block)"]})
            with anyio.fail_after(10):
                while not api.called("set_position"):  # the motion has started
                    await anyio.sleep(0.01)
            tg.start_soon(client.call_tool, "get_state", {"episode_id": eid})  # waits
            with anyio.fail_after(3):  # the motion alone takes more than 8 s
                stopped = structured(await client.call_tool("arm_stop", {"episode_id": eid}))
    assert stopped["stop_latched"] and api.called("emergency_stop")
