"""The stop latch belongs to the arm: new episodes, reconnects and the agent cannot clear it.

A real-mode xArm whose SDK object is `BlockCellStandIn` (a stand-in: no controller can
run here), driven through the real MCP client and server.
"""

from __future__ import annotations

from pathlib import Path

import pytest
from arm_deps import require
from arm_server_helpers import BlockCellStandIn, User, loose_blocks, xarm_toolbox
from mcp import Client
from mcp_helpers import structured, text

from verigraph.server import build_server

require("xarm")

pytestmark = pytest.mark.anyio
CLEARING = ("clean_error", "clean_warn", "motion_enable", "set_state")


async def load(client: Client) -> str:
    return str(structured(await client.call_tool("load_scene", {"graph": loose_blocks()}))[
        "episode_id"])


def calls_since(api: BlockCellStandIn, mark: int) -> list[str]:
    return [name for name, _, _ in api.calls[mark:]]


async def test_a_new_episode_neither_unlatches_nor_clears_the_controller(
        tmp_path: Path) -> None:
    api, user = BlockCellStandIn(), User()
    box = xarm_toolbox(tmp_path, api)
    async with Client(build_server(box), elicitation_callback=user) as client:
        eid = await load(client)
        await client.call_tool("arm_stop", {"episode_id": eid, "reason": "person in cell"})
        await client.call_tool("end_episode", {"episode_id": eid})
        mark = len(api.calls)
        eid = await load(client)  # the same arm again
        reconnect = calls_since(api, mark)
        status = structured(await client.call_tool("arm_status", {"episode_id": eid}))
        out = structured(await client.call_tool("execute_actions", {
            "episode_id": eid, "actions": ["move(green_block, on, red_block)"]}))
    assert "connect" in reconnect and not set(CLEARING) & set(reconnect)
    assert api.state == 4  # the controller's e-stop state is untouched
    assert status["stop_latched"] and status["stop_reason"] == "person in cell"
    assert out["violation"]["constraint"] == "arm_refused" and api.motions() == []
    assert user.asked == []  # a latched arm is never put to the user as a motion


async def test_a_controller_error_is_cleared_only_by_a_confirmed_reset(tmp_path: Path) -> None:
    api = BlockCellStandIn()
    api.error_code = 31  # e.g. a collision the controller detected before we connected
    api.state = 4
    no, yes = User(approve=False), User()
    server = build_server(xarm_toolbox(tmp_path, api))
    async with Client(server, elicitation_callback=no) as client:
        eid = await load(client)
        status = structured(await client.call_tool("arm_status", {"episode_id": eid}))
        refused = await client.call_tool("arm_reset", {"episode_id": eid})
    assert not set(CLEARING) & {name for name, _, _ in api.calls}
    assert status["stop_latched"] and "controller error 31" in status["stop_reason"]
    assert refused.is_error and "did not approve" in text(refused)
    assert api.error_code == 31 and "controller error 31" in no.asked[0]
    mark = len(api.calls)
    async with Client(server, elicitation_callback=yes) as client:
        reset = structured(await client.call_tool("arm_reset", {"episode_id": eid}))
    assert not reset["stop_latched"] and api.error_code == 0 and api.state == 0
    assert "clean_error" in calls_since(api, mark) and api.motions() == []  # nothing moved


async def test_arm_reset_is_announced_as_destructive(tmp_path: Path) -> None:
    async with Client(build_server(xarm_toolbox(tmp_path, BlockCellStandIn()))) as client:
        tools = {t.name: t for t in (await client.list_tools()).tools}
    annotations = tools["arm_reset"].annotations
    # MCP's default for destructiveHint is true, so a destructive tool may leave it out;
    # it must never say false or claim to be read-only.
    assert annotations is not None and annotations.destructive_hint in (None, True)
    assert not annotations.read_only_hint
