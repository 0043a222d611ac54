"""The real-arm confirmation over streamable HTTP, the transport remote clients use.

The HTTP endpoint is stateless with JSON responses, so the server cannot push a request
to the client; on protocol 2026-07-28 the question rides an InputRequiredResult and the
client's retry carries the answer. The app is `verigraph serve --transport http`'s own
(`server.http.http_app`, bearer token on) under uvicorn on a loopback port, in this
process so that the test can look at the arm: an xArm in mode `real` whose SDK object
is `BlockCellStandIn`, a stand-in for hardware that cannot run here.
"""

from __future__ import annotations

from contextlib import AbstractContextManager
from pathlib import Path
from typing import Any

import httpx2
import pytest
from arm_deps import require
from arm_server_helpers import BlockCellStandIn, User, loose_blocks, xarm_toolbox
from mcp import Client
from mcp.client.streamable_http import streamable_http_client
from mcp.types import CallToolResult
from mcp_helpers import free_port, http_in_thread, structured, text

from verigraph.server.http import HttpOptions
from verigraph.tools import Toolbox

require("xarm")

pytestmark = pytest.mark.anyio
TOKEN = "elicit-over-http"


def serving(box: Toolbox) -> AbstractContextManager[str]:
    return http_in_thread(box, HttpOptions(port=free_port(), tokens=(TOKEN,)))


def http() -> httpx2.AsyncClient:
    return httpx2.AsyncClient(headers={"Authorization": f"Bearer {TOKEN}"},
                              timeout=httpx2.Timeout(30, read=60))


async def run_stack(url: str, user: User) -> tuple[CallToolResult, dict[str, Any]]:
    """Load the cell, ask to stack green on red, read the episode afterwards."""
    async with http() as h, Client(streamable_http_client(url, http_client=h),
                                   elicitation_callback=user) as client:
        assert client.protocol_version == "2026-07-28"
        state = structured(await client.call_tool("load_scene", {"graph": loose_blocks()}))
        eid = state["episode_id"]
        assert state["arm_mode"] == "real"
        result = await client.call_tool("execute_actions", {
            "episode_id": eid, "actions": ["move(green_block, on, red_block)"]})
        after = structured(await client.call_tool("get_state", {"episode_id": eid}))
    return result, after


async def test_approved_motion_moves_the_arm_over_http(tmp_path: Path) -> None:
    api = BlockCellStandIn()
    user = User(approve=True)
    with serving(xarm_toolbox(tmp_path, api)) as url:
        result, after = await run_stack(url, user)
    out = structured(result)
    assert out["ok"] and out["executed"] == ["move(green_block, on, red_block)"]
    assert len(user.asked) == 1 and "REAL arm" in user.asked[0]
    assert "pick green_block" in user.asked[0]
    assert api.boxes["green_block"][0][2] == pytest.approx(0.075)  # it rests on red
    assert after["calls"] == 1 and after["executed"] == ["move(green_block, on, red_block)"]


async def test_refused_motion_moves_nothing_over_http(tmp_path: Path) -> None:
    api = BlockCellStandIn()
    user = User(approve=False)
    with serving(xarm_toolbox(tmp_path, api)) as url:
        result, after = await run_stack(url, user)
    assert result.is_error and len(user.asked) == 1
    assert "nothing moved and the episode is unchanged" in text(result)
    assert api.motions() == []
    assert after["calls"] == 0 and after["tau"] == 0 and after["executed"] == []
